!> DATBOX/COMMAND.DAT reader: Fracas's own run-control deck, one
!> "keyword value" per line (or "keyword = value"), keywords case-insensitive,
!> '!' or '#' start a comment. The same parser serves the driver's
!> "--set keyword=value" through apply_command_setting.
module fracas_read_command
  use fracas_kinds, only: wp
  use fracas_errors, only: input_error
  use fracas_deck, only: run_control_t
  use fracas_datbox_text, only: text_file_t, load_text, parse_real, parse_int, lower, itoa, rtoa, edit_distance
  implicit none
  private
  public :: read_command, apply_command_setting, check_run_control, command_keywords

  integer, parameter :: n_keys = 30
  character(len=21), parameter :: keys(n_keys) = [character(len=21) :: &
    'time_step', 'number_of_steps', 'final_time', 'theta', 'detection_frequency', &
    'nlgs_check', 'nlgs_tolerance', 'nlgs_relaxation', 'nlgs_sweeps_per_check', &
    'nlgs_max_checks', 'nlgs_order', 'nlgs_seed', 'output_dof_every', 'output_vtk_every', &
    'output_hdf5_every', 'progress_every', 'plane', 'newton_tolerance', 'newton_max_iterations', &
    'linear_solver', 'nlgs_unconverged', 'output_vtk_disks', 'output_vtk_precision', 'driven_start', &
    'detection_approach', 'nlgs_check_pass', 'cohesive_damage', 'output_restart_every', 'crack_step_limit', &
    'crack_step_cuts']
  integer, parameter :: k_time_step = 1, k_number_of_steps = 2, k_final_time = 3
  !> Largest NLGS sweep budget of a step (sweeps per check x checks).
  real(wp), parameter :: max_sweeps_per_step = 1.0e8_wp

