!> Contact laws as pure procedures. Each law is rewritten as a shifted
!> Signorini–Coulomb problem on the local velocity (LMGC90's change of
!> variables): the local solver sees u~ = u + shift, with friction mu, and
!> never needs to know which law it is solving.
module fracas_contact_laws
  use fracas_kinds, only: wp
  use fracas_small_matrix, only: adjugate_3x3
  use fracas_deck, only: law_input_t
  use fracas_read_tact_behav, only: known_laws
  use fracas_errors, only: input_error
  use fracas_ids, only: st_slifw, st_slibw, st_cslfw, st_cslbw
  use fracas_czm, only: czm_t, czm_mac, czm_mp3, czm_mal, czm_th, czm_expo, czm_abp, czm_abp_corners, czm_beta_power
  implicit none
  private
  public :: law_t, law_from_input, law_friction, law_shift, law_local_problem, &
            law_iqs_clb, law_gap_sgr_clb, law_rst_clb, law_iqs_ds_clb, law_gap_sgr_ds_clb, &
            law_vel_sgr_clb, law_rst_ds_clb, law_czm, law_iqs_clb_g0, law_elastic_repell, law_visco_elastic_repell, law_coupled_dof, &
            cohesive_elimination, coh_size, coh_law, coh_u0, coh_wprime, coh_av, coh_k, coh_jh, coh_j0, &
            coh_h, coh_factor, coh_released, coh_prev, coh_uend, coh_bracket, &
            cohesive_end_jump, n_internals, int_jump, int_beta, int_tps, czm_mode_jump

  !> Gaps below this (m) count as closed for the laws that act only on closed
  !> contacts: far below any physical length, far above round-off of coordinates.
  real(wp), parameter :: closed_gap = 1.0e-14_wp

  !> The local vectors of a contact in dimension nd (2 or 3) are ordered tangential
  !> part first, normal last: (t, n) in 2D, (t1, t2, n) in 3D; a local block W is
  !> stored by rows, w((i-1) nd + j) = W_ij (2D: tt, tn, nt, nn).
  !>
  !> Layout of a cohesive contact's step data coh(coh_size(nd)) (the arrays below are
  !> indexed by nd, so coh_k(2) is a constant): A = (I - W K)^-1 (1 : nd^2), W' = A W
  !> (coh_wprime), a (coh_av, nd), K's diagonal (coh_k, nd) at the spring factor
  !> beta0^k; coh_law: the law's index when damage is solved within the step (0:
  !> LMGC90's explicit update); coh_h: time step; coh_factor: the step's spring factor
  !> over beta0^k (1 while it does not damage; the impulse is coh_factor (a + K u~));
  !> coh_released: the damage energy the contact released in the step (J per unit
  !> thickness), once the step is solved; coh_prev, coh_prev+1: the factor and the law's
  !> answer g of the previous pass (nlgs, damage within the step); coh_jh: see coh_j0;
  !> coh_bracket .. coh_bracket+3: the step's factors with f - g < 0 and > 0 and those
  !> values (a factor < 0: none yet), bracketing the root f = g (nlgs); coh_u0 (nd): the
  !> law's jumps at the start of the step (its internals, which the end-of-step jumps
  !> of the previous step set); coh_uend (nd): u~ at the end of the step of the last
  !> check pass's local solution; coh_j0 (nd) and coh_jh: the law's jumps at the end of
  !> the step are coh(coh_j0:) + coh(coh_jh) u~ (cohesive_end_jump).
  integer, parameter :: coh_wprime(2:3) = [5, 10], coh_av(2:3) = [9, 19], coh_k(2:3) = [11, 22], &
                        coh_law(2:3) = [13, 25], coh_h(2:3) = [14, 26], coh_factor(2:3) = [15, 27], &
                        coh_released(2:3) = [16, 28], coh_prev(2:3) = [17, 29], coh_jh(2:3) = [19, 31], &
                        coh_bracket(2:3) = [20, 32], coh_u0(2:3) = [24, 36], coh_uend(2:3) = [26, 39], &
                        coh_j0(2:3) = [28, 42], coh_size(2:3) = [29, 44]

  !> A cohesive contact's internals as LMGC90 writes them: L (the length it carries;
  !> IQS_CLB_g0: g_ref), the jumps (int_jump .. int_jump + nd - 1: tangential, normal),
  !> beta, the time damage started.
  integer, parameter :: int_jump = 2, int_beta(2:3) = [4, 5], int_tps(2:3) = [5, 6], n_internals(2:3) = [5, 6]

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
    case ('IQS_MAL_CZM', 'MAL_CZM', 'IQS_TH_CZM', 'TH_CZM', 'IQS_EXPO_CZM', 'EXPO_CZM', 'IQS_ABP_CZM', 'ABP_CZM')
      select case (trim(inp%name))
      case ('IQS_MAL_CZM', 'MAL_CZM')
        call set_czm(czm_mal)
      case ('IQS_TH_CZM', 'TH_CZM')
        call set_czm(czm_th)
        law%czm%dp1 = param(9)
        law%czm%dp2 = param(10)
      case ('IQS_ABP_CZM', 'ABP_CZM')
        call set_czm(czm_abp)
        law%czm%du1 = param(9)
        law%czm%du2 = param(10)
        law%czm%phi = param(11)
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
        if (law%czm%family == czm_abp) call check_abp()
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
    !> ABP: phi in [0, 1] and, in both pure modes, du beyond the elastic opening s/c and
    !> corners (czm_abp_corners) that needed no clamp: the envelope's area is then G.
    subroutine check_abp()
      real(wp) :: s, g, c, di, dp, sp, du, area
      integer :: mode
      character(len=2) :: tag
      if (law%czm%phi < 0.0_wp .or. law%czm%phi > 1.0_wp) &
        call bad(11, "phi of law '"//trim(inp%nickname)//"' must be in [0, 1]")
      do mode = 1, 2
        s = merge(law%czm%s1, law%czm%s2, mode == 1)
        g = merge(law%czm%g1, law%czm%g2, mode == 1)
        c = merge(law%czm%cn, law%czm%ct, mode == 1)
        di = s / c
        tag = merge('I ', 'II', mode == 1)
        call czm_abp_corners(law%czm, real(mode - 1, wp), s, g, di, dp, sp, du)
        if (du <= di) call bad(8 + mode, "du"//achar(48 + mode)//" of law '"//trim(inp%nickname)// &
                                         "' must exceed the elastic opening s/c of mode "//trim(tag))
        area = 0.5_wp * (s * dp - sp * di + sp * du)
        if (abs(area - g) > 1.0e-9_wp * g) call bad(8 + mode, "law '"//trim(inp%nickname)//"': in mode "// &
          trim(tag)//" its G, s, du and phi make no tri-linear envelope of area G (the corner dp = "// &
          "(2 G phi + sp s/c)/s, sp = 2 G (1 - phi)/du, must lie between s/c and du)")
      end do
    end subroutine check_abp

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
  !> u~ = u + shift: u~n >= 0, Rn >= 0, u~n Rn = 0, Coulomb on (u~t, R) (in 3D the
  !> isotropic disk |R_T| <= mu Rn). gap: gap at the detection configuration; h: time
  !> step; u_begin: local relative velocity (tangential, normal: nd values) at the
  !> beginning of the step. active = .false. means the contact takes no reaction this
  !> step (RST laws while open).
  pure subroutine law_shift(law, gap, h, u_begin, shift, active)
    type(law_t), intent(in) :: law
    real(wp), intent(in) :: gap, h, u_begin(:)
    real(wp), intent(out) :: shift(:)
    logical, intent(out) :: active
    integer :: nd
    nd = size(shift)
    shift = 0.0_wp
    active = .true.
    select case (law%kind)
    case (law_iqs_clb, law_iqs_ds_clb, law_iqs_clb_g0)
      ! Inelastic quasi-shock: an existing overlap is forgiven, not pushed out
      ! (IQS_CLB_g0: the caller passes the gap beyond the contact's reference gap).
      shift(nd) = max(0.0_wp, gap) / h
    case (law_gap_sgr_clb, law_gap_sgr_ds_clb)
      ! Signorini on the predicted end gap: overlaps are corrected.
      shift(nd) = gap / h
    case (law_czm)
      ! The normal jump starts from the gap (IQS variants: its positive part).
      if (law%czm%iqs) then
        shift(nd) = max(0.0_wp, gap) / h
      else
        shift(nd) = gap / h
      end if
    case (law_vel_sgr_clb)
      active = gap <= closed_gap
    case (law_elastic_repell)
      ! A spring F = stiff (-g_end)+ (law_local_problem adds its compliance to W)
      shift(nd) = gap / h
    case (law_visco_elastic_repell)
      ! Spring and dashpot once closed (as LMGC90: from a closed gap on)
      active = gap <= 0.0_wp
      if (active) shift(nd) = law%stiff / (law%stiff * h + law%etan) * gap
    case (law_rst_clb, law_rst_ds_clb)
      ! Newton restitution once the contact is closed: u+ + e u- >= 0. A gap
      ! within closed_gap of zero is round-off of bodies placed in contact.
      if (gap <= closed_gap) then
        shift(1:nd - 1) = law%restt * u_begin(1:nd - 1)
        shift(nd) = law%restn * u_begin(nd)
      else
        active = .false.
      end if
    end select
  end subroutine law_shift

  !> The local problem law `law` poses on one contact this step, as a shifted
  !> Signorini–Coulomb problem the exact local solver takes unchanged, in dimension
  !> nd = size(u_begin) (2 or 3; vectors tangential part first, blocks by rows):
  !> in: gap at the detection configuration, time step h, local velocity
  !> u_begin and status at the start of the step, cohesive internals
  !> (n_internals(nd): L, the jumps, beta, TPSini; IQS_CLB_g0: g_ref; unused by other
  !> laws), the length carried by the contact and its Delassus block w (nd x nd);
  !> out: the velocity shift (nd), friction mu, whether the contact takes a reaction
  !> this step, and for a cohesive contact (beta > 0) the cohesive impulse
  !> r_coh = a + K u~ at the start damage beta0 (midpoint: the traction at the mean
  !> of the start and end jumps, the end jumps following the bodies' theta
  !> displacement over the step, so that the impulse's work on the bodies is the
  !> change of the spring's energy; else at the end jumps as LMGC90, u_t + h u~_t and
  !> h u~_n), eliminated locally with K = diag(kt, .., kt, kn)
  !> (coh(coh_size(nd)); coh_law is left 0); weff (nd x nd) is the block the local
  !> solver solves with (W, or W' with cohesion). solvable = .false. for a zero or
  !> singular block (both sides driven): no contact reaction then, while the cohesive
  !> impulse still follows from the law. The damage of a 3D contact sees the norm of
  !> its tangential jump (czm_mode_jump).
  pure subroutine law_local_problem(law, gap, h, u_begin, status_begin, internals, length, w, midpoint, theta, &
                                    shift, mu, active, cohesive, coh, weff, solvable)
    type(law_t), intent(in) :: law
    real(wp), intent(in) :: gap, h, u_begin(:), internals(:), length, w(:), theta
    logical, intent(in) :: midpoint
    integer, intent(in) :: status_begin
    real(wp), intent(out) :: shift(:), mu, coh(:), weff(:)
    logical, intent(out) :: active, cohesive, solvable
    real(wp) :: beta, e, kn, cstiff(3)   ! (1:nd; an automatic array would be a malloc per call)
    integer :: nd, nn, j0, jh, av, kk, wq
    nd = size(u_begin)
    nn = nd * nd
    j0 = coh_j0(nd); jh = coh_jh(nd); av = coh_av(nd); kk = coh_k(nd); wq = coh_wprime(nd)
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
      beta = internals(int_beta(nd))
      mu = mu * (1.0_wp - beta)**law%czm%friction_power
      if (beta > 0.0_wp) then
        cohesive = .true.
        e = beta**czm_beta_power(law%czm) * length
        cstiff(1:nd - 1) = law%czm%ct
        cstiff(nd) = law%czm%cn
        associate (u0 => internals(int_jump:int_jump + nd - 1))
          if (midpoint) then
            ! the traction at the mean of the start jumps (internals) and the end ones
            ! j0 + theta h u~ (the bodies' relative theta displacement added to the start
            ! jump; normal: to the shifted gap): damage within the step (czm_step_factor)
            coh(j0:j0 + nd - 2) = u0(1:nd - 1) + (1.0_wp - theta) * h * u_begin(1:nd - 1)
            coh(j0 + nd - 1) = (1.0_wp - theta) * h * shift(nd)
            coh(jh) = theta * h
            coh(av:av + nd - 1) = -0.5_wp * h * e * cstiff(1:nd) * (u0 + coh(j0:j0 + nd - 1))
            coh(kk:kk + nd - 1) = -0.5_wp * h * coh(jh) * e * cstiff(1:nd)
          else
            ! LMGC90: the traction at the end jumps u_t + h u~_t, h u~_n
            coh(j0:j0 + nd - 2) = u0(1:nd - 1)
            coh(j0 + nd - 1) = 0.0_wp
            coh(jh) = h
            coh(kk:kk + nd - 1) = -h**2 * e * cstiff(1:nd)
            ! from the tangential jump at the start
            coh(av:av + nd - 2) = -h * e * law%czm%ct * u0(1:nd - 1)
            coh(av + nd - 1) = 0.0_wp
          end if
          call cohesive_elimination(w, coh(kk:kk + nd - 1), coh(1:nn), coh(wq:wq + nn - 1), solvable)
          coh(coh_u0(nd):coh_u0(nd) + nd - 1) = u0
        end associate
        coh(coh_h(nd)) = h
        coh(coh_factor(nd)) = 1.0_wp
        coh(coh_prev(nd)) = -1.0_wp        ! no previous pass
        coh([coh_bracket(nd), coh_bracket(nd) + 2]) = -1.0_wp
        ! The tensile cohesive impulse also acts while the gap is open, and
        ! between bodies whose normal motion is driven.
        active = .true.
        weff = coh(wq:wq + nn - 1)
        return
      end if
    end if
    if (law%kind == law_coupled_dof) then
      ! LMGC90's COUPLED_DOF: both relative velocities held at 0 whatever the sign of
      ! the reaction (a bilateral joint). Solved as the limit of a stiff spring
      ! r = K u (the cohesive elimination, K u W ~ coupled_stiffness u): the velocity
      ! left is 1e-8 of the free one; the Signorini part adds nothing then.
      cohesive = .true.
      kn = -coupled_stiffness / max(minval(w(1:nn:nd + 1)), tiny(1.0_wp))
      coh(kk:kk + nd - 1) = kn
      call cohesive_elimination(w, coh(kk:kk + nd - 1), coh(1:nn), coh(wq:wq + nn - 1), solvable)
      coh(coh_h(nd)) = h
      coh(coh_factor(nd)) = 1.0_wp
      coh(coh_prev(nd)) = -1.0_wp
      active = .true.
      weff = coh(wq:wq + nn - 1)
      return
    end if
    weff = w
    active = active .and. w(nn) > 1.0e-18_wp
    solvable = active
    ! REPELL laws: the local solve sees the spring's compliance (LMGC90's WWnn), so
    ! that rn = stiff h (-g_end)+ (+ dashpot): a penalty contact, not Signorini's
    if (law%kind == law_elastic_repell) weff(nn) = weff(nn) + 1.0_wp / (law%stiff * h**2)
    if (law%kind == law_visco_elastic_repell) weff(nn) = weff(nn) + 1.0_wp / (law%stiff * h**2 + law%etan * h)
  end subroutine law_local_problem

  !> The law's jumps u1 (nd: tangential, normal) at the end of the step of a cohesive
  !> contact (coh from law_local_problem) whose shifted local velocity is u~ there.
  !> (Explicit shapes from nd: the NLGS calls it for every cohesive contact at every
  !> check; through assumed shapes it took 4 times the instructions.)
  pure subroutine cohesive_end_jump(nd, coh, utilde, u1)
    integer, intent(in) :: nd
    real(wp), intent(in) :: coh(coh_size(nd)), utilde(nd)
    real(wp), intent(out) :: u1(nd)
    u1 = coh(coh_j0(nd):coh_j0(nd) + nd - 1) + coh(coh_jh(nd)) * utilde
  end subroutine cohesive_end_jump

  !> The jump a cohesive law (fracas_czm) sees, (ut, un), from a contact's jump u
  !> (nd: tangential, normal): in 2D u itself, in 3D the norm of the tangential part
  !> (the laws are isotropic in the tangent plane: they see ut only squared).
  pure function czm_mode_jump(u) result(j)
    real(wp), intent(in) :: u(:)
    real(wp) :: j(2)
    if (size(u) == 2) then
      j = u
    else
      j = [norm2(u(1:size(u) - 1)), u(size(u))]
    end if
  end function czm_mode_jump

  !> Elimination of a cohesive impulse K u~ (K = diag(kd), kd = (kt, .., kn)) from
  !> u~ = u~free + W r (W by rows, nd x nd, nd = size(kd)): A = (I - W K)^-1 and the
  !> block W' = A W the contact part is solved with, both by rows; solvable = .false.
  !> when W' is zero or singular (both sides driven).
  pure subroutine cohesive_elimination(w, kd, amat, wprime, solvable)
    real(wp), intent(in) :: w(:), kd(:)
    real(wp), intent(out) :: amat(:), wprime(:)
    logical, intent(out) :: solvable
    real(wp) :: m(4), det, kt, kn, m3(3, 3), a3(3, 3), w3(3, 3)
    integer :: i
    if (size(kd) == 2) then
      kt = kd(1); kn = kd(2)
      m = [1.0_wp - w(1) * kt, -w(2) * kn, -w(3) * kt, 1.0_wp - w(4) * kn]
      det = m(1) * m(4) - m(2) * m(3)
      amat = [m(4), -m(2), -m(3), m(1)] / det
      wprime(1) = amat(1) * w(1) + amat(2) * w(3)
      wprime(2) = amat(1) * w(2) + amat(2) * w(4)
      wprime(3) = amat(3) * w(1) + amat(4) * w(3)
      wprime(4) = amat(3) * w(2) + amat(4) * w(4)
      solvable = wprime(1) * wprime(4) - wprime(2) * wprime(3) > 1.0e-30_wp * max(wprime(4), tiny(1.0_wp))**2 .and. &
                 wprime(4) > 1.0e-18_wp
    else
      w3 = transpose(reshape(w(1:9), [3, 3]))          ! by rows
      do i = 1, 3
        m3(:, i) = -w3(:, i) * kd(i)
        m3(i, i) = m3(i, i) + 1.0_wp
      end do
      call adjugate_3x3(m3, a3, det)
      a3 = a3 / det
      amat = reshape(transpose(a3), [9])
      w3 = matmul(a3, w3)
      wprime = reshape(transpose(w3), [9])
      call adjugate_3x3(w3, a3, det)            ! (det W'; A is already in amat)
      solvable = det > 1.0e-30_wp * max(w3(3, 3), tiny(1.0_wp))**3 .and. w3(3, 3) > 1.0e-18_wp
    end if
  end subroutine cohesive_elimination
end module fracas_contact_laws
