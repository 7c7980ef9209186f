!> SPSPx: sphere (candidate) against sphere (antagonist).
module fracas_spspx
  use fracas_kinds, only: wp
  use fracas_frame_3d, only: tangents_of_normal
  implicit none
  private
  public :: spspx_geometry

contains

  !> Gap, contact point and frame (columns t1, t2, n; n from the antagonist to
  !> the candidate, t1 x t2 = n, fracas_frame_3d: tangents_of_normal) of two
  !> spheres. The point is mid-gap on the line of centres, as LMGC90's SPSPx
  !> places it.
  pure subroutine spspx_geometry(c_cd, r_cd, c_an, r_an, gap, point, frame)
    real(wp), intent(in) :: c_cd(3), r_cd, c_an(3), r_an
    real(wp), intent(out) :: gap, point(3), frame(3, 3)
    real(wp) :: d(3), dist
    d = c_cd - c_an
    dist = norm2(d)
    if (dist > 0.0_wp) then
      frame(:, 3) = d / dist
    else
      frame(:, 3) = [0.0_wp, 0.0_wp, 1.0_wp]   ! coincident centres: any direction is as good
    end if
    call tangents_of_normal(frame(:, 3), frame(:, 1), frame(:, 2))
    gap = dist - r_cd - r_an
    point = c_an + (r_an + 0.5_wp * gap) * frame(:, 3)
  end subroutine spspx_geometry
end module fracas_spspx
