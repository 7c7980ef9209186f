!> GPV.INI / GPV.OUT.n reader (Gauss-point values of meshed bodies): the
!> '$steps' header, then per MAILx body '$bdyty' and its number (columns
!> 9-15), per element '$blmty', the element line (geometry in columns 2-6,
!> rank in 7-13), '$model' MECAx and the value lines (D14.7 fields of 14
!> columns from column 1), '$$$$$$' at the end of the body. Per Gauss point
!> LMGC90 writes a stress line and a strain line (xx, yy, xy, zz), and a line
!> of internal values for the J2 model. The empty '$steps 0' file of
!> pylmgc90 gives no records.
module fracas_read_gpv
  use fracas_kinds, only: wp
  use fracas_deck, only: gpv_record_t, body_input_t, model_input_t
  use fracas_read_bodies, only: body_lookup_t, body_lookup, find_body, no_such_body
  use fracas_datbox_text, only: text_file_t, load_text, line_error, field, &
                                keyword_of, is_data, get_real, get_int, get_word, itoa, get_steps
  implicit none
  private
  public :: read_gpv_file

  integer, parameter :: value_width = 14

contains

  !> Read PATH. With BODIES and MODELS, bodies and elements must exist with
  !> the written geometry, and the lines per Gauss point follow the model
  !> (3 for 'mater J2iso', 2 otherwise); without them, a third line is
  !> recognised by its different number of values. STEPS_LINE returns the
  !> line number of '$steps' (0 if absent).
  subroutine read_gpv_file(path, step, time, records, bodies, models, steps_line)
    character(len=*), intent(in) :: path
    integer, intent(out) :: step
    real(wp), intent(out) :: time
    type(gpv_record_t), allocatable, intent(out) :: records(:)
    type(body_input_t), intent(in), optional :: bodies(:)
    type(model_input_t), intent(in), optional :: models(:)
    integer, intent(out), optional :: steps_line
    type(text_file_t) :: tf
    type(body_lookup_t) :: lookup
    integer :: i, n, body, ib
    character(len=5) :: kw
    character(len=:), allocatable :: word

    call load_text(path, tf)
    step = 0
    time = 0.0_wp
    if (present(steps_line)) steps_line = 0
    if (present(bodies)) lookup = body_lookup(bodies)
    n = 0
    do i = 1, tf%n
      if (keyword_of(tf%lines(i)) == 'blmty') n = n + 1
    end do
    allocate (records(n))
    n = 0
    body = 0
    ib = 0
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
                                                      //"(' MAILx  number')")
        associate (ln => tf%lines(i + 1))
          word = get_word(ln, 2, 6, 'body model')
          if (word /= 'MAILx') call line_error(ln, 2, "body model '"//word//"' has no Gauss-point values " &
                                               //'(expected MAILx)')
          body = get_int(ln, 9, 15, 'body number')
          if (body < 1) call line_error(ln, 9, 'body number must be >= 1, found '//itoa(body))
          if (present(bodies)) then
            ib = find_body(lookup, 'MAILx', body)
            if (ib == 0) call line_error(ln, 9, no_such_body(bodies, 'MAILx', body))
          end if
        end associate
        i = i + 2
      case ('blmty')
        if (body == 0) call line_error(tf%lines(i), 1, "'$blmty' before any '$bdyty'")
        n = n + 1
        records(n)%body = body
        if (ib > 0) then
          call read_element_values(tf, i, records(n), bodies(ib), models)
        else
          call read_element_values(tf, i, records(n))
        end if
      case ('$$$$$')
        body = 0
        ib = 0
        i = i + 1
      case default
        if (tf%lines(i)%text(1:1) == '$') then
          call line_error(tf%lines(i), 1, "unknown keyword '"//trim(field(tf%lines(i), 1, 6))// &
                          "' (expected $steps, $bdyty, $blmty, $model or $$$$$$)")
        else
          call line_error(tf%lines(i), 1, "unexpected line: '"//trim(field(tf%lines(i), 1, 40))//"'")
        end if
      end select
    end do
  end subroutine read_gpv_file

  !> One element block from its '$blmty' line (tf%lines(i)); i ends at the
  !> next keyword after its values.
  subroutine read_element_values(tf, i, r, b, models)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(gpv_record_t), intent(inout) :: r
    type(body_input_t), intent(in), optional :: b
    type(model_input_t), intent(in), optional :: models(:)
    integer :: first, nlines, k, j, per_gp, ngp, nv, g, line_in_gp, pos, m
    integer, allocatable :: counts(:)
    character(len=:), allocatable :: word

    if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$blmty' must be followed by an element line " &
                                                  //"(' Q4xxx  rank')")
    associate (ln => tf%lines(i + 1))
      r%src = ln%src
      r%kind = get_word(ln, 2, 6, 'element geometry')
      r%element = get_int(ln, 7, 13, 'element rank')
      if (present(b)) then
        if (r%element < 1 .or. r%element > size(b%elements)) &
          call line_error(ln, 7, 'element '//itoa(r%element)//' does not exist (MAILx body '//itoa(r%body)// &
                          ' has '//itoa(size(b%elements))//' elements)')
        if (b%elements(r%element)%kind /= r%kind) &
          call line_error(ln, 2, 'element '//itoa(r%element)//' of MAILx body '//itoa(r%body)//' is a '// &
                          b%elements(r%element)%kind//' in BODIES.DAT, not a '//r%kind)
      else if (r%element < 1) then
        call line_error(ln, 7, 'element rank must be >= 1, found '//itoa(r%element))
      end if
    end associate
    i = i + 2
    if (i > tf%n) call line_error(tf%lines(i - 1), 1, "expected '$model' after the element line")
    if (keyword_of(tf%lines(i)) /= 'model') call line_error(tf%lines(i), 1, "expected '$model' after the element line")
    if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$model' must be followed by ' MECAx'")
    word = get_word(tf%lines(i + 1), 2, 6, 'physics (MECAx)')
    if (word /= 'MECAx') call line_error(tf%lines(i + 1), 2, "physics '"//word//"' is not supported (MECAx only)")
    i = i + 2
    ! Value lines up to the next keyword: count the values of each.
    first = i
    nlines = 0
    do while (is_data(tf, first + nlines))
      nlines = nlines + 1
    end do
    if (nlines == 0) call line_error(tf%lines(i - 1), 1, 'expected the Gauss-point value lines of element ' &
                                     //itoa(r%element))
    allocate (counts(nlines))
    do k = 1, nlines
      counts(k) = (len(tf%lines(first + k - 1)%text) + value_width - 1)/value_width
    end do
    per_gp = 2
    if (present(b) .and. present(models)) then
      m = 0
      do k = 1, size(models)
        if (models(k)%nickname == b%elements(r%element)%model) m = k
      end do
      if (m > 0) then
        ! J2 writes a line of internals; so does MatLib (isext MatL_), whose
        ! elastic law keeps one internal value (read, not used by elas_).
        if (models(m)%material == 'J2iso' .or. models(m)%external == 'MatL_') per_gp = 3
      end if
    else
      do k = 2, nlines
        if (counts(k) /= counts(1)) then
          per_gp = k
          exit
        end if
      end do
    end if
    if (mod(nlines, per_gp) /= 0) &
      call line_error(tf%lines(first + nlines - 1), 1, itoa(nlines)//' value lines for element '//itoa(r%element)// &
                      ': expected '//itoa(per_gp)//' lines per Gauss point')
    ngp = nlines/per_gp
    nv = sum(counts(1:per_gp))
    do g = 2, ngp
      do line_in_gp = 1, per_gp
        k = (g - 1)*per_gp + line_in_gp
        if (counts(k) /= counts(line_in_gp)) &
          call line_error(tf%lines(first + k - 1), 1, 'Gauss point '//itoa(g)//' line '//itoa(line_in_gp)//' has ' &
                          //itoa(counts(k))//' values, Gauss point 1 had '//itoa(counts(line_in_gp)))
      end do
    end do
    allocate (r%values(nv, ngp))
    do g = 1, ngp
      pos = 0
      do line_in_gp = 1, per_gp
        k = (g - 1)*per_gp + line_in_gp
        do j = 1, counts(k)
          pos = pos + 1
          r%values(pos, g) = get_real(tf%lines(first + k - 1), value_width*(j - 1) + 1, value_width*j, &
                                      'Gauss-point value '//itoa(j))
        end do
      end do
    end do
    i = first + nlines
  end subroutine read_element_values
end module fracas_read_gpv
