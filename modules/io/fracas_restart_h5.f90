!> Restart points in OUTBOX/fracas.h5: everything a run needs to continue
!> exactly as if it had not stopped, at full precision, as plain arrays (the
!> solver layer converts its scene to and from restart_state_t).
!>
!>   /restart                 attribute last: step of the latest restart point
!>   /restart/<step>          one point (group name: the step number, no padding)
!>     attributes  step, steps_done, step_level (halvings of the time step
!>                 the next step starts with: crack_step_limit), time, bodies, contactors, vtk_frames, outbox_writes
!>     X, V        (3, nb) body displacements and velocities at the end of the step
!>     energies    energy audit accumulators (names in attribute names)
!>     rng_state   the NLGS shuffle generator, a 64-bit state as two 32-bit halves
!>     history/    contacts of the step as the next step reads them: first (nt+1),
!>                 inter, an, sub, status (n), force, point (2, n), internals (5, n)
!>     pairs       (4, np) broad-phase pairs kept between rough detections
!>                 (candidate, antagonist, interaction, law), pair_alert (np)
!>     mesh/       only with meshed bodies: X, V (2, nnodes), gp (gp_size, ngp),
!>                 fint (2, nnodes), energies (5: kinetic0, work_gravity,
!>                 work_forces, work_supports, plastic_work)
!>     cracks/     only with cohesive interfaces of meshes: beta (npts),
!>                 flags (3, npts: glued, seen, partner), broken_step (nedges)
!>
!> Layout in doc/output_layout.md; use in doc/restart.md.
module fracas_restart_h5
  use fracas_kinds, only: wp, ik, i8
  use fracas_errors, only: fatal
  use fracas_strings, only: itoa, rtoa
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use fracas_files, only: file_exists
  use fracas_h5, only: hid_t, h5_open_file, h5_close_file, h5_create_group, h5_open_group, &
                       h5_close_group, h5_exists, h5_write_attr, h5_read_attr, h5_has_attr, &
                       h5_write_dataset, h5_read_dataset
  implicit none
  private
  public :: restart_state_t, restart_h5_write, restart_h5_read, n_energies, energy_names
  public :: restart_bad, restart_check_real1, restart_check_real2

  integer, parameter :: n_energies = 7
  character(len=*), parameter :: energy_names = 'kinetic0,work_gravity,work_forces,work_supports,' // &
                                                'dissipated,cohesive_energy,damage_dissipated'

  type :: restart_state_t
    integer :: step = 0, steps_done = 0
    integer :: step_level = 0            !< halvings of the time step the next step starts with
    real(wp) :: time = 0.0_wp
    integer :: vtk_frames = 0, outbox_writes = 0
    integer(i8) :: rng_state = 0_i8
    real(wp) :: energies(n_energies) = 0.0_wp
    real(wp), allocatable :: x(:, :), v(:, :)
    integer :: ntactors = 0
    integer, allocatable :: first(:), inter(:), an(:), sub(:), status(:)
    real(wp), allocatable :: force(:, :), point(:, :), internals(:, :)
    integer, allocatable :: pairs(:, :)
    real(wp), allocatable :: pair_alert(:)
    ! Meshed bodies (unallocated without) and their cohesive interfaces.
    real(wp), allocatable :: mesh_x(:, :), mesh_v(:, :), mesh_gp(:, :), mesh_fint(:, :), mesh_energies(:)
    real(wp), allocatable :: crack_beta(:), crack_family_damage(:)
    integer, allocatable :: crack_flags(:, :), crack_broken_step(:)
    !> Running sums of POSTPRO.DAT's commands (DISSIPATED ENERGY's cumulative
    !> column), so that a restarted run continues them; empty in older files.
    real(wp), allocatable :: postpro_sums(:)
    character(len=:), allocatable :: where   !< 'PATH:/restart/<step>' (read only, for messages)
  end type restart_state_t

