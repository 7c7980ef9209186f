!> The 2D contact frame, shared by the body models' contact sides
!> (fracas_rbdy2_side, fracas_mailx_side): local (t, n) <-> global components.
module fracas_frame_2d
  use fracas_kinds, only: wp
  implicit none
  private
  public :: frame2_local, frame2_add_local, frame2_global
contains
  include 'frame_2d.inc'
end module fracas_frame_2d
