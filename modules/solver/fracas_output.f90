!> Everything a run writes: DISPLAY/*.vtu + DISPLAY/fracas.pvd (ParaView),
!> OUTBOX/fracas.h5 (states, contacts, solver and energy series) and
!> OUTBOX/DOF.OUT.n + Vloc_Rloc.OUT.n in LMGC90's layout. Converts the scene
!> to the plain arrays and records the io writers take.
module fracas_output
  use fracas_kinds, only: wp, ik
  use fracas_errors, only: fatal
  use fracas_ids, only: inter_names, status_names, n_inter
  use fracas_files, only: make_dir, file_exists
  use fracas_deck, only: dof_record_t, contact_record_t
  use fracas_vtk, only: vtk_field, write_vtu, pvd_t, pvd_init, pvd_add, vtk_poly_line, vtk_vertex
  use fracas_contactors, only: tactor_center, tactor_vertices, tactor_kind_name, tk_polyg, tk_jonc
  use fracas_scene, only: scene_t, step_report_t
  use fracas_version, only: version_string
  use fracas_contact_laws, only: law_czm
  use fracas_write_outbox, only: write_dof_file, write_vloc_rloc_file
  use fracas_results_h5, only: results_h5_t, results_open, results_write_bodies, results_write_help, &
                               results_write_snapshot, results_append_step, results_close
  implicit none
  private
  public :: output_t, output_open, output_vtk, output_outbox, output_snapshot, output_series, &
            output_close, series_names

  integer, parameter :: n_series = 23
  character(len=24), parameter :: series_names(n_series) = [character(len=24) :: &
    'step', 'time', 'contacts', 'active_contacts', 'sweeps', 'converged', 'residual_natural_map', &
    'residual_onepq', 'quad_dv', 'maxm_dv', 'mean_dvor', 'kinetic_energy', 'work_gravity', &
    'work_forces', 'work_supports', 'dissipated', 'cohesive_energy', 'damage_dissipated', 'balance_error', &
    'mean_overlap', 'max_overlap', 'solve_time', 'step_time']
  integer, parameter :: n_outline = 24   !< segments of a circle outline

  type :: output_t
    character(len=:), allocatable :: outbox, display
    type(pvd_t) :: pvd
    integer :: n_vtk = 0, n_out = 0
    type(results_h5_t) :: h5
    logical :: h5_open = .false.
  end type output_t

contains

  !> Create OUTBOX/ and DISPLAY/ under out_dir and open OUTBOX/fracas.h5.
  !> Existing results are kept unless overwrite is set.
  subroutine output_open(o, sc, out_dir, case_dir, overwrite, with_vtk, with_h5)
    type(output_t), intent(out) :: o
    type(scene_t), intent(in) :: sc
    character(len=*), intent(in) :: out_dir, case_dir
    logical, intent(in) :: overwrite, with_vtk, with_h5
    character(len=5), allocatable :: law_names(:)
    integer :: k
    o%outbox = trim(out_dir)//'/OUTBOX'
    o%display = trim(out_dir)//'/DISPLAY'
    if (.not. overwrite) then
      if (file_exists(o%outbox//'/fracas.h5') .or. file_exists(o%outbox//'/DOF.OUT.1') .or. &
          file_exists(o%display//'/fracas.pvd')) call fatal('results already exist in '// &
          trim(out_dir)//' (OUTBOX/ or DISPLAY/): pass --overwrite to replace them, or --output DIR')
    end if
    call make_dir(o%outbox, parents=.true.)
    if (with_vtk) then
      call make_dir(o%display, parents=.true.)
      call pvd_init(o%pvd, o%display//'/fracas.pvd')
    end if
    if (with_h5) then
      call results_open(o%h5, o%outbox//'/fracas.h5', overwrite, case_dir, sc%h, sc%theta, series_names, &
                        version=version_string)
      o%h5_open = .true.
      call results_write_bodies(o%h5, sc%bodies%number, sc%bodies%mass(1, :), sc%bodies%mass(3, :), &
                                sc%bodies%avrd, sc%bodies%ref)
      allocate (law_names(size(sc%laws)))
      do k = 1, size(sc%laws)
        law_names(k) = sc%laws(k)%nickname
      end do
      call results_write_help(o%h5, status_names, inter_names, law_names)
    end if
  end subroutine output_open

  !> DISPLAY/bodies_NNNNNN.vtu (contactor outlines) and contacts_NNNNNN.vtu
  !> (contact points), listed in DISPLAY/fracas.pvd as parts 0 and 1.
  subroutine output_vtk(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    character(len=32) :: bname, cname
    o%n_vtk = o%n_vtk + 1
    write (bname, '(a,i6.6,a)') 'bodies_', o%n_vtk, '.vtu'
    write (cname, '(a,i6.6,a)') 'contacts_', o%n_vtk, '.vtu'
    call write_bodies_vtu(o%display//'/'//trim(bname), sc)
    call write_contacts_vtu(o%display//'/'//trim(cname), sc)
    call pvd_add(o%pvd, sc%time, trim(bname), part=0)
    call pvd_add(o%pvd, sc%time, trim(cname), part=1)
  end subroutine output_vtk

  subroutine write_bodies_vtu(path, sc)
    character(len=*), intent(in) :: path
    type(scene_t), intent(in) :: sc
    real(wp), allocatable :: pts(:, :), vel(:, :), outline(:, :)
    integer(ik), allocatable :: conn(:), offs(:), types(:), body(:), kind(:)
    real(wp), allocatable :: rot(:), spin(:)
    integer :: k, j, np, nt, m
    nt = sc%tactors%n
    ! Sizes first (polygons: vertices + centre + closing point), then the points.
    np = 0
    do k = 1, nt
      if (sc%tactors%kind(k) == tk_polyg) then
        np = np + sc%tactors%vfirst(k + 1) - sc%tactors%vfirst(k) + 2
      else
        np = np + n_outline + 2
      end if
    end do
    allocate (pts(3, np), conn(np), offs(nt), types(nt), body(nt), kind(nt), vel(3, nt), rot(nt), spin(nt))
    np = 0
    do k = 1, nt
      associate (t => sc%tactors, b => sc%bodies)
        outline = tactor_outline(sc, k)
        m = size(outline, 2)
        pts(1:2, np + 1:np + m) = outline
        pts(3, np + 1:np + m) = 0.0_wp
        conn(np + 1:np + m) = [(int(np + j, ik), j=0, m - 1)]
        np = np + m
        offs(k) = int(np, ik)
        types(k) = vtk_poly_line
        body(k) = int(t%body(k), ik)
        kind(k) = int(t%kind(k), ik)
        vel(:, k) = [b%v(1, t%body(k)), b%v(2, t%body(k)), 0.0_wp]
        rot(k) = b%x(3, t%body(k))
        spin(k) = b%v(3, t%body(k))
      end associate
    end do
    call write_vtu(path, pts, conn, offs, types, &
                   cell_fields=[vtk_field('body', body), vtk_field('contactor_kind', kind), &
                                vtk_field('velocity', vel), vtk_field('rotation', rot), vtk_field('spin', spin)], &
                   time=sc%time)
  end subroutine write_bodies_vtu

  !> Outline of contactor k in the current configuration, as a polyline that
  !> starts at the contactor centre (a spoke shows the rotation) and closes.
  function tactor_outline(sc, k) result(p)
    type(scene_t), intent(in) :: sc
    integer, intent(in) :: k
    real(wp), allocatable :: p(:, :), v(:, :)
    real(wp) :: q(3), c(2), ang, s
    integer :: j, nv
    associate (t => sc%tactors, b => sc%bodies)
      q = b%ref(:, t%body(k)) + b%x(:, t%body(k))
      c = tactor_center(t, k, q)
      select case (t%kind(k))
      case (tk_polyg)
        v = tactor_vertices(t, k, q)
        nv = size(v, 2)
        allocate (p(2, nv + 2))
        p(:, 1) = c
        p(:, 2:nv + 1) = v
        p(:, nv + 2) = v(:, 1)
      case (tk_jonc)
        allocate (p(2, n_outline + 2))
        p(:, 1) = c
        do j = 0, n_outline
          s = 2.0_wp * acos(-1.0_wp) * j / n_outline
          p(:, j + 2) = c + stadium_point(t%ax1(k), t%ax2(k), q(3), s)
        end do
      case default
        allocate (p(2, n_outline + 2))
        p(:, 1) = c
        do j = 0, n_outline
          ang = q(3) + 2.0_wp * acos(-1.0_wp) * j / n_outline
          p(:, j + 2) = c + t%radius(k) * [cos(ang), sin(ang)]
        end do
      end select
    end associate
  end function tactor_outline

  !> Point of a stadium outline (half length a1, half thickness a2, axis angle
  !> phi) in the direction of parameter s around it.
  pure function stadium_point(a1, a2, phi, s) result(p)
    real(wp), intent(in) :: a1, a2, phi, s
    real(wp) :: p(2), lx, ly
    lx = a2 * cos(s) + sign(a1, cos(s))
    ly = a2 * sin(s)
    p = [lx * cos(phi) - ly * sin(phi), lx * sin(phi) + ly * cos(phi)]
  end function stadium_point

  subroutine write_contacts_vtu(path, sc)
    character(len=*), intent(in) :: path
    type(scene_t), intent(in) :: sc
    real(wp), allocatable :: pts(:, :), nrm(:, :), reac(:, :), rn(:), rt(:), gap(:), beta(:)
    integer(ik), allocatable :: conn(:), offs(:), types(:), status(:), inter(:), cdb(:), anb(:)
    integer :: k, n
    n = sc%contacts%n
    allocate (pts(3, n), nrm(3, n), reac(3, n), rn(n), rt(n), gap(n), beta(n), conn(n), offs(n), types(n), &
              status(n), inter(n), cdb(n), anb(n))
    associate (c => sc%contacts)
      do k = 1, n
        pts(:, k) = [c%point(:, k), 0.0_wp]
        nrm(:, k) = [c%normal(:, k), 0.0_wp]
        rt(k) = c%r(1, k) / sc%h
        rn(k) = c%r(2, k) / sc%h
        reac(:, k) = [rt(k) * c%normal(2, k) + rn(k) * c%normal(1, k), &
                      -rt(k) * c%normal(1, k) + rn(k) * c%normal(2, k), 0.0_wp]
        gap(k) = c%gap(k) + sc%h * c%u(2, k)
        beta(k) = 0.0_wp
        if (sc%laws(c%law(k))%kind == law_czm) beta(k) = c%internals(4, k)
        conn(k) = int(k - 1, ik)
        offs(k) = int(k, ik)
        types(k) = vtk_vertex
        status(k) = int(c%status(k), ik)
        inter(k) = int(c%inter(k), ik)
        cdb(k) = int(c%cdb(k), ik)
        anb(k) = int(c%anb(k), ik)
      end do
    end associate
    call write_vtu(path, pts, conn, offs, types, &
                   cell_fields=[vtk_field('normal', nrm), vtk_field('reaction', reac), vtk_field('rn', rn), &
                                vtk_field('rt', rt), vtk_field('gap', gap), vtk_field('status', status), &
                                vtk_field('inter', inter), vtk_field('cd_body', cdb), vtk_field('an_body', anb), &
                                vtk_field('beta', beta), vtk_field('broken', broken_flags(sc))], &
                   time=sc%time)
  end subroutine write_contacts_vtu

  !> OUTBOX/DOF.OUT.n and OUTBOX/Vloc_Rloc.OUT.n (n counts the writes).
  subroutine output_outbox(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    type(dof_record_t), allocatable :: dofs(:)
    type(contact_record_t), allocatable :: recs(:)
    character(len=16) :: num
    integer :: k, it, m, pos
    integer :: per_type(n_inter)
    o%n_out = o%n_out + 1
    write (num, '(i0)') o%n_out
    allocate (dofs(sc%bodies%n))
    do k = 1, sc%bodies%n
      dofs(k)%body = sc%bodies%number(k)
      dofs(k)%x = sc%bodies%x(:, k)
      dofs(k)%v = sc%bodies%v(:, k)
    end do
    call write_dof_file(o%outbox//'/DOF.OUT.'//trim(num), sc%step, sc%time, dofs)
    ! LMGC90 lists interactions type by type, numbered within their type.
    allocate (recs(sc%contacts%n))
    per_type = 0
    m = 0
    associate (c => sc%contacts, t => sc%tactors)
      do it = 1, n_inter
        do k = 1, c%n
          if (c%inter(k) /= it) cycle
          m = m + 1
          per_type(it) = per_type(it) + 1
          pos = m
          recs(pos)%inter = inter_names(it)
          recs(pos)%number = per_type(it)
          recs(pos)%cdtac = tactor_kind_name(t%kind(c%cd(k)))
          recs(pos)%antac = tactor_kind_name(t%kind(c%an(k)))
          recs(pos)%cdver = c%cdver(k)
          recs(pos)%anseg = c%anseg(k)
          recs(pos)%icdbdy = sc%bodies%number(c%cdb(k))
          recs(pos)%ianbdy = sc%bodies%number(c%anb(k))
          recs(pos)%icdtac = t%rank(c%cd(k))
          recs(pos)%iantac = t%rank(c%an(k))
          recs(pos)%behav = sc%laws(c%law(k))%nickname
          recs(pos)%status = status_names(c%status(k))
          recs(pos)%iadj = t%kind_index(c%an(k))
          recs(pos)%rlt = c%r(1, k) / sc%h
          recs(pos)%rln = c%r(2, k) / sc%h
          recs(pos)%vlt = c%u(1, k)
          recs(pos)%vln = c%u(2, k)
          recs(pos)%gap = c%gap(k) + sc%h * c%u(2, k)
          recs(pos)%normal = c%normal(:, k)
          recs(pos)%coor = c%point(:, k)
          recs(pos)%has_geometry = .true.
          if (sc%laws(c%law(k))%kind == law_czm) then
            recs(pos)%internals = c%internals(:, k)
          else
            allocate (recs(pos)%internals(0))
          end if
        end do
      end do
    end associate
    call write_vloc_rloc_file(o%outbox//'/Vloc_Rloc.OUT.'//trim(num), sc%step, sc%time, recs)
  end subroutine output_outbox

  !> One snapshot of bodies and contacts in OUTBOX/fracas.h5.
  subroutine output_snapshot(o, sc)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    integer :: n
    real(wp), allocatable :: gap_end(:)
    if (.not. o%h5_open) return
    n = sc%contacts%n
    associate (c => sc%contacts, t => sc%tactors)
      gap_end = c%gap(1:n) + sc%h * c%u(2, 1:n)
      if (any(sc%laws%kind == law_czm)) then
        call results_write_snapshot(o%h5, sc%step, sc%time, sc%bodies%x, sc%bodies%v, c%inter(1:n), &
          sc%bodies%number(c%cdb(1:n)), sc%bodies%number(c%anb(1:n)), t%rank(c%cd(1:n)), t%rank(c%an(1:n)), &
          c%status(1:n), c%law(1:n), c%normal(:, 1:n), c%point(:, 1:n), c%r(:, 1:n) / sc%h, c%u(:, 1:n), gap_end, &
          internals=c%internals(:, 1:n), broken=broken_flags(sc))
      else
        call results_write_snapshot(o%h5, sc%step, sc%time, sc%bodies%x, sc%bodies%v, c%inter(1:n), &
          sc%bodies%number(c%cdb(1:n)), sc%bodies%number(c%anb(1:n)), t%rank(c%cd(1:n)), t%rank(c%an(1:n)), &
          c%status(1:n), c%law(1:n), c%normal(:, 1:n), c%point(:, 1:n), c%r(:, 1:n) / sc%h, c%u(:, 1:n), gap_end)
      end if
    end associate
  end subroutine output_snapshot

  !> One row of the per-step series (same order as series_names).
  subroutine output_series(o, sc, rep)
    type(output_t), intent(inout) :: o
    type(scene_t), intent(in) :: sc
    type(step_report_t), intent(in) :: rep
    real(wp) :: balance
    if (.not. o%h5_open) return
    balance = rep%kinetic + sc%cohesive_energy - sc%kinetic0 - &
              (sc%work_gravity + sc%work_forces + sc%work_supports - sc%dissipated)
    call results_append_step(o%h5, [real(sc%step, wp), sc%time, real(rep%contacts, wp), &
      real(rep%nlgs%nactive, wp), real(rep%nlgs%sweeps, wp), merge(1.0_wp, 0.0_wp, rep%nlgs%converged), &
      rep%nlgs%residual, rep%nlgs%residual_onepq, rep%nlgs%quad_dv, rep%nlgs%maxm_dv, rep%nlgs%mean_dvor, &
      rep%kinetic, sc%work_gravity, sc%work_forces, sc%work_supports, sc%dissipated, sc%cohesive_energy, &
      sc%damage_dissipated, balance, &
      rep%mean_overlap, rep%max_overlap, rep%solve_seconds, rep%step_seconds])
  end subroutine output_series

  !> 1 for the contacts of a cohesive law whose interface is broken (beta = 0).
  function broken_flags(sc) result(f)
    type(scene_t), intent(in) :: sc
    integer(ik), allocatable :: f(:)
    integer :: k
    allocate (f(sc%contacts%n))
    do k = 1, sc%contacts%n
      f(k) = 0
      if (sc%laws(sc%contacts%law(k))%kind /= law_czm) cycle
      if (sc%contacts%internals(4, k) <= 0.0_wp) f(k) = 1
    end do
  end function broken_flags

  !> Close the results; complete = .false. for a run stopped on an error
  !> (fracas.h5 then keeps complete = 0).
  subroutine output_close(o, complete)
    type(output_t), intent(inout) :: o
    logical, intent(in), optional :: complete
    if (o%h5_open) call results_close(o%h5, complete)
    o%h5_open = .false.
  end subroutine output_close
end module fracas_output
