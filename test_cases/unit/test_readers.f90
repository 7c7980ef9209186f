!> DATBOX readers and OUTBOX writers against the LMGC90-written decks of
!> ../shared/lmgc90_decks (folder from $FRACAS_LMGC90_DECKS, else the path
!> relative to test_cases/unit). Reference values are copied from the deck
!> files named in the comments (and their case.md); counts were taken with
!> grep on those files.
program test_readers
  use, intrinsic :: iso_c_binding, only: c_int
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_deck, only: deck_t, body_input_t, material_input_t, law_input_t, see_rule_input_t, &
                         driven_dof_input_t, dof_record_t, contact_record_t, run_control_t, model_input_t, &
                         gpv_record_t
  use fracas_datbox_text, only: parse_real, parse_int
  use fracas_strings, only: itoa
  use fracas_read_bodies, only: read_bodies
  use fracas_read_bulk_behav, only: read_bulk_behav
  use fracas_read_tact_behav, only: read_tact_behav, law_param_count
  use fracas_read_drv_dof, only: read_drv_dof
  use fracas_read_dof, only: read_dof_file
  use fracas_read_vloc_rloc, only: read_vloc_rloc_file
  use fracas_read_models, only: read_models, check_element_models
  use fracas_read_gpv, only: read_gpv_file
  use fracas_read_command, only: apply_command_setting, check_run_control
  use fracas_read_deck, only: read_deck
  use fracas_write_outbox, only: write_dof_file, write_vloc_rloc_file, write_gpv_file
  use fracas_files, only: remove_file, dir_exists
  implicit none

  interface
    integer(c_int) function c_getpid() bind(C, name='getpid')
      import :: c_int
    end function c_getpid
  end interface

  character(len=:), allocatable :: decks, tmp
  character(len=18), parameter :: cases(6) = [character(len=18) :: 'disks_box', 'driven_evolution', 'drum', &
                                               'glued_pair_czm', 'mixed_disk_polygon', 'polygons_ground']
  character(len=18), parameter :: mesh_cases(5) = [character(len=18) :: 'mesh_block_drop', 'mesh_disk_on_mesh', &
                                                    'mesh_exploded_beam', 'mesh_plastic_bar', 'mesh_t3_pair_czm']
  integer :: ic, n

  decks = env_or('FRACAS_LMGC90_DECKS', '../../../shared/lmgc90_decks')
  tmp = env_or('TMPDIR', '/tmp')
  tmp = tmp//'/fracas_test_readers_'//itoa(int(c_getpid()))

  call test_numbers()
  call test_command()
  if (dir_exists(decks)) then
    call test_disks_box()
    call test_driven_evolution()
    call test_drum()
    call test_glued_pair_czm()
    call test_mixed_disk_polygon()
    call test_polygons_ground()
    do ic = 1, size(cases)
      do n = 1, 3
        call round_trip_dof(trim(cases(ic)), n)
        call round_trip_vloc(trim(cases(ic)), n)
      end do
    end do
    call test_mesh_t3_pair_czm()
    call test_mesh_block_drop()
    call test_mesh_disk_on_mesh()
    call test_mesh_plastic_bar()
    call test_mesh_exploded_beam()
    call test_mesh_decks()
    do ic = 1, size(mesh_cases)
      do n = 1, 3
        call round_trip_dof(trim(mesh_cases(ic)), n)
        if (mesh_cases(ic) /= 'mesh_plastic_bar') call round_trip_vloc(trim(mesh_cases(ic)), n)   ! no contact law
        call round_trip_gpv(trim(mesh_cases(ic)), n)
      end do
    end do
  else
    ! ctest reports the test skipped on this line (SKIP_REGULAR_EXPRESSION)
    write (*, '(a)') 'SKIPPED: LMGC90 decks not found at '//decks//' (configure with '// &
      '-DFRACAS_LMGC90_DECKS=DIR or set FRACAS_LMGC90_DECKS): the deck readers are not tested'
  end if
  call test_plalp_layout()
  call test_valid_minimal()
  call test_finish()

