!> MODELS.DAT reader (finite-element models of meshed bodies) and the checks
!> that tie the elements of BODIES.DAT to their model and material.
!>
!> A model: a '$model' line, the nickname line (columns 2-6), then the
!> physics (9-13), element (16-20), first option name (23-27) and value
!> (30-34) on one line, and one more option per line (name 23-27, value
!> 30-34). Fracas runs LMGC90's internal mechanical models: physics MECAx,
!> elements T3xxx, Q4xxx, T6xxx, Q8xxx, Q4P0x, options kine_ (small|large),
!> form_ (UpdtL|TotaL), mater (elas_|J2iso|neoh_), mstrg (lump_|coher), aniso
!> (iso__), isext (no___|MatL_). mater neoh_ (LMGC90's MatLib neo-Hookean law)
!> is finite strain: it needs kine_ large and form_ TotaL, as in LMGC90. The rigid model (element Rxx2D) that pylmgc90
!> writes for rigid bodies is read and kept; no element may use it.
module fracas_read_models
  use fracas_kinds, only: wp
  use fracas_deck, only: model_input_t, body_input_t, material_input_t, model_finite_strain
  use fracas_errors, only: input_error, warn
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, is_blank, &
                                keyword_of, is_data, get_word, itoa
  implicit none
  private
  public :: read_models, check_element_models, model_elements

  !> Elements Fracas runs (model 'finel' column), and the geometry each one
  !> needs in BODIES.DAT (Q4P0x is a Q4 with a constant-pressure field).
  character(len=5), parameter :: model_elements(5) = ['T3xxx', 'Q4xxx', 'T6xxx', 'Q8xxx', 'Q4P0x']
  character(len=5), parameter :: element_geometry(5) = ['T3xxx', 'Q4xxx', 'T6xxx', 'Q8xxx', 'Q4xxx']
  character(len=5), parameter :: rigid_element = 'Rxx2D'

  integer, parameter :: n_options = 7
  character(len=5), parameter :: option_names(n_options) = ['kine_', 'form_', 'mater', 'mstrg', 'aniso', 'isext', &
                                                            'cplth']
  !> Accepted values per option (blank-padded lists). 'form_ xxxxx' is what
  !> pylmgc90 writes for "no formulation" (small strain). isext MatL_: LMGC90's
  !> MatLib computes the same laws as its internal models for the 'mater' values
  !> Fracas runs (elas_: linear isotropic elasticity, J2iso: J2 plasticity with
  !> isotropic hardening, from the same BULK_BEHAV.DAT constants), so a MatLib
  !> model runs as the internal one; neoh_ (MatLib's NEOHOOKEAN, finite strain)
  !> runs as Fracas's neo-Hookean law; other 'mater' values are refused by name.
  !> cplth: coupling with a thermal model, only 'no___' (none).
  character(len=5), parameter :: option_values(3, n_options) = reshape([character(len=5) :: &
    'small', 'large', '     ', 'UpdtL', 'TotaL', 'xxxxx', 'elas_', 'J2iso', 'neoh_', 'lump_', 'coher', '     ', &
    'iso__', '     ', '     ', 'no___', 'MatL_', '     ', 'no___', '     ', '     '], [3, n_options])
  character(len=*), parameter :: option_meaning(n_options) = [character(len=40) :: &
    'kinematics', 'large-strain formulation', 'material model', 'mass matrix storage', 'anisotropy', &
    'external material library', 'thermal coupling']

contains

  !> Read PATH into MODELS.
  subroutine read_models(path, models)
    character(len=*), intent(in) :: path
    type(model_input_t), allocatable, intent(out) :: models(:)
    type(text_file_t) :: tf
    integer :: i, n, k

    call load_text(path, tf)
    n = 0
    do i = 1, tf%n
      if (keyword_of(tf%lines(i)) == 'model') n = n + 1
    end do
    allocate (models(n))
    n = 0
    i = 1
    do while (i <= tf%n)
      if (keyword_of(tf%lines(i)) /= 'model') then
        if (tf%lines(i)%text(1:1) == '$') then
          call line_error(tf%lines(i), 1, "unknown keyword '"//trim(field(tf%lines(i), 1, 6))//"' (expected $model)")
        else
          call line_error(tf%lines(i), 1, "expected '$model' (start of a model), found '"// &
                          trim(field(tf%lines(i), 1, 40))//"'")
        end if
      end if
      n = n + 1
      call read_model(tf, i, models(n))
      do k = 1, n - 1
        if (models(k)%nickname == models(n)%nickname) &
          call input_error(models(n)%src%file, models(n)%src%line, 2, "model '"//trim(models(n)%nickname)// &
                           "' is defined twice (first at line "//itoa(models(k)%src%line)//')')
      end do
    end do
  end subroutine read_models

  !> One model from its '$model' line (tf%lines(i)); i ends at the next keyword.
  subroutine read_model(tf, i, m)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(model_input_t), intent(out) :: m
    integer :: seen(n_options), j
    character(len=:), allocatable :: element

    if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$model' must be followed by the model " &
                                                  //'nickname line (columns 2-6)')
    i = i + 1
    associate (ln => tf%lines(i))
      m%src = ln%src
      m%nickname = get_word(ln, 2, 6, 'model nickname')
      if (.not. is_blank(ln, 7, len(ln%text))) call line_error(ln, 7, "the model nickname line holds only the " &
                                                               //'nickname (columns 2-6)')
    end associate
    if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 2, "model '"//trim(m%nickname)// &
                                                  "' needs its physics and element line (physics in columns " &
                                                  //'9-13, element in 16-20)')
    i = i + 1
    associate (ln => tf%lines(i))
      m%physics = get_word(ln, 9, 13, 'physics (MECAx)')
      if (m%physics /= 'MECAx') call line_error(ln, 9, "physics '"//trim(m%physics)//"' is not supported " &
                                                //'(Fracas runs MECAx models only)')
      element = get_word(ln, 16, 20, 'finite element')
      if (element /= rigid_element .and. findloc(model_elements, element, dim=1) == 0) &
        call line_error(ln, 16, "element '"//element//"' is not supported (supported: "//word_list(model_elements) &
                        //'; '//rigid_element//' for the rigid model)')
      m%element = element
    end associate
    ! Options: the first one on the physics line, then one per line.
    seen = 0
    j = i
    do while (is_data(tf, j))
      if (j > i) then
        if (.not. is_blank(tf%lines(j), 1, 22)) &
          call line_error(tf%lines(j), 1, "expected an option line (option in columns 23-27, value in 30-34) " &
                          //"of model '"//trim(m%nickname)//"', or the next '$model'")
      end if
      if (.not. is_blank(tf%lines(j), 23, len(tf%lines(j)%text))) call read_option(tf%lines(j), m, seen)
      j = j + 1
    end do
    i = j
    if (m%element == rigid_element) then
      if (any(seen > 0)) call input_error(m%src%file, maxval(seen), 23, &
                                          'the rigid model ('//rigid_element//') takes no options')
      return
    end if
    if (m%kinematic == 'large' .and. seen(2) == 0) &
      call input_error(m%src%file, m%src%line, 2, "model '"//trim(m%nickname)//"' has 'kine_ large' but no " &
                       //"'form_' option (UpdtL or TotaL)")
    if (m%material == 'neoh_' .and. (m%kinematic /= 'large' .or. m%formulation /= 'TotaL')) &
      call input_error(m%src%file, merge(seen(3), m%src%line, seen(3) > 0), 23, "model '"//trim(m%nickname)// &
                       "': 'mater neoh_' (neo-Hookean, finite strain) needs 'kine_ large' and 'form_ TotaL' "// &
                       '(LMGC90 runs it so only)')
    ! Read so that LMGC90's decks run, but not what is computed: say so.
    if (m%kinematic == 'large' .and. .not. model_finite_strain(m)) call warn(m%src%file//':'//itoa(seen(1))// &
      ": model '"//trim(m%nickname)// &
      "' asks for large kinematics (kine_ large, form_ "//trim(m%formulation)//"): Fracas runs it with small " &
      //'strain (linear strain about the reference configuration), which agrees with LMGC90 only while '// &
      'rotations and strains stay small (doc/mesh_mechanics.md)')
  end subroutine read_model

  !> One 'option value' pair (columns 23-27 and 30-34) into M.
  subroutine read_option(ln, m, seen)
    type(text_line_t), intent(in) :: ln
    type(model_input_t), intent(inout) :: m
    integer, intent(inout) :: seen(:)
    character(len=:), allocatable :: name, value
    integer :: k
    ! pylmgc90 writes 'cplth_' (6 characters); LMGC90 reads columns 23-27.
    if (field(ln, 23, 29) == 'cplth_') then
      name = 'cplth'
    else
      name = get_word(ln, 23, 27, 'model option name')
    end if
    k = findloc(option_names, name, dim=1)
    if (k == 0) call line_error(ln, 23, "unknown model option '"//name//"' (supported: "//word_list(option_names)//')')
    if (seen(k) > 0) call line_error(ln, 23, "option '"//name//"' is given twice (first at line "//itoa(seen(k))//')')
    seen(k) = ln%src%line
    value = get_word(ln, 30, max(34, len(ln%text)), 'value of option '//name)
    if (all(option_values(:, k) /= value) .or. len(value) > 5) &
      call line_error(ln, 30, trim(option_meaning(k))//" '"//name//' '//value//"' is not supported (Fracas runs: " &
                      //word_list(pack(option_values(:, k), option_values(:, k) /= ''))//')')
    select case (name)
    case ('kine_')
      m%kinematic = value
    case ('form_')
      m%formulation = value
    case ('mater')
      m%material = value
    case ('mstrg')
      m%mass_storage = value
    case ('aniso')
      m%anisotropy = value
    case ('isext')
      m%external = value
    end select
    if (name == 'form_' .and. value == 'xxxxx') m%formulation = ''
  end subroutine read_option

  !> Every element of the meshed bodies names a model of MODELS that suits its
  !> geometry, and a material whose law suits the model's 'mater' option
  !> (elas_: ELAS, J2iso: ELAS_PLAS). A model without 'mater' takes it from the law
  !> of its first element's material, as LMGC90's internal models do (e.g. its
  !> braudel example). Errors at the element's 'model ... behav' line.
  subroutine check_element_models(bodies, models, materials)
    type(body_input_t), intent(in) :: bodies(:)
    type(model_input_t), intent(inout) :: models(:)
    type(material_input_t), intent(in) :: materials(:)
    integer :: ib, ie, im, imat, k
    character(len=:), allocatable :: need

    do ib = 1, size(bodies)
      if (bodies(ib)%model /= 'MAILx') cycle
      do ie = 1, size(bodies(ib)%elements)
        associate (e => bodies(ib)%elements(ie))
          im = 0
          do k = 1, size(models)
            if (models(k)%nickname == e%model) im = k
          end do
          if (im == 0) call input_error(e%model_src%file, e%model_src%line, 23, "model '"//trim(e%model)// &
                                        "' is not defined in MODELS.DAT (defined: "//model_list(models)//')')
          associate (m => models(im))
            if (m%element == rigid_element) &
              call input_error(e%model_src%file, e%model_src%line, 23, "model '"//trim(e%model)//"' is the rigid " &
                               //'model ('//rigid_element//'), not a finite-element model for a '//e%kind)
            k = findloc(model_elements, m%element, dim=1)
            if (element_geometry(k) /= e%kind) &
              call input_error(e%model_src%file, e%model_src%line, 23, "model '"//trim(e%model)//"' (MODELS.DAT " &
                               //'line '//itoa(m%src%line)//') is for '//element_geometry(k)//' elements ('// &
                               m%element//'), not for this '//e%kind)
            imat = 0
            do k = 1, size(materials)
              if (materials(k)%nickname == e%behav) imat = k
            end do
            if (imat == 0) cycle   ! reported by the BODIES.DAT reader
            if (m%material == '') then
              m%material = 'elas_'
              if (materials(imat)%law == 'ELAS_PLAS') m%material = 'J2iso'
            end if
            if (materials(imat)%law == 'ELAS_PLAS' .and. materials(imat)%density == 0.0_wp) &
              call input_error(e%model_src%file, e%model_src%line, 37, "material '"//trim(e%behav)// &
                               "' is massless (Umas = 0) and plastic (ELAS_PLAS): quasi-static plasticity is "// &
                               'not supported (its Newton loop does not converge here); give it a density')
            need = 'ELAS'
            if (m%material == 'J2iso') need = 'ELAS_PLAS'
            if (materials(imat)%law /= need) &
              call input_error(e%model_src%file, e%model_src%line, 37, "material '"//trim(e%behav)//"' ("// &
                               trim(materials(imat)%law)//") does not suit model '"//trim(e%model)// &
                               "': 'mater "//m%material//"' needs an "//need//' material')
          end associate
        end associate
      end do
    end do
  end subroutine check_element_models

  function model_list(models) result(s)
    type(model_input_t), intent(in) :: models(:)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, size(models)
      if (k > 1) s = s//', '
      s = s//trim(models(k)%nickname)
    end do
    if (len(s) == 0) s = 'none'
  end function model_list

  function word_list(words) result(s)
    character(len=*), intent(in) :: words(:)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, size(words)
      if (k > 1) s = s//', '
      s = s//trim(words(k))
    end do
  end function word_list
end module fracas_read_models
