!> Command-line helpers shared by the programs of src/.
module fracas_command_line
  use fracas_errors, only: fatal
  implicit none
  private
  public :: argument_value

contains

  !> Command argument k, the value of option `option`; a clear error if absent.
  function argument_value(k, option) result(str)
    integer, intent(in) :: k
    character(len=*), intent(in) :: option
    character(len=:), allocatable :: str
    integer :: n
    if (k > command_argument_count()) call fatal('option '//option//' needs a value')
    call get_command_argument(k, length=n)
    allocate (character(len=n) :: str)
    call get_command_argument(k, str)
  end function argument_value
end module fracas_command_line
