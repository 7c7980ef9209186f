!> fracas_vtk and fracas_files: write small .vtu files (ASCII and base64 binary)
!> and a .pvd, read them back and check structure and numbers; time a 1e5-cell file.
!> Files go to a directory next to the test executable (the build tree).
program test_vtk
  use, intrinsic :: iso_fortran_env, only: int8, int32, int64
  use fracas_kinds, only: wp, ik, i8
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_files, only: make_dir, file_exists, dir_exists, remove_file, atomic_rename
  use fracas_vtk, only: vtk_field_t, vtk_field, write_vtu, pvd_t, pvd_init, pvd_add, pvd_free, &
                        vtk_vertex, vtk_line, vtk_poly_line, vtk_polygon
  implicit none

  character(len=:), allocatable :: dir, txt
  real(wp) :: pts(3, 6), vel(3, 6), gap(4)
  integer(ik) :: conn(10), offs(4), types(4), ids(6), status(4)
  type(pvd_t) :: pvd
  integer :: k, ios, u

  dir = out_dir()//'test_vtk_out'
  call make_dir(dir, parents=.true.)
  call check_true('make_dir created the output directory', dir_exists(dir))
  call make_dir(dir)   ! existing: fine
  call make_dir(dir//'/a/b/c', parents=.true.)
  call check_true('make_dir parents', dir_exists(dir//'/a/b/c'))
  call check_true('dir_exists false on a file name', .not. dir_exists(dir//'/nothing_here'))

  ! fracas_files: rename and remove
  open (newunit=u, file=dir//'/x.part', status='replace', action='write', iostat=ios)
  write (u, '(a)') 'hello'
  close (u)
  call atomic_rename(dir//'/x.part', dir//'/x.txt')
  call check_true('atomic_rename: target exists', file_exists(dir//'/x.txt'))
  call check_true('atomic_rename: source gone', .not. file_exists(dir//'/x.part'))
  call remove_file(dir//'/x.txt')
  call check_true('remove_file', .not. file_exists(dir//'/x.txt'))
  call remove_file(dir//'/x.txt')   ! missing: fine
  call atomic_rename(dir//'/missing', dir//'/y', stat=ios)
  call check_true('atomic_rename of a missing file reports failure', ios /= 0)

  ! a grid: a square polygon (0-3), a line (3-4), a poly-line (0,4,5), a vertex (5)
  pts = reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, &
                 0.0_wp, 1.0_wp, 0.0_wp, 2.0_wp, 2.0_wp, 0.0_wp, -1.0_wp, 3.5_wp, 0.0_wp], [3, 6])
  conn = [0, 1, 2, 3, 3, 4, 0, 4, 5, 5]
  offs = [4, 6, 9, 10]
  types = [vtk_polygon, vtk_line, vtk_poly_line, vtk_vertex]
  do k = 1, 6
    vel(:, k) = [0.1_wp*k, -0.25_wp*k, 1.0e-12_wp*k]
    ids(k) = 100 + k
  end do
  gap = [1.5e-3_wp, -2.0e-7_wp, 0.0_wp, 123.456_wp]
  status = [1, 2, 3, 9]

  do k = 1, 2
    call write_vtu(dir//'/grid_'//trim(merge('ascii ', 'binary', k == 1))//'.vtu', pts, conn, offs, types, &
                   point_fields=[vtk_field('velocity', vel), vtk_field('id', ids)], &
                   cell_fields=[vtk_field('gap', gap), vtk_field('status', status)], &
                   ascii=(k == 1), time=0.75_wp)
  end do
  call check_true('no .part file left', .not. file_exists(dir//'/grid_ascii.vtu.part'))

  ! ASCII file: parse the arrays back
  txt = slurp(dir//'/grid_ascii.vtu')
  call check_xml_frame('ascii', txt)
  call check_true('ascii: format attribute', index(txt, 'format="ascii"') > 0)
  call check_reals('ascii Points', ascii_reals(txt, 'Points', 18), reshape(pts, [18]))
  call check_reals('ascii velocity', ascii_reals(txt, 'velocity', 18), reshape(vel, [18]))
  call check_reals('ascii gap', ascii_reals(txt, 'gap', 4), gap)
  call check_reals('ascii TimeValue', ascii_reals(txt, 'TimeValue', 1), [0.75_wp])
  call check_ints('ascii id', ascii_ints(txt, 'id', 6), ids)
  call check_ints('ascii status', ascii_ints(txt, 'status', 4), status)
  call check_ints('ascii connectivity', ascii_ints(txt, 'connectivity', 10), conn)
  call check_ints('ascii offsets', ascii_ints(txt, 'offsets', 4), offs)
  call check_ints('ascii types', ascii_ints(txt, 'types', 4), types)

  ! binary file: decode the base64 arrays
  txt = slurp(dir//'/grid_binary.vtu')
  call check_xml_frame('binary', txt)
  call check_true('binary: header_type UInt64', index(txt, 'header_type="UInt64"') > 0)
  call check_reals('binary Points', transfer(b64_array(txt, 'Points', 18*8), 1.0_wp, 18), reshape(pts, [18]))
  call check_reals('binary velocity', transfer(b64_array(txt, 'velocity', 18*8), 1.0_wp, 18), reshape(vel, [18]))
  call check_reals('binary gap', transfer(b64_array(txt, 'gap', 4*8), 1.0_wp, 4), gap)
  call check_ints('binary id', transfer(b64_array(txt, 'id', 6*4), 1_int32, 6), ids)
  call check_ints('binary connectivity', transfer(b64_array(txt, 'connectivity', 40), 1_int32, 10), conn)
  call check_ints('binary offsets', transfer(b64_array(txt, 'offsets', 16), 1_int32, 4), offs)
  call check_ints('binary types', int(b64_array(txt, 'types', 4), ik), types)
  call check_true('binary: Int32 type for integer fields', index(txt, '<DataArray type="Int32" Name="id"') > 0)
  call check_true('binary: Float64 vectors have 3 components', &
                  index(txt, '<DataArray type="Float64" Name="velocity" NumberOfComponents="3"') > 0)

  ! 2-D points are padded with z = 0; empty grids are valid
  call write_vtu(dir//'/flat.vtu', pts(1:2, :), conn, offs, types, ascii=.true.)
  txt = slurp(dir//'/flat.vtu')
  call check_reals('2-row points padded', ascii_reals(txt, 'Points', 18), reshape(pts, [18]))
  call write_vtu(dir//'/empty.vtu', pts(:, 1:0), conn(1:0), offs(1:0), types(1:0), &
                 cell_fields=[vtk_field('gap', gap(1:0))])
  txt = slurp(dir//'/empty.vtu')
  call check_xml_frame('empty', txt)
  call check_true('empty: zero points and cells', index(txt, 'NumberOfPoints="0" NumberOfCells="0"') > 0)

  ! .pvd collection: always complete, rewritten on each add
  call pvd_init(pvd, dir//'/fracas.pvd')
  txt = slurp(dir//'/fracas.pvd')
  call check_true('pvd: empty collection is complete', index(txt, '</VTKFile>') > 0 .and. count_of(txt, '<DataSet') == 0)
  do k = 1, 3
    call pvd_add(pvd, 0.1_wp*k, 'grid_'//achar(48 + k)//'.vtu')
    txt = slurp(dir//'/fracas.pvd')
    call check_true('pvd: '//achar(48 + k)//' data set(s) listed', count_of(txt, '<DataSet') == k)
    call check_true('pvd: complete after add', index(txt, '</Collection>') > 0 .and. index(txt, '</VTKFile>') > 0)
  end do
  call check_true('pvd: last file listed', index(txt, 'file="grid_3.vtu"') > 0)
  call check_true('pvd: times', index(txt, 'timestep="3.0000000000000004E-001"') > 0 .or. &
                  index(txt, 'timestep="3.0000000000000000E-001"') > 0)
  call check_true('pvd: no .part left', .not. file_exists(dir//'/fracas.pvd.part'))
  call pvd_free(pvd)

  call big_file()
  call test_finish()

contains

  !> 1e5 contact points as vertices with six fields: must take well under a second in release.
  subroutine big_file()
    integer, parameter :: n = 100000
    real(wp), allocatable :: p(:, :), nrm(:, :), r(:, :), g(:)
    integer(ik), allocatable :: c(:), o(:), t(:), st(:)
    integer(i8) :: t0, t1, rate
    integer :: i
    real(wp) :: secs
    allocate (p(3, n), nrm(3, n), r(3, n), g(n), c(n), o(n), t(n), st(n))
    do i = 1, n
      p(:, i) = [real(i, wp), 0.5_wp*i, 0.0_wp]
      nrm(:, i) = [cos(0.001_wp*i), sin(0.001_wp*i), 0.0_wp]
      r(:, i) = 3.0_wp*nrm(:, i)
      g(i) = 1.0e-6_wp*i
      c(i) = i - 1
      o(i) = i
      t(i) = vtk_vertex
      st(i) = mod(i, 4) + 1
    end do
    call system_clock(t0, rate)
    call write_vtu(dir//'/big.vtu', p, c, o, t, cell_fields=[vtk_field('normal', nrm), &
                   vtk_field('reaction', r), vtk_field('rn', r(1, :)), vtk_field('rt', r(2, :)), &
                   vtk_field('status', st), vtk_field('gap', g)])
    call system_clock(t1)
    secs = real(t1 - t0, wp)/real(rate, wp)
    write (*, '(a,f8.3,a)') 'INFO 1e5-vertex .vtu written in ', secs, ' s'
    call check_true('1e5-vertex .vtu written in < 5 s', secs < 5.0_wp)
    txt = slurp(dir//'/big.vtu')
    call check_reals('big: gap read back', transfer(b64_array(txt, 'gap', 8*n), 1.0_wp, n), g)
    call check_ints('big: status read back', transfer(b64_array(txt, 'status', 4*n), 1_int32, n), st)
    call remove_file(dir//'/big.vtu')
  end subroutine big_file

  !> Directory of this executable, with a trailing '/' ('' if unknown).
  function out_dir() result(d)
    character(len=:), allocatable :: d
    character(len=4096) :: arg0
    integer :: i
    call get_command_argument(0, arg0)
    i = index(arg0, '/', back=.true.)
    d = arg0(1:i)
  end function out_dir

  function slurp(path) result(s)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: s
    integer :: u, n, ios
    open (newunit=u, file=path, access='stream', form='unformatted', action='read', status='old', iostat=ios)
    if (ios /= 0) then
      s = ''
      call check_true('open '//path, .false.)
      return
    end if
    inquire (unit=u, size=n)
    allocate (character(len=n) :: s)
    read (u) s
    close (u)
  end function slurp

  subroutine check_xml_frame(tag, s)
    character(len=*), intent(in) :: tag, s
    call check_true(tag//': XML declaration', index(s, '<?xml version="1.0"?>') == 1)
    call check_true(tag//': UnstructuredGrid', index(s, '<VTKFile type="UnstructuredGrid"') > 0)
    call check_true(tag//': closed', index(s, '</VTKFile>') > 0)
    call check_true(tag//': DataArrays balanced', count_of(s, '<DataArray') == count_of(s, '</DataArray>'))
    if (tag /= 'empty') call check_true(tag//': counts', index(s, 'NumberOfPoints="6" NumberOfCells="4"') > 0)
  end subroutine check_xml_frame

  integer function count_of(s, pat) result(n)
    character(len=*), intent(in) :: s, pat
    integer :: i, j
    n = 0
    i = 1
    do
      j = index(s(i:), pat)
      if (j == 0) exit
      n = n + 1
      i = i + j + len(pat) - 1
    end do
  end function count_of

  !> Text between the '>' that ends <DataArray ... Name="NAME" ...> and </DataArray>.
  function array_text(s, name) result(body)
    character(len=*), intent(in) :: s, name
    character(len=:), allocatable :: body
    integer :: i, j, k
    i = index(s, 'Name="'//name//'"')
    if (i == 0) then
      body = ''
      call check_true('array '//name//' present', .false.)
      return
    end if
    j = i + index(s(i:), '>')
    k = j + index(s(j:), '</DataArray>') - 2
    body = s(j:k)
  end function array_text

  function ascii_reals(s, name, n) result(v)
    character(len=*), intent(in) :: s, name
    integer, intent(in) :: n
    real(wp) :: v(n)
    character(len=:), allocatable :: body
    integer :: ios, i
    body = array_text(s, name)
    do i = 1, len(body)
      if (body(i:i) == achar(10)) body(i:i) = ' '
    end do
    v = -999.0_wp
    read (body, *, iostat=ios) v
    call check_true('read '//name, ios == 0)
  end function ascii_reals

  function ascii_ints(s, name, n) result(v)
    character(len=*), intent(in) :: s, name
    integer, intent(in) :: n
    integer(ik) :: v(n)
    character(len=:), allocatable :: body
    integer :: ios, i
    body = array_text(s, name)
    do i = 1, len(body)
      if (body(i:i) == achar(10)) body(i:i) = ' '
    end do
    v = -999
    read (body, *, iostat=ios) v
    call check_true('read '//name, ios == 0)
  end function ascii_ints

  !> Decode a binary DataArray: check the UInt64 byte-count header, return the bytes.
  function b64_array(s, name, nbytes) result(b)
    character(len=*), intent(in) :: s, name
    integer, intent(in) :: nbytes
    integer(int8), allocatable :: b(:)
    integer(int8), allocatable :: all(:)
    all = b64_decode(trim(adjustl(strip_nl(array_text(s, name)))))
    call check_true(name//': decoded size', size(all) == 8 + nbytes)
    call check_true(name//': byte-count header', transfer(all(1:8), 1_int64) == int(nbytes, int64))
    b = all(9:)
  end function b64_array

  function strip_nl(s) result(r)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: r
    integer :: i
    r = s
    do i = 1, len(r)
      if (r(i:i) == achar(10)) r(i:i) = ' '
    end do
  end function strip_nl

  function b64_decode(s) result(b)
    character(len=*), intent(in) :: s
    integer(int8), allocatable :: b(:)
    character(len=*), parameter :: alpha = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/'
    integer :: i, n, npad, t, k, q(4), j
    n = len(s)
    npad = 0
    if (n >= 1) then
      if (s(n:n) == '=') npad = 1
    end if
    if (n >= 2) then
      if (s(n - 1:n) == '==') npad = 2
    end if
    allocate (b(3*(n/4) - npad))
    k = 0
    do i = 1, n, 4
      do j = 1, 4
        q(j) = max(0, index(alpha, s(i + j - 1:i + j - 1)) - 1)
      end do
      t = ior(ior(ishft(q(1), 18), ishft(q(2), 12)), ior(ishft(q(3), 6), q(4)))
      do j = 1, 3
        if (k + j <= size(b)) b(k + j) = int(iand(ishft(t, -8*(3 - j)), 255) - merge(256, 0, iand(ishft(t, -8*(3 - j)), 255) > 127), int8)
      end do
      k = k + 3
    end do
  end function b64_decode

  subroutine check_reals(name, got, ref)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: got(:), ref(:)
    call check_true(name//' size', size(got) == size(ref))
    call check_close(name//' max error', maxval(abs(got - ref)), 0.0_wp, 1.0e-15_wp*max(1.0_wp, maxval(abs(ref))))
  end subroutine check_reals

  subroutine check_ints(name, got, ref)
    character(len=*), intent(in) :: name
    integer(ik), intent(in) :: got(:), ref(:)
    call check_true(name, size(got) == size(ref) .and. all(got == ref))
  end subroutine check_ints
end program test_vtk