contains

  !> Comma separated list of the keywords.
  function command_keywords() result(s)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, n_keys
      if (k > 1) s = s//', '
      s = s//trim(keys(k))
    end do
  end function command_keywords

  !> Read PATH into RUN (starting from the defaults of run_control_t), then
  !> check_run_control.
  subroutine read_command(path, run)
    character(len=*), intent(in) :: path
    type(run_control_t), intent(out) :: run
    type(text_file_t) :: tf
    integer :: i, key
    integer :: seen(n_keys)

    call load_text(path, tf, keep_comments=.true.)
    seen = 0
    do i = 1, tf%n
      call apply_line(run, tf%lines(i)%text, path, tf%lines(i)%src%line, key)
      if (key == 0) cycle
      if (seen(key) > 0) call input_error(path, tf%lines(i)%src%line, first_col(tf%lines(i)%text), &
                                          "keyword '"//trim(keys(key))//"' is given twice (first at line " &
                                          //itoa(seen(key))//')')
      if ((key == k_number_of_steps .and. seen(k_final_time) > 0) .or. &
          (key == k_final_time .and. seen(k_number_of_steps) > 0)) &
        call input_error(path, tf%lines(i)%src%line, first_col(tf%lines(i)%text), &
                         'give either number_of_steps or final_time, not both (the other is at line ' &
                         //itoa(max(seen(k_final_time), seen(k_number_of_steps)))//')')
      seen(key) = tf%lines(i)%src%line
    end do
    call check_run_control(run, path, 1, seen)
  end subroutine read_command

  !> Apply one "keyword=value" (or "keyword value") setting, e.g. from the
  !> command line; ORIGIN names it in messages (e.g. '--set'). Setting
  !> number_of_steps drops final_time and the other way round.
  subroutine apply_command_setting(run, text, origin)
    type(run_control_t), intent(inout) :: run
    character(len=*), intent(in) :: text, origin
    integer :: key
    call apply_line(run, text, origin, 0, key)
    if (key == 0) call input_error(origin, 0, 0, "expected 'keyword=value', found '"//trim(text)//"'")
  end subroutine apply_command_setting

  !> Checks that need the whole deck: time_step given, and number_of_steps or
  !> final_time. With final_time, number_of_steps = nint(final_time/time_step).
  !> Values each valid alone but unusable together are refused: a step count
  !> past the largest integer, a sweep budget past 1e8 per step, a time step that is not a
  !> normal number. A missing keyword is reported at ORIGIN:LINE:1 (LINE 1 for
  !> a file, 0 for command-line settings, where no line is shown); a bad
  !> combination at the line of the keyword (key_lines(k): line of keyword k).
  subroutine check_run_control(run, origin, line, key_lines)
    type(run_control_t), intent(inout) :: run
    character(len=*), intent(in) :: origin
    integer, intent(in), optional :: line
    integer, intent(in), optional :: key_lines(:)
    integer :: l
    real(wp) :: nsteps
    l = 0
    if (present(line)) l = line
    if (run%time_step <= 0.0_wp) call input_error(origin, l, 1, &
                                                 "required keyword 'time_step' is missing (the time step, a real > 0)")
    if (run%time_step < tiny(1.0_wp)) call input_error(origin, line_of(1), 1, 'time_step '//rtoa(run%time_step)// &
      ' is below the smallest normal double: the time could not advance')
    if (run%final_time > 0.0_wp) then
      nsteps = run%final_time/run%time_step
      if (.not. nsteps < real(huge(1), wp)) call input_error(origin, line_of(k_final_time), 1, &
        'final_time / time_step = '//rtoa(nsteps)//' steps, more than the largest step count ('//itoa(huge(1))//')')
      run%number_of_steps = max(1, nint(nsteps))
    else if (run%number_of_steps <= 0) then
      call input_error(origin, l, 1, "one of 'number_of_steps' (an integer >= 1) or 'final_time' (a real > 0) " &
                       //'is required')
    end if
    if (real(run%nlgs_sweeps_per_check, wp)*real(run%nlgs_max_checks, wp) > max_sweeps_per_step) &
      call input_error(origin, line_of(10), 1, 'nlgs_sweeps_per_check x nlgs_max_checks = '// &
        rtoa(real(run%nlgs_sweeps_per_check, wp)*real(run%nlgs_max_checks, wp))// &
        ' sweeps per step, more than '//rtoa(max_sweeps_per_step)//' (a step that does not converge would run '// &
        'for hours; LMGC90 decks allow 1e3 to 1e5)')

  contains

    !> Line of keyword k if known, else the default line.
    integer function line_of(k)
      integer, intent(in) :: k
      line_of = l
      if (present(key_lines)) then
        if (key_lines(k) > 0) line_of = key_lines(k)
      end if
    end function line_of
  end subroutine check_run_control

  integer function first_col(text)
    character(len=*), intent(in) :: text
    first_col = verify(text, ' ')
    if (first_col == 0) first_col = 1
  end function first_col

  !> Parse one line: KEY returns the keyword index, 0 for a blank/comment line.
  subroutine apply_line(run, text, origin, line, key)
    type(run_control_t), intent(inout) :: run
    character(len=*), intent(in) :: text, origin
    integer, intent(in) :: line
    integer, intent(out) :: key
    character(len=:), allocatable :: s, word, value
    integer :: n, a, b, c, vcol, k

    key = 0
    s = text
    ! Comments: '!' or '#' to the end of the line.
    n = scan(s, '!#')
    if (n > 0) s = s(1:n - 1)
    if (len_trim(s) == 0) return
    a = verify(s, ' ')
    b = a
    do while (b <= len_trim(s))
      if (s(b:b) == ' ' .or. s(b:b) == '=') exit
      b = b + 1
    end do
    word = lower(s(a:b - 1))
    do k = 1, n_keys
      if (word == trim(keys(k))) key = k
    end do
    if (key == 0) call input_error(origin, line, a, "unknown keyword '"//s(a:b - 1)//"'"//suggestion(word))
    ! Value: after blanks and an optional '='.
    c = b
    do while (c <= len_trim(s))
      if (s(c:c) /= ' ') exit
      c = c + 1
    end do
    if (c <= len_trim(s)) then
      if (s(c:c) == '=') c = c + 1
    end if
    do while (c <= len_trim(s))
      if (s(c:c) /= ' ') exit
      c = c + 1
    end do
    vcol = c
    value = trim(s(min(c, len(s) + 1):))
    if (len(value) == 0) call input_error(origin, line, vcol, "keyword '"//trim(keys(key))//"' needs a value: " &
                                          //expected(key))
    if (index(value, ' ') > 0) call input_error(origin, line, vcol + index(value, ' '), &
                                                "one value expected after '"//trim(keys(key))//"', found '"//value//"'")
    call set_value(run, key, value, origin, line, vcol)
  end subroutine apply_line

  !> What a keyword takes, for messages.
  function expected(key) result(s)
    integer, intent(in) :: key
    character(len=:), allocatable :: s
    if (len(choices(key)) > 0) then
      s = 'one of '//replace_spaces(choices(key))
      return
    end if
    select case (trim(keys(key)))
    case ('time_step', 'final_time', 'newton_tolerance')
      s = 'a real > 0'
    case ('nlgs_tolerance')
      s = 'a real >= 2.2e-16 (a smaller tolerance cannot be met in double precision)'
    case ('theta')
      s = 'a real in [0.5, 1]'
    case ('nlgs_relaxation')
      s = 'a real in (0, 2)'
    case ('number_of_steps', 'detection_frequency', 'nlgs_sweeps_per_check', 'nlgs_max_checks', &
          'newton_max_iterations')
      s = 'an integer >= 1'
    case ('nlgs_seed')
      s = 'an integer'
    case ('crack_step_limit')
      s = 'a real >= 0 (softening lengths per step; 0: off)'
    case ('crack_step_cuts')
      s = 'an integer in [1, 30]'
    case default
      s = 'an integer >= 0'
    end select
  end function expected

  subroutine set_value(run, key, value, origin, line, col)
    type(run_control_t), intent(inout) :: run
    integer, intent(in) :: key, line, col
    character(len=*), intent(in) :: value, origin
    real(wp) :: x
    integer :: i
    character(len=:), allocatable :: lv

    lv = lower(value)
    select case (trim(keys(key)))
    case ('time_step')
      run%time_step = real_in(0.0_wp, huge(1.0_wp), .false.)
    case ('number_of_steps')
      run%number_of_steps = int_min(1)
      run%final_time = -1.0_wp
    case ('final_time')
      run%final_time = real_in(0.0_wp, huge(1.0_wp), .false.)
      run%number_of_steps = 0
    case ('theta')
      run%theta = real_in(0.5_wp, 1.0_wp, .true.)
    case ('detection_frequency')
      run%detection_frequency = int_min(1)
    case ('nlgs_check')
      run%nlgs_check = word()
    case ('nlgs_tolerance')
      run%nlgs_tolerance = real_in(epsilon(1.0_wp), huge(1.0_wp), .true.)
    case ('nlgs_relaxation')
      run%nlgs_relaxation = real_in(0.0_wp, 2.0_wp, .false.)
    case ('nlgs_sweeps_per_check')
      run%nlgs_sweeps_per_check = int_min(1)
    case ('nlgs_max_checks')
      run%nlgs_max_checks = int_min(1)
    case ('nlgs_order')
      run%nlgs_order = word()
    case ('nlgs_seed')
      run%nlgs_seed = int_min(-huge(1))
    case ('output_dof_every')
      run%output_dof_every = int_min(0)
    case ('output_vtk_every')
      run%output_vtk_every = int_min(0)
    case ('output_hdf5_every')
      run%output_hdf5_every = int_min(0)
    case ('output_restart_every')
      run%output_restart_every = int_min(0)
    case ('progress_every')
      run%progress_every = int_min(0)
    case ('plane')
      run%plane = word()
    case ('newton_tolerance')
      run%newton_tolerance = real_in(0.0_wp, huge(1.0_wp), .false.)
    case ('newton_max_iterations')
      run%newton_max_iterations = int_min(1)
    case ('linear_solver')
      run%linear_solver = word()
    case ('driven_start')
      run%driven_start = word()
    case ('cohesive_damage')
      run%cohesive_damage = word()
    case ('crack_step_limit')
      run%crack_step_limit = real_in(0.0_wp, huge(1.0_wp), .true.)
    case ('crack_step_cuts')
      run%crack_step_cuts = int_min(1)
      if (run%crack_step_cuts > 30) call input_error(origin, line, col, "value "//itoa(run%crack_step_cuts)// &
        " out of range for 'crack_step_cuts': expected "//expected(key))
    case ('detection_approach')
      run%detection_approach = word() == 'yes'
    case ('nlgs_check_pass')
      run%nlgs_check_pass = word() == 'yes'
    case ('nlgs_unconverged')
      run%nlgs_unconverged = word()
    case ('output_vtk_disks')
      run%output_vtk_disks = word()
    case ('output_vtk_precision')
      run%output_vtk_precision = word()
    end select

  contains

    subroutine bad()
      call input_error(origin, line, col, "bad value '"//value//"' for '"//trim(keys(key))//"': expected " &
                       //expected(key))
    end subroutine bad

    !> A real in [lo, hi] (closed) or (lo, hi) (open).
    real(wp) function real_in(lo, hi, closed)
      real(wp), intent(in) :: lo, hi
      logical, intent(in) :: closed
      character(len=:), allocatable :: msg
      logical :: ok
      if (.not. parse_real(value, x, msg)) call bad()
      if (closed) then
        ok = x >= lo .and. x <= hi
      else
        ok = x > lo .and. x < hi
      end if
      if (.not. ok) call input_error(origin, line, col, "value "//rtoa(x)//" out of range for '"// &
                                     trim(keys(key))//"': expected "//expected(key))
      real_in = x
    end function real_in

    integer function int_min(lo)
      integer, intent(in) :: lo
      character(len=:), allocatable :: msg
      if (.not. parse_int(value, i, msg)) call bad()
      if (i < lo) call input_error(origin, line, col, "value "//itoa(i)//" out of range for '"// &
                                   trim(keys(key))//"': expected "//expected(key))
      int_min = i
    end function int_min

    !> The keyword's word (one of choices(key), any case), as the list spells it.
    function word() result(w)
      character(len=:), allocatable :: w, rest
      integer :: sp
      rest = choices(key)//' '
      do while (len_trim(rest) > 0)
        sp = index(rest, ' ')
        w = rest(:sp - 1)
        if (lower(w) == lv) return
        rest = adjustl(rest(sp + 1:))
      end do
      call bad()
    end function word
  end subroutine set_value

  !> The words a keyword takes (space-separated; '' for a number), as they are spelt.
  function choices(key) result(s)
    integer, intent(in) :: key
    character(len=:), allocatable :: s
    select case (trim(keys(key)))
    case ('nlgs_check'); s = 'Quad Maxm QM/16'
    case ('nlgs_order'); s = 'stored reversed shuffled colored'
    case ('plane'); s = 'strain stress axisym'
    case ('linear_solver'); s = 'auto dense cholmod'
    case ('driven_start'); s = 'lmgc90 imposed initial'
    case ('cohesive_damage'); s = 'implicit explicit lmgc90'
    case ('detection_approach', 'nlgs_check_pass'); s = 'yes no'
    case ('nlgs_unconverged'); s = 'warn fail stop'
    case ('output_vtk_disks'); s = 'points polygons'
    case ('output_vtk_precision'); s = 'single double'
    case default; s = ''
    end select
  end function choices

  !> 'a b c' -> 'a, b, c'.
  function replace_spaces(words) result(s)
    character(len=*), intent(in) :: words
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    do i = 1, len(words)
      if (words(i:i) == ' ') then
        s = s//', '
      else
        s = s//words(i:i)
      end if
    end do
  end function replace_spaces

  !> ' (did you mean 'x'?)' for the closest keyword, or the list of keywords.
  function suggestion(word) result(s)
    character(len=*), intent(in) :: word
    character(len=:), allocatable :: s
    integer :: k, d, best, kbest
    best = huge(1)
    kbest = 0
    do k = 1, n_keys
      d = edit_distance(word, trim(keys(k)))
      if (d < best) then
        best = d
        kbest = k
      end if
    end do
    if (kbest > 0 .and. best <= max(2, len(word)/3)) then
      s = "; did you mean '"//trim(keys(kbest))//"'?"
    else
      s = ' (known keywords: '//command_keywords()//')'
    end if
  end function suggestion

end module fracas_read_command
