!> The one working precision of Fracas and the integer kinds used for counts.
module fracas_kinds
  use, intrinsic :: iso_fortran_env, only: real64, int32, int64
  implicit none
  private
  public :: wp, ik, i8, resolvable_length

  integer, parameter :: wp = real64   !< working precision for every real
  integer, parameter :: ik = int32    !< default integer (ids, counts)
  integer, parameter :: i8 = int64    !< long counters (clock ticks, sizes)

contains

  !> Largest coordinate (and step displacement) at which a body of this size
  !> is still resolved to a thousandth of its size: a coordinate x is stored to
  !> about |x| eps (the state checks of the body models and fracas_state_guard).
  elemental real(wp) function resolvable_length(size) result(l)
    real(wp), intent(in) :: size
    l = 1.0e-3_wp * size / epsilon(1.0_wp)
  end function resolvable_length
end module fracas_kinds
