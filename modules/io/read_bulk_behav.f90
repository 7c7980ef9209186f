!> BULK_BEHAV.DAT reader: $gravy (gravity vector) and $behav materials
!> (nickname, law name, density 'Umas='). Only the density is used for now;
!> the other parameters of a law (continuation lines) are skipped.
module fracas_read_bulk_behav
  use fracas_kinds, only: wp
  use fracas_deck, only: material_input_t
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, check_line_end, &
                                keyword_of, get_real, get_word, itoa, rtoa
  implicit none
  private
  public :: read_bulk_behav

contains

  subroutine read_bulk_behav(path, gravity, materials)
    character(len=*), intent(in) :: path
    real(wp), intent(out) :: gravity(3)
    type(material_input_t), allocatable, intent(out) :: materials(:)
    type(text_file_t) :: tf
    integer :: i, nm, k, ngrav
    character(len=5) :: kw

    call load_text(path, tf)
    gravity = 0.0_wp
    nm = 0
    do i = 1, tf%n
      if (keyword_of(tf%lines(i)) == 'behav') nm = nm + 1
    end do
    allocate (materials(nm))
    nm = 0
    ngrav = 0
    i = 1
    do while (i <= tf%n)
      kw = keyword_of(tf%lines(i))
      select case (kw)
      case ('gravy')
        ngrav = ngrav + 1
        if (ngrav > 1) call line_error(tf%lines(i), 1, "'$gravy' given twice")
        call need_next(tf, i, "'$gravy' must be followed by the gravity line (grv1= grv2= grv3=)")
        gravity(1) = get_real(tf%lines(i + 1), 25, 38, "gravity x 'grv1='")
        gravity(2) = get_real(tf%lines(i + 1), 46, 59, "gravity y 'grv2='")
        gravity(3) = get_real(tf%lines(i + 1), 67, 80, "gravity z 'grv3='")
        call check_line_end(tf%lines(i + 1), 80, 'the gravity line')
        i = i + 2
      case ('behav')
        call need_next(tf, i, "'$behav' must be followed by a material line (nickname, law, Umas=)")
        nm = nm + 1
        call read_material(tf%lines(i + 1), materials(nm))
        do k = 1, nm - 1
          if (materials(k)%nickname == materials(nm)%nickname) &
            call line_error(tf%lines(i + 1), 2, "material '"//trim(materials(nm)%nickname)// &
                            "' is defined twice (first at line "//itoa(materials(k)%src%line)//')')
        end do
        ! Continuation lines (other parameters of the law) are skipped.
        i = i + 2
        do while (i <= tf%n)
          if (tf%lines(i)%text(1:1) == '$') exit
          i = i + 1
        end do
      case default
        if (tf%lines(i)%text(1:1) == '$') then
          call line_error(tf%lines(i), 1, "unknown keyword '"//trim(field(tf%lines(i), 1, 6))// &
                          "' (expected $gravy or $behav)")
        else
          call line_error(tf%lines(i), 1, "expected '$gravy' or '$behav', found '"// &
                          trim(field(tf%lines(i), 1, 40))//"'")
        end if
      end select
    end do
  end subroutine read_bulk_behav

  subroutine need_next(tf, i, message)
    type(text_file_t), intent(in) :: tf
    integer, intent(in) :: i
    character(len=*), intent(in) :: message
    logical :: ok
    ok = i + 1 <= tf%n
    if (ok) ok = tf%lines(i + 1)%text(1:1) /= '$'
    if (.not. ok) call line_error(tf%lines(i), 1, message)
  end subroutine need_next

  subroutine read_material(ln, m)
    type(text_line_t), intent(in) :: ln
    type(material_input_t), intent(out) :: m
    m%src = ln%src
    m%nickname = get_word(ln, 2, 6, 'material nickname')
    m%law = get_word(ln, 9, 38, 'bulk law name')
    if (m%law == 'RIGID' .or. field(ln, 41, 45) == 'Umas=') then
      m%density = get_real(ln, 46, 59, "density 'Umas='")
      if (m%density <= 0.0_wp) call line_error(ln, 46, "density 'Umas=' must be > 0, found "//rtoa(m%density))
      if (m%density < tiny(1.0_wp)) call line_error(ln, 46, "density 'Umas=' "//rtoa(m%density)// &
        ' is below the smallest normal double ('//rtoa(tiny(1.0_wp))//'): masses would underflow')
      call check_line_end(ln, 59, 'the material line')
    end if
  end subroutine read_material
end module fracas_read_bulk_behav
