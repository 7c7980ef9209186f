!> DKJCx: disk (candidate) against a JONCx wall (antagonist): a segment of half
!> length ax1 along the body's x axis, thickened by ax2 (rounded ends).
module fracas_dkjcx
  use fracas_kinds, only: wp
  implicit none
  private
  public :: dkjcx_geometry

contains

  !> c_jc and angle place the wall; the normal points from the wall to the disk.
  pure subroutine dkjcx_geometry(c_cd, r_cd, c_jc, angle, ax1, ax2, gap, normal, point)
    real(wp), intent(in) :: c_cd(2), r_cd, c_jc(2), angle, ax1, ax2
    real(wp), intent(out) :: gap, normal(2), point(2)
    real(wp) :: axis(2), s, closest(2), d(2), dist
    axis = [cos(angle), sin(angle)]
    s = dot_product(c_cd - c_jc, axis)
    if (abs(s) < ax1) then
      ! Facing the flat side: the normal is the wall's own normal, exactly.
      normal = [-axis(2), axis(1)]
      dist = dot_product(c_cd - c_jc, normal)
      if (dist < 0.0_wp) then
        normal = -normal
        dist = -dist
      end if
      closest = c_jc + s * axis
    else
      ! Beyond an end: the rounded cap around the segment's end point.
      s = sign(ax1, s)
      closest = c_jc + s * axis
      d = c_cd - closest
      dist = norm2(d)
      if (dist > 0.0_wp) then
        normal = d / dist
      else
        normal = [-axis(2), axis(1)]
      end if
    end if
    gap = dist - r_cd - ax2
    ! On the disk's surface, as LMGC90 puts it (its lever arm is the radius)
    point = c_cd - r_cd * normal
  end subroutine dkjcx_geometry
end module fracas_dkjcx
