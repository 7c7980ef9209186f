!> SPCDx: sphere (candidate) against CYLND (antagonist), the CYLND taken as a
!> capsule: the points within its radius of its axis segment.
!> LMGC90's SPCDx takes the cylinder's ends flat (at +-High along the axis,
!> the rim a circle) while its CDPLx rounds them (a sphere of radius byrd at
!> each end); we round them in both, so one CYLND is one shape: a sphere on
!> the axis beyond an end has a gap smaller by byrd than LMGC90's.
module fracas_spcdx
  use fracas_kinds, only: wp
  use fracas_spspx, only: spspx_geometry
  implicit none
  private
  public :: spcdx_geometry, capsule_axis_point

contains

  !> Gap, point (mid-gap) and frame (columns t1, t2, n, n from the CYLND to
  !> the sphere) of a sphere (centre c, radius r) and a CYLND (centre p, unit
  !> axis e, half length h, radius rc): the sphere against the sphere of radius
  !> rc at the nearest point of the axis segment.
  pure subroutine spcdx_geometry(c, r, p, e, h, rc, gap, point, frame)
    real(wp), intent(in) :: c(3), r, p(3), e(3), h, rc
    real(wp), intent(out) :: gap, point(3), frame(3, 3)
    call spspx_geometry(c, r, capsule_axis_point(c, p, e, h), rc, gap, point, frame)
  end subroutine spcdx_geometry

  !> The point of the segment p +- h e nearest to x.
  pure function capsule_axis_point(x, p, e, h) result(q)
    real(wp), intent(in) :: x(3), p(3), e(3), h
    real(wp) :: q(3)
    q = p + max(-h, min(h, dot_product(x - p, e))) * e
  end function capsule_axis_point
end module fracas_spcdx
