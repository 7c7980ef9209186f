!> VTK XML writers for ParaView: one UnstructuredGrid file (.vtu) from plain
!> arrays, and a collection file (.pvd) listing the .vtu files with their times.
!>
!> Data arrays are written inline, base64-encoded raw binary (VTK "binary" format,
!> uncompressed, UInt64 byte-count header, the machine's byte order), or as ASCII
!> text on request. Both are valid XML. Every file is written to PATH.part and
!> renamed to PATH, so a reader never sees a half-written file.
!>
!> Usage:
!>   call write_vtu('DISPLAY/bodies_000001.vtu', xyz, conn, offs, types, &
!>                  point_fields=[vtk_field('velocity', v3)], &
!>                  cell_fields=[vtk_field('id', ids), vtk_field('spin', w)], time=t)
!>   call pvd_init(pvd, 'DISPLAY/fracas.pvd')
!>   call pvd_add(pvd, t, 'bodies_000001.vtu')
module fracas_vtk
  use, intrinsic :: iso_fortran_env, only: int8, int32, int64
  use fracas_kinds, only: wp, ik
  use fracas_strings, only: itoa
  use fracas_errors, only: fatal
  use fracas_files, only: atomic_rename
  implicit none
  private
  public :: vtk_field_t, vtk_field, write_vtu, pvd_t, pvd_init, pvd_add, pvd_free
  public :: vtk_vertex, vtk_poly_vertex, vtk_line, vtk_poly_line, vtk_triangle, &
            vtk_polygon, vtk_quad

  !> VTK cell type codes.
  integer(ik), parameter :: vtk_vertex = 1, vtk_poly_vertex = 2, vtk_line = 3, vtk_poly_line = 4, &
                            vtk_triangle = 5, vtk_polygon = 7, vtk_quad = 9

  !> One named data array attached to the points or to the cells of a grid.
  !> Values are flattened component-fastest: tuple k is values((k-1)*ncomp+1 : k*ncomp).
  !> An integer field (is_int) is written as Int32, a real field as Float64.
  type :: vtk_field_t
    character(len=:), allocatable :: name
    integer :: ncomp = 1
    logical :: is_int = .false.
    real(wp), allocatable :: r(:)      !< values of a real field
    integer(ik), allocatable :: i(:)   !< values of an integer field
  end type vtk_field_t

  !> vtk_field(name, values): build a field from a 1-D array (one component) or a
  !> 2-D array (ncomp, n) of real(wp) or integer values.
  interface vtk_field
    module procedure field_r1, field_r2, field_i1, field_i2
  end interface vtk_field

  !> A .pvd collection: the whole file is rewritten (PATH.part + rename) at each add.
  type :: pvd_t
    character(len=:), allocatable :: path
    character(len=:), allocatable :: body   !< the <DataSet .../> lines so far
    integer :: n = 0                        !< number of data sets listed
  end type pvd_t

  character(len=*), parameter :: nl = achar(10)
  character(len=64), parameter :: b64_alphabet = &
    'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/'

contains

  ! ------------------------------------------------------------------ fields

  function field_r1(name, values) result(f)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: values(:)
    type(vtk_field_t) :: f
    f%name = name
    f%ncomp = 1
    f%is_int = .false.
    f%r = values
  end function field_r1

  function field_r2(name, values) result(f)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: values(:, :)
    type(vtk_field_t) :: f
    f%name = name
    f%ncomp = size(values, 1)
    f%is_int = .false.
    f%r = reshape(values, [size(values)])
  end function field_r2

  function field_i1(name, values) result(f)
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: values(:)
    type(vtk_field_t) :: f
    f%name = name
    f%ncomp = 1
    f%is_int = .true.
    f%i = values
  end function field_i1

  function field_i2(name, values) result(f)
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: values(:, :)
    type(vtk_field_t) :: f
    f%name = name
    f%ncomp = size(values, 1)
    f%is_int = .true.
    f%i = reshape(values, [size(values)])
  end function field_i2

  ! ------------------------------------------------------------------ .vtu

  !> Write a VTK XML UnstructuredGrid file.
  !>   points(2 or 3, np)   coordinates (a 2-row array gets z = 0)
  !>   connectivity(:)      0-based point indices of all cells, one after another
  !>   offsets(nc)          end of each cell in connectivity (VTK convention:
  !>                        cell k uses connectivity(offsets(k-1)+1 : offsets(k)))
  !>   cell_types(nc)       VTK cell type codes (vtk_vertex, vtk_polygon, ...)
  !>   point_fields, cell_fields: fields with np (resp. nc) tuples
  !>   ascii                .true.: ASCII text arrays (default: base64 binary)
  !>   time                 written as FieldData TimeValue (read by ParaView)
  !> Bad sizes or indices are programming errors: fatal with the reason.
  subroutine write_vtu(path, points, connectivity, offsets, cell_types, point_fields, cell_fields, &
                       ascii, time)
    character(len=*), intent(in) :: path
    real(wp), intent(in) :: points(:, :)
    integer(ik), intent(in) :: connectivity(:), offsets(:), cell_types(:)
    type(vtk_field_t), intent(in), optional :: point_fields(:), cell_fields(:)
    logical, intent(in), optional :: ascii
    real(wp), intent(in), optional :: time
    integer :: np, nc, u, ios, k
    logical :: asc
    real(wp), allocatable :: xyz(:, :)
    character(len=:), allocatable :: part

    asc = .false.
    if (present(ascii)) asc = ascii
    np = size(points, 2)
    nc = size(offsets)
    call check_grid(path, points, connectivity, offsets, cell_types)
    if (present(point_fields)) call check_fields(path, 'point', point_fields, np)
    if (present(cell_fields)) call check_fields(path, 'cell', cell_fields, nc)

    part = trim(path)//'.part'
    open (newunit=u, file=part, status='replace', access='stream', form='unformatted', &
          action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot open '//part//' for writing')

    write (u) '<?xml version="1.0"?>'//nl
    write (u) '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="'//byte_order()// &
      '" header_type="UInt64">'//nl
    write (u) '<UnstructuredGrid>'//nl
    if (present(time)) then
      write (u) '<FieldData>'//nl
      call put_real(u, 'TimeValue', 1, [time], asc, ntuples=1)
      write (u) '</FieldData>'//nl
    end if
    write (u) '<Piece NumberOfPoints="'//itoa(np)//'" NumberOfCells="'//itoa(nc)//'">'//nl

    if (present(point_fields)) then
      write (u) '<PointData>'//nl
      do k = 1, size(point_fields)
        call put_field(u, point_fields(k), asc)
      end do
      write (u) '</PointData>'//nl
    end if
    if (present(cell_fields)) then
      write (u) '<CellData>'//nl
      do k = 1, size(cell_fields)
        call put_field(u, cell_fields(k), asc)
      end do
      write (u) '</CellData>'//nl
    end if

    write (u) '<Points>'//nl
    if (size(points, 1) == 3) then
      call put_real(u, 'Points', 3, reshape(points, [3*np]), asc)
    else
      allocate (xyz(3, np))
      xyz(1:2, :) = points(1:2, :)
      xyz(3, :) = 0.0_wp
      call put_real(u, 'Points', 3, reshape(xyz, [3*np]), asc)
    end if
    write (u) '</Points>'//nl

    write (u) '<Cells>'//nl
    call put_int(u, 'connectivity', 1, connectivity, asc)
    call put_int(u, 'offsets', 1, offsets, asc)
    call put_uint8(u, 'types', cell_types, asc)
    write (u) '</Cells>'//nl
    write (u) '</Piece>'//nl
    write (u) '</UnstructuredGrid>'//nl
    write (u) '</VTKFile>'//nl
    close (u, iostat=ios)
    if (ios /= 0) call fatal('cannot write '//part)
    call atomic_rename(part, path)
  end subroutine write_vtu

  subroutine check_grid(path, points, connectivity, offsets, cell_types)
    character(len=*), intent(in) :: path
    real(wp), intent(in) :: points(:, :)
    integer(ik), intent(in) :: connectivity(:), offsets(:), cell_types(:)
    character(len=:), allocatable :: w
    integer :: k, np
    w = 'write_vtu '//trim(path)//': '
    np = size(points, 2)
    if (size(points, 1) /= 2 .and. size(points, 1) /= 3) &
      call fatal(w//'points must have 2 or 3 rows, got '//itoa(size(points, 1)))
    if (size(cell_types) /= size(offsets)) &
      call fatal(w//itoa(size(offsets))//' offsets but '//itoa(size(cell_types))//' cell types')
    if (size(offsets) > 0) then
      if (offsets(size(offsets)) /= size(connectivity)) &
        call fatal(w//'last offset '//itoa(offsets(size(offsets)))//' /= connectivity size '// &
                   itoa(size(connectivity)))
      if (offsets(1) < 0) call fatal(w//'negative first offset')
      do k = 2, size(offsets)
        if (offsets(k) < offsets(k - 1)) call fatal(w//'offsets decrease at cell '//itoa(k))
      end do
    else if (size(connectivity) /= 0) then
      call fatal(w//'connectivity given without cells')
    end if
    if (size(connectivity) > 0) then
      if (minval(connectivity) < 0 .or. maxval(connectivity) >= np) &
        call fatal(w//'connectivity out of range 0..'//itoa(np - 1)//' (indices are 0-based)')
    end if
  end subroutine check_grid

  subroutine check_fields(path, where, fields, ntuples)
    character(len=*), intent(in) :: path, where
    type(vtk_field_t), intent(in) :: fields(:)
    integer, intent(in) :: ntuples
    integer :: k, nv
    do k = 1, size(fields)
      if (.not. allocated(fields(k)%name)) call fatal('write_vtu '//trim(path)//': unnamed '//where//' field')
      if (fields(k)%ncomp < 1) call fatal('write_vtu '//trim(path)//': field '//fields(k)%name// &
                                          ' has no components')
      nv = -1
      if (fields(k)%is_int .and. allocated(fields(k)%i)) nv = size(fields(k)%i)
      if (.not. fields(k)%is_int .and. allocated(fields(k)%r)) nv = size(fields(k)%r)
      if (nv /= fields(k)%ncomp*ntuples) &
        call fatal('write_vtu '//trim(path)//': '//where//' field '//fields(k)%name//' has '// &
                   itoa(nv)//' values, expected '//itoa(fields(k)%ncomp)//' x '//itoa(ntuples))
    end do
  end subroutine check_fields

  subroutine put_field(u, f, asc)
    integer, intent(in) :: u
    type(vtk_field_t), intent(in) :: f
    logical, intent(in) :: asc
    if (f%is_int) then
      call put_int(u, f%name, f%ncomp, f%i, asc)
    else
      call put_real(u, f%name, f%ncomp, f%r, asc)
    end if
  end subroutine put_field

  !> <DataArray type="Float64" ...> for real values.
  subroutine put_real(u, name, ncomp, v, asc, ntuples)
    integer, intent(in) :: u, ncomp
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: v(:)
    logical, intent(in) :: asc
    integer, intent(in), optional :: ntuples
    character(len=:), allocatable :: buf
    integer :: ios
    call open_array(u, 'Float64', name, ncomp, asc, ntuples)
    if (asc) then
      if (size(v) > 0) then
        allocate (character(len=25*size(v)) :: buf)
        write (buf, '(*(es25.16e3))', iostat=ios) v
        write (u) trim(buf)//nl
      end if
    else
      call put_b64(u, transfer(v, [0_int8]))
    end if
    write (u) '</DataArray>'//nl
  end subroutine put_real

  !> <DataArray type="Int32" ...> for integer values.
  subroutine put_int(u, name, ncomp, v, asc)
    integer, intent(in) :: u, ncomp
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: v(:)
    logical, intent(in) :: asc
    character(len=:), allocatable :: buf
    integer :: ios
    call open_array(u, 'Int32', name, ncomp, asc)
    if (asc) then
      if (size(v) > 0) then
        allocate (character(len=12*size(v)) :: buf)
        write (buf, '(*(i12))', iostat=ios) v
        write (u) trim(buf)//nl
      end if
    else
      call put_b64(u, transfer(int(v, int32), [0_int8]))
    end if
    write (u) '</DataArray>'//nl
  end subroutine put_int

  !> <DataArray type="UInt8" ...> (cell types).
  subroutine put_uint8(u, name, v, asc)
    integer, intent(in) :: u
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: v(:)
    logical, intent(in) :: asc
    character(len=:), allocatable :: buf
    integer :: ios
    call open_array(u, 'UInt8', name, 1, asc)
    if (asc) then
      if (size(v) > 0) then
        allocate (character(len=4*size(v)) :: buf)
        write (buf, '(*(i4))', iostat=ios) v
        write (u) trim(buf)//nl
      end if
    else
      call put_b64(u, int(v, int8))
    end if
    write (u) '</DataArray>'//nl
  end subroutine put_uint8

  subroutine open_array(u, vtype, name, ncomp, asc, ntuples)
    integer, intent(in) :: u, ncomp
    character(len=*), intent(in) :: vtype, name
    logical, intent(in) :: asc
    integer, intent(in), optional :: ntuples
    character(len=:), allocatable :: s
    s = '<DataArray type="'//vtype//'" Name="'//xml_escape(name)//'"'
    if (ncomp > 1 .or. name == 'Points') s = s//' NumberOfComponents="'//itoa(ncomp)//'"'
    if (present(ntuples)) s = s//' NumberOfTuples="'//itoa(ntuples)//'"'
    s = s//' format="'//merge('ascii ', 'binary', asc)
    write (u) trim(s)//'">'//nl
  end subroutine open_array

  !> Base64 of [UInt64 byte count][bytes], one line.
  subroutine put_b64(u, bytes)
    integer, intent(in) :: u
    integer(int8), intent(in) :: bytes(:)
    integer(int8), allocatable :: all(:)
    allocate (all(8 + size(bytes)))
    all(1:8) = transfer(int(size(bytes), int64), [0_int8], 8)
    all(9:) = bytes
    write (u) base64(all)//nl
  end subroutine put_b64

  !> Standard base64 (RFC 4648, with '=' padding).
  pure function base64(b) result(s)
    integer(int8), intent(in) :: b(:)
    character(len=4*((size(b) + 2)/3)) :: s
    integer :: n, i, j, t, b0, b1, b2
    n = size(b)
    j = 0
    do i = 1, n - 2, 3
      b0 = iand(int(b(i)), 255)
      b1 = iand(int(b(i + 1)), 255)
      b2 = iand(int(b(i + 2)), 255)
      t = ior(ior(ishft(b0, 16), ishft(b1, 8)), b2)
      s(j + 1:j + 1) = b64_alphabet(ishft(t, -18) + 1:ishft(t, -18) + 1)
      s(j + 2:j + 2) = b64_alphabet(iand(ishft(t, -12), 63) + 1:iand(ishft(t, -12), 63) + 1)
      s(j + 3:j + 3) = b64_alphabet(iand(ishft(t, -6), 63) + 1:iand(ishft(t, -6), 63) + 1)
      s(j + 4:j + 4) = b64_alphabet(iand(t, 63) + 1:iand(t, 63) + 1)
      j = j + 4
    end do
    select case (mod(n, 3))
    case (1)
      b0 = iand(int(b(n)), 255)
      t = ishft(b0, 16)
      s(j + 1:j + 1) = b64_alphabet(ishft(t, -18) + 1:ishft(t, -18) + 1)
      s(j + 2:j + 2) = b64_alphabet(iand(ishft(t, -12), 63) + 1:iand(ishft(t, -12), 63) + 1)
      s(j + 3:j + 4) = '=='
    case (2)
      b0 = iand(int(b(n - 1)), 255)
      b1 = iand(int(b(n)), 255)
      t = ior(ishft(b0, 16), ishft(b1, 8))
      s(j + 1:j + 1) = b64_alphabet(ishft(t, -18) + 1:ishft(t, -18) + 1)
      s(j + 2:j + 2) = b64_alphabet(iand(ishft(t, -12), 63) + 1:iand(ishft(t, -12), 63) + 1)
      s(j + 3:j + 3) = b64_alphabet(iand(ishft(t, -6), 63) + 1:iand(ishft(t, -6), 63) + 1)
      s(j + 4:j + 4) = '='
    end select
  end function base64

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

  ! ------------------------------------------------------------------ .pvd

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
    write (u) '<?xml version="1.0"?>'//nl// &
      '<VTKFile type="Collection" version="0.1" byte_order="'//byte_order()//'">'//nl// &
      '<Collection>'//nl//pvd%body//'</Collection>'//nl//'</VTKFile>'//nl
    close (u, iostat=ios)
    if (ios /= 0) call fatal('cannot write '//part)
    call atomic_rename(part, pvd%path)
  end subroutine pvd_write

  ! ------------------------------------------------------------------ text

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
