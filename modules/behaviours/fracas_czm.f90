!> Frictional cohesive zone laws (the paper's equations 4-5): the cohesive
!> traction sigma = beta^k C [u] with C = diag(ct, cn), k = 2 for the Monerie–
!> Acary/RCC law (MAC) and k = 1 for the envelope laws (MP3, MAL, TH, EXPO);
!> beta in [0, 1] never grows. Each law's beta update is one pure function.
!> Only opening (<un>+) and sliding drive damage.
module fracas_czm
  use fracas_kinds, only: wp
  implicit none
  private
  public :: czm_t, czm_mac, czm_mp3, czm_mal, czm_th, czm_expo, czm_beta_update, czm_beta_power, &
            czm_stored_energy, beta_broken

  integer, parameter :: czm_mac = 1, czm_mp3 = 2, czm_mal = 3, czm_th = 4, czm_expo = 5
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

  !> Beta at the end of a step of length h, from beta_old and the end-of-step
  !> jumps (ut, un). Never larger than beta_old; below beta_broken it is 0.
  pure real(wp) function czm_beta_update(p, beta_old, ut, un, h) result(beta)
    type(czm_t), intent(in) :: p
    real(wp), intent(in) :: beta_old, ut, un, h
    real(wp) :: y, unp, d, m, s, g, c, di, dk, dp, du, phi
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
      ! Mode mixity m in [0, 1] (0: pure opening, 1: pure sliding) blends the
      ! mode I and mode II parameters linearly (our rule, stated in doc/czm.md).
      m = ut**2 / (ut**2 + unp**2)
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
end module fracas_czm
