!> BULK_BEHAV.DAT reader: $gravy (gravity vector) and $behav materials
!> (nickname, law name, density 'Umas='). RIGID needs only the density. ELAS
!> (isotropic elasticity: EYng, Epss) and ELAS_PLAS (also von Mises plasticity
!> with linear isotropic hardening: SIG0, K___) are read from their
!> continuation lines (label in columns 41-45, values in 46-59 and 67-80, or
!> an option word from column 46); options Fracas does not run are refused at
!> their line. The continuation lines of other laws are skipped.
module fracas_read_bulk_behav
  use fracas_kinds, only: wp
  use fracas_deck, only: material_input_t, source_t
  use fracas_errors, only: input_error
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, check_line_end, &
                                keyword_of, is_data, get_real, get_word, itoa, rtoa
  implicit none
  private
  public :: read_bulk_behav

contains

  !> gravity_src: the gravity line (for checks of the built scene), the file alone without $gravy.
  subroutine read_bulk_behav(path, gravity, materials, gravity_src)
    character(len=*), intent(in) :: path
    real(wp), intent(out) :: gravity(3)
    type(material_input_t), allocatable, intent(out) :: materials(:)
    type(source_t), intent(out), optional :: gravity_src
    type(text_file_t) :: tf
    integer :: i, nm, k, ngrav
    character(len=5) :: kw

    call load_text(path, tf)
    gravity = 0.0_wp
    if (present(gravity_src)) gravity_src = source_t(path, 0)
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
        if (present(gravity_src)) gravity_src = tf%lines(i + 1)%src
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
        i = i + 2
        select case (materials(nm)%law)
        case ('ELAS', 'ELAS_PLAS')
          call read_elastic_plastic(tf, i, materials(nm))
        case default
          ! Continuation lines (other parameters of the law) are skipped.
          do while (is_data(tf, i))
            i = i + 1
          end do
        end select
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
    if (m%law == 'RIGID' .or. m%law == 'ELAS' .or. m%law == 'ELAS_PLAS' .or. field(ln, 41, 45) == 'Umas=') then
      m%density = get_real(ln, 46, 59, "density 'Umas='")
      ! 0: massless (quasi-static) meshed bodies, as LMGC90; rigid bodies refuse it (scene)
      if (m%density < 0.0_wp) call line_error(ln, 46, "density 'Umas=' must be >= 0, found "//rtoa(m%density))
      if (m%density > 0.0_wp .and. m%density < tiny(1.0_wp)) call line_error(ln, 46, "density 'Umas=' "//rtoa(m%density)// &
        ' is below the smallest normal double ('//rtoa(tiny(1.0_wp))//'): masses would underflow')
      call check_line_end(ln, 59, 'the material line')
    end if
  end subroutine read_material

  !> The continuation lines of an ELAS or ELAS_PLAS material, from line i up
  !> to the next keyword; i ends there. ELAS: 'elas: standard', 'ani_:
  !> isotropic', 'EYng= E  Epss= nu'. ELAS_PLAS adds 'crit: Von-Mises',
  !> 'isoh: linear', 'SIG0= s0  K___= k' (sigma_y = s0 + k p), or 'isoh: Swift',
  !> 'C0__= c  EPS0= e  n___= 1' (sigma_y = c (e + p): Swift's law with n = 1),
  !> 'cinh: none', 'visc: none'.
  subroutine read_elastic_plastic(tf, i, m)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(material_input_t), intent(inout) :: m
    integer, parameter :: n_labels = 9
    character(len=5), parameter :: labels(n_labels) = &
      ['elas:', 'ani_:', 'EYng=', 'crit:', 'isoh:', 'SIG0=', 'cinh:', 'visc:', 'C0__=']
    integer :: seen(n_labels), k, nl
    logical :: plastic, swift
    real(wp) :: c0, eps0, expo
    character(len=5) :: label
    character(len=:), allocatable :: what

    plastic = m%law == 'ELAS_PLAS'
    nl = merge(n_labels, 3, plastic)
    what = trim(m%law)//" material '"//trim(m%nickname)//"'"
    seen = 0
    do while (is_data(tf, i))
      associate (ln => tf%lines(i))
        label = field(ln, 41, 45)
        k = findloc(labels(1:nl), label, dim=1)
        if (k == 0) call line_error(ln, 41, "unknown parameter '"//trim(label)//"' for "//trim(m%law)// &
                                    ' (expected: '//label_list(labels(1:nl))//')')
        if (seen(k) > 0) call line_error(ln, 41, "'"//label//"' is given twice for "//what// &
                                         ' (first at line '//itoa(seen(k))//')')
        seen(k) = ln%src%line
        select case (label)
        case ('elas:')
          call need_option(ln, 'standard', 'elasticity')
        case ('ani_:')
          call need_option(ln, 'isotropic', 'anisotropy')
        case ('EYng=')
          m%young = get_real(ln, 46, 59, "Young's modulus 'EYng='")
          m%poisson = get_real(ln, 67, 80, "Poisson's ratio 'Epss='")
          if (m%young <= 0.0_wp) call line_error(ln, 46, "Young's modulus 'EYng=' must be > 0, found "//rtoa(m%young))
          if (m%poisson <= -1.0_wp .or. m%poisson >= 0.5_wp) &
            call line_error(ln, 67, "Poisson's ratio 'Epss=' must be in (-1, 0.5), found "//rtoa(m%poisson))
        case ('crit:')
          call need_option(ln, 'Von-Mises', 'yield criterion')
        case ('isoh:')
          swift = index(adjustl(field(ln, 46, 60)), 'Swift') == 1
          if (.not. swift) call need_option(ln, 'linear', 'isotropic hardening')
        case ('C0__=')
          ! LMGC90's Swift law sigma_y = C0 (EPS0 + p)^n; n = 1 is linear hardening
          c0 = get_real(ln, 46, 59, "Swift coefficient 'C0__='")
          eps0 = get_real(ln, 67, 80, "Swift strain offset 'EPS0='")
          expo = get_real(ln, 88, 101, "Swift exponent 'n___='")
          if (expo /= 1.0_wp) call line_error(ln, 88, "Swift hardening C0 (EPS0 + p)^n is supported for n = 1 "// &
            "only (linear hardening), found n = "//rtoa(expo))
          m%yield0 = c0 * eps0
          m%hardening = c0
          if (m%yield0 <= 0.0_wp) call line_error(ln, 46, "initial yield stress C0 EPS0 must be > 0, found " &
                                                  //rtoa(m%yield0))
        case ('SIG0=')
          m%yield0 = get_real(ln, 46, 59, "initial yield stress 'SIG0='")
          m%hardening = get_real(ln, 67, 80, "hardening modulus 'K___='")
          if (m%yield0 <= 0.0_wp) call line_error(ln, 46, "initial yield stress 'SIG0=' must be > 0, found " &
                                                  //rtoa(m%yield0))
          if (m%hardening < 0.0_wp) call line_error(ln, 67, "hardening modulus 'K___=' must be >= 0, found " &
                                                    //rtoa(m%hardening))
        case ('cinh:')
          call need_option(ln, 'none', 'kinematic hardening')
        case ('visc:')
          call need_option(ln, 'none', 'viscosity')
        end select
      end associate
      i = i + 1
    end do
    if (seen(3) == 0) call line_error_src(m, what//" needs its elastic constants line 'EYng= ...  Epss= ...'")
    if (plastic .and. seen(6) == 0 .and. seen(9) == 0) &
      call line_error_src(m, what//" needs its hardening line 'SIG0= ...  K___= ...' (after 'isoh: linear') "// &
                          "or 'C0__= ...  EPS0= ...  n___= ...' (after 'isoh: Swift')")

  contains

    !> The option word from column 46 must be WANTED (Fracas runs no other).
    subroutine need_option(ln, wanted, name)
      type(text_line_t), intent(in) :: ln
      character(len=*), intent(in) :: wanted, name
      character(len=:), allocatable :: w
      w = get_word(ln, 46, 70, name//" option after '"//field(ln, 41, 45)//"'")
      if (w /= wanted) call line_error(ln, 46 + verify(field(ln, 46, 70), ' ') - 1, name//" '"//w// &
                                       "' is not supported for "//trim(m%law)//' (Fracas runs: '//wanted//')')
    end subroutine need_option
  end subroutine read_elastic_plastic

  function label_list(labels) result(s)
    character(len=*), intent(in) :: labels(:)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, size(labels)
      if (k > 1) s = s//' '
      s = s//labels(k)
    end do
  end function label_list

  !> An error at the material line of M.
  subroutine line_error_src(m, message)
    type(material_input_t), intent(in) :: m
    character(len=*), intent(in) :: message
    call input_error(m%src%file, m%src%line, 2, message)
  end subroutine line_error_src
end module fracas_read_bulk_behav
