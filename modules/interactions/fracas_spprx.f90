!> SPPRx: sphere (candidate) against POLYR (antagonist, convex polyhedron).
module fracas_spprx
  use fracas_kinds, only: wp
  use fracas_frame_3d, only: cross3, tangents_of_normal
  implicit none
  private
  public :: spprx_geometry, closest_on_triangle

contains

  !> Contact of a sphere (centre c, radius r) with a convex polyhedron (global
  !> vertices vert, outward triangles faces), within the alert distance. As
  !> LMGC90's SPPRx, the point is the projection of the centre on the
  !> polyhedron's surface, the gap the distance to it less r, the normal from
  !> that point to the centre (the face's normal when the projection is inside
  !> a face); a centre inside the polyhedron goes to the nearest face plane
  !> (gap = -depth - r, normal that face's). Frame: tangents_of_normal.
  pure subroutine spprx_geometry(c, r, vert, faces, alert, found, gap, point, frame)
    real(wp), intent(in) :: c(3), r, vert(:, :), alert
    integer, intent(in) :: faces(:, :)
    logical, intent(out) :: found
    real(wp), intent(out) :: gap, point(3), frame(3, 3)
    real(wp) :: q(3), d2, best, nrm(3), sd, sdmax
    integer :: k, kmax
    ! signed distance to each face plane: all <= 0 means the centre is inside
    sdmax = -huge(1.0_wp)
    kmax = 1
    do k = 1, size(faces, 2)
      nrm = face_normal(k)
      sd = dot_product(c - vert(:, faces(1, k)), nrm)
      if (sd > sdmax) then
        sdmax = sd
        kmax = k
      end if
    end do
    if (sdmax <= 0.0_wp) then
      frame(:, 3) = face_normal(kmax)
      point = c - sdmax * frame(:, 3)
      gap = sdmax - r
    else
      best = huge(1.0_wp)
      do k = 1, size(faces, 2)
        q = closest_on_triangle(c, vert(:, faces(1, k)), vert(:, faces(2, k)), vert(:, faces(3, k)))
        d2 = sum((c - q)**2)
        if (d2 < best) then
          best = d2
          point = q
        end if
      end do
      gap = sqrt(best) - r
      frame(:, 3) = (c - point) / sqrt(best)
    end if
    call tangents_of_normal(frame(:, 3), frame(:, 1), frame(:, 2))
    found = gap < alert
  contains
    pure function face_normal(k) result(n)
      integer, intent(in) :: k
      real(wp) :: n(3)
      n = cross3(vert(:, faces(2, k)) - vert(:, faces(1, k)), vert(:, faces(3, k)) - vert(:, faces(1, k)))
      n = n / norm2(n)
    end function face_normal
  end subroutine spprx_geometry

  !> The point of the triangle (a, b, c) closest to p (by the Voronoi regions
  !> of its vertices, edges and face).
  pure function closest_on_triangle(p, a, b, c) result(q)
    real(wp), intent(in) :: p(3), a(3), b(3), c(3)
    real(wp) :: q(3), ab(3), ac(3), ap(3), bp(3), cp(3), d1, d2, d3, d4, d5, d6, va, vb, vc, v, w, den
    ab = b - a; ac = c - a; ap = p - a
    d1 = dot_product(ab, ap); d2 = dot_product(ac, ap)
    if (d1 <= 0.0_wp .and. d2 <= 0.0_wp) then
      q = a
      return
    end if
    bp = p - b
    d3 = dot_product(ab, bp); d4 = dot_product(ac, bp)
    if (d3 >= 0.0_wp .and. d4 <= d3) then
      q = b
      return
    end if
    vc = d1 * d4 - d3 * d2
    if (vc <= 0.0_wp .and. d1 >= 0.0_wp .and. d3 <= 0.0_wp) then
      q = a + d1 / (d1 - d3) * ab
      return
    end if
    cp = p - c
    d5 = dot_product(ab, cp); d6 = dot_product(ac, cp)
    if (d6 >= 0.0_wp .and. d5 <= d6) then
      q = c
      return
    end if
    vb = d5 * d2 - d1 * d6
    if (vb <= 0.0_wp .and. d2 >= 0.0_wp .and. d6 <= 0.0_wp) then
      q = a + d2 / (d2 - d6) * ac
      return
    end if
    va = d3 * d6 - d5 * d4
    if (va <= 0.0_wp .and. d4 - d3 >= 0.0_wp .and. d5 - d6 >= 0.0_wp) then
      q = b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)
      return
    end if
    den = 1.0_wp / (va + vb + vc)
    v = vb * den
    w = vc * den
    q = a + v * ab + w * ac
  end function closest_on_triangle
end module fracas_spprx
