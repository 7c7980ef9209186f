!> A small seeded random generator (xorshift64*), identical on every compiler
!> and platform, so a shuffled NLGS order is reproducible from its seed.
module fracas_random
  use fracas_kinds, only: i8
  implicit none
  private
  public :: rng_t, rng_seed, rng_below, rng_permute

  type :: rng_t
    integer(i8) :: state = 88172645463325252_i8
  end type rng_t

contains

  subroutine rng_seed(rng, seed)
    type(rng_t), intent(out) :: rng
    integer, intent(in) :: seed
    integer :: i
    integer(i8) :: dummy
    rng%state = ieor(88172645463325252_i8, int(seed, i8) * 2654435761_i8)
    if (rng%state == 0_i8) rng%state = 1_i8
    do i = 1, 8
      dummy = next(rng)
    end do
  end subroutine rng_seed

  !> Next 64-bit value (xorshift64* with the multiplier folded to 63 bits).
  integer(i8) function next(rng)
    type(rng_t), intent(inout) :: rng
    rng%state = ieor(rng%state, shiftr(rng%state, 12))
    rng%state = ieor(rng%state, shiftl(rng%state, 25))
    rng%state = ieor(rng%state, shiftr(rng%state, 27))
    next = shiftr(rng%state * 2685821657736338717_i8, 1)
  end function next

  !> Uniform integer in 0 .. n-1.
  integer function rng_below(rng, n)
    type(rng_t), intent(inout) :: rng
    integer, intent(in) :: n
    rng_below = int(modulo(next(rng), int(n, i8)))
  end function rng_below

  !> Fisher–Yates shuffle of an index list in place.
  subroutine rng_permute(rng, idx)
    type(rng_t), intent(inout) :: rng
    integer, intent(inout) :: idx(:)
    integer :: i, j, tmp
    do i = size(idx), 2, -1
      j = 1 + rng_below(rng, i)
      tmp = idx(i); idx(i) = idx(j); idx(j) = tmp
    end do
  end subroutine rng_permute
end module fracas_random
