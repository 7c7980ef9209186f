!> Frictional cohesive zone laws (the paper's equations 4-5): the cohesive
!> traction sigma = beta^k C [u] with C = diag(ct, cn), k = 2 for the Monerie–
!> Acary/RCC law (MAC) and k = 1 for the envelope laws (MP3, MAL, TH, EXPO, ABP);
!> beta in [0, 1] never grows. Each law's beta update is one pure function.
!> Only opening (<un>+) and sliding drive damage.
module fracas_czm
  use fracas_kinds, only: wp
  implicit none
  private
  public :: czm_t, czm_mac, czm_mp3, czm_mal, czm_th, czm_expo, czm_abp, czm_abp_corners, czm_beta_update, czm_beta_power, &
            czm_stored_energy, beta_broken, czm_damage_energy, czm_step_dissipation, czm_step_factor, &
            czm_softening_length

  integer, parameter :: czm_mac = 1, czm_mp3 = 2, czm_mal = 3, czm_th = 4, czm_expo = 5, czm_abp = 6
  !> Below this beta the interface is broken (beta set to 0), as in LMGC90.
  real(wp), parameter :: beta_broken = 1.0e-12_wp

  type :: czm_t
    integer :: family = 0
    real(wp) :: cn = 0.0_wp, ct = 0.0_wp      !< initial stiffnesses (Pa/m)
    real(wp) :: visco = 0.0_wp, w = 0.0_wp    !< MAC: damage viscosity b, Dupré energy w (J/m^2)
    real(wp) :: smax = 0.0_wp                 !< MP3: strength (Pa)
    real(wp) :: s1 = 0.0_wp, s2 = 0.0_wp      !< strengths in mode I and II (Pa)
    real(wp) :: g1 = 0.0_wp, g2 = 0.0_wp      !< fracture energies in mode I and II (J/m^2)
    real(wp) :: dp1 = 0.0_wp, dp2 = 0.0_wp    !< TH: end of the plateau in mode I and II (m)
    real(wp) :: eta = 0.0_wp                  !< EXPO: residual stress ratio of the cut-off
    real(wp) :: du1 = 0.0_wp, du2 = 0.0_wp    !< ABP: full-separation opening in mode I and II (m)
    real(wp) :: phi = 0.0_wp                  !< ABP: share of G on the first softening branch
    logical :: iqs = .true.                   !< IQS variant: an initial overlap is forgiven
    real(wp) :: friction_power = 1.0_wp       !< mu(beta) = mu (1 - beta)^p
  end type czm_t

contains

  !> Exponent k of beta in the traction beta^k C u.
  pure integer function czm_beta_power(p)
    type(czm_t), intent(in) :: p
    czm_beta_power = merge(2, 1, p%family == czm_mac)
  end function czm_beta_power

  !> Energy per unit length in the cohesive springs: 1/2 beta^k (cn un^2 + ct ut^2).
  !> The springs act in both directions (a compressed normal spring, possible
  !> only between driven bodies, stores energy too); only opening drives damage.
  pure real(wp) function czm_stored_energy(p, beta, ut, un) result(e)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: beta, ut, un
    e = 0.5_wp * beta**czm_beta_power(p) * (p%cn * un**2 + p%ct * ut**2)
  end function czm_stored_energy

  !> The envelope of a law (not MAC) in the mode of the jump (ut, un): mode mixity m in
  !> [0, 1] (0: pure opening, 1: pure sliding; our rule, doc/czm.md: the mode I and
  !> mode II parameters blended linearly), stiffness c, strength s, energy g and the
  !> opening di at the end of the linear branch.
  pure subroutine envelope(p, ut, un, c, s, g, di, m)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: ut, un
    real(wp), intent(out) :: c, s, g, di, m
    real(wp) :: unp
    unp = max(un, 0.0_wp)
    m = 0.0_wp
    if (ut /= 0.0_wp) m = ut**2 / (ut**2 + unp**2)
    c = (1.0_wp - m) * p%cn + m * p%ct
    select case (p%family)
    case (czm_mp3)
      s = p%smax
      g = p%w
      di = 0.5_wp * s * (1.0_wp / p%cn + 1.0_wp / p%ct)
    case default
      s = (1.0_wp - m) * p%s1 + m * p%s2
      g = (1.0_wp - m) * p%g1 + m * p%g2
      di = s / c
    end select
  end subroutine envelope

  !> Beta at the end of a step of length h, from beta_old and the end-of-step
  !> jumps (ut, un). Never larger than beta_old; below beta_broken it is 0.
  pure real(wp) function czm_beta_update(p, beta_old, ut, un, h) result(beta)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: beta_old, ut, un, h
    real(wp) :: y, unp, d, m, s, g, c, di, dk, dp, du, phi, sp
    beta = beta_old
    if (beta_old <= 0.0_wp) return
    unp = max(un, 0.0_wp)
    select case (p%family)
    case (czm_mac)
      ! Implicit Euler of b beta' = -(w - beta Y)^-, Y = cn <un>+^2 + ct ut^2.
      y = p%cn * unp**2 + p%ct * ut**2
      if (beta_old * y > p%w) beta = min(beta_old, (h * p%w + p%visco * beta_old) / (p%visco + h * y))
    case default
      d = sqrt(unp**2 + ut**2)
      if (d <= 0.0_wp) return
      call envelope(p, ut, un, c, s, g, di, m)
      if (d <= di) return
      select case (p%family)
      case (czm_mp3, czm_mal)
        ! Linear to (di, s), then parabolic softening with zero slope at the peak.
        dk = 1.5_wp * (g / s - 0.5_wp * di)
        if (d < di + dk) then
          beta = min(beta_old, (di / d) * (1.0_wp - ((d - di) / dk)**2))
        else
          beta = 0.0_wp
        end if
      case (czm_th)
        ! Trapezoid: plateau at s up to dp, linear decay to du; area g.
        dp = max(di, (1.0_wp - m) * p%dp1 + m * p%dp2)
        du = 2.0_wp * g / s - dp + di
        if (d <= dp) then
          beta = min(beta_old, di / d)
        else if (d < du) then
          beta = min(beta_old, (di / d) * (du - d) / (du - dp))
        else
          beta = 0.0_wp
        end if
      case (czm_abp)
        ! Tri-linear: (di, s) to (dp, sp) to (du, 0); area g.
        call czm_abp_corners(p, m, s, g, di, dp, sp, du)
        if (d <= dp) then
          beta = min(beta_old, (s + (sp - s) * (d - di) / (dp - di)) / (c * d))
        else if (d < du) then
          beta = min(beta_old, sp * (du - d) / ((du - dp) * c * d))
        else
          beta = 0.0_wp
        end if
      case (czm_expo)
        ! Exponential softening s exp(phi (di - d)), cut off at du.
        phi = s / (g - 0.5_wp * s * di)
        du = di - log(p%eta) / phi
        if (d < du) then
          beta = min(beta_old, (s / (c * d)) * exp(phi * (di - d)))
        else
          beta = 0.0_wp
        end if
      end select
    end select
    if (beta < beta_broken) beta = 0.0_wp
  end function czm_beta_update

  !> Energy per unit length a law has dissipated once its damage is beta, on a
  !> monotonic path in the mode of the jump (ut, un): D(beta) = Phi(d) - 1/2 beta c d^2,
  !> Phi the work of the envelope up to the opening d where it gives beta. A state
  !> function of beta (for a fixed mode), so a sequence of steps dissipates exactly
  !> D(beta_end) - D(1) whatever their size; D(0) is the law's fracture energy.
  !> MAC (Y-driven, beta^2 traction): D = w (1 - beta), the viscous part aside.
  pure real(wp) function czm_damage_energy(p, beta, ut, un) result(e)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: beta, ut, un
    real(wp) :: c, s, g, di, m, d, dk, x, dp, du, phi, f, lo, hi, sp, a
    integer :: it
    if (p%family == czm_mac) then
      e = p%w * (1.0_wp - beta)
      return
    end if
    call envelope(p, ut, un, c, s, g, di, m)
    select case (p%family)
    case (czm_mp3, czm_mal)
      ! beta = (di/d)(1 - x^2), d = di + dk x: di x^2 + beta dk x - di (1 - beta) = 0.
      dk = 1.5_wp * (g / s - 0.5_wp * di)
      x = min(1.0_wp, (-beta * dk + sqrt((beta * dk)**2 + 4.0_wp * di**2 * (1.0_wp - beta))) / (2.0_wp * di))
      d = di + dk * x
      e = 0.5_wp * c * di**2 + c * di * dk * (x - x**3 / 3.0_wp) - 0.5_wp * beta * c * d**2
    case (czm_th)
      dp = max(di, (1.0_wp - m) * p%dp1 + m * p%dp2)
      du = 2.0_wp * g / s - dp + di
      if (beta * dp >= di) then
        d = di / beta                                   ! on the plateau
        e = 0.5_wp * s * di + s * (d - di)
      else
        d = di * du / (beta * (du - dp) + di)            ! on the linear decay
        e = 0.5_wp * s * di + s * (dp - di) + s * ((d - dp) - 0.5_wp * (d - dp)**2 / (du - dp))
      end if
      e = e - 0.5_wp * beta * c * d**2
    case (czm_abp)
      call czm_abp_corners(p, m, s, g, di, dp, sp, du)
      if (beta <= 0.0_wp) then
        e = g
      else if (dp > di .and. beta * c * dp >= sp) then
        a = (sp - s) / (dp - di)                          ! on the first branch: beta c d = s + a (d - di)
        d = (s - a * di) / (beta * c - a)
        e = 0.5_wp * s * di + 0.5_wp * (d - di) * (s + beta * c * d) - 0.5_wp * beta * c * d**2
      else
        d = sp * du / (beta * c * (du - dp) + sp)         ! on the second: beta c d = sp (du - d)/(du - dp)
        e = 0.5_wp * s * di + 0.5_wp * (dp - di) * (s + sp) + 0.5_wp * (d - dp) * (sp + beta * c * d) &
            - 0.5_wp * beta * c * d**2
      end if
    case default
      ! EXPO: beta c d = s exp(phi (di - d)) on [di, du), cut to 0 at du; the opening of
      ! beta by Newton on log(c d beta / s) + phi (d - di) = 0 (increasing in d), bracketed.
      phi = s / (g - 0.5_wp * s * di)
      du = di - log(p%eta) / phi
      d = du
      if (beta > 0.0_wp) then
        lo = di; hi = du; d = di
        do it = 1, 100
          f = log(c * d * beta / s) + phi * (d - di)
          if (abs(f) <= 1.0e-14_wp) exit
          if (f > 0.0_wp) then
            hi = d
          else
            lo = d
          end if
          d = d - f / (1.0_wp / d + phi)
          if (d <= lo .or. d >= hi) d = 0.5_wp * (lo + hi)
        end do
      end if
      e = 0.5_wp * s * di + (s / phi) * (1.0_wp - exp(phi * (di - d))) - 0.5_wp * beta * c * d**2
    end select
    e = max(0.0_wp, e)
  end function czm_damage_energy

  !> Energy per unit length dissipated by damage in a step that takes beta from
  !> beta0 to beta1 at the end-of-step jump (ut, un): D(beta1) - D(beta0)
  !> (czm_damage_energy), plus for the viscous MAC law (b > 0) its viscous part
  !> b (beta0 - beta1)^2 / h (implicit Euler of b beta' = -(w - beta Y)).
  pure real(wp) function czm_step_dissipation(p, beta0, beta1, ut, un, h) result(e)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: beta0, beta1, ut, un, h
    e = 0.0_wp
    if (beta1 >= beta0) return
    e = max(0.0_wp, czm_damage_energy(p, beta1, ut, un) - czm_damage_energy(p, beta0, ut, un))
    if (p%family == czm_mac) e = e + p%visco * (beta0 - beta1)**2 / h
  end function czm_step_dissipation

  !> The factor f of the cohesive traction f C (u0 + u1)/2 (u0, u1 the jumps at the
  !> start and the end of the step) that a step applies with damage consistent within
  !> the step (doc/czm.md): beta0^k while the step does not damage (the midpoint rule:
  !> the springs' work is the change of their energy), else the discrete-gradient value
  !> whose work over the step's jump is the law's own energy along it,
  !>   f (u1.C u1 - u0.C u0)/2 = psi(beta1, u1) - psi(beta0, u0) + dissipation,
  !> so that a crack costs its fracture energy whatever its opening per step; both
  !> agree where damage starts, so f is continuous in u1. Kept in [beta1^k, beta0^k]
  !> ([0, beta0^k] for a viscous MAC law);
  !> beta1^k where the step does not stretch the springs (u1.C u1 <= u0.C u0).
  pure real(wp) function czm_step_factor(p, beta0, beta1, u0, u1, h) result(f)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: beta0, beta1, u0(2), u1(2), h
    real(wp) :: work, den, lo
    integer :: k
    k = czm_beta_power(p)
    f = beta0**k
    if (beta1 >= beta0) return
    den = 0.5_wp * (p%ct * (u1(1)**2 - u0(1)**2) + p%cn * (u1(2)**2 - u0(2)**2))
    if (den <= 0.0_wp) then
      f = beta1**k
      return
    end if
    work = czm_stored_energy(p, beta1, u1(1), u1(2)) - czm_stored_energy(p, beta0, u0(1), u0(2)) + &
           czm_step_dissipation(p, beta0, beta1, u1(1), u1(2), h)
    ! A rate-independent law's factor falls from beta0^k to beta1^k along the step, so
    ! its mean lies between them; the bracket also tames the quotient where the stretch
    ! is round-off. A viscous MAC law damages at rest: its mean may fall below beta1^k.
    lo = beta1**k
    if (p%family == czm_mac .and. p%visco > 0.0_wp) lo = 0.0_wp
    f = min(beta0**k, max(lo, work / den))
  end function czm_step_factor

  !> The corners of the ABP law's tri-linear envelope in the mode of mixity m (strength
  !> s, energy g, di = s/c from envelope): full separation du (blended linearly like the
  !> other parameters), the second corner (dp, sp) with sp = 2 g (1 - phi)/du and
  !> dp = (2 g phi + sp di)/s, so that the area is g; dp kept in [di, du] (the deck's
  !> pure modes are checked to need no clamp, law_from_input).
  pure subroutine czm_abp_corners(p, m, s, g, di, dp, sp, du)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: m, s, g, di
    real(wp), intent(out) :: dp, sp, du
    du = (1.0_wp - m) * p%du1 + m * p%du2
    sp = 2.0_wp * g * (1.0_wp - p%phi) / du
    dp = min(du, max(di, (2.0_wp * g * p%phi + sp * di) / s))
  end subroutine czm_abp_corners

  !> The opening over which a law softens in the mode of the jump (ut, un), the
  !> scale of crack_step_limit (doc/czm.md §9): from the end of its linear branch
  !> to full separation (MP3, MAL, TH, ABP); EXPO, whose cut-off lies far out, the
  !> length 1/phi over which its traction falls by e; MAC, whose damage only
  !> tends to 0 (traction w^2 / (c d^3) past the opening sqrt(w / c) where damage
  !> starts, c the mode's stiffness), that opening or d / 3, over which the
  !> traction falls by e, whichever is longer.
  pure real(wp) function czm_softening_length(p, ut, un) result(l)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: ut, un
    real(wp) :: c, s, g, di, m, dp, sp, du
    call envelope(p, ut, un, c, s, g, di, m)
    select case (p%family)
    case (czm_mac)
      l = max(sqrt(p%w / c), sqrt(max(un, 0.0_wp)**2 + ut**2) / 3.0_wp)
    case (czm_mp3, czm_mal)
      l = 1.5_wp * (g / s - 0.5_wp * di)
    case (czm_th)
      dp = max(di, (1.0_wp - m) * p%dp1 + m * p%dp2)
      l = (2.0_wp * g / s - dp + di) - dp
    case (czm_abp)
      call czm_abp_corners(p, m, s, g, di, dp, sp, du)
      l = du - di
    case default
      l = (g - 0.5_wp * s * di) / s
    end select
  end function czm_softening_length
end module fracas_czm