contains

  !> Write restart point st into the open results file fid (the caller
  !> flushes: the driver writes it just before a snapshot, which flushes).
  subroutine restart_h5_write(fid, st)
    integer(hid_t), intent(in) :: fid
    type(restart_state_t), intent(in) :: st
    integer(hid_t) :: groot, g, gh
    character(len=:), allocatable :: name
    integer(ik) :: halves(2)
    name = itoa(st%step)
    if (h5_exists(fid, 'restart')) then
      call h5_open_group(fid, 'restart', groot)
    else
      call h5_create_group(fid, 'restart', groot)
    end if
    if (h5_exists(groot, name)) call fatal('restart point of step '//name//' written twice')
    call h5_create_group(groot, name, g)
    call h5_write_attr(g, 'step', int(st%step, ik))
    call h5_write_attr(g, 'steps_done', int(st%steps_done, ik))
    call h5_write_attr(g, 'step_level', int(st%step_level, ik))
    call h5_write_attr(g, 'time', st%time)
    call h5_write_attr(g, 'bodies', int(size(st%x, 2), ik))
    call h5_write_attr(g, 'contactors', int(st%ntactors, ik))
    call h5_write_attr(g, 'vtk_frames', int(st%vtk_frames, ik))
    call h5_write_attr(g, 'outbox_writes', int(st%outbox_writes, ik))
    call h5_write_dataset(g, 'X', st%x)
    call h5_write_dataset(g, 'V', st%v)
    call h5_write_dataset(g, 'energies', st%energies)
    call h5_write_attr(g, 'energy_names', energy_names)
    halves = transfer(st%rng_state, halves)
    call h5_write_dataset(g, 'rng_state', halves)
    call h5_create_group(g, 'history', gh)
    call h5_write_dataset(gh, 'first', st%first)
    call h5_write_dataset(gh, 'inter', st%inter)
    call h5_write_dataset(gh, 'an', st%an)
    call h5_write_dataset(gh, 'sub', st%sub)
    call h5_write_dataset(gh, 'status', st%status)
    call h5_write_dataset(gh, 'force', st%force)
    call h5_write_dataset(gh, 'point', st%point)
    if (allocated(st%internals)) call h5_write_dataset(gh, 'internals', st%internals)
    call h5_close_group(gh)
    call h5_write_dataset(g, 'pairs', st%pairs)
    call h5_write_dataset(g, 'pair_alert', st%pair_alert)
    if (allocated(st%postpro_sums)) call h5_write_dataset(g, 'postpro_sums', st%postpro_sums)
    if (allocated(st%mesh_x)) then
      call h5_create_group(g, 'mesh', gh)
      call h5_write_dataset(gh, 'X', st%mesh_x)
      call h5_write_dataset(gh, 'V', st%mesh_v)
      call h5_write_dataset(gh, 'gp', st%mesh_gp)
      call h5_write_dataset(gh, 'fint', st%mesh_fint)
      call h5_write_dataset(gh, 'energies', st%mesh_energies)
      call h5_close_group(gh)
    end if
    if (allocated(st%crack_beta)) then
      call h5_create_group(g, 'cracks', gh)
      call h5_write_dataset(gh, 'beta', st%crack_beta)
      call h5_write_dataset(gh, 'flags', st%crack_flags)
      call h5_write_dataset(gh, 'broken_step', st%crack_broken_step)
      call h5_write_dataset(gh, 'family_damage', st%crack_family_damage)
      call h5_close_group(gh)
    end if
    call h5_close_group(g)
    call h5_write_attr(groot, 'last', int(st%step, ik))
    call h5_close_group(groot)
  end subroutine restart_h5_write

  !> Read the restart point of step `step` (< 0: the latest) from PATH.
  subroutine restart_h5_read(path, step, st)
    character(len=*), intent(in) :: path
    integer, intent(in) :: step
    type(restart_state_t), intent(out) :: st
    integer(hid_t) :: fid, groot, g, gh
    integer(ik) :: ival
    integer(ik), allocatable :: halves(:)
    real(wp), allocatable :: e(:)
    character(len=:), allocatable :: name
    if (.not. file_exists(path)) call fatal('restart file '//trim(path)//' does not exist')
    call h5_open_file(path, fid)
    if (.not. h5_exists(fid, 'restart')) call fatal(trim(path)//' holds no restart point (written by '// &
      'a Fracas without restart points, or stopped before its first snapshot)')
    call h5_open_group(fid, 'restart', groot)
    if (step < 0) then
      call h5_read_attr(groot, 'last', ival)
      name = itoa(int(ival))
    else
      name = itoa(step)
    end if
    if (.not. h5_exists(groot, name)) call fatal(trim(path)//' has no restart point at step '//name// &
      ' (restart points are written with every HDF5 snapshot and at the last step; see h5ls '// &
      trim(path)//'/restart)')
    call h5_open_group(groot, name, g)
    st%where = trim(path)//':/restart/'//name
    call h5_read_attr(g, 'step', ival); st%step = ival
    call h5_read_attr(g, 'steps_done', ival); st%steps_done = ival
    st%step_level = 0   ! files of versions without crack_step_limit
    if (h5_has_attr(g, 'step_level')) then
      call h5_read_attr(g, 'step_level', ival); st%step_level = ival
    end if
    call h5_read_attr(g, 'time', st%time)
    call h5_read_attr(g, 'contactors', ival); st%ntactors = ival
    call h5_read_attr(g, 'vtk_frames', ival); st%vtk_frames = ival
    call h5_read_attr(g, 'outbox_writes', ival); st%outbox_writes = ival
    call h5_read_dataset(g, 'X', st%x)
    call h5_read_dataset(g, 'V', st%v)
    call h5_read_dataset(g, 'energies', e)
    if (size(e) /= n_energies) call fatal('restart point '//st%where//'/energies: '//itoa(size(e))// &
                                          ' values, expected '//itoa(n_energies))
    st%energies = e
    call h5_read_dataset(g, 'rng_state', halves)
    if (size(halves) /= 2) call fatal('restart point '//st%where//'/rng_state: '//itoa(size(halves))// &
                                      ' values, expected 2')
    st%rng_state = transfer(halves, st%rng_state)
    call h5_open_group(g, 'history', gh)
    call h5_read_dataset(gh, 'first', st%first)
    call h5_read_dataset(gh, 'inter', st%inter)
    call h5_read_dataset(gh, 'an', st%an)
    call h5_read_dataset(gh, 'sub', st%sub)
    call h5_read_dataset(gh, 'status', st%status)
    call h5_read_dataset(gh, 'force', st%force)
    call h5_read_dataset(gh, 'point', st%point)
    if (h5_exists(gh, 'internals')) call h5_read_dataset(gh, 'internals', st%internals)
    call h5_close_group(gh)
    call h5_read_dataset(g, 'pairs', st%pairs)
    call h5_read_dataset(g, 'pair_alert', st%pair_alert)
    if (h5_exists(g, 'postpro_sums')) then
      call h5_read_dataset(g, 'postpro_sums', st%postpro_sums)
    else
      allocate (st%postpro_sums(0))
    end if
    if (h5_exists(g, 'mesh')) then
      call h5_open_group(g, 'mesh', gh)
      call h5_read_dataset(gh, 'X', st%mesh_x)
      call h5_read_dataset(gh, 'V', st%mesh_v)
      call h5_read_dataset(gh, 'gp', st%mesh_gp)
      call h5_read_dataset(gh, 'fint', st%mesh_fint)
      call h5_read_dataset(gh, 'energies', st%mesh_energies)
      call h5_close_group(gh)
    end if
    if (h5_exists(g, 'cracks')) then
      call h5_open_group(g, 'cracks', gh)
      call h5_read_dataset(gh, 'beta', st%crack_beta)
      call h5_read_dataset(gh, 'flags', st%crack_flags)
      call h5_read_dataset(gh, 'broken_step', st%crack_broken_step)
      call h5_read_dataset(gh, 'family_damage', st%crack_family_damage)
      call h5_close_group(gh)
    end if
    call h5_close_group(g)
    call h5_close_group(groot)
    call h5_close_file(fid)
  end subroutine restart_h5_read

  ! Checks of a restart point's datasets before any is used (fracas_restart's
  ! validate_point and the body models' *_check_restart): an error names the dataset,
  ! 'PATH:/restart/<step>/<dataset>: what'.

  !> Stop the run: dataset (or the point itself, '') of st is not what the deck needs.
  subroutine restart_bad(st, dataset, what)
    type(restart_state_t), intent(in) :: st
    character(len=*), intent(in) :: dataset, what
    if (len(dataset) > 0) then
      call fatal('restart point '//st%where//'/'//dataset//': '//what)
    else
      call fatal('restart point '//st%where//': '//what)
    end if
  end subroutine restart_bad

  !> n finite values.
  subroutine restart_check_real1(st, dataset, a, n)
    type(restart_state_t), intent(in) :: st
    character(len=*), intent(in) :: dataset
    real(wp), intent(in) :: a(:)
    integer, intent(in) :: n
    integer :: i
    if (size(a) /= n) call restart_bad(st, dataset, itoa(size(a))//' values, expected '//itoa(n))
    do i = 1, n
      if (.not. ieee_is_finite(a(i))) call restart_bad(st, dataset, 'value '//itoa(i)//' is '//rtoa(a(i)))
    end do
  end subroutine restart_check_real1

  !> Shape (n1, n2) (h5py shows (n2, n1)), finite rows.
  subroutine restart_check_real2(st, dataset, a, n1, n2)
    type(restart_state_t), intent(in) :: st
    character(len=*), intent(in) :: dataset
    real(wp), intent(in) :: a(:, :)
    integer, intent(in) :: n1, n2
    integer :: j
    if (size(a, 1) /= n1 .or. size(a, 2) /= n2) call restart_bad(st, dataset, 'shape ('//itoa(size(a, 2))//', '// &
      itoa(size(a, 1))//') as h5py shows it, expected ('//itoa(n2)//', '//itoa(n1)//')')
    do j = 1, n2
      if (.not. all(ieee_is_finite(a(:, j)))) call restart_bad(st, dataset, 'row '//itoa(j - 1)//' (from 0) is not finite')
    end do
  end subroutine restart_check_real2
end module fracas_restart_h5
