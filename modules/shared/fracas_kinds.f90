!> The one working precision of Fracas and the integer kinds used for counts.
module fracas_kinds
  use, intrinsic :: iso_fortran_env, only: real64, int32, int64
  implicit none
  private
  public :: wp, ik, i8

  integer, parameter :: wp = real64   !< working precision for every real
  integer, parameter :: ik = int32    !< default integer (ids, counts)
  integer, parameter :: i8 = int64    !< long counters (clock ticks, sizes)
end module fracas_kinds
