!> Contact laws as pure procedures. Each law is rewritten as a shifted
!> Signorini–Coulomb problem on the local velocity (LMGC90's change of
!> variables): the local solver sees u~ = u + shift, with friction mu, and
!> never needs to know which law it is solving.
module fracas_contact_laws
  use fracas_kinds, only: wp
  use fracas_deck, only: law_input_t
  use fracas_read_tact_behav, only: known_laws
  use fracas_errors, only: input_error
  use fracas_ids, only: st_slifw, st_slibw, st_cslfw, st_cslbw
  use fracas_czm, only: czm_t, czm_mac, czm_mp3, czm_mal, czm_th, czm_expo, czm_beta_power
  implicit none
  private
  public :: law_t, law_from_input, law_friction, law_shift, law_local_problem, &
            law_iqs_clb, law_gap_sgr_clb, law_rst_clb, law_iqs_ds_clb, law_gap_sgr_ds_clb, &
            law_vel_sgr_clb, law_rst_ds_clb, law_czm, law_iqs_clb_g0, law_elastic_repell, law_visco_elastic_repell, law_coupled_dof, &
            cohesive_elimination, coh_size, coh_law, coh_u0t, &
            coh_h, coh_factor, coh_released, coh_u0n, coh_prev, coh_uend, coh_bracket, &
            cohesive_end_jump

  !> Gaps below this (m) count as closed for the laws that act only on closed
  !> contacts: far below any physical length, far above round-off of coordinates.
  real(wp), parameter :: closed_gap = 1.0e-14_wp

  !> Layout of a cohesive contact's step data coh(coh_size): A = (I - W K)^-1 (1:4),
  !> W' = A W (5:8), a (9:10), K (11:12) at the spring factor beta0^k; coh_law: the
  !> law's index when damage is solved within the step (0: LMGC90's explicit update);
  !> coh_u0t, coh_u0n: the law's jumps at the start of the step (its internals, which
  !> the end-of-step jumps of the previous step set); coh_h: time step; coh_factor:
  !> the step's spring factor over beta0^k (1 while it does not damage; the impulse
  !> is coh_factor (a + K u~)); coh_released: the damage energy the contact released
  !> in the step (J per unit thickness), once the step is solved; coh_prev, coh_prev+1:
  !> the factor and the law's answer g of the previous pass (nlgs, damage within the step);
  !> coh_uend, coh_uend+1: u~ at the end of the step of the last check pass's local solution;
  !> coh_j0, coh_j0+1 and coh_jh: the law's jumps at the end of the step are
  !> coh(coh_j0:coh_j0+1) + coh(coh_jh) u~ (cohesive_end_jump).
  !> coh_bracket .. coh_bracket+3: the step's factors with f - g < 0 and > 0 and those
  !> values (a factor < 0: none yet), bracketing the root f = g (nlgs).
  integer, parameter :: coh_size = 29, coh_law = 13, coh_u0t = 14, coh_h = 15, coh_factor = 16, coh_released = 17, &
                        coh_u0n = 18, coh_prev = 19, coh_uend = 21, coh_j0 = 23, coh_jh = 25, coh_bracket = 26

  integer, parameter :: law_iqs_clb = 1, law_gap_sgr_clb = 2, law_rst_clb = 3, &
                        law_iqs_ds_clb = 4, law_gap_sgr_ds_clb = 5, law_vel_sgr_clb = 6, &
                        law_rst_ds_clb = 7, law_czm = 8, law_iqs_clb_g0 = 9, law_elastic_repell = 10, &
                        law_visco_elastic_repell = 11, law_coupled_dof = 12

  !> COUPLED_DOF's stiff spring, times the contact's smallest Delassus term: the
  !> relative velocity it leaves is 1/coupled_stiffness of the free one.
  real(wp), parameter :: coupled_stiffness = 1.0e8_wp

  !> A contact law ready for the solver.
  type :: law_t
    character(len=5) :: nickname = ''
    character(len=30) :: name = ''
    integer :: kind = 0
    real(wp) :: mu_dynamic = 0.0_wp   !< friction used after sliding
    real(wp) :: mu_static = 0.0_wp    !< friction used otherwise
    real(wp) :: restn = 0.0_wp, restt = 0.0_wp  !< Newton restitution (RST laws)
    real(wp) :: stiff = 0.0_wp, etan = 0.0_wp   !< repulsive spring F/gap and its dashpot (REPELL laws)
    type(czm_t) :: czm                          !< cohesive part (kind law_czm)
  end type law_t

