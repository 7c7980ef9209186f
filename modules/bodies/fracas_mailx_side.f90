!> The contact side of a meshed 2D body (mailx): node weights, G = C H^T and
!> H G, local velocity and impulse of a contact on the body's contact dofs
!> (mailx_side.inc). The body model knows no contact: it is given the frame,
!> nodes and weights.
module fracas_mailx_side
  use fracas_kinds, only: wp
  implicit none
  private
  public :: mesh2_add_node, mesh2_point_velocity, mesh2_add_g, mesh2_add_hg, mesh2_add_impulse
contains
  include 'mailx_side.inc'
end module fracas_mailx_side
