!> A thin layer over the HDF5 Fortran API for Fracas outputs: files, groups,
!> attributes, whole-array datasets (one HDF5 write per array) and appendable
!> 1-D series. Every HDF5 failure is fatal through fracas_errors, naming the object.
!>
!> Shapes: a Fortran array a(ncomp, n) is stored as an HDF5 dataset that h5py
!> sees with shape (n, ncomp) (row k = column k of a). A 1-D array of n values
!> is a dataset of shape (n,). Reals are stored as 64-bit IEEE floats, integers
!> as 32-bit signed integers, strings as variable-length strings.
!>
!> Ids: files, groups and series datasets are HDF5 ids (integer(hid_t), re-exported
!> here) that the caller closes with h5_close_file / h5_close_group /
!> h5_close_series. All other ids are opened and closed inside each call.
!> h5_close_file warns if objects of the file are still open (an id leak).
!> Groups and files are created with link and attribute creation order tracked,
!> so h5py lists members in the order they were written.
!> Set FRACAS_HDF5_DEBUG=1 in the environment to see HDF5's own error stacks.
module fracas_h5
  use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_null_ptr, c_char, c_null_char, &
                                         c_size_t, c_f_pointer, c_associated
  use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5close_f, h5kind_to_type, &
                  H5_REAL_KIND, H5_INTEGER_KIND, H5T_STRING, H5T_FORTRAN_S1, H5T_STRING_F, &
                  H5T_INTEGER_F, H5T_FLOAT_F, &
                  h5fcreate_f, h5fopen_f, h5fclose_f, h5fflush_f, h5fget_obj_count_f, &
                  H5F_ACC_TRUNC_F, H5F_ACC_EXCL_F, H5F_ACC_RDONLY_F, H5F_ACC_RDWR_F, &
                  H5F_SCOPE_GLOBAL_F, H5F_OBJ_ALL_F, &
                  h5gcreate_f, h5gopen_f, h5gclose_f, &
                  h5dcreate_f, h5dopen_f, h5dclose_f, h5dwrite_f, h5dread_f, h5dget_space_f, &
                  h5dget_type_f, h5dset_extent_f, h5dvlen_reclaim_f, &
                  h5screate_f, h5screate_simple_f, h5sclose_f, h5sselect_hyperslab_f, &
                  h5sget_simple_extent_ndims_f, h5sget_simple_extent_dims_f, &
                  H5S_SCALAR_F, H5S_UNLIMITED_F, H5S_SELECT_SET_F, &
                  h5acreate_f, h5aopen_f, h5aclose_f, h5awrite_f, h5aread_f, h5aexists_f, &
                  h5adelete_f, h5aget_space_f, h5aget_type_f, &
                  h5tcopy_f, h5tclose_f, h5tset_size_f, h5tget_size_f, h5tget_class_f, &
                  h5tis_variable_str_f, &
                  h5pcreate_f, h5pclose_f, h5pset_chunk_f, h5pset_deflate_f, &
                  h5pset_link_creation_order_f, h5pset_attr_creation_order_f, &
                  h5pset_link_phase_change_f, &
                  H5P_DATASET_CREATE_F, H5P_GROUP_CREATE_F, H5P_FILE_CREATE_F, H5P_DEFAULT_F, &
                  H5P_CRT_ORDER_TRACKED_F, H5P_CRT_ORDER_INDEXED_F, &
                  h5lexists_f, h5ldelete_f, h5eset_auto_f, h5iget_name_f
  use fracas_kinds, only: wp, ik
  use fracas_strings, only: itoa
  use fracas_errors, only: fatal, warn, error_exit_running
  use fracas_files, only: file_exists
  implicit none
  private
  public :: hid_t, h5_series_t
  public :: h5_init, h5_finalize
  public :: h5_create_file, h5_open_file, h5_close_file, h5_flush, h5_open_objects, h5_file_renamed
  public :: h5_create_group, h5_open_group, h5_close_group, h5_exists
  public :: h5_write_attr, h5_read_attr, h5_has_attr
  public :: h5_write_dataset, h5_read_dataset, h5_dataset_dims
  public :: h5_create_series, h5_open_series, h5_append, h5_close_series
  public :: h5_dataset_hook, h5_set_dataset_hook

  !> An extendible, chunked 1-D dataset kept open for appends.
  type :: h5_series_t
    integer(hid_t) :: dset = -1
    integer(hsize_t) :: n = 0          !< current length
    logical :: is_int = .false.        !< integer (Int32) or real (Float64) values
    character(len=:), allocatable :: name
  end type h5_series_t

  !> h5_write_attr(loc, name, value): integer, real or string scalar, or integer/real
  !> 1-D array, on a file (root group), group or dataset id. Replaces an existing one.
  interface h5_write_attr
    module procedure wattr_int, wattr_real, wattr_str, wattr_int1, wattr_real1
  end interface h5_write_attr

  !> h5_read_attr(loc, name, value): integer, real or (deferred-length) string scalar.
  interface h5_read_attr
    module procedure rattr_int, rattr_real, rattr_str
  end interface h5_read_attr

  !> h5_write_dataset(loc, name, data [, compress]): real(wp)/integer 1-D or 2-D
  !> array, or 1-D array of strings. An existing dataset of that name is replaced.
  interface h5_write_dataset
    module procedure wds_real1, wds_real2, wds_int1, wds_int2, wds_str1
  end interface h5_write_dataset

  !> h5_read_dataset(loc, name, data): into an allocatable array of the same rank
  !> and type (strings: character(len=:), allocatable :: data(:)).
  interface h5_read_dataset
    module procedure rds_real1, rds_real2, rds_int1, rds_int2, rds_str1
  end interface h5_read_dataset

  !> h5_append(series, value): one value, or a 1-D array of values, at the end.
  interface h5_append
    module procedure app_real, app_int, app_real1, app_int1
  end interface h5_append

  interface
    integer(c_size_t) function c_strlen(s) bind(C, name='strlen')
      import :: c_size_t, c_ptr
      type(c_ptr), value :: s
    end function c_strlen
  end interface

  !> Called on every dataset this module creates, while it is open, with its path in
  !> the file without the leading '/' (fracas_h5_describe sets its units and description:
  !> attributes written at once sit in the dataset's header; added at the end of a run
  !> they take a second header block each, ~30 % of a file of small snapshots, and time).
  abstract interface
    subroutine h5_dataset_hook(dset, path)
      import :: hid_t
      integer(hid_t), intent(in) :: dset
      character(len=*), intent(in) :: path
    end subroutine h5_dataset_hook
  end interface
  procedure(h5_dataset_hook), pointer :: dataset_hook => null()

  logical :: initialised = .false.
  !> The file created or opened last (a run has one open at a time): errors name it.
  character(len=:), allocatable :: last_file
  integer(hid_t) :: t_real = -1, t_int = -1

