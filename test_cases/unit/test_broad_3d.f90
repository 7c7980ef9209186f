!> The 3D broad phase (fracas_broad_3d) against its definition.
!> 1. Hand cases (references computed by hand, exact up to the 1e-9 margins):
!>    two spheres r = 1 and 0.5, alert 0.1, centres 1.6 - 1e-9 apart: one pair,
!>    1.6 + 1e-9: none; the same on one body: none; a sphere r = 0.5 over a
!>    PLANx (10, 10, 0.5): at height 1.05 (box distance 0.55 <= 0.6) a pair, at
!>    1.15 (0.65) none although the plane's bounding sphere (14.15) holds it; beyond
!>    the rim at (10.3, 0, 0.8) (0.424) a pair, (10.5, 0, 0.9) (0.640) none; the
!>    same under the plane: at height -1.05 a pair, at (-10.5, 0, -0.9) none; over a
!>    PLANx turned 30 degrees about x, 1.1 - 1e-9 along its normal: a pair.
!> 2. Random scenes, 4 seeds: 1500 polydisperse spheres, 200 POLYR boxes (bound
!>    from their vertices), bodies carrying two contactors, a huge sphere (big by
!>    the mean rule), a floor and a tilted wall (PLANx, tested as boxes); seed 3
!>    also throws 20 contactors 1e9..1e12 away (clamped cells) and one NaN centre.
!>    Reference: the O(n^2) loop (broad3_brute) with the same predicate: the
!>    same number of pairs and the same sorted list, exactly.
!> Planted (each went red): 12 forward neighbours instead of 13; cells of side
!> r_max + alert; the box test without abs(); pairs sorted by the second index only.
program test_broad_3d
  use fracas_kinds, only: wp
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use fracas_broad_3d, only: broad3_t, broad3_pairs, broad3_brute, tactor3_bound, broad3_big
  use fracas_contactors_3d, only: tactor3_t, tk3_spher, tk3_planx, tk3_polyr, polyr_from_surface, box_surface
  use fracas_frame_3d, only: rotation_of_vector, identity3
  use fracas_random, only: rng_t, rng_seed, rng_below
  use fracas_testing, only: check_true, test_finish
  implicit none
  type(rng_t) :: rng
  integer :: seed

  call hand_cases()
  do seed = 1, 4
    call random_scene(seed)
  end do
  call test_finish()

