!> PLPLx (polygon/polygon) and PLJCx (polygon/wall, the wall seen as its
!> rectangle): contacts between two convex polygons by the common-plane rule.
!> The face of largest separation is the reference face (its polygon is the
!> antagonist); the facing edge of the other polygon (the candidate) is clipped
!> to the reference face, giving one contact point (vertex on face) or two
!> (face on face, so that a resting block carries a moment). Normals are always
!> face normals: no spurious direction from vertex-vertex configurations.
module fracas_plplx
  use fracas_kinds, only: wp
  implicit none
  private
  public :: polygon_pair, polygon_contact_t

  !> Up to two contact points; ref_is_a tells which polygon is the antagonist.
  type :: polygon_contact_t
    integer :: n = 0
    logical :: ref_is_a = .true.
    real(wp) :: normal(2) = 0.0_wp      !< from the antagonist (reference) to the candidate
    real(wp) :: gap(2) = 0.0_wp
    real(wp) :: point(2, 2) = 0.0_wp
    integer :: cdver(2) = 0             !< nearest candidate vertex of each point
    integer :: anseg = 0                !< reference (antagonist) edge
  end type polygon_contact_t

contains

  !> Contacts of convex polygons a and b (vertices (2,n), counter-clockwise)
  !> within the alert distance. a_is_ref forces a to be the antagonist (walls);
  !> otherwise a is preferred unless b's face separates clearly more, so that
  !> the roles do not flip between steps for parallel faces.
  pure subroutine polygon_pair(a, b, alert, a_is_ref, res)
    real(wp), intent(in) :: a(:, :), b(:, :), alert
    logical, intent(in) :: a_is_ref
    type(polygon_contact_t), intent(out) :: res
    real(wp) :: sep_a, sep_b, tol
    integer :: ia, ib
    call max_separation(a, b, sep_a, ia)
    if (sep_a > alert) return
    if (a_is_ref) then
      call clip(a, b, ia, alert, res)
      res%ref_is_a = .true.
      return
    end if
    call max_separation(b, a, sep_b, ib)
    if (sep_b > alert) return
    ! A separating face always wins over a non-separating one (else a separated
    ! pair would be clipped onto a face it crosses and report an overlap).
    tol = 1.0e-3_wp * min(size_of(a), size_of(b))
    if (sep_b > sep_a + tol .or. (sep_b > 0.0_wp .and. sep_a <= 0.0_wp)) then
      call clip(b, a, ib, alert, res)
      res%ref_is_a = .false.
    else
      call clip(a, b, ia, alert, res)
      res%ref_is_a = .true.
    end if
  end subroutine polygon_pair

  pure real(wp) function size_of(p)
    real(wp), intent(in) :: p(:, :)
    size_of = max(maxval(p(1, :)) - minval(p(1, :)), maxval(p(2, :)) - minval(p(2, :)))
  end function size_of

  !> Outward unit normal of edge i (from vertex i to i+1) of a ccw polygon.
  pure function edge_normal(p, i) result(nrm)
    real(wp), intent(in) :: p(:, :)
    integer, intent(in) :: i
    real(wp) :: nrm(2), e(2)
    e = p(:, 1 + mod(i, size(p, 2))) - p(:, i)
    nrm = [e(2), -e(1)] / norm2(e)
  end function edge_normal

  !> Largest over the edges of r of the smallest signed distance of the
  !> vertices of o to that edge's line (positive: separated along it).
  pure subroutine max_separation(r, o, sep, iedge)
    real(wp), intent(in) :: r(:, :), o(:, :)
    real(wp), intent(out) :: sep
    integer, intent(out) :: iedge
    integer :: i, j
    real(wp) :: nrm(2), s
    sep = -huge(1.0_wp)
    iedge = 1
    do i = 1, size(r, 2)
      nrm = edge_normal(r, i)
      s = huge(1.0_wp)
      do j = 1, size(o, 2)
        s = min(s, dot_product(o(:, j) - r(:, i), nrm))
      end do
      if (s > sep) then
        sep = s
        iedge = i
      end if
    end do
  end subroutine max_separation

  !> Clip the edge of inc facing reference edge iref of ref to that edge's extent.
  pure subroutine clip(ref, inc, iref, alert, res)
    real(wp), intent(in) :: ref(:, :), inc(:, :), alert
    integer, intent(in) :: iref
    type(polygon_contact_t), intent(inout) :: res
    real(wp) :: nr(2), tr(2), r0(2), r1(2), len, p0(2), p1(2), s0, s1, d, best, q(2), g, sq, u
    integer :: j, jinc, ninc, k, v0, v1
    ninc = size(inc, 2)
    nr = edge_normal(ref, iref)
    r0 = ref(:, iref)
    r1 = ref(:, 1 + mod(iref, size(ref, 2)))
    len = norm2(r1 - r0)
    tr = (r1 - r0) / len
    ! Incident edge: the most anti-parallel to the reference normal.
    best = huge(1.0_wp)
    jinc = 1
    do j = 1, ninc
      d = dot_product(edge_normal(inc, j), nr)
      if (d < best) then
        best = d
        jinc = j
      end if
    end do
    v0 = jinc
    v1 = 1 + mod(jinc, ninc)
    p0 = inc(:, v0)
    p1 = inc(:, v1)
    s0 = dot_product(p0 - r0, tr)
    s1 = dot_product(p1 - r0, tr)
    res%normal = nr
    res%anseg = iref
    res%n = 0
    do k = 1, 2
      ! Each end of the incident edge, moved along it into the reference face's
      ! extent [0, len]; dropped if the edge does not reach there.
      sq = merge(s0, s1, k == 1)
      if (s1 /= s0) then
        sq = max(0.0_wp, min(len, sq))
        u = (sq - s0) / (s1 - s0)
        if (u < -1.0e-12_wp .or. u > 1.0_wp + 1.0e-12_wp) cycle
        q = p0 + (p1 - p0) * u
      else
        q = merge(p0, p1, k == 1)
        if (sq < 0.0_wp .or. sq > len) cycle
      end if
      g = dot_product(q - r0, nr)
      if (g > alert) cycle
      ! Two points closer than 1e-3 of the face carry no moment between them and
      ! make a singular pair of constraints: keep the one with the smaller gap.
      if (k == 2 .and. res%n == 1) then
        if (abs(dot_product(q - res%point(:, 1), tr)) <= 1.0e-3_wp * len) then
          if (g < res%gap(1)) then
            res%gap(1) = g
            res%point(:, 1) = q - 0.5_wp * g * nr
            res%cdver(1) = v1
          end if
          cycle
        end if
      end if
      res%n = res%n + 1
      res%gap(res%n) = g
      res%point(:, res%n) = q - 0.5_wp * g * nr
      res%cdver(res%n) = merge(v0, v1, k == 1)
    end do
    if (res%n == 0) call corner_to_corner(ref, inc, r0, r1, nr, alert, res)
  end subroutine clip

  !> The facing edge lies beyond the end of the reference face (corners
  !> approaching): one contact at the incident vertex nearest to the face, with
  !> the face normal and the true clearance as gap, so the pair is seen before
  !> it overlaps.
  pure subroutine corner_to_corner(ref, inc, r0, r1, nr, alert, res)
    real(wp), intent(in) :: ref(:, :), inc(:, :), r0(2), r1(2), nr(2), alert
    type(polygon_contact_t), intent(inout) :: res
    real(wp) :: e(2), t, d(2), dist, best, q(2), foot(2)
    integer :: j, jbest
    best = huge(1.0_wp)
    jbest = 1
    e = r1 - r0
    do j = 1, size(inc, 2)
      t = max(0.0_wp, min(1.0_wp, dot_product(inc(:, j) - r0, e) / dot_product(e, e)))
      d = inc(:, j) - (r0 + t * e)
      dist = norm2(d)
      if (dist < best) then
        best = dist
        jbest = j
        foot = r0 + t * e
      end if
    end do
    if (best > alert .or. size(ref, 2) < 3) return
    q = inc(:, jbest)
    res%n = 1
    res%gap(1) = sign(best, dot_product(q - foot, nr))
    res%point(:, 1) = 0.5_wp * (q + foot)
    res%cdver(1) = jbest
  end subroutine corner_to_corner
end module fracas_plplx
