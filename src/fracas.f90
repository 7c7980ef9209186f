!> fracas: run (or check) a case directory holding DATBOX/.
!>   fracas [options] CASE_DIR
program fracas
  use, intrinsic :: iso_fortran_env, only: output_unit, int64
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal, warn, set_cleanup, stop_run, exit_unconverged, set_error_context, last_error, &
                           status_t
  use fracas_strings, only: itoa, rtoa
  use fracas_datbox_text, only: parse_int
  use fracas_deck, only: deck_t
  use fracas_read_deck, only: read_deck
  use fracas_mailx, only: mailx_solver_summary
  use fracas_scene, only: scene_t, step_report_t, scene_build, scene_free
  use fracas_stepping, only: stepping_t, scene_advance
  use fracas_output, only: output_t, output_prepare, output_open, output_vtk, output_outbox, output_snapshot, &
                           output_series, output_close, output_summary, output_timing
  use fracas_version, only: version_report
  use fracas_state_guard, only: scene_check_start, scene_fault
  use fracas_restart, only: restart_save, restart_load
  use fracas_postpro, only: postpro_sums, postpro_restore_sums
  use fracas_command_line, only: argument_value
  implicit none

  character(len=:), allocatable :: case_dir, command_file, out_dir, arg, restart_file, fault
  character(len=1024), allocatable :: settings(:)
  logical :: check_only, quiet, overwrite
  type(deck_t) :: deck
  type(scene_t) :: sc
  type(output_t) :: out
  type(step_report_t) :: rep
  type(status_t) :: status
  type(stepping_t) :: stepping
  integer :: i, nargs, nsteps, istep, first_step, every, unconverged, late, hdf5_every, first_unconverged
  integer :: restart_every
  integer :: restart_step, vtk_frames, outbox_writes
  integer(int64) :: total_sweeps
  real(wp) :: late_max
  integer(int64) :: t0, t1, rate
  real(wp) :: worst_residual
  real(wp), allocatable :: pp_sums(:)   !< POSTPRO running sums of the restart point
  ! Wall and CPU seconds of reading the deck, building the scene (meshes
  ! assembled and factorized) and the time loop, for OUTBOX/fracas.h5.
  real(wp) :: read_wall, read_cpu, setup_wall, setup_cpu, loop_wall, loop_cpu, cpu0, cpu1

  call main()

