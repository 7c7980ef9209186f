!> The one way Fracas reports a failure: a message on standard error, then a
!> non-zero exit. Input errors name file:line:column and what was expected.
!> Before the exit, registered clean-up (e.g. marking partial output) runs.
module fracas_errors
  use, intrinsic :: iso_fortran_env, only: error_unit
  use fracas_strings, only: itoa
  implicit none
  private
  public :: fatal, input_error, warn, set_cleanup, cleanup_proc, stop_run, itoa, error_exit_running, &
            set_error_context, last_error
  public :: status_t, raise, failed
  public :: exit_error, exit_unconverged

  !> Exit statuses of the programs (documented in fracas --help and doc/):
  !> 0 success; exit_error: an error was reported (bad input, a failure during
  !> the run); exit_unconverged: the run ended, or stopped, because NLGS steps
  !> did not converge and the run control makes that fatal. (2 is left to the
  !> Fortran run-time library, which uses it for its own errors.)
  integer, parameter :: exit_error = 1, exit_unconverged = 3

  !> The outcome of a library routine that can fail at run time (a factorization,
  !> a solve): the caller decides what a failure means (stop the run with a
  !> message naming the body, try something else, hand it to Python or to
  !> another rank). Routines taking an optional status stop the run as before
  !> when the caller passes none (raise).
  type :: status_t
    logical :: ok = .true.
    character(len=:), allocatable :: message   !< what failed (set when not ok)
  end type status_t

  abstract interface
    subroutine cleanup_proc()
    end subroutine cleanup_proc
  end interface

  procedure(cleanup_proc), pointer :: cleanup => null()
  logical :: in_cleanup = .false.
  !> What the program is doing, prefixed to the messages of fatal and stop_run:
  !> the step ('step N (t=...)', set by the driver around each step; '' when
  !> none). The object that failed is named by the message (see status_t).
  character(len=:), allocatable :: step_context
  !> The message of the error being reported (fracas.h5's end_reason).
  character(len=:), allocatable :: last_message

contains

  !> Register a procedure run once before a fatal exit (at most one).
  subroutine set_cleanup(proc)
    procedure(cleanup_proc) :: proc
    cleanup => proc
  end subroutine set_cleanup

  !> Stop the run with a message (exit status 1).
  subroutine fatal(message)
    character(len=*), intent(in) :: message
    call stop_run(message, exit_error)
  end subroutine fatal

  !> A failure of a routine that takes an optional status: recorded in status
  !> when the caller passed one, else the run stops with the message (fatal).
  subroutine raise(status, message)
    type(status_t), intent(inout), optional :: status
    character(len=*), intent(in) :: message
    if (.not. present(status)) call fatal(message)
    status%ok = .false.
    status%message = message
  end subroutine raise

  !> Has a routine reported a failure in status? (Without a status a failure
  !> has stopped the run, so an absent status never holds one.)
  pure logical function failed(status)
    type(status_t), intent(in), optional :: status
    failed = .false.
    if (present(status)) failed = .not. status%ok
  end function failed

  !> Set the step context of error messages ('' clears it).
  subroutine set_error_context(step)
    character(len=*), intent(in) :: step
    step_context = step
  end subroutine set_error_context

  !> The message of the error being reported ('' before any).
  function last_error() result(s)
    character(len=:), allocatable :: s
    s = ''
    if (allocated(last_message)) s = last_message
  end function last_error

  !> MESSAGE with its context: 'step N (t=...): message' (the step left out when
  !> the message names it already).
  function in_context(message) result(s)
    character(len=*), intent(in) :: message
    character(len=:), allocatable :: s
    s = trim(message)
    if (allocated(step_context)) then
      if (len(step_context) > 0 .and. index(s, 'step ') /= 1) s = step_context//': '//s
    end if
  end function in_context

  !> Stop the run on bad input: "FILE:LINE:COL: message" (exit status 1).
  !> line or col <= 0 are left out (a whole-file or whole-line problem).
  subroutine input_error(file, line, col, message)
    character(len=*), intent(in) :: file, message
    integer, intent(in) :: line, col
    character(len=:), allocatable :: where
    where = trim(file)
    if (line > 0) where = where//':'//itoa(line)
    if (line > 0 .and. col > 0) where = where//':'//itoa(col)
    write (error_unit, '(a)') where//': '//trim(message)
    last_message = where//': '//trim(message)
    call run_cleanup()
    error stop 1, quiet=.true.
  end subroutine input_error

  !> End the program with exit status STATUS after MESSAGE (on standard
  !> error, as an error) and the registered clean-up.
  subroutine stop_run(message, status)
    character(len=*), intent(in) :: message
    integer, intent(in) :: status
    last_message = in_context(message)
    write (error_unit, '(a)') 'fracas: error: '//last_message
    call run_cleanup()
    error stop status, quiet=.true.
  end subroutine stop_run

  !> A warning on standard error; the run goes on.
  subroutine warn(message)
    character(len=*), intent(in) :: message
    write (error_unit, '(a)') 'fracas: warning: '//trim(message)
  end subroutine warn

  !> True while the clean-up before an error exit runs: what it calls must not
  !> report a second error (it would stop the clean-up half way), only warn.
  logical function error_exit_running()
    error_exit_running = in_cleanup
  end function error_exit_running

  subroutine run_cleanup()
    if (associated(cleanup) .and. .not. in_cleanup) then
      in_cleanup = .true.
      call cleanup()
    end if
  end subroutine run_cleanup

end module fracas_errors
