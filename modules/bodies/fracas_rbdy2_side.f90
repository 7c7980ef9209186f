!> The contact side of a rigid 2D body (rbdy2): H rows, Delassus part, local
!> velocity and impulse of a contact on the body's dofs (rbdy2_side.inc). The
!> body model knows no contact: it is given the frame and lever arms.
module fracas_rbdy2_side
  use fracas_kinds, only: wp
  use fracas_frame_2d, only: frame2_local, frame2_global
  implicit none
  private
  public :: rigid2_h_rows, rigid2_add_delassus, rigid2_add_spin, rigid2_pair_velocity, rigid2_moment, &
            rigid2_add_impulse, rigid2_point_velocity, rigid2_add_velocity, rigid2_side_impulse, &
            rigid2_pair_impulse, rigid2_levers
contains
  include 'rbdy2_side.inc'
end module fracas_rbdy2_side
