!> Unit tests of the exact 2D local Signorini–Coulomb solver. References: the
!> closed-form solution of each case (written next to it), and the FCLib
!> natural map, which is zero exactly at a solution (fclib_siconos.md §2.1).
program test_local_solver
  use fracas_kinds, only: wp
  use fracas_ids, only: st_noctc, st_stick, st_slifw, st_slibw
  use fracas_local_solver, only: coulomb_2d, natural_map_2d, gs_sweep_2d_packed, pk_size, inverse_block
  use fracas_random, only: rng_t, rng_seed, rng_below
  use fracas_testing, only: check_close, check_true, test_finish
  implicit none
  real(wp) :: rt, rn, ut, un, wtt, wtn, wnn, uft, ufn, mu, worst, a, b, cc
  integer :: status, i
  type(rng_t) :: rng

  ! Separating: uf_n >= 0 gives r = 0.
  call coulomb_2d(0.3_wp, 0.1_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.5_wp, rt, rn, status)
  call check_true('open contact: no reaction', rt == 0.0_wp .and. rn == 0.0_wp .and. status == st_noctc)

  ! Stick with W = I: r = -uf = (0.1, 1), inside the cone |0.1| <= 0.5.
  call coulomb_2d(-0.1_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.5_wp, rt, rn, status)
  call check_true('stick status', status == st_stick)
  call check_close('stick rt', rt, 0.1_wp, 1e-15_wp)
  call check_close('stick rn', rn, 1.0_wp, 1e-15_wp)

  ! Slide backward with W = I, uf = (-1, -1), mu = 0.3: rn = 1, rt = +0.3, ut = -0.7.
  call coulomb_2d(-1.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.3_wp, rt, rn, status)
  call check_true('slide backward status', status == st_slibw)
  call check_close('slide backward rn', rn, 1.0_wp, 1e-15_wp)
  call check_close('slide backward rt', rt, 0.3_wp, 1e-15_wp)

  ! Slide forward with coupling: W = [2 0.5; 0.5 1], uf = (2, -1), mu = 0.2:
  ! rt = -0.2 rn, un = -1 + (1 - 0.2*0.5) rn = 0 -> rn = 1/0.9.
  call coulomb_2d(2.0_wp, -1.0_wp, 2.0_wp, 0.5_wp, 0.5_wp, 1.0_wp, 0.2_wp, rt, rn, status)
  call check_true('slide forward status', status == st_slifw)
  call check_close('slide forward rn', rn, 1.0_wp / 0.9_wp, 1e-14_wp)
  call check_close('slide forward rt', rt, -0.2_wp / 0.9_wp, 1e-14_wp)

  ! 10000 random SPD blocks and free velocities (seed 7): the natural map of
  ! the local solution must vanish to round-off.
  call rng_seed(rng, 7)
  worst = 0.0_wp
  do i = 1, 10000
    a = 0.1_wp + uniform(); b = uniform() - 0.5_wp; cc = 0.1_wp + uniform()
    wtt = a; wtn = b * sqrt(a * cc) * 0.9_wp; wnn = cc
    uft = 2.0_wp * uniform() - 1.0_wp; ufn = 2.0_wp * uniform() - 1.0_wp
    mu = uniform()
    call coulomb_2d(uft, ufn, wtt, wtn, wtn, wnn, mu, rt, rn, status)
    ut = uft + wtt * rt + wtn * rn
    un = ufn + wtn * rt + wnn * rn
    worst = max(worst, sqrt(natural_map_2d(ut, un, rt, rn, mu)) / (1.0_wp + abs(uft) + abs(ufn)))
  end do
  call check_close('worst natural map over 10000 random local problems', worst, 0.0_wp, 1e-12_wp)
  call kernels_agree(1.0_wp)
  call kernels_agree(0.9_wp)
  call test_finish()

contains

  !> The rigid kernel's lean sweep (sweep_plain: no check, no cohesion) writes the
  !> rigid sides' H out by hand; the general one (sweep_general) goes through the
  !> rigid body model's side procedures (rbdy2_side.inc). From the same state, one
  !> sweep of each must give the same impulses and body velocities bit for bit:
  !> 60 random contacts between 20 bodies (random frames, lever arms, inverse
  !> masses, Delassus blocks, shifts, friction, warm-start impulses).
  subroutine kernels_agree(relax)
    real(wp), intent(in) :: relax
    integer, parameter :: nb = 20, nc = 60
    integer :: cb(2, nc), icoh(nc), st1(nc), st2(nc), k
    real(wp) :: cr(pk_size, nc), r1(2, nc), r2(2, nc), bv1(6, nb), bv2(6, nb), coh(22, 1), sums(6), maxes(2)
    real(wp) :: ang, wa, wb, wc
    do k = 1, nc
      cb(1, k) = 1 + rng_below(rng, nb)
      cb(2, k) = 1 + mod(cb(1, k) + rng_below(rng, nb - 1), nb)
      ang = 6.283185307179586_wp * uniform()
      cr(1:2, k) = [cos(ang), sin(ang)]
      cr(3:6, k) = [(uniform() - 0.5_wp, i=1, 4)]
      wa = 0.5_wp + uniform(); wb = 0.3_wp * (uniform() - 0.5_wp); wc = 0.5_wp + uniform()
      cr(7:10, k) = [wa, wb, wb, wc]
      cr(19, k) = uniform()
      cr(11:16, k) = inverse_block(wa, wb, wb, wc, cr(19, k))
      cr(17:18, k) = [uniform() - 0.5_wp, uniform() - 0.7_wp]
      cr(20, k) = 0.0_wp
      r1(:, k) = [0.1_wp * (uniform() - 0.5_wp), 0.2_wp * uniform()]
    end do
    do k = 1, nb
      bv1(1:3, k) = [(uniform() - 0.5_wp, i=1, 3)]
      bv1(4:6, k) = [(0.5_wp + uniform(), i=1, 3)]
    end do
    icoh = 0
    coh = 0.0_wp
    st1 = st_noctc
    st2 = st_noctc
    r2 = r1
    bv2 = bv1
    call gs_sweep_2d_packed(nc, cb, cr, icoh, .false., coh, r1, st1, bv1, relax, .false., sums, maxes)
    call gs_sweep_2d_packed(nc, cb, cr, icoh, .false., coh, r2, st2, bv2, relax, .true., sums, maxes, .false.)
    call check_true('lean and general rigid sweeps agree bit for bit (relax '//merge('1.0', '0.9', relax == 1.0_wp)// &
                    '), '//'impulses and velocities', all(r1 == r2) .and. all(bv1 == bv2) .and. any(r1 /= 0.0_wp))
  end subroutine kernels_agree

  real(wp) function uniform()
    uniform = real(rng_below(rng, 1000000), wp) / 1.0e6_wp
  end function uniform
end program test_local_solver
