!> DOF.INI / DOF.OUT.n reader: the '$steps' header (step and time), then per
!> body a '$bdyty' block with the body number (columns 9-15):
!> - RBDY2: the NO3xx node line X(1..3) (displacement from the reference: x,
!>   y, rotation) and its continuation line V(1..3), values at columns 35-48,
!>   56-69, 77-90;
!> - MAILx: '$model' MECAx, '$nodty', then per node a NO2xx line (node number
!>   in columns 7-13) with X(1..2) and its continuation line V(1..2), values
!>   at columns 35-48, 56-69.
module fracas_read_dof
  use fracas_kinds, only: wp
  use fracas_deck, only: dof_record_t, body_input_t
  use fracas_read_bodies, only: body_lookup_t, body_lookup, find_body, no_such_body
  use fracas_datbox_text, only: text_file_t, load_text, line_error, field, check_line_end, &
                                keyword_of, is_data, get_real, get_int, get_word, itoa, get_steps
  implicit none
  private
  public :: read_dof_file

  integer, parameter :: value_col(3) = [35, 56, 77]

contains

  !> Read PATH. With BODIES, body numbers (within their model) and node
  !> numbers must exist and appear once. A file without '$steps' gives step
  !> 0, time 0. STEPS_LINE returns the line number of '$steps' (0 if absent).
  subroutine read_dof_file(path, step, time, records, bodies, steps_line)
    character(len=*), intent(in) :: path
    integer, intent(out) :: step
    real(wp), intent(out) :: time
    type(dof_record_t), allocatable, intent(out) :: records(:)
    type(body_input_t), intent(in), optional :: bodies(:)
    integer, intent(out), optional :: steps_line
    type(text_file_t) :: tf
    type(body_lookup_t) :: lookup
    integer :: i, n, ib
    integer, allocatable :: seen(:)
    character(len=5) :: kw
    character(len=:), allocatable :: model

    call load_text(path, tf)
    step = 0
    time = 0.0_wp
    if (present(steps_line)) steps_line = 0
    n = 0
    do i = 1, tf%n
      if (keyword_of(tf%lines(i)) == 'bdyty') n = n + 1
    end do
    allocate (records(n))
    if (present(bodies)) then
      lookup = body_lookup(bodies)
      allocate (seen(size(bodies)))
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
        if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$bdyty' must be followed by a body line " &
                                                      //"(' RBDY2  number' or ' MAILx  number')")
        n = n + 1
        ib = 0
        associate (ln => tf%lines(i + 1), r => records(n))
          r%src = ln%src
          model = get_word(ln, 2, 6, 'body model')
          if (model /= 'RBDY2' .and. model /= 'MAILx') &
            call line_error(ln, 2, "unknown body model '"//model//"' (supported: RBDY2, MAILx)")
          r%model = model
          r%body = get_int(ln, 9, 15, 'body number')
          if (r%body < 1) call line_error(ln, 9, 'body number must be >= 1, found '//itoa(r%body))
          if (present(bodies)) then
            ib = find_body(lookup, model, r%body)
            if (ib == 0) call line_error(ln, 9, no_such_body(bodies, model, r%body))
            if (seen(ib) > 0) call line_error(ln, 9, model//' body '//itoa(r%body)//' is already given at line ' &
                                              //itoa(seen(ib)))
            seen(ib) = ln%src%line
          end if
        end associate
        i = i + 2
        if (model == 'MAILx') then
          if (ib > 0) then
            call read_mesh_record(tf, i, records(n), size(bodies(ib)%node_coor, 2))
          else
            call read_mesh_record(tf, i, records(n), -1)
          end if
        else
          call read_rigid_record(tf, i, records(n))
        end if
      case ('$$$$$')
        i = i + 1
      case default
        if (tf%lines(i)%text(1:1) == '$') then
          call line_error(tf%lines(i), 1, "unknown keyword '"//trim(field(tf%lines(i), 1, 6))// &
                          "' (expected $steps, $bdyty, $model, $nodty or $$$$$$)")
        else
          call line_error(tf%lines(i), 1, "unexpected line: '"//trim(field(tf%lines(i), 1, 40))//"'")
        end if
      end select
    end do
  end subroutine read_dof_file

  !> '$nodty', the X line and the V line of a rigid body, from line i; i ends after them.
  subroutine read_rigid_record(tf, i, r)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(dof_record_t), intent(inout) :: r
    integer :: k
    if (i > tf%n) call line_error(tf%lines(i - 1), 1, "expected '$nodty' after the body line")
    if (keyword_of(tf%lines(i)) /= 'nodty') call line_error(tf%lines(i), 1, "expected '$nodty' after the body line")
    if (.not. (is_data(tf, i + 1) .and. is_data(tf, i + 2))) &
      call line_error(tf%lines(i), 1, "'$nodty' must be followed by the NO3xx line X(1..3) and the line V(1..3)")
    associate (lx => tf%lines(i + 1), lv => tf%lines(i + 2))
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
  end subroutine read_rigid_record

  !> '$model', ' MECAx', '$nodty' and the node line pairs of a meshed body,
  !> from line i; i ends after them. Node numbers in 1..NNODES (unchecked if
  !> NNODES < 0), each once.
  subroutine read_mesh_record(tf, i, r, nnodes)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(dof_record_t), intent(inout) :: r
    integer, intent(in) :: nnodes
    integer :: n, k, j, node
    integer, allocatable :: given_at(:)
    character(len=:), allocatable :: word

    if (i > tf%n) call line_error(tf%lines(i - 1), 1, "expected '$model' after the MAILx body line")
    if (keyword_of(tf%lines(i)) /= 'model') call line_error(tf%lines(i), 1, "expected '$model' after the MAILx body line")
    if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$model' must be followed by ' MECAx'")
    word = get_word(tf%lines(i + 1), 2, 6, 'physics (MECAx)')
    if (word /= 'MECAx') call line_error(tf%lines(i + 1), 2, "physics '"//word//"' is not supported (MECAx only)")
    i = i + 2
    if (i > tf%n) call line_error(tf%lines(i - 1), 1, "expected '$nodty' after '$model'")
    if (keyword_of(tf%lines(i)) /= 'nodty') call line_error(tf%lines(i), 1, "expected '$nodty' after '$model'")
    i = i + 1
    ! Node line pairs up to the next keyword.
    n = 0
    j = i
    do while (is_data(tf, j))
      n = n + 1
      j = j + 1
    end do
    if (mod(n, 2) /= 0) call line_error(tf%lines(j - 1), 1, 'each NO2xx line X(1..2) is followed by its line ' &
                                        //'V(1..2): found an odd number of lines')
    n = n/2
    allocate (r%nodes(n), r%node_x(2, n), r%node_v(2, n), given_at(max(nnodes, 0)))
    given_at = 0
    do k = 1, n
      associate (lx => tf%lines(i), lv => tf%lines(i + 1))
        word = get_word(lx, 2, 6, 'node type')
        if (word /= 'NO2xx') call line_error(lx, 2, "unknown node type '"//word//"' for MAILx (supported: NO2xx)")
        if (.not. (len(lv%text) > 0 .and. lv%text(1:1) == ' ' .and. field(lv, 2, 6) == '     ')) &
          call line_error(lv, 1, 'expected the line V(1..2) of node '//trim(field(lx, 7, 13))//', found a new ' &
                          //'node line')
        node = get_int(lx, 7, 13, 'node number')
        if (node < 1) call line_error(lx, 7, 'node number must be >= 1, found '//itoa(node))
        if (nnodes >= 0) then
          if (node > nnodes) call line_error(lx, 7, 'node '//itoa(node)//' does not exist (MAILx body '// &
                                             itoa(r%body)//' has '//itoa(nnodes)//' nodes)')
          if (given_at(node) > 0) call line_error(lx, 7, 'node '//itoa(node)//' is already given at line ' &
                                                  //itoa(given_at(node)))
          given_at(node) = lx%src%line
        end if
        r%nodes(k) = node
        do j = 1, 2
          r%node_x(j, k) = get_real(lx, value_col(j), value_col(j) + 13, 'X('//itoa(j)//')')
          r%node_v(j, k) = get_real(lv, value_col(j), value_col(j) + 13, 'V('//itoa(j)//')')
        end do
      end associate
      i = i + 2
    end do
  end subroutine read_mesh_record
end module fracas_read_dof
