!> Work arrays refilled on every use (the solver's packed records, slot maps):
!> one way to make sure an array has room for n entries.
module fracas_grow
  use fracas_kinds, only: wp
  implicit none
  private
  public :: grow

  !> call grow(a, n [, fill]) for a(:), call grow(a, m, n) for a(m, :): when a is not
  !> allocated or holds fewer than n entries (columns), it is allocated anew with
  !> max(n, 16) of them, its contents dropped (fill, if given, sets the new array;
  !> a kept array keeps its contents).
  interface grow
    module procedure grow_int, grow_real, grow_int2, grow_real2
  end interface grow

  integer, parameter :: min_size = 16

contains

  subroutine grow_int(a, n, fill)
    integer, allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    integer, intent(in), optional :: fill
    if (allocated(a)) then
      if (size(a) >= n) return
      deallocate (a)
    end if
    allocate (a(max(n, min_size)))
    if (present(fill)) a = fill
  end subroutine grow_int

  subroutine grow_real(a, n)
    real(wp), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    if (allocated(a)) then
      if (size(a) >= n) return
      deallocate (a)
    end if
    allocate (a(max(n, min_size)))
  end subroutine grow_real

  subroutine grow_int2(a, m, n)
    integer, allocatable, intent(inout) :: a(:, :)
    integer, intent(in) :: m, n
    if (allocated(a)) then
      if (size(a, 1) == m .and. size(a, 2) >= n) return
      deallocate (a)
    end if
    allocate (a(m, max(n, min_size)))
  end subroutine grow_int2

  subroutine grow_real2(a, m, n)
    real(wp), allocatable, intent(inout) :: a(:, :)
    integer, intent(in) :: m, n
    if (allocated(a)) then
      if (size(a, 1) == m .and. size(a, 2) >= n) return
      deallocate (a)
    end if
    allocate (a(m, max(n, min_size)))
  end subroutine grow_real2
end module fracas_grow
