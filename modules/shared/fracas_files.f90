!> Small file-system operations through the C library (no shell commands):
!> atomic rename (the last step of every "write PATH.part, then rename" output),
!> existence tests, directory creation and listing, file removal.
module fracas_files
  use, intrinsic :: iso_c_binding, only: c_int, c_long, c_char, c_null_char, c_ptr, c_associated
  use fracas_errors, only: fatal
  implicit none
  private
  public :: atomic_rename, file_exists, dir_exists, make_dir, remove_file, list_dir, name_t

  !> One name of a directory listing.
  type :: name_t
    character(len=:), allocatable :: s
  end type name_t

  interface
    integer(c_int) function c_rename(from, to) bind(C, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: from(*), to(*)
    end function c_rename

    !> mode_t is an unsigned int on the POSIX systems we target (Linux, BSD, macOS).
    integer(c_int) function c_mkdir(path, mode) bind(C, name='mkdir')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode
    end function c_mkdir

    integer(c_int) function c_remove(path) bind(C, name='remove')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_remove

    type(c_ptr) function c_opendir(path) bind(C, name='opendir')
      import :: c_ptr, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_opendir

    integer(c_int) function c_closedir(dir) bind(C, name='closedir')
      import :: c_int, c_ptr
      type(c_ptr), value :: dir
    end function c_closedir

    !> modules/shared/fracas_dirlist.c
    integer(c_long) function c_list_dir(path, buf, buflen) bind(C, name='fracas_list_dir')
      import :: c_long, c_char
      character(kind=c_char), intent(in) :: path(*)
      character(kind=c_char), intent(inout) :: buf(*)
      integer(c_long), value :: buflen
    end function c_list_dir
  end interface

contains

  !> Rename FROM to TO in one step (C rename: atomic within a file system; TO is
  !> replaced if it exists). On failure: fatal, or stat /= 0 when stat is present.
  subroutine atomic_rename(from, to, stat)
    character(len=*), intent(in) :: from, to
    integer, intent(out), optional :: stat
    integer(c_int) :: rc
    rc = c_rename(cstr(from), cstr(to))
    if (present(stat)) then
      stat = int(rc)
    else if (rc /= 0) then
      call fatal('cannot rename '//trim(from)//' to '//trim(to))
    end if
  end subroutine atomic_rename

  !> True if PATH names an existing file or directory.
  logical function file_exists(path)
    character(len=*), intent(in) :: path
    inquire (file=trim(path), exist=file_exists)
  end function file_exists

  !> True if PATH names an existing directory (or a link to one).
  logical function dir_exists(path)
    character(len=*), intent(in) :: path
    type(c_ptr) :: dir
    integer(c_int) :: rc
    dir = c_opendir(cstr(path))
    dir_exists = c_associated(dir)
    if (dir_exists) rc = c_closedir(dir)
  end function dir_exists

  !> Create directory PATH (mode 0777 minus umask); an existing directory is fine.
  !> parents=.true. creates missing parent directories too (as mkdir -p).
  !> On failure: fatal, or stat /= 0 when stat is present.
  subroutine make_dir(path, parents, stat)
    character(len=*), intent(in) :: path
    logical, intent(in), optional :: parents
    integer, intent(out), optional :: stat
    logical :: p
    integer :: i, ierr
    character(len=:), allocatable :: pth
    p = .false.
    if (present(parents)) p = parents
    pth = trim(path)
    ierr = 0
    if (p) then
      do i = 2, len(pth) - 1
        if (pth(i:i) == '/' .and. pth(i - 1:i - 1) /= '/') then
          call make_one(pth(1:i - 1), ierr)
          if (ierr /= 0) exit
        end if
      end do
    end if
    if (ierr == 0) call make_one(pth, ierr)
    if (present(stat)) then
      stat = ierr
    else if (ierr /= 0) then
      call fatal('cannot create directory '//pth)
    end if
  end subroutine make_dir

  subroutine make_one(path, ierr)
    character(len=*), intent(in) :: path
    integer, intent(out) :: ierr
    integer(c_int) :: rc
    ierr = 0
    if (len(path) == 0) return
    if (dir_exists(path)) return
    rc = c_mkdir(cstr(path), int(o'777', c_int))
    ! A concurrent creator may have won the race: accept an existing directory.
    if (rc /= 0 .and. .not. dir_exists(path)) ierr = 1
  end subroutine make_one

  !> Remove file PATH; a missing file is fine. On failure: fatal, or stat /= 0.
  subroutine remove_file(path, stat)
    character(len=*), intent(in) :: path
    integer, intent(out), optional :: stat
    integer(c_int) :: rc
    integer :: ierr
    ierr = 0
    if (file_exists(path)) then
      rc = c_remove(cstr(path))
      if (rc /= 0) ierr = 1
    end if
    if (present(stat)) then
      stat = ierr
    else if (ierr /= 0) then
      call fatal('cannot remove '//trim(path))
    end if
  end subroutine remove_file

  !> The entries of directory PATH (files and directories, without '.' and
  !> '..'), in no particular order; none if PATH is not a readable directory.
  subroutine list_dir(path, names)
    character(len=*), intent(in) :: path
    type(name_t), allocatable, intent(out) :: names(:)
    character(kind=c_char), allocatable :: buf(:)
    integer(c_long) :: need
    integer :: i, j, n
    allocate (buf(4096))
    need = c_list_dir(cstr(path), buf, size(buf, kind=c_long))
    if (need > size(buf, kind=c_long)) then
      ! Entries may appear between the two calls: ask for some room to spare.
      deallocate (buf)
      allocate (buf(need + 4096))
      need = min(c_list_dir(cstr(path), buf, size(buf, kind=c_long)), size(buf, kind=c_long))
    end if
    n = 0
    do i = 1, int(need)
      if (buf(i) == c_null_char) n = n + 1
    end do
    allocate (names(n))
    n = 0
    j = 1
    do i = 1, int(need)
      if (buf(i) /= c_null_char) cycle
      n = n + 1
      allocate (character(len=i - j) :: names(n)%s)
      names(n)%s = transfer(buf(j:i - 1), names(n)%s)
      j = i + 1
    end do
  end subroutine list_dir

  !> Trimmed, NUL-terminated copy of a Fortran string for the C library.
  pure function cstr(s) result(c)
    character(len=*), intent(in) :: s
    character(kind=c_char, len=len_trim(s) + 1) :: c
    c = trim(s)//c_null_char
  end function cstr
end module fracas_files
