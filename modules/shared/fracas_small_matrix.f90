!> Small dense matrices in closed form: the 3 x 3 blocks of 3D contacts.
module fracas_small_matrix
  use fracas_kinds, only: wp
  implicit none
  private
  public :: adjugate_3x3

contains

  !> The adjugate (transposed cofactors) of a 3 x 3 matrix and its determinant:
  !> the inverse is adj / det where det is not zero.
  pure subroutine adjugate_3x3(a, adj, det)
    real(wp), intent(in) :: a(3, 3)
    real(wp), intent(out) :: adj(3, 3), det
    adj(1, 1) = a(2, 2) * a(3, 3) - a(2, 3) * a(3, 2)
    adj(1, 2) = a(1, 3) * a(3, 2) - a(1, 2) * a(3, 3)
    adj(1, 3) = a(1, 2) * a(2, 3) - a(1, 3) * a(2, 2)
    adj(2, 1) = a(2, 3) * a(3, 1) - a(2, 1) * a(3, 3)
    adj(2, 2) = a(1, 1) * a(3, 3) - a(1, 3) * a(3, 1)
    adj(2, 3) = a(1, 3) * a(2, 1) - a(1, 1) * a(2, 3)
    adj(3, 1) = a(2, 1) * a(3, 2) - a(2, 2) * a(3, 1)
    adj(3, 2) = a(1, 2) * a(3, 1) - a(1, 1) * a(3, 2)
    adj(3, 3) = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)
    det = a(1, 1) * adj(1, 1) + a(1, 2) * adj(2, 1) + a(1, 3) * adj(3, 1)
  end subroutine adjugate_3x3
end module fracas_small_matrix
