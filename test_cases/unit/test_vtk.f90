!> fracas_vtk and fracas_files: write small .vtu files in the three encodings
!> (ascii, appended raw, appended zlib) and a .pvd, read them back and check
!> structure and numbers (reference: the arrays written); the cell helpers
!> (fixed-size cells, vertex cells); Float32 output; a 1e5-point file in time;
!> and memory: 200 frames of 1e4 points must not grow the resident set by more
!> than 4 MB (each frame holds 0.6 MB of data: a leak of one frame's arrays would
!> add 100 MB; a planted leak of the points alone, 0.24 MB a frame, fails it).
!> Files go to a directory next to the test executable.
program test_vtk
  use, intrinsic :: iso_fortran_env, only: int8, int32, int64, real32
  use fracas_kinds, only: wp, ik, i8
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_files, only: make_dir, file_exists, dir_exists, remove_file, atomic_rename, list_dir, name_t, executable_dir
  use fracas_vtk, only: vtu_t, vtu_begin, vtu_points, vtu_cells, vtu_cells_fixed, vtu_vertex_cells, &
                        vtu_point_data, vtu_cell_data, vtu_field_data, vtu_end, zlib_uncompress, &
                        pvd_t, pvd_init, pvd_add, pvd_free, vtk_vertex, vtk_line, vtk_poly_line, vtk_polygon, &
                        vtk_triangle
  implicit none

  character(len=:), allocatable :: dir, txt
  character(len=5), parameter :: encodings(3) = [character(len=5) :: 'ascii', 'raw', 'zlib']
  real(wp) :: pts(3, 6), vel(3, 6), gap(4)
  integer(ik) :: conn(10), offs(4), types(4), ids(6), status(4)
  type(pvd_t) :: pvd
  type(vtu_t) :: w
  type(name_t), allocatable :: names(:)
  integer :: k, ios, u, e

  dir = executable_dir()//'test_vtk_out'
  call make_dir(dir, parents=.true.)
  call check_true('make_dir created the output directory', dir_exists(dir))
  call make_dir(dir)   ! existing: fine
  call make_dir(dir//'/a/b/c', parents=.true.)
  call check_true('make_dir parents', dir_exists(dir//'/a/b/c'))
  call check_true('dir_exists false on a file name', .not. dir_exists(dir//'/nothing_here'))

  ! fracas_files: rename, remove, list
  open (newunit=u, file=dir//'/x.part', status='replace', action='write', iostat=ios)
  write (u, '(a)') 'hello'
  close (u)
  call atomic_rename(dir//'/x.part', dir//'/x.txt')
  call check_true('atomic_rename: target exists', file_exists(dir//'/x.txt'))
  call check_true('atomic_rename: source gone', .not. file_exists(dir//'/x.part'))
  call list_dir(dir, names)
  call check_true('list_dir sees x.txt and a/', has_name(names, 'x.txt') .and. has_name(names, 'a') &
                  .and. .not. has_name(names, '.') .and. .not. has_name(names, '..'))
  call remove_file(dir//'/x.txt')
  call check_true('remove_file', .not. file_exists(dir//'/x.txt'))
  call remove_file(dir//'/x.txt')   ! missing: fine
  call atomic_rename(dir//'/missing', dir//'/y', stat=ios)
  call check_true('atomic_rename of a missing file reports failure', ios /= 0)
  call list_dir(dir//'/nothing_here', names)
  call check_true('list_dir of a missing folder is empty', size(names) == 0)

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
  status = [1, 2, 3, 200]

  do e = 1, 3
    call vtu_begin(w, dir//'/grid_'//trim(encodings(e))//'.vtu', 6, 4, time=0.75_wp, encoding=trim(encodings(e)))
    call vtu_points(w, pts)
    call vtu_cells(w, conn, offs, types)
    call vtu_point_data(w, 'velocity', vel)
    call vtu_point_data(w, 'id', ids)
    call vtu_cell_data(w, 'gap', gap)
    call vtu_cell_data(w, 'status', status)
    call vtu_end(w)
    call check_true(trim(encodings(e))//': no .part file left', &
                    .not. file_exists(dir//'/grid_'//trim(encodings(e))//'.vtu.part'))
    txt = slurp(dir//'/grid_'//trim(encodings(e))//'.vtu')
    call check_xml_frame(trim(encodings(e)), txt)
    call check_reals(trim(encodings(e))//' Points', reals(txt, 'Points', 18), reshape(pts, [18]))
    call check_reals(trim(encodings(e))//' velocity', reals(txt, 'velocity', 18), reshape(vel, [18]))
    call check_reals(trim(encodings(e))//' gap', reals(txt, 'gap', 4), gap)
    call check_reals(trim(encodings(e))//' TimeValue', reals(txt, 'TimeValue', 1), [0.75_wp])
    call check_ints(trim(encodings(e))//' id', ints32(txt, 'id', 6), ids)
    call check_ints(trim(encodings(e))//' status', ints32(txt, 'status', 4), status)
    call check_ints(trim(encodings(e))//' connectivity', int(ints64(txt, 'connectivity', 10), ik), conn)
    call check_ints(trim(encodings(e))//' offsets', int(ints64(txt, 'offsets', 4), ik), offs)
    call check_ints(trim(encodings(e))//' types', uints8(txt, 'types', 4), types)
    call check_true(trim(encodings(e))//': Int32 type for integer fields', index(txt, '<DataArray type="Int32" Name="id"') > 0)
    call check_true(trim(encodings(e))//': Float64 vectors have 3 components', &
                    index(txt, '<DataArray type="Float64" Name="velocity" NumberOfComponents="3"') > 0)
  end do
  txt = slurp(dir//'/grid_zlib.vtu')
  call check_true('zlib: compressor named', index(txt, 'compressor="vtkZLibDataCompressor"') > 0)
  call check_true('zlib: appended data', index(txt, '<AppendedData encoding="raw">') > 0)

  ! Float32 reals, 2-row points padded with z = 0, fixed-size cells
  call vtu_begin(w, dir//'/tri.vtu', 4, 2, encoding='zlib', single=.true.)
  call vtu_points(w, pts(1:2, 1:4))
  call vtu_cells_fixed(w, reshape([0_ik, 1_ik, 2_ik, 0_ik, 2_ik, 3_ik], [3, 2]), vtk_triangle)
  call vtu_cell_data(w, 'area', [0.5_wp, 0.5_wp])
  call vtu_end(w)
  txt = slurp(dir//'/tri.vtu')
  call check_true('single: Float32 type', index(txt, '<DataArray type="Float32" Name="area"') > 0)
  call check_reals('single: 2-row points padded', real(transfer(appended(txt, 'Points', 48), 1.0_real32, 12), wp), &
                   reshape(pts(:, 1:4), [12]))
  call check_ints('fixed cells: offsets', int(ints64(txt, 'offsets', 2), ik), [3_ik, 6_ik])
  call check_ints('fixed cells: types', uints8(txt, 'types', 2), [vtk_triangle, vtk_triangle])

  ! vertex cells; an empty grid is valid
  call vtu_begin(w, dir//'/cloud.vtu', 3, 3)
  call vtu_points(w, pts(:, 1:3))
  call vtu_vertex_cells(w)
  call vtu_point_data(w, 'radius', [0.1_wp, 0.2_wp, 0.3_wp])
  call vtu_end(w)
  txt = slurp(dir//'/cloud.vtu')
  call check_ints('vertex cells: connectivity', int(ints64(txt, 'connectivity', 3), ik), [0_ik, 1_ik, 2_ik])
  call check_ints('vertex cells: types', uints8(txt, 'types', 3), [vtk_vertex, vtk_vertex, vtk_vertex])
  call vtu_begin(w, dir//'/empty.vtu', 0, 0)
  call vtu_points(w, pts(:, 1:0))
  call vtu_cells(w, conn(1:0), offs(1:0), types(1:0))
  call vtu_cell_data(w, 'gap', gap(1:0))
  call vtu_end(w)
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
  call memory_stays_flat()
  call test_finish()

contains

  !> 1e5 contact points as vertices with six fields: must take well under a second in release.
  subroutine big_file()
    integer, parameter :: n = 100000
    real(wp), allocatable :: p(:, :), nrm(:, :), r(:, :), g(:)
    integer(ik), allocatable :: st(:)
    integer(i8) :: t0, t1, rate
    integer :: i
    real(wp) :: secs
    allocate (p(3, n), nrm(3, n), r(3, n), g(n), st(n))
    do i = 1, n
      p(:, i) = [real(i, wp), 0.5_wp*i, 0.0_wp]
      nrm(:, i) = [cos(0.001_wp*i), sin(0.001_wp*i), 0.0_wp]
      r(:, i) = 3.0_wp*nrm(:, i)
      g(i) = 1.0e-6_wp*i
      st(i) = mod(i, 4) + 1
    end do
    call system_clock(t0, rate)
    call write_cloud(dir//'/big.vtu', p, nrm, r, g, st)
    call system_clock(t1)
    secs = real(t1 - t0, wp)/real(rate, wp)
    write (*, '(a,f8.3,a)') 'INFO 1e5-vertex .vtu written in ', secs, ' s'
    call check_true('1e5-vertex .vtu written in < 5 s', secs < 5.0_wp)
    txt = slurp(dir//'/big.vtu')
    call check_reals('big: gap read back', reals(txt, 'gap', n), g)
    call check_ints('big: status read back', ints32(txt, 'status', n), st)
    call remove_file(dir//'/big.vtu')
  end subroutine big_file

  subroutine write_cloud(path, p, nrm, r, g, st)
    character(len=*), intent(in) :: path
    real(wp), intent(in) :: p(:, :), nrm(:, :), r(:, :), g(:)
    integer(ik), intent(in) :: st(:)
    type(vtu_t) :: v
    call vtu_begin(v, path, size(g), size(g))
    call vtu_points(v, p)
    call vtu_vertex_cells(v)
    call vtu_point_data(v, 'normal', nrm)
    call vtu_point_data(v, 'reaction', r)
    call vtu_point_data(v, 'rn', r(1, :))
    call vtu_point_data(v, 'rt', r(2, :))
    call vtu_point_data(v, 'status', st)
    call vtu_point_data(v, 'gap', g)
    call vtu_end(v)
  end subroutine write_cloud

  !> The resident set after 200 frames of 1e4 points stays within 4 MB of the
  !> one after 20 frames (Linux: /proc/self/status; skipped elsewhere).
  subroutine memory_stays_flat()
    integer, parameter :: n = 10000, frames = 200
    real(wp), allocatable :: p(:, :), nrm(:, :), r(:, :), g(:)
    integer(ik), allocatable :: st(:)
    integer :: i, rss0, rss1
    allocate (p(3, n), nrm(3, n), r(3, n), g(n), st(n))
    do i = 1, n
      p(:, i) = [real(i, wp), 0.5_wp*i, 0.0_wp]
      nrm(:, i) = [cos(0.001_wp*i), sin(0.001_wp*i), 0.0_wp]
      r(:, i) = 3.0_wp*nrm(:, i)
      g(i) = 1.0e-6_wp*i
      st(i) = mod(i, 4) + 1
    end do
    rss0 = -1
    do i = 1, frames
      call write_cloud(dir//'/frame.vtu', p, nrm, r, g, st)
      if (i == 20) rss0 = resident_kb()
    end do
    rss1 = resident_kb()
    call remove_file(dir//'/frame.vtu')
    if (rss0 < 0 .or. rss1 < 0) then
      write (*, '(a)') 'INFO resident set not readable here: memory check skipped'
      return
    end if
    write (*, '(a,i0,a,i0,a,i0,a)') 'INFO resident set after 20 frames ', rss0, ' kB, after ', frames, ' frames ', &
      rss1, ' kB'
    call check_true('resident set grows by less than 4 MB over 180 frames', rss1 - rss0 < 4096)
  end subroutine memory_stays_flat

  !> VmRSS of this process in kB (-1 if unknown).
  integer function resident_kb() result(kb)
    character(len=256) :: line
    integer :: u, ios
    kb = -1
    open (newunit=u, file='/proc/self/status', action='read', status='old', iostat=ios)
    if (ios /= 0) return
    do
      read (u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:6) == 'VmRSS:') then
        read (line(7:), *, iostat=ios) kb
        exit
      end if
    end do
    close (u)
  end function resident_kb

  logical function has_name(list, name)
    type(name_t), intent(in) :: list(:)
    character(len=*), intent(in) :: name
    integer :: i
    has_name = .false.
    do i = 1, size(list)
      if (list(i)%s == name) has_name = .true.
    end do
  end function has_name


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
    integer :: nopen
    call check_true(tag//': XML declaration', index(s, '<?xml version="1.0"?>') == 1)
    call check_true(tag//': UnstructuredGrid', index(s, '<VTKFile type="UnstructuredGrid"') > 0)
    call check_true(tag//': closed', index(s, '</VTKFile>') > 0)
    nopen = count_of(s, '<DataArray')
    call check_true(tag//': DataArrays balanced', nopen == count_of(s, '</DataArray>') + count_of(s, 'offset="'))
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

  !> The opening tag of DataArray NAME.
  function tag_of(s, name) result(tag)
    character(len=*), intent(in) :: s, name
    character(len=:), allocatable :: tag
    integer :: i, j
    i = index(s, 'Name="'//name//'"')
    if (i == 0) then
      tag = ''
      call check_true('array '//name//' present', .false.)
      return
    end if
    i = index(s(1:i), '<DataArray', back=.true.)
    j = i + index(s(i:), '>') - 1
    tag = s(i:j)
  end function tag_of

  !> The values of DataArray NAME as bytes, whatever its encoding (ascii
  !> arrays are read as text by the callers).
  function appended(s, name, nbytes) result(b)
    character(len=*), intent(in) :: s, name
    integer, intent(in) :: nbytes
    integer(int8), allocatable :: b(:)
    character(len=:), allocatable :: tag
    integer(int64) :: off, hdr(3), nblocks, k, pos, csize
    integer(int64), allocatable :: csizes(:)
    integer :: ios, stat
    integer(int64) :: base
    allocate (b(nbytes))
    b = 0
    tag = tag_of(s, name)
    call check_true(name//': appended', index(tag, 'format="appended"') > 0)
    tag = tag(index(tag, 'offset="') + 8:)
    read (tag(1:index(tag, '"') - 1), *, iostat=ios) off
    call check_true(name//': offset read', ios == 0)
    base = index(s, '<AppendedData encoding="raw">') + len('<AppendedData encoding="raw">') + 1   ! newline, '_'
    pos = base + off + 1
    if (index(s, 'compressor="vtkZLibDataCompressor"') == 0) then
      call check_true(name//': byte-count header', transfer(bytes_at(s, pos, 8_int64), 1_int64) == int(nbytes, int64))
      b = bytes_at(s, pos + 8, int(nbytes, int64))
      return
    end if
    hdr = transfer(bytes_at(s, pos, 24_int64), hdr)
    nblocks = hdr(1)
    call check_true(name//': zlib block count', nblocks == (nbytes + hdr(2) - 1) / hdr(2))
    call check_true(name//': zlib last block size', hdr(3) == mod(int(nbytes, int64), hdr(2)))
    allocate (csizes(nblocks))
    if (nblocks > 0) csizes = transfer(bytes_at(s, pos + 24, 8 * nblocks), csizes)
    pos = pos + 24 + 8 * nblocks
    do k = 1, nblocks
      csize = csizes(k)
      call zlib_uncompress(bytes_at(s, pos, csize), b((k - 1) * hdr(2) + 1:min(k * hdr(2), int(nbytes, int64))), stat)
      call check_true(name//': zlib block inflates', stat == 0)
      pos = pos + csize
    end do
  end function appended

  function bytes_at(s, p0, n) result(r)
    character(len=*), intent(in) :: s
    integer(int64), intent(in) :: p0, n
    integer(int8) :: r(n)
    r = transfer(s(p0:p0 + n - 1), r)
  end function bytes_at

  !> Text inside an inline (ascii) DataArray.
  function inline_text(s, name) result(body)
    character(len=*), intent(in) :: s, name
    character(len=:), allocatable :: body
    integer :: i, j, k
    i = index(s, 'Name="'//name//'"')
    j = i + index(s(i:), '>')
    k = j + index(s(j:), '</DataArray>') - 2
    body = s(j:k)
    do i = 1, len(body)
      if (body(i:i) == achar(10)) body(i:i) = ' '
    end do
  end function inline_text

  function reals(s, name, n) result(v)
    character(len=*), intent(in) :: s, name
    integer, intent(in) :: n
    real(wp) :: v(n)
    integer :: ios
    character(len=:), allocatable :: text
    v = -999.0_wp
    if (index(tag_of(s, name), 'format="ascii"') > 0) then
      text = inline_text(s, name)
      read (text, *, iostat=ios) v
      call check_true('read '//name, ios == 0)
    else
      v = transfer(appended(s, name, 8 * n), 1.0_wp, n)
    end if
  end function reals

  function ints32(s, name, n) result(v)
    character(len=*), intent(in) :: s, name
    integer, intent(in) :: n
    integer(ik) :: v(n)
    integer :: ios
    character(len=:), allocatable :: text
    v = -999
    if (index(tag_of(s, name), 'format="ascii"') > 0) then
      text = inline_text(s, name)
      read (text, *, iostat=ios) v
      call check_true('read '//name, ios == 0)
    else
      v = transfer(appended(s, name, 4 * n), 1_int32, n)
    end if
  end function ints32

  function ints64(s, name, n) result(v)
    character(len=*), intent(in) :: s, name
    integer, intent(in) :: n
    integer(int64) :: v(n)
    integer :: ios
    character(len=:), allocatable :: text
    v = -999
    if (index(tag_of(s, name), 'format="ascii"') > 0) then
      text = inline_text(s, name)
      read (text, *, iostat=ios) v
      call check_true('read '//name, ios == 0)
    else
      v = transfer(appended(s, name, 8 * n), 1_int64, n)
    end if
  end function ints64

  function uints8(s, name, n) result(v)
    character(len=*), intent(in) :: s, name
    integer, intent(in) :: n
    integer(ik) :: v(n)
    integer :: ios
    character(len=:), allocatable :: text
    v = -999
    if (index(tag_of(s, name), 'format="ascii"') > 0) then
      text = inline_text(s, name)
      read (text, *, iostat=ios) v
      call check_true('read '//name, ios == 0)
    else
      v = iand(int(appended(s, name, n), ik), 255)
    end if
  end function uints8

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