contains

  function env_or(name, default) result(v)
    character(len=*), intent(in) :: name, default
    character(len=:), allocatable :: v
    integer :: length, stat
    call get_environment_variable(name, length=length, status=stat)
    if (stat /= 0 .or. length == 0) then
      v = default
    else
      allocate (character(len=length) :: v)
      call get_environment_variable(name, value=v)
    end if
  end function env_or

  function dat(case_name, file) result(p)
    character(len=*), intent(in) :: case_name, file
    character(len=:), allocatable :: p
    p = decks//'/'//case_name//'/DATBOX/'//file
  end function dat

  subroutine close_rel(name, got, ref, rel)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: got, ref, rel
    call check_close(name, got, ref, rel*max(abs(ref), tiny(1.0_wp)))
  end subroutine close_rel

  integer function count_kind(bodies, kind) result(c)
    type(body_input_t), intent(in) :: bodies(:)
    character(len=*), intent(in) :: kind
    integer :: b, t
    c = 0
    do b = 1, size(bodies)
      do t = 1, size(bodies(b)%tactors)
        if (bodies(b)%tactors(t)%kind == kind) c = c + 1
      end do
    end do
  end function count_kind

  !> The number parser: exponent letters, blanks, bare-sign exponents, refusals.
  subroutine test_numbers()
    real(wp) :: x
    integer :: i
    character(len=:), allocatable :: msg
    call check_true('parse 0.1000000D+01', parse_real(' 0.1000000D+01', x, msg))
    call check_close('value 0.1000000D+01', x, 1.0_wp, 0.0_wp)
    call check_true('parse 2.5e-3', parse_real('2.5e-3', x, msg))
    call check_close('value 2.5e-3', x, 2.5e-3_wp, 1e-18_wp)
    call check_true('parse -1.5E+02', parse_real('-1.5E+02 ', x, msg))
    call check_close('value -1.5E+02', x, -150.0_wp, 0.0_wp)
    call check_true('parse 3d0', parse_real('3d0', x, msg))
    call check_true('parse .5', parse_real('.5', x, msg))
    call check_true('parse 7', parse_real('7', x, msg))
    call check_true('parse 0.1234567-100 (D14.7 3-digit exponent)', parse_real('0.1234567-100', x, msg))
    call check_close('value 0.1234567-100', x*1.0e100_wp, 0.1234567_wp, 1e-12_wp)
    call check_true('refuse abc', .not. parse_real('abc', x, msg))
    call check_true("message found 'abc'", msg == "found 'abc'")
    call check_true('refuse NaN', .not. parse_real('NaN', x, msg))
    call check_true('NaN message', index(msg, 'NaN') > 0)
    call check_true('refuse Inf', .not. parse_real('-Infinity', x, msg))
    call check_true('refuse 1e400', .not. parse_real('1e400', x, msg))
    call check_true('refuse 1.2.3', .not. parse_real('1.2.3', x, msg))
    call check_true('refuse 1e', .not. parse_real('1e', x, msg))
    call check_true('refuse blanks', .not. parse_real('     ', x, msg))
    call check_true('parse int 42', parse_int('   42', i, msg) .and. i == 42)
    call check_true('refuse int 4.2', .not. parse_int('4.2', i, msg))
  end subroutine test_numbers

  subroutine test_command()
    type(run_control_t) :: run
    call apply_command_setting(run, 'time_step=1e-3', '--set')
    call apply_command_setting(run, 'THETA = 0.6', '--set')
    call apply_command_setting(run, 'nlgs_check qm/16', '--set')
    call apply_command_setting(run, 'final_time=0.25', '--set')
    call check_run_control(run, '--set')
    call check_close('--set time_step', run%time_step, 1.0e-3_wp, 0.0_wp)
    call check_close('--set theta', run%theta, 0.6_wp, 0.0_wp)
    call check_true('--set nlgs_check QM/16', run%nlgs_check == 'QM/16')
    call check_true('final_time 0.25 / 1e-3 -> 250 steps', run%number_of_steps == 250)
    call apply_command_setting(run, 'number_of_steps=10', '--set')
    call check_run_control(run, '--set')
    call check_true('number_of_steps overrides final_time', run%number_of_steps == 10 .and. run%final_time < 0)
    ! Meshed bodies: defaults, then settings.
    call check_true('plane strain by default', run%plane == 'strain' .and. run%linear_solver == 'auto')
    call apply_command_setting(run, 'plane = Stress', '--set')
    call apply_command_setting(run, 'newton_tolerance 1e-8', '--set')
    call apply_command_setting(run, 'newton_max_iterations=30', '--set')
    call apply_command_setting(run, 'linear_solver CHOLMOD', '--set')
    call check_true('--set plane stress', run%plane == 'stress')
    call check_close('--set newton_tolerance', run%newton_tolerance, 1.0e-8_wp, 0.0_wp)
    call check_true('--set newton_max_iterations', run%newton_max_iterations == 30)
    call check_true('--set linear_solver cholmod', run%linear_solver == 'cholmod')
  end subroutine test_command

  subroutine test_disks_box()
    type(body_input_t), allocatable :: bodies(:)
    type(material_input_t), allocatable :: mats(:)
    type(law_input_t), allocatable :: laws(:)
    type(see_rule_input_t), allocatable :: rules(:)
    type(driven_dof_input_t), allocatable :: drv(:)
    type(dof_record_t), allocatable :: dof(:)
    real(wp) :: g(3), t
    integer :: step

    ! BULK_BEHAV.DAT: grv2=-9.8100000e+00; STONE Umas= 2.6000000e+03, TDURx 1.0000000e+03.
    call read_bulk_behav(dat('disks_box', 'BULK_BEHAV.DAT'), g, mats)
    call check_close('disks_box gravity y', g(2), -9.81_wp, 1e-12_wp)
    call check_true('disks_box 2 materials', size(mats) == 2)
    call check_true('disks_box material 1 STONE RIGID', mats(1)%nickname == 'STONE' .and. mats(1)%law == 'RIGID')
    call check_close('disks_box STONE density', mats(1)%density, 2600.0_wp, 1e-9_wp)
    ! BODIES.DAT: 154 bodies, 150 DISKx then 4 JONCx walls; body 1 byrd= 1.4170220E-02,
    ! coo1= 3.0212789E-02; last wall axe1= 4.7000000E-01 axe2= 1.0000000E-02 (grep JONCx).
    call read_bodies(dat('disks_box', 'BODIES.DAT'), bodies, mats)
    call check_true('disks_box 154 bodies', size(bodies) == 154)
    call check_true('disks_box 150 DISKx', count_kind(bodies, 'DISKx') == 150)
    call check_true('disks_box 4 JONCx', count_kind(bodies, 'JONCx') == 4)
    call check_true('disks_box body numbers by order', bodies(154)%number == 154)
    call close_rel('disks_box body 1 radius', bodies(1)%tactors(1)%radius, 1.4170220e-2_wp, 1e-12_wp)
    call close_rel('disks_box body 1 x', bodies(1)%coor(1), 3.0212789e-2_wp, 1e-12_wp)
    call close_rel('disks_box body 1 avrd', bodies(1)%avrd, 1.4170220e-2_wp, 1e-12_wp)
    call check_true('disks_box body 1 material STONE', bodies(1)%behav == 'STONE')
    call check_true('disks_box body 1 colour BLEUx', bodies(1)%tactors(1)%color == 'BLEUx')
    call close_rel('disks_box wall ax1', bodies(154)%tactors(1)%ax1, 0.47_wp, 1e-12_wp)
    call close_rel('disks_box wall ax2', bodies(154)%tactors(1)%ax2, 0.01_wp, 1e-12_wp)
    ! TACT_BEHAV.DAT: iqsdd IQS_CLB fric 0.3, iqsdw IQS_CLB fric 0.5; two $seety, alert 1e-3.
    call read_tact_behav(dat('disks_box', 'TACT_BEHAV.DAT'), laws, rules)
    call check_true('disks_box 2 laws', size(laws) == 2)
    call check_true('disks_box law 1 iqsdd IQS_CLB', laws(1)%nickname == 'iqsdd' .and. laws(1)%name == 'IQS_CLB')
    call check_close('disks_box fric 1', laws(1)%params(1), 0.3_wp, 1e-15_wp)
    call check_close('disks_box fric 2', laws(2)%params(1), 0.5_wp, 1e-15_wp)
    call check_true('disks_box label fric=', laws(1)%param_labels(1) == 'fric=')
    call check_true('disks_box 2 see rules', size(rules) == 2)
    call check_close('disks_box alert', rules(1)%alert, 1.0e-3_wp, 1e-18_wp)
    call check_true('disks_box rule 2 DISKx-JONCx WALLx iqsdw', rules(2)%antac == 'JONCx' .and. &
                    rules(2)%ancol == 'WALLx' .and. rules(2)%behav == 'iqsdw')
    call check_close('disks_box no global alert', rules(1)%global_alert, 0.0_wp, 0.0_wp)
    ! DRV_DOF.DAT: bodies 151-154, vlocy 1..3 with RAMPI 1: 12 lines.
    call read_drv_dof(dat('disks_box', 'DRV_DOF.DAT'), decks//'/disks_box/DATBOX', drv, bodies)
    call check_true('disks_box 12 driven dofs', size(drv) == 12)
    call check_true('disks_box first driven body 151 dof 1 vlocy', drv(1)%body == 151 .and. drv(1)%dof == 1 &
                    .and. drv(1)%kind == 'vlocy')
    call check_close('disks_box RAMPI', drv(1)%rampi, 1.0_wp, 0.0_wp)
    ! DOF.INI: 152 bodies; body 1 V(1)= 2.7027822e-01, V(3)= 4.4864945e+00; body 2 V(1)=-4.6004131e-02.
    call read_dof_file(dat('disks_box', 'DOF.INI'), step, t, dof, bodies)
    call check_true('disks_box DOF.INI step 0', step == 0)
    call check_true('disks_box DOF.INI 152 records', size(dof) == 152)
    call close_rel('disks_box DOF.INI body 1 V(1)', dof(1)%v(1), 2.7027822e-1_wp, 1e-12_wp)
    call close_rel('disks_box DOF.INI body 1 V(3)', dof(1)%v(3), 4.4864945_wp, 1e-12_wp)
    call close_rel('disks_box DOF.INI body 2 V(1)', dof(2)%v(1), -4.6004131e-2_wp, 1e-12_wp)
  end subroutine test_disks_box

  subroutine test_driven_evolution()
    type(driven_dof_input_t), allocatable :: drv(:)
    type(law_input_t), allocatable :: laws(:)
    type(see_rule_input_t), allocatable :: rules(:)
    ! DRV_DOF.DAT: body 1 'force 1 evolution force_x.dat', 'vlocy 3' RAMPI 1; body 2 vlocy 1-3.
    ! force_x.dat: (0,0) (0.2,0) (0.6,300) (1,300) (1.2,0) (3,0).
    call read_drv_dof(dat('driven_evolution', 'DRV_DOF.DAT'), decks//'/driven_evolution/DATBOX', drv)
    call check_true('driven_evolution 5 driven dofs', size(drv) == 5)
    call check_true('driven_evolution force dof 1 evolution', drv(1)%kind == 'force' .and. drv(1)%dof == 1 &
                    .and. drv(1)%evolution)
    call check_true('driven_evolution file name', drv(1)%evolution_file == 'force_x.dat')
    call check_true('driven_evolution 6 points', size(drv(1)%evo_t) == 6)
    call check_close('driven_evolution t(3)', drv(1)%evo_t(3), 0.6_wp, 1e-15_wp)
    call check_close('driven_evolution v(3)', drv(1)%evo_v(3), 300.0_wp, 0.0_wp)
    call check_close('driven_evolution t(6)', drv(1)%evo_t(6), 3.0_wp, 0.0_wp)
    call check_true('driven_evolution vlocy 3 of body 1', drv(2)%body == 1 .and. drv(2)%dof == 3 .and. &
                    .not. drv(2)%evolution)
    ! TACT_BEHAV.DAT: iqsds IQS_DS_CLB dyfr= 4.0000000e-01 stfr= 5.0000000e-01, alert 1e-2.
    call read_tact_behav(dat('driven_evolution', 'TACT_BEHAV.DAT'), laws, rules)
    call check_true('IQS_DS_CLB has 2 parameters', size(laws(1)%params) == 2 .and. law_param_count('IQS_DS_CLB') == 2)
    call check_close('IQS_DS_CLB dfric', laws(1)%params(1), 0.4_wp, 1e-15_wp)
    call check_close('IQS_DS_CLB sfric', laws(1)%params(2), 0.5_wp, 1e-15_wp)
    call check_close('driven_evolution alert', rules(1)%alert, 1.0e-2_wp, 1e-17_wp)
  end subroutine test_driven_evolution

  subroutine test_drum()
    type(body_input_t), allocatable :: bodies(:)
    type(driven_dof_input_t), allocatable :: drv(:)
    ! BODIES.DAT: 97 DISKx and the drum, body 98, xKSID byrd= 1.1000000E-01.
    ! DRV_DOF.DAT: body 98 vlocy 3 CT 1 RAMPI 1.
    call read_bodies(dat('drum', 'BODIES.DAT'), bodies)
    call check_true('drum 98 bodies', size(bodies) == 98)
    call check_true('drum 1 xKSID', count_kind(bodies, 'xKSID') == 1 .and. bodies(98)%tactors(1)%kind == 'xKSID')
    call close_rel('drum xKSID radius', bodies(98)%tactors(1)%radius, 0.11_wp, 1e-12_wp)
    call read_drv_dof(dat('drum', 'DRV_DOF.DAT'), decks//'/drum/DATBOX', drv, bodies)
    call check_true('drum 3 driven dofs of body 98', size(drv) == 3 .and. all(drv%body == 98))
    call check_close('drum vlocy 3 CT', drv(3)%ct, 1.0_wp, 0.0_wp)
  end subroutine test_drum

  subroutine test_glued_pair_czm()
    type(body_input_t), allocatable :: bodies(:)
    type(law_input_t), allocatable :: laws(:)
    type(see_rule_input_t), allocatable :: rules(:)
    type(material_input_t), allocatable :: mats(:)
    type(contact_record_t), allocatable :: c(:)
    real(wp) :: g(3), t
    integer :: step
    ! TACT_BEHAV.DAT: macz1 IQS_MAC_CZM dyfr 0.73 stfr 0.73 / cn 1e10 ct 1e11 / b 0 w 40.
    call read_tact_behav(dat('glued_pair_czm', 'TACT_BEHAV.DAT'), laws, rules)
    call check_true('IQS_MAC_CZM 6 parameters', size(laws(1)%params) == 6)
    call check_close('IQS_MAC_CZM dfric', laws(1)%params(1), 0.73_wp, 1e-15_wp)
    call close_rel('IQS_MAC_CZM cn', laws(1)%params(3), 1.0e10_wp, 1e-15_wp)
    call close_rel('IQS_MAC_CZM ct', laws(1)%params(4), 1.0e11_wp, 1e-15_wp)
    call check_close('IQS_MAC_CZM w', laws(1)%params(6), 40.0_wp, 0.0_wp)
    call check_true('IQS_MAC_CZM labels', laws(1)%param_labels(3) == 'cn  =' .and. laws(1)%param_labels(6) == 'w   =')
    ! BULK_BEHAV.DAT: gravity 0; BODIES.DAT: two 4-vertex POLYG, first vertex (-0.5, -0.5).
    call read_bulk_behav(dat('glued_pair_czm', 'BULK_BEHAV.DAT'), g, mats)
    call check_close('glued gravity 0', maxval(abs(g)), 0.0_wp, 0.0_wp)
    call read_bodies(dat('glued_pair_czm', 'BODIES.DAT'), bodies, mats)
    call check_true('glued 2 POLYG of 4 vertices', count_kind(bodies, 'POLYG') == 2 .and. &
                    size(bodies(2)%tactors(1)%vertices, 2) == 4)
    call check_close('glued vertex 1 x', bodies(1)%tactors(1)%vertices(1, 1), -0.5_wp, 0.0_wp)
    call check_close('glued body 2 y', bodies(2)%coor(2), 1.0_wp, 0.0_wp)
    ! OUTBOX/Vloc_Rloc.OUT.1 (case.md): step 30, 2 PLPLx, CDVER 2 / ANSEG 3, Cstck,
    ! rln/H -0.1525000D+06, internals 0.5 0 3.05e-5 1 -99.
    call read_vloc_rloc_file(decks//'/glued_pair_czm/OUTBOX/Vloc_Rloc.OUT.1', step, t, c, bodies, laws)
    call check_true('glued Vloc step 30', step == 30)
    call close_rel('glued Vloc time', t, 3.0e-3_wp, 1e-12_wp)
    call check_true('glued 2 PLPLx', size(c) == 2 .and. all(c%inter == 'PLPLx'))
    call check_true('glued CDVER 2 ANSEG 3', c(1)%cdver == 2 .and. c(1)%anseg == 3)
    call check_true('glued bodies 2 on 1, status Cstck, iadj 1', c(1)%icdbdy == 2 .and. c(1)%ianbdy == 1 .and. &
                    c(1)%status == 'Cstck' .and. c(1)%iadj == 1)
    call close_rel('glued rln', c(1)%rln, -1.525e5_wp, 1e-12_wp)
    call check_true('glued 5 internals', size(c(1)%internals) == 5)
    call check_close('glued L', c(1)%internals(1), 0.5_wp, 0.0_wp)
    call close_rel('glued un', c(1)%internals(3), 3.05e-5_wp, 1e-12_wp)
    call check_close('glued TPSini', c(1)%internals(5), -99.0_wp, 0.0_wp)
    call check_true('glued geometry lines', c(1)%has_geometry)
    call check_close('glued n(2)', c(1)%normal(2), 1.0_wp, 0.0_wp)
  end subroutine test_glued_pair_czm

  subroutine test_mixed_disk_polygon()
    type(body_input_t), allocatable :: bodies(:)
    type(law_input_t), allocatable :: laws(:)
    type(see_rule_input_t), allocatable :: rules(:)
    type(dof_record_t), allocatable :: dof(:)
    type(contact_record_t), allocatable :: c(:)
    real(wp) :: t
    integer :: step, k
    logical :: dkpl, pljc
    ! BODIES.DAT: 16 bodies, 7 DISKx, 6 POLYG, 3 JONCx.
    call read_bodies(dat('mixed_disk_polygon', 'BODIES.DAT'), bodies)
    call check_true('mixed 16 bodies', size(bodies) == 16)
    call check_true('mixed 7 DISKx 6 POLYG 3 JONCx', count_kind(bodies, 'DISKx') == 7 .and. &
                    count_kind(bodies, 'POLYG') == 6 .and. count_kind(bodies, 'JONCx') == 3)
    ! TACT_BEHAV.DAT: 4 laws, rstcw RST_CLB rstn 0.3 rstt 0 / fric 0.5; 5 $seety.
    call read_tact_behav(dat('mixed_disk_polygon', 'TACT_BEHAV.DAT'), laws, rules)
    call check_true('mixed 4 laws 5 rules', size(laws) == 4 .and. size(rules) == 5)
    call check_true('mixed law 4 RST_CLB', laws(4)%name == 'RST_CLB' .and. size(laws(4)%params) == 3)
    call check_close('RST_CLB restn', laws(4)%params(1), 0.3_wp, 1e-15_wp)
    call check_close('RST_CLB fric', laws(4)%params(3), 0.5_wp, 1e-15_wp)
    ! DOF.INI: body 1 X(3)= 7.8539816e-01 (rotated square), body 15 X(3)=-1.5707963e+00.
    call read_dof_file(dat('mixed_disk_polygon', 'DOF.INI'), step, t, dof, bodies)
    call check_true('mixed DOF.INI 3 records', size(dof) == 3)
    call close_rel('mixed body 1 rotation', dof(1)%x(3), 7.8539816e-1_wp, 1e-12_wp)
    call check_true('mixed second record is body 15', dof(2)%body == 15)
    ! OUTBOX/Vloc_Rloc.OUT.1: DKPLx (CDVER 0) and PLJCx records; 10 records.
    call read_vloc_rloc_file(decks//'/mixed_disk_polygon/OUTBOX/Vloc_Rloc.OUT.1', step, t, c, bodies, laws)
    call check_true('mixed Vloc.1 10 records', size(c) == 10)
    dkpl = .false.
    pljc = .false.
    do k = 1, size(c)
      if (c(k)%inter == 'DKPLx') dkpl = .true.
      if (c(k)%inter == 'PLJCx') then
        if (.not. pljc) call check_true('mixed first PLJCx: POLYG 1 of body 1, CDVER 4, on body 14, slifw', &
                                        c(k)%icdbdy == 1 .and. c(k)%cdver == 4 .and. c(k)%ianbdy == 14 .and. &
                                        c(k)%status == 'slifw')
        pljc = .true.
      end if
    end do
    call check_true('mixed has DKPLx and PLJCx', dkpl .and. pljc)
  end subroutine test_mixed_disk_polygon

  subroutine test_polygons_ground()
    type(body_input_t), allocatable :: bodies(:)
    ! BODIES.DAT: 20 POLYG (4-7 vertices) and one JONCx ground.
    call read_bodies(dat('polygons_ground', 'BODIES.DAT'), bodies)
    call check_true('polygons_ground 21 bodies', size(bodies) == 21)
    call check_true('polygons_ground 20 POLYG 1 JONCx', count_kind(bodies, 'POLYG') == 20 .and. &
                    count_kind(bodies, 'JONCx') == 1)
  end subroutine test_polygons_ground

  !> mesh_t3_pair_czm: two MAILx bodies of 16 T3, an ALpxx polyline of 4
  !> segments on body 1 and 8 CLxxx points on body 2 (BODIES.DAT), the MODELS.DAT
  !> T3 model, the ELAS material, DRV_DOF.DAT on mesh nodes, CLALp records.
  subroutine test_mesh_t3_pair_czm()
    type(body_input_t), allocatable :: bodies(:)
    type(material_input_t), allocatable :: mats(:)
    type(model_input_t), allocatable :: models(:)
    type(driven_dof_input_t), allocatable :: drv(:)
    type(contact_record_t), allocatable :: c(:)
    type(law_input_t), allocatable :: laws(:)
    type(see_rule_input_t), allocatable :: rules(:)
    real(wp) :: g(3), t
    integer :: step
    ! BULK_BEHAV.DAT: STONE ELAS Umas= 2.5e3, EYng= 1.0e10, Epss= 2.5e-1.
    call read_bulk_behav(dat('mesh_t3_pair_czm', 'BULK_BEHAV.DAT'), g, mats)
    call check_true('t3 pair: STONE ELAS', size(mats) == 1 .and. mats(1)%law == 'ELAS')
    call close_rel('t3 pair: STONE density', mats(1)%density, 2500.0_wp, 1e-12_wp)
    call close_rel('t3 pair: STONE E', mats(1)%young, 1.0e10_wp, 1e-12_wp)
    call close_rel('t3 pair: STONE nu', mats(1)%poisson, 0.25_wp, 1e-12_wp)
    ! BODIES.DAT: MAILx 1 and 2, 16 T3xxx and 15 NO2xx each; body 1 element 1 nodes 1 4 2,
    ! model M2DT3 behav STONE; body 1 node 15 (0.1, 0.05), body 2 node 15 (0.1, 0.1).
    call read_bodies(dat('mesh_t3_pair_czm', 'BODIES.DAT'), bodies, mats)
    call check_true('t3 pair: 2 MAILx bodies numbered 1, 2', size(bodies) == 2 .and. all(bodies%model == 'MAILx') &
                    .and. bodies(1)%number == 1 .and. bodies(2)%number == 2)
    call check_true('t3 pair: 16 T3 elements, 15 nodes', size(bodies(1)%elements) == 16 .and. &
                    size(bodies(2)%node_coor, 2) == 15 .and. all(bodies(2)%elements%kind == 'T3xxx'))
    call check_true('t3 pair: element 1 nodes 1 4 2', all(bodies(1)%elements(1)%nodes == [1, 4, 2]))
    call check_true('t3 pair: element model M2DT3 behav STONE', bodies(1)%elements(16)%model == 'M2DT3' .and. &
                    bodies(1)%elements(16)%behav == 'STONE')
    call close_rel('t3 pair: body 1 node 15 x', bodies(1)%node_coor(1, 15), 0.1_wp, 1e-12_wp)
    call close_rel('t3 pair: body 2 node 15 y', bodies(2)%node_coor(2, 15), 0.1_wp, 1e-12_wp)
    ! One ALpxx line and 3 '+' lines: one polyline 3-6-9-12-15.
    call check_true('t3 pair: one ALpxx polyline 3-6-9-12-15', size(bodies(1)%tactors) == 1 .and. &
                    bodies(1)%tactors(1)%kind == 'ALpxx' .and. all(bodies(1)%tactors(1)%nodes == [3, 6, 9, 12, 15]))
    ! 8 CLxxx lines (1 + 7 '+'): 8 contactors; first 4-1 at 0.25, second 4-1 at 0.75, last 13-10 at 0.75.
    call check_true('t3 pair: 8 CLxxx contactors', size(bodies(2)%tactors) == 8 .and. &
                    all(bodies(2)%tactors%kind == 'CLxxx') .and. all(bodies(2)%tactors%color == 'GLUEx'))
    call check_true('t3 pair: CLxxx 1 on edge 4-1', all(bodies(2)%tactors(1)%nodes == [4, 1]))
    call check_close('t3 pair: CLxxx 1 apab', bodies(2)%tactors(1)%apab, 0.25_wp, 0.0_wp)
    call check_close('t3 pair: CLxxx 2 apab', bodies(2)%tactors(2)%apab, 0.75_wp, 0.0_wp)
    call check_true('t3 pair: CLxxx 8 on edge 13-10', all(bodies(2)%tactors(8)%nodes == [13, 10]))
    ! MODELS.DAT: M2DT3 MECAx T3xxx, iso__, no___, small, lump_, elas_.
    call read_models(dat('mesh_t3_pair_czm', 'MODELS.DAT'), models)
    call check_true('t3 pair: model M2DT3', size(models) == 1 .and. models(1)%nickname == 'M2DT3' .and. &
                    models(1)%element == 'T3xxx' .and. models(1)%kinematic == 'small' .and. &
                    models(1)%material == 'elas_' .and. models(1)%external == 'no___' .and. &
                    models(1)%mass_storage == 'lump_')
    call check_element_models(bodies, models, mats)
    ! DRV_DOF.DAT: MAILx 1 nodes 1 4 7 10 13 and MAILx 2 nodes 3 6 9 12 15, vlocy 1 and 2: 20 lines;
    ! MAILx 2 node 3 vlocy 2: CT 1e-2, RAMPI 0, RAMP 5e3.
    call read_drv_dof(dat('mesh_t3_pair_czm', 'DRV_DOF.DAT'), decks//'/mesh_t3_pair_czm/DATBOX', drv, bodies)
    call check_true('t3 pair: 20 driven dofs on MAILx nodes', size(drv) == 20 .and. all(drv%model == 'MAILx'))
    call check_true('t3 pair: driven 1 is MAILx 1 node 1 dof 1', drv(1)%body == 1 .and. drv(1)%node == 1 .and. &
                    drv(1)%dof == 1)
    call check_true('t3 pair: driven 12 is MAILx 2 node 3 dof 2', drv(12)%body == 2 .and. drv(12)%node == 3 .and. &
                    drv(12)%dof == 2)
    call close_rel('t3 pair: driven 12 CT', drv(12)%ct, 1.0e-2_wp, 1e-12_wp)
    call close_rel('t3 pair: driven 12 RAMP', drv(12)%ramp, 5.0e3_wp, 1e-12_wp)
    ! OUTBOX/Vloc_Rloc.OUT.1: 8 CLALp at step 100; record 1 MAILx 2 CLxxx 1 on MAILx 1 ALpxx 1
    ! segment 1, Cstck, rln/H -0.5925286D+04, internals 0.1249982D-01 ... -0.99D+02.
    call read_tact_behav(dat('mesh_t3_pair_czm', 'TACT_BEHAV.DAT'), laws, rules)
    call read_vloc_rloc_file(decks//'/mesh_t3_pair_czm/OUTBOX/Vloc_Rloc.OUT.1', step, t, c, bodies, laws)
    call check_true('t3 pair: 8 CLALp at step 100', step == 100 .and. size(c) == 8 .and. all(c%inter == 'CLALp'))
    call check_true('t3 pair: CLALp 1 ids', c(1)%cdbdy == 'MAILx' .and. c(1)%icdbdy == 2 .and. c(1)%icdtac == 1 .and. &
                    c(1)%anbdy == 'MAILx' .and. c(1)%ianbdy == 1 .and. c(1)%iantac == 1 .and. c(1)%anseg == 1 .and. &
                    c(1)%status == 'Cstck' .and. c(1)%iadj == 1)
    call close_rel('t3 pair: CLALp 1 rln', c(1)%rln, -0.5925286e4_wp, 1e-12_wp)
    call check_true('t3 pair: CLALp 1 has 5 internals', size(c(1)%internals) == 5)
    call close_rel('t3 pair: CLALp 1 L', c(1)%internals(1), 0.1249982e-1_wp, 1e-12_wp)
    call check_close('t3 pair: CLALp 1 TPSini', c(1)%internals(5), -99.0_wp, 0.0_wp)
  end subroutine test_mesh_t3_pair_czm

  !> mesh_block_drop: RBDY2 1 (a JONCx ground) then MAILx 1 (32 Q4, 45 nodes,
  !> 9 CLxxx), numbered per model; MODELS.DAT with the rigid model; DOF.INI of
  !> the mesh; CLJCx records with the one internal (contact length).
  subroutine test_mesh_block_drop()
    type(body_input_t), allocatable :: bodies(:)
    type(material_input_t), allocatable :: mats(:)
    type(model_input_t), allocatable :: models(:)
    type(dof_record_t), allocatable :: dof(:)
    type(contact_record_t), allocatable :: c(:)
    type(gpv_record_t), allocatable :: gpv(:)
    real(wp) :: g(3), t
    integer :: step
    call read_bulk_behav(dat('mesh_block_drop', 'BULK_BEHAV.DAT'), g, mats)
    ! BLOCK ELAS: Umas 2e3, EYng 1e9, Epss 0.3; TDURx RIGID 1e3.
    call check_true('block drop: BLOCK ELAS, TDURx RIGID', mats(1)%law == 'ELAS' .and. mats(2)%law == 'RIGID')
    call close_rel('block drop: BLOCK E', mats(1)%young, 1.0e9_wp, 1e-12_wp)
    call read_bodies(dat('mesh_block_drop', 'BODIES.DAT'), bodies, mats)
    call check_true('block drop: RBDY2 1 then MAILx 1', size(bodies) == 2 .and. bodies(1)%model == 'RBDY2' .and. &
                    bodies(1)%number == 1 .and. bodies(2)%model == 'MAILx' .and. bodies(2)%number == 1)
    call check_true('block drop: 32 Q4, 45 nodes, 9 CLxxx', size(bodies(2)%elements) == 32 .and. &
                    all(bodies(2)%elements%kind == 'Q4xxx') .and. size(bodies(2)%node_coor, 2) == 45 .and. &
                    size(bodies(2)%tactors) == 9)
    ! Q4xxx 1 nodes 1 6 7 2; CLxxx 1 noda 6 nodb 1 apab 0, CLxxx 2 the same edge at apab 1.
    call check_true('block drop: Q4 1 nodes 1 6 7 2', all(bodies(2)%elements(1)%nodes == [1, 6, 7, 2]))
    call check_true('block drop: CLxxx 1 and 2 on edge 6-1 at 0 and 1', all(bodies(2)%tactors(1)%nodes == [6, 1]) &
                    .and. bodies(2)%tactors(1)%apab == 0.0_wp .and. bodies(2)%tactors(2)%apab == 1.0_wp)
    ! MODELS.DAT: M2DQ4 (Q4xxx) and the rigid model (Rxx2D).
    call read_models(dat('mesh_block_drop', 'MODELS.DAT'), models)
    call check_true('block drop: models M2DQ4 and rigid', size(models) == 2 .and. models(1)%element == 'Q4xxx' .and. &
                    models(2)%nickname == 'rigid' .and. models(2)%element == 'Rxx2D')
    call check_element_models(bodies, models, mats)
    ! DOF.INI: MAILx 1, 45 nodes, X = 0, V = (5e-2, 0).
    call read_dof_file(dat('mesh_block_drop', 'DOF.INI'), step, t, dof, bodies)
    call check_true('block drop: DOF.INI one MAILx record of 45 nodes', size(dof) == 1 .and. dof(1)%model == 'MAILx' &
                    .and. dof(1)%body == 1 .and. size(dof(1)%nodes) == 45 .and. dof(1)%nodes(45) == 45)
    call check_close('block drop: DOF.INI V(1) node 45', dof(1)%node_v(1, 45), 0.05_wp, 1e-15_wp)
    call check_close('block drop: DOF.INI X(2) node 45', dof(1)%node_x(2, 45), 0.0_wp, 0.0_wp)
    ! GPV.INI: '$steps 0' only.
    call read_gpv_file(dat('mesh_block_drop', 'GPV.INI'), step, t, gpv, bodies, models)
    call check_true('block drop: empty GPV.INI', size(gpv) == 0 .and. step == 0)
    ! Vloc_Rloc.OUT.2 (step 102): 9 CLJCx; 1: MAILx 1 CLxxx 1 on RBDY2 1 JONCx 1, stick,
    ! rlt/H -0.3816599D+03, one internal 0.1250025D-01.
    call read_vloc_rloc_file(decks//'/mesh_block_drop/OUTBOX/Vloc_Rloc.OUT.2', step, t, c, bodies)
    call check_true('block drop: 9 CLJCx at step 102', step == 102 .and. size(c) == 9 .and. all(c%inter == 'CLJCx'))
    call check_true('block drop: CLJCx 1 ids', c(1)%cdbdy == 'MAILx' .and. c(1)%cdtac == 'CLxxx' .and. &
                    c(1)%anbdy == 'RBDY2' .and. c(1)%antac == 'JONCx' .and. c(1)%status == 'stick')
    call close_rel('block drop: CLJCx 1 rlt', c(1)%rlt, -0.3816599e3_wp, 1e-12_wp)
    call check_true('block drop: CLJCx 1 one internal', size(c(1)%internals) == 1)
    call close_rel('block drop: CLJCx 1 taille_ele', c(1)%internals(1), 0.1250025e-1_wp, 1e-12_wp)
  end subroutine test_mesh_block_drop

  !> mesh_disk_on_mesh: a DISKx (RBDY2 1) and a Q4 slab (MAILx 1) with one
  !> ALpxx of 16 segments; DKALp records.
  subroutine test_mesh_disk_on_mesh()
    type(body_input_t), allocatable :: bodies(:)
    type(contact_record_t), allocatable :: c(:)
    type(driven_dof_input_t), allocatable :: drv(:)
    type(dof_record_t), allocatable :: dof(:)
    real(wp) :: t
    integer :: step
    call read_bodies(dat('mesh_disk_on_mesh', 'BODIES.DAT'), bodies)
    call check_true('disk on mesh: RBDY2 1 and MAILx 1', size(bodies) == 2 .and. bodies(1)%model == 'RBDY2' .and. &
                    bodies(2)%model == 'MAILx' .and. bodies(2)%number == 1)
    ! ALpxx line + 15 '+ALpxx': one polyline of 17 nodes, 3-6-...-51.
    call check_true('disk on mesh: one ALpxx of 16 segments', size(bodies(2)%tactors) == 1 .and. &
                    size(bodies(2)%tactors(1)%nodes) == 17 .and. bodies(2)%tactors(1)%nodes(1) == 3 .and. &
                    bodies(2)%tactors(1)%nodes(17) == 51)
    ! DRV_DOF.DAT: 17 bottom nodes, vlocy 1 and 2: 34 lines.
    call read_drv_dof(dat('mesh_disk_on_mesh', 'DRV_DOF.DAT'), decks//'/mesh_disk_on_mesh/DATBOX', drv, bodies)
    call check_true('disk on mesh: 34 driven MAILx dofs', size(drv) == 34 .and. all(drv%model == 'MAILx'))
    ! DOF.INI: RBDY2 1 only, V = (0.5, -1, 0).
    call read_dof_file(dat('mesh_disk_on_mesh', 'DOF.INI'), step, t, dof, bodies)
    call check_true('disk on mesh: DOF.INI RBDY2 1', size(dof) == 1 .and. dof(1)%model == 'RBDY2')
    call check_close('disk on mesh: DOF.INI V(2)', dof(1)%v(2), -1.0_wp, 0.0_wp)
    ! Vloc_Rloc.OUT.1 (step 26): 3 DKALp, segments 4, 5, 6; record 2 slifw, rln/H 0.5863285D+04.
    call read_vloc_rloc_file(decks//'/mesh_disk_on_mesh/OUTBOX/Vloc_Rloc.OUT.1', step, t, c, bodies)
    call check_true('disk on mesh: 3 DKALp on segments 4 5 6', size(c) == 3 .and. all(c%inter == 'DKALp') .and. &
                    all(c%anseg == [4, 5, 6]))
    call check_true('disk on mesh: DKALp 2 slifw, iadj 2', c(2)%status == 'slifw' .and. c(2)%iadj == 2 .and. &
                    c(2)%cdtac == 'DISKx' .and. c(2)%antac == 'ALpxx')
    call close_rel('disk on mesh: DKALp 2 rln', c(2)%rln, 0.5863285e4_wp, 1e-12_wp)
    call check_true('disk on mesh: DKALp internal 0', size(c(2)%internals) == 1)
    call check_close('disk on mesh: DKALp internal value', c(2)%internals(1), 0.0_wp, 0.0_wp)
  end subroutine test_mesh_disk_on_mesh

  !> mesh_plastic_bar: ELAS_PLAS, the Q4P0x J2 model, GPV.OUT with 3 lines per Gauss point.
  subroutine test_mesh_plastic_bar()
    type(body_input_t), allocatable :: bodies(:)
    type(material_input_t), allocatable :: mats(:)
    type(model_input_t), allocatable :: models(:)
    type(gpv_record_t), allocatable :: gpv(:), gpv_free(:)
    real(wp) :: g(3), t
    integer :: step
    ! STEEL ELAS_PLAS: Umas 7.8e3, EYng 2e11, Epss 0.3, SIG0 2e8, K___ 2e9.
    call read_bulk_behav(dat('mesh_plastic_bar', 'BULK_BEHAV.DAT'), g, mats)
    call check_true('plastic bar: STEEL ELAS_PLAS', mats(1)%law == 'ELAS_PLAS')
    call close_rel('plastic bar: E', mats(1)%young, 2.0e11_wp, 1e-12_wp)
    call close_rel('plastic bar: nu', mats(1)%poisson, 0.3_wp, 1e-12_wp)
    call close_rel('plastic bar: SIG0', mats(1)%yield0, 2.0e8_wp, 1e-12_wp)
    call close_rel('plastic bar: K', mats(1)%hardening, 2.0e9_wp, 1e-12_wp)
    call read_bodies(dat('mesh_plastic_bar', 'BODIES.DAT'), bodies, mats)
    call check_true('plastic bar: MAILx 1, 20 Q4, 33 nodes, no contactor', size(bodies) == 1 .and. &
                    size(bodies(1)%elements) == 20 .and. size(bodies(1)%node_coor, 2) == 33 .and. &
                    size(bodies(1)%tactors) == 0)
    ! M2DJ2: MECAx Q4P0x, iso__, no___, UpdtL, large, lump_, J2iso.
    call read_models(dat('mesh_plastic_bar', 'MODELS.DAT'), models)
    call check_true('plastic bar: M2DJ2 Q4P0x large UpdtL J2iso', models(1)%element == 'Q4P0x' .and. &
                    models(1)%kinematic == 'large' .and. models(1)%formulation == 'UpdtL' .and. &
                    models(1)%material == 'J2iso')
    call check_element_models(bodies, models, mats)
    ! GPV.OUT.2 (step 60): 20 elements, 4 Gauss points of 3 lines (4 + 4 + 6 values); element 1
    ! Gauss point 1: stress xx 0.2350181D+09, p 0.1903801D-02, von Mises 0.2038076D+09;
    ! Gauss point 4: Cp^-1 11 0.9965429D+00.
    call read_gpv_file(decks//'/mesh_plastic_bar/OUTBOX/GPV.OUT.2', step, t, gpv, bodies, models)
    call check_true('plastic bar: GPV 20 elements at step 60', step == 60 .and. size(gpv) == 20)
    call check_true('plastic bar: 14 values at 4 Gauss points', size(gpv(1)%values, 1) == 14 .and. &
                    size(gpv(1)%values, 2) == 4 .and. gpv(1)%kind == 'Q4xxx' .and. gpv(20)%element == 20)
    call close_rel('plastic bar: GP 1 stress xx', gpv(1)%values(1, 1), 0.2350181e9_wp, 1e-12_wp)
    call close_rel('plastic bar: GP 1 p', gpv(1)%values(13, 1), 0.1903801e-2_wp, 1e-12_wp)
    call close_rel('plastic bar: GP 1 von Mises', gpv(1)%values(14, 1), 0.2038076e9_wp, 1e-12_wp)
    call close_rel('plastic bar: GP 4 Cp-1 11', gpv(1)%values(9, 4), 0.9965429_wp, 1e-12_wp)
    ! Without the model, the third line is told by its 6 values.
    call read_gpv_file(decks//'/mesh_plastic_bar/OUTBOX/GPV.OUT.2', step, t, gpv_free)
    call check_true('plastic bar: GPV read without models: same layout', size(gpv_free) == 20 .and. &
                    size(gpv_free(1)%values, 1) == 14 .and. size(gpv_free(1)%values, 2) == 4)
  end subroutine test_mesh_plastic_bar

  !> mesh_exploded_beam: 48 MAILx bodies of one T3; body 2 has ALpxx 1, ALpxx 2
  !> (one line each) and the CLxxx line with its '+' line: contactors 3 and 4.
  subroutine test_mesh_exploded_beam()
    type(body_input_t), allocatable :: bodies(:)
    type(driven_dof_input_t), allocatable :: drv(:)
    type(contact_record_t), allocatable :: c(:)
    type(gpv_record_t), allocatable :: gpv(:)
    real(wp) :: t
    integer :: step
    call read_bodies(dat('mesh_exploded_beam', 'BODIES.DAT'), bodies)
    call check_true('exploded: 48 MAILx of one T3', size(bodies) == 48 .and. bodies(48)%number == 48 .and. &
                    all([(size(bodies(step)%elements) == 1, step=1, 48)]))
    call check_true('exploded: body 2 contactors ALpxx ALpxx CLxxx CLxxx', size(bodies(2)%tactors) == 4 .and. &
                    all(bodies(2)%tactors%kind == ['ALpxx', 'ALpxx', 'CLxxx', 'CLxxx']))
    call check_true('exploded: body 2 ALpxx 1 is 2-1, CLxxx 4 on 1-3 at 0.75', &
                    all(bodies(2)%tactors(1)%nodes == [2, 1]) .and. all(bodies(2)%tactors(4)%nodes == [1, 3]) .and. &
                    bodies(2)%tactors(4)%apab == 0.75_wp)
    ! DRV_DOF.DAT: bodies 1, 3 (2 nodes, vlocy 1 and 2) and 46, 48 (2 nodes, vlocy 2 CT -5e-2 RAMP 500).
    call read_drv_dof(dat('mesh_exploded_beam', 'DRV_DOF.DAT'), decks//'/mesh_exploded_beam/DATBOX', drv, bodies)
    call check_true('exploded: 12 driven dofs', size(drv) == 12)
    call check_true('exploded: last driven MAILx 48 node 2 dof 2', drv(12)%body == 48 .and. drv(12)%node == 2 .and. &
                    drv(12)%dof == 2)
    call close_rel('exploded: last driven CT', drv(12)%ct, -0.05_wp, 1e-12_wp)
    ! Vloc_Rloc.OUT.1: 116 CLALp; GPV.OUT.1: 48 T3 of 3 identical Gauss points.
    call read_vloc_rloc_file(decks//'/mesh_exploded_beam/OUTBOX/Vloc_Rloc.OUT.1', step, t, c, bodies)
    call check_true('exploded: 116 CLALp', size(c) == 116 .and. all(c%inter == 'CLALp'))
    call read_gpv_file(decks//'/mesh_exploded_beam/OUTBOX/GPV.OUT.1', step, t, gpv, bodies)
    call check_true('exploded: GPV 48 T3 of 3 points of 8 values', size(gpv) == 48 .and. gpv(48)%body == 48 .and. &
                    size(gpv(1)%values, 1) == 8 .and. size(gpv(1)%values, 2) == 3)
    ! Body 1: stress xx -0.7107041D+07, strain gamma_xy -0.4492888D-03.
    call close_rel('exploded: GPV body 1 stress xx', gpv(1)%values(1, 2), -0.7107041e7_wp, 1e-12_wp)
    call close_rel('exploded: GPV body 1 gamma xy', gpv(1)%values(7, 3), -0.4492888e-3_wp, 1e-12_wp)
  end subroutine test_mesh_exploded_beam

  !> read_deck on each mesh deck with its run control from test_cases/compat.
  subroutine test_mesh_decks()
    type(deck_t) :: deck
    integer :: k
    do k = 1, size(mesh_cases)
      call read_deck(decks//'/'//trim(mesh_cases(k)), deck, '../compat/'//trim(mesh_cases(k))//'/run.dat')
      call check_true(trim(mesh_cases(k))//': read_deck reads the models', size(deck%models) >= 1 .and. &
                      any(deck%bodies%model == 'MAILx') .and. size(deck%gpv_ini) == 0)
      call check_true(trim(mesh_cases(k))//': plane strain', deck%run%plane == 'strain')
    end do
    call check_close('plastic bar: newton_tolerance', deck%run%newton_tolerance, 1.0e-6_wp, 0.0_wp)
    call check_true('t3 pair: 1000 steps', deck%run%number_of_steps == 1000)
  end subroutine test_mesh_decks

  !> PLALp (polygon vertex on a mesh polyline): no LMGC90 file of this type in
  !> the fixtures, so the id line is checked against the layout of LMGC90's
  !> PLALp writer (1X,A5,2X,I5,2X,A5,2X,I5,2X,A5,2X,I5,2X,A5,2X,A5,2X,I5,2X,A5,
  !> 2X,I5,2X,I5,9X,A5,1X,I5: vertex after 'CDVER', segment without a label),
  !> then read back.
  subroutine test_plalp_layout()
    type(contact_record_t) :: r(1)
    type(contact_record_t), allocatable :: b(:)
    character(len=103) :: expected
    character(len=:), allocatable :: f, text
    real(wp) :: t
    integer :: step, k, line_start, nl
    r(1)%inter = 'PLALp'
    r(1)%number = 1
    r(1)%cdbdy = 'RBDY2'; r(1)%icdbdy = 3; r(1)%cdtac = 'POLYG'; r(1)%icdtac = 1; r(1)%cdver = 4
    r(1)%behav = 'gapc3'
    r(1)%anbdy = 'MAILx'; r(1)%ianbdy = 2; r(1)%antac = 'ALpxx'; r(1)%iantac = 1; r(1)%anseg = 7
    r(1)%status = 'slifw'; r(1)%iadj = 2
    r(1)%rln = 12.5_wp
    allocate (r(1)%internals(0))
    write (expected, '(1X,A5,2X,I5,2X,A5,2X,I5,2X,A5,2X,I5,2X,A5,2X,A5,2X,I5,2X,A5,2X,I5,2X,I5,9X,A5,1X,I5)') &
      'RBDY2', 3, 'POLYG', 1, 'CDVER', 4, 'gapc3', 'MAILx', 2, 'ALpxx', 1, 7, 'slifw', 2
    f = tmp//'_plalp'
    call write_vloc_rloc_file(f, 5, 0.5_wp, r)
    text = slurp(f)
    ! The id line is line 9 (5 header lines, the rule, $icdan, the column header).
    line_start = 1
    nl = 0
    do k = 1, len(text)
      if (text(k:k) == achar(10)) then
        nl = nl + 1
        if (nl == 8) line_start = k + 1
        if (nl == 9) exit
      end if
    end do
    call check_true('PLALp id line in LMGC90 layout', text(line_start:k - 1) == expected)
    call read_vloc_rloc_file(f, step, t, b)
    call check_true('PLALp read back', size(b) == 1 .and. b(1)%cdver == 4 .and. b(1)%anseg == 7 .and. &
                    b(1)%status == 'slifw' .and. b(1)%iadj == 2 .and. b(1)%ianbdy == 2 .and. b(1)%anbdy == 'MAILx')
    call check_close('PLALp rln read back', b(1)%rln, 12.5_wp, 0.0_wp)
    call remove_file(f)
  end subroutine test_plalp_layout

  !> The deck test_cases/broken/valid_minimal reads through read_deck.
  subroutine test_valid_minimal()
    type(deck_t) :: deck
    call read_deck('../broken/valid_minimal', deck)
    call check_true('valid_minimal: 2 bodies', size(deck%bodies) == 2)
    call check_true('valid_minimal: run control read', deck%run%time_step > 0 .and. deck%run%number_of_steps > 0)
  end subroutine test_valid_minimal

  function slurp(path) result(s)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: s
    integer :: u, sz
    open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read')
    inquire (unit=u, size=sz)
    allocate (character(len=sz) :: s)
    if (sz > 0) read (u) s
    close (u)
  end function slurp

  !> LMGC90 DOF.OUT.n -> read -> write -> read: same values; write again: same
  !> bytes; and our file is byte-identical to LMGC90's.
  subroutine round_trip_dof(case_name, n)
    character(len=*), intent(in) :: case_name
    integer, intent(in) :: n
    type(dof_record_t), allocatable :: a(:), b(:)
    real(wp) :: ta, tb
    integer :: sa, sb, k, j
    logical :: same
    character(len=:), allocatable :: orig, f1, f2, name
    name = case_name//' DOF.OUT.'//itoa(n)
    orig = decks//'/'//case_name//'/OUTBOX/DOF.OUT.'//itoa(n)
    f1 = tmp//'_dof1'
    f2 = tmp//'_dof2'
    call read_dof_file(orig, sa, ta, a)
    call write_dof_file(f1, sa, ta, a)
    call read_dof_file(f1, sb, tb, b)
    same = sa == sb .and. size(a) == size(b) .and. abs(ta - tb) <= 1e-7_wp*abs(ta)
    if (same) then
      do k = 1, size(a)
        same = same .and. a(k)%body == b(k)%body .and. a(k)%model == b(k)%model
        do j = 1, 3
          same = same .and. abs(a(k)%x(j) - b(k)%x(j)) <= 1e-7_wp*abs(a(k)%x(j)) &
                 .and. abs(a(k)%v(j) - b(k)%v(j)) <= 1e-7_wp*abs(a(k)%v(j))
        end do
        if (a(k)%model == 'MAILx' .and. same) then
          same = size(a(k)%nodes) == size(b(k)%nodes)
          if (same) same = all(a(k)%nodes == b(k)%nodes) .and. all(rel_eq(a(k)%node_x, b(k)%node_x)) .and. &
                           all(rel_eq(a(k)%node_v, b(k)%node_v))
        end if
      end do
    end if
    call check_true(name//': read-write-read same values', same)
    call write_dof_file(f2, sb, tb, b)
    call check_true(name//': write-read-write same bytes', slurp(f1) == slurp(f2))
    call check_true(name//': written file byte-identical to LMGC90', slurp(f1) == slurp(orig))
    call remove_file(f1)
    call remove_file(f2)
  end subroutine round_trip_dof

  subroutine round_trip_vloc(case_name, n)
    character(len=*), intent(in) :: case_name
    integer, intent(in) :: n
    type(contact_record_t), allocatable :: a(:), b(:)
    real(wp) :: ta, tb
    integer :: sa, sb, k
    logical :: same
    character(len=:), allocatable :: orig, f1, f2, name
    name = case_name//' Vloc_Rloc.OUT.'//itoa(n)
    orig = decks//'/'//case_name//'/OUTBOX/Vloc_Rloc.OUT.'//itoa(n)
    f1 = tmp//'_vloc1'
    f2 = tmp//'_vloc2'
    call read_vloc_rloc_file(orig, sa, ta, a)
    call write_vloc_rloc_file(f1, sa, ta, a)
    call read_vloc_rloc_file(f1, sb, tb, b)
    same = sa == sb .and. size(a) == size(b) .and. abs(ta - tb) <= 1e-7_wp*abs(ta)
    if (same) then
      do k = 1, size(a)
        same = same .and. a(k)%inter == b(k)%inter .and. a(k)%number == b(k)%number .and. &
               a(k)%icdbdy == b(k)%icdbdy .and. a(k)%icdtac == b(k)%icdtac .and. a(k)%ianbdy == b(k)%ianbdy .and. &
               a(k)%iantac == b(k)%iantac .and. a(k)%cdver == b(k)%cdver .and. a(k)%anseg == b(k)%anseg .and. &
               a(k)%behav == b(k)%behav .and. a(k)%status == b(k)%status .and. a(k)%iadj == b(k)%iadj .and. &
               a(k)%cdtac == b(k)%cdtac .and. a(k)%antac == b(k)%antac .and. &
               a(k)%has_geometry .eqv. b(k)%has_geometry
        same = same .and. rel_eq(a(k)%rlt, b(k)%rlt) .and. rel_eq(a(k)%rln, b(k)%rln) .and. &
               rel_eq(a(k)%vlt, b(k)%vlt) .and. rel_eq(a(k)%vln, b(k)%vln) .and. rel_eq(a(k)%gap, b(k)%gap) .and. &
               all(rel_eq(a(k)%normal, b(k)%normal)) .and. all(rel_eq(a(k)%coor, b(k)%coor))
        same = same .and. size(a(k)%internals) == size(b(k)%internals)
        if (same) same = all(rel_eq(a(k)%internals, b(k)%internals))
      end do
    end if
    call check_true(name//': read-write-read same values', same)
    call write_vloc_rloc_file(f2, sb, tb, b)
    call check_true(name//': write-read-write same bytes', slurp(f1) == slurp(f2))
    call check_true(name//': written file byte-identical to LMGC90', slurp(f1) == slurp(orig))
    call remove_file(f1)
    call remove_file(f2)
  end subroutine round_trip_vloc

  !> LMGC90 GPV.OUT.n -> read -> write -> read: same values; write again: same
  !> bytes; and our file is byte-identical to LMGC90's. Read with the case's
  !> bodies and models (lines per Gauss point from the model).
  subroutine round_trip_gpv(case_name, n)
    character(len=*), intent(in) :: case_name
    integer, intent(in) :: n
    type(gpv_record_t), allocatable :: a(:), b(:)
    type(body_input_t), allocatable :: bodies(:)
    type(model_input_t), allocatable :: models(:)
    real(wp) :: ta, tb
    integer :: sa, sb, k
    logical :: same
    character(len=:), allocatable :: orig, f1, f2, name
    name = case_name//' GPV.OUT.'//itoa(n)
    orig = decks//'/'//case_name//'/OUTBOX/GPV.OUT.'//itoa(n)
    f1 = tmp//'_gpv1'
    f2 = tmp//'_gpv2'
    call read_bodies(dat(case_name, 'BODIES.DAT'), bodies)
    call read_models(dat(case_name, 'MODELS.DAT'), models)
    call read_gpv_file(orig, sa, ta, a, bodies, models)
    call write_gpv_file(f1, sa, ta, a)
    call read_gpv_file(f1, sb, tb, b, bodies, models)
    same = sa == sb .and. size(a) == size(b) .and. abs(ta - tb) <= 1e-7_wp*abs(ta) .and. size(a) > 0
    if (same) then
      do k = 1, size(a)
        same = same .and. a(k)%body == b(k)%body .and. a(k)%element == b(k)%element .and. a(k)%kind == b(k)%kind &
               .and. all(shape(a(k)%values) == shape(b(k)%values))
        if (same) same = all(rel_eq(a(k)%values, b(k)%values))
      end do
    end if
    call check_true(name//': read-write-read same values', same)
    call write_gpv_file(f2, sb, tb, b)
    call check_true(name//': write-read-write same bytes', slurp(f1) == slurp(f2))
    call check_true(name//': written file byte-identical to LMGC90', slurp(f1) == slurp(orig))
    call remove_file(f1)
    call remove_file(f2)
  end subroutine round_trip_gpv

  elemental logical function rel_eq(x, y)
    real(wp), intent(in) :: x, y
    rel_eq = abs(x - y) <= 1e-7_wp*abs(x)
  end function rel_eq
end program test_readers
