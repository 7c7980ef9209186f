!> Reads a whole case directory (CASE_DIR/DATBOX/...) into a deck_t and checks
!> that its files agree with each other. Each error names the file, line and
!> column of the record that refers to something missing.
!>
!> Files: BULK_BEHAV.DAT, BODIES.DAT, TACT_BEHAV.DAT and COMMAND.DAT are
!> required, and MODELS.DAT when BODIES.DAT has meshed (MAILx) bodies;
!> DRV_DOF.DAT, DOF.INI, Vloc_Rloc.INI and GPV.INI are optional (absent:
!> nothing driven, everything at rest, no contact history, no initial
!> Gauss-point values). A rigid deck reads no MODELS.DAT nor GPV.INI.
module fracas_read_deck
  use fracas_kinds, only: wp
  use fracas_errors, only: input_error
  use fracas_deck, only: deck_t
  use fracas_files, only: file_exists, dir_exists
  use fracas_datbox_text, only: itoa, rtoa
  use fracas_read_bodies, only: read_bodies
  use fracas_read_models, only: read_models, check_element_models
  use fracas_read_gpv, only: read_gpv_file
  use fracas_read_bulk_behav, only: read_bulk_behav
  use fracas_read_tact_behav, only: read_tact_behav
  use fracas_read_drv_dof, only: read_drv_dof
  use fracas_read_dof, only: read_dof_file
  use fracas_read_vloc_rloc, only: read_vloc_rloc_file
  use fracas_read_command, only: read_command, apply_command_setting, check_run_control
  implicit none
  private
  public :: read_deck

contains

  !> Read CASE_DIR into DECK. COMMAND_FILE defaults to CASE_DIR/DATBOX/COMMAND.DAT.
  !> SETTINGS are 'keyword=value' overrides of COMMAND.DAT (the driver's
  !> --set options), applied before the run-control checks.
  subroutine read_deck(case_dir, deck, command_file, settings)
    character(len=*), intent(in) :: case_dir
    type(deck_t), intent(out) :: deck
    character(len=*), intent(in), optional :: command_file
    character(len=*), intent(in), optional :: settings(:)
    character(len=:), allocatable :: dat, cmd, path
    integer :: k, dof_line, vloc_line, gpv_line, gpv_step, first_mesh
    real(wp) :: gpv_time

    deck%case_dir = strip_slash(case_dir)
    dat = deck%case_dir//'/DATBOX'
    deck%datbox = dat
    if (.not. dir_exists(dat)) &
      call input_error(dat, 0, 0, 'DATBOX folder not found (a case directory holds DATBOX/BODIES.DAT, ...)')

    call read_bulk_behav(required(dat//'/BULK_BEHAV.DAT'), deck%gravity, deck%materials)
    call read_bodies(required(dat//'/BODIES.DAT'), deck%bodies, deck%materials)

    ! Meshed bodies: their elements' models (MODELS.DAT) and initial Gauss-point values (GPV.INI).
    first_mesh = findloc(deck%bodies%model, 'MAILx', dim=1)
    gpv_line = 0
    if (first_mesh > 0) then
      path = dat//'/MODELS.DAT'
      associate (b => deck%bodies(first_mesh))
        if (.not. file_exists(path)) &
          call input_error(b%src%file, b%src%line, 2, 'MAILx body '//itoa(b%number)//" is meshed: its elements' " &
                           //"models (here '"//trim(b%elements(1)%model)//"') are defined in MODELS.DAT, which " &
                           //'is missing ('//path//')')
      end associate
      call read_models(path, deck%models)
      call check_element_models(deck%bodies, deck%models, deck%materials)
      path = dat//'/GPV.INI'
      if (file_exists(path)) then
        call read_gpv_file(path, gpv_step, gpv_time, deck%gpv_ini, deck%bodies, deck%models, gpv_line)
      else
        allocate (deck%gpv_ini(0))
      end if
    else
      allocate (deck%models(0), deck%gpv_ini(0))
    end if

    call read_tact_behav(required(dat//'/TACT_BEHAV.DAT'), deck%laws, deck%see_rules)

    path = dat//'/DRV_DOF.DAT'
    if (file_exists(path)) then
      call read_drv_dof(path, dat, deck%driven, deck%bodies)
    else
      allocate (deck%driven(0))
    end if

    dof_line = 0
    path = dat//'/DOF.INI'
    if (file_exists(path)) then
      call read_dof_file(path, deck%dof_step, deck%dof_time, deck%dof_ini, deck%bodies, dof_line)
    else
      allocate (deck%dof_ini(0))
    end if

    vloc_line = 0
    path = dat//'/Vloc_Rloc.INI'
    if (file_exists(path)) then
      call read_vloc_rloc_file(path, deck%vloc_step, deck%vloc_time, deck%vloc_ini, deck%bodies, deck%laws, vloc_line)
    else
      allocate (deck%vloc_ini(0))
    end if

    if (present(command_file)) then
      cmd = command_file
    else
      cmd = dat//'/COMMAND.DAT'
    end if
    call read_command(required(cmd), deck%run)
    if (present(settings)) then
      do k = 1, size(settings)
        call apply_command_setting(deck%run, settings(k), '--set')
      end do
      call check_run_control(deck%run, '--set')
    end if

    ! DOF.INI, Vloc_Rloc.INI and GPV.INI describe the same restart state.
    if (dof_line > 0 .and. vloc_line > 0) then
      if (deck%dof_step /= deck%vloc_step .or. &
          abs(deck%dof_time - deck%vloc_time) > 1.0e-3_wp*deck%run%time_step) &
        call input_error(dat//'/Vloc_Rloc.INI', vloc_line, 1, '$steps '//itoa(deck%vloc_step)//' time= ' &
                         //rtoa(deck%vloc_time)//' does not match DOF.INI ($steps '//itoa(deck%dof_step) &
                         //' time= '//rtoa(deck%dof_time)//')')
    end if
    if (dof_line > 0 .and. gpv_line > 0) then
      if (deck%dof_step /= gpv_step .or. abs(deck%dof_time - gpv_time) > 1.0e-3_wp*deck%run%time_step) &
        call input_error(dat//'/GPV.INI', gpv_line, 1, '$steps '//itoa(gpv_step)//' time= '//rtoa(gpv_time) &
                         //' does not match DOF.INI ($steps '//itoa(deck%dof_step)//' time= ' &
                         //rtoa(deck%dof_time)//')')
    end if
  end subroutine read_deck

  !> PATH, or an input error if the file is missing.
  function required(path) result(p)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: p
    if (.not. file_exists(path)) call input_error(path, 0, 0, 'required file not found')
    p = path
  end function required

  function strip_slash(s) result(r)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    r = trim(s)
    do while (len(r) > 1)
      if (r(len(r):len(r)) /= '/') exit
      r = r(1:len(r) - 1)
    end do
  end function strip_slash
end module fracas_read_deck
