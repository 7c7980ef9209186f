!> A scene ready to run: bodies, contactors, laws, detection, contacts and
!> solver built from the deck, and one Moreau–Jean step:
!> free velocity -> detection at the theta configuration -> warm start ->
!> NLGS -> velocity and position update -> history for the next step.
module fracas_scene
  use fracas_kinds, only: wp, i8
  use fracas_deck, only: deck_t, body_input_t
  use fracas_errors, only: input_error, status_t, failed
  use fracas_ids, only: inter_id, status_id, bm_rigid, bm_mesh
  use fracas_rbdy2, only: rbdy2_t, rbdy2_init, rbdy2_add_drives, rbdy2_add_step_work, rbdy2_begin_step, &
                          rbdy2_detection_coor, rbdy2_end_step, rbdy2_kinetic_energy, rbdy2_energy_terms
  use fracas_energy, only: energy_terms_t, energy_add
  use fracas_frame_2d, only: frame2_global
  use fracas_rbdy2_side, only: rigid2_add_impulse, rigid2_moment
  use fracas_mailx, only: mailx_t, mailx_build, mailx_begin_step, mailx_detection_coor, mailx_converged, &
                          mailx_end_step, mailx_kinetic_energy, mailx_set_contact_hint, mailx_free, &
                          mailx_energy_terms
  use fracas_cracks, only: cracks_t, cracks_init, cracks_update
  use fracas_contactors, only: tactors_t, tactors_build, body_area_inertia, polygon_area_moments
  use fracas_contact_laws, only: law_t, law_from_input, law_czm, law_iqs_clb_g0, law_coupled_dof, n_internals, &
                                 int_jump, int_beta, int_tps
  use fracas_detection, only: detection_t, detection_init, detect_rough, detect_fine
  use fracas_contacts, only: contacts_t, history_t, history_build, history_find, history_from_contacts, &
                             history_find_near, history_knows_pair
  use fracas_sides_2d, only: bodies2_t
  use fracas_nlgs, only: nlgs_t, nlgs_settings_t, nlgs_report_t, nlgs_init, nlgs_prepare, nlgs_solve, &
                         nlgs_update_cohesive
  implicit none
  private
  public :: scene_t, step_report_t, scene_build, scene_free, scene_step, scene_body_impulses, scene_kinetic_energy, &
            scene_energy_terms

  real(wp), parameter :: pi = acos(-1.0_wp)

  !> What one step did, for progress lines and the HDF5 series.
  type :: step_report_t
    type(nlgs_report_t) :: nlgs
    integer :: contacts = 0
    real(wp) :: kinetic = 0.0_wp
    real(wp) :: mean_overlap = 0.0_wp, max_overlap = 0.0_wp
    integer :: late_contacts = 0         !< new contacts already overlapping when first detected
    real(wp) :: late_overlap = 0.0_wp    !< their largest overlap
    ! Wall time of the step and of its parts (doc/benchmarks.md):
    real(wp) :: bodies_seconds = 0.0_wp  !< free velocities (meshes: residual, factorizations, Newton)
    real(wp) :: detect_seconds = 0.0_wp  !< contact detection and history
    real(wp) :: prepare_seconds = 0.0_wp !< Delassus blocks (meshes: compliance, G blocks) and laws
    real(wp) :: solve_seconds = 0.0_wp   !< NLGS sweeps (meshes: and the final solve of their velocities)
    real(wp) :: velocity_seconds = 0.0_wp !< of solve_seconds: the final solve of the meshes' velocities
    real(wp) :: step_seconds = 0.0_wp    !< the whole step
    integer :: newton_iterations = 0     !< meshed bodies: Newton iterations of the step
    logical :: newton_converged = .true. !< ... and whether their loop converged
    !> Largest change of a damaging cohesive zone's jump in the step, in softening
    !> lengths (crack_step_limit); sub-steps the step was cut into, and sub-steps
    !> done again shorter (fracas_stepping).
    real(wp) :: crack_increment = 0.0_wp
    integer :: substeps = 1, rejected = 0
  end type step_report_t

  type :: scene_t
    real(wp) :: h = 0.0_wp, theta = 0.5_wp, time = 0.0_wp
    integer :: step = 0, steps_done = 0, detection_frequency = 1
    !> The run's time step (h is shorter in the sub-steps of a cut step), the
    !> sub-steps of the current step already done, and the number of halvings
    !> of the time step the next step starts with (fracas_stepping).
    real(wp) :: h_step = 0.0_wp
    integer :: substep = 0, step_level = 0
    type(rbdy2_t) :: bodies                  !< rigid bodies (RBDY2)
    type(mailx_t) :: meshes                  !< meshed bodies (MAILx); n = 0 in a rigid scene
    real(wp) :: newton_tolerance = 1.0e-6_wp
    integer :: newton_max_iterations = 20
    logical :: detection_approach = .true.
    type(tactors_t) :: tactors
    type(cracks_t) :: cracks                 !< cohesive interfaces of meshes (none without)
    type(law_t), allocatable :: laws(:)
    type(detection_t) :: det
    type(contacts_t) :: contacts
    type(history_t) :: hist
    type(nlgs_t) :: solver
    integer, allocatable :: first_tactor(:)  !< first contactor of each body, in deck order
    integer, allocatable :: rigid_deck(:), mesh_deck(:)  !< deck index of each rigid / meshed body
    logical, allocatable :: movable(:)
    real(wp), allocatable :: q(:, :)         !< detection configuration of the step (rigid bodies)
    real(wp), allocatable :: xn(:, :)        !< detection configuration of the mesh nodes
    ! Energy audit, accumulated over the run (J per unit thickness): the initial
    ! energy of all bodies and the contacts' dissipation; each body model keeps
    ! its own terms (scene_energy_terms).
    real(wp) :: kinetic0 = 0.0_wp, dissipated = 0.0_wp
    ! Cohesive zones: energy stored in the cohesive springs now (zero at the
    ! start: jumps start at 0), and the part of the dissipation due to damage.
    ! coh_work (per step) is unused beyond the check that it closes the audit.
    real(wp) :: cohesive_energy = 0.0_wp, damage_dissipated = 0.0_wp
  end type scene_t

