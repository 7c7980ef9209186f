!> Nonlinear Gauss–Seidel on the contact reactions, "exchange local–global"
!> mode: after each contact update the two bodies' velocities are updated, so
!> each contact sees its neighbours' latest reactions. Contacts between two
!> rigid bodies run in the packed rigid kernel; contacts with a meshed side in
!> the mesh kernel, on the velocities of the meshed bodies' contact dofs
!> (doc/architecture.md); both in one sweep. Convergence is measured as LMGC90
!> does: after each block of sweeps, a check pass evaluates every contact's
!> update without applying it, and LMGC90's normalised norms (Quad, Maxm,
!> QM/16) of those updates decide; after convergence the FCLib natural map is
!> computed too.
module fracas_nlgs
  use fracas_kinds, only: wp, i8
  use fracas_ids, only: st_noctc, st_stick, st_slifw, st_slibw, st_cnctc, st_cstck, st_cslfw, st_cslbw
  use fracas_random, only: rng_t, rng_seed, rng_permute
  use fracas_contacts, only: contacts_t
  use fracas_contact_laws, only: law_t, law_local_problem, law_czm, cohesive_elimination, coh_size, coh_law, &
                                 coh_factor, coh_released, coh_u0, coh_h, coh_prev, coh_uend, coh_bracket, coh_wprime, &
                                 coh_av, coh_k, cohesive_end_jump, n_internals, int_jump, int_beta, int_tps
  use fracas_czm, only: czm_t, czm_beta_update, czm_stored_energy, czm_step_dissipation, czm_step_factor, &
                        czm_beta_power, czm_softening_length
  use fracas_local_solver, only: natural_map_2d, inverse_block
  use fracas_sides_2d, only: bodies2_t, sides2_t, contact_velocity, rigid_pair, sides2_restart_velocities, &
                             sides2_rigid_bodies, sides2_prepare, sides2_delassus, &
                             sides2_begin_velocities, sides2_reserve, sides2_pack_bodies, sides2_pack_contacts, &
                             sides2_unpack_contacts, sides2_sweep, sides2_unpack_bodies, sides2_local_velocities
  use fracas_lmgc_norms, only: lmgc_norms_t, lmgc_norms
  use fracas_grow, only: grow
  use fracas_errors, only: fatal, itoa
  implicit none
  private
  public :: nlgs_settings_t, nlgs_report_t, nlgs_t, nlgs_init, nlgs_prepare, nlgs_solve, &
            contact_velocity, nlgs_update_cohesive

  type :: nlgs_settings_t
    character(len=5) :: check = 'Quad '
    real(wp) :: tol = 1.0e-4_wp
    real(wp) :: relax = 1.0_wp
    integer :: sweeps_per_check = 50
    integer :: max_checks = 400
    logical :: check_pass = .true.    !< LMGC90's check pass (else the change of the last sweep)
    character(len=8) :: order = 'stored'
    integer :: seed = 1
    !> Cohesive damage solved with the contacts within each step (else updated after
    !> the step, from the start-of-step damage).
    logical :: damage_in_step = .false.
    !> Within the step: the springs' traction at the mean of the start and end jumps
    !> with the discrete-gradient factor (implicit); else at the end jumps with the
    !> law's beta^k at the check pass's jumps, as LMGC90 (lmgc90).
    logical :: damage_midpoint = .false.
    !> The step's theta: with midpoint springs, the cohesive jumps follow the bodies'
    !> theta displacement.
    real(wp) :: theta = 1.0_wp
  end type nlgs_settings_t

  type :: nlgs_report_t
    integer :: sweeps = 0
    logical :: converged = .true.
    real(wp) :: quad_dv = 0.0_wp, maxm_dv = 0.0_wp, quad_dvr = 0.0_wp, maxm_dvr = 0.0_wp
    real(wp) :: mean_dvor = 0.0_wp
    real(wp) :: residual = 0.0_wp        !< natural map ||F|| / ||q||
    real(wp) :: residual_onepq = 0.0_wp  !< ||F|| / (1 + ||q||)
    integer :: nactive = 0               !< contacts with a non-zero reaction
    integer(i8) :: updates = 0           !< local solves done: swept contacts of every sweep and check pass
    real(wp) :: velocity_seconds = 0.0_wp !< meshes: wall time of the final solve of their velocities
  end type nlgs_report_t

  !> Solver state kept between steps (random stream, work arrays). The sweeps
  !> run on packed copies of the active contacts and of the bodies they touch
  !> (ws: each body model's part and each kernel's records, fracas_sides_2d),
  !> built once per step (per block of sweeps in shuffled order).
  type :: nlgs_t
    type(nlgs_settings_t) :: s
    type(rng_t) :: rng
    type(czm_t), allocatable :: cz(:)      !< the cohesive part of each law (index: c%law)
    integer, allocatable :: order(:)
    real(wp), allocatable :: qfree(:, :)   !< (2,n) free local velocity incl. law shift
    type(sides2_t) :: ws                   !< the sweep kernels' workspace
  end type nlgs_t

