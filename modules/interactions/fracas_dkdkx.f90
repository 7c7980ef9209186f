!> DKDKx: disk (candidate) against disk (antagonist).
module fracas_dkdkx
  use fracas_kinds, only: wp
  implicit none
  private
  public :: dkdkx_geometry

contains

  !> Gap, normal (from antagonist to candidate) and contact point: on the
  !> candidate's surface, as LMGC90 places it (its outputs: the point is gap/2
  !> from mid-gap, on the candidate's side; the lever arms follow).
  pure subroutine dkdkx_geometry(c_cd, r_cd, c_an, r_an, gap, normal, point)
    real(wp), intent(in) :: c_cd(2), r_cd, c_an(2), r_an
    real(wp), intent(out) :: gap, normal(2), point(2)
    real(wp) :: d(2), dist
    d = c_cd - c_an
    dist = norm2(d)
    if (dist > 0.0_wp) then
      normal = d / dist
    else
      normal = [0.0_wp, 1.0_wp]   ! coincident centres: any direction is as good
    end if
    gap = dist - r_cd - r_an
    point = c_cd - r_cd * normal
  end subroutine dkdkx_geometry
end module fracas_dkdkx
