!> Unit tests of the cohesive beta updates (fracas_czm: czm_beta_update) against
!> the closed forms of each law. The quasi-static curve of a law is obtained by
!> walking a fine monotonic path of the jump with the update (beta at each point
!> from the previous one), the stress being sigma = beta^k c d (k = 2 for MAC,
!> 1 otherwise); its peak and its work int sigma dd are compared with:
!>
!> * MAC (Monerie–Acary / RCC), b = 0 [../shared/reference/czm.md §1.2, lmgc90.md §5.3]:
!>   beta = min(1, w/(c d^2)); sigma = c d up to d0 = sqrt(w/c), peak sqrt(c w),
!>   then w^2/(c d^3); work up to d: w - (w/2)(d0/d)^2 -> w.
!>   b > 0: implicit Euler of b beta' = -(w - beta Y)^-, Y = cn <un>+^2 + ct ut^2:
!>   beta_new = (b beta + h w)/(b + h Y) when beta Y > w, else unchanged (czm.md §1.3 step 4).
!> * MP3 (Monerie–Perales, czm.md §1.2): di = (smax/2)(1/cn + 1/ct), dk = 1.5 (w/smax - di/2),
!>   beta = (di/d)(1 - ((d - di)/dk)^2) on [di, di + dk], 0 beyond; with cn = ct = c the
!>   stress is c d up to smax at di, then smax (1 - x^2), x = (d - di)/dk; work
!>   smax di/2 + 2/3 smax dk = w. With cn /= ct the mode I peak is cn di.
!> * MAL (czm.md §1.2, lmgc90.md §5.3): the MP3 shape per mode with di = s/c:
!>   mode I (s1, G1, cn), mode II (s2, G2, ct): peaks s1, s2, works G1, G2.
!> * TH (Tvergaard–Hutchinson trapezoid, lmgc90.md §5.3): linear to di = s/c, plateau s
!>   to dp, linear to zero at du = 2G/s - dp + di: peak s, work G.
!> * EXPO (lmgc90.md §5.3): linear to di = s/c, then s exp(phi (di - d)),
!>   phi = s/(G - s di/2), cut to 0 at du = di - ln(eta)/phi: peak s, work
!>   s di/2 + (G - s di/2)(1 - eta) = G - eta (G - s di/2).
!> * ABP (tri-linear, lmgc90.md §5.3): linear to (di, s), di = s/c, then to (dp, sp), then
!>   to (du, 0), sp = 2G (1 - phi)/du, dp = (2 G phi + sp di)/s: peak s, work G.
!> And for every envelope law the damage energy D(beta) (czm_damage_energy, a closed
!> form per law) against the walk's work up to d less the stored 1/2 beta c d^2.
!> Irreversibility: beta never grows; on unloading beta is frozen and the stress
!> goes back along the secant beta^k c d; reloading follows the secant until the
!> envelope, then damage resumes.
program test_czm_laws
  use fracas_kinds, only: wp
  use fracas_czm, only: czm_t, czm_mac, czm_mp3, czm_mal, czm_th, czm_expo, czm_abp, czm_beta_update, &
                        czm_beta_power, czm_stored_energy, beta_broken, czm_step_factor, czm_damage_energy
  use fracas_testing, only: check_close, check_true, test_finish
  implicit none
  integer, parameter :: opening = 1, sliding = 2
  real(wp), parameter :: h = 1.0e-4_wp
  type(czm_t) :: p
  real(wp) :: energy, peak, dpeak, beta, beta2, d0, di, dk, dp, du, phi, ref, y, growth
  real(wp), allocatable :: path(:)
  integer :: i

  ! ------------------------------------------------------------------ MAC, b = 0
  p = czm_t(family=czm_mac, cn=1.0e10_wp, ct=1.0e11_wp, visco=0.0_wp, w=40.0_wp)
  d0 = sqrt(p%w / p%cn)
  ! Pointwise: beta = min(1, w/(cn un^2)) on a monotonic opening.
  beta = 1.0_wp
  do i = 1, 5
    beta = czm_beta_update(p, beta, 0.0_wp, 0.5_wp * i * d0, h)
    call check_close('MAC b=0 beta(un) = min(1, w/(cn un^2))', beta, min(1.0_wp, p%w / (p%cn * (0.5_wp * i * d0)**2)), &
                     1e-15_wp)
  end do
  ! Peak and energy in mode I: fine uniform path to d0, geometric to 1000 d0.
  path = [uniform(0.0_wp, d0, 4000), geometric(d0, 1000.0_wp * d0, 200000)]
  call walk(p, opening, path, energy, peak, dpeak, growth)
  call check_close('MAC mode I peak / sqrt(cn w)', peak / sqrt(p%cn * p%w), 1.0_wp, 1e-12_wp)
  call check_close('MAC mode I opening at peak / sqrt(w/cn)', dpeak / d0, 1.0_wp, 1e-12_wp)
  ref = p%w - 0.5_wp * p%w * (d0 / path(size(path)))**2
  call check_close('MAC mode I work to 1000 d0 / (w - w/2 (d0/d)^2)', energy / ref, 1.0_wp, 1e-8_wp)
  call check_close('MAC mode I work / w (tail 5e-7 w left)', energy / p%w, 1.0_wp, 1e-6_wp)
  call check_true('MAC mode I: beta never grows', growth <= 0.0_wp)
  ! Softening branch sigma = w^2/(cn d^3) at d = 3 d0.
  beta = czm_beta_update(p, 1.0_wp, 0.0_wp, 3.0_wp * d0, h)
  call check_close('MAC sigma(3 d0) / (w^2/(cn (3 d0)^3))', beta**2 * p%cn * 3.0_wp * d0 / &
                   (p%w**2 / (p%cn * (3.0_wp * d0)**3)), 1.0_wp, 1e-14_wp)
  ! Mode II: the same with ct.
  d0 = sqrt(p%w / p%ct)
  path = [uniform(0.0_wp, d0, 4000), geometric(d0, 1000.0_wp * d0, 200000)]
  call walk(p, sliding, path, energy, peak, dpeak, growth)
  call check_close('MAC mode II peak / sqrt(ct w)', peak / sqrt(p%ct * p%w), 1.0_wp, 1e-12_wp)
  call check_close('MAC mode II work / w', energy / p%w, 1.0_wp, 1e-6_wp)
  ! Negative sliding drives damage like positive sliding; compression does not.
  call check_close('MAC beta(ut = -2 d0t) = 1/4', czm_beta_update(p, 1.0_wp, -2.0_wp * d0, 0.0_wp, h), 0.25_wp, 1e-15_wp)
  call check_close('MAC: no damage in compression', czm_beta_update(p, 1.0_wp, 0.0_wp, -1.0_wp, h), 1.0_wp, 0.0_wp)
  ! Mixed mode on a radial path (un, ut) = d (a, b): Y = (cn a^2 + ct b^2) d^2.
  y = p%cn * 0.6_wp**2 + p%ct * 0.8_wp**2
  call check_close('MAC mixed radial path beta = w/(Y)', czm_beta_update(p, 1.0_wp, 0.8_wp * 1.0e-4_wp, &
                   0.6_wp * 1.0e-4_wp, h), p%w / (y * 1.0e-8_wp), 1e-15_wp)
  ! Irreversibility: up to 3 d0, down to 0, up to 5 d0 (mode I).
  d0 = sqrt(p%w / p%cn)
  call cycle_check(p, opening, d0, 'MAC')
  call step_factor_bracket(p, d0, 'MAC')

  ! ------------------------------------------------------------------ MAC, b > 0
  ! Implicit Euler: beta_new = (b beta_old + h w)/(b + h Y) when beta_old Y > w.
  p = czm_t(family=czm_mac, cn=1.0e10_wp, ct=1.0e11_wp, visco=2.0e-3_wp, w=40.0_wp)
  y = p%cn * (2.0e-4_wp)**2 + p%ct * (1.0e-5_wp)**2
  beta = czm_beta_update(p, 0.8_wp, 1.0e-5_wp, 2.0e-4_wp, h)
  call check_close('MAC b>0 implicit Euler (b beta + h w)/(b + h Y)', beta, &
                   (p%visco * 0.8_wp + h * p%w) / (p%visco + h * y), 1e-15_wp)
  call check_close('MAC b>0 discrete flow rule b (beta - beta_old)/h + (beta Y - w) = 0', &
                   (p%visco * (beta - 0.8_wp) / h + (beta * y - p%w)) / p%w, 0.0_wp, 1e-13_wp)
  call check_true('MAC b>0 beta between w/Y and beta_old', beta < 0.8_wp .and. beta > p%w / y)
  ! Below the threshold (beta_old Y <= w) beta does not move.
  call check_close('MAC b>0 below threshold: beta unchanged', &
                   czm_beta_update(p, 0.5_wp, 0.0_wp, 0.9_wp * sqrt(p%w / (0.5_wp * p%cn)), h), 0.5_wp, 0.0_wp)
  ! b -> 0 recovers min(beta, w/Y); b -> infinity freezes beta.
  p%visco = 1.0e-12_wp
  call check_close('MAC b->0 limit w/Y', czm_beta_update(p, 1.0_wp, 0.0_wp, 2.0e-4_wp, h), &
                   p%w / (p%cn * 4.0e-8_wp), 1e-9_wp)
  p%visco = 1.0e12_wp
  call check_close('MAC b->inf: beta frozen', czm_beta_update(p, 1.0_wp, 0.0_wp, 2.0e-4_wp, h), 1.0_wp, 1e-12_wp)
  ! Below beta_broken the interface is broken: beta = 0 exactly, and stays 0.
  p%visco = 0.0_wp
  call check_close('MAC beta below 1e-12 -> 0', czm_beta_update(p, 1.0_wp, 0.0_wp, 1.0e3_wp, h), 0.0_wp, 0.0_wp)
  call check_close('MAC broken stays broken', czm_beta_update(p, 0.0_wp, 0.0_wp, 0.0_wp, h), 0.0_wp, 0.0_wp)
  call check_true('beta_broken = 1e-12 (LMGC90)', beta_broken == 1.0e-12_wp)
  call check_true('MAC beta power 2', czm_beta_power(p) == 2)
  call check_close('MAC stored energy 1/2 beta^2 (cn un^2 + ct ut^2)', czm_stored_energy(p, 0.5_wp, 1.0e-5_wp, &
                   2.0e-5_wp), 0.125_wp * (1.0e10_wp * 4.0e-10_wp + 1.0e11_wp * 1.0e-10_wp), 1e-15_wp)

  ! ------------------------------------------------------------------ MP3
  p = czm_t(family=czm_mp3, cn=1.0e11_wp, ct=1.0e11_wp, smax=1.0e6_wp, w=40.0_wp)
  di = 0.5_wp * p%smax * (1.0_wp / p%cn + 1.0_wp / p%ct)
  dk = 1.5_wp * (p%w / p%smax - 0.5_wp * di)
  path = [uniform(0.0_wp, di, 2000), uniform(di, di + dk, 200000), uniform(di + dk, 2.0_wp * (di + dk), 100)]
  call walk(p, opening, path, energy, peak, dpeak, growth)
  call check_close('MP3 mode I peak / smax', peak / p%smax, 1.0_wp, 1e-12_wp)
  call check_close('MP3 mode I opening at peak / di', dpeak / di, 1.0_wp, 1e-6_wp)
  call check_close('MP3 mode I work / w', energy / p%w, 1.0_wp, 1e-9_wp)
  call check_true('MP3: beta never grows', growth <= 0.0_wp)
  call check_close('MP3 beta = 0 beyond di + dk', czm_beta_update(p, 1.0_wp, 0.0_wp, 1.001_wp * (di + dk), h), &
                   0.0_wp, 0.0_wp)
  call check_close('MP3 sigma(di + dk/2) / (3/4 smax)', czm_beta_update(p, 1.0_wp, 0.0_wp, di + 0.5_wp * dk, h) * &
                   p%cn * (di + 0.5_wp * dk) / (0.75_wp * p%smax), 1.0_wp, 1e-14_wp)
  call walk(p, sliding, path, energy, peak, dpeak, growth)
  call check_close('MP3 mode II peak / smax', peak / p%smax, 1.0_wp, 1e-12_wp)
  call check_close('MP3 mode II work / w', energy / p%w, 1.0_wp, 1e-9_wp)
  call cycle_check(p, opening, di, 'MP3')
  call step_factor_bracket(p, di, 'MP3')
  ! cn /= ct (LMGC90's di is the mean compliance): mode I peak cn di,
  ! work cn di^2/2 + 2/3 cn di dk.
  p%ct = 3.0e11_wp
  di = 0.5_wp * p%smax * (1.0_wp / p%cn + 1.0_wp / p%ct)
  dk = 1.5_wp * (p%w / p%smax - 0.5_wp * di)
  path = [uniform(0.0_wp, di, 2000), uniform(di, di + dk, 200000)]
  call walk(p, opening, path, energy, peak, dpeak, growth)
  call check_close('MP3 cn/=ct mode I peak / (cn di)', peak / (p%cn * di), 1.0_wp, 1e-12_wp)
  call check_close('MP3 cn/=ct mode I work / (cn di^2/2 + 2/3 cn di dk)', &
                   energy / (0.5_wp * p%cn * di**2 + 2.0_wp / 3.0_wp * p%cn * di * dk), 1.0_wp, 1e-9_wp)
  call check_true('MP3 beta power 1', czm_beta_power(p) == 1)

  ! ------------------------------------------------------------------ MAL
  p = czm_t(family=czm_mal, cn=1.0e11_wp, ct=5.0e10_wp, s1=1.0e6_wp, s2=2.0e6_wp, g1=40.0_wp, g2=100.0_wp)
  di = p%s1 / p%cn
  dk = 1.5_wp * (p%g1 / p%s1 - 0.5_wp * di)
  path = [uniform(0.0_wp, di, 2000), uniform(di, di + dk, 200000), uniform(di + dk, 2.0_wp * (di + dk), 100)]
  call walk(p, opening, path, energy, peak, dpeak, growth)
  call check_close('MAL mode I peak / s1', peak / p%s1, 1.0_wp, 1e-12_wp)
  call check_close('MAL mode I work / G1', energy / p%g1, 1.0_wp, 1e-9_wp)
  di = p%s2 / p%ct
  dk = 1.5_wp * (p%g2 / p%s2 - 0.5_wp * di)
  path = [uniform(0.0_wp, di, 2000), uniform(di, di + dk, 200000), uniform(di + dk, 2.0_wp * (di + dk), 100)]
  call walk(p, sliding, path, energy, peak, dpeak, growth)
  call check_close('MAL mode II peak / s2', peak / p%s2, 1.0_wp, 1e-12_wp)
  call check_close('MAL mode II work / G2', energy / p%g2, 1.0_wp, 1e-9_wp)
  call check_true('MAL: beta never grows', growth <= 0.0_wp)
  call cycle_check(p, sliding, (di + 0.3_wp * dk) / 3.0_wp, 'MAL')
  call step_factor_bracket(p, p%s1 / p%cn, 'MAL')
  call damage_energy_check(p, opening, [(p%s1 / p%cn * (1.0_wp + 0.5_wp * i), i = 1, 12)], 'MAL')

  ! ------------------------------------------------------------------ TH
  p = czm_t(family=czm_th, cn=1.0e11_wp, ct=5.0e10_wp, s1=1.0e6_wp, s2=2.0e6_wp, g1=40.0_wp, g2=100.0_wp, &
            dp1=2.0e-5_wp, dp2=6.0e-5_wp)
  di = p%s1 / p%cn
  dp = p%dp1
  du = 2.0_wp * p%g1 / p%s1 - dp + di
  path = [uniform(0.0_wp, di, 2000), uniform(di, dp, 20000), uniform(dp, du, 20000), uniform(du, 2.0_wp * du, 100)]
  call walk(p, opening, path, energy, peak, dpeak, growth)
  call check_close('TH mode I peak / s1', peak / p%s1, 1.0_wp, 1e-12_wp)
  call check_close('TH mode I work / G1', energy / p%g1, 1.0_wp, 1e-9_wp)
  call check_close('TH plateau: sigma((di+dp)/2) / s1', czm_beta_update(p, 1.0_wp, 0.0_wp, 0.5_wp * (di + dp), h) * &
                   p%cn * 0.5_wp * (di + dp) / p%s1, 1.0_wp, 1e-14_wp)
  di = p%s2 / p%ct
  dp = p%dp2
  du = 2.0_wp * p%g2 / p%s2 - dp + di
  path = [uniform(0.0_wp, di, 2000), uniform(di, dp, 20000), uniform(dp, du, 20000), uniform(du, 2.0_wp * du, 100)]
  call walk(p, sliding, path, energy, peak, dpeak, growth)
  call check_close('TH mode II peak / s2', peak / p%s2, 1.0_wp, 1e-12_wp)
  call check_close('TH mode II work / G2', energy / p%g2, 1.0_wp, 1e-9_wp)
  call check_true('TH: beta never grows', growth <= 0.0_wp)
  call cycle_check(p, opening, p%s1 / p%cn, 'TH')
  call damage_energy_check(p, opening, [(p%s1 / p%cn * (1.0_wp + 0.5_wp * i), i = 1, 12)], 'TH')
  call step_factor_bracket(p, p%s1 / p%cn, 'TH')

  ! ------------------------------------------------------------------ EXPO
  p = czm_t(family=czm_expo, cn=1.0e11_wp, ct=5.0e10_wp, s1=1.0e6_wp, s2=2.0e6_wp, g1=40.0_wp, g2=100.0_wp, &
            eta=1.0e-4_wp)
  di = p%s1 / p%cn
  phi = p%s1 / (p%g1 - 0.5_wp * p%s1 * di)
  du = di - log(p%eta) / phi
  path = [uniform(0.0_wp, di, 2000), uniform(di, du, 400000), uniform(du, 2.0_wp * du, 100)]
  call walk(p, opening, path, energy, peak, dpeak, growth)
  call check_close('EXPO mode I peak / s1', peak / p%s1, 1.0_wp, 1e-12_wp)
  ref = p%g1 - p%eta * (p%g1 - 0.5_wp * p%s1 * di)
  call check_close('EXPO mode I work / (G1 - eta (G1 - s1 di/2))', energy / ref, 1.0_wp, 1e-9_wp)
  call check_close('EXPO mode I work / G1 (eta = 1e-4)', energy / p%g1, 1.0_wp, 1.0e-4_wp)
  beta = czm_beta_update(p, 1.0_wp, 0.0_wp, di + 1.0_wp / phi, h)
  call check_close('EXPO sigma(di + 1/phi) / (s1/e)', beta * p%cn * (di + 1.0_wp / phi) / (p%s1 * exp(-1.0_wp)), &
                   1.0_wp, 1e-14_wp)
  di = p%s2 / p%ct
  phi = p%s2 / (p%g2 - 0.5_wp * p%s2 * di)
  du = di - log(p%eta) / phi
  path = [uniform(0.0_wp, di, 2000), uniform(di, du, 400000), uniform(du, 2.0_wp * du, 100)]
  call walk(p, sliding, path, energy, peak, dpeak, growth)
  call check_close('EXPO mode II peak / s2', peak / p%s2, 1.0_wp, 1e-12_wp)
  ref = p%g2 - p%eta * (p%g2 - 0.5_wp * p%s2 * di)
  call check_close('EXPO mode II work / (G2 - eta (G2 - s2 di/2))', energy / ref, 1.0_wp, 1e-9_wp)
  call check_true('EXPO: beta never grows', growth <= 0.0_wp)
  call cycle_check(p, opening, p%s1 / p%cn, 'EXPO')
  call step_factor_bracket(p, p%s1 / p%cn, 'EXPO')
  ! Once cut (d >= du, mode I) the interface stays broken even if closed again.
  di = p%s1 / p%cn
  phi = p%s1 / (p%g1 - 0.5_wp * p%s1 * di)
  du = di - log(p%eta) / phi
  call check_close('EXPO just below du: beta > 0', czm_beta_update(p, 1.0_wp, 0.0_wp, 0.999_wp * du, h) * p%cn * &
                   0.999_wp * du / p%s1, exp(phi * (di - 0.999_wp * du)), 1e-12_wp)
  beta = czm_beta_update(p, 1.0_wp, 0.0_wp, 1.01_wp * du, h)
  beta2 = czm_beta_update(p, beta, 0.0_wp, 0.1_wp * di, h)
  call check_true('EXPO broken beyond du and stays broken', beta == 0.0_wp .and. beta2 == 0.0_wp)
  call damage_energy_check(p, opening, [(di * (1.0_wp + 0.5_wp * i), i = 1, 12)], 'EXPO')

  ! ------------------------------------------------------------------ ABP
  p = czm_t(family=czm_abp, cn=1.0e11_wp, ct=5.0e10_wp, s1=1.0e6_wp, s2=2.0e6_wp, g1=40.0_wp, g2=100.0_wp, &
            du1=6.0e-5_wp, du2=1.5e-4_wp, phi=0.5_wp)
  call abp_pure_mode(p, opening, 'ABP mode I')
  call abp_pure_mode(p, sliding, 'ABP mode II')
  call cycle_check(p, opening, p%s1 / p%cn, 'ABP')
  call step_factor_bracket(p, p%s1 / p%cn, 'ABP')
  beta = czm_beta_update(p, 1.0_wp, 0.0_wp, 1.01_wp * p%du1, h)
  beta2 = czm_beta_update(p, beta, 0.0_wp, 0.1_wp * p%s1 / p%cn, h)
  call check_true('ABP broken beyond du and stays broken', beta == 0.0_wp .and. beta2 == 0.0_wp)

  call test_finish()

contains

  !> ABP in one pure mode: the walk's peak s and work G, the traction at the corner dp
  !> (sp) and half-way down the last piece (sp/2), beta never growing, and D(beta).
  subroutine abp_pure_mode(p, mode, name)
    type(czm_t), intent(in) :: p
    integer, intent(in) :: mode
    character(*), intent(in) :: name
    real(wp) :: c, s, g, di, sp, dp, du, work, pk, dpk, gr, d
    integer :: j
    c = merge(p%cn, p%ct, mode == opening)
    s = merge(p%s1, p%s2, mode == opening)
    g = merge(p%g1, p%g2, mode == opening)
    du = merge(p%du1, p%du2, mode == opening)
    di = s / c
    sp = 2.0_wp * g * (1.0_wp - p%phi) / du
    dp = (2.0_wp * g * p%phi + sp * di) / s
    call walk(p, mode, [uniform(0.0_wp, di, 2000), uniform(di, dp, 20000), uniform(dp, du, 20000), &
                        uniform(du, 2.0_wp * du, 100)], work, pk, dpk, gr)
    call check_close(name // ' peak / s', pk / s, 1.0_wp, 1e-12_wp)
    call check_close(name // ' work / G', work / g, 1.0_wp, 1e-9_wp)
    call check_true(name // ': beta never grows', gr <= 0.0_wp)
    d = 0.5_wp * (dp + du)
    call check_close(name // ' sigma(dp) / sp', upd(p, mode, 1.0_wp, dp) * c * dp / sp, 1.0_wp, 1e-13_wp)
    call check_close(name // ' sigma((dp + du)/2) / (sp/2)', upd(p, mode, 1.0_wp, d) * c * d / (0.5_wp * sp), 1.0_wp, 1e-13_wp)
    call damage_energy_check(p, mode, [(di + (1.1_wp * du - di) * j / 12.0_wp, j = 1, 12)], name)
  end subroutine abp_pure_mode

  !> D(beta) (czm_damage_energy) at the damage a monotonic pure-mode path reaches at each
  !> opening d(:) against the path's own work up to d less the stored 1/2 beta^k c d^2
  !> (walk: trapezoidal work on 20000 points per segment).
  subroutine damage_energy_check(p, mode, d, name)
    type(czm_t), intent(in) :: p
    integer, intent(in) :: mode
    real(wp), intent(in) :: d(:)
    character(*), intent(in) :: name
    real(wp) :: work, pk, dpk, gr, c, b, ref, worst
    integer :: j
    c = merge(p%cn, p%ct, mode == opening)
    worst = 0.0_wp
    do j = 1, size(d)
      call walk(p, mode, uniform(0.0_wp, d(j), 20000), work, pk, dpk, gr)
      b = merge(czm_beta_update(p, 1.0_wp, 0.0_wp, d(j), h), czm_beta_update(p, 1.0_wp, d(j), 0.0_wp, h), &
                mode == opening)
      ref = work - 0.5_wp * b**czm_beta_power(p) * c * d(j)**2
      if (mode == opening) then
        worst = max(worst, abs(czm_damage_energy(p, b, 0.0_wp, d(j)) - ref))
      else
        worst = max(worst, abs(czm_damage_energy(p, b, d(j), 0.0_wp) - ref))
      end if
    end do
    call check_close(name // ': D(beta) - (work - stored), of G, worst over the path', &
                     worst / merge(p%g1, p%g2, mode == opening), 0.0_wp, 1.0e-7_wp)
  end subroutine damage_energy_check

  !> The factor of a damaging step (czm_step_factor) is the mean of a traction factor
  !> that falls from beta0^k to beta1^k along the step, so it lies between them, also
  !> when the step's stretch is so small that its work / stretch quotient is round-off
  !> (0/0 at zero motion: it gave values far outside, even 0). Openings 1.1 to 5 times
  !> dref, directions from mode II to mode I, increments 0.1 to 1e-14 of the opening.
  subroutine step_factor_bracket(p, dref, name)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: dref
    character(*), intent(in) :: name
    real(wp), parameter :: scales(5) = [1.1_wp, 1.5_wp, 2.0_wp, 3.0_wp, 5.0_wp]
    real(wp) :: a, u0(2), u1(2), b0, b1, f, worst
    integer :: i, j, m, k, n
    k = czm_beta_power(p)
    worst = 0.0_wp
    n = 0
    do m = 1, size(scales)
      do i = 0, 4
        a = i * 0.125_wp * acos(-1.0_wp)
        u0 = scales(m) * dref * [cos(a), sin(a)]
        b0 = czm_beta_update(p, 1.0_wp, u0(1), u0(2), h)
        do j = 1, 14
          u1 = u0 * (1.0_wp + 10.0_wp**(-j))
          b1 = czm_beta_update(p, b0, u1(1), u1(2), h)
          if (.not. (b1 < b0 .and. b1 > 0.0_wp)) cycle
          f = czm_step_factor(p, b0, b1, u0, u1, h)
          worst = max(worst, (b1**k - f) / b0**k, (f - b0**k) / b0**k)
          n = n + 1
        end do
      end do
    end do
    call check_true(name // ': damaging steps sampled for the step factor', n >= 50)
    call check_close(name // ': step factor outside [beta1^k, beta0^k] by', worst, 0.0_wp, 0.0_wp)
  end subroutine step_factor_bracket

  !> n + 1 evenly spaced points from a to b (a excluded when used after another segment
  !> is harmless: a repeated point adds no work).
  function uniform(a, b, n) result(x)
    real(wp), intent(in) :: a, b
    integer, intent(in) :: n
    real(wp) :: x(n + 1)
    integer :: j
    x = [(a + (b - a) * real(j, wp) / n, j = 0, n)]
    x(n + 1) = b
  end function uniform

  !> n + 1 points in geometric progression from a > 0 to b.
  function geometric(a, b, n) result(x)
    real(wp), intent(in) :: a, b
    integer, intent(in) :: n
    real(wp) :: x(n + 1)
    integer :: j
    x = [(a * (b / a)**(real(j, wp) / n), j = 0, n)]
    x(1) = a
    x(n + 1) = b
  end function geometric

  !> Walk the monotonic path s(:) of the opening (mode = opening) or the slip
  !> (mode = sliding) from a sound interface, updating beta at each point.
  !> Work by the trapezoidal rule on sigma = beta^k c s, the peak stress and
  !> where it is reached, and the largest growth of beta between points.
  subroutine walk(p, mode, s, work, peak, speak, growth)
    type(czm_t), intent(in) :: p
    integer, intent(in) :: mode
    real(wp), intent(in) :: s(:)
    real(wp), intent(out) :: work, peak, speak, growth
    real(wp) :: beta, beta_new, sig, sig_old, c
    integer :: j
    c = merge(p%cn, p%ct, mode == opening)
    beta = 1.0_wp
    work = 0.0_wp
    peak = 0.0_wp
    speak = 0.0_wp
    growth = -huge(1.0_wp)
    sig_old = 0.0_wp
    do j = 1, size(s)
      if (mode == opening) then
        beta_new = czm_beta_update(p, beta, 0.0_wp, s(j), h)
      else
        beta_new = czm_beta_update(p, beta, s(j), 0.0_wp, h)
      end if
      growth = max(growth, beta_new - beta)
      beta = beta_new
      sig = beta**czm_beta_power(p) * c * s(j)
      if (j > 1) work = work + 0.5_wp * (sig + sig_old) * (s(j) - s(j - 1))
      if (sig > peak) then
        peak = sig
        speak = s(j)
      end if
      sig_old = sig
    end do
  end subroutine walk

  !> Load to 3 d1 (d1: end of the elastic range), unload to 0, reload to 5 d1:
  !> beta frozen while unloading and reloading below 3 d1 (stress on the secant
  !> beta^k c d), damage resuming beyond 3 d1 at the monotonic envelope.
  subroutine cycle_check(p, mode, d1, name)
    type(czm_t), intent(in) :: p
    integer, intent(in) :: mode
    real(wp), intent(in) :: d1
    character(len=*), intent(in) :: name
    real(wp) :: beta, beta_max, beta_mono, s, dmax_frozen, growth
    integer :: j
    beta = 1.0_wp
    growth = -1.0_wp
    do j = 1, 300
      s = 3.0_wp * d1 * j / 300.0_wp
      beta_max = beta
      beta = upd(p, mode, beta, s)
      growth = max(growth, beta - beta_max)
    end do
    beta_max = beta               ! beta at 3 d1
    dmax_frozen = 0.0_wp
    do j = 299, 0, -1             ! unload to 0 and reload to 3 d1: frozen
      s = 3.0_wp * d1 * j / 300.0_wp
      beta = upd(p, mode, beta, s)
      dmax_frozen = max(dmax_frozen, abs(beta - beta_max))
    end do
    do j = 1, 300
      s = 3.0_wp * d1 * j / 300.0_wp
      beta = upd(p, mode, beta, s)
      dmax_frozen = max(dmax_frozen, abs(beta - beta_max))
    end do
    call check_close(name//' unload/reload below the previous maximum: beta frozen', dmax_frozen, 0.0_wp, 0.0_wp)
    do j = 301, 500               ! beyond: back on the monotonic envelope
      s = 3.0_wp * d1 * j / 300.0_wp
      beta_max = beta
      beta = upd(p, mode, beta, s)
      growth = max(growth, beta - beta_max)
    end do
    beta_mono = upd(p, mode, 1.0_wp, 5.0_wp * d1)
    call check_close(name//' reload to 5 d1: beta on the monotonic envelope', beta, beta_mono, 1e-15_wp)
    call check_true(name//' cycle: beta never grows', growth <= 0.0_wp)
  end subroutine cycle_check

  !> Beta after a step to the jump s (opening or slip) from beta_old.
  real(wp) function upd(p, mode, beta_old, s)
    type(czm_t), intent(in) :: p
    integer, intent(in) :: mode
    real(wp), intent(in) :: beta_old, s
    if (mode == opening) then
      upd = czm_beta_update(p, beta_old, 0.0_wp, s, h)
    else
      upd = czm_beta_update(p, beta_old, s, 0.0_wp, h)
    end if
  end function upd
end program test_czm_laws
