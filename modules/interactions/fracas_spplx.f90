!> SPPLx: sphere (candidate) against PLANx (antagonist, a flat box of half
!> lengths a1, a2 along its axes alpha, beta and half thickness a3 along its
!> third axis gamma, the plane's normal).
module fracas_spplx
  use fracas_kinds, only: wp
  use fracas_frame_3d, only: tangents_of_normal
  implicit none
  private
  public :: spplx_geometry, planx_face_frame

contains

  !> Contact of a sphere (centre c, radius r) with a PLANx (centre p, frame pf:
  !> columns alpha, beta, gamma; half axes a), within the alert distance:
  !> found is false when the sphere is farther than alert from the box's
  !> either face or beyond its rim. As LMGC90's SPPLx: over a face (the
  !> centre's projection within a1, a2) the normal is +-gamma (the face on the
  !> sphere's side) and gap = |(c - p).gamma| - a3 - r; beyond the face but
  !> within r + a3 of its rim, the normal goes from the nearest point of the
  !> mid-plane rectangle to the centre and gap = distance - r - a3 (the rim
  !> taken rounded). Frame columns t1, t2, n, t1 x t2 = n: over the upper face
  !> (alpha, beta, gamma), over the lower (alpha, -beta, -gamma), at the rim
  !> tangents_of_normal. Point: mid-gap on the normal through the centre.
  pure subroutine spplx_geometry(c, r, p, pf, a, alert, found, gap, point, frame)
    real(wp), intent(in) :: c(3), r, p(3), pf(3, 3), a(3), alert
    logical, intent(out) :: found
    real(wp), intent(out) :: gap, point(3), frame(3, 3)
    real(wp) :: s(3), q(3), dist
    s = matmul(c - p, pf)          ! the centre in the box's axes
    found = abs(s(3)) - r - a(3) < alert .and. abs(s(1)) < r + a(1) + a(3) .and. abs(s(2)) < r + a(2) + a(3)
    gap = 0.0_wp; point = 0.0_wp; frame = 0.0_wp
    if (.not. found) return
    if (abs(s(1)) < a(1) .and. abs(s(2)) < a(2)) then
      frame = planx_face_frame(pf, s(3) >= 0.0_wp)
      gap = abs(s(3)) - a(3) - r
    else
      q = [max(-a(1), min(a(1), s(1))), max(-a(2), min(a(2), s(2))), 0.0_wp]
      dist = norm2(s - q)
      frame(:, 3) = matmul(pf, s - q) / dist
      call tangents_of_normal(frame(:, 3), frame(:, 1), frame(:, 2))
      gap = dist - r - a(3)
      found = gap < alert
      if (.not. found) return
    end if
    point = c - (r + 0.5_wp * gap) * frame(:, 3)
  end subroutine spplx_geometry

  !> The contact frame over a PLANx's face (pf: its axes alpha, beta, gamma):
  !> (alpha, beta, gamma) over the upper face, (alpha, -beta, -gamma) over the
  !> lower one (n from the plane towards the other body, t1 x t2 = n).
  pure function planx_face_frame(pf, upper) result(frame)
    real(wp), intent(in) :: pf(3, 3)
    logical, intent(in) :: upper
    real(wp) :: frame(3, 3)
    frame = pf
    if (.not. upper) frame(:, 2:3) = -pf(:, 2:3)
  end function planx_face_frame
end module fracas_spplx