contains

  !> Build the runtime scene from the deck (the deck is not needed afterwards).
  subroutine scene_build(deck, sc)
    type(deck_t), intent(in) :: deck
    type(scene_t), intent(out) :: sc
    integer :: nb, ib, im, k, j, pos, nv, nh
    integer, allocatable :: number(:), cd(:), an(:), sub(:), inter(:), status(:)
    real(wp), allocatable :: ref(:, :), mass(:), inertia(:), avrd(:), force(:, :), internals(:, :), points(:, :)
    real(wp) :: density, area, polar, gyrd
    character(len=5), allocatable :: nick(:)
    type(nlgs_settings_t) :: ns
    type(body_input_t), allocatable :: bodies(:)

    sc%h = deck%run%time_step
    sc%h_step = sc%h
    sc%theta = deck%run%theta
    sc%detection_frequency = max(1, deck%run%detection_frequency)
    sc%newton_tolerance = deck%run%newton_tolerance
    sc%newton_max_iterations = deck%run%newton_max_iterations
    sc%detection_approach = deck%run%detection_approach
    bodies = deck%bodies
    sc%rigid_deck = pack([(ib, ib=1, size(bodies))], bodies%model /= 'MAILx')
    sc%mesh_deck = pack([(ib, ib=1, size(bodies))], bodies%model == 'MAILx')
    nb = size(sc%rigid_deck)
    do ib = 1, nb
      call polygons_to_centroid(bodies(sc%rigid_deck(ib)))
    end do
    allocate (number(nb), ref(3, nb), mass(nb), inertia(nb), avrd(nb))
    do ib = 1, nb
      associate (bd => bodies(sc%rigid_deck(ib)))
        density = -1.0_wp
        do im = 1, size(deck%materials)
          if (deck%materials(im)%nickname == bd%behav) density = deck%materials(im)%density
        end do
        if (density < 0.0_wp) call input_error(bd%src%file, bd%src%line, 23, "material '"//bd%behav// &
          "' is not defined in BULK_BEHAV.DAT")
        if (density == 0.0_wp) call input_error(bd%src%file, bd%src%line, 23, "material '"//bd%behav// &
          "' has density 0: a rigid body needs a mass (only meshed bodies may be massless)")
        call body_area_inertia(bd, area, polar)
        avrd(ib) = bd%avrd
        gyrd = bd%gyrd
        ! As LMGC90: without gyrd, both radii come from the contactors (a
        ! given avrd alone is not kept).
        if (gyrd <= 0.0_wp) avrd(ib) = 0.0_wp
        if (avrd(ib) <= 0.0_wp) avrd(ib) = sqrt(area / pi)
        if (gyrd <= 0.0_wp .and. area > 0.0_wp) gyrd = sqrt(polar / area)
        if (avrd(ib) <= 0.0_wp .or. gyrd <= 0.0_wp) call input_error(bd%src%file, bd%src%line, 0, &
          'body has no size: give avrd and gyrd or at least one contactor')
        number(ib) = ib
        ref(:, ib) = bd%coor
        mass(ib) = density * pi * avrd(ib)**2
        inertia(ib) = mass(ib) * gyrd**2
      end associate
    end do
    call rbdy2_init(sc%bodies, number, ref, mass, inertia, avrd, deck%gravity(1:2))
    ! LMGC90 starts a driven dof of a rigid body at its imposed value (lmgc90)
    sc%bodies%driven_start_imposed = deck%run%driven_start /= 'initial'
    call rbdy2_add_drives(sc%bodies, pack(deck%driven, deck%driven%model /= 'MAILx'))
    do k = 1, size(deck%dof_ini)
      associate (d => deck%dof_ini(k))
        if (d%model == 'MAILx') cycle
        if (d%body < 1 .or. d%body > nb) call input_error(d%src%file, d%src%line, 9, &
          'body number out of range')
        sc%bodies%xbegin(:, d%body) = d%x
        sc%bodies%x(:, d%body) = d%x
        sc%bodies%vbegin(:, d%body) = d%v
        sc%bodies%v(:, d%body) = d%v
      end associate
    end do
    sc%time = deck%dof_time
    sc%step = deck%dof_step
    sc%movable = .not. sc%bodies%clamped
    sc%kinetic0 = rbdy2_kinetic_energy(sc%bodies)
    ! Meshed bodies (none in a rigid scene: empty arrays, no finite-element work).
    call mailx_build(deck, sc%meshes, sc%h, sc%theta)
    sc%kinetic0 = sc%kinetic0 + sc%meshes%kinetic0 + sc%meshes%elastic
    allocate (sc%xn(2, sc%meshes%nnodes))

    allocate (sc%laws(size(deck%laws)), nick(size(deck%laws)))
    do k = 1, size(deck%laws)
      ! A law no see rule uses acts nowhere (LMGC90's decks carry laws its
      ! solver has and ours lacks): only the used ones must be runnable.
      if (any(deck%see_rules%behav == deck%laws(k)%nickname)) sc%laws(k) = law_from_input(deck%laws(k))
      nick(k) = deck%laws(k)%nickname
    end do
    call tactors_build(bodies, sc%tactors)
    ! First contactor of each body in deck order (contactors are listed in that order).
    allocate (sc%first_tactor(size(bodies) + 1))
    k = 1
    do ib = 1, size(bodies)
      sc%first_tactor(ib) = k
      if (allocated(bodies(ib)%tactors)) k = k + size(bodies(ib)%tactors)
    end do
    sc%first_tactor(size(bodies) + 1) = k
    sc%contacts%with_mesh = sc%meshes%n > 0
    if (sc%meshes%n > 0) call mailx_set_contact_hint(sc%meshes, sc%tactors%nodes)
    call cracks_init(sc%cracks, sc%tactors, sc%meshes)
    call detection_init(sc%det, sc%tactors, deck%see_rules, nick)
    allocate (sc%q(3, nb))

    ! History from Vloc_Rloc.INI: contactors named by (body, rank in body). The
    ! scene's body models (rbdy2, mailx) and its Vloc_Rloc records are 2D.
    nv = size(deck%vloc_ini)
    allocate (cd(nv), an(nv), sub(nv), inter(nv), status(nv), force(2, nv), internals(n_internals(2), nv), &
              points(2, nv))
    nh = 0
    do k = 1, nv
      associate (r => deck%vloc_ini(k))
        j = inter_id(r%inter)
        if (j == 0) cycle   ! a type this build does not treat: nothing to warm start
        nh = nh + 1
        cd(nh) = tactor_of(r%cdbdy, r%icdbdy, r%icdtac)
        an(nh) = tactor_of(r%anbdy, r%ianbdy, r%iantac)
        sub(nh) = r%cdver
        inter(nh) = j
        pos = status_id(r%status)
        if (pos == 0) call input_error(r%src%file, r%src%line, 71, "unknown contact status '"//r%status//"'")
        status(nh) = pos
        force(:, nh) = [r%rlt, r%rln]
        points(:, nh) = r%coor
        internals(:, nh) = 0.0_wp
        if (allocated(r%internals)) then
          pos = min(n_internals(2), size(r%internals))
          internals(1:pos, nh) = r%internals(1:pos)
        end if
      end associate
    end do
    sc%contacts%with_cohesion = any(sc%laws%kind == law_czm .or. sc%laws%kind == law_iqs_clb_g0 .or. &
                                    sc%laws%kind == law_coupled_dof)
    if (sc%contacts%with_cohesion) then
      call history_build(sc%hist, sc%tactors%n, cd(1:nh), an(1:nh), sub(1:nh), inter(1:nh), status(1:nh), &
                         force(:, 1:nh), points(:, 1:nh), internals(:, 1:nh))
    else
      call history_build(sc%hist, sc%tactors%n, cd(1:nh), an(1:nh), sub(1:nh), inter(1:nh), status(1:nh), &
                         force(:, 1:nh), points(:, 1:nh))
    end if

    ns%check = deck%run%nlgs_check
    ns%tol = deck%run%nlgs_tolerance
    ns%relax = deck%run%nlgs_relaxation
    ns%sweeps_per_check = deck%run%nlgs_sweeps_per_check
    ns%max_checks = deck%run%nlgs_max_checks
    ns%order = deck%run%nlgs_order
    ns%seed = deck%run%nlgs_seed
    ns%check_pass = deck%run%nlgs_check_pass
    ns%damage_in_step = deck%run%cohesive_damage /= 'explicit'
    ns%damage_midpoint = deck%run%cohesive_damage == 'implicit'
    ns%theta = deck%run%theta
    call nlgs_init(sc%solver, ns)

  contains

    !> Contactor of rank `rank` on body `ibody` of model `model` (numbered within its model).
    integer function tactor_of(model, ibody, rank)
      character(len=*), intent(in) :: model
      integer, intent(in) :: ibody, rank
      integer :: ideck
      associate (r => deck%vloc_ini(k))
        if (model == 'MAILx') then
          if (ibody < 1 .or. ibody > size(sc%mesh_deck)) call input_error(r%src%file, r%src%line, 9, &
            'MAILx body number out of range in Vloc_Rloc.INI')
          ideck = sc%mesh_deck(ibody)
        else
          if (ibody < 1 .or. ibody > nb) call input_error(r%src%file, r%src%line, 9, &
            'body number out of range in Vloc_Rloc.INI')
          ideck = sc%rigid_deck(ibody)
        end if
        tactor_of = sc%first_tactor(ideck) + rank - 1
        if (rank < 1 .or. tactor_of >= sc%first_tactor(ideck + 1)) call input_error(r%src%file, &
          r%src%line, 23, 'contactor number out of range in Vloc_Rloc.INI')
      end associate
    end function tactor_of
  end subroutine scene_build

  !> What a scene holds outside Fortran's reach (the meshes' factorizations).
  subroutine scene_free(sc)
    type(scene_t), intent(inout) :: sc
    call mailx_free(sc%meshes)
  end subroutine scene_free

  !> A body whose node is given as (0, 0, 0) and whose contactors are all
  !> polygons has absolute vertices (as LMGC90 reads them): its node becomes the
  !> area centroid and the vertices are made relative to it.
  subroutine polygons_to_centroid(bd)
    type(body_input_t), intent(inout) :: bd
    real(wp) :: area, a, cen(2), c(2), polar
    integer :: it
    if (any(bd%coor /= 0.0_wp) .or. .not. allocated(bd%tactors)) return
    if (size(bd%tactors) == 0) return
    if (any(bd%tactors%kind /= 'POLYG')) return
    area = 0.0_wp
    cen = 0.0_wp
    do it = 1, size(bd%tactors)
      call polygon_area_moments(bd%tactors(it)%vertices, a, c, polar)
      area = area + a
      cen = cen + a * c
    end do
    cen = cen / area
    bd%coor(1:2) = cen
    do it = 1, size(bd%tactors)
      bd%tactors(it)%vertices(1, :) = bd%tactors(it)%vertices(1, :) - cen(1)
      bd%tactors(it)%vertices(2, :) = bd%tactors(it)%vertices(2, :) - cen(2)
    end do
  end subroutine polygons_to_centroid

  !> Advance the scene by one time step, of length sc%h. A meshed body whose
  !> iteration matrix does not factorize: status (the scene is then left
  !> mid-step), or the run stops. finishes_step = .false.: a sub-step of a cut
  !> step (the step counters stay; fracas_stepping).
  subroutine scene_step(sc, rep, status, finishes_step)
    type(scene_t), intent(inout), target :: sc
    type(step_report_t), intent(out) :: rep
    type(status_t), intent(out), optional :: status
    logical, intent(in), optional :: finishes_step
    integer :: k, pos, nover, checks, checks_left
    logical :: pair_known, swapped, at_start, finishes
    integer(i8) :: t0, t1, t2, rate
    real(wp) :: margin, vmax, gap_end, stored, coh_work, released, dissipated_all
    real(wp), allocatable :: imp(:, :)
    type(nlgs_report_t) :: newton_rep
    type(bodies2_t) :: bd
    call system_clock(t0, rate)
    bd%rbdy2 => sc%bodies
    bd%mailx => sc%meshes
    t1 = t0
    finishes = .true.
    if (present(finishes_step)) finishes = finishes_step
    at_start = sc%step == 0 .and. sc%substep == 0   ! the run's first (sub-)step from the deck
    associate (b => sc%bodies, c => sc%contacts, m => sc%meshes)
      call rbdy2_begin_step(b, sc%time, sc%h, sc%theta)
      call rbdy2_detection_coor(b, sc%h, sc%theta, sc%q)
      if (m%n > 0) then
        call mailx_begin_step(m, sc%time, status)
        if (failed(status)) return
        call mailx_detection_coor(m, sc%xn)
      end if
      call lap(rep%bodies_seconds)
      if (mod(sc%steps_done, sc%detection_frequency) == 0) then
        ! Between rough detections bodies move at most about vmax h per step,
        ! and a pair closes by at most 2 vmax h within a step.
        vmax = 0.0_wp
        do k = 1, b%n
          vmax = max(vmax, norm2(b%vfree(1:2, k)) + abs(b%vfree(3, k)) * b%avrd(k), &
                     norm2(b%vbegin(1:2, k)) + abs(b%vbegin(3, k)) * b%avrd(k))
        end do
        if (m%nnodes > 0) vmax = max(vmax, maxval(norm2(m%vfree, dim=1)), maxval(norm2(m%vbegin, dim=1)))
        margin = 2.0_wp * vmax * sc%h_step * sc%detection_frequency
        if (m%n > 0) then
          call detect_rough(sc%det, sc%tactors, sc%q, sc%movable, margin, sc%xn, m%movable)
        else
          call detect_rough(sc%det, sc%tactors, sc%q, sc%movable, margin)
        end if
      end if
      if (sc%detection_approach) then
        call detect_fine(sc%det, sc%tactors, sc%q, c, sc%xn, b%vfree, m%vfree, sc%h)
      else
        call detect_fine(sc%det, sc%tactors, sc%q, c, sc%xn)
      end if
      do k = 1, c%n
        pair_known = .false.
        swapped = .false.
        pos = history_find(sc%hist, c%inter(k), c%cd(k), c%an(k), c%sub(k))
        if (pos == 0 .and. c%sub(k) > 0) &      ! polygons: the key may have changed, not the contact
          call history_find_near(sc%hist, c%inter(k), c%cd(k), c%an(k), c%point(:, k), &
                                 0.5_wp * max(c%length(k), tiny(1.0_wp)), pos, swapped)
        if (pos > 0) then
          c%r(:, k) = sc%h * sc%hist%force(:, pos)
          c%status_begin(k) = sc%hist%status(pos)
          if (c%with_cohesion) c%internals(:, k) = sc%hist%internals(:, pos)
          if (swapped) then     ! the tangent t = (n2, -n1) turned with the normal
            c%r(1, k) = -c%r(1, k)
            if (c%with_cohesion) c%internals(int_jump, k) = -c%internals(int_jump, k)
          end if
        else
          ! A contact seen first with an overlap was missed while approaching:
          ! the alert distance is shorter than what bodies travel in a step.
          ! (A polygon pair in contact may only have moved its contact point.)
          if (c%gap(k) < 0.0_wp .and. .not. at_start) pair_known = history_knows_pair(sc%hist, c%cd(k), c%an(k))
          if (c%gap(k) < 0.0_wp .and. .not. at_start .and. .not. pair_known) then
            rep%late_contacts = rep%late_contacts + 1
            rep%late_overlap = max(rep%late_overlap, -c%gap(k))
          end if
          ! Interfaces present at the start of a simulation are glued (beta = 1);
          ! contacts made later start without cohesion.
          if (c%with_cohesion) then
            c%internals(:, k) = 0.0_wp
            c%internals(1, k) = c%length(k)
            c%internals(int_beta(c%nd), k) = merge(1.0_wp, 0.0_wp, at_start)
            c%internals(int_tps(c%nd), k) = -99.0_wp
          end if
          ! IQS_CLB_g0: the gap at the first step is the reference (LMGC90), 0 later
          if (sc%laws(c%law(k))%kind == law_iqs_clb_g0) then
            c%internals(:, k) = 0.0_wp
            c%internals(1, k) = merge(max(0.0_wp, c%gap(k)), 0.0_wp, at_start)
          end if
        end if
      end do
      call lap(rep%detect_seconds)
      call nlgs_prepare(sc%solver, c, bd, sc%laws, sc%h)
      call lap(rep%prepare_seconds)
      call nlgs_solve(sc%solver, c, bd, rep%nlgs)
      call lap(rep%solve_seconds)
      rep%velocity_seconds = rep%nlgs%velocity_seconds
      ! Nonlinear meshed bodies: Newton iterations, the contact problem solved
      ! in each (warm-started from the last), as LMGC90. The step's NLGS sweep
      ! budget (sweeps_per_check x max_checks, what --check bounds) is shared by
      ! its Newton iterations: each solve gets the checks left, and a step that
      ! has used them all ends unconverged (it used to repeat the whole budget at
      ! every iteration, up to newton_max_iterations + 1 times).
      checks = sc%solver%s%max_checks
      do
        if (mailx_converged(m, sc%newton_tolerance, sc%newton_max_iterations, status)) exit
        checks_left = checks - (rep%nlgs%sweeps + sc%solver%s%sweeps_per_check - 1) / sc%solver%s%sweeps_per_check
        if (checks_left < 1) then
          rep%nlgs%converged = .false.
          exit
        end if
        sc%solver%s%max_checks = checks_left
        call lap(rep%bodies_seconds)
        b%v = b%vfree
        call nlgs_prepare(sc%solver, c, bd, sc%laws, sc%h, newton_again=.true.)
        call lap(rep%prepare_seconds)
        call nlgs_solve(sc%solver, c, bd, newton_rep)
        call lap(rep%solve_seconds)
        rep%nlgs%sweeps = rep%nlgs%sweeps + newton_rep%sweeps
        rep%nlgs%updates = rep%nlgs%updates + newton_rep%updates
        rep%velocity_seconds = rep%velocity_seconds + newton_rep%velocity_seconds
        rep%nlgs%converged = newton_rep%converged
      end do
      sc%solver%s%max_checks = checks
      if (failed(status)) return
      call lap(rep%bodies_seconds)
      rep%newton_iterations = m%iterations
      rep%newton_converged = m%newton_converged
      call nlgs_update_cohesive(c, sc%laws, sc%h, sc%time + sc%h, stored, coh_work, released, rep%crack_increment)
      call cracks_update(sc%cracks, c, sc%laws, at_start, sc%step + 1)

      ! Energy audit of the step (before the begin state is overwritten).
      call scene_body_impulses(sc, imp)
      call rbdy2_add_step_work(b, sc%time, sc%h, sc%theta, imp)
      dissipated_all = 0.0_wp
      nover = 0
      do k = 1, c%n
        if (.not. c%active(k)) cycle
        dissipated_all = dissipated_all - 0.5_wp * sum(c%r(:, k) * (c%u(:, k) + c%u_begin(:, k)))
        gap_end = c%gap(k) + sc%h * c%u(2, k)
        if (gap_end < 0.0_wp) then
          rep%mean_overlap = rep%mean_overlap - gap_end
          rep%max_overlap = max(rep%max_overlap, -gap_end)
          nover = nover + 1
        end if
      end do
      if (nover > 0) rep%mean_overlap = rep%mean_overlap / nover
      ! Contact work -r.(u + u_begin)/2 is dissipated, except what the cohesive
      ! springs store; of that dissipation, damage is the energy released when
      ! beta drops (the rest is friction, impacts and the O(h) dissipation of
      ! the implicit springs).
      sc%dissipated = sc%dissipated + dissipated_all - (stored - sc%cohesive_energy)
      sc%damage_dissipated = sc%damage_dissipated + released
      sc%cohesive_energy = stored

      call rbdy2_end_step(b, sc%h, sc%theta)
      if (m%n > 0) call mailx_end_step(m)
      call history_from_contacts(sc%hist, c, sc%tactors%n, sc%h)
      sc%time = sc%time + sc%h
      if (finishes) then
        sc%step = sc%step + 1
        sc%steps_done = sc%steps_done + 1
        sc%substep = 0
      else
        sc%substep = sc%substep + 1
      end if
      rep%contacts = c%n
      rep%kinetic = scene_kinetic_energy(sc)
    end associate
    call system_clock(t2)
    rep%step_seconds = real(t2 - t0, wp) / real(rate, wp)

  contains

    !> Add the wall time since the last lap to acc.
    subroutine lap(acc)
      real(wp), intent(inout) :: acc
      call system_clock(t2)
      acc = acc + real(t2 - t1, wp) / real(rate, wp)
      t1 = t2
    end subroutine lap
  end subroutine scene_step

  !> The kinetic energy of all bodies: each body model's.
  real(wp) function scene_kinetic_energy(sc) result(e)
    type(scene_t), intent(in) :: sc
    e = rbdy2_kinetic_energy(sc%bodies)
    if (sc%meshes%n > 0) e = e + mailx_kinetic_energy(sc%meshes)
  end function scene_kinetic_energy

  !> The energy audit's terms of all bodies: each body model's, added up.
  type(energy_terms_t) function scene_energy_terms(sc) result(e)
    type(scene_t), intent(in) :: sc
    e = rbdy2_energy_terms(sc%bodies)
    call energy_add(e, mailx_energy_terms(sc%meshes))
  end function scene_energy_terms

  !> Total contact impulse on every body (3,nb) from the current reactions.
  subroutine scene_body_impulses(sc, imp)
    type(scene_t), intent(in) :: sc
    real(wp), allocatable, intent(out) :: imp(:, :)
    real(wp), parameter :: one(3) = 1.0_wp
    integer :: k
    real(wp) :: px, py, rt, rn
    allocate (imp(3, sc%bodies%n))
    imp = 0.0_wp
    associate (c => sc%contacts)
      do k = 1, c%n
        rt = c%r(1, k); rn = c%r(2, k)
        call frame2_global(c%frame(1, 2, k), c%frame(2, 2, k), rt, rn, px, py)
        if (c%cdm(k) == bm_rigid) call rigid2_add_impulse(imp(:, c%cdb(k)), one, 1.0_wp, px, py, &
                                                          rigid2_moment(rt, rn, c%lever(1, k), c%lever(2, k)))
        if (c%anm(k) == bm_rigid) call rigid2_add_impulse(imp(:, c%anb(k)), one, -1.0_wp, px, py, &
                                                          rigid2_moment(rt, rn, c%lever(3, k), c%lever(4, k)))
      end do
    end associate
  end subroutine scene_body_impulses
end module fracas_scene
