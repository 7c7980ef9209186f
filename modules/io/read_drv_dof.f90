!> DRV_DOF.DAT reader: driven velocities ('vlocy') and forces ('force') per
!> body and dof, either as CT, AMP, OMEGA, PHI, RAMPI, RAMP (columns 15-28,
!> 30-43, 45-58, 60-73, 75-88, 90-103) or as 'evolution FILE', a two-column
!> (time, value) file in the DATBOX folder. A rigid body (RBDY2) has one node
!> and 3 dofs; a meshed body (MAILx, after '$model' MECAx) names its node
!> ('$nodty' NO2xx k) before each '$dofty' block, 2 dofs per node.
module fracas_read_drv_dof
  use fracas_kinds, only: wp
  use fracas_deck, only: driven_dof_input_t, body_input_t
  use fracas_read_bodies, only: body_lookup_t, body_lookup, find_body, no_such_body
  use fracas_errors, only: input_error, warn
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, check_line_end, &
                                keyword_of, is_data, get_real, get_int, get_word, itoa, rtoa, &
                                parse_real
  use fracas_files, only: file_exists, dir_exists
  implicit none
  private
  public :: read_drv_dof, read_evolution_file

  integer, parameter :: value_col(6) = [15, 30, 45, 60, 75, 90]
  character(len=5), parameter :: value_name(6) = ['CT   ', 'AMP  ', 'OMEGA', 'PHI  ', 'RAMPI', 'RAMP ']

