!> Unit tests of the exact 3D local Signorini–Coulomb solver coulomb_3d (FCLib
!> order n, t1, t2). References: closed-form cases, and the FCLib natural map,
!> which is zero exactly at a solution (reference/fclib_siconos.md §2.1), on
!> random symmetric and unsymmetric blocks from cold and warm starts.
program test_coulomb_3d
  use fracas_kinds, only: wp
  use fracas_ids, only: st_noctc, st_stick, st_slifw
  use fracas_local_solver, only: coulomb_3d, inverse_block_3d, natural_map_3d
  use fracas_random, only: rng_t, rng_seed, rng_below
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_frame_3d, only: identity3
  implicit none
  real(wp) :: w(9), wi(9), q(3), r(3), u(3), mu, worst, m(3, 3), a(3, 3), worst_inv
  integer :: status, i, j, fails, nslide
  type(rng_t) :: rng

  w = [1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp]
  wi = inverse_block_3d(w)

  ! Separating: q_n >= 0 gives r = 0.
  r = 1.0_wp
  call coulomb_3d([0.1_wp, 0.3_wp, -0.2_wp], w, wi, 0.5_wp, r, status)
  call check_true('open contact: no reaction', all(r == 0.0_wp) .and. status == st_noctc)

  ! Stick with W = I: r = -q inside the cone.
  r = 0.0_wp
  call coulomb_3d([-1.0_wp, 0.1_wp, -0.2_wp], w, wi, 0.5_wp, r, status)
  call check_true('stick status', status == st_stick)
  call check_close('stick r_n', r(1), 1.0_wp, 1e-15_wp)
  call check_close('stick r_t2', r(3), 0.2_wp, 1e-15_wp)

  ! Slide with W = I, q = (-1, 3, 4), mu = 0.5: r_n = 1, r_T = -0.5 (0.6, 0.8),
  ! u_T = (3, 4) - 0.5 (0.6, 0.8) = 4.5 (0.6, 0.8).
  r = 0.0_wp
  call coulomb_3d([-1.0_wp, 3.0_wp, 4.0_wp], w, wi, 0.5_wp, r, status)
  call check_true('slide status', status == st_slifw)
  call check_close('slide r_n', r(1), 1.0_wp, 1e-14_wp)
  call check_close('slide r_t1', r(2), -0.3_wp, 1e-14_wp)
  call check_close('slide r_t2', r(3), -0.4_wp, 1e-14_wp)

  ! Frictionless: r_T = 0, r_n = -q_n / W_nn.
  r = 0.0_wp
  call coulomb_3d([-2.0_wp, 3.0_wp, 4.0_wp], 2.0_wp * w, inverse_block_3d(2.0_wp * w), 0.0_wp, r, status)
  call check_close('frictionless r_n', r(1), 1.0_wp, 1e-15_wp)
  call check_true('frictionless r_T = 0', r(2) == 0.0_wp .and. r(3) == 0.0_wp)

  ! 20000 random blocks (seed 11): SPD (M M^T + 0.05 I) and, every other one,
  ! SPD plus a 10 % unsymmetric part; random q, mu in [0, 1.5]; start from 0 or
  ! from a random reaction (the warm start of a sweep). The natural map must vanish.
  call rng_seed(rng, 11)
  worst = 0.0_wp
  worst_inv = 0.0_wp
  fails = 0
  nslide = 0
  do i = 1, 20000
    m = reshape([(2.0_wp * uniform() - 1.0_wp, j=1, 9)], [3, 3])
    a = matmul(m, transpose(m))
    a(1, 1) = a(1, 1) + 0.05_wp; a(2, 2) = a(2, 2) + 0.05_wp; a(3, 3) = a(3, 3) + 0.05_wp
    if (mod(i, 2) == 0) a = a + 0.1_wp * reshape([(2.0_wp * uniform() - 1.0_wp, j=1, 9)], [3, 3])
    w = reshape(a, [9])
    wi = inverse_block_3d(w)
    worst_inv = max(worst_inv, maxval(abs(matmul(a, reshape(wi, [3, 3])) - identity3())))
    q = [(2.0_wp * uniform() - 1.0_wp, j=1, 3)]
    mu = 1.5_wp * uniform()
    if (mod(i, 3) == 0) then
      r = [uniform(), uniform() - 0.5_wp, uniform() - 0.5_wp]
    else
      r = 0.0_wp
    end if
    call coulomb_3d(q, w, wi, mu, r, status)
    if (status < 0) then
      fails = fails + 1
      cycle
    end if
    if (status == st_slifw) nslide = nslide + 1
    u = q + matmul(a, r)
    worst = max(worst, sqrt(natural_map_3d(u, r, mu)) / (1.0_wp + sum(abs(q))))
  end do
  call check_close('3x3 inverse: worst |W W^-1 - I|', worst_inv, 0.0_wp, 1e-9_wp)
  call check_true('enough sliding cases exercised (> 5000)', nslide > 5000)
  call check_true('local solver found an exact solution on >= 99.5 % of random blocks', fails <= 100)
  call check_close('worst natural map over 20000 random 3D local problems', worst, 0.0_wp, 1e-12_wp)
  write (*, '(a,i0,a,i0)') 'sliding cases ', nslide, ', no exact solution found ', fails
  call test_finish()

contains

  real(wp) function uniform()
    uniform = real(rng_below(rng, 1000000), wp) / 1.0e6_wp
  end function uniform
end program test_coulomb_3d
