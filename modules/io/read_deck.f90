!> Reads a whole case directory (CASE_DIR/DATBOX/...) into a deck_t and checks
!> that its files agree with each other. Each error names the file, line and
!> column of the record that refers to something missing.
!>
!> Files: BULK_BEHAV.DAT and BODIES.DAT are required, and MODELS.DAT when
!> BODIES.DAT has meshed (MAILx) bodies; TACT_BEHAV.DAT, DRV_DOF.DAT, DOF.INI,
!> Vloc_Rloc.INI, GPV.INI and POSTPRO.DAT are optional (absent: no contact, nothing
!> driven, everything at rest, no contact history, no initial Gauss-point values, no
!> POSTPRO files; a missing TACT_BEHAV.DAT, DOF.INI or Vloc_Rloc.INI is said in a
!> warning). A
!> rigid deck reads no MODELS.DAT nor GPV.INI. The run control comes from
!> COMMAND.DAT (or the file given) and the --set settings; without
!> COMMAND.DAT, from the defaults and --set alone (time_step and
!> number_of_steps or final_time must then be set).
module fracas_read_deck
  use fracas_kinds, only: wp
  use fracas_errors, only: input_error, warn
  use fracas_deck, only: deck_t, run_control_t
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
  use fracas_read_postpro, only: read_postpro
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

    call read_bulk_behav(required(dat//'/BULK_BEHAV.DAT'), deck%gravity, deck%materials, deck%gravity_src)
    call read_bodies(required(dat//'/BODIES.DAT'), deck%bodies, deck%materials)

    ! Meshed bodies: their elements' models (MODELS.DAT) and initial Gauss-point values (GPV.INI).
    first_mesh = 0
    do k = size(deck%bodies), 1, -1
      if (deck%bodies(k)%model == 'MAILx') first_mesh = k
    end do
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

    path = dat//'/TACT_BEHAV.DAT'
    if (file_exists(path)) then
      call read_tact_behav(path, deck%laws, deck%see_rules)
    else
      ! LMGC90's decks without contact (a meshed beam, a bar) come without it
      allocate (deck%laws(0), deck%see_rules(0))
      call warn(path//' not found: no contact laws, the bodies never touch')
    end if

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
      call warn(path//' not found: every body starts at rest in its reference configuration')
    end if

    vloc_line = 0
    path = dat//'/Vloc_Rloc.INI'
    if (file_exists(path)) then
      call read_vloc_rloc_file(path, deck%vloc_step, deck%vloc_time, deck%vloc_ini, deck%bodies, deck%laws, vloc_line)
    else
      allocate (deck%vloc_ini(0))
      call warn(path//' not found: the run starts without contact history (no warm start, '// &
                'cohesive interfaces present at step 0 start glued)')
    end if
    call check_see_rules(deck)
    call warn_unread_files(dat)

    path = dat//'/POSTPRO.DAT'
    if (file_exists(path)) then
      call read_postpro(path, deck%bodies, deck%postpro)
    else
      allocate (deck%postpro(0))
    end if

    allocate (deck%settings(0))
    if (present(settings)) deck%settings = [character(len=256) :: settings]
    if (present(command_file)) then
      cmd = command_file
    else
      cmd = dat//'/COMMAND.DAT'
      ! LMGC90's old decks have a COMMAND.DAT in LMGC90's own command language:
      ! then ours is FRACAS.DAT (fracas-tools command writes it there).
      if (lmgc90_command_file(cmd)) then
        call warn(cmd//' is LMGC90''s command language, not Fracas''s run control: not read; '// &
                  'the run control comes from '//dat//'/FRACAS.DAT if present, --set or --command')
        cmd = dat//'/FRACAS.DAT'
      end if
    end if
    if (file_exists(cmd)) then
      deck%command_file = cmd
      call read_command(cmd, deck%run)
      do k = 1, size(deck%settings)
        call apply_command_setting(deck%run, deck%settings(k), '--set')
      end do
      if (size(deck%settings) > 0) call check_run_control(deck%run, '--set')
    else if (present(command_file)) then
      call input_error(cmd, 0, 0, 'run-control file not found (--command)')
    else
      ! An LMGC90 deck has no COMMAND.DAT: the defaults and --set make the run control.
      deck%command_file = ''
      do k = 1, size(deck%settings)
        call apply_command_setting(deck%run, deck%settings(k), '--set')
      end do
      if (.not. run_is_set(deck%run)) call input_error(cmd, 0, 0, &
        'not found, and no run control given: this deck (an LMGC90 deck?) needs a time step and a number '// &
        'of steps. Give them with --set time_step=H --set number_of_steps=N (or final_time=T; every '// &
        'other setting has a default, see doc/input_reference.md), or a run-control file with '// &
        '--command FILE, or write '//cmd//' with: fracas-tools command CASE_DIR --dt H --steps N')
      call check_run_control(deck%run, '--set')
      call warn('no '//cmd//': run control from --set and the defaults (fracas-tools command writes a COMMAND.DAT)')
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
    call check_plastic_restart(deck)
  end subroutine read_deck

  !> LMGC90 files of physics Fracas does not have: present in DATBOX, they mean
  !> the example's script sets that physics up; Fracas runs the mechanics alone.
  subroutine warn_unread_files(dat)
    character(len=*), intent(in) :: dat
    character(len=*), parameter :: names(3) = [character(len=17) :: 'MP_DEM.DAT', 'PTPT2_NETWORK.DAT', 'RUPTURE.DAT']
    character(len=*), parameter :: what(3) = [character(len=80) :: &
      'LMGC90''s multiphysics parameters (thermal, electrical conduction)', &
      'a network of PTPT2 point-to-point links', 'rupture parameters read by the example''s script']
    integer :: k
    do k = 1, size(names)
      if (file_exists(dat//'/'//trim(names(k)))) call warn(dat//'/'//trim(names(k))//': '//trim(what(k))// &
        ', which Fracas does not have: not read (the mechanics alone is run)')
    end do
  end subroutine warn_unread_files

  !> PATH exists and is written in LMGC90's old command language (upper-case
  !> commands such as 'READ BODIES', 'COMPUTE FREE VELOCITY'), which no Fracas
  !> run-control keyword (one word with '_') looks like.
  logical function lmgc90_command_file(path)
    character(len=*), intent(in) :: path
    character(len=512) :: line
    integer :: unit, ios, n
    lmgc90_command_file = .false.
    if (.not. file_exists(path)) return
    open (newunit=unit, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    n = 0
    do while (n < 200)
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      n = n + 1
      line = adjustl(line)
      if (line(1:11) == 'READ BODIES' .or. line(1:16) == 'READ BEHAVIOURS' .or. line(1:12) == 'COMPUTE MASS' .or. &
          line(1:21) == 'COMPUTE FREE VELOCITY' .or. line(1:12) == 'UPDATE DOF' .or. line(1:10) == 'WRITE LAST') then
        lmgc90_command_file = .true.
        exit
      end if
    end do
    close (unit)
  end function lmgc90_command_file

  !> Warn when DOF.INI displaces an elastoplastic meshed body that GPV.INI gives
  !> no Gauss-point values for: its plastic strain would restart at zero, with
  !> stresses recomputed elastically from the displacement (not the state the
  !> displacement came from). Flags per body first: exploded meshes have a body
  !> (and a DOF.INI record) per element.
  subroutine check_plastic_restart(deck)
    type(deck_t), intent(in) :: deck
    logical, allocatable :: plastic(:), has_gpv(:)   ! per MAILx body number
    integer :: k, ie, n
    n = 0
    do k = 1, size(deck%bodies)
      if (deck%bodies(k)%model == 'MAILx') n = max(n, deck%bodies(k)%number)
    end do
    allocate (plastic(n), has_gpv(n))
    plastic = .false.
    has_gpv = .false.
    do k = 1, size(deck%bodies)
      associate (b => deck%bodies(k))
        if (b%model /= 'MAILx') cycle
        do ie = 1, size(b%elements)
          plastic(b%number) = plastic(b%number) .or. &
            any(deck%models%nickname == b%elements(ie)%model .and. deck%models%material == 'J2iso')
        end do
      end associate
    end do
    do k = 1, size(deck%gpv_ini)
      if (deck%gpv_ini(k)%body >= 1 .and. deck%gpv_ini(k)%body <= n) has_gpv(deck%gpv_ini(k)%body) = .true.
    end do
    do k = 1, size(deck%dof_ini)
      associate (r => deck%dof_ini(k))
        if (r%model /= 'MAILx' .or. .not. allocated(r%node_x)) cycle
        if (r%body < 1 .or. r%body > n) cycle
        if (.not. plastic(r%body) .or. has_gpv(r%body)) cycle
        if (all(r%node_x == 0.0_wp)) cycle
        call warn(trim(r%src%file)//':'//itoa(r%src%line)//': DOF.INI displaces MAILx body '// &
          itoa(r%body)//', which is elastoplastic (J2iso), but GPV.INI gives no Gauss-point values for it: '// &
          'its plastic strain restarts at zero and its stresses are recomputed elastically from the '// &
          'displacement. For an exact restart, give as GPV.INI the GPV.OUT.n written with that DOF.OUT.n')
      end associate
    end do
  end subroutine check_plastic_restart

  !> True when the run control names a time step and a length of run.
  logical function run_is_set(run)
    type(run_control_t), intent(in) :: run
    run_is_set = run%time_step > 0.0_wp .and. (run%number_of_steps > 0 .or. run%final_time > 0.0_wp)
  end function run_is_set

  !> Warn about see rules that can never apply: no contactor of that type has
  !> that colour (a typo in a colour leaves pairs without contact).
  subroutine check_see_rules(deck)
    type(deck_t), intent(in) :: deck
    integer :: k
    do k = 1, size(deck%see_rules)
      associate (r => deck%see_rules(k))
        if (.not. has_tactor(r%cdtac, r%cdcol)) call warn(rule_where(k)//'see rule '//r%cdtac//'/'//r%cdcol// &
          ' - '//r%antac//'/'//r%ancol//': no '//r%cdtac//' contactor has colour '//r%cdcol//': the rule never applies')
        if (.not. has_tactor(r%antac, r%ancol)) call warn(rule_where(k)//'see rule '//r%cdtac//'/'//r%cdcol// &
          ' - '//r%antac//'/'//r%ancol//': no '//r%antac//' contactor has colour '//r%ancol//': the rule never applies')
      end associate
    end do

  contains

    logical function has_tactor(kind, color)
      character(len=*), intent(in) :: kind, color
      integer :: ib, it
      character(len=5) :: k2
      has_tactor = .false.
      do ib = 1, size(deck%bodies)
        if (.not. allocated(deck%bodies(ib)%tactors)) cycle
        do it = 1, size(deck%bodies(ib)%tactors)
          k2 = deck%bodies(ib)%tactors(it)%kind
          if (k2 == 'DISKb') k2 = 'DISKx'     ! detection sees a DISKb as a DISKx
          if (k2 == kind .and. deck%bodies(ib)%tactors(it)%color == color) then
            has_tactor = .true.
            return
          end if
        end do
      end do
    end function has_tactor

    function rule_where(k) result(s)
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      s = ''
      if (allocated(deck%see_rules(k)%src%file)) s = deck%see_rules(k)%src%file//':'// &
                                                      itoa(deck%see_rules(k)%src%line)//': '
    end function rule_where
  end subroutine check_see_rules

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
