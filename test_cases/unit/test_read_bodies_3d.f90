!> Reading LMGC90's 3D rigid DATBOX (fracas_read_bodies_3d, read_drv_dof's RBDY3
!> blocks) and building RBDY3 bodies from it (fracas_contactors_3d,
!> fracas_rbdy3), on the deck test_cases/broken/rbdy3_deck_refused (which the
!> 2D scene refuses: broken.rbdy3_deck_refused). References: the values
!> written in the deck, and for the mass properties the formulas (density
!> 2500: sphere r = 0.1, m = 4/3 pi r^3 rho, I = 2/5 m r^2; two SPHEb at
!> +-0.2 along x: I about x = 2 (2/5 m r^2), across 2 (2/5 m r^2 + 0.04 m);
!> plate 2 x 1 x 0.1: m = 500 kg; POLYR cube of side 0.2: m = 20 kg,
!> I = m (0.2^2 + 0.2^2) / 12, centre at its node). Round-off tolerances (the deck's 8 digits
!> where read values are compared: 1e-7).
!> Planted bugs watched red: the NO6xx second line read into coo1..3 (centre
!> z 0 for 0.15); the 'I1' line test at columns 31-32 (line taken as a
!> contactor: error); the DOF.INI V lines swapped (omega_2 0 for 5); the frame
!> written by rows (a(1..3) = the first row: read back off by 1.0); given
!> I1 I2 I3 of a several-contactor body ignored (0.92 for 5).
!> LMGC90's rule for given I1 I2 I3 on a several-contactor body's PLAIN line
!> (kept, times the density, global axes) checked on the two-sphere body.
!> Also one step, then DOF.OUT in LMGC90's 3D layout (fracas_write_outbox:
!> write_dof_file_3d) read back with read_dof_3d (8 digits).
program test_read_bodies_3d
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_deck, only: material_input_t, driven_dof_input_t
  use fracas_deck_3d, only: body3_input_t, dof3_record_t
  use fracas_read_bodies_3d, only: read_bodies_3d, read_dof_3d
  use fracas_read_bulk_behav, only: read_bulk_behav
  use fracas_read_drv_dof, only: read_drv_dof
  use fracas_contactors_3d, only: tactor3_t, tactors3_from_input, body3_mass_properties
  use fracas_rbdy3, only: rbdy3_t, rbdy3_init, rbdy3_add_drives, rbdy3_begin_step, rbdy3_end_step, rbdy3_set_dof, &
                          rbdy3_dof_records
  use fracas_write_outbox, only: write_dof_file_3d
  use fracas_files, only: executable_dir
  use fracas_frame_3d, only: rotation_of_vector, identity3
  implicit none
  character(len=*), parameter :: dir = '../broken/rbdy3_deck_refused/DATBOX'
  real(wp), parameter :: pi = acos(-1.0_wp), rho = 2500.0_wp
  type(body3_input_t), allocatable :: bodies(:)
  type(material_input_t), allocatable :: materials(:)
  type(driven_dof_input_t), allocatable :: driven(:)
  type(dof3_record_t), allocatable :: dofs(:), back(:), written(:)
  type(tactor3_t), allocatable :: t(:)
  type(rbdy3_t) :: b
  real(wp) :: gravity(3), centre(3, 4), frame(3, 3, 4), mass(4), inertia(3, 4), avrd(4), m1, i1, time
  integer :: k, step

  call read_bulk_behav(dir//'/BULK_BEHAV.DAT', gravity, materials)
  call read_bodies_3d(dir//'/BODIES.DAT', bodies, materials)
  call check_true('four RBDY3 read', size(bodies) == 4)
  call check_true('body 1: one SPHER, body 2: two SPHEb, body 3: one PLANx', &
                  size(bodies(1)%tactors) == 1 .and. bodies(1)%tactors(1)%kind == 'SPHER' .and. &
                  size(bodies(2)%tactors) == 2 .and. bodies(2)%tactors(2)%kind == 'SPHEb' .and. &
                  bodies(3)%tactors(1)%kind == 'PLANx' .and. bodies(4)%tactors(1)%kind == 'POLYR')
  call check_true('POLYR: 8 vertices, 12 faces, face 1 = (1, 3, 2)', size(bodies(4)%tactors(1)%vert, 2) == 8 .and. &
                  size(bodies(4)%tactors(1)%faces, 2) == 12 .and. all(bodies(4)%tactors(1)%faces(:, 1) == [1, 3, 2]))
  call check_close('body 1 node z (coo3)', bodies(1)%coor(3), 0.15_wp, 1.0e-15_wp)
  call check_close('body 1 radius', bodies(1)%tactors(1)%radius, 0.1_wp, 1.0e-15_wp)
  call check_close('body 2 second SPHEb offset x', bodies(2)%tactors(2)%shift(1), -0.2_wp, 1.0e-15_wp)
  call check_close('body 3 PLANx axe2', bodies(3)%tactors(1)%axes(2), 0.5_wp, 1.0e-15_wp)
  call check_close('body 3 PLANx gamma(2) = -sin 30', bodies(3)%tactors(1)%frame(2, 3), -0.5_wp, 1.0e-15_wp)

  do k = 1, 4
    t = tactors3_from_input(bodies(k)%tactors)
    avrd(k) = bodies(k)%avrd
    call body3_mass_properties(t, bodies(k)%coor(1:3), rho, avrd(k), centre(:, k), frame(:, :, k), mass(k), inertia(:, k))
  end do
  m1 = 4.0_wp / 3.0_wp * pi * 1.0e-3_wp * rho
  i1 = 0.4_wp * m1 * 0.01_wp
  call check_close('sphere mass', mass(1), m1, 1.0e-12_wp * m1)
  call check_close('sphere inertia 2/5 m r^2', inertia(2, 1), i1, 1.0e-12_wp * i1)
  call check_close('sphere centre z', centre(3, 1), 0.15_wp, 1.0e-15_wp)
  call check_close('two SPHEb: mass', mass(2), 2.0_wp * m1, 1.0e-12_wp * m1)
  call check_close('two SPHEb: I about x', inertia(1, 2), 2.0_wp * i1, 1.0e-12_wp * i1)
  call check_close('two SPHEb: I across', inertia(3, 2), 2.0_wp * (i1 + 0.04_wp * m1), 1.0e-12_wp * i1)
  call check_close('two SPHEb: first axis along x', abs(frame(1, 1, 2)), 1.0_wp, 1.0e-14_wp)
  call check_close('two SPHEb: centre', norm2(centre(:, 2) - [1.0_wp, 0.0_wp, 0.5_wp]), 0.0_wp, 1.0e-15_wp)
  call check_close('plate: mass', mass(3), 500.0_wp, 1.0e-10_wp)
  call check_close('plate: frame = its localframe (30 deg about x, 8 digits)', &
                   maxval(abs(frame(:, :, 3) - rotation_of_vector([pi / 6.0_wp, 0.0_wp, 0.0_wp]))), 0.0_wp, 1.0e-7_wp)
  call check_close('plate: centre = node + offset', centre(3, 3), -0.05_wp, 1.0e-15_wp)
  ! the two-sphere body with I1 I2 I3 given on its PLAIN line: kept (times the density), global axes
  t = tactors3_from_input(bodies(2)%tactors)
  avrd(2) = 0.0_wp
  call body3_mass_properties(t, bodies(2)%coor(1:3), rho, avrd(2), centre(:, 2), frame(:, :, 2), mass(2), &
                             inertia(:, 2), given=[1.0e-3_wp, 2.0e-3_wp, 3.0e-3_wp])
  call check_close('two SPHEb, I given: I2 = rho 2e-3', inertia(2, 2), rho * 2.0e-3_wp, 1.0e-15_wp)
  call check_close('two SPHEb, I given: global axes', maxval(abs(frame(:, :, 2) - identity3())), 0.0_wp, 0.0_wp)
  call check_close('two SPHEb, I given: mass unchanged', mass(2), 2.0_wp * m1, 1.0e-12_wp * m1)
  t = tactors3_from_input(bodies(2)%tactors)
  call body3_mass_properties(t, bodies(2)%coor(1:3), rho, avrd(2), centre(:, 2), frame(:, :, 2), mass(2), inertia(:, 2), &
                             given=bodies(2)%inertia)
  call check_close('two SPHEb, I line zero: computed (I about x)', inertia(1, 2), 2.0_wp * i1, 1.0e-12_wp * i1)
  call check_close('POLYR cube: mass', mass(4), 20.0_wp, 1.0e-12_wp)
  call check_close('POLYR cube: I = m (a^2 + b^2) / 12', inertia(2, 4), 20.0_wp * 0.08_wp / 12.0_wp, 1.0e-13_wp)
  call check_close('POLYR cube: centre at its node', norm2(centre(:, 4) - [0.5_wp, 0.3_wp, 0.1_wp]), 0.0_wp, 1.0e-15_wp)
  call check_close('gravity z', gravity(3), -9.81_wp, 1.0e-15_wp)

  call rbdy3_init(b, [1, 2, 3, 4], centre, frame, mass, inertia, avrd, gravity)
  call read_drv_dof(dir//'/DRV_DOF.DAT', dir, driven)
  call check_true('six drives on RBDY3 3', size(driven) == 6 .and. all(driven%model == 'RBDY3') .and. all(driven%body == 3))
  call rbdy3_add_drives(b, driven)
  call check_true('plate clamped', b%clamped(3) .and. .not. b%clamped(1))
  call read_dof_3d(dir//'/DOF.INI', 4, step, time, dofs)
  call check_true('DOF.INI: step 0, one record for body 1', step == 0 .and. size(dofs) == 1 .and. dofs(1)%body == 1)
  call check_close('DOF.INI: V(1)', dofs(1)%v(1), 0.5_wp, 1.0e-15_wp)
  call check_close('DOF.INI: V(5) (omega about the second principal axis)', dofs(1)%v(5), 5.0_wp, 1.0e-15_wp)
  call check_close('DOF.INI: frame gamma(3)', dofs(1)%frame(3, 3), 1.0_wp, 1.0e-15_wp)
  call rbdy3_set_dof(b, dofs(1))
  call rbdy3_begin_step(b, 0.0_wp, 1.0e-3_wp, 0.5_wp)
  call check_close('drive: plate omega_3 = 2 (ct)', b%v(6, 3), 2.0_wp, 0.0_wp)
  call check_close('free fall: sphere v_z = -g h', b%vfree(3, 1), -9.81e-3_wp, 1.0e-15_wp)
  call check_close('sphere spin kept (no gyroscopic torque on a sphere)', b%vfree(5, 1), 5.0_wp, 0.0_wp)
  ! One step, DOF.OUT written in LMGC90's 3D layout and read back (D14.7: 8 digits).
  call rbdy3_end_step(b, 1.0e-3_wp, 0.5_wp)
  written = rbdy3_dof_records(b)
  call write_dof_file_3d(executable_dir()//'test_read_bodies_3d_DOF.OUT', 1, 1.0e-3_wp, written)
  call read_dof_3d(executable_dir()//'test_read_bodies_3d_DOF.OUT', 4, step, time, back)
  call check_true('DOF.OUT 3D read back: step 1, 4 bodies', step == 1 .and. size(back) == 4 .and. all(back%body == [1, 2, 3, 4]))
  call check_close('DOF.OUT 3D read back: time', time, 1.0e-3_wp, 1.0e-10_wp)
  do k = 1, 4
    call check_close('DOF.OUT 3D read back: X, V (8 digits)', maxval(abs([back(k)%x - written(k)%x, back(k)%v - written(k)%v])), &
                     0.0_wp, 5.0e-8_wp * max(1.0_wp, maxval(abs(written(k)%v))))
    call check_close('DOF.OUT 3D read back: frame (8 digits)', maxval(abs(back(k)%frame - written(k)%frame)), 0.0_wp, 5.0e-8_wp)
  end do
  call check_close('sphere after one step: z = 0.15 - g h^2 / 2', b%ref(3, 1) + written(1)%x(3), 0.15_wp - 0.5_wp * 9.81e-6_wp, &
                   1.0e-15_wp)
  call test_finish()
end program test_read_bodies_3d
