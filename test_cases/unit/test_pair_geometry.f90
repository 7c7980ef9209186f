!> Unit tests of the fine detection geometry of DKDKx, DKJCx and DKKDx against
!> hand-computed values (distances between circles and segments).
program test_pair_geometry
  use fracas_kinds, only: wp
  use fracas_dkdkx, only: dkdkx_geometry
  use fracas_dkjcx, only: dkjcx_geometry
  use fracas_dkkdx, only: dkkdx_geometry
  use fracas_testing, only: check_close, test_finish
  implicit none
  real(wp) :: gap, n(2), p(2)
  real(wp), parameter :: pi = acos(-1.0_wp)

  ! Disks of radii 1 and 2 with centres 3.5 apart along (3,4)/5: gap 0.5.
  call dkdkx_geometry([3.0_wp * 0.7_wp, 4.0_wp * 0.7_wp], 1.0_wp, [0.0_wp, 0.0_wp], 2.0_wp, gap, n, p)
  call check_close('DKDKx gap', gap, 0.5_wp, 1e-14_wp)
  call check_close('DKDKx normal x', n(1), 0.6_wp, 1e-14_wp)
  ! The point is on the candidate's surface, as LMGC90 puts it: 3.5 - 1 along n.
  call check_close('DKDKx point y (on the candidate)', p(2), 2.5_wp * 0.8_wp, 1e-14_wp)

  ! Disk r = 0.1 at (0.3, 0.12) above a horizontal wall of half length 1,
  ! half thickness 0.01 centred at 0: gap = 0.12 - 0.1 - 0.01 = 0.01, n = (0,1).
  call dkjcx_geometry([0.3_wp, 0.12_wp], 0.1_wp, [0.0_wp, 0.0_wp], 0.0_wp, 1.0_wp, 0.01_wp, gap, n, p)
  call check_close('DKJCx flat gap', gap, 0.01_wp, 1e-14_wp)
  call check_close('DKJCx flat normal y', n(2), 1.0_wp, 1e-14_wp)
  ! Same wall rotated by pi/2 (vertical), disk to its left: normal (-1, 0).
  call dkjcx_geometry([-0.2_wp, 0.5_wp], 0.1_wp, [0.0_wp, 0.0_wp], pi / 2, 1.0_wp, 0.01_wp, gap, n, p)
  call check_close('DKJCx rotated gap', gap, 0.09_wp, 1e-14_wp)
  call check_close('DKJCx rotated normal x', n(1), -1.0_wp, 1e-14_wp)
  ! Beyond the end of the wall: distance to the rounded end (1, 0) is 0.5.
  call dkjcx_geometry([1.3_wp, 0.4_wp], 0.1_wp, [0.0_wp, 0.0_wp], 0.0_wp, 1.0_wp, 0.01_wp, gap, n, p)
  call check_close('DKJCx end-cap gap', gap, 0.39_wp, 1e-14_wp)

  ! Disk r = 0.1 inside a drum of radius 1 at distance 0.8 from its centre:
  ! gap 0.1, normal pointing back to the centre.
  call dkkdx_geometry([0.0_wp, -0.8_wp], 0.1_wp, [0.0_wp, 0.0_wp], 1.0_wp, gap, n, p)
  call check_close('DKKDx gap', gap, 0.1_wp, 1e-14_wp)
  call check_close('DKKDx normal y', n(2), 1.0_wp, 1e-14_wp)
  call check_close('DKKDx point y', p(2), -0.95_wp, 1e-14_wp)
  call test_finish()
end program test_pair_geometry
