!> PRPLx: POLYR (candidate, convex polyhedron) against PLANx (antagonist).
module fracas_prplx
  use fracas_kinds, only: wp
  use fracas_spplx, only: planx_face_frame
  implicit none
  private
  public :: prplx_contacts, prplx_max_points

  !> Contact points kept per pair, as LMGC90's PRPLx (the deepest vertices).
  integer, parameter :: prplx_max_points = 4

contains

  !> Contacts of a polyhedron (vertices vert(3, nv), global; centre c) with a
  !> PLANx (centre p, axes pf, half axes a), as LMGC90's PRPLx: the face on the
  !> polyhedron's centre side; every vertex over the face (within a1, a2 plus
  !> the alert distance) with gap = (v - p).n - a3 < alert is a candidate, the
  !> prplx_max_points deepest are kept (the first ones met on ties). Each
  !> contact is at its vertex (LMGC90's point), normal n = +-gamma, frame
  !> planx_face_frame (the same for all). Out: npt points, their vertex
  !> numbers, gaps and points.
  pure subroutine prplx_contacts(vert, c, p, pf, a, alert, npt, ivert, gap, point, frame)
    real(wp), intent(in) :: vert(:, :), c(3), p(3), pf(3, 3), a(3), alert
    integer, intent(out) :: npt, ivert(prplx_max_points)
    real(wp), intent(out) :: gap(prplx_max_points), point(3, prplx_max_points), frame(3, 3)
    real(wp) :: s(3), g
    integer :: k, worst
    frame = planx_face_frame(pf, dot_product(c - p, pf(:, 3)) >= 0.0_wp)
    npt = 0
    ivert = 0; gap = 0.0_wp; point = 0.0_wp
    do k = 1, size(vert, 2)
      s = matmul(vert(:, k) - p, pf)
      if (abs(s(1)) > a(1) + alert .or. abs(s(2)) > a(2) + alert) cycle
      g = dot_product(vert(:, k) - p, frame(:, 3)) - a(3)
      if (g >= alert) cycle
      if (npt < prplx_max_points) then
        npt = npt + 1
        worst = npt
      else
        worst = maxloc(gap, dim=1)
        if (g >= gap(worst)) cycle
      end if
      ivert(worst) = k
      gap(worst) = g
      point(:, worst) = vert(:, k)
    end do
  end subroutine prplx_contacts
end module fracas_prplx
