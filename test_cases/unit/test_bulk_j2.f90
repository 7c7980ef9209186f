!> Bulk laws at one material point (fracas_bulk), against closed forms:
!> 1. plane stress, uniaxial stress tension -> compression -> tension cycle with
!>    linear isotropic hardening: yield at yield0, plastic slope E H / (E + H),
!>    elastic unloading slope E, reverse yield at -sigma_y(p), lateral strains
!>    -nu sigma / E - eps_p / 2, p and the plastic work yield0 p + H p^2 / 2
!>    (the 1D elastoplastic solution, exact along piecewise-monotone paths);
!> 2. plane strain, uniaxial strain: sigma_xx = K eps + 2/3 sigma_y(p),
!>    p = (2 G eps - yield0) / (3 G + H) (a radial path: the return is exact);
!> 3. plane strain, uniaxial stress (sigma_yy = 0): yield at
!>    sigma_xx = yield0 / sqrt(1 - nu + nu^2) (../shared/lmgc90_decks/
!>    mesh_plastic_bar/case.md), and the case's small-strain reference at its
!>    step 60 (sigma_xx 2.351698e8, p 1.9072e-3: 7 and 5 printed digits) with
!>    the deck's strain history. Its sigma_zz 1.1005e8 is not used: the return
!>    at the deck's steps gives 1.0973e8 and the step-converged path 1.1008e8
!>    (sigma_zz is the component the yield condition barely fixes here);
!> 4. the consistent tangent against central differences of bulk_update
!>    (1e-6 relative), elastic and plastic states, both planes, all 4 columns
!>    in plane strain (the zz column is used by mean-dilatation elements);
!> 5. elastic plane stress Hooke: sigma = E/(1-nu^2) [...] and eps_zz;
!> 6. simple shear (both planes, a radial path): tau = G gamma up to
!>    yield0/sqrt(3), then tau = sigma_y(p)/sqrt(3) with gamma_p = sqrt(3) p,
!>    and elastic unloading tau = tau_1 - G (gamma_1 - gamma).
program test_bulk_j2
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_bulk, only: bulk_t, bulk_j2, bulk_elastic, plane_strain, plane_stress, bulk_update, &
                         bulk_plastic_work, gp_size, gp_sxx, gp_syy, gp_szz, gp_exx, gp_eyy, gp_ezz, &
                         gp_pxx, gp_pgxy, gp_p
  implicit none

  real(wp), parameter :: young = 2.0e11_wp, nu = 0.3_wp, sy0 = 2.0e8_wp
  type(bulk_t) :: steel

  steel = bulk_t(law=bulk_j2, density=7800.0_wp, young=young, poisson=nu, yield0=sy0, &
                 hardening=0.1_wp * young)
  call uniaxial_stress_cycle()
  call uniaxial_strain_plane_strain()
  call uniaxial_stress_plane_strain()
  call tangent_checks()
  call plane_stress_hooke()
  call simple_shear(plane_strain)
  call simple_shear(plane_stress)
  call test_finish()