contains

  ! ================================================================ library

  !> Open the HDF5 library once (called by every file open/create). HDF5's own
  !> error-stack printing is switched off (our messages name the object) unless
  !> the environment variable FRACAS_HDF5_DEBUG is set.
  subroutine h5_init()
    integer :: err, stat
    if (initialised) return
    call h5open_f(err)
    call check(err, 'cannot initialise the HDF5 library')
    call get_environment_variable('FRACAS_HDF5_DEBUG', status=stat)
    if (stat /= 0) call h5eset_auto_f(0, err)
    t_real = h5kind_to_type(wp, H5_REAL_KIND)
    t_int = h5kind_to_type(ik, H5_INTEGER_KIND)
    initialised = .true.
  end subroutine h5_init

  !> Close the HDF5 library (optional, at the end of a program).
  subroutine h5_finalize()
    integer :: err
    if (.not. initialised) return
    call h5close_f(err)
    initialised = .false.
  end subroutine h5_finalize

  !> An HDF5 failure stops the run, except in the clean-up of an error exit
  !> (closing fracas.h5 with complete = 0), which goes on to close what it can.
  subroutine check(err, what)
    integer, intent(in) :: err
    character(len=*), intent(in) :: what
    character(len=:), allocatable :: msg
    if (err >= 0) return
    msg = 'HDF5: '//what
    if (allocated(last_file)) msg = msg//' (in '//last_file//'; disk full?)'
    if (error_exit_running()) then
      call warn(msg)
    else
      call fatal(msg)
    end if
  end subroutine check

  ! ================================================================ files

  !> Create PATH. If it exists: replaced when overwrite, else fatal.
  subroutine h5_create_file(path, overwrite, fid)
    character(len=*), intent(in) :: path
    logical, intent(in) :: overwrite
    integer(hid_t), intent(out) :: fid
    integer :: err
    integer(hid_t) :: fcpl
    call h5_init()
    last_file = trim(path)
    if (.not. overwrite .and. file_exists(path)) &
      call fatal(trim(path)//' exists; refusing to overwrite it (pass --overwrite to replace it)')
    call h5pcreate_f(H5P_FILE_CREATE_F, fcpl, err)
    call check(err, 'file creation properties for '//trim(path))
    call track_order(fcpl, trim(path))
    if (overwrite) then
      call h5fcreate_f(trim(path), H5F_ACC_TRUNC_F, fid, err, creation_prp=fcpl)
    else
      call h5fcreate_f(trim(path), H5F_ACC_EXCL_F, fid, err, creation_prp=fcpl)
    end if
    if (err < 0) call fatal('HDF5: cannot create file '//trim(path)// &
                            ' (does its directory exist, is it writable?)')
    call h5pclose_f(fcpl, err)
  end subroutine h5_create_file

  !> The open file was renamed to PATH (for messages).
  subroutine h5_file_renamed(path)
    character(len=*), intent(in) :: path
    last_file = trim(path)
  end subroutine h5_file_renamed

  !> Open an existing file, read-only unless writable.
  subroutine h5_open_file(path, fid, writable)
    character(len=*), intent(in) :: path
    integer(hid_t), intent(out) :: fid
    logical, intent(in), optional :: writable
    integer :: err
    logical :: w
    call h5_init()
    last_file = trim(path)
    w = .false.
    if (present(writable)) w = writable
    if (.not. file_exists(path)) call fatal('HDF5 file '//trim(path)//' does not exist')
    if (w) then
      call h5fopen_f(trim(path), H5F_ACC_RDWR_F, fid, err)
    else
      call h5fopen_f(trim(path), H5F_ACC_RDONLY_F, fid, err)
    end if
    call check(err, 'cannot open file '//trim(path))
  end subroutine h5_open_file

  !> Number of objects (groups, datasets, attributes, types) of the file still open,
  !> the file itself not counted.
  integer function h5_open_objects(fid) result(n)
    integer(hid_t), intent(in) :: fid
    integer(size_t) :: cnt
    integer :: err
    call h5fget_obj_count_f(fid, H5F_OBJ_ALL_F, cnt, err)
    call check(err, 'cannot count open objects')
    n = int(cnt) - 1
  end function h5_open_objects

  !> Flush and close a file; warns if ids of it are still open.
  subroutine h5_close_file(fid)
    integer(hid_t), intent(inout) :: fid
    integer :: err, n
    if (fid < 0) return
    n = h5_open_objects(fid)
    if (n > 0) call warn('HDF5: closing a file with '//itoa(n)//' object(s) still open')
    call h5fflush_f(fid, H5F_SCOPE_GLOBAL_F, err)
    call h5fclose_f(fid, err)
    call check(err, 'cannot close file')
    fid = -1
  end subroutine h5_close_file

  !> Write buffered data and metadata to disk (the file stays open).
  subroutine h5_flush(fid)
    integer(hid_t), intent(in) :: fid
    integer :: err
    call h5fflush_f(fid, H5F_SCOPE_GLOBAL_F, err)
    call check(err, 'cannot flush file')
  end subroutine h5_flush

  ! ================================================================ groups

  !> Create group NAME (a path relative to loc; parents must exist).
  subroutine h5_create_group(loc, name, gid)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: gid
    integer :: err
    integer(hid_t) :: gcpl
    call h5pcreate_f(H5P_GROUP_CREATE_F, gcpl, err)
    call check(err, 'group creation properties for '//name)
    call track_order(gcpl, name)
    call h5gcreate_f(loc, name, gid, err, gcpl_id=gcpl)
    if (err < 0) call fatal('HDF5: cannot create group '//name)
    call h5pclose_f(gcpl, err)
  end subroutine h5_create_group

  subroutine h5_open_group(loc, name, gid)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: gid
    integer :: err
    call h5gopen_f(loc, name, gid, err)
    call check(err, 'cannot open group '//name)
  end subroutine h5_open_group

  subroutine h5_close_group(gid)
    integer(hid_t), intent(inout) :: gid
    integer :: err
    if (gid < 0) return
    call h5gclose_f(gid, err)
    call check(err, 'cannot close group')
    gid = -1
  end subroutine h5_close_group

  subroutine track_order(plist, what)
    integer(hid_t), intent(in) :: plist
    character(len=*), intent(in) :: what
    integer :: err
    call h5pset_link_creation_order_f(plist, ior(H5P_CRT_ORDER_TRACKED_F, H5P_CRT_ORDER_INDEXED_F), err)
    call check(err, 'link creation order for '//what)
    call h5pset_attr_creation_order_f(plist, ior(H5P_CRT_ORDER_TRACKED_F, H5P_CRT_ORDER_INDEXED_F), err)
    call check(err, 'attribute creation order for '//what)
    ! Links kept in the group's header up to 32 (HDF5's default: 8, then a heap and two
    ! B-trees of about 2 kB): a snapshot's groups hold 10 to 30 datasets.
    call h5pset_link_phase_change_f(plist, 32, 24, err)
    call check(err, 'link storage for '//what)
  end subroutine track_order

  !> True if the link PATH (e.g. 'snapshots/000001/bodies/X') exists under loc.
  logical function h5_exists(loc, path) result(ex)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: path
    integer :: err, i
    character(len=:), allocatable :: p
    p = trim(path)
    ex = .false.
    ! h5lexists fails on a missing intermediate group: test each prefix in turn.
    do i = 2, len(p)
      if (p(i:i) == '/') then
        call h5lexists_f(loc, p(1:i - 1), ex, err)
        if (err < 0 .or. .not. ex) then
          ex = .false.
          return
        end if
      end if
    end do
    if (len(p) == 0) return
    call h5lexists_f(loc, p, ex, err)
    if (err < 0) ex = .false.
  end function h5_exists

  subroutine replace_link(loc, name)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer :: err
    if (h5_exists(loc, name)) then
      call h5ldelete_f(loc, name, err)
      call check(err, 'cannot replace '//name)
    end if
  end subroutine replace_link

  ! ================================================================ attributes

  logical function h5_has_attr(loc, name) result(ex)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer :: err
    call h5aexists_f(loc, name, ex, err)
    call check(err, 'cannot test attribute '//name)
  end function h5_has_attr

  !> Create (or re-create) attribute NAME on loc and write it from ptr.
  subroutine put_attr(loc, name, ftype, mtype, rank, dims, ptr)
    integer(hid_t), intent(in) :: loc, ftype, mtype
    character(len=*), intent(in) :: name
    integer, intent(in) :: rank
    integer(hsize_t), intent(in) :: dims(:)
    type(c_ptr), intent(in) :: ptr
    integer(hid_t) :: space, attr
    integer :: err
    if (h5_has_attr(loc, name)) then
      call h5adelete_f(loc, name, err)
      call check(err, 'cannot replace attribute '//name)
    end if
    if (rank == 0) then
      call h5screate_f(H5S_SCALAR_F, space, err)
    else
      call h5screate_simple_f(rank, dims, space, err)
    end if
    call check(err, 'dataspace for attribute '//name)
    call h5acreate_f(loc, name, ftype, space, attr, err)
    call check(err, 'cannot create attribute '//name)
    if (product(dims) > 0) then
      call h5awrite_f(attr, mtype, ptr, err)
      call check(err, 'cannot write attribute '//name)
    end if
    call h5aclose_f(attr, err)
    call h5sclose_f(space, err)
  end subroutine put_attr

  subroutine wattr_int(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: value
    integer(ik), target :: buf(1)
    buf(1) = value
    call put_attr(loc, name, t_int, t_int, 0, [1_hsize_t], c_loc(buf))
  end subroutine wattr_int

  subroutine wattr_real(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: value
    real(wp), target :: buf(1)
    buf(1) = value
    call put_attr(loc, name, t_real, t_real, 0, [1_hsize_t], c_loc(buf))
  end subroutine wattr_real

  subroutine wattr_int1(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: value(:)
    integer(ik), allocatable, target :: buf(:)
    buf = value
    if (size(buf) == 0) then
      call put_attr(loc, name, t_int, t_int, 1, [0_hsize_t], c_null_ptr)
    else
      call put_attr(loc, name, t_int, t_int, 1, [size(buf, kind=hsize_t)], c_loc(buf))
    end if
  end subroutine wattr_int1

  subroutine wattr_real1(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: value(:)
    real(wp), allocatable, target :: buf(:)
    buf = value
    if (size(buf) == 0) then
      call put_attr(loc, name, t_real, t_real, 1, [0_hsize_t], c_null_ptr)
    else
      call put_attr(loc, name, t_real, t_real, 1, [size(buf, kind=hsize_t)], c_loc(buf))
    end if
  end subroutine wattr_real1

  !> A variable-length string attribute (h5py reads it as str); trailing blanks dropped.
  subroutine wattr_str(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name, value
    character(kind=c_char), allocatable, target :: flat(:)
    type(c_ptr), allocatable, target :: ptrs(:)
    call pack_strings([value], flat, ptrs)
    call put_attr(loc, name, H5T_STRING, H5T_STRING, 0, [1_hsize_t], c_loc(ptrs))
  end subroutine wattr_str

  !> NUL-terminated copies of strings in one buffer, and a pointer to each.
  subroutine pack_strings(s, flat, ptrs)
    character(len=*), intent(in) :: s(:)
    character(kind=c_char), allocatable, target, intent(out) :: flat(:)
    type(c_ptr), allocatable, intent(out) :: ptrs(:)
    integer :: i, j, k, l
    allocate (flat(sum(len_trim(s)) + size(s)), ptrs(size(s)))
    k = 0
    do i = 1, size(s)
      l = len_trim(s(i))
      ptrs(i) = c_loc(flat(k + 1))
      do j = 1, l
        flat(k + j) = s(i)(j:j)
      end do
      flat(k + l + 1) = c_null_char
      k = k + l + 1
    end do
  end subroutine pack_strings

  !> Open attribute NAME of loc; also returns its type and space (caller closes).
  subroutine open_attr(loc, name, attr, space, atype)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: attr, space, atype
    integer :: err
    if (.not. h5_has_attr(loc, name)) call fatal('HDF5: no attribute '//name)
    call h5aopen_f(loc, name, attr, err)
    call check(err, 'cannot open attribute '//name)
    call h5aget_space_f(attr, space, err)
    call check(err, 'cannot get the space of attribute '//name)
    call h5aget_type_f(attr, atype, err)
    call check(err, 'cannot get the type of attribute '//name)
  end subroutine open_attr

  subroutine close_attr(attr, space, atype)
    integer(hid_t), intent(in) :: attr, space, atype
    integer :: err
    call h5tclose_f(atype, err)
    call h5sclose_f(space, err)
    call h5aclose_f(attr, err)
  end subroutine close_attr

  subroutine rattr_int(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(ik), intent(out) :: value
    integer(ik), target :: buf(1)
    integer(hid_t) :: attr, space, atype
    integer :: err
    type(c_ptr) :: cp
    call open_attr(loc, name, attr, space, atype)
    call require_class(atype, H5T_INTEGER_F, 'attribute '//name, 'integer')
    cp = c_loc(buf)
    call h5aread_f(attr, t_int, cp, err)
    call check(err, 'cannot read attribute '//name)
    value = buf(1)
    call close_attr(attr, space, atype)
  end subroutine rattr_int

  subroutine rattr_real(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(wp), intent(out) :: value
    real(wp), target :: buf(1)
    integer(hid_t) :: attr, space, atype
    integer :: err, cls
    type(c_ptr) :: cp
    call open_attr(loc, name, attr, space, atype)
    call h5tget_class_f(atype, cls, err)
    if (cls /= H5T_FLOAT_F .and. cls /= H5T_INTEGER_F) &
      call fatal('HDF5: attribute '//name//' is not a number')
    cp = c_loc(buf)
    call h5aread_f(attr, t_real, cp, err)
    call check(err, 'cannot read attribute '//name)
    value = buf(1)
    call close_attr(attr, space, atype)
  end subroutine rattr_real

  !> A scalar string attribute, variable- or fixed-length.
  subroutine rattr_str(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    character(len=:), allocatable, intent(out) :: value
    type(c_ptr), target :: ptrs(1)
    character(kind=c_char), allocatable, target :: flat(:)
    integer(hid_t) :: attr, space, atype, mtype
    integer(size_t) :: sz
    integer :: err
    logical :: vlen
    type(c_ptr) :: cp
    call open_attr(loc, name, attr, space, atype)
    call require_class(atype, H5T_STRING_F, 'attribute '//name, 'string')
    call h5tis_variable_str_f(atype, vlen, err)
    if (vlen) then
      cp = c_loc(ptrs)
      call h5aread_f(attr, H5T_STRING, cp, err)
      call check(err, 'cannot read attribute '//name)
      value = from_cstr(ptrs(1))
      cp = c_loc(ptrs)
      call h5dvlen_reclaim_f(H5T_STRING, space, H5P_DEFAULT_F, cp, err)
    else
      call h5tget_size_f(atype, sz, err)
      allocate (flat(max(1_size_t, sz)))
      call h5tcopy_f(H5T_FORTRAN_S1, mtype, err)
      call h5tset_size_f(mtype, max(1_size_t, sz), err)
      cp = c_loc(flat)
      call h5aread_f(attr, mtype, cp, err)
      call check(err, 'cannot read attribute '//name)
      call h5tclose_f(mtype, err)
      value = from_chars(flat)
    end if
    call close_attr(attr, space, atype)
  end subroutine rattr_str

  subroutine require_class(htype, cls_wanted, what, expected)
    integer(hid_t), intent(in) :: htype
    integer, intent(in) :: cls_wanted
    character(len=*), intent(in) :: what, expected
    integer :: cls, err
    call h5tget_class_f(htype, cls, err)
    call check(err, 'cannot get the type class of '//what)
    if (cls /= cls_wanted) call fatal('HDF5: '//what//' is not of type '//expected)
  end subroutine require_class

  function from_cstr(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: n, i
    if (.not. c_associated(p)) then
      s = ''
      return
    end if
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate (character(len=n) :: s)
    do i = 1, n
      s(i:i) = chars(i)
    end do
  end function from_cstr

  !> Characters up to the first NUL, trailing blanks dropped.
  pure function from_chars(c) result(s)
    character(kind=c_char), intent(in) :: c(:)
    character(len=:), allocatable :: s
    integer :: n, i
    n = size(c)
    do i = 1, size(c)
      if (c(i) == c_null_char) then
        n = i - 1
        exit
      end if
    end do
    allocate (character(len=n) :: s)
    do i = 1, n
      s(i:i) = c(i)
    end do
    s = trim(s)
  end function from_chars

  ! ================================================================ datasets

  !> Set (or with no argument, clear) the hook called on every dataset created.
  subroutine h5_set_dataset_hook(hook)
    procedure(h5_dataset_hook), optional :: hook
    dataset_hook => null()
    if (present(hook)) dataset_hook => hook
  end subroutine h5_set_dataset_hook

  subroutine created(dset)
    integer(hid_t), intent(in) :: dset
    character(len=:), allocatable :: path
    character(len=1) :: probe
    integer(size_t) :: n
    integer :: err
    if (.not. associated(dataset_hook)) return
    call h5iget_name_f(dset, probe, 1_size_t, n, err)     ! the length first
    call check(err, 'name of a new dataset')
    allocate (character(len=n + 1) :: path)
    call h5iget_name_f(dset, path, len(path, kind=size_t), n, err)
    call check(err, 'name of a new dataset')
    if (path(1:1) == '/') then
      call dataset_hook(dset, path(2:n))
    else
      call dataset_hook(dset, path(1:n))
    end if
  end subroutine created

  !> Create dataset NAME of the given type and Fortran-order dims, and write it
  !> in one call from ptr. compress > 0: chunked, deflate level compress.
  subroutine put_dataset(loc, name, htype, rank, dims, ptr, compress)
    integer(hid_t), intent(in) :: loc, htype
    character(len=*), intent(in) :: name
    integer, intent(in) :: rank
    integer(hsize_t), intent(in) :: dims(:)
    type(c_ptr), intent(in) :: ptr
    integer, intent(in), optional :: compress
    integer(hid_t) :: space, dset, dcpl
    integer(hsize_t) :: chunk(rank)
    integer :: err
    call replace_link(loc, name)
    call h5screate_simple_f(rank, dims, space, err)
    call check(err, 'dataspace for '//name)
    dcpl = H5P_DEFAULT_F
    if (present(compress)) then
      if (compress > 0 .and. product(dims) > 0) then
        call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, err)
        chunk = dims
        ! about 64k values per chunk, whole rows (first dimension) kept together
        chunk(rank) = max(1_hsize_t, min(dims(rank), 65536_hsize_t/max(1_hsize_t, product(dims(1:rank - 1)))))
        call h5pset_chunk_f(dcpl, rank, chunk, err)
        call check(err, 'chunking of '//name)
        call h5pset_deflate_f(dcpl, min(compress, 9), err)
        call check(err, 'compression of '//name)
      end if
    end if
    call h5dcreate_f(loc, name, htype, space, dset, err, dcpl_id=dcpl)
    call check(err, 'cannot create dataset '//name)
    call created(dset)
    if (product(dims) > 0) then
      call h5dwrite_f(dset, htype, ptr, err)
      call check(err, 'cannot write dataset '//name)
    end if
    if (dcpl /= H5P_DEFAULT_F) call h5pclose_f(dcpl, err)
    call h5dclose_f(dset, err)
    call h5sclose_f(space, err)
  end subroutine put_dataset

  subroutine wds_real1(loc, name, data, compress)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(wp), intent(in), target :: data(:)
    real(wp), allocatable, target :: tmp(:)
    type(c_ptr) :: cp
    integer, intent(in), optional :: compress
    if (size(data) == 0) then
      call put_dataset(loc, name, t_real, 1, [0_hsize_t], c_null_ptr)
    else
      if (is_contiguous(data)) then
        cp = c_loc(data)
      else
        tmp = data
        cp = c_loc(tmp)
      end if
      call put_dataset(loc, name, t_real, 1, [size(data, kind=hsize_t)], cp, compress)
    end if
  end subroutine wds_real1

  subroutine wds_real2(loc, name, data, compress)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(wp), intent(in), target :: data(:, :)
    real(wp), allocatable, target :: tmp(:, :)
    type(c_ptr) :: cp
    integer, intent(in), optional :: compress
    integer(hsize_t) :: dims(2)
    dims = shape(data, kind=hsize_t)
    if (size(data) == 0) then
      call put_dataset(loc, name, t_real, 2, dims, c_null_ptr)
    else
      if (is_contiguous(data)) then
        cp = c_loc(data)
      else
        tmp = data
        cp = c_loc(tmp)
      end if
      call put_dataset(loc, name, t_real, 2, dims, cp, compress)
    end if
  end subroutine wds_real2

  subroutine wds_int1(loc, name, data, compress)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(ik), intent(in), target :: data(:)
    integer(ik), allocatable, target :: tmp(:)
    type(c_ptr) :: cp
    integer, intent(in), optional :: compress
    if (size(data) == 0) then
      call put_dataset(loc, name, t_int, 1, [0_hsize_t], c_null_ptr)
    else
      if (is_contiguous(data)) then
        cp = c_loc(data)
      else
        tmp = data
        cp = c_loc(tmp)
      end if
      call put_dataset(loc, name, t_int, 1, [size(data, kind=hsize_t)], cp, compress)
    end if
  end subroutine wds_int1

  subroutine wds_int2(loc, name, data, compress)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(ik), intent(in), target :: data(:, :)
    integer(ik), allocatable, target :: tmp(:, :)
    type(c_ptr) :: cp
    integer, intent(in), optional :: compress
    integer(hsize_t) :: dims(2)
    dims = shape(data, kind=hsize_t)
    if (size(data) == 0) then
      call put_dataset(loc, name, t_int, 2, dims, c_null_ptr)
    else
      if (is_contiguous(data)) then
        cp = c_loc(data)
      else
        tmp = data
        cp = c_loc(tmp)
      end if
      call put_dataset(loc, name, t_int, 2, dims, cp, compress)
    end if
  end subroutine wds_int2

  !> A 1-D dataset of variable-length strings (trailing blanks dropped).
  !> h5py reads the elements as bytes: use dset.asstr()[:] for str.
  subroutine wds_str1(loc, name, data, compress)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: data(:)
    integer, intent(in), optional :: compress
    character(kind=c_char), allocatable, target :: flat(:)
    type(c_ptr), allocatable, target :: ptrs(:)
    if (present(compress)) continue   ! strings are never compressed
    if (size(data) == 0) then
      call put_dataset(loc, name, H5T_STRING, 1, [0_hsize_t], c_null_ptr)
    else
      call pack_strings(data, flat, ptrs)
      call put_dataset(loc, name, H5T_STRING, 1, [size(data, kind=hsize_t)], c_loc(ptrs))
    end if
  end subroutine wds_str1

  !> Fortran-order dims of dataset NAME (h5py shows them reversed).
  subroutine h5_dataset_dims(loc, name, dims)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, allocatable, intent(out) :: dims(:)
    integer(hid_t) :: dset, space
    integer :: err
    call open_dataset(loc, name, dset, space)
    call space_dims(space, name, dims)
    call h5sclose_f(space, err)
    call h5dclose_f(dset, err)
  end subroutine h5_dataset_dims

  subroutine open_dataset(loc, name, dset, space)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: dset, space
    integer :: err
    if (.not. h5_exists(loc, name)) call fatal('HDF5: no dataset '//name)
    call h5dopen_f(loc, name, dset, err)
    call check(err, 'cannot open dataset '//name)
    call h5dget_space_f(dset, space, err)
    call check(err, 'cannot get the space of dataset '//name)
  end subroutine open_dataset

  subroutine space_dims(space, name, dims)
    integer(hid_t), intent(in) :: space
    character(len=*), intent(in) :: name
    integer, allocatable, intent(out) :: dims(:)
    integer(hsize_t), allocatable :: d(:), maxd(:)
    integer :: rank, err
    call h5sget_simple_extent_ndims_f(space, rank, err)
    call check(err, 'cannot get the rank of '//name)
    allocate (d(rank), maxd(rank))
    if (rank > 0) then
      call h5sget_simple_extent_dims_f(space, d, maxd, err)
      call check(err, 'cannot get the dims of '//name)
    end if
    dims = int(d)
  end subroutine space_dims

  !> Open dataset NAME, check its rank and type class; return dims.
  subroutine open_for_read(loc, name, rank, cls, dset, space, dims)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, intent(in) :: rank, cls
    integer(hid_t), intent(out) :: dset, space
    integer, allocatable, intent(out) :: dims(:)
    integer(hid_t) :: dtype
    integer :: err, c
    call open_dataset(loc, name, dset, space)
    call space_dims(space, name, dims)
    if (size(dims) /= rank) call fatal('HDF5: dataset '//name//' has rank '//itoa(size(dims))// &
                                       ', expected '//itoa(rank))
    call h5dget_type_f(dset, dtype, err)
    call h5tget_class_f(dtype, c, err)
    call h5tclose_f(dtype, err)
    if (c /= cls .and. .not. (cls == H5T_FLOAT_F .and. c == H5T_INTEGER_F)) &
      call fatal('HDF5: dataset '//name//' has an unexpected type')
  end subroutine open_for_read

  subroutine close_read(dset, space)
    integer(hid_t), intent(in) :: dset, space
    integer :: err
    call h5sclose_f(space, err)
    call h5dclose_f(dset, err)
  end subroutine close_read

  subroutine rds_real1(loc, name, data)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(wp), allocatable, target, intent(out) :: data(:)
    integer(hid_t) :: dset, space
    integer, allocatable :: dims(:)
    integer :: err
    type(c_ptr) :: cp
    call open_for_read(loc, name, 1, H5T_FLOAT_F, dset, space, dims)
    allocate (data(dims(1)))
    if (size(data) > 0) then
      cp = c_loc(data)
      call h5dread_f(dset, t_real, cp, err)
      call check(err, 'cannot read dataset '//name)
    end if
    call close_read(dset, space)
  end subroutine rds_real1

  subroutine rds_real2(loc, name, data)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(wp), allocatable, target, intent(out) :: data(:, :)
    integer(hid_t) :: dset, space
    integer, allocatable :: dims(:)
    integer :: err
    type(c_ptr) :: cp
    call open_for_read(loc, name, 2, H5T_FLOAT_F, dset, space, dims)
    allocate (data(dims(1), dims(2)))
    if (size(data) > 0) then
      cp = c_loc(data)
      call h5dread_f(dset, t_real, cp, err)
      call check(err, 'cannot read dataset '//name)
    end if
    call close_read(dset, space)
  end subroutine rds_real2

  subroutine rds_int1(loc, name, data)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(ik), allocatable, target, intent(out) :: data(:)
    integer(hid_t) :: dset, space
    integer, allocatable :: dims(:)
    integer :: err
    type(c_ptr) :: cp
    call open_for_read(loc, name, 1, H5T_INTEGER_F, dset, space, dims)
    allocate (data(dims(1)))
    if (size(data) > 0) then
      cp = c_loc(data)
      call h5dread_f(dset, t_int, cp, err)
      call check(err, 'cannot read dataset '//name)
    end if
    call close_read(dset, space)
  end subroutine rds_int1

  subroutine rds_int2(loc, name, data)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(ik), allocatable, target, intent(out) :: data(:, :)
    integer(hid_t) :: dset, space
    integer, allocatable :: dims(:)
    integer :: err
    type(c_ptr) :: cp
    call open_for_read(loc, name, 2, H5T_INTEGER_F, dset, space, dims)
    allocate (data(dims(1), dims(2)))
    if (size(data) > 0) then
      cp = c_loc(data)
      call h5dread_f(dset, t_int, cp, err)
      call check(err, 'cannot read dataset '//name)
    end if
    call close_read(dset, space)
  end subroutine rds_int2

  !> A 1-D string dataset (variable- or fixed-length) into data(n), its length
  !> that of the longest element.
  subroutine rds_str1(loc, name, data)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    character(len=:), allocatable, intent(out) :: data(:)
    integer(hid_t) :: dset, space, dtype, mtype
    integer, allocatable :: dims(:)
    type(c_ptr), allocatable, target :: ptrs(:)
    character(kind=c_char), allocatable, target :: flat(:)
    type :: str_t
      character(len=:), allocatable :: s
    end type str_t
    type(str_t), allocatable :: tmp(:)
    integer(size_t) :: sz
    integer :: err, i, n, l
    logical :: vlen
    type(c_ptr) :: cp
    call open_for_read(loc, name, 1, H5T_STRING_F, dset, space, dims)
    n = dims(1)
    allocate (tmp(n))
    call h5dget_type_f(dset, dtype, err)
    call h5tis_variable_str_f(dtype, vlen, err)
    if (n > 0) then
      if (vlen) then
        allocate (ptrs(n))
        cp = c_loc(ptrs)
        call h5dread_f(dset, H5T_STRING, cp, err)
        call check(err, 'cannot read dataset '//name)
        do i = 1, n
          tmp(i)%s = from_cstr(ptrs(i))
        end do
        cp = c_loc(ptrs)
        call h5dvlen_reclaim_f(H5T_STRING, space, H5P_DEFAULT_F, cp, err)
      else
        call h5tget_size_f(dtype, sz, err)
        l = max(1, int(sz))
        allocate (flat(l*n))
        call h5tcopy_f(H5T_FORTRAN_S1, mtype, err)
        call h5tset_size_f(mtype, int(l, size_t), err)
        cp = c_loc(flat)
        call h5dread_f(dset, mtype, cp, err)
        call check(err, 'cannot read dataset '//name)
        call h5tclose_f(mtype, err)
        do i = 1, n
          tmp(i)%s = from_chars(flat((i - 1)*l + 1:i*l))
        end do
      end if
    end if
    call h5tclose_f(dtype, err)
    call close_read(dset, space)
    l = 0
    do i = 1, n
      l = max(l, len(tmp(i)%s))
    end do
    allocate (character(len=l) :: data(n))
    do i = 1, n
      data(i) = tmp(i)%s
    end do
  end subroutine rds_str1

  ! ================================================================ series

  !> Create an empty extendible 1-D dataset NAME under loc (chunk: values per
  !> chunk, default 1024) and keep it open in s for h5_append.
  subroutine h5_create_series(loc, name, s, is_int, chunk)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    type(h5_series_t), intent(out) :: s
    logical, intent(in), optional :: is_int
    integer, intent(in), optional :: chunk
    integer(hid_t) :: space, dcpl, htype
    integer(hsize_t) :: ch(1)
    integer :: err
    s%is_int = .false.
    if (present(is_int)) s%is_int = is_int
    ch = 1024
    if (present(chunk)) ch = max(1, chunk)
    htype = merge(t_int, t_real, s%is_int)
    call replace_link(loc, name)
    call h5screate_simple_f(1, [0_hsize_t], space, err, maxdims=[H5S_UNLIMITED_F])
    call check(err, 'dataspace for series '//name)
    call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, err)
    call h5pset_chunk_f(dcpl, 1, ch, err)
    call check(err, 'chunking of series '//name)
    call h5dcreate_f(loc, name, htype, space, s%dset, err, dcpl_id=dcpl)
    call check(err, 'cannot create series '//name)
    call created(s%dset)
    call h5pclose_f(dcpl, err)
    call h5sclose_f(space, err)
    s%n = 0
    s%name = name
  end subroutine h5_create_series

  !> Open an existing 1-D series (e.g. to go on appending after a restart).
  subroutine h5_open_series(loc, name, s)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    type(h5_series_t), intent(out) :: s
    integer(hid_t) :: space, dtype
    integer, allocatable :: dims(:)
    integer :: err, cls
    call open_dataset(loc, name, s%dset, space)
    call space_dims(space, name, dims)
    call h5sclose_f(space, err)
    if (size(dims) /= 1) call fatal('HDF5: series '//name//' is not 1-D')
    s%n = dims(1)
    call h5dget_type_f(s%dset, dtype, err)
    call h5tget_class_f(dtype, cls, err)
    call h5tclose_f(dtype, err)
    s%is_int = cls == H5T_INTEGER_F
    s%name = name
  end subroutine h5_open_series

  subroutine h5_close_series(s)
    type(h5_series_t), intent(inout) :: s
    integer :: err
    if (s%dset < 0) return
    call h5dclose_f(s%dset, err)
    call check(err, 'cannot close series')
    s%dset = -1
  end subroutine h5_close_series

  !> Extend the series by m values and write them from ptr (memory type mtype).
  subroutine append_raw(s, m, mtype, ptr)
    type(h5_series_t), intent(inout) :: s
    integer, intent(in) :: m
    integer(hid_t), intent(in) :: mtype
    type(c_ptr), intent(in) :: ptr
    integer(hid_t) :: fspace, mspace
    integer(hsize_t) :: newn
    integer :: err
    if (s%dset < 0) call fatal('HDF5: append to a series that is not open')
    if (m <= 0) return
    newn = s%n + m
    call h5dset_extent_f(s%dset, [newn], err)
    call check(err, 'cannot extend series '//s%name)
    call h5dget_space_f(s%dset, fspace, err)
    call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, [s%n], [int(m, hsize_t)], err)
    call check(err, 'cannot select the end of series '//s%name)
    call h5screate_simple_f(1, [int(m, hsize_t)], mspace, err)
    call h5dwrite_f(s%dset, mtype, ptr, err, mem_space_id=mspace, file_space_id=fspace)
    call check(err, 'cannot append to series '//s%name)
    call h5sclose_f(mspace, err)
    call h5sclose_f(fspace, err)
    s%n = newn
  end subroutine append_raw

  subroutine app_real(s, value)
    type(h5_series_t), intent(inout) :: s
    real(wp), intent(in) :: value
    real(wp), target :: buf(1)
    integer(ik), target :: ibuf(1)
    if (s%is_int) then
      ibuf(1) = nint(value, ik)
      call append_raw(s, 1, t_int, c_loc(ibuf))
    else
      buf(1) = value
      call append_raw(s, 1, t_real, c_loc(buf))
    end if
  end subroutine app_real

  subroutine app_int(s, value)
    type(h5_series_t), intent(inout) :: s
    integer(ik), intent(in) :: value
    real(wp), target :: buf(1)
    integer(ik), target :: ibuf(1)
    if (s%is_int) then
      ibuf(1) = value
      call append_raw(s, 1, t_int, c_loc(ibuf))
    else
      buf(1) = real(value, wp)
      call append_raw(s, 1, t_real, c_loc(buf))
    end if
  end subroutine app_int

  subroutine app_real1(s, values)
    type(h5_series_t), intent(inout) :: s
    real(wp), intent(in) :: values(:)
    real(wp), allocatable, target :: buf(:)
    integer(ik), allocatable, target :: ibuf(:)
    if (size(values) == 0) return
    if (s%is_int) then
      ibuf = nint(values, ik)
      call append_raw(s, size(ibuf), t_int, c_loc(ibuf))
    else
      buf = values
      call append_raw(s, size(buf), t_real, c_loc(buf))
    end if
  end subroutine app_real1

  subroutine app_int1(s, values)
    type(h5_series_t), intent(inout) :: s
    integer(ik), intent(in) :: values(:)
    real(wp), allocatable, target :: buf(:)
    integer(ik), allocatable, target :: ibuf(:)
    if (size(values) == 0) return
    if (s%is_int) then
      ibuf = values
      call append_raw(s, size(ibuf), t_int, c_loc(ibuf))
    else
      buf = real(values, wp)
      call append_raw(s, size(buf), t_real, c_loc(buf))
    end if
  end subroutine app_int1

end module fracas_h5
