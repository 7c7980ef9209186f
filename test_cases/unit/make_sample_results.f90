!> Helper for tools/tests/test_output_files.py (not a unit test): writes a small
!> sample of every Fracas output file into a directory, for h5py and an XML
!> parser to check against doc/output_layout.md.
!>
!>   make_sample_results OUTDIR [--overwrite] [--incomplete]
!>
!> OUTDIR/fracas.h5           results file (3 bodies, 4 series rows, 2 snapshots)
!> OUTDIR/disks_000001.vtu    3 disks as points with a radius (appended, zlib)
!> OUTDIR/shapes_000001.vtu   the same 3 disks as filled 16-gons (appended, raw)
!> OUTDIR/contacts_000001.vtu 2 contact points as vertices (ASCII)
!> OUTDIR/fracas.pvd          the collection listing the three at one time
!> --overwrite  replace an existing fracas.h5 (without it, an existing file is fatal)
!> --incomplete leave fracas.h5 without results_close (complete stays 0)
program make_sample_results
  use fracas_kinds, only: wp, ik
  use fracas_errors, only: fatal
  use fracas_files, only: make_dir
  use fracas_ids, only: status_names, inter_names
  use fracas_results_h5, only: results_h5_t, results_open, results_write_bodies, results_write_help, &
                               results_write_snapshot, results_append_step, results_flush, results_close
  use fracas_vtk, only: vtu_t, vtu_begin, vtu_points, vtu_cells, vtu_vertex_cells, vtu_point_data, vtu_cell_data, &
                        vtu_end, pvd_t, pvd_init, pvd_add, vtk_polygon
  implicit none

  integer, parameter :: nb = 3, nc = 2, nseg = 16
  character(len=4096) :: arg
  character(len=:), allocatable :: dir
  logical :: overwrite, incomplete
  type(results_h5_t) :: r
  type(pvd_t) :: pvd
  type(vtu_t) :: w
  character(len=20), parameter :: cols(6) = [character(len=20) :: 'step', 'time', 'contacts', 'sweeps', &
                                              'converged', 'kinetic_energy']
  real(wp) :: ref(3, nb), X(3, nb), V(3, nb), radius(nb), mass(nb), inertia(nb)
  real(wp) :: normal(2, nc), point(2, nc), reaction(2, nc), velocity(2, nc), gap(nc), internals(3, nc)
  real(wp) :: pts(3, nb*nseg), cvel(3, nb), rot(nb), spin(nb), rglob(3, nc), pc(3, nc), nglob(3, nc), centres(2, nb)
  integer(ik) :: conn(nb*nseg), offs(nb), types(nb), ids(nb)
  integer :: i, k, step

  if (command_argument_count() < 1) call fatal('usage: make_sample_results OUTDIR [--overwrite] [--incomplete]')
  call get_command_argument(1, arg)
  dir = trim(arg)
  overwrite = .false.
  incomplete = .false.
  do i = 2, command_argument_count()
    call get_command_argument(i, arg)
    select case (trim(arg))
    case ('--overwrite')
      overwrite = .true.
    case ('--incomplete')
      incomplete = .true.
    case default
      call fatal('make_sample_results: unknown option '//trim(arg))
    end select
  end do
  call make_dir(dir, parents=.true.)

  ! three disks on a line, the middle one resting on the two others
  ref = reshape([0.0_wp, 0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 1.7_wp, 0.0_wp], [3, nb])
  radius = [1.0_wp, 1.0_wp, 0.9_wp]
  mass = 3.14159_wp*radius**2
  inertia = 0.5_wp*mass*radius**2
  X = 0.0_wp
  X(2, 3) = -0.01_wp
  X(3, :) = [0.0_wp, 0.1_wp, -0.2_wp]
  V = 0.0_wp
  V(2, 3) = -0.5_wp
  V(3, :) = [0.0_wp, 1.0_wp, -2.0_wp]
  normal = reshape([-0.5_wp, 0.8660254_wp, 0.5_wp, 0.8660254_wp], [2, nc])
  point = reshape([0.5_wp, 0.85_wp, 1.5_wp, 0.85_wp], [2, nc])
  reaction = reshape([0.1_wp, 12.0_wp, -0.1_wp, 11.5_wp], [2, nc])
  velocity = reshape([0.0_wp, 0.0_wp, 1.0e-3_wp, -2.0e-3_wp], [2, nc])
  gap = [-1.0e-4_wp, 2.0e-5_wp]
  internals = reshape([1.0_wp, 0.0_wp, 0.5_wp, 1.0_wp, 1.0e-3_wp, 0.25_wp], [3, nc])

  call results_open(r, dir//'/fracas.h5', overwrite, dir, 1.0e-3_wp, 0.5_wp, cols, version='sample')
  call results_write_bodies(r, [1_ik, 2_ik, 3_ik], mass, inertia, radius, ref)
  call results_write_help(r, status_names, inter_names, [character(len=5) :: 'iqsc0', 'IQS_C'])
  do step = 1, 4
    call results_append_step(r, [real(step, wp), 1.0e-3_wp*step, real(nc, wp), real(10*step, wp), &
                                 1.0_wp, 0.5_wp*sum(mass*V(2, :)**2)])
    if (step == 2 .or. step == 4) &
      call results_write_snapshot(r, int(step, ik), 1.0e-3_wp*step, ref + X, V, [1_ik, 1_ik], &
                                  [3_ik, 3_ik], [1_ik, 2_ik], [1_ik, 1_ik], [1_ik, 1_ik], [2_ik, 3_ik], &
                                  [1_ik, 2_ik], normal, point, reaction, velocity, gap, internals=internals)
  end do
  if (incomplete) then
    call results_flush(r)
  else
    call results_close(r)
  end if

  ! DISPLAY-like files: body outlines (VTK_POLYGON) and contact points (VTK_VERTEX)
  do i = 1, nb
    do k = 1, nseg
      pts(:, (i - 1)*nseg + k) = [ref(1, i) + X(1, i) + radius(i)*cos(6.283185307179586_wp*(k - 1)/nseg + X(3, i)), &
                                  ref(2, i) + X(2, i) + radius(i)*sin(6.283185307179586_wp*(k - 1)/nseg + X(3, i)), &
                                  0.0_wp]
      conn((i - 1)*nseg + k) = (i - 1)*nseg + k - 1
    end do
    offs(i) = i*nseg
    types(i) = vtk_polygon
    ids(i) = i
    cvel(:, i) = [V(1, i), V(2, i), 0.0_wp]
    rot(i) = X(3, i)
    spin(i) = V(3, i)
  end do
  centres = ref(1:2, :) + X(1:2, :)
  call vtu_begin(w, dir//'/disks_000001.vtu', nb, nb, time=4.0e-3_wp)
  call vtu_points(w, centres)
  call vtu_vertex_cells(w)
  call vtu_point_data(w, 'radius', radius)
  call vtu_point_data(w, 'body', ids)
  call vtu_point_data(w, 'velocity', cvel)
  call vtu_point_data(w, 'rotation', rot)
  call vtu_point_data(w, 'spin', spin)
  call vtu_end(w)
  call vtu_begin(w, dir//'/shapes_000001.vtu', nb*nseg, nb, time=4.0e-3_wp, encoding='raw')
  call vtu_points(w, pts)
  call vtu_cells(w, conn, offs, types)
  call vtu_cell_data(w, 'body', ids)
  call vtu_cell_data(w, 'velocity', cvel)
  call vtu_cell_data(w, 'rotation', rot)
  call vtu_cell_data(w, 'spin', spin)
  call vtu_end(w)
  do i = 1, nc
    pc(:, i) = [point(1, i), point(2, i), 0.0_wp]
    nglob(:, i) = [normal(1, i), normal(2, i), 0.0_wp]
    ! global reaction = rt t + rn n with t = (n_y, -n_x)
    rglob(:, i) = [reaction(1, i)*normal(2, i) + reaction(2, i)*normal(1, i), &
                   -reaction(1, i)*normal(1, i) + reaction(2, i)*normal(2, i), 0.0_wp]
  end do
  call vtu_begin(w, dir//'/contacts_000001.vtu', nc, nc, time=4.0e-3_wp, encoding='ascii')
  call vtu_points(w, pc)
  call vtu_vertex_cells(w)
  call vtu_point_data(w, 'normal', nglob)
  call vtu_point_data(w, 'reaction', rglob)
  call vtu_point_data(w, 'rn', reaction(2, :))
  call vtu_point_data(w, 'rt', reaction(1, :))
  call vtu_point_data(w, 'status', [2_ik, 3_ik])
  call vtu_point_data(w, 'gap', gap)
  call vtu_end(w)
  call pvd_init(pvd, dir//'/fracas.pvd')
  call pvd_add(pvd, 4.0e-3_wp, 'disks_000001.vtu', part=0)
  call pvd_add(pvd, 4.0e-3_wp, 'shapes_000001.vtu', part=1)
  call pvd_add(pvd, 4.0e-3_wp, 'contacts_000001.vtu', part=2)
end program make_sample_results
