!> fracas_h5 and fracas_results_h5: write files, read them back with the HDF5
!> Fortran API and compare; no HDF5 id may stay open; a 1e5-contact snapshot is timed.
!> Files go to a directory next to the test executable (the build tree).
program test_h5
  use fracas_kinds, only: wp, ik, i8
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_files, only: make_dir, remove_file, file_exists, executable_dir
  use fracas_h5, only: hid_t, h5_series_t, h5_create_file, h5_open_file, h5_close_file, &
                       h5_open_objects, h5_create_group, h5_open_group, h5_close_group, h5_exists, &
                       h5_write_attr, h5_read_attr, h5_has_attr, h5_write_dataset, h5_read_dataset, &
                       h5_dataset_dims, h5_create_series, h5_open_series, h5_append, h5_close_series, &
                       h5_flush
  use fracas_results_h5, only: results_h5_t, results_open, results_write_bodies, results_write_help, &
                               results_write_snapshot, results_append_step, results_close
  implicit none

  character(len=:), allocatable :: dir

  dir = executable_dir()//'test_h5_out'
  call make_dir(dir, parents=.true.)
  call low_level()
  call results_file()
  call big_snapshot()
  call test_finish()

contains

  subroutine low_level()
    character(len=:), allocatable :: path, s
    character(len=:), allocatable :: names(:)
    integer(hid_t) :: f, g
    type(h5_series_t) :: sr, si
    real(wp) :: a2(3, 4), x
    real(wp), allocatable :: r1(:), r2(:, :)
    integer(ik), allocatable :: i1(:), i2(:, :)
    integer(ik) :: b2(2, 5), n
    integer, allocatable :: dims(:)
    integer :: k

    path = dir//'/low.h5'
    call remove_file(path)
    call h5_create_file(path, .false., f)
    call check_true('create: file exists', file_exists(path))
    call h5_write_attr(f, 'program', 'fracas')
    call h5_write_attr(f, 'n', 42_ik)
    call h5_write_attr(f, 'x', 2.5_wp)
    call h5_write_attr(f, 'n', 43_ik)   ! replaced
    call h5_write_attr(f, 'v', [1.0_wp, 2.0_wp])
    call h5_write_attr(f, 'iv', [1_ik, 2_ik, 3_ik])
    call h5_create_group(f, 'g', g)
    call h5_write_attr(g, 'label', 'a group  ')
    do k = 1, 4
      a2(:, k) = [1.0_wp*k, 10.0_wp*k, 100.0_wp*k]
    end do
    b2 = reshape([(k, k=1, 10)], [2, 5])
    call h5_write_dataset(g, 'a2', a2)
    call h5_write_dataset(g, 'a2z', a2, compress=4)
    call h5_write_dataset(g, 'a1', a2(2, :))          ! a non-contiguous section
    call h5_write_dataset(g, 'b2', b2)
    call h5_write_dataset(g, 'b1', b2(1, :))
    call h5_write_dataset(g, 'empty', a2(:, 1:0))
    call h5_write_dataset(g, 'empty1', b2(1, 1:0))
    call h5_write_dataset(g, 'names', [character(len=6) :: 'noctc', 'stick', 'Cslfw ', ''])
    call h5_write_dataset(g, 'b1', b2(2, :))          ! replaced
    call h5_create_series(g, 'sr', sr)
    call h5_create_series(g, 'si', si, is_int=.true., chunk=4)
    do k = 1, 10
      call h5_append(sr, 0.5_wp*k)
      call h5_append(si, int(k, ik))
    end do
    call h5_append(sr, [100.0_wp, 200.0_wp])
    call h5_append(si, [11_ik, 12_ik])
    call h5_append(si, 13.0_wp)                        ! converted to the series' type
    call h5_flush(f)
    call check_true('series length', sr%n == 12 .and. si%n == 13)
    call h5_close_series(sr)
    call h5_close_series(si)
    call h5_close_group(g)
    call check_true('no ids left open before close', h5_open_objects(f) == 0)
    call h5_close_file(f)

    ! read back
    call h5_open_file(path, f)
    call h5_read_attr(f, 'program', s)
    call check_true('string attribute', s == 'fracas')
    call h5_read_attr(f, 'n', n)
    call check_true('integer attribute (replaced)', n == 43)
    call h5_read_attr(f, 'x', x)
    call check_close('real attribute', x, 2.5_wp, 0.0_wp)
    call check_true('has_attr', h5_has_attr(f, 'v') .and. .not. h5_has_attr(f, 'nope'))
    call check_true('exists', h5_exists(f, 'g/a2') .and. .not. h5_exists(f, 'g/zz') .and. &
                    .not. h5_exists(f, 'nogroup/a2'))
    call h5_open_group(f, 'g', g)
    call h5_read_attr(g, 'label', s)
    call check_true('string attribute, trailing blanks dropped', s == 'a group')
    call h5_read_dataset(g, 'a2', r2)
    call check_true('2-D real shape', all(shape(r2) == [3, 4]))
    call check_close('2-D real values', maxval(abs(r2 - a2)), 0.0_wp, 0.0_wp)
    call h5_read_dataset(g, 'a2z', r2)
    call check_close('2-D real values (compressed)', maxval(abs(r2 - a2)), 0.0_wp, 0.0_wp)
    call h5_read_dataset(g, 'a1', r1)
    call check_close('1-D real from a section', maxval(abs(r1 - a2(2, :))), 0.0_wp, 0.0_wp)
    call h5_read_dataset(g, 'b2', i2)
    call check_true('2-D integer', all(shape(i2) == [2, 5]) .and. all(i2 == b2))
    call h5_read_dataset(g, 'b1', i1)
    call check_true('1-D integer (replaced)', all(i1 == b2(2, :)))
    call h5_dataset_dims(g, 'empty', dims)
    call check_true('empty 2-D dataset dims', all(dims == [3, 0]))
    call h5_read_dataset(g, 'empty1', i1)
    call check_true('empty 1-D dataset', size(i1) == 0)
    call h5_read_dataset(g, 'names', names)
    call check_true('string dataset', size(names) == 4 .and. names(1) == 'noctc' .and. &
                    names(3) == 'Cslfw' .and. names(4) == '' .and. len(names) == 5)
    call h5_read_dataset(g, 'sr', r1)
    call check_true('real series', size(r1) == 12)
    call check_close('real series values', r1(10) + r1(12), 205.0_wp, 0.0_wp)
    call h5_read_dataset(g, 'si', i1)
    call check_true('integer series', size(i1) == 13 .and. all(i1 == [(k, k=1, 13)]))
    call h5_close_group(g)
    call check_true('no ids left open after reading', h5_open_objects(f) == 0)
    call h5_close_file(f)

    ! re-open for writing: series go on
    call h5_open_file(path, f, writable=.true.)
    call h5_open_group(f, 'g', g)
    call h5_open_series(g, 'si', si)
    call check_true('reopened series length and type', si%n == 13 .and. si%is_int)
    call h5_append(si, 14_ik)
    call h5_close_series(si)
    call h5_read_dataset(g, 'si', i1)
    call check_true('appended after reopening', size(i1) == 14 .and. i1(14) == 14)
    call h5_close_group(g)
    call h5_close_file(f)

    ! overwrite=.true. replaces the file
    call h5_create_file(path, .true., f)
    call check_true('overwritten file is empty', .not. h5_exists(f, 'g'))
    call h5_close_file(f)
  end subroutine low_level

  subroutine results_file()
    type(results_h5_t) :: r
    character(len=:), allocatable :: path, s
    character(len=:), allocatable :: names(:)
    character(len=24), parameter :: cols(4) = [character(len=24) :: 'step', 'time', 'contacts', 'residual_natural_map']
    integer(hid_t) :: f, g
    integer(ik) :: n, num(3)
    integer(ik), allocatable :: i1(:)
    real(wp), allocatable :: r1(:), r2(:, :)
    real(wp) :: x, ref(3, 3), XX(3, 3), VV(3, 3), nrm(2, 2), pt(2, 2), rea(2, 2), vel(2, 2), gp(2), intl(4, 2)
    integer :: k

    path = dir//'/fracas.h5'
    call remove_file(path)
    call results_open(r, path, .false., '/some/case', 1.0e-3_wp, 0.5_wp, cols, version='0.1.0')
    num = [1, 2, 5]
    ref = reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.1_wp, 2.0_wp, 1.0_wp, 0.2_wp], [3, 3])
    call results_write_bodies(r, num, [1.0_wp, 2.0_wp, 3.0_wp], [0.1_wp, 0.2_wp, 0.3_wp], &
                              [0.5_wp, 0.5_wp, 0.25_wp], ref)
    call results_write_help(r, [character(len=5) :: 'noctc', 'stick', 'slifw'], &
                            [character(len=5) :: 'DKDKx', 'DKJCx'], [character(len=5) :: 'iqsc0', 'IQS_C'])
    do k = 1, 5
      call results_append_step(r, [real(k, wp), 1.0e-3_wp*k, real(2*k, wp), 1.0e-10_wp/k])
    end do
    XX = ref + 0.01_wp
    VV = -ref
    nrm = reshape([0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp], [2, 2])
    pt = reshape([0.5_wp, 0.0_wp, 1.5_wp, 0.5_wp], [2, 2])
    rea = reshape([0.1_wp, 9.81_wp, 0.0_wp, 4.0_wp], [2, 2])
    vel = reshape([0.0_wp, 0.0_wp, 1.0e-3_wp, -2.0e-3_wp], [2, 2])
    gp = [-1.0e-6_wp, 2.0e-6_wp]
    intl = reshape([(0.1_wp*k, k=1, 8)], [4, 2])
    call results_write_snapshot(r, 3_ik, 3.0e-3_wp, XX, VV, [1_ik, 2_ik], [1_ik, 2_ik], [2_ik, 5_ik], &
                                [1_ik, 1_ik], [1_ik, 1_ik], [2_ik, 3_ik], [1_ik, 2_ik], nrm, pt, rea, vel, gp, &
                                internals=intl)
    call results_write_snapshot(r, 5_ik, 5.0e-3_wp, XX, VV, [integer(ik) ::], [integer(ik) ::], &
                                [integer(ik) ::], [integer(ik) ::], [integer(ik) ::], [integer(ik) ::], &
                                [integer(ik) ::], nrm(:, 1:0), pt(:, 1:0), rea(:, 1:0), vel(:, 1:0), gp(1:0))
    call results_close(r)
    call results_close(r)   ! a second close does nothing

    call h5_open_file(path, f)
    call h5_read_attr(f, 'program', s)
    call check_true('results: program', s == 'fracas')
    call h5_read_attr(f, 'version', s)
    call check_true('results: version', s == '0.1.0')
    call h5_read_attr(f, 'case_dir', s)
    call check_true('results: case_dir', s == '/some/case')
    call h5_read_attr(f, 'complete', n)
    call check_true('results: complete = 1 after close', n == 1)
    call h5_read_attr(f, 'time_step', x)
    call check_close('results: time_step', x, 1.0e-3_wp, 0.0_wp)
    call h5_read_attr(f, 'theta', x)
    call check_close('results: theta', x, 0.5_wp, 0.0_wp)

    call h5_read_dataset(f, 'bodies/number', i1)
    call check_true('bodies/number', all(i1 == num))
    call h5_read_dataset(f, 'bodies/reference', r2)
    call check_close('bodies/reference', maxval(abs(r2 - ref)), 0.0_wp, 0.0_wp)
    call h5_read_dataset(f, 'bodies/radius', r1)
    call check_close('bodies/radius', r1(3), 0.25_wp, 0.0_wp)
    call h5_open_group(f, 'bodies', g)
    call h5_read_attr(g, 'model', s)
    call check_true('bodies model', s == 'RBDY2')
    call h5_close_group(g)

    call h5_read_dataset(f, 'series/time', r1)
    call check_true('series/time length', size(r1) == 5)
    call check_close('series/time values', r1(5), 5.0e-3_wp, 0.0_wp)
    call h5_read_dataset(f, 'series/residual_natural_map', r1)
    call check_close('series/residual values', r1(4), 0.25e-10_wp, 0.0_wp)
    call h5_open_group(f, 'series', g)
    call h5_read_attr(g, 'columns', s)
    call check_true('series columns attribute', s == 'step,time,contacts,residual_natural_map')
    call h5_close_group(g)

    call h5_read_dataset(f, 'help/status', names)
    call check_true('help/status', size(names) == 3 .and. names(2) == 'stick')
    call h5_read_dataset(f, 'help/law', names)
    call check_true('help/law', names(2) == 'IQS_C')
    call h5_read_dataset(f, 'help/series_columns', names)
    call check_true('help/series_columns', size(names) == 4 .and. names(4) == 'residual_natural_map')

    call h5_read_dataset(f, 'snapshot_index/step', i1)
    call check_true('snapshot_index/step', all(i1 == [3, 5]))
    call h5_open_group(f, 'snapshots', g)
    call h5_read_attr(g, 'count', n)
    call check_true('snapshots count', n == 2)
    call h5_close_group(g)
    call h5_open_group(f, 'snapshots/000001', g)
    call h5_read_attr(g, 'step', n)
    call check_true('snapshot 1 step', n == 3)
    call h5_read_attr(g, 'time', x)
    call check_close('snapshot 1 time', x, 3.0e-3_wp, 0.0_wp)
    call h5_read_dataset(g, 'bodies/X', r2)
    call check_close('snapshot X', maxval(abs(r2 - XX)), 0.0_wp, 0.0_wp)
    call h5_read_dataset(g, 'contacts/reaction', r2)
    call check_close('snapshot reaction', maxval(abs(r2 - rea)), 0.0_wp, 0.0_wp)
    call h5_read_dataset(g, 'contacts/internals', r2)
    call check_true('snapshot internals shape', all(shape(r2) == [4, 2]))
    call check_close('snapshot internals', maxval(abs(r2 - intl)), 0.0_wp, 0.0_wp)
    call h5_read_dataset(g, 'contacts/an_body', i1)
    call check_true('snapshot an_body', all(i1 == [2, 5]))
    call h5_read_dataset(g, 'contacts/status', i1)
    call check_true('snapshot status', all(i1 == [2, 3]))
    call h5_close_group(g)
    call h5_read_dataset(f, 'snapshots/000002/contacts/gap', r1)
    call check_true('snapshot without contacts', size(r1) == 0)
    call check_true('snapshot without internals', .not. h5_exists(f, 'snapshots/000002/contacts/internals'))
    call check_true('results: no ids left open', h5_open_objects(f) == 0)
    call h5_close_file(f)
  end subroutine results_file

  !> One snapshot of 1e5 contacts: one HDF5 write per array, must be fast.
  subroutine big_snapshot()
    integer, parameter :: nc = 100000, nb = 20000
    type(results_h5_t) :: r
    real(wp), allocatable :: X(:, :), V(:, :), nrm(:, :), pt(:, :), rea(:, :), vel(:, :), gp(:), intl(:, :)
    real(wp), allocatable :: back(:, :)
    integer(ik), allocatable :: ia(:), ib(:)
    integer(i8) :: t0, t1, rate
    real(wp) :: secs
    integer(hid_t) :: f
    integer :: k
    character(len=:), allocatable :: path
    allocate (X(3, nb), V(3, nb), nrm(2, nc), pt(2, nc), rea(2, nc), vel(2, nc), gp(nc), intl(5, nc), &
              ia(nc), ib(nc))
    do k = 1, nb
      X(:, k) = [real(k, wp), 2.0_wp*k, 0.0_wp]
    end do
    V = 0.5_wp*X
    do k = 1, nc
      nrm(:, k) = [cos(1.0e-4_wp*k), sin(1.0e-4_wp*k)]
      ia(k) = mod(k, nb) + 1
      ib(k) = mod(7*k, nb) + 1
    end do
    pt = 2.0_wp*nrm
    rea = 3.0_wp*nrm
    vel = -nrm
    gp = 1.0e-7_wp
    intl = 0.25_wp
    path = dir//'/big.h5'
    call results_open(r, path, .true., '.', 1.0e-4_wp, 0.5_wp, [character(len=4) :: 'step', 'time'])
    call system_clock(t0, rate)
    call results_write_snapshot(r, 1_ik, 1.0e-4_wp, X, V, ia, ia, ib, ia, ib, ia, ib, nrm, pt, rea, vel, gp, &
                                internals=intl)
    call system_clock(t1)
    secs = real(t1 - t0, wp)/real(rate, wp)
    write (*, '(a,f8.3,a)') 'INFO snapshot of 1e5 contacts written in ', secs, ' s'
    call check_true('snapshot of 1e5 contacts in < 2 s', secs < 2.0_wp)
    call system_clock(t0)
    do k = 1, 10000
      call results_append_step(r, [real(k, wp), 1.0e-4_wp*k])
    end do
    call system_clock(t1)
    secs = real(t1 - t0, wp)/real(rate, wp)
    write (*, '(a,f8.3,a)') 'INFO 1e4 series rows appended in ', secs, ' s'
    call check_true('1e4 series rows in < 5 s', secs < 5.0_wp)
    call results_close(r)
    call h5_open_file(path, f)
    call h5_read_dataset(f, 'snapshots/000001/contacts/normal', back)
    call check_close('big snapshot normal read back', maxval(abs(back - nrm)), 0.0_wp, 0.0_wp)
    call h5_close_file(f)
    call remove_file(path)
  end subroutine big_snapshot

end program test_h5
