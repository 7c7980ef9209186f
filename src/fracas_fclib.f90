!> fracas-fclib: solve an FCLib local frictional-contact problem (HDF5) with
!> Fracas' stored-Delassus NLGS and report sweeps, time and the natural-map error.
!>   fracas-fclib [options] PROBLEM.hdf5
program fracas_fclib
  use, intrinsic :: iso_fortran_env, only: output_unit
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal, warn
  use fracas_fclib_io, only: fclib_local_t, fclib_read_local, fclib_write_reactions, fclib_read_reactions
  use fracas_sdl, only: sdl_problem_t, sdl_settings_t, sdl_report_t, sdl_history_t, sdl_build, sdl_solve, &
                        sdl_error, sdl_history_points
  use fracas_version, only: version_report
  use fracas_command_line, only: argument_value
  use fracas_strings, only: lower, itoa
  implicit none

  character(len=:), allocatable :: arg, path, out_file, hist_file, eval_file
  type(fclib_local_t) :: prob
  type(sdl_problem_t) :: p
  type(sdl_settings_t) :: s
  type(sdl_report_t) :: rep, best
  type(sdl_history_t) :: hist
  real(wp), allocatable :: r(:, :), rbest(:, :)
  integer :: nargs, i, repeat, irun
  logical :: quiet

  call main()

