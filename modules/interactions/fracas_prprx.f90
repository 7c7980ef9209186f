!> PRPRx: POLYR (candidate) against POLYR (antagonist), both convex. Not
!> LMGC90's algorithm (its PRPRx offers several detections: common plane,
!> face-to-face with shrinking, ...): separating axes, then clipping.
!> 1. Axes: the triangles' normals of both polyhedra and the cross products of
!>    their edges; along each, the separation of the two projections. The
!>    largest separation is the gap estimate (exact for face contacts; for a
!>    separated edge-edge or vertex-vertex pair it is at most the distance);
!>    not found if it reaches the alert distance. A face axis is kept unless an
!>    edge axis separates more by 1e-9 of the size (stable face contacts).
!> 2. Face axis: the reference face (all the vertices of its polyhedron in
!>    its plane, a convex polygon) and the incident face of the other (the
!>    face most opposed to it, its vertices in its plane) clipped by the
!>    reference face's sides (Sutherland–Hodgman); each clipped point below
!>    the alert distance is a contact at that point (on the incident face),
!>    gap its distance to the reference plane; more than prprx_max_points
!>    are reduced to the deepest and then, in turn, the farthest from those
!>    kept.
!> 3. Edge axis (only from a pair of supporting edges: both ends of each at
!>    its polyhedron's extreme projection): one contact at the middle of the
!>    two edges' closest points, gap the separation.
!> The normal is the axis from the antagonist to the candidate, the frame
!> tangents_of_normal, the same for all points of the pair.
module fracas_prprx
  use fracas_kinds, only: wp
  use fracas_frame_3d, only: cross3, tangents_of_normal, sort_columns
  implicit none
  private
  public :: prprx_contacts, prprx_max_points

  integer, parameter :: prprx_max_points = 4
  !> Largest number of vertices of a face polygon (the polyhedron's vertices in one plane).
  integer, parameter :: max_face = 64

contains

  pure subroutine prprx_contacts(va, fa, vb, fb, alert, npt, gap, point, frame)
    real(wp), intent(in) :: va(:, :), vb(:, :), alert
    integer, intent(in) :: fa(:, :), fb(:, :)
    integer, intent(out) :: npt
    real(wp), intent(out) :: gap(prprx_max_points), point(3, prprx_max_points), frame(3, 3)
    real(wp) :: size_ab, best, sep, n(3), ca(3), cb(3), axis(3), e1(3), e2(3), p1(3), p2(3), best_axis(3)
    real(wp) :: pa(size(va, 2)), pb(size(vb, 2))
    integer :: k, l, i, j, kind, kbest, ea(2), eb(2), best_ea(2), best_eb(2)
    npt = 0
    gap = 0.0_wp; point = 0.0_wp; frame = 0.0_wp
    ca = sum(va, dim=2) / size(va, 2)
    cb = sum(vb, dim=2) / size(vb, 2)
    size_ab = max(maxval(maxval(va, dim=2) - minval(va, dim=2)), maxval(maxval(vb, dim=2) - minval(vb, dim=2)))
    best = -huge(1.0_wp)
    kind = 0; kbest = 0
    ! face normals of B (reference on the antagonist: n from B to A), then of A
    call best_face(vb, fb, va, 2, best, kind, kbest)
    call best_face(va, fa, vb, 1, best, kind, kbest)
    ! edge-edge axes, oriented from B to A
    do k = 1, size(fa, 2)
      do i = 1, 3
        ea = [fa(i, k), fa(mod(i, 3) + 1, k)]
        if (ea(1) > ea(2)) cycle     ! each edge once (the other triangle lists it reversed)
        e1 = va(:, ea(2)) - va(:, ea(1))
        do l = 1, size(fb, 2)
          do j = 1, 3
            eb = [fb(j, l), fb(mod(j, 3) + 1, l)]
            if (eb(1) > eb(2)) cycle
            e2 = vb(:, eb(2)) - vb(:, eb(1))
            axis = cross3(e1, e2)
            if (norm2(axis) <= 1.0e-9_wp * norm2(e1) * norm2(e2)) cycle
            axis = axis / norm2(axis)
            if (dot_product(axis, ca - cb) < 0.0_wp) axis = -axis
            pa = matmul(axis, va)
            pb = matmul(axis, vb)
            sep = minval(pa) - maxval(pb)
            ! only the pair of supporting edges (both ends at the extreme projections): an
            ! axis is shared by every pair of edges parallel to the two
            if (max(pa(ea(1)), pa(ea(2))) > minval(pa) + 1.0e-9_wp * size_ab .or. &
                min(pb(eb(1)), pb(eb(2))) < maxval(pb) - 1.0e-9_wp * size_ab) cycle
            if (sep > best + 1.0e-9_wp * size_ab) then
              best = sep; kind = 3; best_axis = axis; best_ea = ea; best_eb = eb
            end if
          end do
        end do
      end do
    end do
    if (best >= alert) return
    select case (kind)
    case (1)
      n = normal_of(va, fa(:, kbest))
      call clip_faces(va, fa(:, kbest), n, vb, fb, alert, npt, gap, point)
      frame(:, 3) = -n
    case (2)
      n = normal_of(vb, fb(:, kbest))
      call clip_faces(vb, fb(:, kbest), n, va, fa, alert, npt, gap, point)
      frame(:, 3) = n
    case (3)
      call closest_on_segments(va(:, best_ea(1)), va(:, best_ea(2)), vb(:, best_eb(1)), vb(:, best_eb(2)), p1, p2)
      npt = 1
      gap(1) = best
      point(:, 1) = 0.5_wp * (p1 + p2)
      frame(:, 3) = best_axis
    end select
    if (npt > 0) call tangents_of_normal(frame(:, 3), frame(:, 1), frame(:, 2))
  end subroutine prprx_contacts

  !> Reference face (its polyhedron vr, triangle tri, outward normal nr), the
  !> incident polyhedron vi, fi: clip and keep the points below alert.
  pure subroutine clip_faces(vr, tri, nr, vi, fi, alert, npt, gap, point)
    real(wp), intent(in) :: vr(:, :), nr(3), vi(:, :), alert
    integer, intent(in) :: tri(3), fi(:, :)
    integer, intent(inout) :: npt
    real(wp), intent(inout) :: gap(:), point(:, :)
    real(wp) :: ref(3, max_face), inc(3, 2 * max_face), tmp(3, 2 * max_face), o(3), side(3), d, dmin
    real(wp) :: cand(3, 2 * max_face), cgap(2 * max_face)
    integer :: nref, ninc, ntmp, m, q, kmin, ncand
    logical :: taken(2 * max_face)
    o = vr(:, tri(1))
    call face_polygon(vr, o, nr, ref, nref)
    ! incident face: the triangle most opposed to nr
    dmin = huge(1.0_wp)
    kmin = 1
    do m = 1, size(fi, 2)
      d = dot_product(normal_of(vi, fi(:, m)), nr)
      if (d < dmin) then
        dmin = d; kmin = m
      end if
    end do
    call face_polygon(vi, vi(:, fi(1, kmin)), normal_of(vi, fi(:, kmin)), inc, ninc)
    ! clip by each side of the reference polygon (counter-clockwise about nr)
    do m = 1, nref
      if (ninc == 0) exit
      side = cross3(nr, ref(:, mod(m, nref) + 1) - ref(:, m))   ! inward
      call clip_by_plane(inc, ninc, ref(:, m), side, tmp, ntmp)
      inc(:, 1:ntmp) = tmp(:, 1:ntmp)
      ninc = ntmp
    end do
    ncand = 0
    do m = 1, ninc
      d = dot_product(inc(:, m) - o, nr)
      if (d >= alert) cycle
      ncand = ncand + 1
      cand(:, ncand) = inc(:, m)
      cgap(ncand) = d
    end do
    ! keep the deepest, then in turn the farthest from those kept
    taken = .false.
    do m = 1, min(ncand, prprx_max_points)
      if (m == 1) then
        q = minloc(cgap(1:ncand), dim=1)
      else
        q = 0
        d = -1.0_wp
        do kmin = 1, ncand
          if (taken(kmin)) cycle
          if (min_dist(cand(:, kmin), point(:, 1:m - 1)) > d) then
            d = min_dist(cand(:, kmin), point(:, 1:m - 1)); q = kmin
          end if
        end do
      end if
      taken(q) = .true.
      npt = m
      point(:, m) = cand(:, q)
      gap(m) = cgap(q)
    end do
  end subroutine clip_faces

  !> The face of polyhedron (v, f) along whose outward normal the other
  !> polyhedron's vertices vo are the most separated, if more than best:
  !> best, kind = this_kind and kbest updated.
  pure subroutine best_face(v, f, vo, this_kind, best, kind, kbest)
    real(wp), intent(in) :: v(:, :), vo(:, :)
    integer, intent(in) :: f(:, :), this_kind
    real(wp), intent(inout) :: best
    integer, intent(inout) :: kind, kbest
    real(wp) :: n(3), sep
    integer :: k
    do k = 1, size(f, 2)
      n = normal_of(v, f(:, k))
      sep = minval(matmul(n, vo)) - dot_product(n, v(:, f(1, k)))
      if (sep > best) then
        best = sep; kind = this_kind; kbest = k
      end if
    end do
  end subroutine best_face

  pure real(wp) function min_dist(x, pts) result(d)
    real(wp), intent(in) :: x(3), pts(:, :)
    integer :: k
    d = huge(1.0_wp)
    do k = 1, size(pts, 2)
      d = min(d, norm2(x - pts(:, k)))
    end do
  end function min_dist

  pure function normal_of(v, tri) result(n)
    real(wp), intent(in) :: v(:, :)
    integer, intent(in) :: tri(3)
    real(wp) :: n(3)
    n = cross3(v(:, tri(2)) - v(:, tri(1)), v(:, tri(3)) - v(:, tri(1)))
    n = n / norm2(n)
  end function normal_of

  !> The vertices of v in the plane (o, n) (within 1e-9 of the size), counter-
  !> clockwise about n (sorted by angle about their mean): the face polygon.
  pure subroutine face_polygon(v, o, n, poly, np)
    real(wp), intent(in) :: v(:, :), o(3), n(3)
    real(wp), intent(out) :: poly(3, max_face)
    integer, intent(out) :: np
    real(wp) :: ext, c(3), t1(3), t2(3), ang(max_face)
    integer :: k
    ext = maxval(maxval(v, dim=2) - minval(v, dim=2))
    np = 0
    do k = 1, size(v, 2)
      if (abs(dot_product(v(:, k) - o, n)) > 1.0e-9_wp * ext) cycle
      if (np == max_face) exit
      np = np + 1
      poly(:, np) = v(:, k)
    end do
    c = sum(poly(:, 1:np), dim=2) / np
    call tangents_of_normal(n, t1, t2)
    do k = 1, np
      ang(k) = atan2(dot_product(poly(:, k) - c, t2), dot_product(poly(:, k) - c, t1))
    end do
    call sort_columns(ang(1:np), poly(:, 1:np))
  end subroutine face_polygon

  !> Sutherland–Hodgman: the part of the polygon p(:, 1:np) on the side
  !> (x - o).s >= 0.
  pure subroutine clip_by_plane(p, np, o, s, q, nq)
    real(wp), intent(in) :: p(:, :), o(3), s(3)
    integer, intent(in) :: np
    real(wp), intent(out) :: q(:, :)
    integer, intent(out) :: nq
    real(wp) :: da, db
    integer :: k, kn
    nq = 0
    do k = 1, np
      kn = mod(k, np) + 1
      da = dot_product(p(:, k) - o, s)
      db = dot_product(p(:, kn) - o, s)
      if (da >= 0.0_wp) then
        nq = nq + 1
        q(:, nq) = p(:, k)
      end if
      if ((da >= 0.0_wp) .neqv. (db >= 0.0_wp)) then
        nq = nq + 1
        q(:, nq) = p(:, k) + da / (da - db) * (p(:, kn) - p(:, k))
      end if
    end do
  end subroutine clip_by_plane

  !> Closest points p1 on [a1, b1] and p2 on [a2, b2] (non-parallel segments).
  pure subroutine closest_on_segments(a1, b1, a2, b2, p1, p2)
    real(wp), intent(in) :: a1(3), b1(3), a2(3), b2(3)
    real(wp), intent(out) :: p1(3), p2(3)
    real(wp) :: d1(3), d2(3), r(3), a, e, f, b, c, den, s, t
    d1 = b1 - a1; d2 = b2 - a2; r = a1 - a2
    a = dot_product(d1, d1); e = dot_product(d2, d2); f = dot_product(d2, r)
    b = dot_product(d1, d2); c = dot_product(d1, r)
    den = a * e - b * b
    s = 0.0_wp
    if (den > 0.0_wp) s = max(0.0_wp, min(1.0_wp, (b * f - c * e) / den))
    t = (b * s + f) / e
    if (t < 0.0_wp) then
      t = 0.0_wp; s = max(0.0_wp, min(1.0_wp, -c / a))
    else if (t > 1.0_wp) then
      t = 1.0_wp; s = max(0.0_wp, min(1.0_wp, (b - c) / a))
    end if
    p1 = a1 + s * d1
    p2 = a2 + t * d2
  end subroutine closest_on_segments
end module fracas_prprx
