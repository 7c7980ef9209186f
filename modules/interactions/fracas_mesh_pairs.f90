!> Geometry of contacts with mesh contactors: a point against a polyline of
!> mesh nodes (CLALp, PLALp) and a point against one segment (DKALp).
!> Polylines are walked with the body on their right: the outward normal of
!> segment a -> b is (-d2, d1)/|d|, d = b - a, and the local tangent
!> t = (n2, -n1) is the segment's direction.
module fracas_mesh_pairs
  use fracas_kinds, only: wp
  implicit none
  private
  public :: point_polyline, point_segment_distance

  !> How far past a segment's end a point may project and still count as
  !> facing it (fraction of the segment length): closes the gaps at polyline
  !> joints without reaching round a corner.
  real(wp), parameter :: end_tolerance = 1.0e-3_wp

contains

  !> The segment of the polyline (nodes(k) -> nodes(k+1), coordinates xn) that
  !> point p faces, with the smallest |gap| among those whose gap is within
  !> [-depth, reach]; facing also requires the candidate's outward normal
  !> cd_normal to be opposed to the segment's (no test if cd_normal = 0).
  !> A point deeper than the alert distance (depth) behind a segment is not a
  !> contact: in a mesh, points of one element lie behind the edges of its
  !> neighbours.
  !> Returns the segment, the projection parameter s in [0, 1] along it, the
  !> gap and the segment's outward normal; beyond: p projects past the
  !> segment's end (within end_tolerance), not onto it.
  pure subroutine point_polyline(p, xn, nodes, reach, depth, cd_normal, found, seg, s, gap, normal, beyond)
    real(wp), intent(in) :: p(2), xn(:, :), reach, depth, cd_normal(2)
    integer, intent(in) :: nodes(:)
    logical, intent(out) :: found
    integer, intent(out) :: seg
    real(wp), intent(out) :: s, gap, normal(2)
    logical, intent(out), optional :: beyond
    integer :: k
    real(wp) :: a(2), d(2), len2, sk, gk, nk(2), best
    found = .false.
    seg = 0; s = 0.0_wp; gap = 0.0_wp; normal = 0.0_wp
    if (present(beyond)) beyond = .false.
    best = huge(1.0_wp)
    do k = 1, size(nodes) - 1
      a = xn(:, nodes(k))
      d = xn(:, nodes(k + 1)) - a
      len2 = sum(d**2)
      if (len2 <= 0.0_wp) cycle
      sk = dot_product(p - a, d) / len2
      if (sk < -end_tolerance .or. sk > 1.0_wp + end_tolerance) cycle
      nk = [-d(2), d(1)] / sqrt(len2)
      if (dot_product(nk, cd_normal) > 0.0_wp) cycle
      gk = dot_product(p - a, nk)
      if (gk > reach .or. gk < -depth) cycle
      if (abs(gk) < best) then
        best = abs(gk)
        found = .true.
        seg = k
        s = min(1.0_wp, max(0.0_wp, sk))
        gap = gk
        normal = nk
        if (present(beyond)) beyond = sk < 0.0_wp .or. sk > 1.0_wp
      end if
    end do
  end subroutine point_polyline

  !> Distance from p to the segment [a, b]: the nearest point (parameter s in
  !> [0, 1]), the distance and the unit normal from the nearest point to p
  !> (the segment's outward normal if p lies on it).
  pure subroutine point_segment_distance(p, a, b, s, dist, normal, nearest)
    real(wp), intent(in) :: p(2), a(2), b(2)
    real(wp), intent(out) :: s, dist, normal(2), nearest(2)
    real(wp) :: d(2), len2, r(2)
    d = b - a
    len2 = sum(d**2)
    s = 0.0_wp
    if (len2 > 0.0_wp) s = min(1.0_wp, max(0.0_wp, dot_product(p - a, d) / len2))
    nearest = a + s * d
    r = p - nearest
    dist = norm2(r)
    if (dist > 0.0_wp) then
      normal = r / dist
    else
      normal = [-d(2), d(1)] / max(sqrt(len2), tiny(1.0_wp))
    end if
  end subroutine point_segment_distance
end module fracas_mesh_pairs
