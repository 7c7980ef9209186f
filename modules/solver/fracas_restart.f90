!> Exact restart: the scene state that the next step reads, to and from a
!> restart point of fracas.h5 (fracas_restart_h5). A run restarted from the
!> point of step N does, step for step, bit for bit what the uninterrupted run
!> did after step N: body states, the contact history (reactions as stored,
!> statuses, cohesive internals, contact points), the broad-phase pairs kept
!> between rough detections, step counters, time, the NLGS shuffle generator
!> and the energy audit.
module fracas_restart
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal
  use fracas_strings, only: itoa
  use fracas_scene, only: scene_t
  use fracas_restart_h5, only: restart_state_t, restart_h5_write, restart_h5_read
  use fracas_results_h5, only: results_h5_t
  use fracas_mailx, only: mailx_restore_state
  implicit none
  private
  public :: restart_save, restart_load

contains

  !> Write the scene's restart point (after a step) into the open results file.
  !> vtk_frames, outbox_writes: output files written so far (their numbering continues).
  subroutine restart_save(r, sc, vtk_frames, outbox_writes)
    type(results_h5_t), intent(in) :: r
    type(scene_t), intent(in) :: sc
    integer, intent(in) :: vtk_frames, outbox_writes
    type(restart_state_t) :: st
    integer :: n
    if (.not. r%is_open) return
    st%step = sc%step
    st%steps_done = sc%steps_done
    st%time = sc%time
    st%vtk_frames = vtk_frames
    st%outbox_writes = outbox_writes
    st%rng_state = sc%solver%rng%state
    st%energies = [sc%kinetic0, sc%work_gravity, sc%work_forces, sc%work_supports, sc%dissipated, &
                   sc%cohesive_energy, sc%damage_dissipated]
    st%x = sc%bodies%x
    st%v = sc%bodies%v
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
    associate (m => sc%meshes)
      if (m%nnodes > 0) then
        st%mesh_x = m%x
        st%mesh_v = m%v
        st%mesh_gp = m%gp
        st%mesh_fint = m%fint
        st%mesh_energies = [m%kinetic0, m%work_gravity, m%work_forces, m%work_supports, m%plastic_work]
      end if
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
    call restart_h5_write(r%fid, st)
  end subroutine restart_save

  !> Put the scene built from the deck into the state of the restart point of
  !> step `step` (< 0: the latest) of PATH. The deck must describe the same
  !> bodies and contactors. Returns the output counters to continue from.
  subroutine restart_load(path, step, sc, vtk_frames, outbox_writes)
    character(len=*), intent(in) :: path
    integer, intent(in) :: step
    type(scene_t), intent(inout) :: sc
    integer, intent(out) :: vtk_frames, outbox_writes
    type(restart_state_t) :: st
    integer :: n
    call restart_h5_read(path, step, st)
    if (size(st%x, 2) /= sc%bodies%n .or. st%ntactors /= sc%tactors%n) &
      call fatal('restart from '//trim(path)//': the restart point has '//itoa(size(st%x, 2))//' bodies and '// &
                 itoa(st%ntactors)//' contactors, the deck '//itoa(sc%bodies%n)//' and '//itoa(sc%tactors%n)// &
                 ' (restart with the deck of the run that wrote it)')
    if (size(st%first) /= sc%tactors%n + 1 .and. size(st%first) /= 0) &
      call fatal('restart from '//trim(path)//': contact history does not match the contactors')
    if (sc%contacts%with_cohesion .neqv. allocated(st%internals)) &
      call fatal('restart from '//trim(path)//': the deck and the restart point disagree on cohesive laws')
    if (allocated(st%mesh_x) .neqv. sc%meshes%nnodes > 0) &
      call fatal('restart from '//trim(path)//': the deck and the restart point disagree on meshed bodies')
    if (allocated(st%mesh_x)) then
      if (size(st%mesh_x, 2) /= sc%meshes%nnodes .or. size(st%mesh_gp, 2) /= sc%meshes%ngp) &
        call fatal('restart from '//trim(path)//': the restart point has '//itoa(size(st%mesh_x, 2))// &
                   ' mesh nodes and '//itoa(size(st%mesh_gp, 2))//' Gauss points, the deck '// &
                   itoa(sc%meshes%nnodes)//' and '//itoa(sc%meshes%ngp))
      call mailx_restore_state(sc%meshes, st%mesh_x, st%mesh_v, st%mesh_gp, st%mesh_fint, st%mesh_energies)
    end if
    if (allocated(st%crack_beta) .neqv. sc%cracks%npts > 0) &
      call fatal('restart from '//trim(path)//': the deck and the restart point disagree on cohesive interfaces')
    if (allocated(st%crack_beta)) then
      if (size(st%crack_beta) /= sc%cracks%npts .or. size(st%crack_broken_step) /= sc%cracks%nedges .or. &
          size(st%crack_flags, 1) /= 4 .or. size(st%crack_family_damage) /= sc%cracks%nfamilies) &
        call fatal('restart from '//trim(path)//': cohesive interfaces do not match the deck')
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
    sc%time = st%time
    sc%solver%rng%state = st%rng_state
    sc%kinetic0 = st%energies(1)
    sc%work_gravity = st%energies(2)
    sc%work_forces = st%energies(3)
    sc%work_supports = st%energies(4)
    sc%dissipated = st%energies(5)
    sc%cohesive_energy = st%energies(6)
    sc%damage_dissipated = st%energies(7)
    ! End of the step = beginning of the next (rbdy2_end_step).
    sc%bodies%x = st%x
    sc%bodies%xbegin = st%x
    sc%bodies%v = st%v
    sc%bodies%vbegin = st%v
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
    vtk_frames = st%vtk_frames
    outbox_writes = st%outbox_writes
  end subroutine restart_load
end module fracas_restart
