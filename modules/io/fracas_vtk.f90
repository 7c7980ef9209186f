!> VTK XML writers for ParaView: UnstructuredGrid files (.vtu) of any cell
!> types with point, cell and field data, and collection files (.pvd) listing
!> them with their times.
!>
!> A .vtu is built piece by piece in a vtu_t and written at vtu_end:
!>
!>   call vtu_begin(w, 'DISPLAY/disks_000001.vtu', npoints, ncells, time=t)
!>   call vtu_points(w, xy)                        ! (2 or 3, npoints)
!>   call vtu_vertex_cells(w)                      ! or vtu_cells / vtu_cells_fixed
!>   call vtu_point_data(w, 'radius', r)           ! real or integer, (n) or (ncomp, n)
!>   call vtu_cell_data(w, 'status', st)
!>   call vtu_end(w)                               ! PATH.part, then renamed to PATH
!>
!> Encodings: 'zlib' (default: appended raw binary, each array compressed with
!> zlib in blocks as VTK's vtkZLibDataCompressor, UInt64 headers; deflate with
!> the run-length strategy, two to three times faster than zlib's default on
!> simulation data for files about 15 % bigger), 'raw'
!> (appended raw binary, uncompressed) and 'ascii' (inline text, for reading
!> by eye). Reals are Float64 (Float32 with single=.true.), integers Int32
!> (connectivity and offsets Int64), cell types UInt8. Every array is
!> converted and compressed as it is added: the caller's arrays can be
!> temporaries, and nothing but the encoded bytes stays in memory.
!> A .pvd is rewritten whole (PATH.part + rename) at each pvd_add, so a
!> reader always sees a complete collection.
module fracas_vtk
  use, intrinsic :: iso_fortran_env, only: int8, int32, int64, real32
  use, intrinsic :: iso_c_binding, only: c_int, c_long, c_long_long, c_signed_char, c_ptr, c_loc
  use fracas_kinds, only: wp, ik
  use fracas_strings, only: itoa
  use fracas_errors, only: fatal
  use fracas_files, only: atomic_rename, close_written
  use fracas_datbox_text, only: itoa
  implicit none
  private
  public :: vtu_t, vtu_begin, vtu_points, vtu_cells, vtu_cells_fixed, vtu_vertex_cells, &
            vtu_point_data, vtu_cell_data, vtu_field_data, vtu_field_strings, vtu_end, vtu_abort
  public :: pvd_t, pvd_init, pvd_add, pvd_free
  public :: zlib_uncompress
  public :: vtk_vertex, vtk_poly_vertex, vtk_line, vtk_poly_line, vtk_triangle, vtk_polygon, vtk_quad, &
            vtk_quadratic_triangle, vtk_quadratic_quad

  !> VTK cell type codes.
  integer(ik), parameter :: vtk_vertex = 1, vtk_poly_vertex = 2, vtk_line = 3, vtk_poly_line = 4, &
                            vtk_triangle = 5, vtk_polygon = 7, vtk_quad = 9, &
                            vtk_quadratic_triangle = 22, vtk_quadratic_quad = 23

  integer, parameter :: enc_zlib = 1, enc_raw = 2, enc_ascii = 3
  integer(int64), parameter :: zblock = 32768   !< uncompressed bytes per zlib block (VTK's default)

  !> A .vtu being built (see the module comment).
  type :: vtu_t
    character(len=:), allocatable :: path
    integer :: np = 0, nc = 0
    integer :: encoding = enc_zlib
    integer :: level = 1                       !< zlib level (1: fast)
    logical :: single = .false.                !< reals as Float32
    logical :: open = .false.
    logical :: has_points = .false., has_cells = .false.
    !> XML of each section so far (DataArray elements).
    character(len=:), allocatable :: x_field, x_point, x_cell, x_points, x_cells
    integer(int8), allocatable :: blob(:)      !< appended data
    integer(int64) :: nblob = 0
  end type vtu_t

  !> vtu_point_data / vtu_cell_data (w, name, values): values real(wp) or
  !> integer(ik), 1-D (one component) or 2-D (ncomp, n).
  interface vtu_point_data
    module procedure point_r1, point_r2, point_i1, point_i2
  end interface vtu_point_data
  interface vtu_cell_data
    module procedure cell_r1, cell_r2, cell_i1, cell_i2
  end interface vtu_cell_data

  !> A .pvd collection: the whole file is rewritten (PATH.part + rename) at each add.
  type :: pvd_t
    character(len=:), allocatable :: path
    character(len=:), allocatable :: body   !< the <DataSet .../> lines so far
    integer :: n = 0                        !< number of data sets listed
  end type pvd_t

  character(len=*), parameter :: nl = achar(10)

  interface
    !> modules/io/fracas_zlib.c
    integer(c_long) function c_zlib_bound(block) bind(C, name='fracas_zlib_bound')
      import :: c_long
      integer(c_long), value :: block
    end function c_zlib_bound
    integer(c_long) function c_zlib_blocks(src, n, block, level, rle, dst, cap, sizes) &
      bind(C, name='fracas_zlib_blocks')
      import :: c_long, c_int, c_signed_char, c_long_long
      integer(c_signed_char), intent(in) :: src(*)
      integer(c_long), value :: n, block, cap
      integer(c_int), value :: level, rle
      integer(c_signed_char), intent(inout) :: dst(*)
      integer(c_long_long), intent(out) :: sizes(*)
    end function c_zlib_blocks
    integer(c_int) function c_uncompress(dest, dest_len, source, source_len) bind(C, name='uncompress')
      import :: c_int, c_long, c_ptr
      type(c_ptr), value :: dest, source
      integer(c_long), intent(inout) :: dest_len
      integer(c_long), value :: source_len
    end function c_uncompress
  end interface

contains

  ! ================================================================ .vtu

  !> Start a .vtu of npoints points and ncells cells at PATH.
  !>   encoding 'zlib' (default), 'raw' or 'ascii'; level: zlib level 1..9 (default 1);
  !>   single: reals as Float32; time: written as FieldData TimeValue (read by ParaView).
  subroutine vtu_begin(w, path, npoints, ncells, time, encoding, level, single)
    type(vtu_t), intent(out) :: w
    character(len=*), intent(in) :: path
    integer, intent(in) :: npoints, ncells
    real(wp), intent(in), optional :: time
    character(len=*), intent(in), optional :: encoding
    integer, intent(in), optional :: level
    logical, intent(in), optional :: single
    if (npoints < 0 .or. ncells < 0) call fatal('vtu_begin '//trim(path)//': negative size')
    w%path = trim(path)
    w%np = npoints
    w%nc = ncells
    if (present(encoding)) then
      select case (encoding)
      case ('zlib')
        w%encoding = enc_zlib
      case ('raw')
        w%encoding = enc_raw
      case ('ascii')
        w%encoding = enc_ascii
      case default
        call fatal("vtu_begin: unknown encoding '"//encoding//"' (zlib, raw or ascii)")
      end select
    end if
    if (present(level)) w%level = max(1, min(9, level))
    if (present(single)) w%single = single
    w%x_field = ''
    w%x_point = ''
    w%x_cell = ''
    w%x_points = ''
    w%x_cells = ''
    allocate (w%blob(0))
    w%nblob = 0
    w%open = .true.
    if (present(time)) call vtu_field_data(w, 'TimeValue', [time])
  end subroutine vtu_begin

  !> The point coordinates: (2, np) (z = 0) or (3, np).
  subroutine vtu_points(w, points)
    type(vtu_t), intent(inout) :: w
    real(wp), intent(in) :: points(:, :)
    real(wp), allocatable :: xyz(:, :)
    call require(w, 'vtu_points')
    if (size(points, 2) /= w%np .or. (size(points, 1) /= 2 .and. size(points, 1) /= 3)) &
      call fatal('vtu_points '//w%path//': expected (2 or 3, '//itoa(w%np)//') points, got ('// &
                 itoa(size(points, 1))//', '//itoa(size(points, 2))//')')
    allocate (xyz(3, w%np))
    xyz(1:size(points, 1), :) = points
    if (size(points, 1) == 2) xyz(3, :) = 0.0_wp
    call add_real(w, w%x_points, 'Points', 3, reshape(xyz, [3*w%np]), always_ncomp=.true.)
    w%has_points = .true.
  end subroutine vtu_points

  !> Cells of any types: connectivity (0-based point indices of all cells one
  !> after another), offsets(nc) (end of cell k in connectivity) and types(nc)
  !> (VTK codes: vtk_triangle, vtk_quad, vtk_polygon, ...).
  subroutine vtu_cells(w, connectivity, offsets, types)
    type(vtu_t), intent(inout) :: w
    integer(ik), intent(in) :: connectivity(:), offsets(:), types(:)
    character(len=:), allocatable :: where
    integer :: k
    call require(w, 'vtu_cells')
    where = 'vtu_cells '//w%path//': '
    if (size(offsets) /= w%nc .or. size(types) /= w%nc) &
      call fatal(where//itoa(size(offsets))//' offsets and '//itoa(size(types))//' types for '// &
                 itoa(w%nc)//' cells')
    if (w%nc > 0) then
      if (offsets(w%nc) /= size(connectivity)) call fatal(where//'last offset '//itoa(offsets(w%nc))// &
                                                          ' /= connectivity size '//itoa(size(connectivity)))
      if (offsets(1) < 0) call fatal(where//'negative first offset')
      do k = 2, w%nc
        if (offsets(k) < offsets(k - 1)) call fatal(where//'offsets decrease at cell '//itoa(k))
      end do
    else if (size(connectivity) /= 0) then
      call fatal(where//'connectivity given without cells')
    end if
    if (size(connectivity) > 0) then
      if (minval(connectivity) < 0 .or. maxval(connectivity) >= w%np) &
        call fatal(where//'connectivity out of range 0..'//itoa(w%np - 1)//' (indices are 0-based)')
    end if
    call add_int64(w, w%x_cells, 'connectivity', int(connectivity, int64))
    call add_int64(w, w%x_cells, 'offsets', int(offsets, int64))
    call add_uint8(w, w%x_cells, 'types', types)
    w%has_cells = .true.
  end subroutine vtu_cells

  !> Cells all of one type and size: nodes(m, nc) 0-based (e.g. m = 3 for
  !> vtk_triangle, 4 for vtk_quad).
  subroutine vtu_cells_fixed(w, nodes, cell_type)
    type(vtu_t), intent(inout) :: w
    integer(ik), intent(in) :: nodes(:, :)
    integer(ik), intent(in) :: cell_type
    integer :: k, m
    m = size(nodes, 1)
    if (size(nodes, 2) /= w%nc) call fatal('vtu_cells_fixed '//w%path//': '//itoa(size(nodes, 2))// &
                                           ' cells given for '//itoa(w%nc))
    call vtu_cells(w, reshape(nodes, [size(nodes)]), [(int(m*k, ik), k=1, w%nc)], [(cell_type, k=1, w%nc)])
  end subroutine vtu_cells_fixed

  !> One vtk_vertex cell per point (point clouds: glyphs in ParaView).
  subroutine vtu_vertex_cells(w)
    type(vtu_t), intent(inout) :: w
    integer :: k
    if (w%nc /= w%np) call fatal('vtu_vertex_cells '//w%path//': needs as many cells as points')
    call vtu_cells(w, [(int(k - 1, ik), k=1, w%np)], [(int(k, ik), k=1, w%np)], [(vtk_vertex, k=1, w%np)])
  end subroutine vtu_vertex_cells

  !> A FieldData array (one tuple per value), e.g. TimeValue.
  subroutine vtu_field_data(w, name, values)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: values(:)
    logical :: single
    call require(w, 'vtu_field_data')
    single = w%single
    w%single = .false.      ! field data (the time) keeps every digit
    call add_real(w, w%x_field, name, 1, values, ntuples=size(values))
    w%single = single
  end subroutine vtu_field_data

  !> A FieldData array of strings (one tuple per string, trailing blanks
  !> dropped), e.g. the names behind an integer cell field. Written inline as
  !> VTK writes String arrays in ASCII: each string as its character codes
  !> followed by 0.
  subroutine vtu_field_strings(w, name, strings)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: strings(:)
    character(len=:), allocatable :: codes
    integer :: i, j
    call require(w, 'vtu_field_strings')
    codes = ''
    do i = 1, size(strings)
      do j = 1, len_trim(strings(i))
        codes = codes//' '//itoa(iachar(strings(i)(j:j)))
      end do
      codes = codes//' 0'
    end do
    w%x_field = w%x_field//'<DataArray type="String" Name="'//xml_escape(name)//'" NumberOfTuples="'// &
                itoa(size(strings))//'" format="ascii">'//nl//codes//nl//'</DataArray>'//nl
  end subroutine vtu_field_strings

  subroutine point_r1(w, name, values)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: values(:)
    call check_tuples(w, 'point', name, size(values), 1, w%np)
    call add_real(w, w%x_point, name, 1, values)
  end subroutine point_r1

  subroutine point_r2(w, name, values)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: values(:, :)
    call check_tuples(w, 'point', name, size(values), size(values, 1), w%np)
    call add_real(w, w%x_point, name, size(values, 1), reshape(values, [size(values)]))
  end subroutine point_r2

  subroutine point_i1(w, name, values)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: values(:)
    call check_tuples(w, 'point', name, size(values), 1, w%np)
    call add_int32(w, w%x_point, name, 1, values)
  end subroutine point_i1

  subroutine point_i2(w, name, values)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: values(:, :)
    call check_tuples(w, 'point', name, size(values), size(values, 1), w%np)
    call add_int32(w, w%x_point, name, size(values, 1), reshape(values, [size(values)]))
  end subroutine point_i2

  subroutine cell_r1(w, name, values)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: values(:)
    call check_tuples(w, 'cell', name, size(values), 1, w%nc)
    call add_real(w, w%x_cell, name, 1, values)
  end subroutine cell_r1

  subroutine cell_r2(w, name, values)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: values(:, :)
    call check_tuples(w, 'cell', name, size(values), size(values, 1), w%nc)
    call add_real(w, w%x_cell, name, size(values, 1), reshape(values, [size(values)]))
  end subroutine cell_r2

  subroutine cell_i1(w, name, values)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: values(:)
    call check_tuples(w, 'cell', name, size(values), 1, w%nc)
    call add_int32(w, w%x_cell, name, 1, values)
  end subroutine cell_i1

  subroutine cell_i2(w, name, values)
    type(vtu_t), intent(inout) :: w
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: values(:, :)
    call check_tuples(w, 'cell', name, size(values), size(values, 1), w%nc)
    call add_int32(w, w%x_cell, name, size(values, 1), reshape(values, [size(values)]))
  end subroutine cell_i2

  !> Write the file (PATH.part, renamed to PATH) and free the buffers.
  !> Points and cells must have been given.
  subroutine vtu_end(w)
    type(vtu_t), intent(inout) :: w
    integer :: u, ios
    character(len=:), allocatable :: part, head
    call require(w, 'vtu_end')
    if (.not. w%has_points) call fatal('vtu_end '//w%path//': no points given (vtu_points)')
    if (.not. w%has_cells) call fatal('vtu_end '//w%path//': no cells given (vtu_cells)')
    head = '<?xml version="1.0"?>'//nl//'<VTKFile type="UnstructuredGrid" version="1.0" byte_order="'// &
           byte_order()//'" header_type="UInt64"'
    if (w%encoding == enc_zlib) head = head//' compressor="vtkZLibDataCompressor"'
    head = head//'>'//nl//'<UnstructuredGrid>'//nl
    if (len(w%x_field) > 0) head = head//'<FieldData>'//nl//w%x_field//'</FieldData>'//nl
    head = head//'<Piece NumberOfPoints="'//itoa(w%np)//'" NumberOfCells="'//itoa(w%nc)//'">'//nl
    if (len(w%x_point) > 0) head = head//'<PointData>'//nl//w%x_point//'</PointData>'//nl
    if (len(w%x_cell) > 0) head = head//'<CellData>'//nl//w%x_cell//'</CellData>'//nl
    head = head//'<Points>'//nl//w%x_points//'</Points>'//nl//'<Cells>'//nl//w%x_cells//'</Cells>'//nl// &
           '</Piece>'//nl//'</UnstructuredGrid>'//nl

    part = w%path//'.part'
    open (newunit=u, file=part, status='replace', access='stream', form='unformatted', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot open '//part//' for writing')
    write (u, iostat=ios) head
    if (ios == 0 .and. w%encoding /= enc_ascii) then
      write (u, iostat=ios) '<AppendedData encoding="raw">'//nl//'_'
      if (ios == 0 .and. w%nblob > 0) write (u, iostat=ios) w%blob(1:w%nblob)
      if (ios == 0) write (u, iostat=ios) nl//'</AppendedData>'//nl
    end if
    if (ios == 0) write (u, iostat=ios) '</VTKFile>'//nl
    if (ios /= 0) call fatal('cannot write '//part//' (disk full?)')
    call close_written(u, part)
    call atomic_rename(part, w%path)
    call vtu_abort(w)
  end subroutine vtu_end

  !> Drop a .vtu being built without writing it.
  subroutine vtu_abort(w)
    type(vtu_t), intent(inout) :: w
    if (allocated(w%blob)) deallocate (w%blob)
    w%x_field = ''
    w%x_point = ''
    w%x_cell = ''
    w%x_points = ''
    w%x_cells = ''
    w%nblob = 0
    w%open = .false.
  end subroutine vtu_abort

  ! ---------------------------------------------------------------- helpers

  subroutine require(w, who)
    type(vtu_t), intent(in) :: w
    character(len=*), intent(in) :: who
    if (.not. w%open) call fatal(who//': no .vtu begun (vtu_begin)')
  end subroutine require

  subroutine check_tuples(w, where, name, nvalues, ncomp, ntuples)
    type(vtu_t), intent(in) :: w
    character(len=*), intent(in) :: where, name
    integer, intent(in) :: nvalues, ncomp, ntuples
    call require(w, 'vtu_'//where//'_data')
    if (ncomp < 1) call fatal('vtu '//w%path//': '//where//' field '//name//' has no components')
    if (nvalues /= ncomp*ntuples) &
      call fatal('vtu '//w%path//': '//where//' field '//name//' has '//itoa(nvalues)//' values, expected '// &
                 itoa(ncomp)//' x '//itoa(ntuples))
  end subroutine check_tuples

  !> Opening tag of a DataArray.
  function array_tag(w, vtype, name, ncomp, ntuples, always_ncomp) result(s)
    type(vtu_t), intent(in) :: w
    character(len=*), intent(in) :: vtype, name
    integer, intent(in) :: ncomp
    integer, intent(in), optional :: ntuples
    logical, intent(in), optional :: always_ncomp
    character(len=:), allocatable :: s
    logical :: force
    force = .false.
    if (present(always_ncomp)) force = always_ncomp
    s = '<DataArray type="'//vtype//'" Name="'//xml_escape(name)//'"'
    if (ncomp > 1 .or. force) s = s//' NumberOfComponents="'//itoa(ncomp)//'"'
    if (present(ntuples)) s = s//' NumberOfTuples="'//itoa(ntuples)//'"'
    if (w%encoding == enc_ascii) then
      s = s//' format="ascii">'
    else
      s = s//' format="appended" offset="'//itoa(w%nblob)//'"/>'//nl
    end if
  end function array_tag

  subroutine add_real(w, section, name, ncomp, v, ntuples, always_ncomp)
    type(vtu_t), intent(inout) :: w
    character(len=:), allocatable, intent(inout) :: section
    character(len=*), intent(in) :: name
    integer, intent(in) :: ncomp
    real(wp), intent(in) :: v(:)
    integer, intent(in), optional :: ntuples
    logical, intent(in), optional :: always_ncomp
    character(len=:), allocatable :: buf
    integer :: ios
    if (w%single) then
      section = section//array_tag(w, 'Float32', name, ncomp, ntuples, always_ncomp)
    else
      section = section//array_tag(w, 'Float64', name, ncomp, ntuples, always_ncomp)
    end if
    if (w%encoding == enc_ascii) then
      allocate (character(len=25*size(v) + 1) :: buf)
      buf(:) = ' '
      if (size(v) > 0) write (buf, '(*(es25.16e3))', iostat=ios) v
      section = section//nl//trim(buf)//nl//'</DataArray>'//nl
    else if (w%single) then
      call append_bytes(w, transfer(real(v, real32), [0_int8]))
    else
      call append_bytes(w, transfer(v, [0_int8]))
    end if
  end subroutine add_real

  subroutine add_int32(w, section, name, ncomp, v)
    type(vtu_t), intent(inout) :: w
    character(len=:), allocatable, intent(inout) :: section
    character(len=*), intent(in) :: name
    integer, intent(in) :: ncomp
    integer(ik), intent(in) :: v(:)
    character(len=:), allocatable :: buf
    integer :: ios
    section = section//array_tag(w, 'Int32', name, ncomp)
    if (w%encoding == enc_ascii) then
      allocate (character(len=12*size(v) + 1) :: buf)
      buf(:) = ' '
      if (size(v) > 0) write (buf, '(*(i12))', iostat=ios) v
      section = section//nl//trim(buf)//nl//'</DataArray>'//nl
    else
      call append_bytes(w, transfer(int(v, int32), [0_int8]))
    end if
  end subroutine add_int32

  subroutine add_int64(w, section, name, v)
    type(vtu_t), intent(inout) :: w
    character(len=:), allocatable, intent(inout) :: section
    character(len=*), intent(in) :: name
    integer(int64), intent(in) :: v(:)
    character(len=:), allocatable :: buf
    integer :: ios
    section = section//array_tag(w, 'Int64', name, 1)
    if (w%encoding == enc_ascii) then
      allocate (character(len=21*size(v) + 1) :: buf)
      buf(:) = ' '
      if (size(v) > 0) write (buf, '(*(i21))', iostat=ios) v
      section = section//nl//trim(buf)//nl//'</DataArray>'//nl
    else
      call append_bytes(w, transfer(v, [0_int8]))
    end if
  end subroutine add_int64

  subroutine add_uint8(w, section, name, v)
    type(vtu_t), intent(inout) :: w
    character(len=:), allocatable, intent(inout) :: section
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: v(:)
    character(len=:), allocatable :: buf
    integer :: ios
    if (any(v < 0 .or. v > 255)) call fatal('vtu '//w%path//': '//name//' out of range 0..255')
    section = section//array_tag(w, 'UInt8', name, 1)
    if (w%encoding == enc_ascii) then
      allocate (character(len=4*size(v) + 1) :: buf)
      buf(:) = ' '
      if (size(v) > 0) write (buf, '(*(i4))', iostat=ios) v
      section = section//nl//trim(buf)//nl//'</DataArray>'//nl
    else
      call append_bytes(w, int(v - merge(256, 0, v > 127), int8))   ! UInt8 bit patterns
    end if
  end subroutine add_uint8

  !> Append one array's bytes to the appended data: [UInt64 byte count][bytes]
  !> raw, or zlib blocks with VTK's header [nblocks][block size][last block
  !> size (0: full)][compressed size of each block], then the blocks
  !> (compressed by fracas_zlib.c straight into the appended data).
  subroutine append_bytes(w, bytes)
    type(vtu_t), intent(inout) :: w
    integer(int8), intent(in), contiguous :: bytes(:)
    integer(int64) :: n, nblocks, hpos, cap
    integer(int64), allocatable :: header(:)
    integer(c_long) :: total
    n = size(bytes, kind=int64)
    if (w%encoding == enc_raw) then
      call grow(w, 8_int64 + n)
      w%blob(w%nblob + 1:w%nblob + 8) = transfer(n, [0_int8], 8)
      if (n > 0) w%blob(w%nblob + 9:w%nblob + 8 + n) = bytes
      w%nblob = w%nblob + 8 + n
      return
    end if
    nblocks = (n + zblock - 1) / zblock
    allocate (header(3 + nblocks))
    header(1:3) = [nblocks, zblock, mod(n, zblock)]
    hpos = w%nblob
    cap = nblocks * int(c_zlib_bound(int(zblock, c_long)), int64)
    call grow(w, 8 * (3 + nblocks) + cap)
    w%nblob = w%nblob + 8 * (3 + nblocks)
    if (nblocks > 0) then
      total = c_zlib_blocks(bytes, int(n, c_long), int(zblock, c_long), int(w%level, c_int), 1_c_int, &
                            w%blob(w%nblob + 1:), int(cap, c_long), header(4:))
      if (total < 0) call fatal('vtu '//w%path//': zlib compression failed')
      w%nblob = w%nblob + total
    end if
    w%blob(hpos + 1:hpos + 8 * (3 + nblocks)) = transfer(header, [0_int8], 8 * (3 + nblocks))
  end subroutine append_bytes

  !> Make room for m more bytes in the appended data (doubling).
  subroutine grow(w, m)
    type(vtu_t), intent(inout) :: w
    integer(int64), intent(in) :: m
    integer(int8), allocatable :: tmp(:)
    integer(int64) :: need
    need = w%nblob + m
    if (need <= size(w%blob, kind=int64)) return
    allocate (tmp(max(need, 2 * size(w%blob, kind=int64), 65536_int64)))
    if (w%nblob > 0) tmp(1:w%nblob) = w%blob(1:w%nblob)
    call move_alloc(tmp, w%blob)
  end subroutine grow

  !> Inflate zlib data into out(:) (whose size is the expected length); for
  !> tests and readers. stat = 0 on success.
  subroutine zlib_uncompress(zdata, out, stat)
    integer(int8), intent(in), target :: zdata(:)
    integer(int8), intent(inout), target :: out(:)
    integer, intent(out) :: stat
    integer(c_long) :: n
    n = size(out, kind=c_long)
    stat = int(c_uncompress(c_loc(out), n, c_loc(zdata), size(zdata, kind=c_long)))
    if (stat == 0 .and. n /= size(out, kind=c_long)) stat = -100
  end subroutine zlib_uncompress

  !> 'LittleEndian' or 'BigEndian': the order raw binary values are written in.
  function byte_order() result(s)
    character(len=:), allocatable :: s
    integer(int8) :: b(4)
    b = transfer(1_int32, b)
    if (b(1) == 1_int8) then
      s = 'LittleEndian'
    else
      s = 'BigEndian'
    end if
  end function byte_order

  ! ================================================================ .pvd

  !> Start a collection at PATH and write it (empty) at once.
  subroutine pvd_init(pvd, path)
    type(pvd_t), intent(out) :: pvd
    character(len=*), intent(in) :: path
    pvd%path = trim(path)
    pvd%body = ''
    pvd%n = 0
    call pvd_write(pvd)
  end subroutine pvd_init

  !> List FILE (a path relative to the .pvd's directory) at TIME and rewrite the
  !> whole collection. part: VTK part number (default 0), for several files per time.
  subroutine pvd_add(pvd, time, file, part)
    type(pvd_t), intent(inout) :: pvd
    real(wp), intent(in) :: time
    character(len=*), intent(in) :: file
    integer, intent(in), optional :: part
    character(len=32) :: tbuf
    integer :: ipart
    if (.not. allocated(pvd%path)) call fatal('pvd_add before pvd_init')
    ipart = 0
    if (present(part)) ipart = part
    write (tbuf, '(es24.16e3)') time
    pvd%body = pvd%body//'  <DataSet timestep="'//trim(adjustl(tbuf))//'" group="" part="'// &
               itoa(ipart)//'" file="'//xml_escape(trim(file))//'"/>'//nl
    pvd%n = pvd%n + 1
    call pvd_write(pvd)
  end subroutine pvd_add

  subroutine pvd_free(pvd)
    type(pvd_t), intent(inout) :: pvd
    if (allocated(pvd%path)) deallocate (pvd%path)
    if (allocated(pvd%body)) deallocate (pvd%body)
    pvd%n = 0
  end subroutine pvd_free

  subroutine pvd_write(pvd)
    type(pvd_t), intent(in) :: pvd
    character(len=:), allocatable :: part
    integer :: u, ios
    part = pvd%path//'.part'
    open (newunit=u, file=part, status='replace', access='stream', form='unformatted', &
          action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot open '//part//' for writing')
    write (u, iostat=ios) '<?xml version="1.0"?>'//nl// &
      '<VTKFile type="Collection" version="0.1" byte_order="'//byte_order()//'">'//nl// &
      '<Collection>'//nl//pvd%body//'</Collection>'//nl//'</VTKFile>'//nl
    if (ios /= 0) call fatal('cannot write '//part//' (disk full?)')
    call close_written(u, part)
    call atomic_rename(part, pvd%path)
  end subroutine pvd_write

  ! ================================================================ text

  !> Escape the characters XML forbids in attribute values.
  pure function xml_escape(s) result(r)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    integer :: i
    r = ''
    do i = 1, len(s)
      select case (s(i:i))
      case ('&')
        r = r//'&amp;'
      case ('<')
        r = r//'&lt;'
      case ('>')
        r = r//'&gt;'
      case ('"')
        r = r//'&quot;'
      case default
        r = r//s(i:i)
      end select
    end do
  end function xml_escape

end module fracas_vtk
