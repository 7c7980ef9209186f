!> The contact side of a rigid 3D body (rbdy3): H rows, Delassus part, local
!> velocity and impulse of a contact on the body's dofs (rbdy3_side.inc). The
!> body model knows no contact: it is given the contact frame and lever arms.
module fracas_rbdy3_side
  use fracas_kinds, only: wp
  use fracas_frame_3d, only: cross3
  implicit none
  private
  public :: rigid3_levers, rigid3_h_rows, rigid3_add_delassus, rigid3_add_velocity, rigid3_add_impulse, &
            rigid3_pair_velocity, rigid3_pair_impulse, rigid3_point_velocity
contains
  include 'rbdy3_side.inc'
end module fracas_rbdy3_side
