!> Everything a run writes: DISPLAY/*.vtu + DISPLAY/fracas.pvd (ParaView),
!> OUTBOX/fracas.h5 (what the run was, states, contacts, solver and energy
!> series), OUTBOX/DOF.OUT.n + Vloc_Rloc.OUT.n in LMGC90's layout and the
!> POSTPRO/ files of POSTPRO.DAT. Converts the scene to the plain arrays and
!> records the io writers take.
!>
!> Results never mix: output_open refuses to start where files of an earlier
!> run lie (OUTBOX/, DISPLAY/, POSTPRO/ names a run writes), or removes them
!> all first with overwrite; '.part' files of a killed run are removed.
module fracas_output
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use fracas_kinds, only: wp, ik, i8
  use fracas_errors, only: fatal
  use fracas_ids, only: inter_names, status_names, n_inter, bm_rigid, bm_mesh
  use fracas_files, only: make_dir, file_exists, dir_exists, remove_file, list_dir, name_t, close_written, lock_file
  use fracas_deck, only: dof_record_t, contact_record_t, deck_t, run_control_t, gpv_record_t
  use fracas_datbox_text, only: itoa, load_text, text_file_t
  use fracas_strings, only: rtoa
  use fracas_h5, only: hid_t, h5_write_attr, h5_write_dataset, h5_close_group, h5_create_group, &
                       h5_set_dataset_hook
  use fracas_vtk, only: vtu_t, vtu_begin, vtu_points, vtu_cells, vtu_vertex_cells, vtu_point_data, &
                        vtu_cell_data, vtu_end, pvd_t, pvd_init, pvd_add, vtk_poly_line, vtk_polygon, &
                        vtu_cells_fixed, vtk_line, vtu_field_strings
  use fracas_contactors, only: tactor_center, tactor_vertices, tactor_kind_name, tk_polyg, tk_jonc, tk_disk, &
                               tk_xksid, tk_alpxx
  use fracas_scene, only: scene_t, step_report_t, scene_energy_terms
  use fracas_energy, only: energy_terms_t
  use fracas_version, only: version_string, git_commit, build_type, compiler, compiler_flags
  use fracas_contact_laws, only: law_czm, law_iqs_clb_g0, int_beta
  use fracas_write_outbox, only: write_dof_file, write_vloc_rloc_file, write_gpv_file
  use fracas_mailx, only: mailx_gauss_values, mailx_dof_records, mailx_write_static, mailx_write_snapshot
  use fracas_rbdy2, only: rbdy2_dof_records
  use fracas_elements, only: el_ngauss_gpv, el_name, el_vtk_type, el_vtk_order
  use fracas_cracks, only: crack_paths_t, cracks_paths, cracks_lengths, cracks_fragments, cracks_edge_beta, &
                           fragments_t, cracks_fragment_stats
  use fracas_bulk, only: bulk_j2, bulk_j2_finite, plane_names, gp_sxx, gp_szz, gp_exx, gp_eyy, gp_gxy, gp_ezz, &
                         gp_pxx, gp_pzz, gp_p
  use fracas_results_h5, only: results_h5_t, results_open, results_write_bodies, results_write_help, &
                               results_write_snapshot, results_append_step, results_close, results_flush, &
                               results_group, results_last_snapshot, results_rename
  use fracas_postpro, only: postpro_t, postpro_prepare, postpro_open, postpro_step, postpro_flush, postpro_close, &
                            postpro_owns
  use fracas_h5_describe, only: h5_describe_dataset
  implicit none
  private
  public :: output_t, output_prepare, output_open, output_vtk, output_outbox, output_snapshot, output_series, &
            output_flush, output_close, series_names, output_owns, output_summary, output_timing

  integer, parameter :: n_series = 39
  character(len=24), parameter :: series_names(n_series) = [character(len=24) :: &
    'step', 'time', 'contacts', 'active_contacts', 'sweeps', 'converged', 'residual_natural_map', &
    'residual_onepq', 'quad_dv', 'maxm_dv', 'mean_dvor', 'kinetic_energy', 'work_gravity', &
    'work_forces', 'work_supports', 'dissipated', 'cohesive_energy', 'damage_dissipated', 'balance_error', &
    'mean_overlap', 'max_overlap', 'solve_time', 'step_time', 'elastic_energy', 'plastic_work', &
    'newton_iterations', 'crack_length', 'damaged_length', 'broken_interfaces', 'damaged_interfaces', &
    'bodies_time', 'detect_time', 'prepare_time', 'contact_updates', 'velocity_time', 'fragments', &
    'substeps', 'rejected_substeps', 'crack_increment']
  !> The series that count (stored as Int32; contact_updates, which can pass 2^31, stays Float64).
  character(len=24), parameter :: integer_series(11) = [character(len=24) :: 'step', 'contacts', &
    'active_contacts', 'sweeps', 'converged', 'newton_iterations', 'broken_interfaces', 'damaged_interfaces', &
    'fragments', 'substeps', 'rejected_substeps']
  integer, parameter :: n_outline = 24   !< points of a circle or wall outline
  !> Seconds of wall time between flushes of the POSTPRO files.
  real(wp), parameter :: flush_interval = 2.0_wp
  !> Bytes of OUTBOX/fracas.h5.reserve: disk space held for the run's end, freed
  !> before fracas.h5 is closed, so that a full disk still leaves room for
  !> HDF5's last metadata writes (else the file is left unreadable).
  integer, parameter :: reserve_bytes = 1048576
  character(len=*), parameter :: units_statement = 'the units of the deck: Fracas has no unit system of '// &
    'its own; lengths, masses, times, forces (and so velocities, energies) are in the units the deck '// &
    'was written in (SI for a deck in metres, kilograms and seconds)'

  type :: output_t
    character(len=:), allocatable :: outbox, display
    type(pvd_t) :: pvd
    integer :: n_vtk = 0, n_out = 0
    logical :: disk_points = .true.       !< disks as points with a radius (else filled polygons)
    logical :: vtk_single = .true.        !< reals of the .vtu as Float32
    integer :: part_disks = -1, part_shapes = -1, part_contacts = -1   !< .pvd parts (-1: not written)
    integer :: part_meshes = -1, part_interfaces = -1, part_cracks = -1
    !> Bulk behaviour of each material index (the names of the meshes' `material` field).
    character(len=5), allocatable :: material_names(:)
    type(results_h5_t) :: h5
    logical :: h5_open = .false.
    character(len=:), allocatable :: reserve   !< OUTBOX/fracas.h5.reserve while the run holds it
    character(len=:), allocatable :: lock      !< OUTBOX/fracas.lock, held (flock) by the running run
    type(postpro_t) :: pp
    integer(i8) :: last_flush = 0
    !> CPU time spent writing (so that a loaded machine does not inflate it), and
    !> writes, per kind: VTK frames, HDF5 snapshots, DOF/Vloc_Rloc files, series
    !> rows (with POSTPRO lines).
    real(wp) :: seconds(4) = 0.0_wp
    integer :: writes(4) = 0
  end type output_t

  integer, parameter :: k_vtk = 1, k_snapshot = 2, k_outbox = 3, k_series = 4

contains

  !> The checks of the output requests against the scene (POSTPRO.DAT's
  !> commands and node sets), before anything is written: --check runs them.
  subroutine output_prepare(o, sc, deck)
    type(output_t), intent(out) :: o
    type(scene_t), intent(in) :: sc
    type(deck_t), intent(in) :: deck
    call postpro_prepare(o%pp, deck%postpro, deck%run%nlgs_check, sc%meshes)
  end subroutine output_prepare

  !> Prepare OUT_DIR for the run of DECK (the scene SC built from it; O from
  !> output_prepare): clear or refuse the results of an earlier run (see the
  !> module comment), create OUTBOX/ (and DISPLAY/ if output_vtk_every > 0,
  !> POSTPRO/ if POSTPRO.DAT asks for files), open OUTBOX/fracas.h5 and write
  !> what the run is.
  subroutine output_open(o, sc, deck, out_dir, overwrite)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: out_dir
    logical, intent(in) :: overwrite
    character(len=5), allocatable :: law_names(:)
    integer :: k
    logical :: with_vtk
    o%outbox = trim(out_dir)//'/OUTBOX'
    o%display = trim(out_dir)//'/DISPLAY'
    with_vtk = deck%run%output_vtk_every > 0
    o%disk_points = deck%run%output_vtk_disks /= 'polygons'
    o%vtk_single = deck%run%output_vtk_precision /= 'double'
    call refuse_earlier_results(out_dir, overwrite)
    o%material_names = [(deck%materials(k)%nickname, k=1, size(deck%materials))]
    call make_dir(o%outbox, parents=.true.)
    call lock_output(o, out_dir)
    call clear_earlier_results(out_dir, with_vtk)
    call hold_reserve(o)
    if (with_vtk) then
      k = 0
      if (o%disk_points .and. any(sc%tactors%kind(1:sc%tactors%n) == tk_disk)) then
        o%part_disks = k
        k = k + 1
      end if
      if (any(sc%tactors%kind(1:sc%tactors%n) /= tk_disk .and. sc%tactors%model(1:sc%tactors%n) == bm_rigid) .or. &
          (.not. o%disk_points .and. any(sc%tactors%kind(1:sc%tactors%n) == tk_disk))) then
        o%part_shapes = k
        k = k + 1
      end if
      if (sc%meshes%n > 0) then
        o%part_meshes = k
        k = k + 1
      end if
      if (sc%cracks%nedges > 0) then
        o%part_interfaces = k
        o%part_cracks = k + 1
        k = k + 2
      end if
      o%part_contacts = k
    end if

    ! Created as fracas.h5.part and renamed once its description is on disk: a
    ! fracas.h5 is valid from its first byte (a kill before leaves a .part,
    ! removed by the next run).
    call h5_set_dataset_hook(h5_describe_dataset)   ! units and description on every dataset
    call results_open(o%h5, o%outbox//'/fracas.h5.part', overwrite, deck%case_dir, sc%h, sc%theta, series_names, &
                      version=version_string, integer_series=integer_series)
    o%h5_open = .true.
    call h5_write_attr(o%h5%fid, 'units', units_statement)
    ! Provenance: what built this program (fracas --version says the same).
    call h5_write_attr(o%h5%fid, 'git_commit', git_commit)
    call h5_write_attr(o%h5%fid, 'build_type', build_type)
    call h5_write_attr(o%h5%fid, 'compiler', compiler)
    call h5_write_attr(o%h5%fid, 'compiler_flags', compiler_flags)
    call h5_write_attr(o%h5%fid, 'mpi_ranks', 1_ik)          ! serial: one process,
    call h5_write_attr(o%h5%fid, 'threads', 1_ik)            ! one thread
    call h5_write_attr(o%h5%fid, 'gravity', deck%gravity)
    call results_write_bodies(o%h5, sc%bodies%number, sc%bodies%mass(1, :), sc%bodies%mass(3, :), &
                              sc%bodies%avrd, sc%bodies%ref)
    if (sc%meshes%n > 0) call mesh_static(o, sc)
    allocate (law_names(size(sc%laws)))
    do k = 1, size(sc%laws)
      law_names(k) = sc%laws(k)%nickname
    end do
    call results_write_help(o%h5, status_names, inter_names, law_names)
    call write_run_group(o, deck)
    call write_contactors_group(o, sc)
    call results_flush(o%h5)
    call results_rename(o%h5, o%outbox//'/fracas.h5')
    if (with_vtk) then
      call make_dir(o%display, parents=.true.)
      call pvd_init(o%pvd, o%display//'/fracas.pvd')
    end if

    call postpro_open(o%pp, out_dir)
    call system_clock(o%last_flush)
  end subroutine output_open

  !> Write OUTBOX/fracas.h5.reserve (reserve_bytes of zeros).
  subroutine hold_reserve(o)
    type(output_t), intent(inout) :: o
    integer :: u, ios, k
    character(len=65536) :: zeros
    o%reserve = o%outbox//'/fracas.h5.reserve'
    zeros = repeat(achar(0), len(zeros))
    open (newunit=u, file=o%reserve, status='replace', access='stream', form='unformatted', action='write', &
          iostat=ios)
    if (ios /= 0) call fatal('cannot open '//o%reserve//' for writing')
    do k = 1, reserve_bytes / len(zeros)
      write (u, iostat=ios) zeros
      if (ios /= 0) exit
    end do
    call close_written(u, o%reserve)
  end subroutine hold_reserve

  !> /run: the run control the run used (every COMMAND.DAT keyword, after the
  !> --set settings), where it came from, and the settings themselves.
  subroutine write_run_group(o, deck)
    type(output_t), intent(inout) :: o
    type(deck_t), intent(in) :: deck
    integer(hid_t) :: g
    type(text_file_t) :: tf
    character(len=:), allocatable :: text
    integer :: k
    character(len=200), allocatable :: control(:)
    allocate (control(0))
    associate (r => deck%run)
      call results_group(o%h5, 'run', g)
      call put_r('time_step', r%time_step)
      call put_i('number_of_steps', r%number_of_steps)
      call h5_write_attr(g, 'final_time', r%final_time)       ! -1: not given
      if (r%final_time >= 0.0_wp) call put_r('final_time', r%final_time)
      call put_r('theta', r%theta)
      call put_i('detection_frequency', r%detection_frequency)
      call put_s('nlgs_check', trim(r%nlgs_check))
      call put_r('nlgs_tolerance', r%nlgs_tolerance)
      call put_r('nlgs_relaxation', r%nlgs_relaxation)
      call put_i('nlgs_sweeps_per_check', r%nlgs_sweeps_per_check)
      call put_i('nlgs_max_checks', r%nlgs_max_checks)
      call put_s('nlgs_order', trim(r%nlgs_order))
      call put_i('nlgs_seed', r%nlgs_seed)
      call put_s('nlgs_unconverged', trim(r%nlgs_unconverged))
      call put_i('output_dof_every', r%output_dof_every)
      call put_i('output_vtk_every', r%output_vtk_every)
      call put_s('output_vtk_disks', trim(r%output_vtk_disks))
      call put_s('output_vtk_precision', trim(r%output_vtk_precision))
      call put_i('output_hdf5_every', r%output_hdf5_every)
      if (r%output_restart_every >= 0) then    ! -1, not given, is no keyword value
        call put_i('output_restart_every', r%output_restart_every)
      else
        call h5_write_attr(g, 'output_restart_every', r%output_restart_every)
      end if
      call put_i('progress_every', r%progress_every)
      call put_s('driven_start', trim(r%driven_start))
      call put_s('cohesive_damage', trim(r%cohesive_damage))
      call put_r('crack_step_limit', r%crack_step_limit)
      call put_i('crack_step_cuts', r%crack_step_cuts)
      call put_s('plane', trim(r%plane))
      call put_r('newton_tolerance', r%newton_tolerance)
      call put_i('newton_max_iterations', r%newton_max_iterations)
      call put_s('linear_solver', trim(r%linear_solver))
    end associate
    text = ''
    if (allocated(deck%command_file)) text = deck%command_file
    call h5_write_attr(g, 'command_file', text)
    if (len(text) > 0) then
      ! The file as it was read (comments included), for the record.
      call load_text(deck%command_file, tf, keep_comments=.true.)
      text = ''
      do k = 1, tf%n
        text = text//tf%lines(k)%text//achar(10)
      end do
      call h5_write_attr(g, 'command_text', text)
    end if
    if (allocated(deck%settings)) then
      call h5_write_dataset(g, 'settings', deck%settings)
    else
      call h5_write_dataset(g, 'settings', [character(len=1) ::])
    end if
    ! Every setting as 'keyword value', a COMMAND.DAT the run could be repeated with.
    call h5_write_dataset(g, 'control', control)
    call h5_close_group(g)

  contains

    subroutine put_s(key, value)
      character(len=*), intent(in) :: key, value
      call h5_write_attr(g, key, value)
      control = [character(len=200) :: control, key//' '//value]
    end subroutine put_s

    subroutine put_i(key, value)
      character(len=*), intent(in) :: key
      integer, intent(in) :: value
      call h5_write_attr(g, key, value)
      control = [character(len=200) :: control, key//' '//itoa(value)]
    end subroutine put_i

    subroutine put_r(key, value)
      character(len=*), intent(in) :: key
      real(wp), intent(in) :: value
      character(len=32) :: buf
      call h5_write_attr(g, key, value)
      write (buf, '(es23.16)') value
      control = [character(len=200) :: control, key//' '//trim(adjustl(buf))]
    end subroutine put_r
  end subroutine write_run_group

  !> /contactors: the geometry of every contactor: of a rigid body in its
  !> body's frame, of a meshed body by its mesh nodes.
  subroutine write_contactors_group(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    integer(hid_t) :: g
    integer(ik), allocatable :: first(:), nvert(:), nfirst(:), nnodes(:), body(:)
    integer :: k
    associate (t => sc%tactors)
      allocate (first(t%n), nvert(t%n), nfirst(t%n), nnodes(t%n), body(t%n))
      do k = 1, t%n
        first(k) = 0
        nvert(k) = 0
        nfirst(k) = 0
        nnodes(k) = 0
        if (t%kind(k) == tk_polyg) then
          first(k) = int(t%vfirst(k) - 1, ik)
          nvert(k) = int(t%vfirst(k + 1) - t%vfirst(k), ik)
        end if
        if (t%model(k) == bm_rigid) then
          body(k) = int(sc%bodies%number(t%body(k)), ik)
        else
          body(k) = int(t%body(k), ik)      ! MAILx bodies are numbered in deck order
          nfirst(k) = int(t%nfirst(k) - 1, ik)
          nnodes(k) = int(t%nfirst(k + 1) - t%nfirst(k), ik)
        end if
      end do
      call results_group(o%h5, 'contactors', g)
      call h5_write_attr(g, 'count', int(t%n, ik))
      call h5_write_dataset(g, 'model', int(t%model(1:t%n), ik))
      call h5_write_dataset(g, 'body', body)
      call h5_write_dataset(g, 'rank', int(t%rank(1:t%n), ik))
      call h5_write_dataset(g, 'kind', int(t%kind(1:t%n), ik))
      call h5_write_dataset(g, 'kind_names', [(tactor_kind_name(k), k=tk_disk, tk_alpxx)])
      call h5_write_dataset(g, 'color', t%color(1:t%n))
      call h5_write_dataset(g, 'radius', t%radius(1:t%n))
      call h5_write_dataset(g, 'half_length', t%ax1(1:t%n))
      call h5_write_dataset(g, 'half_thickness', t%ax2(1:t%n))
      call h5_write_dataset(g, 'shift', t%shift(:, 1:t%n))
      call h5_write_dataset(g, 'vertex_first', first)
      call h5_write_dataset(g, 'vertex_count', nvert)
      if (allocated(t%vert)) then
        call h5_write_dataset(g, 'vertices', t%vert)
      else
        call h5_write_dataset(g, 'vertices', reshape([real(wp) ::], [2, 0]))
      end if
      call h5_write_dataset(g, 'node_first', nfirst)
      call h5_write_dataset(g, 'node_count', nnodes)
      if (allocated(t%nodes)) then
        call h5_write_dataset(g, 'nodes', int(t%nodes, ik))
        call h5_write_dataset(g, 'apab', t%apab(1:t%n))
      else
        call h5_write_dataset(g, 'nodes', [integer(ik) ::])
        call h5_write_dataset(g, 'apab', [real(wp) ::])
      end if
      call h5_close_group(g)
    end associate
  end subroutine write_contactors_group

  !> Take OUTBOX/fracas.lock for the run (an flock, released when the process
  !> ends however it ends): two runs never write into the same folder.
  subroutine lock_output(o, out_dir)
    type(output_t), intent(inout) :: o
    character(len=*), intent(in) :: out_dir
    integer :: stat
    o%lock = o%outbox//'/fracas.lock'
    call lock_file(o%lock, stat)
    if (stat == 2) call fatal('another run is writing into '//trim(out_dir)//' ('//o%lock//' is locked by it): '// &
      'wait for it to end, or write elsewhere with --output DIR')
    if (stat /= 0) call fatal('cannot open '//o%lock//' (is '//o%outbox//' writable?)')
  end subroutine lock_output

  !> Refuse to start where results of an earlier run lie (unless overwrite).
  subroutine refuse_earlier_results(out_dir, overwrite)
    character(len=*), intent(in) :: out_dir
    logical, intent(in) :: overwrite
    character(len=7), parameter :: dirs(3) = [character(len=7) :: 'OUTBOX', 'DISPLAY', 'POSTPRO']
    type(name_t), allocatable :: names(:)
    character(len=:), allocatable :: found, path
    integer :: d, k, nfound
    found = ''
    nfound = 0
    do d = 1, size(dirs)
      path = trim(out_dir)//'/'//trim(dirs(d))
      if (.not. dir_exists(path)) cycle
      call list_dir(path, names)
      do k = 1, size(names)
        if (.not. output_owns(trim(dirs(d)), names(k)%s)) cycle
        if (names(k)%s == 'fracas.h5.reserve') cycle   ! space held by a killed run, not a result
        nfound = nfound + 1
        if (nfound <= 3) found = found//', '//trim(dirs(d))//'/'//names(k)%s
      end do
    end do
    if (nfound > 0 .and. .not. overwrite) call fatal('results of an earlier run in '//trim(out_dir)//': '// &
      found(3:)//merge(', ...', '     ', nfound > 3)//' ('//itoa(nfound)//' files). Pass --overwrite to '// &
      'remove them all and run again, or --output DIR to write elsewhere')
  end subroutine refuse_earlier_results

  !> Remove the results of an earlier run (the caller has refused them
  !> unless overwrite) and the '.part' files of a killed run.
  subroutine clear_earlier_results(out_dir, with_vtk)
    character(len=*), intent(in) :: out_dir
    logical, intent(in) :: with_vtk
    character(len=7), parameter :: dirs(3) = [character(len=7) :: 'OUTBOX', 'DISPLAY', 'POSTPRO']
    type(name_t), allocatable :: names(:)
    character(len=:), allocatable :: path, base
    integer :: d, k
    do d = 1, size(dirs)
      path = trim(out_dir)//'/'//trim(dirs(d))
      if (.not. dir_exists(path)) cycle
      call list_dir(path, names)
      do k = 1, size(names)
        base = names(k)%s
        if (len(base) > 5) then
          if (base(len(base) - 4:) == '.part') base = base(1:len(base) - 5)
        end if
        if (output_owns(trim(dirs(d)), base)) call remove_file(path//'/'//names(k)%s)
      end do
      ! A DISPLAY left empty by the clearing, in a run without VTK, goes too.
      if (dirs(d) == 'DISPLAY' .and. .not. with_vtk) then
        call list_dir(path, names)
        if (size(names) == 0) call remove_file(path)
      end if
    end do
  end subroutine clear_earlier_results

  !> True for NAME in folder DIR (OUTBOX, DISPLAY or POSTPRO) when it is a
  !> file a Fracas run writes there: fracas.h5, DOF.OUT.n, Vloc_Rloc.OUT.n,
  !> GPV.OUT.n; fracas.pvd and PIECE_NNNNNN.vtu (PIECE: lower-case letters);
  !> the POSTPRO files of fracas_postpro.
  logical function output_owns(dir, name)
    character(len=*), intent(in) :: dir, name
    integer :: u, v
    output_owns = .false.
    select case (dir)
    case ('OUTBOX')
      output_owns = name == 'fracas.h5' .or. name == 'fracas.h5.reserve' .or. counted(name, 'DOF.OUT.') .or. &
                    counted(name, 'Vloc_Rloc.OUT.') .or. counted(name, 'GPV.OUT.')
    case ('DISPLAY')
      if (name == 'fracas.pvd') then
        output_owns = .true.
      else if (len(name) > 11) then
        u = index(name, '_', back=.true.)
        v = len(name) - 3
        if (u > 1 .and. name(v:) == '.vtu') output_owns = verify(name(1:u - 1), 'abcdefghijklmnopqrstuvwxyz') == 0 &
          .and. v - u - 1 >= 6 .and. verify(name(u + 1:v - 1), '0123456789') == 0
      end if
    case ('POSTPRO')
      output_owns = postpro_owns(name)
    end select

  contains

    logical function counted(s, prefix)
      character(len=*), intent(in) :: s, prefix
      counted = .false.
      if (len(s) <= len(prefix)) return
      counted = s(1:len(prefix)) == prefix .and. verify(s(len(prefix) + 1:), '0123456789') == 0
    end function counted
  end function output_owns

  !> One DISPLAY frame, listed in DISPLAY/fracas.pvd at the scene time:
  !>   disks_NNNNNN.vtu     one vertex per disk at its centre with its radius
  !>                        (point data: draw as Point Gaussian or glyphs)
  !>   shapes_NNNNNN.vtu    polygons and walls as filled polygons, drums as
  !>                        circles (and disks, as filled polygons, when
  !>                        output_vtk_disks = polygons)
  !>   contacts_NNNNNN.vtu  one vertex per contact at its point
  !> Pieces the scene does not have are not written; each piece keeps its
  !> part number in the .pvd for the whole run.
  subroutine output_vtk(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    character(len=6) :: num
    real(wp) :: t0
    call cpu_time(t0)
    o%n_vtk = o%n_vtk + 1
    write (num, '(i6.6)') o%n_vtk
    if (o%part_disks >= 0) then
      call write_disks_vtu(o%display//'/disks_'//num//'.vtu', sc, o%vtk_single)
      call pvd_add(o%pvd, sc%time, 'disks_'//num//'.vtu', part=o%part_disks)
    end if
    if (o%part_shapes >= 0) then
      call write_shapes_vtu(o%display//'/shapes_'//num//'.vtu', sc, o%disk_points, o%vtk_single)
      call pvd_add(o%pvd, sc%time, 'shapes_'//num//'.vtu', part=o%part_shapes)
    end if
    if (o%part_meshes >= 0) then
      call write_meshes_vtu(o%display//'/meshes_'//num//'.vtu', sc, o%vtk_single, o%material_names)
      call pvd_add(o%pvd, sc%time, 'meshes_'//num//'.vtu', part=o%part_meshes)
    end if
    if (o%part_interfaces >= 0) then
      call write_interfaces_vtu(o%display//'/interfaces_'//num//'.vtu', sc, o%vtk_single)
      call pvd_add(o%pvd, sc%time, 'interfaces_'//num//'.vtu', part=o%part_interfaces)
      call write_cracks_vtu(o%display//'/cracks_'//num//'.vtu', sc, o%vtk_single)
      call pvd_add(o%pvd, sc%time, 'cracks_'//num//'.vtu', part=o%part_cracks)
    end if
    call write_contacts_vtu(o%display//'/contacts_'//num//'.vtu', sc, o%vtk_single)
    call pvd_add(o%pvd, sc%time, 'contacts_'//num//'.vtu', part=o%part_contacts)
    call clocked(o, k_vtk, t0)
  end subroutine output_vtk

  !> Add the CPU time since t0 (from cpu_time) to kind k.
  subroutine clocked(o, k, t0)
    type(output_t), intent(inout) :: o
    integer, intent(in) :: k
    real(wp), intent(in) :: t0
    real(wp) :: t1
    call cpu_time(t1)
    o%seconds(k) = o%seconds(k) + (t1 - t0)
    o%writes(k) = o%writes(k) + 1
  end subroutine clocked

  !> One line on what the output cost: for each kind written, the writes and
  !> the CPU time spent (e.g. for a progress report at the end of a run).
  function output_summary(o) result(s)
    type(output_t), intent(in) :: o
    character(len=:), allocatable :: s
    character(len=*), parameter :: what(4) = [character(len=15) :: 'VTK frames', 'HDF5 snapshots', &
                                              'DOF/Vloc files', 'series rows']
    character(len=64) :: buf
    integer :: k
    s = ''
    do k = 1, 4
      if (o%writes(k) == 0) cycle
      write (buf, '(i0,1x,a,1x,f0.3,a,f0.3,a)') o%writes(k), trim(what(k)), o%seconds(k), ' s CPU (', &
        1.0e3_wp * o%seconds(k) / o%writes(k), ' ms each)'
      if (len(s) > 0) s = s//', '
      s = s//trim(buf)
    end do
  end function output_summary

  !> Meshed bodies as an unstructured grid in the current configuration:
  !> point data displacement and velocity; cell data (Gauss-point averages)
  !> stress tensor (xx, yy, zz, xy as a symmetric 3x3), von Mises stress,
  !> equivalent plastic strain, material, body; field data material_names
  !> (the bulk behaviour of material k is entry k).
  subroutine write_meshes_vtu(path, sc, single, material_names)
    character(len=*), intent(in) :: path
    type(scene_t), intent(in) :: sc
    logical, intent(in) :: single
    character(len=*), intent(in) :: material_names(:)
    type(vtu_t) :: w
    real(wp), allocatable :: gp(:, :), stress(:, :), vm(:), p(:), avg(:)
    integer(ik), allocatable :: conn(:), offs(:), types(:), body(:), mat(:)
    integer, allocatable :: piece(:)
    integer :: e, b, ng, nn, nfrag
    associate (m => sc%meshes)
      allocate (gp(size(m%gp, 1), size(m%gp, 2)))
      call mailx_gauss_values(m, gp)
      allocate (conn(size(m%el_nodes)), offs(m%nelem), types(m%nelem), body(m%nelem), mat(m%nelem), &
                stress(6, m%nelem), vm(m%nelem), p(m%nelem))
      do b = 1, m%n
        do e = m%elem_first(b), m%elem_first(b + 1) - 1
          nn = m%el_first(e + 1) - m%el_first(e)
          ! VTK node order of the element, 0-based points
          conn(m%el_first(e):m%el_first(e + 1) - 1) = &
            int(m%el_nodes(m%el_first(e) - 1 + el_vtk_order(m%el_kind(e))) - 1, ik)
          offs(e) = int(m%el_first(e + 1) - 1, ik)
          types(e) = int(el_vtk_type(m%el_kind(e)), ik)
          body(e) = int(b, ik)
          mat(e) = int(m%el_mat(e), ik)
          ng = m%el_gp(e + 1) - m%el_gp(e)
          avg = sum(gp(:, m%el_gp(e):m%el_gp(e + 1) - 1), dim=2) / ng
          ! symmetric tensor as ParaView reads it: xx, yy, zz, xy, yz, xz
          stress(:, e) = [avg(gp_sxx), avg(gp_sxx + 1), avg(gp_szz), avg(gp_sxx + 2), 0.0_wp, 0.0_wp]
          vm(e) = von_mises(avg(gp_sxx:gp_szz))
          p(e) = avg(gp_p)
        end do
      end do
      call vtu_begin(w, path, m%nnodes, m%nelem, time=sc%time, single=single)
      call vtu_field_strings(w, 'material_names', material_names)
      call vtu_points(w, m%ref + m%x)
      call vtu_cells(w, conn, offs, types)
      ! 3 components (z = 0): ParaView's Warp By Vector and glyphs need them.
      call vtu_point_data(w, 'displacement', xyz(m%x))
      call vtu_point_data(w, 'velocity', xyz(m%v))
      call vtu_cell_data(w, 'stress', stress)
      call vtu_cell_data(w, 'von_mises', vm)
      call vtu_cell_data(w, 'plastic_strain', p)
      call vtu_cell_data(w, 'material', mat)
      call vtu_cell_data(w, 'body', body)
      if (sc%cracks%nedges > 0) then        ! fragment of each element (1 .. fragments)
        call cracks_fragments(sc%cracks, sc%meshes, piece, nfrag)
        call vtu_cell_data(w, 'fragment', int(piece(body), ik))
      end if
      call vtu_end(w)
    end associate
  end subroutine write_meshes_vtu

  !> Cohesive interfaces as lines (the candidate edge, current configuration)
  !> with cell data beta (the lowest of its points), broken (1/0), damaged and
  !> family (index in /mesh interface_families; field data family_names
  !> names family k as entry k).
  subroutine write_interfaces_vtu(path, sc, single)
    character(len=*), intent(in) :: path
    type(scene_t), intent(in) :: sc
    logical, intent(in) :: single
    type(vtu_t) :: w
    real(wp), allocatable :: pts(:, :), beta(:)
    integer(ik), allocatable :: nodes(:, :), broken(:), damaged(:), family(:)
    integer :: e, j, ne
    associate (cr => sc%cracks, m => sc%meshes)
      ne = cr%nedges
      allocate (pts(2, 2 * ne), nodes(2, ne), broken(ne), damaged(ne), family(ne))
      beta = cracks_edge_beta(cr)
      do e = 1, ne
        do j = 1, 2
          pts(:, 2 * e - 2 + j) = m%ref(:, cr%edge_nodes(j, e)) + m%x(:, cr%edge_nodes(j, e))
        end do
        nodes(:, e) = [int(2 * e - 2, ik), int(2 * e - 1, ik)]
        broken(e) = merge(1_ik, 0_ik, cr%edge_broken_step(e) > 0)
        damaged(e) = merge(1_ik, 0_ik, beta(e) < 1.0_wp)
        family(e) = int(cr%edge_family(e), ik)
      end do
      call vtu_begin(w, path, 2 * ne, ne, time=sc%time, single=single)
      call vtu_field_strings(w, 'family_names', cr%family_names)
      call vtu_points(w, pts)
      call vtu_cells_fixed(w, nodes, vtk_line)
      call vtu_cell_data(w, 'beta', beta)
      call vtu_cell_data(w, 'broken', broken)
      call vtu_cell_data(w, 'damaged', damaged)
      call vtu_cell_data(w, 'family', family)
      call vtu_end(w)
    end associate
  end subroutine write_interfaces_vtu

  !> Crack paths: the broken edges joined into cracks, as lines with the
  !> crack number (1 = longest) and its length as cell data.
  subroutine write_cracks_vtu(path, sc, single)
    character(len=*), intent(in) :: path
    type(scene_t), intent(in) :: sc
    logical, intent(in) :: single
    type(vtu_t) :: w
    type(crack_paths_t) :: paths
    integer :: ns
    call cracks_paths(sc%cracks, sc%meshes, paths)
    ns = size(paths%seg, 2)
    call vtu_begin(w, path, size(paths%points, 2), ns, time=sc%time, single=single)
    call vtu_points(w, paths%points)
    call vtu_cells_fixed(w, int(paths%seg - 1, ik), vtk_line)
    call vtu_cell_data(w, 'crack', int(paths%seg_crack, ik))
    if (ns > 0) then
      call vtu_cell_data(w, 'crack_length', paths%crack_length(paths%seg_crack))
    else
      call vtu_cell_data(w, 'crack_length', [real(wp) ::])
    end if
    call vtu_end(w)
  end subroutine write_cracks_vtu

  !> Disks as points with their radius (and body state as point data).
  subroutine write_disks_vtu(path, sc, single)
    character(len=*), intent(in) :: path
    type(scene_t), intent(in) :: sc
    logical, intent(in) :: single
    type(vtu_t) :: w
    real(wp), allocatable :: pts(:, :), vel(:, :), ori(:, :), radius(:), rot(:), spin(:)
    integer(ik), allocatable :: body(:)
    real(wp) :: q(3)
    integer :: k, n, ib
    n = count(sc%tactors%kind(1:sc%tactors%n) == tk_disk)
    allocate (pts(2, n), vel(3, n), ori(3, n), radius(n), rot(n), spin(n), body(n))
    n = 0
    associate (t => sc%tactors, b => sc%bodies)
      do k = 1, t%n
        if (t%kind(k) /= tk_disk) cycle
        n = n + 1
        ib = t%body(k)
        q = b%ref(:, ib) + b%x(:, ib)
        pts(:, n) = tactor_center(t, k, q)
        radius(n) = t%radius(k)
        vel(:, n) = [b%v(1, ib), b%v(2, ib), 0.0_wp]
        ori(:, n) = [cos(q(3)), sin(q(3)), 0.0_wp]
        rot(n) = b%x(3, ib)
        spin(n) = b%v(3, ib)
        body(n) = int(b%number(ib), ik)
      end do
    end associate
    call vtu_begin(w, path, n, n, time=sc%time, single=single)
    call vtu_points(w, pts)
    call vtu_vertex_cells(w)
    call vtu_point_data(w, 'radius', radius)
    call vtu_point_data(w, 'body', body)
    call vtu_point_data(w, 'velocity', vel)
    call vtu_point_data(w, 'rotation', rot)
    call vtu_point_data(w, 'spin', spin)
    call vtu_point_data(w, 'orientation', ori)
    call vtu_end(w)
  end subroutine write_disks_vtu

  !> Every contactor that is not a disk drawn as a point (all of them when
  !> disks are drawn as polygons): one cell each, filled polygons (POLYG,
  !> JONCx, disks) or closed poly-lines (xKSID, whose inside is empty).
  subroutine write_shapes_vtu(path, sc, disk_points, single)
    character(len=*), intent(in) :: path
    type(scene_t), intent(in) :: sc
    logical, intent(in) :: disk_points, single
    type(vtu_t) :: w
    real(wp), allocatable :: pts(:, :), vel(:, :), outline(:, :), rot(:), spin(:)
    integer(ik), allocatable :: conn(:), offs(:), types(:), body(:), kind(:)
    integer :: k, j, np, nc, m, ib
    associate (t => sc%tactors, b => sc%bodies)
      np = 0
      nc = 0
      do k = 1, t%n
        if (.not. is_shape(k)) cycle
        nc = nc + 1
        select case (t%kind(k))
        case (tk_polyg)
          np = np + t%vfirst(k + 1) - t%vfirst(k)
        case (tk_xksid)
          np = np + n_outline + 1
        case default
          np = np + n_outline
        end select
      end do
      allocate (pts(2, np), conn(np), offs(nc), types(nc), body(nc), kind(nc), vel(3, nc), rot(nc), spin(nc))
      np = 0
      nc = 0
      do k = 1, t%n
        if (.not. is_shape(k)) cycle
        nc = nc + 1
        ib = t%body(k)
        outline = tactor_outline(sc, k)
        m = size(outline, 2)
        pts(:, np + 1:np + m) = outline
        conn(np + 1:np + m) = [(int(np + j, ik), j=0, m - 1)]
        np = np + m
        offs(nc) = int(np, ik)
        types(nc) = merge(vtk_poly_line, vtk_polygon, t%kind(k) == tk_xksid)
        body(nc) = int(b%number(ib), ik)
        kind(nc) = int(t%kind(k), ik)
        vel(:, nc) = [b%v(1, ib), b%v(2, ib), 0.0_wp]
        rot(nc) = b%x(3, ib)
        spin(nc) = b%v(3, ib)
      end do
    end associate
    call vtu_begin(w, path, np, nc, time=sc%time, single=single)
    call vtu_points(w, pts)
    call vtu_cells(w, conn, offs, types)
    call vtu_cell_data(w, 'body', body)
    call vtu_cell_data(w, 'contactor_kind', kind)
    call vtu_cell_data(w, 'velocity', vel)
    call vtu_cell_data(w, 'rotation', rot)
    call vtu_cell_data(w, 'spin', spin)
    call vtu_end(w)

  contains

    logical function is_shape(k)
      integer, intent(in) :: k
      ! Contactors of meshed bodies are drawn with their mesh (meshes piece).
      is_shape = sc%tactors%model(k) == bm_rigid .and. (sc%tactors%kind(k) /= tk_disk .or. .not. disk_points)
    end function is_shape
  end subroutine write_shapes_vtu

  !> Outline of contactor k in the current configuration: the vertices of a
  !> polygon, n_outline points around a disk or a wall (stadium), a closed
  !> circle of n_outline + 1 points for a drum.
  function tactor_outline(sc, k) result(p)
    type(scene_t), intent(in) :: sc
    integer, intent(in) :: k
    real(wp), allocatable :: p(:, :)
    real(wp) :: q(3), c(2), s
    integer :: j
    associate (t => sc%tactors, b => sc%bodies)
      q = b%ref(:, t%body(k)) + b%x(:, t%body(k))
      c = tactor_center(t, k, q)
      select case (t%kind(k))
      case (tk_polyg)
        p = tactor_vertices(t, k, q)
      case (tk_jonc)
        allocate (p(2, n_outline))
        do j = 0, n_outline - 1
          s = 2.0_wp * acos(-1.0_wp) * j / n_outline
          p(:, j + 1) = c + stadium_point(t%ax1(k), t%ax2(k), q(3), s)
        end do
      case (tk_xksid)
        allocate (p(2, n_outline + 1))
        do j = 0, n_outline
          s = q(3) + 2.0_wp * acos(-1.0_wp) * j / n_outline
          p(:, j + 1) = c + t%radius(k) * [cos(s), sin(s)]
        end do
      case default
        allocate (p(2, n_outline))
        do j = 0, n_outline - 1
          s = q(3) + 2.0_wp * acos(-1.0_wp) * j / n_outline
          p(:, j + 1) = c + t%radius(k) * [cos(s), sin(s)]
        end do
      end select
    end associate
  end function tactor_outline

  !> Point of a stadium outline (half length a1, half thickness a2, axis angle
  !> phi) in the direction of parameter s around it.
  pure function stadium_point(a1, a2, phi, s) result(p)
    real(wp), intent(in) :: a1, a2, phi, s
    real(wp) :: p(2), lx, ly
    lx = a2 * cos(s) + sign(a1, cos(s))
    ly = a2 * sin(s)
    p = [lx * cos(phi) - ly * sin(phi), lx * sin(phi) + ly * cos(phi)]
  end function stadium_point

  !> Contacts as points (point data, for glyphs of the reaction or normal).
  subroutine write_contacts_vtu(path, sc, single)
    character(len=*), intent(in) :: path
    type(scene_t), intent(in) :: sc
    logical, intent(in) :: single
    type(vtu_t) :: w
    real(wp), allocatable :: pts(:, :), nrm(:, :), reac(:, :), rn(:), rt(:), gap(:), beta(:)
    integer(ik), allocatable :: status(:), inter(:), law(:), cdb(:), anb(:)
    integer :: k, n, j, nd
    logical :: czm
    n = sc%contacts%n
    nd = sc%contacts%nd
    czm = any(sc%laws%kind == law_czm)
    allocate (pts(nd, n), nrm(3, n), reac(3, n), rn(n), rt(n), gap(n), beta(n), status(n), inter(n), law(n), cdb(n), &
              anb(n))
    associate (c => sc%contacts)
      do k = 1, n
        pts(:, k) = c%point(:, k)
        nrm(:, k) = 0.0_wp
        nrm(1:nd, k) = c%frame(:, nd, k)
        rt(k) = c%r(1, k) / sc%h         ! (3D: along t1)
        rn(k) = c%r(nd, k) / sc%h
        ! the reaction in global axes: frame times the local reaction
        reac(:, k) = 0.0_wp
        reac(1:nd, k) = c%frame(:, 1, k) * rt(k)
        do j = 2, nd
          reac(1:nd, k) = reac(1:nd, k) + c%frame(:, j, k) * (c%r(j, k) / sc%h)
        end do
        gap(k) = c%gap(k) + sc%h * c%u(nd, k)
        beta(k) = 0.0_wp
        if (sc%laws(c%law(k))%kind == law_czm) beta(k) = c%internals(int_beta(nd), k)
        status(k) = int(c%status(k), ik)
        inter(k) = int(c%inter(k), ik)
        law(k) = int(c%law(k), ik)
        cdb(k) = int(c%cdb(k), ik)     ! body number within its model (cd_model, an_model)
        anb(k) = int(c%anb(k), ik)
      end do
    end associate
    call vtu_begin(w, path, n, n, time=sc%time, single=single)
    call vtu_points(w, pts)
    call vtu_vertex_cells(w)
    call vtu_point_data(w, 'normal', nrm)
    call vtu_point_data(w, 'reaction', reac)
    call vtu_point_data(w, 'rn', rn)
    call vtu_point_data(w, 'rt', rt)
    call vtu_point_data(w, 'gap', gap)
    call vtu_point_data(w, 'status', status)
    call vtu_point_data(w, 'inter', inter)
    call vtu_point_data(w, 'law', law)
    call vtu_point_data(w, 'cd_body', cdb)
    call vtu_point_data(w, 'an_body', anb)
    if (sc%meshes%n > 0) then
      call vtu_point_data(w, 'cd_model', int(sc%contacts%cdm(1:n), ik))
      call vtu_point_data(w, 'an_model', int(sc%contacts%anm(1:n), ik))
    end if
    if (czm) then
      call vtu_point_data(w, 'beta', beta)
      call vtu_point_data(w, 'broken', broken_flags(sc))
    end if
    call vtu_end(w)
  end subroutine write_contacts_vtu

  !> OUTBOX/DOF.OUT.n and OUTBOX/Vloc_Rloc.OUT.n (n counts the writes).
  subroutine output_outbox(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    type(dof_record_t), allocatable :: dofs(:)
    type(contact_record_t), allocatable :: recs(:)
    character(len=16) :: num
    integer :: k, it, m, pos
    integer :: per_type(n_inter)
    real(wp) :: t0
    call cpu_time(t0)
    o%n_out = o%n_out + 1
    write (num, '(i0)') o%n_out
    ! Each body model's records, rigid first (LMGC90's order).
    dofs = [rbdy2_dof_records(sc%bodies), mailx_dof_records(sc%meshes)]
    call write_dof_file(o%outbox//'/DOF.OUT.'//trim(num), sc%step, sc%time, dofs)
    if (sc%meshes%n > 0) call write_gpv_file(o%outbox//'/GPV.OUT.'//trim(num), sc%step, sc%time, gpv_records(sc))
    ! LMGC90 lists interactions type by type, numbered within their type.
    if (sc%contacts%nd /= 2) call fatal('Vloc_Rloc.OUT: only 2D records are written')
    allocate (recs(sc%contacts%n))
    per_type = 0
    m = 0
    associate (c => sc%contacts, t => sc%tactors)
      do it = 1, n_inter
        do k = 1, c%n
          if (c%inter(k) /= it) cycle
          m = m + 1
          per_type(it) = per_type(it) + 1
          pos = m
          recs(pos)%inter = inter_names(it)
          recs(pos)%number = per_type(it)
          recs(pos)%cdtac = tactor_kind_name(t%kind(c%cd(k)))
          recs(pos)%antac = tactor_kind_name(t%kind(c%an(k)))
          recs(pos)%cdver = c%cdver(k)
          recs(pos)%anseg = c%anseg(k)
          recs(pos)%cdbdy = merge('MAILx', 'RBDY2', c%cdm(k) == bm_mesh)
          recs(pos)%anbdy = merge('MAILx', 'RBDY2', c%anm(k) == bm_mesh)
          recs(pos)%icdbdy = c%cdb(k)
          recs(pos)%ianbdy = c%anb(k)
          if (c%cdm(k) == bm_rigid) recs(pos)%icdbdy = sc%bodies%number(c%cdb(k))
          if (c%anm(k) == bm_rigid) recs(pos)%ianbdy = sc%bodies%number(c%anb(k))
          recs(pos)%icdtac = t%rank(c%cd(k))
          recs(pos)%iantac = t%rank(c%an(k))
          recs(pos)%behav = sc%laws(c%law(k))%nickname
          recs(pos)%status = status_names(c%status(k))
          recs(pos)%iadj = t%kind_index(c%an(k))
          recs(pos)%rlt = c%r(1, k) / sc%h
          recs(pos)%rln = c%r(2, k) / sc%h
          recs(pos)%vlt = c%u(1, k)
          recs(pos)%vln = c%u(2, k)
          recs(pos)%gap = c%gap(k) + sc%h * c%u(2, k)
          recs(pos)%normal = c%frame(:, 2, k)
          recs(pos)%coor = c%point(:, k)
          recs(pos)%has_geometry = .true.
          if (sc%laws(c%law(k))%kind == law_czm) then
            recs(pos)%internals = c%internals(:, k)
          else if (sc%laws(c%law(k))%kind == law_iqs_clb_g0) then
            recs(pos)%internals = c%internals(1:1, k)
            recs(pos)%internal_name = 'g_ref'
          else if (c%cdm(k) == bm_mesh .or. c%anm(k) == bm_mesh) then
            recs(pos)%internals = [c%length(k)]   ! LMGC90 writes the length of contacts with meshes
          else
            allocate (recs(pos)%internals(0))
          end if
        end do
      end do
    end associate
    call write_vloc_rloc_file(o%outbox//'/Vloc_Rloc.OUT.'//trim(num), sc%step, sc%time, recs)
    call clocked(o, k_outbox, t0)
  end subroutine output_outbox

  !> Gauss-point values of every element as LMGC90 writes them in GPV.OUT:
  !> small strain, per Gauss point the stress (xx, yy, xy, zz) and the strain
  !> (xx, yy, 2 xy, zz); J2 elements add a line of six internals, the
  !> small-strain counterpart of LMGC90's (plastic strain xx, yy, 2 xy, zz
  !> where LMGC90 writes Cp^-1, then p and the von Mises stress). T3 has one
  !> Gauss point, printed three times as LMGC90 does.
  function gpv_records(sc) result(recs)
    type(scene_t), intent(in) :: sc
    type(gpv_record_t), allocatable :: recs(:)
    real(wp), allocatable :: gp(:, :)
    integer :: b, e, g, ng, np, g0, law
    real(wp) :: cp_shift(4), jac
    associate (ms => sc%meshes)
    allocate (gp(size(ms%gp, 1), size(ms%gp, 2)))
    call mailx_gauss_values(ms, gp)
    allocate (recs(ms%nelem))
    do b = 1, ms%n
      do e = ms%elem_first(b), ms%elem_first(b + 1) - 1
        associate (r => recs(e))
          r%body = b
          r%element = e - ms%elem_first(b) + 1
          r%kind = el_name(ms%el_kind(e))
          ng = ms%el_gp(e + 1) - ms%el_gp(e)
          np = el_ngauss_gpv(ms%el_kind(e))
          law = ms%mats(ms%el_bulk(e))%law
          allocate (r%values(merge(14, 8, law == bulk_j2 .or. law == bulk_j2_finite), np))
          ! finite-strain J2 keeps Cp^-1 - I: LMGC90 writes Cp^-1
          cp_shift = 0.0_wp
          if (law == bulk_j2_finite) cp_shift = [1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp]
          do g = 1, np
            g0 = ms%el_gp(e) + min(g, ng) - 1
            r%values(1:8, g) = gp(gp_sxx:gp_ezz, g0)
            ! finite-strain J2: LMGC90 prints the Kirchhoff von Mises stress, J times
            ! the Cauchy one (J from the Green-Lagrange strain: J^2 = det C)
            jac = 1.0_wp
            if (law == bulk_j2_finite) jac = sqrt(((1.0_wp + 2.0_wp * gp(gp_exx, g0)) * &
              (1.0_wp + 2.0_wp * gp(gp_eyy, g0)) - gp(gp_gxy, g0)**2) * (1.0_wp + 2.0_wp * gp(gp_ezz, g0)))
            if (size(r%values, 1) == 14) r%values(9:14, g) = [gp(gp_pxx:gp_pzz, g0) + cp_shift, gp(gp_p, g0), &
                                                              jac * von_mises(gp(gp_sxx:gp_szz, g0))]
          end do
        end associate
      end do
    end do
    end associate
  end function gpv_records

  !> 2-D vectors (2, n) as 3-D ones (3, n) with z = 0.
  pure function xyz(v) result(r)
    real(wp), intent(in) :: v(:, :)
    real(wp) :: r(3, size(v, 2))
    r(1:2, :) = v
    r(3, :) = 0.0_wp
  end function xyz

  !> Von Mises equivalent stress of a stress (xx, yy, xy, zz).
  pure real(wp) function von_mises(s)
    real(wp), intent(in) :: s(4)
    von_mises = sqrt(0.5_wp * ((s(1) - s(2))**2 + (s(2) - s(4))**2 + (s(4) - s(1))**2) + 3.0_wp * s(3)**2)
  end function von_mises

  !> One snapshot of bodies and contacts in OUTBOX/fracas.h5.
  subroutine output_snapshot(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    integer :: n
    real(wp), allocatable :: gap_end(:)
    real(wp) :: t0
    if (.not. o%h5_open) return
    call cpu_time(t0)
    n = sc%contacts%n
    associate (c => sc%contacts, t => sc%tactors)
      gap_end = c%gap(1:n) + sc%h * c%u(c%nd, 1:n)
      if (any(sc%laws%kind == law_czm)) then
        call results_write_snapshot(o%h5, sc%step, sc%time, sc%bodies%x, sc%bodies%v, c%inter(1:n), &
          c%cdb(1:n), c%anb(1:n), t%rank(c%cd(1:n)), t%rank(c%an(1:n)), &
          c%status(1:n), c%law(1:n), c%frame(:, c%nd, 1:n), c%point(:, 1:n), c%r(:, 1:n) / sc%h, c%u(:, 1:n), gap_end, &
          internals=c%internals(:, 1:n), broken=broken_flags(sc))
      else
        call results_write_snapshot(o%h5, sc%step, sc%time, sc%bodies%x, sc%bodies%v, c%inter(1:n), &
          c%cdb(1:n), c%anb(1:n), t%rank(c%cd(1:n)), t%rank(c%an(1:n)), &
          c%status(1:n), c%law(1:n), c%frame(:, c%nd, 1:n), c%point(:, 1:n), c%r(:, 1:n) / sc%h, c%u(:, 1:n), gap_end)
      end if
    end associate
    if (sc%meshes%n > 0) call mesh_snapshot(o, sc)
    if (sc%cracks%nedges > 0) call cracks_snapshot(o, sc)
    call clocked(o, k_snapshot, t0)
  end subroutine output_snapshot

  !> Cracks in the newest snapshot (group cracks): the crack paths (vertices
  !> in the current configuration, segments, crack of each segment, length of
  !> each crack, longest first), the main crack's origin and tip (reference
  !> configuration), broken length per interface family (names in
  !> /mesh/interface_families), and the fragments (fragment of each meshed body).
  subroutine cracks_snapshot(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    integer(hid_t) :: g, gc
    type(crack_paths_t) :: paths
    real(wp) :: crack, damaged, per_family(sc%cracks%nfamilies)
    integer :: nbroken, ndamaged, nfrag
    integer, allocatable :: piece(:)
    call cracks_paths(sc%cracks, sc%meshes, paths)
    call cracks_lengths(sc%cracks, crack, damaged, per_family, nbroken, ndamaged)
    call cracks_fragments(sc%cracks, sc%meshes, piece, nfrag)
    call results_last_snapshot(o%h5, g)
    call h5_create_group(g, 'cracks', gc)
    call h5_write_dataset(gc, 'points', paths%points)
    call h5_write_dataset(gc, 'segments', int(paths%seg, ik))
    call h5_write_dataset(gc, 'segment_crack', int(paths%seg_crack, ik))
    call h5_write_dataset(gc, 'crack_length', paths%crack_length)
    call h5_write_dataset(gc, 'main_origin', paths%origin)
    call h5_write_dataset(gc, 'main_tip', paths%tip)
    call h5_write_dataset(gc, 'broken_length_per_family', per_family)
    call h5_write_dataset(gc, 'damage_per_family', sc%cracks%family_damage)
    call h5_write_dataset(gc, 'edge_broken_step', int(sc%cracks%edge_broken_step, ik))
    call h5_write_dataset(gc, 'edge_beta', cracks_edge_beta(sc%cracks))
    call h5_write_dataset(gc, 'fragment_of_body', int(piece, ik))
    call h5_write_attr(gc, 'fragments', nfrag)
    call fragments_group(gc, sc, piece, nfrag)
    call h5_close_group(gc)
    call h5_close_group(g)
  end subroutine cracks_snapshot

  !> Group fragments under the cracks of a snapshot: per fragment (fracas_cracks
  !> cracks_fragment_stats) its bodies, elements, mass, centre, velocity, kinetic
  !> energy, second moments, polar and principal moments, major-axis angle.
  subroutine fragments_group(gc, sc, piece, nfrag)
    integer(hid_t), intent(in) :: gc
    type(scene_t), intent(in) :: sc
    integer, intent(in) :: piece(:), nfrag
    type(fragments_t) :: f
    integer(hid_t) :: g
    call cracks_fragment_stats(sc%meshes, piece, nfrag, f)
    call h5_create_group(gc, 'fragments', g)
    call h5_write_attr(g, 'count', nfrag)
    call h5_write_dataset(g, 'bodies', int(f%bodies, ik))
    call h5_write_dataset(g, 'elements', int(f%elements, ik))
    call h5_write_dataset(g, 'mass', f%mass)
    call h5_write_dataset(g, 'centre', f%centre)
    call h5_write_dataset(g, 'velocity', f%velocity)
    call h5_write_dataset(g, 'kinetic_energy', f%kinetic)
    call h5_write_dataset(g, 'second_moments', f%moments)
    call h5_write_dataset(g, 'polar_moment', f%polar)
    call h5_write_dataset(g, 'principal_moments', f%principal)
    call h5_write_dataset(g, 'principal_angle', f%angle)
    call h5_close_group(g)
  end subroutine fragments_group

  !> The meshed bodies' state in the newest snapshot (mailx_write_snapshot), and
  !> the side models of the contacts.
  subroutine mesh_snapshot(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    integer(hid_t) :: g
    call results_last_snapshot(o%h5, g)
    call mailx_write_snapshot(sc%meshes, g)
    call h5_write_dataset(g, 'cd_model', int(sc%contacts%cdm(1:sc%contacts%n), ik))
    call h5_write_dataset(g, 'an_model', int(sc%contacts%anm(1:sc%contacts%n), ik))
    call h5_close_group(g)
  end subroutine mesh_snapshot

  !> Names separated by blanks.
  pure function join(names) result(s)
    character(len=*), intent(in) :: names(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    do i = 1, size(names)
      s = s//trim(names(i))
      if (i < size(names)) s = s//' '
    end do
  end function join

  !> The meshes' fixed description in /mesh (mailx_write_static) and their
  !> cohesive interfaces (families, edges).
  subroutine mesh_static(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    integer(hid_t) :: g
    associate (m => sc%meshes)
      call results_group(o%h5, 'mesh', g)
      call mailx_write_static(m, g)
      if (sc%cracks%nfamilies > 0) call h5_write_attr(g, 'interface_families', join(sc%cracks%family_names))
      if (sc%cracks%nedges > 0) then
        call h5_write_dataset(g, 'interface_edge_nodes', int(sc%cracks%edge_nodes, ik))
        call h5_write_dataset(g, 'interface_edge_family', int(sc%cracks%edge_family, ik))
        call h5_write_dataset(g, 'interface_edge_length', sc%cracks%edge_length)
      end if
      call h5_close_group(g)
    end associate
  end subroutine mesh_static

  !> One row of the per-step series (same order as series_names).
  subroutine output_series(o, sc, rep)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    type(step_report_t), intent(in) :: rep
    real(wp) :: balance, wgrav, wforces, wsupports, crack, damaged
    type(energy_terms_t) :: e
    real(wp) :: per_family(sc%cracks%nfamilies)
    integer :: nbroken, ndamaged
    real(wp) :: t0
    real(wp) :: row(n_series)
    integer :: k
    if (.not. o%h5_open) return
    call cpu_time(t0)
    call cracks_lengths(sc%cracks, crack, damaged, per_family, nbroken, ndamaged)
    ! Every body model's terms together (kinetic0 holds the initial kinetic and
    ! elastic energy; meshes add their strain energy and plastic work).
    e = scene_energy_terms(sc)
    wgrav = e%work_gravity
    wforces = e%work_forces
    wsupports = e%work_supports
    balance = rep%kinetic + e%elastic + e%plastic + sc%cohesive_energy - sc%kinetic0 - &
              (wgrav + wforces + wsupports - sc%dissipated)
    row = [real(sc%step, wp), sc%time, real(rep%contacts, wp), &
      real(rep%nlgs%nactive, wp), real(rep%nlgs%sweeps, wp), merge(1.0_wp, 0.0_wp, rep%nlgs%converged .and. rep%newton_converged), &
      rep%nlgs%residual, rep%nlgs%residual_onepq, rep%nlgs%quad_dv, rep%nlgs%maxm_dv, rep%nlgs%mean_dvor, &
      rep%kinetic, wgrav, wforces, wsupports, sc%dissipated, sc%cohesive_energy, &
      sc%damage_dissipated, balance, &
      rep%mean_overlap, rep%max_overlap, rep%solve_seconds, rep%step_seconds, e%elastic, &
      e%plastic, real(rep%newton_iterations, wp), crack, damaged, real(nbroken, wp), &
      real(ndamaged, wp), rep%bodies_seconds, rep%detect_seconds, rep%prepare_seconds, &
      real(rep%nlgs%updates, wp), rep%velocity_seconds, real(fragment_count(sc), wp), real(rep%substeps, wp), &
      real(rep%rejected, wp), rep%crack_increment]
    ! A sound state can still give non-finite diagnostics (an NLGS residual of a
    ! law stiffness near the largest double): the step's results are nonsense.
    do k = 1, n_series
      if (.not. ieee_is_finite(row(k))) call fatal('the series value '//trim(series_names(k))//' of the step is '// &
        rtoa(row(k))//' (law parameters, masses or velocities beyond double precision?). The run stops; '// &
        'fracas.h5 holds the steps before it and is marked incomplete')
    end do
    call results_append_step(o%h5, row)
    call postpro_step(o%pp, sc, rep)
    call flush_if_due(o)
    call clocked(o, k_series, t0)
  end subroutine output_series

  !> Fragments of the meshed bodies now (0 without cohesive interfaces).
  integer function fragment_count(sc)
    type(scene_t), intent(in) :: sc
    integer, allocatable :: piece(:)
    fragment_count = 0
    if (sc%cracks%nedges > 0) call cracks_fragments(sc%cracks, sc%meshes, piece, fragment_count)
  end function fragment_count

  !> Flush the POSTPRO files every flush_interval seconds (fracas.h5 keeps its own clock).
  subroutine flush_if_due(o)
    type(output_t), intent(inout) :: o
    integer(i8) :: now, rate
    call system_clock(now, rate)
    if (rate <= 0) return
    if (real(now - o%last_flush, wp) <= flush_interval * real(rate, wp)) return
    call postpro_flush(o%pp)
    o%last_flush = now
  end subroutine flush_if_due

  !> Make everything written so far readable on disk (fracas.h5 flushed,
  !> POSTPRO lines handed to the system); the run goes on.
  subroutine output_flush(o)
    type(output_t), intent(inout) :: o
    if (o%h5_open) call results_flush(o%h5)
    call postpro_flush(o%pp)
    call system_clock(o%last_flush)
  end subroutine output_flush

  !> 1 for the contacts of a cohesive law whose interface is broken (beta = 0).
  function broken_flags(sc) result(f)
    type(scene_t), intent(in) :: sc
    integer(ik), allocatable :: f(:)
    integer :: k
    allocate (f(sc%contacts%n))
    do k = 1, sc%contacts%n
      f(k) = 0
      if (sc%laws(sc%contacts%law(k))%kind /= law_czm) cycle
      if (sc%contacts%internals(4, k) <= 0.0_wp) f(k) = 1
    end do
  end function broken_flags

  !> Root attributes NAME_seconds (wall) and NAME_cpu_seconds (CPU time of
  !> the process) of a part of the run the driver timed (read, setup, loop).
  subroutine output_timing(o, name, wall, cpu)
    type(output_t), intent(inout) :: o
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: wall, cpu
    if (.not. o%h5_open) return
    call h5_write_attr(o%h5%fid, name//'_seconds', wall)
    call h5_write_attr(o%h5%fid, name//'_cpu_seconds', cpu)
  end subroutine output_timing

  !> Close every output. complete = .false.: the run stopped before its end
  !> (fracas.h5 keeps complete = 0; end_reason, if given, says why).
  subroutine output_close(o, complete, end_reason)
    type(output_t), intent(inout) :: o
    logical, intent(in), optional :: complete
    character(len=*), intent(in), optional :: end_reason
    integer :: stat
    if (allocated(o%reserve)) then
      call remove_file(o%reserve, stat)
      deallocate (o%reserve)
    end if
    ! Still held until the process ends; a run that starts now takes a new file.
    if (allocated(o%lock)) then
      call remove_file(o%lock, stat)
      deallocate (o%lock)
    end if
    ! An error while closing stops the run; its clean-up closes again with
    ! complete = 0, going on past HDF5 errors (fracas_h5: check).
    call h5_set_dataset_hook()
    if (o%h5_open) call results_close(o%h5, complete, end_reason)
    o%h5_open = .false.
    call postpro_close(o%pp)
  end subroutine output_close
end module fracas_output