contains

  subroutine main()
    check_only = .false.; quiet = .false.; overwrite = .false.
    command_file = ''; out_dir = ''; case_dir = ''; restart_file = ''; restart_step = -1
    allocate (settings(0))
    nargs = command_argument_count()
    i = 0
    do while (i < nargs)
      i = i + 1
      arg = argument_value(i, 'argument')
      select case (arg)
      case ('--check')
        check_only = .true.
      case ('--quiet', '-q')
        quiet = .true.
      case ('--overwrite')
        overwrite = .true.
      case ('--command')
        i = i + 1
        command_file = argument_value(i, arg)
      case ('--output')
        i = i + 1
        out_dir = argument_value(i, arg)
      case ('--restart')
        i = i + 1
        restart_file = argument_value(i, arg)
      case ('--restart-step')
        i = i + 1
        block
          character(len=:), allocatable :: msg
          if (.not. parse_int(argument_value(i, arg), restart_step, msg)) &
            call fatal('--restart-step needs a step number, '//msg)
          if (restart_step < 0) call fatal('--restart-step needs a step number >= 0')
        end block
      case ('--set')
        i = i + 1
        settings = [character(len=1024) :: settings, argument_value(i, arg)]
      case ('--fail-unconverged')
        settings = [character(len=1024) :: settings, 'nlgs_unconverged=fail']
      case ('--version')
        write (output_unit, '(a)') version_report('fracas')
        return
      case ('--help', '-h')
        call usage()
        return
      case default
        if (arg(1:1) == '-') call fatal("unknown option '"//arg//"' (see fracas --help)")
        if (len(case_dir) > 0) call fatal("more than one case directory given: '"//case_dir//"' and '"//arg//"'")
        case_dir = arg
      end select
    end do
    if (len(case_dir) == 0) then
      call usage()
      call fatal('no case directory given')
    end if
    if (len(out_dir) == 0) out_dir = case_dir

    call clocks(t0, cpu0)
    if (len(command_file) > 0) then
      call read_deck(case_dir, deck, command_file, settings=settings)
    else
      call read_deck(case_dir, deck, settings=settings)
    end if
    call clocks(t1, cpu1)
    call since(t0, cpu0, t1, cpu1, read_wall, read_cpu)
    call scene_build(deck, sc)
    stepping%limit = deck%run%crack_step_limit
    stepping%max_cuts = deck%run%crack_step_cuts
    call scene_check_start(sc, deck)
    call clocks(t0, cpu0)
    call since(t1, cpu1, t0, cpu0, setup_wall, setup_cpu)
    nsteps = deck%run%number_of_steps
    vtk_frames = 0; outbox_writes = 0
    if (restart_step >= 0 .and. len(restart_file) == 0) call fatal('--restart-step needs --restart FILE')
    if (len(restart_file) > 0) then
      ! Read the whole state before output_open may replace the file it comes from.
      call restart_load(restart_file, restart_step, sc, vtk_frames, outbox_writes, pp_sums)
      if (sc%steps_done >= nsteps) call fatal('nothing to run: the restart point is at step '// &
        itoa(sc%steps_done)//' of '//itoa(nsteps)//' (raise number_of_steps, e.g. --set number_of_steps=N)')
    end if
    first_step = sc%steps_done + 1
    call output_prepare(out, sc, deck)
    if (allocated(pp_sums)) call postpro_restore_sums(out%pp, pp_sums)
    if (check_only) then
      write (output_unit, '(a,i0,a,i0,a,i0,a,i0,a)') 'check: OK (', sc%bodies%n + sc%meshes%n, ' bodies, ', sc%tactors%n, &
        ' contactors, ', size(sc%laws), ' contact laws, ', nsteps - first_step + 1, ' steps)'
      return
    end if

    call output_open(out, sc, deck, out_dir, overwrite)
    call output_timing(out, 'read', read_wall, read_cpu)
    call output_timing(out, 'setup', setup_wall, setup_cpu)
    call set_cleanup(close_incomplete)
    if (.not. quiet .and. sc%meshes%n > 0) write (output_unit, '(a,i0,a,i0,a,i0,a)') 'fracas: ', sc%meshes%n, &
      ' meshed bodies (', sc%meshes%nnodes, ' nodes, ', sc%meshes%nelem, ' elements); iteration matrices: '// &
      mailx_solver_summary(sc%meshes)
    if (len(restart_file) > 0) then
      out%n_vtk = vtk_frames
      out%n_out = outbox_writes
      if (.not. quiet) write (output_unit, '(a,i0,a,es11.4,a)') 'fracas: restarted from '//restart_file// &
        ' at step ', sc%step, ' (t=', sc%time, ')'
    else if (deck%run%output_vtk_every > 0) then
      call output_vtk(out, sc)
    end if
    every = deck%run%progress_every
    if (every <= 0) every = max(1, nsteps / 20)
    hdf5_every = deck%run%output_hdf5_every
    if (hdf5_every < 0) hdf5_every = max(1, nsteps / 100)   ! not given: about 100 snapshots
    restart_every = deck%run%output_restart_every
    if (restart_every < 0) restart_every = hdf5_every         ! not given: with every snapshot
    total_sweeps = 0; unconverged = 0; worst_residual = 0.0_wp; late = 0; late_max = 0.0_wp
    first_unconverged = 0
    call clocks(t0, cpu0)
    do istep = first_step, nsteps
      call set_error_context(step='step '//itoa(istep)//' (t='//rtoa(sc%time + sc%h)//')')
      call scene_advance(sc, stepping, rep, status)
      if (.not. status%ok) call fatal(status%message)   ! a body whose matrix does not factorize
      fault = scene_fault(sc)
      if (len(fault) > 0) call fatal('step '//itoa(sc%step)//' (t='//rtoa(sc%time)//'): '//fault// &
        '. The run stops; '//out_dir//'/OUTBOX/fracas.h5 holds the steps before it and is marked incomplete')
      total_sweeps = total_sweeps + rep%nlgs%sweeps
      worst_residual = max(worst_residual, rep%nlgs%residual)
      late = late + rep%late_contacts
      late_max = max(late_max, rep%late_overlap)
      call output_series(out, sc, rep)
      ! The last step always ends DISPLAY, whatever the interval.
      if (every_n(deck%run%output_vtk_every) .or. (deck%run%output_vtk_every > 0 .and. istep == nsteps)) &
        call output_vtk(out, sc)
      if (every_n(deck%run%output_dof_every) .or. (deck%run%output_dof_every == 0 .and. istep == nsteps)) &
        call output_outbox(out, sc)
      ! A restart point (which flushes the file) every restart_every steps and at the last step.
      if (every_n(restart_every) .or. istep == nsteps) call restart_save(out%h5, sc, out%n_vtk, out%n_out, &
                                                                               postpro_sums(out%pp))
      if (every_n(hdf5_every)) call output_snapshot(out, sc)
      if (.not. (rep%nlgs%converged .and. rep%newton_converged)) call not_converged()
      if (.not. quiet .and. (mod(istep, every) == 0 .or. istep == nsteps)) call progress()
    end do
    call set_error_context(step='after step '//itoa(nsteps))
    call clocks(t1, cpu1)
    call since(t0, cpu0, t1, cpu1, loop_wall, loop_cpu)
    call output_timing(out, 'loop', loop_wall, loop_cpu)
    call output_close(out)
    call scene_free(sc)
    if (.not. quiet) then
      write (output_unit, '(a,i0,a,f0.3,a,i0,a,es9.2)') 'fracas: done: ', nsteps - first_step + 1, ' steps in ', loop_wall, &
        ' s, ', total_sweeps, ' NLGS sweeps, worst natural-map residual ', worst_residual
      ! The residual is a diagnostic: say what convergence was judged on.
      write (output_unit, '(a)') 'fracas: (the residual is a diagnostic, not the convergence test: steps converge '// &
        'on LMGC90''s '//trim(deck%run%nlgs_check)//' norms below nlgs_tolerance, series/quad_dv and series/converged)'
      if (stepping%limit > 0.0_wp) write (output_unit, '(a,i0,a,i0,a,i0,a,i0,a,es9.2,a)') 'fracas: crack step '// &
        'control: ', stepping%cut_steps, ' steps cut into ', stepping%substeps, ' sub-steps (', stepping%rejected, &
        ' done again shorter; down to time_step/2^', stepping%deepest, ', limit ', stepping%limit, &
        ' softening lengths per step)'
      write (output_unit, '(a)') 'fracas: output: '//output_summary(out)
      write (output_unit, '(a)') 'fracas: results: '//out_dir//'/OUTBOX/fracas.h5'
      if (deck%run%output_vtk_every > 0) write (output_unit, '(a)') 'fracas: ParaView: '//out_dir//'/DISPLAY/fracas.pvd'
    end if
    if (late > 0) then
      block
        character(len=300) :: msg
        write (msg, '(i0,a,es9.2,a)') late, ' contacts were first detected already overlapping (up to ', late_max, ' m)'
        ! Exploded meshes: a wider alert glues wrong pairs (doc/fracture.md section 1); their late
        ! contacts are mostly points turning around a shared corner (doc/hydrided_zircaloy.md section 1).
        if (sc%meshes%n > 0) then
          call warn(trim(msg)//': in an exploded mesh mostly candidate points of an opening interface that turn '// &
                    'around a corner into the range of a neighbouring element''s edge (doc/hydrided_zircaloy.md '// &
                    'section 1); if the overlap is not small against the elements, lower the time step (the alert '// &
                    'of exploded meshes stays below fracas_tools.cohesive.safe_alert, doc/fracture.md section 1)')
        else
          call warn(trim(msg)//': bodies move more than the alert distance in one step; raise the alert '// &
                    'distance or lower the time step')
        end if
      end block
    end if
    if (stepping%unmet > 0) then
      block
        character(len=:), allocatable :: msg
        msg = itoa(stepping%unmet)//' sub-steps opened a damaging cohesive zone by more than crack_step_limit '// &
              'at the shortest step allowed (time_step/2^crack_step_cuts): raise crack_step_cuts '// &
              '(series/crack_increment in fracas.h5 shows where)'
        ! An accuracy target not met is, for the exit status, an unconverged run.
        if (deck%run%nlgs_unconverged == 'fail' .and. unconverged == 0) &
          call stop_run(msg//' (nlgs_unconverged = fail)', exit_unconverged)
        call warn(msg)
      end block
    end if
    if (unconverged > 0) then
      block
        character(len=300) :: msg
        write (msg, '(i0,a,i0,a,i0,a)') unconverged, ' of ', nsteps, ' steps reached the NLGS sweep limit or '// &
          'newton_max_iterations without converging (the first: step ', first_unconverged, &
          '; OUTBOX/fracas.h5 series/converged = 0 marks them)'
        if (deck%run%nlgs_unconverged == 'fail') call stop_run(trim(msg)//' (nlgs_unconverged = fail)', &
                                                              exit_unconverged)
        call warn(trim(msg))
      end block
    end if

  end subroutine main

  !> A step reached the sweep limit: say so (each of the first ones, then
  !> every progress line counts them), and stop if the run control says so.
  subroutine not_converged()
    integer, parameter :: told_max = 10
    character(len=300) :: msg
    unconverged = unconverged + 1
    if (first_unconverged == 0) first_unconverged = sc%step
    if (rep%nlgs%converged) then
      write (msg, '(a,i0,a,es11.4,a,i0,a)') 'step ', sc%step, ' (t=', sc%time, '): the Newton loop of the meshed '// &
        'bodies did not converge in ', rep%newton_iterations, ' iterations (newton_max_iterations)'
    else
      write (msg, '(a,i0,a,es11.4,a,i0,a,es8.2,a)') 'step ', sc%step, ' (t=', sc%time, '): NLGS did not converge in ', &
        rep%nlgs%sweeps, ' sweeps (norm/tolerance ', check_norm(), ' at the last check, below 1 needed)'
    end if
    if (deck%run%nlgs_unconverged == 'stop') then
      call output_close(out, complete=.false., end_reason=trim(msg)//'; stopped: nlgs_unconverged = stop')
      call stop_run(trim(msg)//'. The run stops (nlgs_unconverged = stop); '//out_dir// &
                    '/OUTBOX/fracas.h5 holds the steps up to this one', exit_unconverged)
    end if
    if (quiet) return
    if (unconverged <= told_max) then
      write (output_unit, '(a)') 'fracas: '//trim(msg)
      if (unconverged == told_max) write (output_unit, '(a)') 'fracas: (further unconverged steps are counted '// &
        'in the progress lines)'
      flush (output_unit)
    end if
  end subroutine not_converged

  !> The norm the convergence check uses, over the tolerance.
  real(wp) function check_norm()
    select case (deck%run%nlgs_check)
    case ('Maxm ')
      check_norm = max(rep%nlgs%maxm_dv, rep%nlgs%maxm_dvr, abs(rep%nlgs%mean_dvor))
    case default
      check_norm = max(rep%nlgs%quad_dv, rep%nlgs%quad_dvr, abs(rep%nlgs%mean_dvor))
    end select
  end function check_norm

  !> Clean-up on a fatal error once the output is open: fracas.h5 is closed
  !> with complete = 0, so that no reader takes it for a finished run, and
  !> end_reason = the error message.
  subroutine close_incomplete()
    call output_close(out, complete=.false., end_reason=last_error())
  end subroutine close_incomplete

  !> Wall clock (ticks of system_clock) and process CPU time (s) now.
  subroutine clocks(ticks, cpu)
    integer(int64), intent(out) :: ticks
    real(wp), intent(out) :: cpu
    call system_clock(ticks, rate)
    call cpu_time(cpu)
  end subroutine clocks

  !> Wall and CPU seconds between two clocks readings.
  subroutine since(ticks0, cpu_start, ticks1, cpu_end, wall, cpu)
    integer(int64), intent(in) :: ticks0, ticks1
    real(wp), intent(in) :: cpu_start, cpu_end
    real(wp), intent(out) :: wall, cpu
    wall = real(ticks1 - ticks0, wp) / real(rate, wp)
    cpu = cpu_end - cpu_start
  end subroutine since

  !> True every n steps (never for n = 0).
  logical function every_n(n)
    integer, intent(in) :: n
    every_n = .false.
    if (n > 0) every_n = mod(istep, n) == 0
  end function every_n

  subroutine progress()
    real(wp) :: el, remaining
    call system_clock(t1)
    el = real(t1 - t0, wp) / real(rate, wp)
    remaining = el / (istep - first_step + 1) * (nsteps - istep)
    write (output_unit, '(a,i0,a,i0,a,es11.4,a,i0,a,i0,a,es9.2,a,f0.1,a,f0.1,a)', advance='no') 'step ', istep, '/', &
      nsteps, '  t=', sc%time, '  contacts ', rep%contacts, '  sweeps ', rep%nlgs%sweeps, '  residual ', &
      rep%nlgs%residual, '  elapsed ', el, ' s  remaining ', remaining, ' s'
    if (rep%substeps > 1) write (output_unit, '(a,i0,a)', advance='no') '  cut into ', rep%substeps, ' sub-steps'
    if (.not. rep%nlgs%converged) write (output_unit, '(a)', advance='no') '  NOT CONVERGED'
    if (unconverged > 0) write (output_unit, '(a,i0)', advance='no') '  unconverged steps ', unconverged
    write (output_unit, '(a)') ''
    flush (output_unit)
  end subroutine progress


  subroutine usage()
    write (output_unit, '(a)') &
      'usage: fracas [options] CASE_DIR', &
      '  Runs the NSCD simulation described by CASE_DIR/DATBOX (LMGC90 DATBOX files', &
      '  plus COMMAND.DAT) and writes CASE_DIR/OUTBOX and CASE_DIR/DISPLAY.', &
      'options:', &
      '  --check            read and validate the deck, run nothing', &
      '  --command FILE     run-control deck to use instead of CASE_DIR/DATBOX/COMMAND.DAT', &
      '  --set KEY=VALUE    override one COMMAND.DAT setting (repeatable); without a', &
      '                     COMMAND.DAT (LMGC90 decks), --set time_step=H --set number_of_steps=N', &
      '                     is enough: every other setting has a default', &
      '  --fail-unconverged the same as --set nlgs_unconverged=fail', &
      '  --output DIR       write OUTBOX/ and DISPLAY/ under DIR instead of CASE_DIR', &
      '  --overwrite        replace results already present', &
      '  --restart FILE     continue the run whose OUTBOX/fracas.h5 is FILE from its latest restart', &
      '                     point (bit for bit as if it had not stopped), up to number_of_steps', &
      '  --restart-step N   restart from the point of step N instead (written with every HDF5', &
      '                     snapshot and at the last step)', &
      '  --quiet, -q        no progress lines', &
      '  --version, --help', &
      'exit status:', &
      '  0  the run (or the check) went through', &
      '  1  an error was reported (bad input, a failure during the run)', &
      '  2  an error of the Fortran run-time library (a bug: please report it)', &
      '  3  NLGS steps did not converge and nlgs_unconverged is fail (the run went to', &
      '     its end) or stop (the run stopped at the first such step); with fail also', &
      '     when crack_step_limit could not be met at the shortest step', &
      '  a signal (e.g. 137 for SIGKILL): fracas.h5 keeps complete = 0'
  end subroutine usage
end program fracas
