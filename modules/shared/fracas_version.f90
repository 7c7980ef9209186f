!> The release string of Fracas, written into every results file.
module fracas_version
  implicit none
  private
  public :: version_string
  character(len=*), parameter :: version_string = '0.1.0'
end module fracas_version