contains

  !> Build a law from its TACT_BEHAV.DAT record (parameters in LMGC90's order).
  function law_from_input(inp) result(law)
    type(law_input_t), intent(in) :: inp
    type(law_t) :: law
    law%nickname = inp%nickname
    law%name = inp%name
    select case (trim(inp%name))
    case ('IQS_CLB')
      law%kind = law_iqs_clb
      call set_mu(param(1), param(1))
    case ('GAP_SGR_CLB')
      law%kind = law_gap_sgr_clb
      call set_mu(param(1), param(1))
    case ('VEL_SGR_CLB')
      law%kind = law_vel_sgr_clb
      call set_mu(param(1), param(1))
    case ('IQS_CLB_g0')
      law%kind = law_iqs_clb_g0
      call set_mu(param(1), param(1))
    case ('COUPLED_DOF')
      law%kind = law_coupled_dof
    case ('ELASTIC_REPELL_CLB')
      law%kind = law_elastic_repell
      law%stiff = param(1)
      call set_mu(param(2), param(2))
    case ('VISCO_ELASTIC_REPELL_CLB')
      law%kind = law_visco_elastic_repell
      law%stiff = param(1)
      law%etan = param(2)
      call set_mu(param(3), param(3))
    case ('IQS_DS_CLB')
      law%kind = law_iqs_ds_clb
      call set_mu(param(1), param(2))
    case ('GAP_SGR_DS_CLB')
      law%kind = law_gap_sgr_ds_clb
      call set_mu(param(1), param(2))
    case ('RST_CLB')
      law%kind = law_rst_clb
      law%restn = param(1)
      law%restt = param(2)
      call set_mu(param(3), param(3))
    case ('RST_DS_CLB')
      law%kind = law_rst_ds_clb
      law%restn = param(1)
      law%restt = param(2)
      call set_mu(param(3), param(4))
    case ('IQS_MAC_CZM', 'MAC_CZM')
      call set_czm(czm_mac)
      law%czm%visco = param(5)
      law%czm%w = param(6)
    case ('MP3_CZM')
      call set_czm(czm_mp3)
      law%czm%smax = param(5)
      law%czm%w = param(6)
    case ('IQS_MAL_CZM', 'MAL_CZM', 'IQS_TH_CZM', 'TH_CZM', 'IQS_EXPO_CZM', 'EXPO_CZM')
      select case (trim(inp%name))
      case ('IQS_MAL_CZM', 'MAL_CZM')
        call set_czm(czm_mal)
      case ('IQS_TH_CZM', 'TH_CZM')
        call set_czm(czm_th)
        law%czm%dp1 = param(9)
        law%czm%dp2 = param(10)
      case default
        call set_czm(czm_expo)
        law%czm%eta = param(9)
      end select
      law%czm%s1 = param(5)
      law%czm%s2 = param(6)
      law%czm%g1 = param(7)
      law%czm%g2 = param(8)
    case default
      call input_error(inp%src%file, inp%src%line, 9, "contact law '"//trim(inp%name)// &
        "' is read but not supported by the solver yet (supported: "//known_laws(solver=.true.)//")")
    end select
    ! Checks point at the parameter's own line and column in TACT_BEHAV.DAT.
    if (law%kind == law_czm) then
      if (law%czm%cn <= 0.0_wp) call bad(3, "cohesive normal stiffness cn of law '"//trim(inp%nickname)//"' must be > 0")
      if (law%czm%ct <= 0.0_wp) call bad(4, "cohesive tangential stiffness ct of law '"//trim(inp%nickname)// &
                                         "' must be > 0")
      if (law%czm%visco < 0.0_wp) call bad(5, "damage viscosity of law '"//trim(inp%nickname)//"' must be >= 0")
      select case (law%czm%family)
      case (czm_mac)
        if (law%czm%w <= 0.0_wp) call bad(6, "Dupré energy w of law '"//trim(inp%nickname)//"' must be > 0")
      case (czm_mp3)
        if (law%czm%smax <= 0.0_wp) call bad(5, "strength smax of law '"//trim(inp%nickname)//"' must be > 0")
        if (law%czm%w <= 0.0_wp) call bad(6, "energy w of law '"//trim(inp%nickname)//"' must be > 0")
      case default
        if (law%czm%s1 <= 0.0_wp) call bad(5, "strength s1 of law '"//trim(inp%nickname)//"' must be > 0")
        if (law%czm%s2 <= 0.0_wp) call bad(6, "strength s2 of law '"//trim(inp%nickname)//"' must be > 0")
        if (law%czm%g1 <= 0.0_wp) call bad(7, "energy G1 of law '"//trim(inp%nickname)//"' must be > 0")
        if (law%czm%g2 <= 0.0_wp) call bad(8, "energy G2 of law '"//trim(inp%nickname)//"' must be > 0")
        if (law%czm%family == czm_expo .and. (law%czm%eta <= 0.0_wp .or. law%czm%eta >= 1.0_wp)) &
          call bad(9, "eta of law '"//trim(inp%nickname)//"' must be in (0, 1)")
      end select
    end if
    if (law%kind == law_elastic_repell .or. law%kind == law_visco_elastic_repell) then
      if (law%stiff <= 0.0_wp) call bad(1, "repulsive stiffness F/gap of law '"//trim(inp%nickname)//"' must be > 0")
      if (law%etan < 0.0_wp) call bad(2, "viscosity of law '"//trim(inp%nickname)//"' must be >= 0")
    end if
    select case (law%kind)
    case (law_rst_clb, law_rst_ds_clb)
      if (law%mu_dynamic < 0.0_wp) call bad(3, "friction coefficient of law '"//trim(inp%nickname)//"' must be >= 0")
      if (law%mu_static < 0.0_wp) call bad(4, "friction coefficient of law '"//trim(inp%nickname)//"' must be >= 0")
    case default
      if (law%mu_dynamic < 0.0_wp) call bad(1, "friction coefficient of law '"//trim(inp%nickname)//"' must be >= 0")
      if (law%mu_static < 0.0_wp) call bad(2, "friction coefficient of law '"//trim(inp%nickname)//"' must be >= 0")
    end select
    if (law%restn < 0.0_wp .or. law%restn > 1.0_wp) &
      call bad(1, "normal restitution of law '"//trim(inp%nickname)//"' must be in [0, 1]")

  contains

    !> Input error at parameter i (its line and column when the reader recorded
    !> them; a single-parameter law repeats the value: clamp i).
    subroutine bad(i, msg)
      integer, intent(in) :: i
      character(len=*), intent(in) :: msg
      integer :: j
      if (allocated(inp%param_lines)) then
        if (size(inp%param_lines) > 0) then
          j = min(i, size(inp%param_lines))
          call input_error(inp%src%file, inp%param_lines(j), inp%param_cols(j), msg)
        end if
      end if
      call input_error(inp%src%file, inp%src%line, 0, msg)
    end subroutine bad

    real(wp) function param(i)
      integer, intent(in) :: i
      if (.not. allocated(inp%params)) then
        param = 0.0_wp
      else if (i > size(inp%params)) then
        call input_error(inp%src%file, inp%src%line, 0, "law '"//trim(inp%nickname)// &
          "' has too few parameters")
        param = 0.0_wp
      else
        param = inp%params(i)
      end if
    end function param

    !> Common part of the cohesive laws: dfric, sfric, cn, ct are parameters 1-4.
    subroutine set_czm(family)
      integer, intent(in) :: family
      law%kind = law_czm
      law%czm%family = family
      law%czm%iqs = inp%name(1:4) == 'IQS_'
      call set_mu(param(1), param(2))
      law%czm%cn = param(3)
      law%czm%ct = param(4)
    end subroutine set_czm

    subroutine set_mu(dynamic, static)
      real(wp), intent(in) :: dynamic, static
      law%mu_dynamic = dynamic
      law%mu_static = static
    end subroutine set_mu
  end function law_from_input

  !> Friction coefficient for this step: dynamic if the contact was sliding at
  !> the end of the previous step, static otherwise (equal for non-DS laws).
  pure real(wp) function law_friction(law, status_begin) result(mu)
    type(law_t), intent(in) :: law
    integer, intent(in) :: status_begin
    select case (status_begin)
    case (st_slifw, st_slibw, st_cslfw, st_cslbw)
      mu = law%mu_dynamic
    case default
      mu = law%mu_static
    end select
  end function law_friction

  !> Shift of the local velocity that turns the law into Signorini–Coulomb on
  !> u~ = u + shift: u~n >= 0, Rn >= 0, u~n Rn = 0, Coulomb on (u~t, R).
  !> gap: gap at the detection configuration; h: time step; u_begin: local
  !> relative velocity (t, n) at the beginning of the step. active = .false.
  !> means the contact takes no reaction this step (RST laws while open).
  pure subroutine law_shift(law, gap, h, u_begin, shift, active)
    type(law_t), intent(in) :: law
    real(wp), intent(in) :: gap, h, u_begin(2)
    real(wp), intent(out) :: shift(2)
    logical, intent(out) :: active
    shift = 0.0_wp
    active = .true.
    select case (law%kind)
    case (law_iqs_clb, law_iqs_ds_clb, law_iqs_clb_g0)
      ! Inelastic quasi-shock: an existing overlap is forgiven, not pushed out
      ! (IQS_CLB_g0: the caller passes the gap beyond the contact's reference gap).
      shift(2) = max(0.0_wp, gap) / h
    case (law_gap_sgr_clb, law_gap_sgr_ds_clb)
      ! Signorini on the predicted end gap: overlaps are corrected.
      shift(2) = gap / h
    case (law_czm)
      ! The normal jump starts from the gap (IQS variants: its positive part).
      if (law%czm%iqs) then
        shift(2) = max(0.0_wp, gap) / h
      else
        shift(2) = gap / h
      end if
    case (law_vel_sgr_clb)
      active = gap <= closed_gap
    case (law_elastic_repell)
      ! A spring F = stiff (-g_end)+ (law_local_problem adds its compliance to W)
      shift(2) = gap / h
    case (law_visco_elastic_repell)
      ! Spring and dashpot once closed (as LMGC90: from a closed gap on)
      active = gap <= 0.0_wp
      if (active) shift(2) = law%stiff / (law%stiff * h + law%etan) * gap
    case (law_rst_clb, law_rst_ds_clb)
      ! Newton restitution once the contact is closed: u+ + e u- >= 0. A gap
      ! within closed_gap of zero is round-off of bodies placed in contact.
      if (gap <= closed_gap) then
        shift(1) = law%restt * u_begin(1)
        shift(2) = law%restn * u_begin(2)
      else
        active = .false.
      end if
    end select
  end subroutine law_shift

  !> The local problem law `law` poses on one contact this step, as a shifted
  !> Signorini–Coulomb problem the exact local solver takes unchanged:
  !> in: gap at the detection configuration, time step h, local velocity
  !> u_begin (t, n) and status at the start of the step, cohesive internals
  !> (L, ut, un, beta, TPSini; IQS_CLB_g0: g_ref; unused by other laws), the length carried by the
  !> contact and its Delassus block w (tt, tn, nt, nn);
  !> out: the velocity shift, friction mu, whether the contact takes a reaction
  !> this step, and for a cohesive contact (beta > 0) the cohesive impulse
  !> r_coh = a + K u~ at the start damage beta0 (midpoint: the traction at the mean
  !> of the start and end jumps, the end jumps following the bodies' theta
  !> displacement over the step, so that the impulse's work on the bodies is the
  !> change of the spring's energy; else at the end jumps as LMGC90, u_t + h u~_t and
  !> h u~_n), eliminated locally
  !> (coh, see coh_size; coh_law is left 0); weff is the block the local solver solves with
  !> (W, or W' with cohesion). solvable = .false. for a zero or singular block
  !> (both sides driven): no contact reaction then, while the cohesive impulse
  !> still follows from the law.
  pure subroutine law_local_problem(law, gap, h, u_begin, status_begin, internals, length, w, midpoint, theta, &
                                    shift, mu, active, cohesive, coh, weff, solvable)
    type(law_t), intent(in) :: law
    real(wp), intent(in) :: gap, h, u_begin(2), internals(:), length, w(4), theta
    logical, intent(in) :: midpoint
    integer, intent(in) :: status_begin
    real(wp), intent(out) :: shift(2), mu, coh(coh_size), weff(4)
    logical, intent(out) :: active, cohesive, solvable
    real(wp) :: beta, e, kt, kn
    if (law%kind == law_iqs_clb_g0) then
      ! LMGC90's IQS_CLB_g0: closed at the reference gap g_ref (internals(1), the
      ! gap the contact had at the first step: initially open joints count as shut)
      call law_shift(law, gap - internals(1), h, u_begin, shift, active)
    else
      call law_shift(law, gap, h, u_begin, shift, active)
    end if
    mu = law_friction(law, status_begin)
    cohesive = .false.
    coh = 0.0_wp
    if (law%kind == law_czm) then
      ! beta0 (start of the step) sets the friction mu (1 - beta0)^p and the impulse
      ! r_coh = a + K u~ (u~ = u + shift): (I - W K) u~ = u~free + W a + W r_c.
      beta = internals(4)
      mu = mu * (1.0_wp - beta)**law%czm%friction_power
      if (beta > 0.0_wp) then
        cohesive = .true.
        e = beta**czm_beta_power(law%czm) * length
        if (midpoint) then
          ! the traction at the mean of the start jumps (internals) and the end ones
          ! j0 + theta h u~ (the bodies' relative theta displacement added to the start
          ! jump; normal: to the shifted gap): damage within the step (czm_step_factor)
          coh(coh_j0:coh_j0 + 1) = [internals(2) + (1.0_wp - theta) * h * u_begin(1), &
                                    (1.0_wp - theta) * h * shift(2)]
          coh(coh_jh) = theta * h
          coh(9:10) = -0.5_wp * h * e * [law%czm%ct, law%czm%cn] * (internals(2:3) + coh(coh_j0:coh_j0 + 1))
          kt = -0.5_wp * h * coh(coh_jh) * e * law%czm%ct
          kn = -0.5_wp * h * coh(coh_jh) * e * law%czm%cn
        else
          ! LMGC90: the traction at the end jumps u_t + h u~_t, h u~_n
          coh(coh_j0:coh_j0 + 1) = [internals(2), 0.0_wp]
          coh(coh_jh) = h
          kt = -h**2 * e * law%czm%ct
          kn = -h**2 * e * law%czm%cn
          coh(9:10) = [-h * e * law%czm%ct * internals(2), 0.0_wp]  ! from the tangential jump at the start
        end if
        coh(11:12) = [kt, kn]
        call cohesive_elimination(w, kt, kn, coh(1:4), coh(5:8), solvable)
        coh(coh_u0t) = internals(2)
        coh(coh_u0n) = internals(3)
        coh(coh_h) = h
        coh(coh_factor) = 1.0_wp
        coh(coh_prev) = -1.0_wp        ! no previous pass
        coh([coh_bracket, coh_bracket + 2]) = -1.0_wp
        ! The tensile cohesive impulse also acts while the gap is open, and
        ! between bodies whose normal motion is driven.
        active = .true.
        weff = coh(5:8)
        return
      end if
    end if
    if (law%kind == law_coupled_dof) then
      ! LMGC90's COUPLED_DOF: both relative velocities held at 0 whatever the sign of
      ! the reaction (a bilateral joint). Solved as the limit of a stiff spring
      ! r = K u (the cohesive elimination, K u W ~ coupled_stiffness u): the velocity
      ! left is 1e-8 of the free one; the Signorini part adds nothing then.
      cohesive = .true.
      kn = -coupled_stiffness / max(min(w(1), w(4)), tiny(1.0_wp))
      coh(11:12) = [kn, kn]
      call cohesive_elimination(w, kn, kn, coh(1:4), coh(5:8), solvable)
      coh(coh_h) = h
      coh(coh_factor) = 1.0_wp
      coh(coh_prev) = -1.0_wp
      active = .true.
      weff = coh(5:8)
      return
    end if
    weff = w
    active = active .and. w(4) > 1.0e-18_wp
    solvable = active
    ! REPELL laws: the local solve sees the spring's compliance (LMGC90's WWnn), so
    ! that rn = stiff h (-g_end)+ (+ dashpot): a penalty contact, not Signorini's
    if (law%kind == law_elastic_repell) weff(4) = weff(4) + 1.0_wp / (law%stiff * h**2)
    if (law%kind == law_visco_elastic_repell) weff(4) = weff(4) + 1.0_wp / (law%stiff * h**2 + law%etan * h)
  end subroutine law_local_problem

  !> The law's jumps (t, n) at the end of the step of a cohesive contact (coh from
  !> law_local_problem) whose shifted local velocity is u~ there.
  pure function cohesive_end_jump(coh, utilde) result(u1)
    real(wp), intent(in) :: coh(coh_size), utilde(2)
    real(wp) :: u1(2)
    u1 = coh(coh_j0:coh_j0 + 1) + coh(coh_jh) * utilde
  end function cohesive_end_jump

  !> Elimination of a cohesive impulse K u~ (K = diag(kt, kn)) from u~ = u~free + W r:
  !> A = (I - W K)^-1 and the block W' = A W the contact part is solved with;
  !> solvable = .false. when W' is zero or singular (both sides driven).
  pure subroutine cohesive_elimination(w, kt, kn, amat, wprime, solvable)
    real(wp), intent(in) :: w(4), kt, kn
    real(wp), intent(out) :: amat(4), wprime(4)
    logical, intent(out) :: solvable
    real(wp) :: m(4), det
    m = [1.0_wp - w(1) * kt, -w(2) * kn, -w(3) * kt, 1.0_wp - w(4) * kn]
    det = m(1) * m(4) - m(2) * m(3)
    amat = [m(4), -m(2), -m(3), m(1)] / det
    wprime(1) = amat(1) * w(1) + amat(2) * w(3)
    wprime(2) = amat(1) * w(2) + amat(2) * w(4)
    wprime(3) = amat(3) * w(1) + amat(4) * w(3)
    wprime(4) = amat(3) * w(2) + amat(4) * w(4)
    solvable = wprime(1) * wprime(4) - wprime(2) * wprime(3) > 1.0e-30_wp * max(wprime(4), tiny(1.0_wp))**2 .and. &
               wprime(4) > 1.0e-18_wp
  end subroutine cohesive_elimination
end module fracas_contact_laws