contains

  subroutine main()
    real(wp) :: ea, ep, eo
    nargs = command_argument_count()
    path = ''; out_file = ''; hist_file = ''; eval_file = ''
    repeat = 1
    quiet = .false.
    i = 0
    do while (i < nargs)
      i = i + 1
      arg = argument_value(i, 'argument')
      select case (arg)
      case ('--err-tol')
        s%err_tol = real_value()
        if (s%err_tol < 0.0_wp) call fatal('--err-tol must be >= 0 (0: no natural-map stop)')
      case ('--check')
        i = i + 1
        select case (lower(argument_value(i, arg)))
        case ('quad'); s%check = 'Quad '
        case ('maxm'); s%check = 'Maxm '
        case ('qm/16'); s%check = 'QM/16'
        case ('none'); s%check = 'none '
        case default
          call fatal("--check expects Quad, Maxm, QM/16 or none, got '"//argument_value(i, arg)//"'")
        end select
      case ('--tol')
        s%tol = real_value()
        if (s%tol <= 0.0_wp) call fatal('--tol must be > 0')
      case ('--relax')
        s%relax = real_value()
        if (s%relax <= 0.0_wp .or. s%relax >= 2.0_wp) call fatal('--relax must be in (0, 2)')
      case ('--sweeps-per-check')
        s%sweeps_per_check = int_value()
        if (s%sweeps_per_check < 1) call fatal('--sweeps-per-check must be >= 1')
      case ('--max-sweeps')
        s%max_sweeps = int_value()
        if (s%max_sweeps < 0) call fatal('--max-sweeps must be >= 0')
      case ('--order')
        i = i + 1
        s%order = lower(argument_value(i, arg))
        if (s%order /= 'stored' .and. s%order /= 'reversed' .and. s%order /= 'shuffled') &
          call fatal("--order expects stored, reversed or shuffled, got '"//argument_value(i, arg)//"'")
      case ('--seed')
        s%seed = int_value()
      case ('--accel')
        s%accel = int_value()
        if (s%accel < 0) call fatal('--accel must be >= 0')
      case ('--time-limit')
        s%time_limit = real_value()
      case ('--repeat')
        repeat = int_value()
        if (repeat < 1) call fatal('--repeat must be >= 1')
      case ('--output', '-o')
        i = i + 1
        out_file = argument_value(i, arg)
      case ('--history')
        i = i + 1
        hist_file = argument_value(i, arg)
      case ('--evaluate')
        i = i + 1
        eval_file = argument_value(i, arg)
      case ('--quiet', '-q')
        quiet = .true.
      case ('--version')
        write (output_unit, '(a)') version_report('fracas-fclib')
        return
      case ('--help', '-h')
        call usage()
        return
      case default
        if (arg(1:1) == '-') call fatal("unknown option '"//arg//"' (see fracas-fclib --help)")
        if (len(path) > 0) call fatal("more than one problem file given: '"//path//"' and '"//arg//"'")
        path = arg
      end select
    end do
    if (len(path) == 0) then
      call usage()
      call fatal('no FCLib problem file given')
    end if

    call fclib_read_local(path, prob)
    call sdl_build(prob%dim, prob%nc, prob%row, prob%col, prob%val, prob%q, prob%mu, p)
    if (.not. quiet) write (output_unit, '(a,i0,a,i0,a,i0,a,i0,a,a,a,i0,a,i0,a,es10.3)') &
      'fracas-fclib: '//path//': ', prob%dim, 'D, ', prob%nc, ' contacts, W ', prob%m, ' x ', prob%m, &
      ' (', storage_name(prob%storage), ', ', size(prob%val), ' entries, ', p%nblocks, &
      ' off-diagonal blocks), |q| = ', p%norm_q
    allocate (r(prob%dim, prob%nc), source=0.0_wp)

    if (len(eval_file) > 0) then
      ! evaluate a given r only
      call fclib_read_reactions(eval_file, r)
      call sdl_error(p, r, ea, ep, eo)
      write (output_unit, '(a,3(a,es22.15))') 'evaluate file='//basename(path)//' r='//eval_file, &
        ' err_abs=', ea, ' err_paper=', ep, ' err_onepq=', eo
      return
    end if

    if (len(hist_file) > 0) hist%at = sdl_history_points(s%max_sweeps)
    do irun = 1, repeat
      r = 0.0_wp
      if (irun == 1 .and. len(hist_file) > 0) then
        call sdl_solve(p, s, r, rep, hist)
      else
        call sdl_solve(p, s, r, rep)
      end if
      if (irun == 1 .or. rep%time < best%time) then
        best = rep
        rbest = r
      end if
    end do
    if (.not. quiet) then
      write (output_unit, '(a,i0,a,es10.3,a,a,es10.3,a,es10.3,a,es10.3)') 'fracas-fclib: '// &
        trim(merge('converged     ', 'NOT converged ', best%converged))//' after ', best%sweeps, ' sweeps in ', &
        best%time, ' s', trim(merge(' (best of repeats)', '                  ', repeat > 1)) // &
        ': ||F||/||q|| = ', best%err_paper, ', ||F||/(1+||q||) = ', best%err_onepq, ', ||F|| = ', best%err_abs
      if (s%check /= 'none ') write (output_unit, '(a,5(a,es10.3))') 'fracas-fclib: LMGC90 norms ('// &
        trim(s%check)//'): ', ' QuadDV ', best%quad_dv, ' MaxmDV ', best%maxm_dv, ' QuadDVR ', best%quad_dvr, &
        ' MaxmDVR ', best%maxm_dvr, ' MeanDVoR ', best%mean_dvor
    end if
    if (best%local_failures > 0) call warn(itoa(best%local_failures)// &
                                           ' 3D local solves found no exact sliding solution (approximated)')
    write (output_unit, '(a,i0,a,i0,a,i0,a,es14.7,3(a,es22.15),a,i0,a,i0,a,i0)') 'result file='//basename(path)// &
      ' dim=', prob%dim, ' nc=', prob%nc, ' sweeps=', best%sweeps, ' time_s=', best%time, &
      ' err_paper=', best%err_paper, ' err_onepq=', best%err_onepq, ' err_abs=', best%err_abs, &
      ' converged=', merge(1, 0, best%converged), ' exact_checks=', best%exact_checks, &
      ' local_failures=', best%local_failures
    if (len(out_file) > 0) call fclib_write_reactions(out_file, rbest)
    if (len(hist_file) > 0) call write_history()
  end subroutine main

  subroutine write_history()
    integer :: u, ios, k
    open (newunit=u, file=hist_file, status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write '//hist_file)
    write (u, '(a)') 'sweeps,time_s,err_paper,err_onepq'
    do k = 1, hist%n
      write (u, '(i0,3(a,es22.15))') hist%sweeps(k), ',', hist%time(k), ',', hist%err_paper(k), ',', &
        hist%err_onepq(k)
    end do
    close (u)
  end subroutine write_history

  function storage_name(nz) result(s)
    integer, intent(in) :: nz
    character(len=:), allocatable :: s
    select case (nz)
    case (-2); s = 'CSR'
    case (-1); s = 'CSC'
    case default; s = 'triplet'
    end select
  end function storage_name

  function basename(f) result(b)
    character(len=*), intent(in) :: f
    character(len=:), allocatable :: b
    b = f(index(f, '/', back=.true.) + 1:)
  end function basename

  real(wp) function real_value() result(x)
    integer :: ios
    character(len=:), allocatable :: a
    i = i + 1
    a = argument_value(i, arg)
    read (a, *, iostat=ios) x
    if (ios /= 0) call fatal('option '//arg//" expects a number, got '"//a//"'")
  end function real_value

  integer function int_value() result(n)
    integer :: ios
    character(len=:), allocatable :: a
    i = i + 1
    a = argument_value(i, arg)
    read (a, *, iostat=ios) n
    if (ios /= 0) call fatal('option '//arg//" expects an integer, got '"//a//"'")
  end function int_value




  subroutine usage()
    write (output_unit, '(a)') &
      'usage: fracas-fclib [options] PROBLEM.hdf5', &
      '  Solves an FCLib local frictional-contact problem (/fclib_local: W, q, mu) from r = 0 with', &
      '  the stored-Delassus NLGS (exact 2D local solver; exact 3D stick/slide solver) and prints', &
      '  sweeps, solve time and the natural-map error ||F||/||q|| (and ||F||/(1+||q||)).', &
      'options:', &
      '  --err-tol E          stop when ||F||/||q|| <= E (default 1e-8; 0: no such stop)', &
      '  --check NORM         also require LMGC90''s norm Quad, Maxm or QM/16 (default none)', &
      '  --tol T              tolerance of that norm (default 1e-4)', &
      '  --sweeps-per-check N sweeps between two convergence checks (default 1)', &
      '  --max-sweeps N       give up after N sweeps (default 100000)', &
      '  --relax W            relaxation factor in (0, 2) (default 1)', &
      '  --accel M            Anderson acceleration of the sweeps, memory M (default 10; 0: plain NLGS)', &
      '  --order O            stored, reversed or shuffled (each block of sweeps; default stored)', &
      '  --seed S             seed of the shuffled order (default 1)', &
      '  --time-limit T       give up after T seconds of solve', &
      '  --repeat N           solve N times, report the best time', &
      '  --output FILE        write r as text (one contact per line, normal first)', &
      '  --history FILE       CSV of the error after 1, 2, 3, 4, 5, 6, 8, 10, ... sweeps', &
      '  --evaluate FILE      no solve: print the error of the r read from FILE', &
      '  --quiet, -q          only the final "result" line', &
      '  --version, --help'
  end subroutine usage
end program fracas_fclib
