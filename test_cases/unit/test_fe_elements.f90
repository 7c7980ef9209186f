!> Reference elements (fracas_elements) one at a time, on distorted
!> straight-sided geometries. References:
!> - rigid-body modes: ke r = 0 for translations and the infinitesimal rotation
!>   (1e-10 relative to |ke| |r|); ke symmetric; fi = ke u and elastic energy
!>   = u' ke u / 2 for an elastic material (linearity, 1e-12);
!> - mass: total rho * area (shoelace formula), closed forms T3 consistent
!>   rho A/12 (2 on the diagonal, 1 off), Q4 rectangle rho A/36 [4 2 1 2],
!>   T6 HRZ corners 3/57 and mid-sides 16/57 of rho A (Hinton, Rock, Zienkiewicz
!>   1976);
!> - Q4 Gauss-point order: LMGC90's own strains and stresses (GPV.OUT.2 of
!>   ../shared/lmgc90_decks/mesh_block_drop, element 1, step 102) recomputed
!>   from its nodal displacements (DOF.OUT.2), 7 printed digits: 2e-8 absolute
!>   on strains of about 1e-4;
!> - the element tangent against central differences of fi (1e-6 relative)
!>   in J2 plastic states, all kinds, both planes;
!> - plastic work of a uniform uniaxial strain in plane strain: area times
!>   yield0 p + H p^2 / 2 with p = (2 G eps - yield0) / (3 G + H);
!> - Q4P0 (mean dilatation, plane strain): for any displacement the 3D trace
!>   of the strain is the same at every Gauss point and equals the element
!>   mean of div u (so the elastic pressure is one per element), the 3D
!>   deviator is the Q4's; a plain Q4 has a varying trace (guard).
program test_fe_elements
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_bulk, only: bulk_t, bulk_j2, bulk_elastic, plane_strain, plane_stress, gp_size, gp_p, &
                         gp_stress, gp_strain
  use fracas_elements, only: el_t3, el_q4, el_t6, el_q8, el_q4p0, el_kind_of, el_nnodes, el_ngauss, &
                             el_ngauss_gpv, el_edges, el_edge_midnodes, el_vtk_type, el_vtk_order, &
                             el_mass, el_response, el_area, el_gauss_points_xy, el_geometry_ok, &
                             el_max_gauss
  implicit none

  type(bulk_t) :: elastic, steel
  integer :: kind, plane
  character(len=5), parameter :: names(5) = ['T3xxx', 'Q4xxx', 'T6xxx', 'Q8xxx', 'Q4P0x']

  elastic = bulk_t(law=bulk_elastic, density=2000.0_wp, young=1.0e9_wp, poisson=0.3_wp)
  steel = bulk_t(law=bulk_j2, density=7800.0_wp, young=2.0e11_wp, poisson=0.3_wp, yield0=2.0e8_wp, &
                 hardening=2.0e10_wp)

  call catalogue()
  do kind = el_t3, el_q4p0
    call mass_checks(kind)
    do plane = plane_strain, plane_stress
      call stiffness_checks(kind, plane)
      call tangent_fd(kind, plane)
    end do
  end do
  call mass_closed_forms()
  call lmgc90_q4_gauss_order()
  call plastic_work_uniform()
  call mean_dilatation()
  call test_finish()

