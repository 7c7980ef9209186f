!> DKPLx: disk (candidate) against a convex polygon (antagonist).
module fracas_dkplx
  use fracas_kinds, only: wp
  implicit none
  private
  public :: dkplx_geometry

contains

  !> Gap, normal (from the polygon to the disk), contact point and the polygon
  !> edge involved. Facing an edge, the normal is that edge's normal exactly;
  !> near a vertex it points from the vertex to the centre. The contact point
  !> is on the polygon's boundary, as LMGC90 places it (its outputs).
  pure subroutine dkplx_geometry(c, r, p, gap, normal, point, iedge)
    real(wp), intent(in) :: c(2), r, p(:, :)
    real(wp), intent(out) :: gap, normal(2), point(2)
    integer, intent(out) :: iedge
    integer :: i, j, n
    real(wp) :: e(2), nrm(2), s, smax, t, len, d(2), dist, best, closest(2)
    n = size(p, 2)
    smax = -huge(1.0_wp)
    iedge = 1
    do i = 1, n
      j = 1 + mod(i, n)
      e = p(:, j) - p(:, i)
      nrm = [e(2), -e(1)] / norm2(e)
      s = dot_product(c - p(:, i), nrm)
      if (s > smax) then
        smax = s
        iedge = i
      end if
    end do
    i = iedge
    j = 1 + mod(i, n)
    e = p(:, j) - p(:, i)
    len = norm2(e)
    t = dot_product(c - p(:, i), e) / len
    if (smax <= 0.0_wp .or. (t >= 0.0_wp .and. t <= len)) then
      ! Inside, or facing the edge of largest separation.
      normal = [e(2), -e(1)] / len
      gap = smax - r
      point = c - smax * normal
      return
    end if
    ! Outside beyond an edge end: the nearest point of the boundary.
    best = huge(1.0_wp)
    closest = p(:, 1)
    do i = 1, n
      j = 1 + mod(i, n)
      e = p(:, j) - p(:, i)
      t = max(0.0_wp, min(1.0_wp, dot_product(c - p(:, i), e) / dot_product(e, e)))
      d = c - (p(:, i) + t * e)
      dist = norm2(d)
      if (dist < best) then
        best = dist
        closest = p(:, i) + t * e
        iedge = i
      end if
    end do
    normal = (c - closest) / best
    gap = best - r
    point = closest
  end subroutine dkplx_geometry
end module fracas_dkplx
