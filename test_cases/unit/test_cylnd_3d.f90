!> CYLND (capsule for contact, LMGC90's plain-cylinder mass) and its pairs
!> SPCDx and CDPLx, against hand computations (tolerance 1e-14 unless said).
!> Mass (LMGC90's a_BDARY_CYLND formulas): High h = 1, byrd r = 0.5:
!> V = 2 pi r^2 h = pi/2, I1 = I2 = (r^2/4 + h^2/3) V = 19 pi / 96,
!> I3 = r^2/2 V = pi/16; a body of one CYLND turned: its frame is the CYLND's.
!> SPCDx, CYLND at 0, axis z, h = 1, r = 0.5, sphere radius 0.25:
!>  side (1, 0, 0.3): gap 0.25, n = x, point (0.625, 0, 0.3);
!>  beyond the end on the axis (0, 0, 2): gap 0.25, n = z (LMGC90's flat end: 0.75);
!>  beyond the rim (0.6, 0, 1.8): |(0.6, 0, 0.8)| = 1, gap 0.25, n = (0.6, 0, 0.8);
!>  turned CYLND (axis (0, 0.6, 0.8), centre (1, 2, 3)), sphere at
!>  centre + 0.5 axis + x: gap 0.25, n = x.
!> CDPLx, PLANx (5, 5, 0.5) at 0, alert 0.15, CYLND h = 1, r = 0.5:
!>  lying along x at height 1.1: two contacts, gap 0.1, n = z, points (-1, 0, 0.55), (1, 0, 0.55);
!>  standing at height 2.01: one contact (lower end), gap 0.01;
!>  turned 30 degrees about y, centre height 1 + cos 30 + 0.02: one, gap 0.02;
!>  lying under the plane at -1.1: two, n = -z.
!> BODIES.DAT: a CYLND line as LMGC90 writes it ('High=' at 35-48, 'byrd='
!> at 56-69) with a localframe turned 30 degrees about x and an offset, read
!> (read_bodies_3d) and built: High 1, byrd 0.5, the frame and the offset as
!> written (to the file's 7 digits: 1e-7), mass 2000 pi/2, I3 2000 pi/16,
!> body centre = node + offset.
!> Planted (each went red): the axis segment not clamped (an infinite
!> cylinder); CDPLx keeping the first end only; I1 with h^2/12; the SPCDx
!> normal from the sphere to the CYLND.
program test_cylnd_3d
  use fracas_kinds, only: wp
  use fracas_contactors_3d, only: tactor3_t, tk3_cylnd, cylnd_volume_inertia, body3_mass_properties, &
                                  tactors3_from_input
  use fracas_deck_3d, only: body3_input_t
  use fracas_read_bodies_3d, only: read_bodies_3d
  use fracas_files, only: executable_dir
  use fracas_spcdx, only: spcdx_geometry
  use fracas_cdplx, only: cdplx_contacts, cdplx_max_points
  use fracas_frame_3d, only: rotation_of_vector, identity3, cross3
  use fracas_testing, only: check_true, check_close, test_finish
  implicit none
  real(wp), parameter :: pi = acos(-1.0_wp), tol = 1.0e-14_wp
  real(wp) :: vol, inertia(3), gap, point(3), frame(3, 3), e(3), c(3), rot(3, 3)
  real(wp) :: gaps(cdplx_max_points), points(3, cdplx_max_points), frames(3, 3, cdplx_max_points)
  real(wp) :: centre(3), bframe(3, 3), mass, avrd
  type(tactor3_t) :: t(1)
  integer :: n

  ! mass
  call cylnd_volume_inertia(1.0_wp, 0.5_wp, vol, inertia)
  call check_close('CYLND volume pi/2', vol, pi / 2.0_wp, tol)
  call check_close('CYLND I1 19 pi/96', inertia(1), 19.0_wp * pi / 96.0_wp, tol)
  call check_close('CYLND I2 = I1', inertia(2), 19.0_wp * pi / 96.0_wp, tol)
  call check_close('CYLND I3 pi/16', inertia(3), pi / 16.0_wp, tol)
  rot = rotation_of_vector([0.3_wp, -0.2_wp, 0.5_wp])
  t(1)%kind = tk3_cylnd
  t(1)%radius = 0.5_wp
  t(1)%axes = [1.0_wp, 0.0_wp, 0.0_wp]
  t(1)%frame = rot
  avrd = 0.0_wp
  call body3_mass_properties(t, [1.0_wp, 2.0_wp, 3.0_wp], 2000.0_wp, avrd, centre, bframe, mass, inertia)
  call check_close('body of one CYLND: mass = 2000 pi/2', mass, 1000.0_wp * pi, 1.0e-11_wp)
  call check_close('body of one CYLND: I3 = 2000 pi/16', inertia(3), 125.0_wp * pi, 1.0e-11_wp)
  call check_close('body of one CYLND: its frame is the CYLND''s', maxval(abs(bframe - rot)), 0.0_wp, tol)

  ! SPCDx
  e = [0.0_wp, 0.0_wp, 1.0_wp]
  call spcdx_geometry([1.0_wp, 0.0_wp, 0.3_wp], 0.25_wp, [0.0_wp, 0.0_wp, 0.0_wp], e, 1.0_wp, 0.5_wp, gap, point, frame)
  call check_sp('SPCDx side', 0.25_wp, [1.0_wp, 0.0_wp, 0.0_wp], [0.625_wp, 0.0_wp, 0.3_wp])
  call spcdx_geometry([0.0_wp, 0.0_wp, 2.0_wp], 0.25_wp, [0.0_wp, 0.0_wp, 0.0_wp], e, 1.0_wp, 0.5_wp, gap, point, frame)
  call check_sp('SPCDx beyond the end', 0.25_wp, e, [0.0_wp, 0.0_wp, 1.625_wp])
  call spcdx_geometry([0.6_wp, 0.0_wp, 1.8_wp], 0.25_wp, [0.0_wp, 0.0_wp, 0.0_wp], e, 1.0_wp, 0.5_wp, gap, point, frame)
  call check_sp('SPCDx beyond the rim', 0.25_wp, [0.6_wp, 0.0_wp, 0.8_wp], &
                [0.0_wp, 0.0_wp, 1.0_wp] + 0.625_wp * [0.6_wp, 0.0_wp, 0.8_wp])
  e = [0.0_wp, 0.6_wp, 0.8_wp]
  c = [1.0_wp, 2.0_wp, 3.0_wp]
  call spcdx_geometry(c + 0.5_wp * e + [1.0_wp, 0.0_wp, 0.0_wp], 0.25_wp, c, e, 1.0_wp, 0.5_wp, gap, point, frame)
  call check_sp('SPCDx turned CYLND', 0.25_wp, [1.0_wp, 0.0_wp, 0.0_wp], c + 0.5_wp * e + [0.625_wp, 0.0_wp, 0.0_wp])

  ! CDPLx
  call cdplx_contacts([0.0_wp, 0.0_wp, 1.1_wp], [1.0_wp, 0.0_wp, 0.0_wp], 1.0_wp, 0.5_wp, [0.0_wp, 0.0_wp, 0.0_wp], &
                      identity3(), [5.0_wp, 5.0_wp, 0.5_wp], 0.15_wp, n, gaps, points, frames)
  call check_true('CDPLx lying: two contacts', n == 2)
  call check_pl('CDPLx lying, end -x', 1, 0.1_wp, [0.0_wp, 0.0_wp, 1.0_wp], [-1.0_wp, 0.0_wp, 0.55_wp])
  call check_pl('CDPLx lying, end +x', 2, 0.1_wp, [0.0_wp, 0.0_wp, 1.0_wp], [1.0_wp, 0.0_wp, 0.55_wp])
  call cdplx_contacts([0.0_wp, 0.0_wp, 2.01_wp], [0.0_wp, 0.0_wp, 1.0_wp], 1.0_wp, 0.5_wp, [0.0_wp, 0.0_wp, 0.0_wp], &
                      identity3(), [5.0_wp, 5.0_wp, 0.5_wp], 0.15_wp, n, gaps, points, frames)
  call check_true('CDPLx standing: one contact', n == 1)
  call check_pl('CDPLx standing, lower end', 1, 0.01_wp, [0.0_wp, 0.0_wp, 1.0_wp], [0.0_wp, 0.0_wp, 0.505_wp])
  e = [sin(pi / 6.0_wp), 0.0_wp, cos(pi / 6.0_wp)]
  c = [0.3_wp, -0.2_wp, 1.0_wp + cos(pi / 6.0_wp) + 0.02_wp]
  call cdplx_contacts(c, e, 1.0_wp, 0.5_wp, [0.0_wp, 0.0_wp, 0.0_wp], identity3(), [5.0_wp, 5.0_wp, 0.5_wp], 0.15_wp, &
                      n, gaps, points, frames)
  call check_true('CDPLx turned 30 degrees: one contact', n == 1)
  call check_pl('CDPLx turned 30 degrees, lower end', 1, 0.02_wp, [0.0_wp, 0.0_wp, 1.0_wp], &
                [0.3_wp - sin(pi / 6.0_wp), -0.2_wp, 0.51_wp])
  call cdplx_contacts([0.0_wp, 0.0_wp, -1.1_wp], [1.0_wp, 0.0_wp, 0.0_wp], 1.0_wp, 0.5_wp, [0.0_wp, 0.0_wp, 0.0_wp], &
                      identity3(), [5.0_wp, 5.0_wp, 0.5_wp], 0.15_wp, n, gaps, points, frames)
  call check_true('CDPLx under the plane: two contacts', n == 2)
  call check_pl('CDPLx under the plane, end +x', 2, 0.1_wp, [0.0_wp, 0.0_wp, -1.0_wp], [1.0_wp, 0.0_wp, -0.55_wp])

  ! BODIES.DAT
  block
    type(body3_input_t), allocatable :: bodies(:)
    type(tactor3_t), allocatable :: tb(:)
    character(len=:), allocatable :: path
    integer :: u
    path = executable_dir()//'test_cylnd_3d_BODIES.DAT'
    open (newunit=u, file=path, status='replace', action='write')
    write (u, '(a)') '$bdyty', ' RBDY3      1', '$blmty', ' PLAIN      1  behav  STONE  avrd= 0.0000000D+00', &
      '$nodty', ' NO6xx      1                coo1= 1.0000000D+00  coo2= 2.0000000D+00  coo3= 3.0000000D+00', &
      '                             coo4= 0.0000000D+00  coo5= 0.0000000D+00  coo6= 0.0000000D+00', '$tacty', &
      ' CYLND      1  color  BLUEx  High= 1.0000000D+00  byrd= 5.0000000D-01', &
      '                             localframe', &
      '                             alp1= 1.0000000D+00  alp2= 0.0000000D+00  alp3= 0.0000000D+00', &
      '                             bet1= 0.0000000D+00  bet2= 8.6602540D-01  bet3= 5.0000000D-01', &
      '                             gam1= 0.0000000D+00  gam2=-5.0000000D-01  gam3= 8.6602540D-01', &
      '                             coo1= 0.0000000D+00  coo2= 0.0000000D+00  coo3=-5.0000000D-02', '$$$$$$'
    close (u)
    call read_bodies_3d(path, bodies)
    call check_true('BODIES.DAT: one body, one CYLND', size(bodies) == 1)
    tb = tactors3_from_input(bodies(1)%tactors)
    call check_true('BODIES.DAT: the contactor is a CYLND', tb(1)%kind == tk3_cylnd)
    call check_close('BODIES.DAT: High', tb(1)%axes(1), 1.0_wp, 0.0_wp)
    call check_close('BODIES.DAT: byrd', tb(1)%radius, 0.5_wp, 0.0_wp)
    call check_close('BODIES.DAT: localframe gamma = (0, -1/2, sqrt 3/2)', &
                     maxval(abs(tb(1)%frame(:, 3) - [0.0_wp, -0.5_wp, sqrt(3.0_wp) / 2.0_wp])), 0.0_wp, 1.0e-7_wp)
    rot = tb(1)%frame
    avrd = 0.0_wp
    call body3_mass_properties(tb, bodies(1)%coor(1:3), 2000.0_wp, avrd, centre, bframe, mass, inertia)
    call check_close('BODIES.DAT: mass 2000 pi/2', mass, 1000.0_wp * pi, 1.0e-11_wp)
    call check_close('BODIES.DAT: I3 2000 pi/16', inertia(3), 125.0_wp * pi, 1.0e-11_wp)
    call check_close('BODIES.DAT: centre = node + offset', maxval(abs(centre - [1.0_wp, 2.0_wp, 2.95_wp])), 0.0_wp, &
                     1.0e-15_wp)
    call check_close('BODIES.DAT: body frame = the localframe', maxval(abs(bframe - rot)), 0.0_wp, 0.0_wp)
  end block
  call test_finish()

contains

  !> gap, normal, point of the last spcdx_geometry call, and a right-handed orthonormal frame
  subroutine check_sp(name, g, nref, pref)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: g, nref(3), pref(3)
    call check_close(name//': gap', gap, g, tol)
    call check_close(name//': normal', maxval(abs(frame(:, 3) - nref)), 0.0_wp, tol)
    call check_close(name//': point', maxval(abs(point - pref)), 0.0_wp, tol)
    call check_close(name//': frame right-handed, orthonormal', &
                     maxval(abs(matmul(transpose(frame), frame) - identity3())) + &
                     maxval(abs(cross3(frame(:, 1), frame(:, 2)) - frame(:, 3))), 0.0_wp, tol)
  end subroutine check_sp

  subroutine check_pl(name, k, g, nref, pref)
    character(len=*), intent(in) :: name
    integer, intent(in) :: k
    real(wp), intent(in) :: g, nref(3), pref(3)
    if (k > n) then
      call check_true(name//': contact exists', .false.)
      return
    end if
    call check_close(name//': gap', gaps(k), g, tol)
    call check_close(name//': normal', maxval(abs(frames(:, 3, k) - nref)), 0.0_wp, tol)
    call check_close(name//': point', maxval(abs(points(:, k) - pref)), 0.0_wp, tol)
  end subroutine check_pl
end program test_cylnd_3d
