!> DKKDx: disk (candidate) inside an xKSID (antagonist), the inner side of a
!> hollow disk such as a drum.
module fracas_dkkdx
  use fracas_kinds, only: wp
  implicit none
  private
  public :: dkkdx_geometry

contains

  !> The normal points from the drum wall towards its centre (into the disk).
  pure subroutine dkkdx_geometry(c_cd, r_cd, c_an, r_an, gap, normal, point)
    real(wp), intent(in) :: c_cd(2), r_cd, c_an(2), r_an
    real(wp), intent(out) :: gap, normal(2), point(2)
    real(wp) :: d(2), dist, outward(2)
    d = c_cd - c_an
    dist = norm2(d)
    if (dist > 0.0_wp) then
      outward = d / dist
    else
      outward = [0.0_wp, -1.0_wp]
    end if
    normal = -outward
    gap = r_an - dist - r_cd
    point = c_an + (r_an - 0.5_wp * gap) * outward
  end subroutine dkkdx_geometry
end module fracas_dkkdx