contains

  real(wp) function uniform()
    uniform = rng_below(rng, 1000000) / 1.0e6_wp
  end function uniform

  subroutine hand_cases()
    type(broad3_t) :: b
    real(wp) :: c(3, 2), half(3, 2), frame(3, 3, 2), n(3), th
    character(len=64) :: label
    integer :: k
    real(wp), parameter :: heights(4, 6) = reshape([0.0_wp, 0.0_wp, 1.05_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.15_wp, 0.0_wp, &
                                                   10.3_wp, 0.0_wp, 0.8_wp, 1.0_wp, 10.5_wp, 0.0_wp, 0.9_wp, 0.0_wp, &
                                                   0.0_wp, 0.0_wp, -1.05_wp, 1.0_wp, -10.5_wp, 0.0_wp, -0.9_wp, 0.0_wp], [4, 6])
    c(:, 1) = 0.0_wp
    c(:, 2) = [1.6_wp - 1.0e-9_wp, 0.0_wp, 0.0_wp]
    call broad3_pairs(b, c, [1.0_wp, 0.5_wp], [1, 2], 0.1_wp, [.false., .false.])
    call check_true('two spheres 1.6 - 1e-9 apart: one pair', b%npairs == 1)
    c(1, 2) = 1.6_wp + 1.0e-9_wp
    call broad3_pairs(b, c, [1.0_wp, 0.5_wp], [1, 2], 0.1_wp, [.false., .false.])
    call check_true('two spheres 1.6 + 1e-9 apart: none', b%npairs == 0)
    c(1, 2) = 1.0_wp
    call broad3_pairs(b, c, [1.0_wp, 0.5_wp], [1, 1], 0.1_wp, [.false., .false.])
    call check_true('two spheres of one body: none', b%npairs == 0)
    ! contactor 1 a PLANx (10, 10, 0.5), contactor 2 a sphere r = 0.5; alert 0.1
    half(:, 1) = [10.0_wp, 10.0_wp, 0.5_wp]
    half(:, 2) = 0.0_wp
    frame(:, :, 1) = identity3()
    frame(:, :, 2) = identity3()
    do k = 1, 6
      c(:, 1) = 0.0_wp
      c(:, 2) = heights(1:3, k)
      call broad3_pairs(b, c, [norm2(half(:, 1)), 0.5_wp], [1, 2], 0.1_wp, [.true., .false.], half, frame)
      write (label, '(a,3f6.2,a,i0)') 'sphere at', c(:, 2), ' over a PLANx: pairs = ', nint(heights(4, k))
      call check_true(trim(label), b%npairs == nint(heights(4, k)))
    end do
    th = acos(-1.0_wp) / 6.0_wp
    frame(:, :, 1) = rotation_of_vector([th, 0.0_wp, 0.0_wp])
    n = frame(:, 3, 1)
    c(:, 1) = [1.0_wp, 2.0_wp, 3.0_wp]
    c(:, 2) = c(:, 1) + (1.1_wp - 1.0e-9_wp) * n
    call broad3_pairs(b, c, [norm2(half(:, 1)), 0.5_wp], [1, 2], 0.1_wp, [.true., .false.], half, frame)
    call check_true('sphere 1.1 - 1e-9 along a turned PLANx normal: one pair', b%npairs == 1)
    c(:, 2) = c(:, 1) + (1.1_wp + 1.0e-9_wp) * n
    call broad3_pairs(b, c, [norm2(half(:, 1)), 0.5_wp], [1, 2], 0.1_wp, [.true., .false.], half, frame)
    call check_true('sphere 1.1 + 1e-9 along a turned PLANx normal: none', b%npairs == 0)
  end subroutine hand_cases

  subroutine random_scene(seed)
    integer, intent(in) :: seed
    integer, parameter :: nsph = 1500, npol = 200, nfar = 20
    type(tactor3_t) :: t
    type(broad3_t) :: grid, brute
    real(wp), allocatable :: c(:, :), bound(:), half(:, :), frame(:, :, :)
    integer, allocatable :: body(:), kind(:)
    logical, allocatable :: big(:)
    real(wp) :: vert(3, 8)
    integer :: faces(3, 12), n, k, nb
    character(len=80) :: label
    call rng_seed(rng, seed)
    n = nsph + npol + 3
    if (seed == 3) n = n + nfar + 1
    allocate (c(3, n), bound(n), half(3, n), frame(3, 3, n), body(n), kind(n))
    half = 0.0_wp
    nb = 0
    do k = 1, n
      frame(:, :, k) = identity3()
      ! every tenth contactor shares the previous one's body (and stands next to it)
      if (mod(k, 10) /= 0 .or. k == 1) nb = nb + 1
      body(k) = nb
      c(:, k) = [40.0_wp * uniform(), 40.0_wp * uniform(), 20.0_wp * uniform()]
      if (mod(k, 10) == 0 .and. k > 1) c(:, k) = c(:, k - 1) + 0.3_wp
      if (k <= nsph) then
        kind(k) = tk3_spher
        bound(k) = 0.2_wp + 0.5_wp * uniform()
      else if (k <= nsph + npol) then
        call box_surface([0.2_wp + 0.6_wp * uniform(), 0.2_wp + 0.6_wp * uniform(), 0.2_wp + 0.6_wp * uniform()], &
                         vert, faces)
        t = polyr_from_surface(vert, faces)
        kind(k) = tk3_polyr
        bound(k) = tactor3_bound(t)
      else if (k == nsph + npol + 1) then
        kind(k) = tk3_spher
        bound(k) = 25.0_wp
      else if (k <= nsph + npol + 3) then
        kind(k) = tk3_planx
        half(:, k) = [30.0_wp, 30.0_wp, 0.5_wp]
        bound(k) = norm2(half(:, k))
        c(:, k) = [20.0_wp, 20.0_wp, 0.0_wp]
        if (k == nsph + npol + 3) then
          frame(:, :, k) = rotation_of_vector([0.0_wp, 1.3_wp, 0.0_wp])
          c(:, k) = [38.0_wp, 20.0_wp, 10.0_wp]
        end if
      else
        kind(k) = tk3_spher
        bound(k) = 0.5_wp
        c(:, k) = c(:, k) + 10.0_wp**(9 + mod(k, 4))
        if (mod(k, 3) == 0) c(:, k) = c(:, k - 1) + 0.2_wp    ! far, yet in contact
        if (k == n) c(2, k) = ieee_value(1.0_wp, ieee_quiet_nan)
      end if
    end do
    big = broad3_big(kind, bound)
    call broad3_pairs(grid, c, bound, body, 0.05_wp, big, half, frame)
    call broad3_brute(brute, c, bound, body, 0.05_wp, big, half, frame)
    write (label, '(a,i0,a,i0,a,i0,a,i0,a)') 'seed ', seed, ': ', grid%npairs, ' pairs (brute force ', &
      brute%npairs, '), ', count(big), ' big'
    call check_true(trim(label), grid%npairs == brute%npairs .and. brute%npairs > 1000 .and. count(big) == 3)
    if (grid%npairs == brute%npairs) then
      write (label, '(a,i0,a,i0,a)') 'seed ', seed, ': the same sorted pair list (', grid%ncells, ' cells)'
      call check_true(trim(label), all(grid%pair == brute%pair))
    end if
  end subroutine random_scene
end program test_broad_3d