contains

  subroutine nlgs_init(solver, settings)
    type(nlgs_t), intent(out) :: solver
    type(nlgs_settings_t), intent(in) :: settings
    solver%s = settings
    call rng_seed(solver%rng, settings%seed)
  end subroutine nlgs_init

  !> Component i (1: t, 2: n) of the cohesive impulse a + K u~ of contact k at
  !> its current velocity (0 for a contact without cohesion).
  pure real(wp) function cohesive_impulse(c, k, i) result(rc)
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: k, i
    rc = 0.0_wp
    if (c%cohesive(k)) rc = c%coh(coh_factor(2), k) * (c%coh(coh_av(2) - 1 + i, k) + &
                                                        c%coh(coh_k(2) - 1 + i, k) * (c%u(i, k) + c%shift(i, k)))
  end function cohesive_impulse

  !> After convergence: the jumps, the damage beta and the time damage started
  !> of the cohesive contacts (stored in internals), their statuses relabelled
  !> cohesive, and the energies: stored cohesive energy at the end of the step,
  !> work of the cohesive impulses -r_coh.(u + u_begin)/2 over the step, and the
  !> energy released by damage (each contact's also in coh(coh_released)): with
  !> damage solved within the step, the law's dissipation from beta0 to beta
  !> (czm_step_dissipation); with LMGC90's explicit update, the drop of the stored
  !> energy when beta falls at the end-of-step jumps (never negative). increment:
  !> the largest change of the jump (its opening part) over the step at a contact
  !> whose damage grew, in units of the law's softening length (crack_step_limit).
  subroutine nlgs_update_cohesive(c, laws, h, t_end, stored, coh_work, released, increment)
    type(contacts_t), intent(inout) :: c
    type(law_t), intent(in) :: laws(:)
    real(wp), intent(in) :: h, t_end
    real(wp), intent(out) :: stored, coh_work, released, increment
    integer :: k
    real(wp) :: ut, un, beta, rc(2), e_new, e_k, u1(2)
    stored = 0.0_wp
    coh_work = 0.0_wp
    released = 0.0_wp
    increment = 0.0_wp
    do k = 1, c%n
      if (laws(c%law(k))%kind /= law_czm) cycle
      associate (z => laws(c%law(k))%czm)
        rc = [cohesive_impulse(c, k, 1), cohesive_impulse(c, k, 2)]
        coh_work = coh_work - 0.5_wp * sum(rc * (c%u(:, k) + c%u_begin(:, k)))
        if (c%cohesive(k)) then
          call cohesive_end_jump(2, c%coh(:, k), c%u(:, k) + c%shift(:, k), u1)
        else
          u1 = [c%internals(int_jump, k) + h * c%u(1, k), h * (c%u(2, k) + c%shift(2, k))]
        end if
        ut = u1(1); un = u1(2)
        beta = czm_beta_update(z, c%internals(int_beta(2), k), ut, un, h)
        if (beta < 1.0_wp .and. c%internals(int_tps(2), k) < 0.0_wp) c%internals(int_tps(2), k) = t_end
        if (beta < c%internals(int_beta(2), k)) increment = max(increment, norm2([ut - c%internals(int_jump, k), &
          max(un, 0.0_wp) - max(c%internals(int_jump + 1, k), 0.0_wp)]) / czm_softening_length(z, ut, un))
        e_new = c%length(k) * czm_stored_energy(z, beta, ut, un)
        if (c%cohesive(k) .and. c%coh(coh_law(2), k) > 0.0_wp) then
          e_k = c%length(k) * czm_step_dissipation(z, c%internals(int_beta(2), k), beta, ut, un, h)
        else
          e_k = c%length(k) * czm_stored_energy(z, c%internals(int_beta(2), k), ut, un) - e_new
        end if
        released = released + e_k
        if (c%cohesive(k)) c%coh(coh_released(2), k) = e_k
        c%internals(1:int_beta(2), k) = [c%length(k), ut, un, beta]
        stored = stored + e_new
        if (c%cohesive(k)) then
          select case (c%status(k))
          case (st_noctc)
            if (any(c%r(:, k) /= 0.0_wp)) then
              c%status(k) = st_cstck
            else
              c%status(k) = st_cnctc
            end if
          case (st_stick); c%status(k) = st_cstck
          case (st_slifw); c%status(k) = st_cslfw
          case (st_slibw); c%status(k) = st_cslbw
          end select
        end if
      end associate
    end do
  end subroutine nlgs_update_cohesive

  !> Per-contact data of the step: Delassus blocks (rigid sides from the
  !> inverse masses and lever arms, meshed sides from their bodies' contact
  !> compliance), velocities at the beginning of the step, and the local
  !> problem each contact's law poses (shift, friction, cohesion).
  subroutine nlgs_prepare(solver, c, bd, laws, h, newton_again)
    type(nlgs_t), intent(inout) :: solver
    type(contacts_t), intent(inout) :: c
    type(bodies2_t), intent(in) :: bd        !< the body models (fracas_sides_2d)
    type(law_t), intent(in) :: laws(:)
    real(wp), intent(in) :: h
    !> a further Newton iteration of the same step (same contacts): the damage
    !> factors start from the last iteration's instead of 1
    logical, intent(in), optional :: newton_again
    integer :: k
    real(wp) :: weff(4), coh(coh_size(2)), internals(n_internals(2)), factor
    logical :: active, cohesive, solvable, carry
    carry = .false.
    if (present(newton_again)) carry = newton_again .and. solver%s%damage_midpoint
    call require_2d(c)
    call sides2_prepare(solver%ws, c, bd)
    if (.not. allocated(solver%cz)) solver%cz = laws%czm
    internals = 0.0_wp
    call sides2_local_velocities(c, bd, .true., c%u_begin)
    do k = 1, c%n
      call sides2_delassus(solver%ws, c, k, bd)
      ! A nearly rigid tangential direction would make the stick test ill-posed.
      c%w(1, k) = max(c%w(1, k), 1.0e-6_wp * c%w(4, k))
      if (c%with_cohesion) internals = c%internals(:, k)
      call law_local_problem(laws(c%law(k)), c%gap(k), h, c%u_begin(:, k), c%status_begin(k), internals, &
                             c%length(k), c%w(:, k), solver%s%damage_midpoint, solver%s%theta, c%shift(:, k), &
                             c%mu(k), active, &
                             cohesive, coh, weff, solvable)
      c%active(k) = active
      factor = 1.0_wp
      if (carry .and. c%cohesive(k)) factor = c%coh(coh_factor(2), k)
      c%cohesive(k) = cohesive
      if (cohesive) then
        if (solver%s%damage_in_step .and. laws(c%law(k))%kind == law_czm) coh(coh_law(2)) = c%law(k)
        c%coh(:, k) = coh
      end if
      if (cohesive .and. nint(coh(coh_law(2))) /= 0 .and. factor /= 1.0_wp) then
        call set_damage_factor(c, k, factor)      ! (also sets wi)
      else
        c%wi(:, k) = 0.0_wp
        if (solvable) c%wi(:, k) = inverse_block(weff(1), weff(2), weff(3), weff(4), c%mu(k))
      end if
      if (.not. c%active(k)) then
        c%r(:, k) = 0.0_wp
        c%status(k) = st_noctc   ! as LMGC90 reports a contact the law leaves open
      end if
    end do

  end subroutine nlgs_prepare

  !> The scene NLGS is the 2D specialisation: its kernels (fracas_local_solver), the
  !> packed records and the contact sides it includes are those of nd = 2. A store of
  !> another dimension stops here, where the kernels are chosen (3D rigid: issue 21).
  subroutine require_2d(c)
    type(contacts_t), intent(in) :: c
    if (c%nd /= 2) call fatal('nlgs: no contact kernel for dimension '//itoa(c%nd)// &
                              ' (only 2D contacts are solved)')
  end subroutine require_2d

  !> Solve the step's contact problem (nlgs_solve_once). With damage within the
  !> step, the spring factors of the cohesive contacts follow the jumps after each
  !> check pass (damage_factors: the NLGS converges only once they settle); should
  !> the final jumps still move a factor, the problem is solved again from there
  !> (warm start), up to max_passes times within the step's sweep budget. Solving the nonmonotone softening law inside
  !> each local update instead made Gauss–Seidel cycle; a factor frozen over a block of
  !> sweeps keeps each block a linear problem. The report adds up the sweeps of all
  !> passes.
  subroutine nlgs_solve(solver, c, bd, report)
    type(nlgs_t), intent(inout) :: solver
    type(contacts_t), intent(inout) :: c
    type(bodies2_t), intent(in) :: bd
    type(nlgs_report_t), intent(out) :: report
    integer, parameter :: max_passes = 100
    type(nlgs_report_t) :: once
    integer :: pass, checks
    logical :: changed
    call nlgs_solve_once(solver, c, bd, report)
    if (.not. (solver%s%damage_midpoint .and. c%with_cohesion)) return   ! lmgc90: no further pass
    checks = solver%s%max_checks
    do pass = 2, max_passes + 1
      call damage_factors(solver, c, c%u(:, 1:c%n) + c%shift(:, 1:c%n), changed)
      if (.not. changed) return
      ! The passes share the step's sweep budget (sweeps_per_check x max_checks).
      solver%s%max_checks = checks - (report%sweeps + solver%s%sweeps_per_check - 1) / solver%s%sweeps_per_check
      if (pass > max_passes .or. solver%s%max_checks < 1) exit
      call sides2_restart_velocities(bd)
      call nlgs_solve_once(solver, c, bd, once)
      solver%s%max_checks = checks
      once%sweeps = once%sweeps + report%sweeps
      once%updates = once%updates + report%updates
      once%velocity_seconds = once%velocity_seconds + report%velocity_seconds
      once%converged = once%converged .and. report%converged
      report = once
    end do
    solver%s%max_checks = checks
    report%converged = .false.      ! the damage did not settle within the passes or the budget
  end subroutine nlgs_solve

  !> The spring factor of each cohesive contact with damage within the step, from the
  !> end-of-step jump u~ gives: g = czm_step_factor at the damage the law
  !> gives there, over beta0^k (1 while the step does not damage), or with end-jump
  !> springs (lmgc90) g = (beta1/beta0)^k, as LMGC90's check pass sets the beta its
  !> next sweeps use (updated at each check, not stored), taken as it is. With
  !> midpoint springs the factor solves f = g(f) per contact: once the step's passes
  !> bracket the root (f - g of both signs), by regula falsi with the Illinois rule;
  !> before, by the secant through this pass and the previous one where that line
  !> slopes up, else g (a fixed point pass). g jumps where the end jump reaches the
  !> damage envelope (loading and unloading differ there): a bracket narrower than
  !> the tolerance, whose ends the last two passes confirmed, is a solution. A, W' and
  !> W'^-1 for the new factor. changed: some factor moved by more than the NLGS
  !> tolerance (relative: the cohesive impulse is proportional to the factor).
  subroutine damage_factors(solver, c, utilde, changed)
    type(nlgs_t), intent(in) :: solver
    type(contacts_t), intent(inout) :: c
    real(wp), intent(in) :: utilde(:, :)     !< (2,n) u + shift at the end of the step
    logical, intent(out) :: changed
    integer :: k, law
    real(wp) :: u1(2), beta0, beta1, f, g, r_now, r_prev, slope
    logical :: bracketed
    changed = .false.
    do k = 1, c%n
      if (.not. c%cohesive(k)) cycle
      law = nint(c%coh(coh_law(2), k))
      if (law == 0) cycle
      associate (p => solver%cz(law), h => c%coh(coh_h(2), k), old => c%coh(coh_factor(2), k))
        beta0 = c%internals(int_beta(2), k)
        call cohesive_end_jump(2, c%coh(:, k), utilde(:, k), u1)
        beta1 = czm_beta_update(p, beta0, u1(1), u1(2), h)
        if (solver%s%damage_midpoint) then
          g = czm_step_factor(p, beta0, beta1, c%coh(coh_u0(2):coh_u0(2) + 1, k), u1, h) / &
              beta0**czm_beta_power(p)
        else
          g = (beta1 / beta0)**czm_beta_power(p)   ! LMGC90's check pass: beta^k at the jumps it reached
        end if
        if (abs(g - old) <= solver%s%tol * max(g, old)) cycle
        f = g
        r_now = old - g
        r_prev = 0.0_wp
        if (c%coh(coh_prev(2), k) >= 0.0_wp) r_prev = c%coh(coh_prev(2), k) - c%coh(coh_prev(2) + 1, k)
        if (solver%s%damage_midpoint) then     ! (lmgc90: f = g, as LMGC90's checks)
          associate (br => c%coh(coh_bracket(2):coh_bracket(2) + 3, k))   ! (f, r) with r < 0, then with r > 0
            if (r_now < 0.0_wp) then
              br(1:2) = [old, r_now]
            else
              br(3:4) = [old, r_now]
            end if
            bracketed = br(1) >= 0.0_wp .and. br(3) >= 0.0_wp
            if (bracketed .and. abs(br(3) - br(1)) <= solver%s%tol * max(br(1), br(3))) then
              ! The root is within the tolerance: at a kink of the law (the end jump on
              ! the damage envelope, g jumps there), confirmed if the last two passes
              ! fell on either side; else the other end is stale (the neighbours moved).
              if (r_prev * r_now < 0.0_wp) cycle     ! (the previous pass stays the record)
              if (r_now < 0.0_wp) then
                br(3) = -1.0_wp
              else
                br(1) = -1.0_wp
              end if
              bracketed = .false.
            end if
            if (bracketed) then
              ! regula falsi; Illinois: an end kept twice counts half (it may be stale:
              ! the neighbours move too), so the next point comes closer to it
              if (r_prev * r_now > 0.0_wp) then
                if (r_now < 0.0_wp) then
                  br(4) = 0.5_wp * br(4)
                else
                  br(2) = 0.5_wp * br(2)
                end if
              end if
              f = br(1) - br(2) * (br(3) - br(1)) / (br(4) - br(2))
            else if (c%coh(coh_prev(2), k) >= 0.0_wp .and. c%coh(coh_prev(2), k) /= old) then
              slope = (r_now - r_prev) / (old - c%coh(coh_prev(2), k))
              if (slope > 0.0_wp) f = min(1.0_wp, max(0.0_wp, old - r_now / slope))
            end if
          end associate
        end if
        c%coh(coh_prev(2):coh_prev(2) + 1, k) = [old, g]
        changed = .true.
      end associate
      call set_damage_factor(c, k, f)
    end do
  end subroutine damage_factors

  !> Cohesive contact k's spring factor f (over beta0^k): A, W' and W'^-1 for it.
  subroutine set_damage_factor(c, k, f)
    type(contacts_t), intent(inout) :: c
    integer, intent(in) :: k
    real(wp), intent(in) :: f
    logical :: solvable
    c%coh(coh_factor(2), k) = f
    call cohesive_elimination(c%w(:, k), f * c%coh(coh_k(2):coh_k(2) + 1, k), c%coh(1:4, k), &
                              c%coh(coh_wprime(2):coh_wprime(2) + 3, k), solvable)
    c%wi(:, k) = 0.0_wp
    if (solvable) c%wi(:, k) = inverse_block(c%coh(coh_wprime(2), k), c%coh(coh_wprime(2) + 1, k), c%coh(coh_wprime(2) + 2, k), &
                                               c%coh(coh_wprime(2) + 3, k), c%mu(k))
  end subroutine set_damage_factor

  !> Solve the step's contact problem with the cohesive spring factors frozen. On
  !> entry b%v = vfree (rigid), m%vfree (meshes), and c%r holds the warm start; on
  !> exit the velocities are vfree + M^-1 H^T r (rigid) and vfree + A_ff^-1 H^T r
  !> (meshes), and c%u the final local velocities.
  subroutine nlgs_solve_once(solver, c, bd, report)
    type(nlgs_t), intent(inout) :: solver
    type(contacts_t), intent(inout) :: c
    type(bodies2_t), intent(in) :: bd
    type(nlgs_report_t), intent(out) :: report
    integer :: k, iblock, isweep, n
    real(wp) :: sums(7), maxes(2), fsum, qsum, vscale
    logical :: diverged
    call require_2d(c)
    n = c%n
    diverged = .false.
    report%sweeps = 0
    call grow(solver%order, n)
    call grow(solver%qfree, 2, n)
    call sides2_reserve(solver%ws, n, bd)
    ! Free local velocities (the rigid pairs' warm start on the way) and the
    ! velocity scale of the step: free relative velocities and body speeds.
    call sides2_begin_velocities(c, bd, solver%qfree, vscale)
    select case (solver%s%order)
    case ('reversed')
      solver%order(1:n) = [(n + 1 - k, k=1, n)]
    case ('colored')
      call colour_order()
    case default
      solver%order(1:n) = [(k, k=1, n)]
    end select
    call sides2_pack_bodies(solver%ws, c, bd)
    if (solver%s%order /= 'shuffled') call pack_contacts()
    report%converged = n == 0
    if (n > 0) then
      blocks: do iblock = 1, solver%s%max_checks
        if (solver%s%order == 'shuffled') then
          if (iblock > 1) call unpack_contacts()
          call rng_permute(solver%rng, solver%order(1:n))
          call pack_contacts()
        end if
        if (solver%s%check_pass) then
          do isweep = 1, solver%s%sweeps_per_check
            call sweep(.false., .false.)
            report%sweeps = report%sweeps + 1
          end do
          ! LMGC90's check: one more pass that evaluates every contact's update
          ! from the state the sweeps reached, without applying it.
          call sweep(.true., .true.)
        else
          ! The change of the block's last sweep.
          do isweep = 1, solver%s%sweeps_per_check
            call sweep(isweep == solver%s%sweeps_per_check, .false.)
            report%sweeps = report%sweeps + 1
          end do
        end if
        call norms(report)
        if (solver%s%damage_in_step .and. c%with_cohesion .and. .not. diverged) then
          ! LMGC90 (lmgc90) sets beta at every check, but only the checks that do not
          ! converge lead to more sweeps: the bodies get the impulse of the last ones.
          if (solver%s%damage_midpoint .or. .not. report%converged) call settle_damage()
        end if
        if (report%converged .or. diverged) exit blocks   ! NaN/Inf: the caller's state check names it
      end do blocks
      call unpack_contacts()
    end if
    call sides2_unpack_bodies(solver%ws, c, bd, report%velocity_seconds)
    ! Final local velocities, statuses and the natural-map residual.
    call sides2_local_velocities(c, bd, .false., c%u)
    fsum = 0.0_wp; qsum = 0.0_wp
    report%nactive = 0
    do k = 1, n
      if (.not. c%active(k)) cycle
      if (c%r(1, k) == 0.0_wp .and. c%r(2, k) == 0.0_wp) then
        c%status(k) = st_noctc
      else
        report%nactive = report%nactive + 1
      end if
      ! The natural map of the contact part (the total minus the cohesive impulse).
      fsum = fsum + natural_map_2d(c%u(1, k) + c%shift(1, k), c%u(2, k) + c%shift(2, k), &
                                   c%r(1, k) - cohesive_impulse(c, k, 1), c%r(2, k) - cohesive_impulse(c, k, 2), c%mu(k))
      qsum = qsum + sum(solver%qfree(:, k)**2)
    end do
    report%residual = 0.0_wp
    if (qsum > 0.0_wp) report%residual = sqrt(fsum / qsum)
    report%residual_onepq = sqrt(fsum) / (1.0_wp + sqrt(qsum))

  contains

    !> Damage within the step: the spring factors from the check pass's u~; while
    !> one moves the NLGS has not converged (the records are packed again).
    subroutine settle_damage()
      logical :: changed
      if (.not. solver%s%check_pass) return     ! u~ comes from the check pass
      call damage_factors(solver, c, c%coh(coh_uend(2):coh_uend(2) + 1, 1:n), changed)
      if (.not. changed) return
      report%converged = .false.
      if (solver%s%order /= 'shuffled') then
        call unpack_contacts()
        call pack_contacts()
      end if
    end subroutine settle_damage

    !> Coloured order: the active contacts in stored order, cut in blocks of
    !> colour_block; in each block, greedy colours (two contacts sharing a body
    !> never share one) and the contacts sorted by colour, stored order inside a
    !> colour. Consecutive updates then touch different bodies, so the core can
    !> overlap them, while a block stays in cache. A contact that finds no free
    !> colour among 64 goes to the last. Inactive contacts follow (not swept).
    subroutine colour_order()
      integer, parameter :: colour_block = 256, ncol = 64
      integer(i8), allocatable :: used(:)
      integer :: blk(colour_block), col(colour_block), cnt(0:ncol), k, mc, j, cc, nact
      allocate (used(sides2_rigid_bodies(bd)))
      used = 0_i8
      nact = 0
      mc = 0
      do k = 1, n
        if (c%active(k) .and. rigid_pair(c, k)) then
          mc = mc + 1
          blk(mc) = k
        end if
        if (mc == colour_block .or. (k == n .and. mc > 0)) then
          cnt = 0
          do j = 1, mc
            cc = min(ncol - 1, trailz(not(ior(used(c%cdb(blk(j))), used(c%anb(blk(j)))))))
            col(j) = cc
            cnt(cc + 1) = cnt(cc + 1) + 1
            used(c%cdb(blk(j))) = ibset(used(c%cdb(blk(j))), cc)
            used(c%anb(blk(j))) = ibset(used(c%anb(blk(j))), cc)
          end do
          do cc = 1, ncol
            cnt(cc) = cnt(cc) + cnt(cc - 1)
          end do
          do j = 1, mc
            cnt(col(j)) = cnt(col(j)) + 1
            solver%order(nact + cnt(col(j))) = blk(j)
            used(c%cdb(blk(j))) = 0_i8
            used(c%anb(blk(j))) = 0_i8
          end do
          nact = nact + mc
          mc = 0
        end if
      end do
      do k = 1, n
        if (c%active(k) .and. rigid_pair(c, k)) cycle
        nact = nact + 1
        solver%order(nact) = k
      end do
    end subroutine colour_order

    !> The active contacts' records in the current sweep order (fracas_sides_2d).
    subroutine pack_contacts()
      call sides2_pack_contacts(solver%ws, c, solver%order(1:n))
    end subroutine pack_contacts

    !> Impulses and statuses back to the contact store.
    subroutine unpack_contacts()
      call sides2_unpack_contacts(solver%ws, c)
    end subroutine unpack_contacts

    !> One Gauss–Seidel sweep; with check, LMGC90's norm sums of this sweep.
    subroutine sweep(check, evaluate_only)
      logical, intent(in) :: check, evaluate_only
      real(wp) :: s6(6)
      report%updates = report%updates + solver%ws%np + solver%ws%ng
      call sides2_sweep(solver%ws, c, solver%s%relax, check, evaluate_only, s6, maxes)
      if (check) sums(1:6) = s6
    end subroutine sweep

    !> LMGC90's normalised errors from the sums of the last check sweep.
    subroutine norms(rep)
      type(nlgs_report_t), intent(inout) :: rep
      type(lmgc_norms_t) :: nrm
      call lmgc_norms(solver%s%check, solver%s%tol, sums(1:6), maxes, vscale, nrm, rep%converged)
      rep%quad_dv = nrm%quad_dv; rep%maxm_dv = nrm%maxm_dv; rep%quad_dvr = nrm%quad_dvr
      rep%maxm_dvr = nrm%maxm_dvr; rep%mean_dvor = nrm%mean_dvor
      diverged = .not. nrm%finite
    end subroutine norms
  end subroutine nlgs_solve_once
end module fracas_nlgs
