!> Torque-free rotation of an asymmetric rigid body (fracas_rbdy3), I = (1, 2, 3)
!> kg m^2, spun about its intermediate axis with a small perturbation: the
!> Dzhanibekov flip. References (stated per check):
!> - kinetic energy E and |L| are invariants of the exact motion; the step
!>   (LMGC90's: explicit gyroscopic torque at the begin velocity, theta = 0.5)
!>   is first order on them, so their largest relative drift over T = 20 s
!>   must halve (ratio 2 +- 0.05) when h is halved (measured when this test was
!>   written: E 2.32e-3 -> 1.16e-3, |L| 1.16e-3 -> 0.58e-3 at h = 1e-3 -> 5e-4)
!>   and stay below 5e-3 (E) and 2.5e-3 (|L|) at h = 1e-3;
!> - the global vector L is conserved by the exact motion: drift below 2.5e-3
!>   of |L| at h = 1e-3 (measured 1.24e-3; same first-order error);
!> - the frame stays a rotation to round-off (exact updates): |F^T F - I| < 1e-11
!>   after 40000 steps (measured 1.8e-13; 2.5e-12 without
!>   the gyroscopic torque: round-off, so the bound is 1e-11);
!> - the flip: omega_2 goes from +2 to below -1.9 rad/s and back; its first
!>   zero crossing time against an RK4 integration of Euler's equations in the
!>   test (h = 1e-4, converged to 1e-6 s: 8.05326 s), within 0.016 s at
!>   h = 5e-4 (measured 8.05524 s, first-order scheme).
!> Planted bugs watched red: the gyroscopic torque left out (no flip, crossing
!> never found, drift ratios 0 and 1.90); the frame turned by [phi]x in place
!> of the exact rotation (orthonormality 2e-2); the torque's sign reversed
!> (L vector drift 1.0, crossing at 6.91 s).
program test_rbdy3_free_rotation
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_rbdy3, only: rbdy3_t, rbdy3_init, rbdy3_begin_step, rbdy3_end_step, rbdy3_kinetic_energy, &
                          rbdy3_angular_momentum
  use fracas_frame_3d, only: identity3
  implicit none
  real(wp), parameter :: inertia(3) = [1.0_wp, 2.0_wp, 3.0_wp], omega0(3) = [1.0e-3_wp, 2.0_wp, 1.0e-3_wp]
  real(wp), parameter :: t_end = 20.0_wp
  real(wp) :: de1, dl1, dlv1, tc1, orth1, wmin1, wlast1, de2, dl2, dlv2, tc2, orth2, wmin2, wlast2, tref

  tref = rk4_crossing(1.0e-4_wp)
  call check_close('RK4 reference crossing converged (h vs h/2) [s]', rk4_crossing(0.5e-4_wp), tref, 1.0e-6_wp)
  call run(1.0e-3_wp, de1, dl1, dlv1, tc1, orth1, wmin1, wlast1)
  call run(0.5e-3_wp, de2, dl2, dlv2, tc2, orth2, wmin2, wlast2)
  write (*, '(a,4es12.4)') 'h=1e-3: energy, |L|, L drift, crossing ', de1, dl1, dlv1, tc1
  write (*, '(a,4es12.4)') 'h=5e-4: energy, |L|, L drift, crossing ', de2, dl2, dlv2, tc2
  write (*, '(a,f10.6)') 'RK4 crossing ', tref
  call check_close('energy drift over 20 s, h = 1e-3', de1, 0.0_wp, 5.0e-3_wp)
  call check_close('|L| drift over 20 s, h = 1e-3', dl1, 0.0_wp, 2.5e-3_wp)
  call check_close('L vector drift over 20 s, h = 1e-3 (relative to |L|)', dlv1, 0.0_wp, 2.5e-3_wp)
  call check_close('energy drift ratio h / (h/2) (first order: 2)', de1 / max(de2, tiny(1.0_wp)), 2.0_wp, 0.05_wp)
  call check_close('|L| drift ratio h / (h/2) (first order: 2)', dl1 / max(dl2, tiny(1.0_wp)), 2.0_wp, 0.05_wp)
  call check_close('frame orthonormal after 40000 steps', orth2, 0.0_wp, 1.0e-11_wp)
  call check_true('flip: omega_2 reaches below -1.9 rad/s', wmin2 < -1.9_wp)
  call check_true('flip back: omega_2 > 0 again by 20 s or still turning (|omega_2| <= 2.01)', abs(wlast2) <= 2.01_wp)
  call check_close('first crossing of omega_2 = 0 vs RK4 [s]', tc2, tref, 0.016_wp)
  call test_finish()

contains

  !> Run the body alone for t_end; relative drifts of E, |L| and L, time of the
  !> first zero of omega_2, |F^T F - I|, min and last omega_2.
  subroutine run(h, de, dl, dlv, tcross, orth, wmin, wlast)
    real(wp), intent(in) :: h
    real(wp), intent(out) :: de, dl, dlv, tcross, orth, wmin, wlast
    type(rbdy3_t) :: b
    real(wp) :: frame(3, 3, 1), e0, l0(3), t, wprev
    integer :: k, nstep
    frame(:, :, 1) = identity3()
    call rbdy3_init(b, [1], reshape([0.0_wp, 0.0_wp, 0.0_wp], [3, 1]), frame, [1.0_wp], &
                    reshape(inertia, [3, 1]), [1.0_wp], [0.0_wp, 0.0_wp, 0.0_wp])
    b%vbegin(4:6, 1) = omega0
    b%v = b%vbegin
    e0 = rbdy3_kinetic_energy(b)
    l0 = rbdy3_angular_momentum(b, 1)
    de = 0.0_wp; dl = 0.0_wp; dlv = 0.0_wp
    tcross = -1.0_wp
    wmin = huge(1.0_wp)
    nstep = nint(t_end / h)
    t = 0.0_wp
    do k = 1, nstep
      wprev = b%vbegin(5, 1)
      call rbdy3_begin_step(b, t, h, 0.5_wp)
      call rbdy3_end_step(b, h, 0.5_wp)
      t = k * h
      de = max(de, abs(rbdy3_kinetic_energy(b) - e0) / e0)
      dl = max(dl, abs(norm2(rbdy3_angular_momentum(b, 1)) - norm2(l0)) / norm2(l0))
      dlv = max(dlv, norm2(rbdy3_angular_momentum(b, 1) - l0) / norm2(l0))
      if (tcross < 0.0_wp .and. b%v(5, 1) <= 0.0_wp .and. wprev > 0.0_wp) &
        tcross = t - h * b%v(5, 1) / (b%v(5, 1) - wprev)
      wmin = min(wmin, b%v(5, 1))
    end do
    orth = maxval(abs(matmul(transpose(b%frame(:, :, 1)), b%frame(:, :, 1)) - identity3()))
    wlast = b%v(5, 1)
  end subroutine run

  !> First zero of omega_2 for Euler's equations I w' = -(w x I w), RK4.
  real(wp) function rk4_crossing(h) result(tc)
    real(wp), intent(in) :: h
    real(wp) :: w(3), k1(3), k2(3), k3(3), k4(3), wnew(3), t
    w = omega0
    t = 0.0_wp
    tc = -1.0_wp
    do while (t < t_end)
      k1 = euler(w)
      k2 = euler(w + 0.5_wp * h * k1)
      k3 = euler(w + 0.5_wp * h * k2)
      k4 = euler(w + h * k3)
      wnew = w + h / 6.0_wp * (k1 + 2.0_wp * k2 + 2.0_wp * k3 + k4)
      if (wnew(2) <= 0.0_wp .and. w(2) > 0.0_wp) then
        tc = t + h * w(2) / (w(2) - wnew(2))
        return
      end if
      w = wnew
      t = t + h
    end do
  end function rk4_crossing

  !> Euler's equations written out (independent of the module's torque).
  pure function euler(w) result(dw)
    real(wp), intent(in) :: w(3)
    real(wp) :: dw(3)
    dw = [(inertia(2) - inertia(3)) * w(2) * w(3) / inertia(1), (inertia(3) - inertia(1)) * w(3) * w(1) / inertia(2), &
          (inertia(1) - inertia(2)) * w(1) * w(2) / inertia(3)]
  end function euler
end program test_rbdy3_free_rotation
