!> The Fracas results file OUTBOX/fracas.h5 (layout: doc/output_layout.md), built
!> on fracas_h5 from plain arrays: it knows nothing of the solver's types.
!>
!>   call results_open(r, 'OUTBOX/fracas.h5', overwrite, case_dir, dt, theta, names)
!>   call results_write_bodies(r, number, mass, inertia, radius, reference)
!>   call results_write_help(r, status_names, inter_names, law_names)
!>   each step:      call results_append_step(r, values)      (values in names' order)
!>   each snapshot:  call results_write_snapshot(r, step, time, X, V, inter, ...)
!>   at the end:     call results_close(r)                    (sets complete = 1)
!>   more data:      call results_group(r, 'mesh', g) ... fracas_h5 calls ... h5_close_group(g)
!>                   call results_last_snapshot(r, g) (the newest snapshot's group)
!>
!> The file is written in place; its root attribute complete stays 0 until
!> results_close, so a crashed or running job's file is recognisable.
!> Series rows are kept in memory and written in blocks; the file is flushed
!> (rows and snapshots made readable on disk) at most every flush_interval
!> seconds of wall time, when a row or a snapshot is added, and at the end: a
!> killed run's file holds everything up to its last flush.
module fracas_results_h5
  use fracas_kinds, only: wp, ik, i8
  use fracas_strings, only: itoa
  use fracas_errors, only: fatal
  use fracas_files, only: file_exists, atomic_rename
  use fracas_h5, only: hid_t, h5_series_t, h5_create_file, h5_close_file, h5_flush, h5_file_renamed, &
                       h5_create_group, h5_open_group, h5_close_group, h5_exists, &
                       h5_write_attr, h5_write_dataset, h5_create_series, h5_append, &
                       h5_close_series
  implicit none
  private
  public :: results_h5_t, results_open, results_write_bodies, results_write_help, &
            results_write_snapshot, results_append_step, results_flush, results_close, &
            results_layout_version, results_group, results_last_snapshot, results_rename

  !> Bumped when the layout changes incompatibly; stored as root attribute layout_version.
  integer(ik), parameter :: results_layout_version = 1

  !> Seconds of wall time between automatic flushes (results_append_step,
  !> results_write_snapshot): a flush costs milliseconds, a step may cost
  !> microseconds.
  real(wp), parameter :: flush_interval = 2.0_wp
  !> Series rows kept in memory before they are written as one block.
  integer, parameter :: row_block = 1024

  type :: results_h5_t
    character(len=:), allocatable :: path
    integer(hid_t) :: fid = -1
    type(h5_series_t), allocatable :: cols(:)     !< /series/<name>
    type(h5_series_t) :: snap_step, snap_time     !< /snapshot_index/{step,time}
    integer :: nsnap = 0                          !< snapshots written
    integer :: nrows = 0                          !< rows appended to /series
    real(wp), allocatable :: rows(:, :)           !< (ncols, row_block) rows not yet written
    integer :: nbuf = 0                           !< rows in rows(:, 1:nbuf)
    integer(i8) :: last_flush = 0                 !< system_clock count
    logical :: is_open = .false.
  end type results_h5_t

contains

  !> Create the results file PATH with its root attributes, /series (one empty
  !> extendible column per name), /snapshots, /snapshot_index and /help.
  !> An existing PATH is replaced only if overwrite; otherwise fatal.
  !> version: the program version string (default 'unknown').
  !> The open results file gets the name PATH (e.g. from the PATH.part it was
  !> created as, once its description is on disk: a reader never finds a
  !> half-created file under PATH).
  subroutine results_rename(r, path)
    type(results_h5_t), intent(inout) :: r
    character(len=*), intent(in) :: path
    call require_open(r, 'results_rename')
    call atomic_rename(r%path, path)
    r%path = trim(path)
    call h5_file_renamed(r%path)
  end subroutine results_rename

  !> integer_series: the series stored as Int32 (counts, flags); the others Float64.
  subroutine results_open(r, path, overwrite, case_dir, dt, theta, series_names, version, integer_series)
    type(results_h5_t), intent(inout) :: r
    character(len=*), intent(in) :: path, case_dir
    logical, intent(in) :: overwrite
    real(wp), intent(in) :: dt, theta
    character(len=*), intent(in) :: series_names(:)
    character(len=*), intent(in), optional :: version
    character(len=*), intent(in), optional :: integer_series(:)
    integer(hid_t) :: g
    logical :: is_int
    integer :: k, j
    character(len=:), allocatable :: cols

    if (r%is_open) call fatal('results_open: '//trim(path)//': a results file is already open')
    if (file_exists(path) .and. .not. overwrite) &
      call fatal('results file '//trim(path)//' already exists; pass --overwrite to replace it')
    do k = 1, size(series_names)
      if (len_trim(series_names(k)) == 0 .or. index(series_names(k), '/') > 0 .or. &
          index(series_names(k), ',') > 0) &
        call fatal('results_open: bad series name "'//trim(series_names(k))//'"')
      do j = 1, k - 1
        if (series_names(j) == series_names(k)) &
          call fatal('results_open: series name "'//trim(series_names(k))//'" given twice')
      end do
    end do

    r%path = trim(path)
    call h5_create_file(r%path, overwrite, r%fid)
    r%is_open = .true.
    r%nsnap = 0
    r%nrows = 0

    call h5_write_attr(r%fid, 'program', 'fracas')
    if (present(version)) then
      call h5_write_attr(r%fid, 'version', version)
    else
      call h5_write_attr(r%fid, 'version', 'unknown')
    end if
    call h5_write_attr(r%fid, 'layout_version', results_layout_version)
    call h5_write_attr(r%fid, 'case_dir', case_dir)
    call h5_write_attr(r%fid, 'created', timestamp())
    call h5_write_attr(r%fid, 'complete', 0_ik)
    call h5_write_attr(r%fid, 'time_step', dt)
    call h5_write_attr(r%fid, 'theta', theta)

    cols = ''
    do k = 1, size(series_names)
      if (k > 1) cols = cols//','
      cols = cols//trim(series_names(k))
    end do
    call h5_create_group(r%fid, 'series', g)
    call h5_write_attr(g, 'columns', cols)
    allocate (r%cols(size(series_names)), r%rows(size(series_names), row_block))
    r%nbuf = 0
    do k = 1, size(series_names)
      is_int = .false.
      if (present(integer_series)) is_int = any(integer_series == series_names(k))
      call h5_create_series(g, trim(series_names(k)), r%cols(k), is_int=is_int)
    end do
    call h5_close_group(g)

    call h5_create_group(r%fid, 'snapshots', g)
    call h5_write_attr(g, 'count', 0_ik)
    call h5_close_group(g)

    call h5_create_group(r%fid, 'snapshot_index', g)
    call h5_create_series(g, 'step', r%snap_step, is_int=.true., chunk=256)
    call h5_create_series(g, 'time', r%snap_time, chunk=256)
    call h5_close_group(g)

    call h5_create_group(r%fid, 'help', g)
    call h5_write_dataset(g, 'series_columns', series_names)
    call h5_close_group(g)

    call h5_flush(r%fid)
    call system_clock(r%last_flush)
  end subroutine results_open

  !> /bodies: serial numbers, mass, inertia, average radius and reference
  !> coordinates (ndof, nb) (x, y, angle for RBDY2). model: default 'RBDY2'.
  subroutine results_write_bodies(r, number, mass, inertia, radius, reference, model)
    type(results_h5_t), intent(inout) :: r
    integer(ik), intent(in) :: number(:)
    real(wp), intent(in) :: mass(:), inertia(:), radius(:), reference(:, :)
    character(len=*), intent(in), optional :: model
    integer(hid_t) :: g
    integer :: nb
    call require_open(r, 'results_write_bodies')
    nb = size(number)
    call same_size('results_write_bodies', 'mass', size(mass), nb)
    call same_size('results_write_bodies', 'inertia', size(inertia), nb)
    call same_size('results_write_bodies', 'radius', size(radius), nb)
    call same_size('results_write_bodies', 'reference columns', size(reference, 2), nb)
    call group_here(r%fid, 'bodies', g)
    if (present(model)) then
      call h5_write_attr(g, 'model', model)
    else
      call h5_write_attr(g, 'model', 'RBDY2')
    end if
    call h5_write_attr(g, 'count', int(nb, ik))
    call h5_write_dataset(g, 'number', number)
    call h5_write_dataset(g, 'mass', mass)
    call h5_write_dataset(g, 'inertia', inertia)
    call h5_write_dataset(g, 'radius', radius)
    call h5_write_dataset(g, 'reference', reference)
    call h5_close_group(g)
  end subroutine results_write_bodies

  !> /help/{status,inter,law}: names of the integer ids 1, 2, ... (row id-1 in h5py).
  subroutine results_write_help(r, status_names, inter_names, law_names)
    type(results_h5_t), intent(inout) :: r
    character(len=*), intent(in) :: status_names(:), inter_names(:), law_names(:)
    integer(hid_t) :: g
    call require_open(r, 'results_write_help')
    call group_here(r%fid, 'help', g)
    call h5_write_dataset(g, 'status', status_names)
    call h5_write_dataset(g, 'inter', inter_names)
    call h5_write_dataset(g, 'law', law_names)
    call h5_close_group(g)
  end subroutine results_write_help

  !> Append one row to /series: values(k) to column k (results_open's order).
  !> Rows are written in blocks of row_block; the file is flushed when more than
  !> flush_interval seconds passed since the last flush.
  subroutine results_append_step(r, values)
    type(results_h5_t), intent(inout) :: r
    real(wp), intent(in) :: values(:)
    call require_open(r, 'results_append_step')
    if (size(values) /= size(r%cols)) &
      call fatal('results_append_step: '//itoa(size(values))//' values for '// &
                 itoa(size(r%cols))//' series columns')
    r%nbuf = r%nbuf + 1
    r%rows(:, r%nbuf) = values
    r%nrows = r%nrows + 1
    if (r%nbuf == row_block) call write_rows(r)
    call flush_if_due(r)
  end subroutine results_append_step

  !> Write the rows held in memory to the /series columns.
  subroutine write_rows(r)
    type(results_h5_t), intent(inout) :: r
    integer :: k
    if (r%nbuf == 0) return
    do k = 1, size(r%cols)
      call h5_append(r%cols(k), r%rows(k, 1:r%nbuf))
    end do
    r%nbuf = 0
  end subroutine write_rows

  !> results_flush when flush_interval seconds have passed since the last one.
  subroutine flush_if_due(r)
    type(results_h5_t), intent(inout) :: r
    integer(i8) :: now, rate
    call system_clock(now, rate)
    if (rate > 0) then
      if (real(now - r%last_flush, wp) > flush_interval*real(rate, wp)) call results_flush(r)
    end if
  end subroutine flush_if_due

  !> Group NAME under the root (created if missing), for data beyond the
  !> standard layout (e.g. /run, /contactors, /mesh); close it with h5_close_group.
  subroutine results_group(r, name, g)
    type(results_h5_t), intent(inout) :: r
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: g
    call require_open(r, 'results_group')
    call group_here(r%fid, name, g)
  end subroutine results_group

  !> The group of the newest snapshot (/snapshots/NNNNNN), to add datasets to
  !> it (e.g. the state of meshed bodies); close it with h5_close_group.
  subroutine results_last_snapshot(r, g)
    type(results_h5_t), intent(inout) :: r
    integer(hid_t), intent(out) :: g
    call require_open(r, 'results_last_snapshot')
    if (r%nsnap == 0) call fatal('results_last_snapshot: no snapshot written yet')
    call h5_open_group(r%fid, 'snapshots/'//snapshot_name(r%nsnap), g)
  end subroutine results_last_snapshot

  !> One snapshot /snapshots/NNNNNN (1, 2, ... zero-padded to 6 digits): body
  !> states X, V (ndof, nb) and the contacts (nc of them). normal, point,
  !> reaction (rt, rn forces), velocity (ut, un) are (nd, nc), nd the contacts'
  !> dimension (2; 3: tangential t1, t2 then normal); internals (nint, nc);
  !> broken (nc) flags the cohesive interfaces that are broken (beta = 0).
  subroutine results_write_snapshot(r, step, time, X, V, inter, cd_body, an_body, cd_tactor, &
                                    an_tactor, status, law, normal, point, reaction, velocity, gap, &
                                    internals, broken)
    type(results_h5_t), intent(inout) :: r
    integer(ik), intent(in) :: step
    real(wp), intent(in) :: time
    real(wp), intent(in) :: X(:, :), V(:, :)
    integer(ik), intent(in) :: inter(:), cd_body(:), an_body(:), cd_tactor(:), an_tactor(:), &
                               status(:), law(:)
    real(wp), intent(in) :: normal(:, :), point(:, :), reaction(:, :), velocity(:, :), gap(:)
    real(wp), intent(in), optional :: internals(:, :)
    integer(ik), intent(in), optional :: broken(:)   !< 1 where a cohesive interface is broken
    character(len=*), parameter :: w = 'results_write_snapshot'
    integer(hid_t) :: gs, g, gsub
    integer :: nc
    character(len=:), allocatable :: name

    call require_open(r, w)
    if (any(shape(V) /= shape(X))) call fatal(w//': X and V shapes differ')
    nc = size(inter)
    call same_size(w, 'cd_body', size(cd_body), nc)
    call same_size(w, 'an_body', size(an_body), nc)
    call same_size(w, 'cd_tactor', size(cd_tactor), nc)
    call same_size(w, 'an_tactor', size(an_tactor), nc)
    call same_size(w, 'status', size(status), nc)
    call same_size(w, 'law', size(law), nc)
    call same_size(w, 'gap', size(gap), nc)
    if (size(normal, 1) /= 2 .and. size(normal, 1) /= 3) &
      call fatal(w//': normal has '//itoa(size(normal, 1))//' rows, expected 2 or 3 (the dimension)')
    call pair_shape(w, 'normal', normal, size(normal, 1), nc)
    call pair_shape(w, 'point', point, size(normal, 1), nc)
    call pair_shape(w, 'reaction', reaction, size(normal, 1), nc)
    call pair_shape(w, 'velocity', velocity, size(normal, 1), nc)
    if (present(internals)) call same_size(w, 'internals columns', size(internals, 2), nc)
    if (present(broken)) call same_size(w, 'broken', size(broken), nc)

    r%nsnap = r%nsnap + 1
    name = snapshot_name(r%nsnap)
    call h5_open_group(r%fid, 'snapshots', gs)
    call h5_create_group(gs, name, g)
    call h5_write_attr(g, 'step', step)
    call h5_write_attr(g, 'time', time)

    call h5_create_group(g, 'bodies', gsub)
    call h5_write_attr(gsub, 'count', int(size(X, 2), ik))
    call h5_write_dataset(gsub, 'X', X)
    call h5_write_dataset(gsub, 'V', V)
    call h5_close_group(gsub)

    call h5_create_group(g, 'contacts', gsub)
    call h5_write_attr(gsub, 'count', int(nc, ik))
    call h5_write_dataset(gsub, 'inter', inter)
    call h5_write_dataset(gsub, 'cd_body', cd_body)
    call h5_write_dataset(gsub, 'an_body', an_body)
    call h5_write_dataset(gsub, 'cd_tactor', cd_tactor)
    call h5_write_dataset(gsub, 'an_tactor', an_tactor)
    call h5_write_dataset(gsub, 'status', status)
    call h5_write_dataset(gsub, 'law', law)
    call h5_write_dataset(gsub, 'normal', normal)
    call h5_write_dataset(gsub, 'point', point)
    call h5_write_dataset(gsub, 'reaction', reaction)
    call h5_write_dataset(gsub, 'velocity', velocity)
    call h5_write_dataset(gsub, 'gap', gap)
    if (present(internals)) call h5_write_dataset(gsub, 'internals', internals)
    if (present(broken)) call h5_write_dataset(gsub, 'broken', broken)
    call h5_close_group(gsub)
    call h5_close_group(g)

    call h5_write_attr(gs, 'count', int(r%nsnap, ik))
    call h5_close_group(gs)
    call h5_append(r%snap_step, step)
    call h5_append(r%snap_time, time)
    call flush_if_due(r)
  end subroutine results_write_snapshot

  !> Write everything buffered to disk (the file stays open, complete stays 0).
  subroutine results_flush(r)
    type(results_h5_t), intent(inout) :: r
    if (.not. r%is_open) return
    call write_rows(r)
    call h5_flush(r%fid)
    call system_clock(r%last_flush)
  end subroutine results_flush

  !> Set complete = 1 (or 0 with complete=.false.: a run stopped before its
  !> end; end_reason then says why), flush and close. Does nothing if the file
  !> is not open.
  subroutine results_close(r, complete, end_reason)
    type(results_h5_t), intent(inout) :: r
    logical, intent(in), optional :: complete
    character(len=*), intent(in), optional :: end_reason
    integer :: k
    logical :: done
    if (.not. r%is_open) return
    done = .true.
    if (present(complete)) done = complete
    call write_rows(r)
    if (present(end_reason)) call h5_write_attr(r%fid, 'end_reason', end_reason)
    if (allocated(r%cols)) then
      do k = 1, size(r%cols)
        call h5_close_series(r%cols(k))
      end do
      deallocate (r%cols)
    end if
    if (allocated(r%rows)) deallocate (r%rows)
    call h5_close_series(r%snap_step)
    call h5_close_series(r%snap_time)
    call h5_write_attr(r%fid, 'complete', merge(1_ik, 0_ik, done))
    call h5_close_file(r%fid)
    r%is_open = .false.
  end subroutine results_close

  ! ---------------------------------------------------------------- helpers

  subroutine require_open(r, who)
    type(results_h5_t), intent(in) :: r
    character(len=*), intent(in) :: who
    if (.not. r%is_open) call fatal(who//': the results file is not open')
  end subroutine require_open

  subroutine same_size(who, what, n, nref)
    character(len=*), intent(in) :: who, what
    integer, intent(in) :: n, nref
    if (n /= nref) call fatal(who//': '//what//' has size '//itoa(n)//', expected '//itoa(nref))
  end subroutine same_size

  subroutine pair_shape(who, what, a, nd, nc)
    character(len=*), intent(in) :: who, what
    real(wp), intent(in) :: a(:, :)
    integer, intent(in) :: nd, nc
    if (size(a, 1) /= nd .or. size(a, 2) /= nc) &
      call fatal(who//': '//what//' has shape ('//itoa(size(a, 1))//','//itoa(size(a, 2))// &
                 '), expected ('//itoa(nd)//','//itoa(nc)//')')
  end subroutine pair_shape

  !> Open group NAME under loc, creating it if missing.
  subroutine group_here(loc, name, g)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: g
    if (h5_exists(loc, name)) then
      call h5_open_group(loc, name, g)
    else
      call h5_create_group(loc, name, g)
    end if
  end subroutine group_here

  !> '000001' ... '999999', then the plain number.
  pure function snapshot_name(k) result(s)
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    character(len=16) :: buf
    if (k <= 999999) then
      write (buf, '(i6.6)') k
    else
      write (buf, '(i0)') k
    end if
    s = trim(buf)
  end function snapshot_name

  !> Local date and time, ISO 8601 (e.g. 2024-05-01T12:30:00+02:00).
  function timestamp() result(s)
    character(len=:), allocatable :: s
    character(len=8) :: d
    character(len=10) :: t
    character(len=5) :: z
    call date_and_time(d, t, z)
    s = d(1:4)//'-'//d(5:6)//'-'//d(7:8)//'T'//t(1:2)//':'//t(3:4)//':'//t(5:6)// &
        z(1:3)//':'//z(4:5)
  end function timestamp

end module fracas_results_h5
