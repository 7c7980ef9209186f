!> Polygon contact geometry against hand-computed values: a block on a block
!> gives two points at the ends of the overlap of the faces, a corner on a face
!> one point, normals are face normals; disk against polygon edge and corner.
program test_polygon_geometry
  use fracas_kinds, only: wp
  use fracas_plplx, only: polygon_pair, polygon_contact_t
  use fracas_dkplx, only: dkplx_geometry
  use fracas_testing, only: check_close, check_true, test_finish
  implicit none
  real(wp) :: a(2, 4), b(2, 4), d(2, 4), gap, n(2), p(2), s2
  type(polygon_contact_t) :: pc
  integer :: iedge

  a = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
  ! Unit square shifted by (0.3, 1.01): face on face, overlap x in [0.3, 1].
  b(1, :) = a(1, :) + 0.3_wp
  b(2, :) = a(2, :) + 1.01_wp
  call polygon_pair(a, b, 0.05_wp, .false., pc)
  call check_close('face on face: two points', real(pc%n, wp), 2.0_wp, 0.0_wp)
  call check_true('face on face: lower block is the reference (antagonist)', pc%ref_is_a)
  call check_close('face on face: gap 1', pc%gap(1), 0.01_wp, 1e-14_wp)
  call check_close('face on face: gap 2', pc%gap(2), 0.01_wp, 1e-14_wp)
  call check_close('face on face: normal y', pc%normal(2), 1.0_wp, 1e-14_wp)
  call check_close('face on face: points span the overlap', abs(pc%point(1, 1) - pc%point(1, 2)), 0.7_wp, 1e-14_wp)
  call check_close('face on face: point in the middle of the gap', pc%point(2, 1), 1.005_wp, 1e-14_wp)
  ! Out of alert range: nothing.
  b(2, :) = a(2, :) + 1.2_wp
  call polygon_pair(a, b, 0.05_wp, .false., pc)
  call check_close('separated blocks: no point', real(pc%n, wp), 0.0_wp, 0.0_wp)
  ! A square turned by 45 degrees standing on its corner 0.01 above the top face.
  s2 = sqrt(0.5_wp)
  d = reshape([0.5_wp, 1.01_wp, 0.5_wp + s2, 1.01_wp + s2, 0.5_wp, 1.01_wp + 2 * s2, 0.5_wp - s2, 1.01_wp + s2], [2, 4])
  call polygon_pair(a, d, 0.05_wp, .false., pc)
  call check_close('corner on face: one point', real(pc%n, wp), 1.0_wp, 0.0_wp)
  call check_close('corner on face: gap', pc%gap(1), 0.01_wp, 1e-14_wp)
  call check_close('corner on face: face normal', pc%normal(2), 1.0_wp, 1e-14_wp)
  call check_close('corner on face: point x', pc%point(1, 1), 0.5_wp, 1e-14_wp)
  ! Overlapping blocks (penetration 0.02): negative gaps.
  b(1, :) = a(1, :) + 0.3_wp
  b(2, :) = a(2, :) + 0.98_wp
  call polygon_pair(a, b, 0.05_wp, .false., pc)
  call check_close('overlap: gap', pc%gap(1), -0.02_wp, 1e-14_wp)

  ! Disk r = 0.2 centred at (0.5, 1.3) above the top edge: gap 0.1, normal (0, 1).
  call dkplx_geometry([0.5_wp, 1.3_wp], 0.2_wp, a, gap, n, p, iedge)
  call check_close('DKPLx edge gap', gap, 0.1_wp, 1e-14_wp)
  call check_close('DKPLx edge normal y', n(2), 1.0_wp, 1e-14_wp)
  call check_close('DKPLx edge index (top edge is 3)', real(iedge, wp), 3.0_wp, 0.0_wp)
  ! Disk beyond the corner (1, 1) along the diagonal: distance 0.3, gap 0.1.
  call dkplx_geometry([1.0_wp + 0.3_wp * s2, 1.0_wp + 0.3_wp * s2], 0.2_wp, a, gap, n, p, iedge)
  call check_close('DKPLx corner gap', gap, 0.1_wp, 1e-14_wp)
  call check_close('DKPLx corner normal x', n(1), s2, 1e-14_wp)
  call test_finish()
end program test_polygon_geometry
