!> The one place for small string helpers used in messages and file names.
module fracas_strings
  use fracas_kinds, only: wp, i8
  implicit none
  private
  public :: itoa, rtoa, rtoa_list, lower, upper

  !> An integer (default or 64-bit) without blanks: 42 -> '42'.
  interface itoa
    module procedure itoa_default, itoa_i8
  end interface itoa

contains

  pure function itoa_default(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write (buf, '(i0)') i
    s = trim(buf)
  end function itoa_default

  pure function itoa_i8(i) result(s)
    integer(i8), intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write (buf, '(i0)') i
    s = trim(buf)
  end function itoa_i8

  !> Short text form of a real for messages (es12.5, blanks removed; a
  !> three-digit exponent keeps its E).
  function rtoa(x) result(s)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    if (abs(x) >= 1.0e100_wp .or. (x /= 0.0_wp .and. abs(x) < 1.0e-99_wp)) then
      write (buf, '(es13.5e3)') x
    else
      write (buf, '(es12.5)') x
    end if
    s = trim(adjustl(buf))
  end function rtoa

  !> '(a, b, c)' in short form (rtoa of each, comma separated).
  function rtoa_list(x) result(s)
    real(wp), intent(in) :: x(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    do i = 1, size(x)
      if (i > 1) s = s//', '
      s = s//rtoa(x(i))
    end do
  end function rtoa_list

  pure function lower(s) result(r)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: r
    integer :: k
    r = s
    do k = 1, len(s)
      if (r(k:k) >= 'A' .and. r(k:k) <= 'Z') r(k:k) = achar(iachar(r(k:k)) + 32)
    end do
  end function lower

  pure function upper(s) result(r)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: r
    integer :: k
    r = s
    do k = 1, len(s)
      if (r(k:k) >= 'a' .and. r(k:k) <= 'z') r(k:k) = achar(iachar(r(k:k)) - 32)
    end do
  end function upper
end module fracas_strings
