!> CDPLx: CYLND (candidate) against PLANx (antagonist), as LMGC90's CDPLx:
!> each end of the CYLND is a sphere of radius byrd at +-High along its axis,
!> and each end sphere within the alert distance of the PLANx is one contact
!> (so up to 2: a CYLND lying on a plane rests on its two ends).
!> Differences from LMGC90, which tests the end's centre against the box
!> enlarged by High (not byrd) in the plane and puts the point on the plane's
!> face: each end sphere is SPPLx's sphere (fracas_spplx: either face, the rim
!> rounded, the point mid-gap), so a CYLND and a SPHER of the same radius meet
!> a PLANx alike.
module fracas_cdplx
  use fracas_kinds, only: wp
  use fracas_spplx, only: spplx_geometry
  implicit none
  private
  public :: cdplx_contacts, cdplx_max_points

  integer, parameter :: cdplx_max_points = 2

contains

  !> Contacts of a CYLND (centre c, unit axis e, half length h, radius r) with
  !> a PLANx (centre p, frame pf, half axes a) within alert: n of them, each
  !> gap(k), point(:, k), frame(:, :, k) (columns t1, t2, n, n from the plane
  !> to the CYLND); the end at c - h e first.
  pure subroutine cdplx_contacts(c, e, h, r, p, pf, a, alert, n, gap, point, frame)
    real(wp), intent(in) :: c(3), e(3), h, r, p(3), pf(3, 3), a(3), alert
    integer, intent(out) :: n
    real(wp), intent(out) :: gap(cdplx_max_points), point(3, cdplx_max_points), frame(3, 3, cdplx_max_points)
    integer :: k
    logical :: found
    n = 0
    gap = 0.0_wp; point = 0.0_wp; frame = 0.0_wp
    do k = -1, 1, 2
      call spplx_geometry(c + k * h * e, r, p, pf, a, alert, found, gap(n + 1), point(:, n + 1), frame(:, :, n + 1))
      if (found) n = n + 1
    end do
  end subroutine cdplx_contacts
end module fracas_cdplx