contains

  !> Distorted straight-sided element of each kind (mid-side nodes at mid-edges).
  subroutine geometry(kind, x)
    integer, intent(in) :: kind
    real(wp), intent(out) :: x(2, 8)
    real(wp), parameter :: tri(2, 3) = reshape([0.0_wp, 0.0_wp, 1.2_wp, 0.1_wp, 0.3_wp, 0.9_wp], [2, 3])
    real(wp), parameter :: quad(2, 4) = reshape([0.0_wp, 0.0_wp, 1.1_wp, 0.1_wp, 1.3_wp, 1.2_wp, -0.1_wp, 0.9_wp], &
                                                [2, 4])
    integer :: nc, i
    x = 0.0_wp
    select case (kind)
    case (el_t3, el_t6)
      nc = 3
      x(:, 1:3) = tri
    case default
      nc = 4
      x(:, 1:4) = quad
    end select
    if (kind == el_t6 .or. kind == el_q8) then
      do i = 1, nc
        x(:, nc + i) = 0.5_wp * (x(:, i) + x(:, modulo(i, nc) + 1))
      end do
    end if
  end subroutine geometry

  pure real(wp) function shoelace(x, nc)
    real(wp), intent(in) :: x(:, :)
    integer, intent(in) :: nc
    integer :: i, j
    shoelace = 0.0_wp
    do i = 1, nc
      j = modulo(i, nc) + 1
      shoelace = shoelace + 0.5_wp * (x(1, i) * x(2, j) - x(1, j) * x(2, i))
    end do
  end function shoelace

  subroutine catalogue()
    integer :: k, e(2, 4), q(4)
    do k = 1, 5
      call check_true('el_kind_of '//names(k), el_kind_of(names(k)) == k)
    end do
    call check_true('el_kind_of unknown -> 0', el_kind_of('H8xxx') == 0 .and. el_kind_of('q4xxx') == 0)
    call check_true('nodes 3 4 6 8 4', all([(el_nnodes(k), k = 1, 5)] == [3, 4, 6, 8, 4]))
    call check_true('Gauss points 1 4 3 9 4', all([(el_ngauss(k), k = 1, 5)] == [1, 4, 3, 9, 4]))
    call check_true('GPV.OUT points 3 4 3 9 4', all([(el_ngauss_gpv(k), k = 1, 5)] == [3, 4, 3, 9, 4]))
    call check_true('VTK types 5 9 22 23 9', all([(el_vtk_type(k), k = 1, 5)] == [5, 9, 22, 23, 9]))
    e = el_edges(el_q8)
    call check_true('Q8 edges (1,2) (2,3) (3,4) (4,1)', all(e == reshape([1, 2, 2, 3, 3, 4, 4, 1], [2, 4])))
    q(1:3) = el_edge_midnodes(el_t6)
    call check_true('T6 mid-side nodes 4 5 6; T3 none', all(q(1:3) == [4, 5, 6]) .and. &
                    all(el_edge_midnodes(el_t3) == 0))
    call check_true('VTK order of Q8 is LMGC90''s', all(el_vtk_order(el_q8) == [1, 2, 3, 4, 5, 6, 7, 8]))
  end subroutine catalogue

  subroutine mass_checks(kind)
    integer, intent(in) :: kind
    real(wp) :: x(2, 8), m(16, 16), area_ref, rho
    integer :: nn, nc, pass, i
    logical :: lump
    character(len=10) :: label
    call geometry(kind, x)
    nn = el_nnodes(kind)
    nc = merge(3, 4, kind == el_t3 .or. kind == el_t6)
    rho = elastic%density
    area_ref = shoelace(x, nc)
    call check_close(names(kind)//' area / shoelace', el_area(kind, x(:, 1:nn)) / area_ref, 1.0_wp, 1.0e-13_wp)
    call check_true(names(kind)//' geometry ok; reversed not ok', el_geometry_ok(kind, x(:, 1:nn)) .and. &
                    .not. el_geometry_ok(kind, x(:, reversed(kind))))
    do pass = 1, 2
      lump = pass == 2
      label = merge('lumped    ', 'consistent', lump)
      call el_mass(kind, x(:, 1:nn), rho, lump, m)
      call check_close(names(kind)//' '//trim(label)//' mass: sum of x-x block / (rho A)', &
                       sum(m(1:2 * nn:2, 1:2 * nn:2)) / (rho * area_ref), 1.0_wp, 1.0e-12_wp)
      call check_close(names(kind)//' '//trim(label)//' mass: x-y coupling', maxval(abs(m(1:2 * nn:2, 2:2 * nn:2))), &
                       0.0_wp, 0.0_wp)
      call check_close(names(kind)//' '//trim(label)//' mass: symmetric', &
                       maxval(abs(m(1:2 * nn, 1:2 * nn) - transpose(m(1:2 * nn, 1:2 * nn)))), 0.0_wp, 0.0_wp)
      if (lump) call check_true(names(kind)//' lumped mass diagonal and positive', &
                                all([(m(i, i) > 0.0_wp, i = 1, 2 * nn)]) .and. &
                                abs(sum(m(1:2 * nn, 1:2 * nn)) - sum([(m(i, i), i = 1, 2 * nn)])) == 0.0_wp)
    end do
  end subroutine mass_checks

  !> Node order that turns the element clockwise.
  function reversed(kind) result(order)
    integer, intent(in) :: kind
    integer, allocatable :: order(:)
    select case (kind)
    case (el_t3)
      order = [1, 3, 2]
    case (el_t6)
      order = [1, 3, 2, 6, 5, 4]
    case (el_q8)
      order = [1, 4, 3, 2, 8, 7, 6, 5]
    case default
      order = [1, 4, 3, 2]
    end select
  end function reversed

  subroutine mass_closed_forms()
    real(wp) :: x(2, 8), m(16, 16), a, ref(4, 4)
    integer :: i, j
    ! T3: rho A / 12 * (1 + delta_ab)
    call geometry(el_t3, x)
    a = shoelace(x, 3)
    call el_mass(el_t3, x(:, 1:3), 1.0_wp, .false., m)
    call check_close('T3 consistent mass / (A/12) diagonal', m(3, 3) / (a / 12.0_wp), 2.0_wp, 1.0e-12_wp)
    call check_close('T3 consistent mass / (A/12) off-diagonal', m(1, 5) / (a / 12.0_wp), 1.0_wp, 1.0e-12_wp)
    call el_mass(el_t3, x(:, 1:3), 1.0_wp, .true., m)
    call check_close('T3 lumped mass / (A/3)', m(4, 4) / (a / 3.0_wp), 1.0_wp, 1.0e-12_wp)
    ! Q4 rectangle 2 x 1: rho A / 36 [4 2 1 2; 2 4 2 1; 1 2 4 2; 2 1 2 4]
    x(:, 1:4) = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
    call el_mass(el_q4, x(:, 1:4), 1.0_wp, .false., m)
    ref = reshape([4, 2, 1, 2, 2, 4, 2, 1, 1, 2, 4, 2, 2, 1, 2, 4], [4, 4]) * (2.0_wp / 36.0_wp)
    call check_close('Q4 rectangle consistent mass against A/36 [4 2 1 2]', &
                     maxval(abs([((m(2 * i, 2 * j) - ref(i, j), i = 1, 4), j = 1, 4)])), 0.0_wp, 1.0e-14_wp)
    call el_mass(el_q4, x(:, 1:4), 1.0_wp, .true., m)
    call check_close('Q4 rectangle lumped mass / (A/4)', m(7, 7) / 0.5_wp, 1.0_wp, 1.0e-14_wp)
    ! T6 HRZ: corners 3/57, mid-sides 16/57 of rho A
    call geometry(el_t6, x)
    a = shoelace(x, 3)
    call el_mass(el_t6, x(:, 1:6), 1.0_wp, .true., m)
    call check_close('T6 HRZ corner mass / (3/57 A)', m(3, 3) / (3.0_wp / 57.0_wp * a), 1.0_wp, 1.0e-12_wp)
    call check_close('T6 HRZ mid-side mass / (16/57 A)', m(12, 12) / (16.0_wp / 57.0_wp * a), 1.0_wp, 1.0e-12_wp)
  end subroutine mass_closed_forms

  subroutine stiffness_checks(kind, plane)
    integer, intent(in) :: kind, plane
    real(wp) :: x(2, 8), u(16), fi(16), ke(16, 16), r(16, 3), gp0(gp_size, 9), gp1(gp_size, 9), ee, pw, kr
    character(len=20) :: label
    integer :: nn, nd, a, mode
    label = names(kind)//merge(' plane strain', ' plane stress', plane == plane_strain)
    call geometry(kind, x)
    nn = el_nnodes(kind)
    nd = 2 * nn
    gp0 = 0.0_wp
    do a = 1, nn
      u(2 * a - 1) = 1.0e-4_wp * sin(1.0_wp + 2.3_wp * a)
      u(2 * a) = 1.0e-4_wp * cos(0.5_wp + 1.7_wp * a)
      r(2 * a - 1:2 * a, 1) = [1.0_wp, 0.0_wp]
      r(2 * a - 1:2 * a, 2) = [0.0_wp, 1.0_wp]
      r(2 * a - 1:2 * a, 3) = [-x(2, a), x(1, a)]
    end do
    call el_response(kind, x(:, 1:nn), u(1:nd), elastic, plane, gp0, gp1, fi, ke, .true., ee, pw)
    kr = 0.0_wp
    do mode = 1, 3
      kr = max(kr, maxval(abs(matmul(ke(1:nd, 1:nd), r(1:nd, mode)))) / &
               (maxval(abs(ke(1:nd, 1:nd))) * maxval(abs(r(1:nd, mode)))))
    end do
    call check_close(trim(label)//': |ke r| / (|ke| |r|), rigid modes', kr, 0.0_wp, 1.0e-10_wp)
    call check_close(trim(label)//': ke symmetric', maxval(abs(ke(1:nd, 1:nd) - transpose(ke(1:nd, 1:nd)))) &
                     / maxval(abs(ke(1:nd, 1:nd))), 0.0_wp, 1.0e-12_wp)
    call check_close(trim(label)//': elastic fi = ke u', maxval(abs(fi(1:nd) - matmul(ke(1:nd, 1:nd), u(1:nd)))) &
                     / maxval(abs(fi(1:nd))), 0.0_wp, 1.0e-12_wp)
    call check_close(trim(label)//': elastic energy / (u''ke u / 2)', &
                     ee / (0.5_wp * dot_product(u(1:nd), matmul(ke(1:nd, 1:nd), u(1:nd)))), 1.0_wp, 1.0e-12_wp)
    call check_close(trim(label)//': elastic plastic work', pw, 0.0_wp, 0.0_wp)
    call check_true(trim(label)//': positive diagonal', all([(ke(a, a) > 0.0_wp, a = 1, nd)]))
  end subroutine stiffness_checks

  !> Element tangent against central differences of fi in plastic states.
  subroutine tangent_fd(kind, plane)
    integer, intent(in) :: kind, plane
    real(wp) :: x(2, 8), u1(16), u2(16), up(16), fi(16), fp(16), fm(16), ke(16, 16), dum(1, 1)
    real(wp) :: gp0(gp_size, 9), gp1(gp_size, 9), gp2(gp_size, 9), gpx(gp_size, 9), ee, pw, h, err
    character(len=20) :: label
    integer :: nn, nd, ng, a, j
    label = names(kind)//merge(' plane strain', ' plane stress', plane == plane_strain)
    call geometry(kind, x)
    nn = el_nnodes(kind)
    nd = 2 * nn
    ng = el_ngauss(kind)
    ! first step: stretch and shear past yield; second step: a different direction
    do a = 1, nn
      u1(2 * a - 1) = 4.0e-3_wp * x(1, a) + 2.0e-3_wp * x(2, a) + 2.0e-4_wp * sin(3.0_wp * a)
      u1(2 * a) = -1.0e-3_wp * x(2, a) + 2.0e-4_wp * cos(2.0_wp * a)
      u2(2 * a - 1) = u1(2 * a - 1) + 1.0e-3_wp * x(1, a) - 3.0e-3_wp * x(2, a)
      u2(2 * a) = u1(2 * a) + 2.0e-3_wp * x(1, a) + 1.0e-4_wp * sin(5.0_wp * a)
    end do
    gp0 = 0.0_wp
    call el_response(kind, x(:, 1:nn), u1(1:nd), steel, plane, gp0, gp1, fi, dum, .false., ee, pw)
    call check_true(trim(label)//': step 1 plastic at every Gauss point', all(gp1(gp_p, 1:ng) > 1.0e-4_wp))
    call el_response(kind, x(:, 1:nn), u2(1:nd), steel, plane, gp1, gp2, fi, ke, .true., ee, pw)
    call check_true(trim(label)//': step 2 plastic at every Gauss point', &
                    all(gp2(gp_p, 1:ng) > gp1(gp_p, 1:ng) + 1.0e-4_wp))
    call check_true(trim(label)//': plastic work > 0', pw > 0.0_wp)
    err = 0.0_wp
    h = 1.0e-6_wp * maxval(abs(u2(1:nd)))
    do j = 1, nd
      up = u2
      up(j) = u2(j) + h
      call el_response(kind, x(:, 1:nn), up(1:nd), steel, plane, gp1, gpx, fp, dum, .false., ee, pw)
      up(j) = u2(j) - h
      call el_response(kind, x(:, 1:nn), up(1:nd), steel, plane, gp1, gpx, fm, dum, .false., ee, pw)
      err = max(err, maxval(abs((fp(1:nd) - fm(1:nd)) / (2.0_wp * h) - ke(1:nd, j))))
    end do
    call check_close(trim(label)//': J2 element tangent against central differences of fi', &
                     err / maxval(abs(ke(1:nd, 1:nd))), 0.0_wp, 1.0e-6_wp)
  end subroutine tangent_fd

  !> LMGC90 mesh_block_drop, element 1 (nodes 1 6 7 2), step 102 (GPV.OUT.2).
  subroutine lmgc90_q4_gauss_order()
    real(wp), parameter :: x(2, 4) = reshape([0.0_wp, 5.0e-4_wp, 2.5e-2_wp, 5.0e-4_wp, 2.5e-2_wp, 2.55e-2_wp, &
                                              0.0_wp, 2.55e-2_wp], [2, 4])
    real(wp), parameter :: u(8) = [0.5037548e-3_wp, -0.5000000e-3_wp, 0.5042452e-3_wp, -0.5000000e-3_wp, &
                                   0.5060098e-3_wp, -0.5026490e-3_wp, 0.5051402e-3_wp, -0.5017835e-3_wp]
    ! strain (xx, yy, gamma) and stress (xx, yy, xy, zz) per Gauss point as printed
    real(wp), parameter :: eps_ref(3, 4) = reshape([ &
      0.2282157e-04_wp, -0.7865516e-04_wp, 0.5130651e-04_wp, &
      0.2282157e-04_wp, -0.9864498e-04_wp, 0.6006476e-04_wp, &
      0.3157982e-04_wp, -0.7865516e-04_wp, 0.3131669e-04_wp, &
      0.3157982e-04_wp, -0.9864498e-04_wp, 0.4007494e-04_wp], [3, 4])
    real(wp), parameter :: sig_ref(4, 4) = reshape([ &
      -0.1465664e+05_wp, -0.9271565e+05_wp, 0.1973327e+05_wp, -0.3221169e+05_wp, &
      -0.2618923e+05_wp, -0.1196250e+06_wp, 0.2310183e+05_wp, -0.4374428e+05_wp, &
      -0.2866684e+04_wp, -0.8766282e+05_wp, 0.1204488e+05_wp, -0.2715885e+05_wp, &
      -0.1439927e+05_wp, -0.1145722e+06_wp, 0.1541344e+05_wp, -0.3869144e+05_wp], [4, 4])
    real(wp) :: gp0(gp_size, 4), gp1(gp_size, 4), fi(8), dum(1, 1), ee, pw, xy(2, el_max_gauss), a
    gp0 = 0.0_wp
    call el_response(el_q4, x, u, elastic, plane_strain, gp0, gp1, fi, dum, .false., ee, pw)
    call check_close('LMGC90 Q4 Gauss order: max |strain - GPV.OUT| (7 digits of DOF.OUT)', &
                     maxval(abs(gp1(gp_strain:gp_strain + 2, :) - eps_ref)), 0.0_wp, 2.0e-8_wp)
    ! stresses from LMGC90's own strains: Hooke in plane strain, 7 digits
    call check_close('LMGC90 Q4 stresses: max |sigma - GPV.OUT| / max |sigma| (E 1e9, nu 0.3)', &
                     maxval(abs(gp1(gp_stress:gp_stress + 3, :) - sig_ref)) / maxval(abs(sig_ref)), 0.0_wp, 2.0e-4_wp)
    call check_true('LMGC90 Q4 strain zz = 0', all(gp1(gp_strain + 3, :) == 0.0_wp))
    call el_gauss_points_xy(el_q4, x, xy)
    a = 1.0_wp / sqrt(3.0_wp)
    call check_close('Q4 Gauss point 2 at (+a, -a): x', xy(1, 2), 0.0125_wp * (1.0_wp + a), 1.0e-15_wp)
    call check_close('Q4 Gauss point 3 at (-a, +a): y', xy(2, 3), 5.0e-4_wp + 0.0125_wp * (1.0_wp + a), 1.0e-15_wp)
  end subroutine lmgc90_q4_gauss_order

  !> Uniform uniaxial strain eps in plane strain on every kind: plastic work =
  !> A (yield0 p + H p^2 / 2), p = (2 G eps - yield0) / (3 G + H).
  subroutine plastic_work_uniform()
    real(wp) :: x(2, 8), u(16), fi(16), dum(1, 1), gp0(gp_size, 9), gp1(gp_size, 9), ee, pw, g, eps, p
    integer :: k, nn, a
    g = steel%young / (2.0_wp * (1.0_wp + steel%poisson))
    eps = 3.0e-3_wp
    p = (2.0_wp * g * eps - steel%yield0) / (3.0_wp * g + steel%hardening)
    do k = el_t3, el_q4p0
      call geometry(k, x)
      nn = el_nnodes(k)
      do a = 1, nn
        u(2 * a - 1:2 * a) = [eps * x(1, a), 0.0_wp]
      end do
      gp0 = 0.0_wp
      call el_response(k, x(:, 1:nn), u(1:2 * nn), steel, plane_strain, gp0, gp1, fi, dum, .false., ee, pw)
      call check_close(names(k)//' uniform strain: plastic work / (A (s0 p + H p^2/2))', &
                       pw / (el_area(k, x(:, 1:nn)) * (steel%yield0 * p + 0.5_wp * steel%hardening * p**2)), &
                       1.0_wp, 1.0e-12_wp)
    end do
  end subroutine plastic_work_uniform
  subroutine mean_dilatation()
    real(wp) :: x(2, 8), u(8), fi(8), dum(1, 1), gp0(gp_size, 4), gb(gp_size, 4), gq(gp_size, 4), ee, pw
    real(wp) :: tr_bar(4), tr_q4(4), mean_div, dev_err, area
    integer :: a, g
    call geometry(el_q4, x)
    do a = 1, 4
      u(2 * a - 1) = 1.0e-4_wp * sin(1.0_wp + 2.3_wp * a)
      u(2 * a) = 1.0e-4_wp * cos(0.5_wp + 1.7_wp * a)
    end do
    gp0 = 0.0_wp
    call el_response(el_q4p0, x(:, 1:4), u, elastic, plane_strain, gp0, gb, fi, dum, .false., ee, pw)
    call el_response(el_q4, x(:, 1:4), u, elastic, plane_strain, gp0, gq, fi, dum, .false., ee, pw)
    do g = 1, 4
      tr_bar(g) = gb(gp_strain, g) + gb(gp_strain + 1, g) + gb(gp_strain + 3, g)
      tr_q4(g) = gq(gp_strain, g) + gq(gp_strain + 1, g)
    end do
    ! element mean of div u = area-weighted mean of the Q4 traces (2x2 rule exact)
    mean_div = 0.0_wp
    area = 0.0_wp
    do g = 1, 4
      mean_div = mean_div + q4_det(x, g) * tr_q4(g)
      area = area + q4_det(x, g)
    end do
    mean_div = mean_div / area
    call check_close('Q4P0: trace at every Gauss point / element mean of div u', &
                     maxval(abs(tr_bar - mean_div)) / abs(mean_div), 0.0_wp, 1.0e-12_wp)
    dev_err = 0.0_wp
    do g = 1, 4
      dev_err = max(dev_err, abs((gb(gp_strain, g) - tr_bar(g) / 3.0_wp) - (gq(gp_strain, g) - tr_q4(g) / 3.0_wp)), &
                    abs((gb(gp_strain + 3, g) - tr_bar(g) / 3.0_wp) - (-tr_q4(g) / 3.0_wp)), &
                    abs(gb(gp_strain + 2, g) - gq(gp_strain + 2, g)))
    end do
    call check_close('Q4P0: 3D strain deviator equals the Q4''s', dev_err / maxval(abs(tr_q4)), 0.0_wp, 1.0e-12_wp)
    call check_true('Q4 guard: the plain Q4 trace varies between Gauss points', &
                    maxval(tr_q4) - minval(tr_q4) > 1.0e-3_wp * maxval(abs(tr_q4)))
  end subroutine mean_dilatation

  !> Jacobian of a Q4 at its Gauss point g (LMGC90 order; weights are 1),
  !> written out here independently of fracas_elements.
  real(wp) function q4_det(x, g)
    real(wp), intent(in) :: x(2, 8)
    integer, intent(in) :: g
    real(wp), parameter :: sx(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp], sy(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
    real(wp) :: xi, eta, jac(2, 2)
    integer :: a
    xi = merge(-1.0_wp, 1.0_wp, mod(g, 2) == 1) / sqrt(3.0_wp)
    eta = merge(-1.0_wp, 1.0_wp, g <= 2) / sqrt(3.0_wp)
    jac = 0.0_wp
    do a = 1, 4
      jac(1, :) = jac(1, :) + 0.25_wp * sx(a) * (1.0_wp + sy(a) * eta) * x(:, a)
      jac(2, :) = jac(2, :) + 0.25_wp * sy(a) * (1.0_wp + sx(a) * xi) * x(:, a)
    end do
    q4_det = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
  end function q4_det
end program test_fe_elements