contains

  !> Read PATH (DRV_DOF.DAT); evolution files are looked up in DATBOX_DIR.
  !> With BODIES, body numbers (within their model) and MAILx node numbers
  !> must exist.
  subroutine read_drv_dof(path, datbox_dir, driven, bodies)
    character(len=*), intent(in) :: path, datbox_dir
    type(driven_dof_input_t), allocatable, intent(out) :: driven(:)
    type(body_input_t), intent(in), optional :: bodies(:)
    type(text_file_t) :: tf
    integer :: i, n, body, node, k, ib, nnod
    type(body_lookup_t) :: lookup
    character(len=5) :: kw
    character(len=5) :: model
    character(len=:), allocatable :: word

    call load_text(path, tf)
    if (present(bodies)) lookup = body_lookup(bodies)
    ! Every data line that is not a body or node line is one driven dof.
    n = 0
    do i = 1, tf%n
      if (keyword_of(tf%lines(i)) == 'dofty') then
        k = i + 1
        do while (is_data(tf, k))
          n = n + 1
          k = k + 1
        end do
      end if
    end do
    allocate (driven(n))
    n = 0
    body = 0
    node = 0
    ib = 0
    model = ''
    i = 1
    do while (i <= tf%n)
      kw = keyword_of(tf%lines(i))
      select case (kw)
      case ('bdyty')
        if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$bdyty' must be followed by a body line " &
                                                      //"(' RBDY2  number' or ' MAILx  number')")
        associate (ln => tf%lines(i + 1))
          model = get_word(ln, 2, 6, 'body model')
          if (model /= 'RBDY2' .and. model /= 'MAILx' .and. model /= 'RBDY3') &
            call line_error(ln, 2, "unknown body model '"//trim(model)//"' (supported: RBDY2, MAILx, RBDY3)")
          body = get_int(ln, 9, 15, 'body number')
          ib = 0
          if (present(bodies)) then
            ib = find_body(lookup, model, body)
            if (ib == 0) call line_error(ln, 9, no_such_body(bodies, model, body))
          end if
        end associate
        node = 0
        i = i + 2
      case ('model')
        if (model /= 'MAILx') call line_error(tf%lines(i), 1, "'$model' belongs to a MAILx body (after its body line)")
        if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$model' must be followed by ' MECAx'")
        word = get_word(tf%lines(i + 1), 2, 6, 'physics (MECAx)')
        if (word /= 'MECAx') call line_error(tf%lines(i + 1), 2, "physics '"//word//"' is not supported " &
                                             //'(Fracas drives MECAx nodes only)')
        i = i + 2
      case ('nodty')
        if (body == 0) call line_error(tf%lines(i), 1, "'$nodty' before any '$bdyty'")
        if (model == 'MAILx') then
          if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$nodty' must be followed by a node " &
                                                        //"line (' NO2xx  number')")
          associate (ln => tf%lines(i + 1))
            word = get_word(ln, 2, 6, 'node type')
            if (word /= 'NO2xx') call line_error(ln, 2, "unknown node type '"//word//"' for MAILx (supported: NO2xx)")
            node = get_int(ln, 7, 13, 'node number')
            if (ib > 0) then
              nnod = size(bodies(ib)%node_coor, 2)
              if (node < 1 .or. node > nnod) call line_error(ln, 7, 'node '//itoa(node)//' does not exist (MAILx body ' &
                                                             //itoa(body)//' has '//itoa(nnod)//' nodes)')
            else if (node < 1) then
              call line_error(ln, 7, 'node number must be >= 1, found '//itoa(node))
            end if
          end associate
          i = i + 2
        else
          if (is_data(tf, i + 1)) then
            ! a rigid body's one node: NO3xx in 2D, NO6xx for RBDY3 (3D, fracas_read_bodies_3d)
            if (get_word(tf%lines(i + 1), 2, 6, 'node type') /= merge('NO6xx', 'NO3xx', model == 'RBDY3')) &
              call line_error(tf%lines(i + 1), 2, "unknown node type '"//trim(field(tf%lines(i + 1), 2, 6))// &
                              "' for "//model//" (supported: "//merge('NO6xx', 'NO3xx', model == 'RBDY3')//")")
            i = i + 1
          end if
          i = i + 1
        end if
      case ('dofty')
        if (body == 0) call line_error(tf%lines(i), 1, "'$dofty' before any '$bdyty'")
        if (model == 'MAILx' .and. node == 0) &
          call line_error(tf%lines(i), 1, "'$dofty' of a MAILx body needs the node it drives: a '$nodty' " &
                          //'line and its NO2xx line before it')
        i = i + 1
        do while (is_data(tf, i))
          n = n + 1
          call read_dof_line(tf%lines(i), model, body, node, datbox_dir, driven(n))
          do k = 1, n - 1
            if (driven(k)%model == model .and. driven(k)%body == body .and. driven(k)%node == node .and. &
                driven(k)%dof == driven(n)%dof .and. driven(k)%kind == driven(n)%kind) &
              call line_error(tf%lines(i), 9, trim(driven(n)%kind)//' of dof '//itoa(driven(n)%dof)//of_what()// &
                              ' is already given at line '//itoa(driven(k)%src%line))
          end do
          i = i + 1
        end do
      case ('$$$$$')
        body = 0
        node = 0
        model = ''
        i = i + 1
      case default
        if (tf%lines(i)%text(1:1) == '$') then
          call line_error(tf%lines(i), 1, "unknown keyword '"//trim(field(tf%lines(i), 1, 6))// &
                          "' (expected $bdyty, $model, $nodty, $dofty or $$$$$$)")
        else
          call line_error(tf%lines(i), 1, "unexpected line (driven dof lines follow '$dofty'): '"// &
                          trim(field(tf%lines(i), 1, 40))//"'")
        end if
      end select
    end do

  contains

    !> " of body 3" (rigid) or " of node 7 of MAILx body 2".
    function of_what() result(s)
      character(len=:), allocatable :: s
      if (model == 'MAILx') then
        s = ' of node '//itoa(node)//' of MAILx body '//itoa(body)
      else
        s = ' of body '//itoa(body)
      end if
    end function of_what
  end subroutine read_drv_dof

  subroutine read_dof_line(ln, model, body, node, datbox_dir, d)
    type(text_line_t), intent(in) :: ln
    character(len=*), intent(in) :: model
    integer, intent(in) :: body, node
    character(len=*), intent(in) :: datbox_dir
    type(driven_dof_input_t), intent(out) :: d
    real(wp) :: v(6)
    integer :: k, shift
    character(len=:), allocatable :: fname

    d%src = ln%src
    d%model = model
    d%body = body
    d%node = node
    d%kind = get_word(ln, 2, 6, "driven dof kind ('vlocy' or 'force')")
    if (d%kind /= 'vlocy' .and. d%kind /= 'force') &
      call line_error(ln, 2, "unknown driven dof kind '"//trim(d%kind)//"' (expected vlocy or force)")
    d%dof = get_int(ln, 9, 13, 'dof index')
    if (model == 'MAILx') then
      if (d%dof < 1 .or. d%dof > 2) call line_error(ln, 9, 'dof index must be 1 or 2 for a MAILx node (x, y), found ' &
                                                    //itoa(d%dof))
    else if (model == 'RBDY3') then
      if (d%dof < 1 .or. d%dof > 6) call line_error(ln, 9, 'dof index must be 1..6 for RBDY3 (translations, ' &
                                                    //'rotations about the principal axes), found '//itoa(d%dof))
    else
      if (d%dof < 1 .or. d%dof > 3) call line_error(ln, 9, 'dof index must be 1, 2 or 3 for RBDY2 (x, y, rotation), ' &
                                                    //'found '//itoa(d%dof))
    end if
    if (adjustl(field(ln, 15, 23)) == 'evolution') then
      d%evolution = .true.
      fname = get_word(ln, 25, max(64, len(ln%text)), 'evolution file name')
      d%evolution_file = fname
      if (.not. file_exists(datbox_dir//'/'//fname)) &
        call line_error(ln, 25, "evolution file '"//datbox_dir//'/'//fname//"' not found")
      if (dir_exists(datbox_dir//'/'//fname)) &
        call line_error(ln, 25, "evolution file '"//datbox_dir//'/'//fname//"' is a directory, not a file")
      call read_evolution_file(datbox_dir//'/'//fname, d%evo_t, d%evo_v)
    else
      ! Old LMGC90 example decks write every value one column to the right
      ! (columns 16-29, 31-44, ...): read them there, and say so.
      shift = 0
      if (len_trim(ln%text) == value_col(6) + 14) then
        if (all([(field(ln, value_col(k), value_col(k)) == ' ' .and. field(ln, value_col(k) + 14, value_col(k) + 14) &
                  /= ' ', k=1, 6)])) shift = 1
      end if
      if (shift == 1) call warn(ln%src%file//':'//itoa(ln%src%line)//': the six values stand one column right '// &
                                'of their fields (columns 16-29, 31-44, ..., 91-104): read there')
      do k = 1, 6
        v(k) = get_real(ln, value_col(k) + shift, value_col(k) + 13 + shift, trim(value_name(k)))
      end do
      d%ct = v(1)
      d%amp = v(2)
      d%omega = v(3)
      d%phi = v(4)
      d%rampi = v(5)
      d%ramp = v(6)
      call check_line_end(ln, value_col(6) + 13 + shift, 'the driven dof line')
    end if
  end subroutine read_dof_line

  !> A free-format two-column file (time, value); '!' and '#' start comments.
  !> Times must be strictly increasing; at least two points.
  subroutine read_evolution_file(path, t, v)
    character(len=*), intent(in) :: path
    real(wp), allocatable, intent(out) :: t(:), v(:)
    type(text_file_t) :: tf
    integer :: i, n, ntok, c1(3), c2(3), k
    character(len=:), allocatable :: s, msg
    real(wp) :: x(2)

    call load_text(path, tf, keep_comments=.true.)
    allocate (t(tf%n), v(tf%n))
    n = 0
    do i = 1, tf%n
      s = tf%lines(i)%text
      k = scan(s, '!#')
      if (k > 0) s = s(1:k - 1)
      if (len_trim(s) == 0) cycle
      call tokens(s, ntok, c1, c2)
      if (ntok /= 2) call line_error(tf%lines(i), 1, 'expected two numbers (time value), found ' &
                                     //itoa(ntok)//merge(' or more', '        ', ntok > 2))
      do k = 1, 2
        if (.not. parse_real(s(c1(k):c2(k)), x(k), msg)) &
          call line_error(tf%lines(i), c1(k), 'expected a real number ('//trim(merge('time ', 'value', k == 1))// &
                          '), '//msg)
      end do
      if (n > 0) then
        if (x(1) <= t(n)) call line_error(tf%lines(i), c1(1), 'times must be strictly increasing: ' &
                                          //rtoa(x(1))//' follows '//rtoa(t(n)))
      end if
      n = n + 1
      t(n) = x(1)
      v(n) = x(2)
    end do
    if (n < 2) call input_error(path, 0, 0, 'an evolution file needs at least two (time, value) lines, found ' &
                                //itoa(n))
    t = t(1:n)
    v = v(1:n)
  end subroutine read_evolution_file

  !> Start and end columns of up to 3 blank/comma separated tokens of s
  !> (ntok counts all of them).
  subroutine tokens(s, ntok, c1, c2)
    character(len=*), intent(in) :: s
    integer, intent(out) :: ntok, c1(3), c2(3)
    integer :: j
    logical :: in_tok, sep
    ntok = 0
    c1 = 0
    c2 = 0
    in_tok = .false.
    do j = 1, len(s)
      sep = s(j:j) == ' ' .or. s(j:j) == ','
      if (.not. sep .and. .not. in_tok) then
        ntok = ntok + 1
        if (ntok <= 3) c1(ntok) = j
      end if
      if (sep .and. in_tok .and. ntok <= 3) c2(ntok) = j - 1
      in_tok = .not. sep
    end do
    if (in_tok .and. ntok <= 3) c2(ntok) = len(s)
  end subroutine tokens
end module fracas_read_drv_dof
