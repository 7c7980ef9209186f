!> DOF.INI / DOF.OUT.n reader: the '$steps' header (step and time), then per
!> body a '$bdyty' block with the body number (columns 9-15) and the NO3xx
!> node line X(1..3) (displacement from the reference: x, y, rotation) and its
!> continuation line V(1..3), values at columns 35-48, 56-69, 77-90.
module fracas_read_dof
  use fracas_kinds, only: wp
  use fracas_deck, only: dof_record_t
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, check_line_end, &
                                keyword_of, is_data, get_real, get_int, get_word, itoa, get_steps
  implicit none
  private
  public :: read_dof_file

  integer, parameter :: value_col(3) = [35, 56, 77]

contains

  !> Read PATH. Body numbers must be in 1..NBODIES (unchecked if NBODIES < 0)
  !> and appear once. A file without '$steps' gives step 0, time 0.
  !> STEPS_LINE returns the line number of '$steps' (0 if absent).
  subroutine read_dof_file(path, step, time, records, nbodies, steps_line)
    character(len=*), intent(in) :: path
    integer, intent(out) :: step
    real(wp), intent(out) :: time
    type(dof_record_t), allocatable, intent(out) :: records(:)
    integer, intent(in), optional :: nbodies
    integer, intent(out), optional :: steps_line
    type(text_file_t) :: tf
    integer :: i, n, nmax, k
    integer, allocatable :: seen(:)
    character(len=5) :: kw
    character(len=:), allocatable :: model

    call load_text(path, tf)
    step = 0
    time = 0.0_wp
    if (present(steps_line)) steps_line = 0
    nmax = -1
    if (present(nbodies)) nmax = nbodies
    n = 0
    do i = 1, tf%n
      if (keyword_of(tf%lines(i)) == 'bdyty') n = n + 1
    end do
    allocate (records(n))
    if (nmax >= 0) then
      allocate (seen(nmax))
      seen = 0
    end if
    n = 0
    i = 1
    do while (i <= tf%n)
      kw = keyword_of(tf%lines(i))
      select case (kw)
      case ('steps')
        if (present(steps_line)) steps_line = tf%lines(i)%src%line
        call get_steps(tf%lines(i), step, time)
        i = i + 1
      case ('bdyty')
        if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$bdyty' must be followed by a body line (' RBDY2  number')")
        n = n + 1
        associate (ln => tf%lines(i + 1), r => records(n))
          r%src = ln%src
          model = get_word(ln, 2, 6, 'body model')
          if (model /= 'RBDY2') call line_error(ln, 2, "unknown body model '"//model//"' (supported: RBDY2)")
          r%model = model
          r%body = get_int(ln, 9, 15, 'body number')
          if (r%body < 1) call line_error(ln, 9, 'body number must be >= 1, found '//itoa(r%body))
          if (nmax >= 0) then
            if (r%body > nmax) call line_error(ln, 9, 'body '//itoa(r%body)//' does not exist (BODIES.DAT has ' &
                                               //itoa(nmax)//' bodies)')
            if (seen(r%body) > 0) call line_error(ln, 9, 'body '//itoa(r%body)//' is already given at line ' &
                                                  //itoa(seen(r%body)))
            seen(r%body) = ln%src%line
          end if
        end associate
        i = i + 2
        ! $nodty, the X line and the V line.
        if (i > tf%n) call line_error(tf%lines(i - 1), 1, "expected '$nodty' after the body line")
        if (keyword_of(tf%lines(i)) /= 'nodty') call line_error(tf%lines(i), 1, "expected '$nodty' after the body line")
        if (.not. (is_data(tf, i + 1) .and. is_data(tf, i + 2))) &
          call line_error(tf%lines(i), 1, "'$nodty' must be followed by the NO3xx line X(1..3) and the line V(1..3)")
        associate (lx => tf%lines(i + 1), lv => tf%lines(i + 2), r => records(n))
          if (get_word(lx, 2, 6, 'node type') /= 'NO3xx') &
            call line_error(lx, 2, "unknown node type '"//trim(field(lx, 2, 6))//"' for RBDY2 (supported: NO3xx)")
          do k = 1, 3
            r%x(k) = get_real(lx, value_col(k), value_col(k) + 13, 'X('//itoa(k)//')')
            r%v(k) = get_real(lv, value_col(k), value_col(k) + 13, 'V('//itoa(k)//')')
          end do
          call check_line_end(lx, 90, 'the X line')
          call check_line_end(lv, 90, 'the V line')
        end associate
        i = i + 3
      case ('$$$$$')
        i = i + 1
      case default
        if (tf%lines(i)%text(1:1) == '$') then
          call line_error(tf%lines(i), 1, "unknown keyword '"//trim(field(tf%lines(i), 1, 6))// &
                          "' (expected $steps, $bdyty, $nodty or $$$$$$)")
        else
          call line_error(tf%lines(i), 1, "unexpected line: '"//trim(field(tf%lines(i), 1, 40))//"'")
        end if
      end select
    end do
  end subroutine read_dof_file
end module fracas_read_dof
