!> Exact restart: the scene state that the next step reads, to and from a
!> restart point of fracas.h5 (fracas_restart_h5). A run restarted from the
!> point of step N does, step for step, bit for bit what the uninterrupted run
!> did after step N: body states, the contact history (reactions as stored,
!> statuses, cohesive internals, contact points), the broad-phase pairs kept
!> between rough detections, step counters, time, the NLGS shuffle generator
!> and the energy audit.
module fracas_restart
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal
  use fracas_strings, only: itoa, rtoa
  use fracas_ids, only: n_inter, n_status
  use fracas_contact_laws, only: n_internals
  use fracas_scene, only: scene_t
  use fracas_state_guard, only: scene_fault
  use fracas_restart_h5, only: restart_state_t, restart_h5_write, restart_h5_read, restart_bad, restart_check_real1, &
                               restart_check_real2
  use fracas_results_h5, only: results_h5_t
  use fracas_rbdy2, only: rbdy2_save_state, rbdy2_restore_state, rbdy2_check_restart
  use fracas_mailx, only: mailx_save_state, mailx_restore_state, mailx_check_restart
  implicit none
  private
  public :: restart_save, restart_load, scene_capture, scene_restore

contains

  !> Write the scene's restart point (after a step) into the open results file.
  !> vtk_frames, outbox_writes: output files written so far (their numbering continues).
  subroutine restart_save(r, sc, vtk_frames, outbox_writes, postpro_sums)
    type(results_h5_t), intent(in) :: r
    type(scene_t), intent(in) :: sc
    integer, intent(in) :: vtk_frames, outbox_writes
    real(wp), intent(in) :: postpro_sums(:)   !< running sums of the POSTPRO commands
    type(restart_state_t) :: st
    if (.not. r%is_open) return
    call scene_capture(sc, st)
    st%vtk_frames = vtk_frames
    st%outbox_writes = outbox_writes
    st%postpro_sums = postpro_sums
    call restart_h5_write(r%fid, st)
  end subroutine restart_save

  !> Put the scene built from the deck into the state of the restart point of
  !> step `step` (< 0: the latest) of PATH. The deck must describe the same
  !> bodies and contactors. Returns the output counters and the POSTPRO
  !> running sums to continue from.
  subroutine restart_load(path, step, sc, vtk_frames, outbox_writes, postpro_sums)
    character(len=*), intent(in) :: path
    integer, intent(in) :: step
    type(scene_t), intent(inout) :: sc
    integer, intent(out) :: vtk_frames, outbox_writes
    real(wp), allocatable, intent(out) :: postpro_sums(:)
    type(restart_state_t) :: st
    call restart_h5_read(path, step, st)
    call validate_point(st, sc)
    call scene_restore(sc, st, checked=.true.)
    vtk_frames = st%vtk_frames
    outbox_writes = st%outbox_writes
    postpro_sums = st%postpro_sums
  end subroutine restart_load

  !> The scene's state at the end of a step, all that the next step reads:
  !> what a restart point holds (and a step done again shorter starts from).
  subroutine scene_capture(sc, st)
    type(scene_t), intent(in) :: sc
    type(restart_state_t), intent(out) :: st
    integer :: n
    st%step = sc%step
    st%steps_done = sc%steps_done
    st%step_level = sc%step_level
    st%time = sc%time
    st%rng_state = sc%solver%rng%state
    ! Each body model's state (rigid: x, v and its work terms, energies(2:4)).
    call rbdy2_save_state(sc%bodies, st%x, st%v, st%energies(2:4))
    st%energies(1) = sc%kinetic0
    st%energies(5:7) = [sc%dissipated, sc%cohesive_energy, sc%damage_dissipated]
    if (sc%meshes%nnodes > 0) &
      call mailx_save_state(sc%meshes, st%mesh_x, st%mesh_v, st%mesh_gp, st%mesh_fint, st%mesh_energies)
    st%ntactors = sc%tactors%n
    associate (h => sc%hist)
      n = h%n
      if (allocated(h%first)) then
        st%first = h%first
      else
        allocate (st%first(0))
      end if
      st%inter = h%inter(1:n)
      st%an = h%an(1:n)
      st%sub = h%sub(1:n)
      st%status = h%status(1:n)
      st%force = h%force(:, 1:n)
      st%point = h%point(:, 1:n)
      if (allocated(h%internals)) st%internals = h%internals(:, 1:n)
    end associate
    associate (d => sc%det)
      n = d%npairs
      allocate (st%pairs(4, n))
      st%pairs(1, :) = d%pair_cd(1:n)
      st%pairs(2, :) = d%pair_an(1:n)
      st%pairs(3, :) = d%pair_inter(1:n)
      st%pairs(4, :) = d%pair_law(1:n)
      st%pair_alert = d%pair_alert(1:n)
    end associate
    associate (cr => sc%cracks)
      if (cr%npts > 0) then
        st%crack_beta = cr%pt_beta
        allocate (st%crack_flags(4, cr%npts))
        st%crack_flags(1, :) = merge(1, 0, cr%pt_glued)
        st%crack_flags(2, :) = merge(1, 0, cr%pt_seen)
        st%crack_flags(3, :) = cr%pt_partner
        st%crack_flags(4, :) = cr%pt_an
        st%crack_broken_step = cr%edge_broken_step
        st%crack_family_damage = cr%family_damage
      end if
    end associate
  end subroutine scene_capture

  !> Put the scene into a state scene_capture took (of this scene, or of the
  !> scene a restart point was written from). checked: the state comes from a
  !> file and must pass the state guard before the meshes are assembled from it.
  subroutine scene_restore(sc, st, checked)
    type(scene_t), intent(inout) :: sc
    type(restart_state_t), intent(in) :: st
    logical, intent(in) :: checked
    integer :: n
    character(len=:), allocatable :: fault
    if (allocated(st%crack_beta)) then
      sc%cracks%pt_beta = st%crack_beta
      sc%cracks%pt_glued = st%crack_flags(1, :) == 1
      sc%cracks%pt_seen = st%crack_flags(2, :) == 1
      sc%cracks%pt_partner = st%crack_flags(3, :)
      sc%cracks%pt_an = st%crack_flags(4, :)
      sc%cracks%edge_broken_step = st%crack_broken_step
      sc%cracks%family_damage = st%crack_family_damage
    end if
    sc%step = st%step
    sc%steps_done = st%steps_done
    sc%step_level = st%step_level
    sc%substep = 0
    sc%time = st%time
    sc%solver%rng%state = st%rng_state
    sc%kinetic0 = st%energies(1)
    sc%dissipated = st%energies(5)
    sc%cohesive_energy = st%energies(6)
    sc%damage_dissipated = st%energies(7)
    call rbdy2_restore_state(sc%bodies, st%x, st%v, st%energies(2:4))
    associate (h => sc%hist)
      n = size(st%inter)
      h%n = n
      if (size(st%first) == 0) then
        if (allocated(h%first)) deallocate (h%first)
      else
        h%first = st%first
      end if
      h%inter = st%inter
      h%an = st%an
      h%sub = st%sub
      h%status = st%status
      h%force = st%force
      h%point = st%point
      if (allocated(st%internals)) h%internals = st%internals
    end associate
    associate (d => sc%det)
      n = size(st%pairs, 2)
      d%npairs = n
      d%pair_cd = st%pairs(1, :)
      d%pair_an = st%pairs(2, :)
      d%pair_inter = st%pairs(3, :)
      d%pair_law = st%pairs(4, :)
      d%pair_alert = st%pair_alert
    end associate
    ! A state read from a file must pass the state guard, as after any step
    ! (finite but absurd values: a body or node beyond what double precision
    ! resolves at its size), before the meshes are assembled from it.
    if (allocated(st%mesh_x)) then
      sc%meshes%x = st%mesh_x
      sc%meshes%v = st%mesh_v
      sc%meshes%gp = st%mesh_gp
    end if
    if (checked) then
      fault = scene_fault(sc)
      if (len(fault) > 0) call fatal('restart point '//st%where//': the state it holds is not sound: '//fault)
    end if
    if (allocated(st%mesh_x)) &
      call mailx_restore_state(sc%meshes, st%mesh_x, st%mesh_v, st%mesh_gp, st%mesh_fint, st%mesh_energies)
  end subroutine scene_restore

  !> Shapes, ranges, finite values and indices of every dataset of a restart
  !> point against the scene built from the deck, before any is used: an error
  !> names the dataset ('PATH:/restart/<step>/history/an: ...'). A point of
  !> another deck is reported by the first dataset that does not fit.
  subroutine validate_point(st, sc)
    type(restart_state_t), intent(in) :: st
    type(scene_t), intent(in) :: sc
    integer :: nt, n, k
    nt = sc%tactors%n
    if (st%step < 0 .or. st%steps_done < 0 .or. st%steps_done > st%step) &
      call bad('', 'step '//itoa(st%step)//' and steps_done '//itoa(st%steps_done)//' are not 0 <= steps_done <= step')
    if (.not. ieee_is_finite(st%time)) call bad('', 'time is '//rtoa(st%time))
    if (st%step_level < 0 .or. st%step_level > 30) call bad('', 'step_level '//itoa(st%step_level)// &
      ' is outside 0 .. 30')
    if (st%vtk_frames < 0 .or. st%outbox_writes < 0) call bad('', 'negative output counters')
    if (size(st%x, 2) /= sc%bodies%n .or. st%ntactors /= nt) &
      call bad('', 'the restart point has '//itoa(size(st%x, 2))//' bodies and '//itoa(st%ntactors)// &
               ' contactors, the deck '//itoa(sc%bodies%n)//' and '//itoa(nt)// &
               ' (restart with the deck of the run that wrote it)')
    call rbdy2_check_restart(sc%bodies, st)
    call real1('energies', st%energies, size(st%energies))
    ! postpro_sums: DISSIPATED ENERGY's running sum (fracas_postpro), or none in older files.
    if (size(st%postpro_sums) > 1) call bad('postpro_sums', itoa(size(st%postpro_sums))//' values, expected 1')
    call real1('postpro_sums', st%postpro_sums, size(st%postpro_sums))
    ! Contact history: first is CSR over the candidate contactors (empty: none kept).
    n = size(st%inter)
    if (size(st%first) /= 0) then
      call int1('history/first', st%first, nt + 1, 1, n + 1)
      if (st%first(1) /= 1 .or. st%first(nt + 1) /= n + 1 .or. any(st%first(2:) < st%first(:nt))) &
        call bad('history/first', 'not a non-decreasing index from 1 to '//itoa(n + 1))
    else if (n /= 0) then
      call bad('history/first', 'empty, with '//itoa(n)//' contacts in history/inter')
    end if
    call int1('history/inter', st%inter, n, 1, n_inter)
    call int1('history/an', st%an, n, 1, nt)
    call int1('history/sub', st%sub, n, 0, huge(1))
    call int1('history/status', st%status, n, 1, n_status)
    ! per-contact vectors have the store's dimension
    call restart_check_real2(st, 'history/force', st%force, sc%contacts%nd, n)
    call restart_check_real2(st, 'history/point', st%point, sc%contacts%nd, n)
    if (sc%contacts%with_cohesion .neqv. allocated(st%internals)) &
      call bad('history/internals', 'the deck and the restart point disagree on cohesive laws')
    if (allocated(st%internals)) call restart_check_real2(st, 'history/internals', st%internals, &
                                                          n_internals(sc%contacts%nd), n)
    ! Broad-phase pairs: candidate, antagonist, interaction type, law.
    n = size(st%pair_alert)
    if (size(st%pairs, 1) /= 4 .or. size(st%pairs, 2) /= n) call bad('pairs', 'shape ('//itoa(size(st%pairs, 1))// &
      ','//itoa(size(st%pairs, 2))//'), expected (4,'//itoa(n)//') as pair_alert')
    call int1('pairs', st%pairs(1, :), n, 1, nt, 'candidate ')
    call int1('pairs', st%pairs(2, :), n, 1, nt, 'antagonist ')
    call int1('pairs', st%pairs(3, :), n, 1, n_inter, 'interaction type ')
    call int1('pairs', st%pairs(4, :), n, 1, size(sc%laws), 'law ')
    call real1('pair_alert', st%pair_alert, n)
    if (any(st%pair_alert < 0.0_wp)) call bad('pair_alert', 'a negative alert distance')
    if (allocated(st%mesh_x) .neqv. sc%meshes%nnodes > 0) &
      call bad('mesh', 'the deck and the restart point disagree on meshed bodies')
    if (allocated(st%mesh_x)) call mailx_check_restart(sc%meshes, st)
    if (allocated(st%crack_beta) .neqv. sc%cracks%npts > 0) &
      call bad('cracks', 'the deck and the restart point disagree on cohesive interfaces')
    if (allocated(st%crack_beta)) then
      n = sc%cracks%npts
      call real1('cracks/beta', st%crack_beta, n)
      if (any(st%crack_beta < 0.0_wp .or. st%crack_beta > 1.0_wp)) call bad('cracks/beta', 'a damage outside [0, 1]')
      if (size(st%crack_flags, 1) /= 4 .or. size(st%crack_flags, 2) /= n) call bad('cracks/flags', 'shape ('// &
        itoa(size(st%crack_flags, 1))//','//itoa(size(st%crack_flags, 2))//'), expected (4,'//itoa(n)//')')
      call int1('cracks/flags', st%crack_flags(1, :), n, 0, 1, 'glued flag ')
      call int1('cracks/flags', st%crack_flags(2, :), n, 0, 1, 'seen flag ')
      call int1('cracks/flags', st%crack_flags(3, :), n, 0, sc%meshes%n, 'partner body ')
      call int1('cracks/flags', st%crack_flags(4, :), n, 0, nt, 'antagonist contactor ')
      call int1('cracks/broken_step', st%crack_broken_step, sc%cracks%nedges, 0, st%step)
      call real1('cracks/family_damage', st%crack_family_damage, sc%cracks%nfamilies)
    end if

  contains

    subroutine bad(dataset, what)
      character(len=*), intent(in) :: dataset, what
      call restart_bad(st, dataset, what)
    end subroutine bad

    subroutine real1(dataset, a, n)
      character(len=*), intent(in) :: dataset
      real(wp), intent(in) :: a(:)
      integer, intent(in) :: n
      call restart_check_real1(st, dataset, a, n)
    end subroutine real1

    !> what: the column's meaning for a 2-D dataset ('candidate ' of pairs).
    subroutine int1(dataset, a, n, lo, hi, what)
      character(len=*), intent(in) :: dataset
      integer, intent(in) :: a(:), n, lo, hi
      character(len=*), intent(in), optional :: what
      character(len=:), allocatable :: w
      integer :: i
      w = ''
      if (present(what)) w = what
      if (size(a) /= n) call bad(dataset, itoa(size(a))//' '//w//'values, expected '//itoa(n))
      do i = 1, n
        if (a(i) < lo .or. a(i) > hi) call bad(dataset, w//'value '//itoa(i - 1)//' (from 0) is '//itoa(a(i))// &
          ', outside '//itoa(lo)//' .. '//itoa(hi))
      end do
    end subroutine int1
  end subroutine validate_point
end module fracas_restart
