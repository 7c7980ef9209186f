!> Small assertions for the unit-test programs of test_cases/unit/. Each check
!> prints one line (PASS/FAIL, name, value, reference, tolerance); test_finish
!> ends the program with a non-zero exit if any check failed.
module fracas_testing
  use fracas_kinds, only: wp
  implicit none
  private
  public :: check_close, check_true, test_finish

  integer :: n_failed = 0, n_passed = 0

contains

  !> |got - ref| <= tol (absolute tolerance).
  subroutine check_close(name, got, ref, tol)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: got, ref, tol
    logical :: ok
    ok = abs(got - ref) <= tol
    if (got /= got) ok = .false.
    call record(ok)
    write (*, '(a,1x,a,3(a,es22.14))') merge('PASS', 'FAIL', ok), name, ' got=', got, ' ref=', ref, ' tol=', tol
  end subroutine check_close

  subroutine check_true(name, cond)
    character(len=*), intent(in) :: name
    logical, intent(in) :: cond
    call record(cond)
    write (*, '(a,1x,a)') merge('PASS', 'FAIL', cond), name
  end subroutine check_true

  subroutine record(ok)
    logical, intent(in) :: ok
    if (ok) then
      n_passed = n_passed + 1
    else
      n_failed = n_failed + 1
    end if
  end subroutine record

  !> Print the tally and exit with status 1 if anything failed.
  subroutine test_finish()
    write (*, '(i0,a,i0,a)') n_passed, ' passed, ', n_failed, ' failed'
    if (n_failed > 0) error stop 1
  end subroutine test_finish
end module fracas_testing