contains

  !> Strain-driven step with sigma_yy = 0 imposed by Newton on eps_yy (gamma = 0).
  subroutine step_uniaxial(mat, plane, exx, eyy, s0, s1)
    type(bulk_t), intent(in) :: mat
    integer, intent(in) :: plane
    real(wp), intent(in) :: exx
    real(wp), intent(inout) :: eyy
    real(wp), intent(in) :: s0(gp_size)
    real(wp), intent(out) :: s1(gp_size)
    real(wp) :: dtan(4, 4)
    integer :: it
    do it = 1, 50
      call bulk_update(mat, plane, [exx, eyy, 0.0_wp, 0.0_wp], s0, s1, dtan)
      if (abs(s1(gp_syy)) <= 1.0e-13_wp * abs(s1(gp_sxx)) + 1.0e-30_wp) exit
      eyy = eyy - s1(gp_syy) / dtan(2, 2)
    end do
  end subroutine step_uniaxial

  subroutine uniaxial_stress_cycle()
    real(wp) :: s0(gp_size), s1(gp_size), eps, eyy, ey, et, h, sig_ref, p_ref, epsp_ref
    real(wp) :: e1, sig1, e_r, e2, sig2, e_r2, wp_sum, err_sig, err_p, err_lat, err_w
    integer :: i, n
    h = steel%hardening
    ey = sy0 / young
    et = young * h / (young + h)
    e1 = 4.0_wp * ey
    sig1 = sy0 + et * (e1 - ey)
    e_r = e1 - 2.0_wp * sig1 / young           ! reverse yield at -sig1
    e2 = -4.0_wp * ey
    sig2 = -(sig1 + et * (e_r - e2))           ! end of the compressive branch
    e_r2 = e2 + 2.0_wp * abs(sig2) / young      ! re-yield in tension
    s0 = 0.0_wp
    eyy = 0.0_wp
    wp_sum = 0.0_wp
    err_sig = 0.0_wp
    err_p = 0.0_wp
    err_lat = 0.0_wp
    err_w = 0.0_wp
    n = 0
    ! 0 -> e1 (40 steps), e1 -> e2 (80 steps), e2 -> 0 (40 steps)
    do i = 1, 160
      if (i <= 40) then
        eps = e1 * i / 40.0_wp
        if (eps <= ey) then
          sig_ref = young * eps
        else
          sig_ref = sy0 + et * (eps - ey)
        end if
      else if (i <= 120) then
        eps = e1 + (e2 - e1) * (i - 40) / 80.0_wp
        if (eps >= e_r) then
          sig_ref = sig1 + young * (eps - e1)
        else
          sig_ref = -(sig1 + et * (e_r - eps))
        end if
      else
        eps = e2 - e2 * (i - 120) / 40.0_wp
        if (eps <= e_r2) then
          sig_ref = sig2 + young * (eps - e2)
        else
          sig_ref = abs(sig2) + et * (eps - e_r2)
        end if
      end if
      call step_uniaxial(steel, plane_stress, eps, eyy, s0, s1)
      wp_sum = wp_sum + bulk_plastic_work(steel, s0(gp_p), s1(gp_p))
      ! p from the stress: each plastic branch adds |d eps| - |d sigma| / E.
      epsp_ref = eps - sig_ref / young
      if (i <= 40) then
        p_ref = epsp_ref
      else if (i <= 120) then
        p_ref = (e1 - sig1 / young) + max(0.0_wp, (e_r - eps) - (abs(sig_ref) - sig1) / young)
      else
        p_ref = (e1 - sig1 / young) + (e_r - e2) - (abs(sig2) - sig1) / young &
                + max(0.0_wp, (eps - e_r2) - (abs(sig_ref) - abs(sig2)) / young)
      end if
      err_sig = max(err_sig, abs(s1(gp_sxx) - sig_ref) / sy0)
      err_p = max(err_p, abs(s1(gp_p) - p_ref) / (ey))
      err_lat = max(err_lat, abs(s1(gp_eyy) - (-nu * sig_ref / young - 0.5_wp * epsp_ref)) / ey, &
                    abs(s1(gp_ezz) - (-nu * sig_ref / young - 0.5_wp * epsp_ref)) / ey, &
                    abs(s1(gp_pxx) - epsp_ref) / ey)
      err_w = max(err_w, abs(wp_sum - (sy0 * p_ref + 0.5_wp * h * p_ref**2)) / (sy0 * ey))
      if (i == 10) call check_close('plane stress: sigma_xx at eps = sigma_y0/E is sigma_y0', s1(gp_sxx) / sy0, &
                                    1.0_wp, 1.0e-8_wp)
      if (i == 20) call check_close('plane stress: slope at 2 eps_y is E H/(E+H)', &
                                    (s1(gp_sxx) - s0(gp_sxx)) / (young * ey / 10.0_wp) / (et / young), &
                                    1.0_wp, 1.0e-8_wp)
      if (i == 42) call check_close('plane stress: unloading slope is E', &
                                    (s1(gp_sxx) - s0(gp_sxx)) / ((e2 - e1) / 80.0_wp) / young, &
                                    1.0_wp, 1.0e-8_wp)
      if (i == 120) n = 1
      s0 = s1
    end do
    call check_close('plane stress cycle: max |sigma_xx - closed form| / sigma_y0', err_sig, 0.0_wp, 1.0e-8_wp)
    call check_close('plane stress cycle: max |p - closed form| / eps_y', err_p, 0.0_wp, 1.0e-8_wp)
    call check_close('plane stress cycle: max |eps_yy, eps_zz, eps_p - closed form| / eps_y', err_lat, &
                     0.0_wp, 1.0e-8_wp)
    call check_close('plane stress cycle: max |plastic work - (s0 p + H p^2/2)| / (s0 eps_y)', err_w, &
                     0.0_wp, 1.0e-8_wp)
    call check_true('plane stress cycle: sigma_zz = 0 and p > 3 eps_y at the end', &
                    abs(s1(gp_szz)) <= 1.0e-12_wp * sy0 .and. s1(gp_p) > 3.0_wp * ey .and. n == 1)
  end subroutine uniaxial_stress_cycle

  subroutine uniaxial_strain_plane_strain()
    real(wp) :: s0(gp_size), s1(gp_size), dtan(4, 4), kb, g, eps, p_ref, sxx, syy, err, ey
    integer :: i
    kb = young / (3.0_wp * (1.0_wp - 2.0_wp * nu))
    g = young / (2.0_wp * (1.0_wp + nu))
    ey = sy0 / (2.0_wp * g)
    s0 = 0.0_wp
    err = 0.0_wp
    do i = 1, 50
      eps = 5.0_wp * ey * i / 50.0_wp
      call bulk_update(steel, plane_strain, [eps, 0.0_wp, 0.0_wp, 0.0_wp], s0, s1, dtan)
      p_ref = max(0.0_wp, (2.0_wp * g * eps - sy0) / (3.0_wp * g + steel%hardening))
      if (p_ref > 0.0_wp) then
        sxx = kb * eps + 2.0_wp / 3.0_wp * (sy0 + steel%hardening * p_ref)
        syy = kb * eps - 1.0_wp / 3.0_wp * (sy0 + steel%hardening * p_ref)
      else
        sxx = (kb + 4.0_wp * g / 3.0_wp) * eps
        syy = (kb - 2.0_wp * g / 3.0_wp) * eps
      end if
      err = max(err, abs(s1(gp_sxx) - sxx) / sxx, abs(s1(gp_syy) - syy) / sxx, &
                abs(s1(gp_szz) - syy) / sxx, abs(s1(gp_p) - p_ref) / ey)
      if (i == 10) call check_close('plane strain uniaxial strain: 2G eps_y = sigma_y0, sigma_xx/((K+4G/3) eps_y)', &
                                    s1(gp_sxx) / ((kb + 4.0_wp * g / 3.0_wp) * ey), 1.0_wp, 1.0e-8_wp)
      s0 = s1
    end do
    call check_close('plane strain uniaxial strain: max rel. error of sigma and p against closed form', &
                     err, 0.0_wp, 1.0e-8_wp)
  end subroutine uniaxial_strain_plane_strain

  subroutine uniaxial_stress_plane_strain()
    real(wp) :: s0(gp_size), s1(gp_size), eyy, sxx_yield, e_yield, eps
    type(bulk_t) :: bar
    integer :: n
    sxx_yield = sy0 / sqrt(1.0_wp - nu + nu**2)
    e_yield = sxx_yield * (1.0_wp - nu**2) / young
    s0 = 0.0_wp
    eyy = 0.0_wp
    call step_uniaxial(steel, plane_strain, e_yield, eyy, s0, s1)
    call check_close('plane strain uniaxial stress: sigma_xx at yield / (s0/sqrt(1-nu+nu^2))', &
                     s1(gp_sxx) / sxx_yield, 1.0_wp, 1.0e-8_wp)
    call check_close('plane strain uniaxial stress: sigma_zz = nu sigma_xx at yield', &
                     s1(gp_szz) / (nu * sxx_yield), 1.0_wp, 1.0e-8_wp)
    call check_close('plane strain uniaxial stress: p at yield / eps_y', s1(gp_p) / e_yield, 0.0_wp, 1.0e-8_wp)
    call step_uniaxial(steel, plane_strain, 1.001_wp * e_yield, eyy, s0, s1)
    call check_true('plane strain uniaxial stress: plastic just past yield', s1(gp_p) > 0.0_wp)
    ! mesh_plastic_bar: E 2e11, nu 0.3, SIG0 2e8, K 2e9, bar length 0.1 m, end velocity
    ! 0.05 min(1, 1000 t), dt 1e-4, theta 0.5: u_n = 2.5e-7 n^2 (n <= 10), 5e-6 (n - 5) after.
    bar = bulk_t(law=bulk_j2, density=7800.0_wp, young=young, poisson=nu, yield0=sy0, hardening=2.0e9_wp)
    s0 = 0.0_wp
    eyy = 0.0_wp
    do n = 1, 60
      if (n <= 10) then
        eps = 2.5e-6_wp * n**2
      else
        eps = 5.0e-5_wp * (n - 5)
      end if
      call step_uniaxial(bar, plane_strain, eps, eyy, s0, s1)
      s0 = s1
    end do
    call check_close('mesh_plastic_bar reference, step 60: sigma_xx / 2.351698e8', s1(gp_sxx) / 2.351698e8_wp, &
                     1.0_wp, 1.0e-6_wp)
    call check_close('mesh_plastic_bar reference, step 60: p / 1.9072e-3', s1(gp_p) / 1.9072e-3_wp, &
                     1.0_wp, 1.0e-4_wp)
  end subroutine uniaxial_stress_plane_strain

  !> Central differences of bulk_update against dtan.
  subroutine tangent_checks()
    real(wp) :: s0(gp_size), dtan(4, 4)
    real(wp) :: base(4), plastic_start(gp_size)
    integer :: plane
    character(len=12) :: pname
    ! A state that has flowed before: eps_p and p non-zero.
    s0 = 0.0_wp
    call bulk_update(steel, plane_strain, [4.0e-3_wp, -1.0e-3_wp, 2.0e-3_wp, 0.0_wp], s0, plastic_start, dtan)
    call check_true('tangent setup: the start state is plastic', plastic_start(gp_p) > 1.0e-4_wp)
    do plane = plane_strain, plane_stress
      pname = merge('plane strain', 'plane stress', plane == plane_strain)
      ! elastic state from a virgin point
      s0 = 0.0_wp
      base = [2.0e-4_wp, -1.0e-4_wp, 1.5e-4_wp, 0.0_wp]
      call compare_fd(steel, plane, base, s0, trim(pname)//' J2 elastic', .false.)
      ! plastic loading from the virgin state and from a hardened state
      base = [6.0e-3_wp, 1.0e-3_wp, 3.0e-3_wp, 0.0_wp]
      call compare_fd(steel, plane, base, s0, trim(pname)//' J2 plastic (virgin)', .true.)
      base = [5.0e-3_wp, -2.5e-3_wp, 4.0e-3_wp, 0.0_wp]
      call compare_fd(steel, plane, base, plastic_start, trim(pname)//' J2 plastic (hardened)', .true.)
      call compare_fd(bulk_t(law=bulk_j2, young=young, poisson=nu, yield0=sy0, hardening=0.0_wp), plane, base, &
                      plastic_start, trim(pname)//' J2 plastic, H = 0', .true.)
      call compare_fd(bulk_t(law=bulk_elastic, young=young, poisson=nu), plane, base, s0, &
                      trim(pname)//' elastic', .false.)
    end do
  end subroutine tangent_checks

  subroutine compare_fd(mat, plane, eps, s0, label, expect_plastic)
    type(bulk_t), intent(in) :: mat
    integer, intent(in) :: plane
    real(wp), intent(in) :: eps(4), s0(gp_size)
    character(len=*), intent(in) :: label
    logical, intent(in) :: expect_plastic
    real(wp) :: s1(gp_size), sp(gp_size), sm(gp_size), dtan(4, 4), dummy(4, 4), e(4), h, err, fd(4)
    integer :: j, ncol
    call bulk_update(mat, plane, eps, s0, s1, dtan)
    call check_true(label//': state is '//merge('plastic', 'elastic', expect_plastic), &
                    (s1(gp_p) > s0(gp_p)) .eqv. expect_plastic)
    ncol = merge(4, 3, plane == plane_strain)
    err = 0.0_wp
    do j = 1, ncol
      h = 1.0e-6_wp * maxval(abs(eps))
      e = eps
      e(j) = eps(j) + h
      call bulk_update(mat, plane, e, s0, sp, dummy)
      e(j) = eps(j) - h
      call bulk_update(mat, plane, e, s0, sm, dummy)
      fd = (sp(1:4) - sm(1:4)) / (2.0_wp * h)
      err = max(err, maxval(abs(fd - dtan(:, j))))
    end do
    call check_close(label//': |dtan - central difference| / max|dtan|', err / maxval(abs(dtan)), 0.0_wp, 1.0e-6_wp)
    call check_close(label//': dtan symmetric', maxval(abs(dtan - transpose(dtan))) / maxval(abs(dtan)), &
                     0.0_wp, 1.0e-12_wp)
  end subroutine compare_fd

  subroutine plane_stress_hooke()
    type(bulk_t) :: el
    real(wp) :: s0(gp_size), s1(gp_size), dtan(4, 4), e(3), c
    el = bulk_t(law=bulk_elastic, density=1.0_wp, young=young, poisson=nu)
    e = [3.0e-4_wp, -1.0e-4_wp, 2.0e-4_wp]
    s0 = 0.0_wp
    call bulk_update(el, plane_stress, [e, 0.0_wp], s0, s1, dtan)
    c = young / (1.0_wp - nu**2)
    call check_close('plane stress Hooke: sigma_xx / (E/(1-nu^2)(exx + nu eyy))', &
                     s1(gp_sxx) / (c * (e(1) + nu * e(2))), 1.0_wp, 1.0e-12_wp)
    call check_close('plane stress Hooke: sigma_yy / (E/(1-nu^2)(eyy + nu exx))', &
                     s1(gp_syy) / (c * (e(2) + nu * e(1))), 1.0_wp, 1.0e-12_wp)
    call check_close('plane stress Hooke: sigma_xy / (E/(2(1+nu)) gamma)', &
                     s1(3) / (young / (2.0_wp * (1.0_wp + nu)) * e(3)), 1.0_wp, 1.0e-12_wp)
    call check_close('plane stress Hooke: eps_zz / (-nu/(1-nu)(exx + eyy))', &
                     s1(gp_ezz) / (-nu / (1.0_wp - nu) * (e(1) + e(2))), 1.0_wp, 1.0e-12_wp)
    call check_close('plane stress Hooke: D(1,2) / (nu E/(1-nu^2))', dtan(1, 2) / (nu * c), 1.0_wp, 1.0e-12_wp)
    call check_true('gp layout: strain xx at 5', gp_exx == 5)
  end subroutine plane_stress_hooke
  subroutine simple_shear(plane)
    integer, intent(in) :: plane
    real(wp) :: s0(gp_size), s1(gp_size), dtan(4, 4), g, h, gam, gam_y, gam1, tau1, p, tau_ref, err
    character(len=12) :: pname
    integer :: i
    pname = merge('plane strain', 'plane stress', plane == plane_strain)
    g = young / (2.0_wp * (1.0_wp + nu))
    h = steel%hardening
    gam_y = sy0 / sqrt(3.0_wp) / g
    gam1 = 4.0_wp * gam_y
    s0 = 0.0_wp
    err = 0.0_wp
    ! load to 4 gamma_y in 20 steps, unload by 1.5 gamma_y in 5 steps (elastic)
    do i = 1, 25
      if (i <= 20) then
        gam = gam1 * i / 20.0_wp
      else
        gam = gam1 - 1.5_wp * gam_y * (i - 20) / 5.0_wp
      end if
      call bulk_update(steel, plane, [0.0_wp, 0.0_wp, gam, 0.0_wp], s0, s1, dtan)
      ! loading: gamma = tau/G + sqrt(3) p, tau = (s0 + H p)/sqrt(3)
      ! (p frozen at its gamma_1 value while unloading)
      p = max(0.0_wp, (merge(gam, gam1, i <= 20) - gam_y) / (sqrt(3.0_wp) + h / (sqrt(3.0_wp) * g)))
      tau1 = (sy0 + h * p) / sqrt(3.0_wp)
      if (gam <= gam_y) then
        tau_ref = g * gam
      else if (i <= 20) then
        tau_ref = tau1
      else
        tau_ref = tau1 - g * (gam1 - gam)
      end if
      err = max(err, abs(s1(3) - tau_ref) / sy0, abs(s1(gp_p) - p) / gam_y, &
                abs(s1(gp_pgxy) - sqrt(3.0_wp) * p) / gam_y, &
                maxval(abs(s1([gp_sxx, gp_syy, gp_szz]))) / sy0)
      s0 = s1
    end do
    call check_close(trim(pname)//' simple shear: max error of tau, p, gamma_p against closed form', &
                     err, 0.0_wp, 1.0e-8_wp)
  end subroutine simple_shear
end program test_bulk_j2
