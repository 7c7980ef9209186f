!> Helper for tools/tests/test_output_files.py (not a unit test): writes a small
!> sample of every Fracas output file into a directory, for h5py and an XML
!> parser to check against doc/output_layout.md.
!>
!>   make_sample_results OUTDIR [--overwrite] [--incomplete]
!>
!> OUTDIR/fracas.h5           results file (3 bodies, 4 series rows, 2 snapshots)
!> OUTDIR/bodies_000001.vtu   3 disks as 16-gon outlines (base64 binary)
!> OUTDIR/contacts_000001.vtu 2 contact points as vertices (ASCII)
!> OUTDIR/fracas.pvd          the collection listing both at one time
!> --overwrite  replace an existing fracas.h5 (without it, an existing file is fatal)
!> --incomplete leave fracas.h5 without results_close (complete stays 0)
program make_sample_results
  use fracas_kinds, only: wp, ik
  use fracas_errors, only: fatal
  use fracas_files, only: make_dir
  use fracas_ids, only: status_names, inter_names
  use fracas_results_h5, only: results_h5_t, results_open, results_write_bodies, results_write_help, &
                               results_write_snapshot, results_append_step, results_flush, results_close
  use fracas_vtk, only: vtk_field, write_vtu, pvd_t, pvd_init, pvd_add, vtk_polygon, vtk_vertex
  implicit none

  integer, parameter :: nb = 3, nc = 2, nseg = 16
  character(len=4096) :: arg
  character(len=:), allocatable :: dir
  logical :: overwrite, incomplete
  type(results_h5_t) :: r
  type(pvd_t) :: pvd
  character(len=20), parameter :: cols(6) = [character(len=20) :: 'step', 'time', 'contacts', 'sweeps', &
                                              'converged', 'kinetic_energy']
  real(wp) :: ref(3, nb), X(3, nb), V(3, nb), radius(nb), mass(nb), inertia(nb)
  real(wp) :: normal(2, nc), point(2, nc), reaction(2, nc), velocity(2, nc), gap(nc), internals(3, nc)
  real(wp) :: pts(3, nb*nseg), cvel(3, nb), rot(nb), spin(nb), rglob(3, nc), pc(3, nc), nglob(3, nc)
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
  call write_vtu(dir//'/bodies_000001.vtu', pts, conn, offs, types, &
                 cell_fields=[vtk_field('velocity', cvel), vtk_field('rotation', rot), vtk_field('spin', spin), &
                              vtk_field('id', ids)], time=4.0e-3_wp)
  do i = 1, nc
    pc(:, i) = [point(1, i), point(2, i), 0.0_wp]
    nglob(:, i) = [normal(1, i), normal(2, i), 0.0_wp]
    ! global reaction = rt t + rn n with t = (n_y, -n_x)
    rglob(:, i) = [reaction(1, i)*normal(2, i) + reaction(2, i)*normal(1, i), &
                   -reaction(1, i)*normal(1, i) + reaction(2, i)*normal(2, i), 0.0_wp]
  end do
  call write_vtu(dir//'/contacts_000001.vtu', pc, [0_ik, 1_ik], [1_ik, 2_ik], [vtk_vertex, vtk_vertex], &
                 cell_fields=[vtk_field('normal', nglob), vtk_field('reaction', rglob), &
                              vtk_field('rn', reaction(2, :)), vtk_field('rt', reaction(1, :)), &
                              vtk_field('status', [2_ik, 3_ik]), vtk_field('gap', gap)], &
                 ascii=.true., time=4.0e-3_wp)
  call pvd_init(pvd, dir//'/fracas.pvd')
  call pvd_add(pvd, 4.0e-3_wp, 'bodies_000001.vtu', part=0)
  call pvd_add(pvd, 4.0e-3_wp, 'contacts_000001.vtu', part=1)
end program make_sample_results
