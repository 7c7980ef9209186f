!> Small file-system operations through the C library (no shell commands):
!> atomic rename (the last step of every "write PATH.part, then rename" output),
!> existence tests, directory creation and listing, file removal; closing a
!> written file with a check that all of it reached the disk.
module fracas_files
  use, intrinsic :: iso_c_binding, only: c_int, c_long, c_long_long, c_char, c_null_char, c_ptr, c_associated
  use, intrinsic :: iso_fortran_env, only: int64
  use fracas_errors, only: fatal, error_exit_running
  use fracas_strings, only: itoa
  implicit none
  private
  public :: atomic_rename, file_exists, dir_exists, make_dir, remove_file, list_dir, name_t, &
            close_written, check_written, disk_size, lock_file
  public :: executable_dir

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
    integer(c_int) function c_lock_file(path) bind(C, name='fracas_lock_file')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_lock_file

    integer(c_long_long) function c_file_size(path) bind(C, name='fracas_file_size')
      import :: c_long_long, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_file_size

    integer(c_long) function c_list_dir(path, buf, buflen) bind(C, name='fracas_list_dir')
      import :: c_long, c_char
      character(kind=c_char), intent(in) :: path(*)
      character(kind=c_char), intent(inout) :: buf(*)
      integer(c_long), value :: buflen
    end function c_list_dir
  end interface

contains

  !> Directory of the running executable, with a trailing '/' ('' if unknown):
  !> where a test program writes what it reads back.
  function executable_dir() result(d)
    character(len=:), allocatable :: d
    character(len=4096) :: arg0
    integer :: i
    call get_command_argument(0, arg0)
    i = index(arg0, '/', back=.true.)
    d = arg0(1:i)
  end function executable_dir

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

  !> Hold an exclusive lock on file PATH (created if missing) until the process
  !> ends, however it ends. stat: 0 taken, 1 PATH cannot be opened, 2 another
  !> process holds it.
  subroutine lock_file(path, stat)
    character(len=*), intent(in) :: path
    integer, intent(out) :: stat
    select case (c_lock_file(cstr(path)))
    case (0); stat = 0
    case (-2); stat = 2
    case default; stat = 1
    end select
  end subroutine lock_file

  !> Bytes of file PATH on disk (-1 if it is not there).
  integer(int64) function disk_size(path)
    character(len=*), intent(in) :: path
    disk_size = int(c_file_size(cstr(path)), int64)
  end function disk_size

  !> Close unit U, written to PATH, and make sure all of it reached the disk.
  !> gfortran (12) reports neither a failed flush nor a failed close: on a full
  !> disk the write(2) fails with ENOSPC, iostat stays 0 and the file is left
  !> short or empty. So the size of the unit is compared with the size on disk;
  !> when they differ PATH is removed and the run stops naming it. During the
  !> fatal-error clean-up the unit is only closed (no second error).
  subroutine close_written(u, path)
    integer, intent(in) :: u
    character(len=*), intent(in) :: path
    integer(int64) :: want, got
    integer :: ios, ios_close
    character(len=256) :: msg
    want = -1
    inquire (unit=u, size=want, iostat=ios)
    msg = ''
    close (u, iostat=ios_close, iomsg=msg)
    if (error_exit_running()) return
    got = disk_size(path)
    if (ios_close /= 0 .or. ios /= 0 .or. got /= want) then
      call remove_file(path, ios)
      call fatal(write_failure(path, got, want, msg))
    end if
  end subroutine close_written

  !> Hand the lines of open unit U (file PATH) to the system and make sure they
  !> reached the disk (see close_written); the unit stays open.
  subroutine check_written(u, path)
    integer, intent(in) :: u
    character(len=*), intent(in) :: path
    integer(int64) :: want, got
    integer :: ios
    character(len=256) :: msg
    msg = ''
    flush (u, iostat=ios, iomsg=msg)
    if (error_exit_running()) return
    want = -1
    if (ios == 0) inquire (unit=u, size=want, iostat=ios)
    got = disk_size(path)
    if (ios /= 0 .or. got /= want) call fatal(write_failure(path, got, want, msg))
  end subroutine check_written

  function write_failure(path, got, want, msg) result(s)
    character(len=*), intent(in) :: path, msg
    integer(int64), intent(in) :: got, want
    character(len=:), allocatable :: s
    if (got < 0) then
      s = 'cannot write '//trim(path)//': the file is gone (output folder removed?)'
    else
      s = 'cannot write '//trim(path)//': '//itoa(got)//' of its '//itoa(want)// &
          ' bytes reached the disk (disk full?)'
    end if
    if (len_trim(msg) > 0) s = s//': '//trim(msg)
    s = s//'. The run stops'
  end function write_failure

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
