!> Patch tests of the reference elements (fracas_elements) on 4 x 4 cell
!> patches. Reference: the imposed field itself (Irons' patch test).
!> - Linear field u = a + A x on distorted meshes of T3, Q4, Q4P0, T6, Q8
!>   (straight sides): the strain and stress at every Gauss point are the
!>   uniform ones (1e-10 relative), elastic in both planes and J2 past yield;
!>   with the field imposed on the boundary nodes only, the assembled elastic
!>   patch (LAPACK dgesv on the interior dofs) reproduces the interior nodes
!>   (1e-10 relative).
!> - Quadratic field u = c (x^2 - y^2, -2 x y) + linear: divergence-free and
!>   harmonic, so in equilibrium without body force in both planes, stress
!>   2 G eps (linear in x, y). T6 on the distorted mesh and Q8 on an affine
!>   (parallelogram) mesh contain it exactly: Gauss-point stresses equal the
!>   exact stress at the Gauss point's position, and the interior is
!>   reproduced (1e-10 relative).
program test_fe_patch
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_bulk, only: bulk_t, bulk_j2, bulk_elastic, plane_strain, plane_stress, bulk_update, gp_size, &
                         gp_stress, gp_strain, gp_p
  use fracas_elements, only: el_t3, el_q4, el_t6, el_q8, el_q4p0, el_nnodes, el_ngauss, el_response, &
                             el_gauss_points_xy, el_geometry_ok, el_max_gauss
  implicit none

  integer, parameter :: ncell = 4, nf = 2 * ncell + 1   ! cells per side, fine-grid nodes per side
  integer, parameter :: nnode = nf * nf
  type(bulk_t) :: elastic, steel
  integer :: plane

  elastic = bulk_t(law=bulk_elastic, density=1000.0_wp, young=7.0e10_wp, poisson=0.33_wp)
  steel = bulk_t(law=bulk_j2, density=7800.0_wp, young=2.0e11_wp, poisson=0.3_wp, yield0=2.0e8_wp, &
                 hardening=2.0e9_wp)
  do plane = plane_strain, plane_stress
    call patch(el_t3, plane, .false., .true.)
    call patch(el_q4, plane, .false., .true.)
    call patch(el_q4p0, plane, .false., .true.)
    call patch(el_t6, plane, .false., .true.)
    call patch(el_q8, plane, .false., .true.)
    call patch(el_t6, plane, .true., .true.)
    call patch(el_q8, plane, .true., .false.)
  end do
  call test_finish()

contains

  pure integer function node_id(i, j)
    integer, intent(in) :: i, j
    node_id = 1 + i + nf * j
  end function node_id

  !> Fine-grid coordinates (nodes at even indices are corners). Distorted:
  !> corners moved by up to 0.2 cell, mid-sides at mid-edges (straight sides);
  !> affine: the uniform grid sheared and stretched.
  subroutine coordinates(distorted, x)
    logical, intent(in) :: distorted
    real(wp), intent(out) :: x(2, nnode)
    integer :: i, j, k
    real(wp) :: s, t
    do j = 0, nf - 1
      do i = 0, nf - 1
        s = real(i, wp) / (nf - 1)
        t = real(j, wp) / (nf - 1)
        k = node_id(i, j)
        if (distorted) then
          x(:, k) = [2.0_wp * s, 1.5_wp * t]
          if (mod(i, 2) == 0 .and. mod(j, 2) == 0) &
            x(:, k) = x(:, k) + 0.2_wp * (2.0_wp / ncell) * [sin(3.1_wp * i + 7.3_wp * j), cos(5.7_wp * i - 2.9_wp * j)]
        else
          x(:, k) = [2.0_wp * s + 0.6_wp * t, 0.3_wp * s + 1.4_wp * t]
        end if
      end do
    end do
    if (.not. distorted) return
    do j = 0, nf - 1
      do i = 0, nf - 1
        k = node_id(i, j)
        if (mod(i, 2) == 1 .and. mod(j, 2) == 0) then
          x(:, k) = 0.5_wp * (x(:, node_id(i - 1, j)) + x(:, node_id(i + 1, j)))
        else if (mod(i, 2) == 0 .and. mod(j, 2) == 1) then
          x(:, k) = 0.5_wp * (x(:, node_id(i, j - 1)) + x(:, node_id(i, j + 1)))
        else if (mod(i, 2) == 1 .and. mod(j, 2) == 1) then
          ! on the diagonal (i-1, j-1) - (i+1, j+1) of the cell (T6)
          x(:, k) = 0.5_wp * (x(:, node_id(i - 1, j - 1)) + x(:, node_id(i + 1, j + 1)))
        end if
      end do
    end do
  end subroutine coordinates

  !> Connectivity on the fine grid, counter-clockwise, LMGC90 node order.
  subroutine connectivity(kind, nel, conn)
    integer, intent(in) :: kind
    integer, intent(out) :: nel, conn(8, 2 * ncell * ncell)
    integer :: ci, cj, i, j
    nel = 0
    do cj = 0, ncell - 1
      do ci = 0, ncell - 1
        i = 2 * ci
        j = 2 * cj
        select case (kind)
        case (el_q4, el_q4p0)
          nel = nel + 1
          conn(1:4, nel) = [node_id(i, j), node_id(i + 2, j), node_id(i + 2, j + 2), node_id(i, j + 2)]
        case (el_q8)
          nel = nel + 1
          conn(1:8, nel) = [node_id(i, j), node_id(i + 2, j), node_id(i + 2, j + 2), node_id(i, j + 2), &
                            node_id(i + 1, j), node_id(i + 2, j + 1), node_id(i + 1, j + 2), node_id(i, j + 1)]
        case (el_t3)
          conn(1:3, nel + 1) = [node_id(i, j), node_id(i + 2, j), node_id(i + 2, j + 2)]
          conn(1:3, nel + 2) = [node_id(i, j), node_id(i + 2, j + 2), node_id(i, j + 2)]
          nel = nel + 2
        case (el_t6)
          conn(1:6, nel + 1) = [node_id(i, j), node_id(i + 2, j), node_id(i + 2, j + 2), &
                                node_id(i + 1, j), node_id(i + 2, j + 1), node_id(i + 1, j + 1)]
          conn(1:6, nel + 2) = [node_id(i, j), node_id(i + 2, j + 2), node_id(i, j + 2), &
                                node_id(i + 1, j + 1), node_id(i + 1, j + 2), node_id(i, j + 1)]
          nel = nel + 2
        end select
      end do
    end do
  end subroutine connectivity

  !> The imposed field at a point and its exact strain (xx, yy, gamma).
  pure subroutine field(quadratic, p, u, eps)
    logical, intent(in) :: quadratic
    real(wp), intent(in) :: p(2)
    real(wp), intent(out) :: u(2), eps(3)
    real(wp), parameter :: a(2) = [1.0e-4_wp, -2.0e-4_wp]
    real(wp), parameter :: grad(2, 2) = reshape([1.2e-3_wp, 0.4e-3_wp, -0.7e-3_wp, -0.5e-3_wp], [2, 2])
    real(wp), parameter :: c = 3.0e-4_wp
    u = a + matmul(grad, p)
    eps = [grad(1, 1), grad(2, 2), grad(1, 2) + grad(2, 1)]
    if (quadratic) then
      u = u + c * [p(1)**2 - p(2)**2, -2.0_wp * p(1) * p(2)]
      eps = eps + c * [2.0_wp * p(1), -2.0_wp * p(1), -4.0_wp * p(2)]
    end if
  end subroutine field

  subroutine patch(kind, plane, quadratic, distorted)
    integer, intent(in) :: kind, plane
    logical, intent(in) :: quadratic, distorted
    real(wp) :: x(2, nnode), u_exact(2 * nnode), eps_exact(3), xe(2, 8), ue(16), fi(16), ke(16, 16)
    real(wp) :: gp0(gp_size, el_max_gauss), gp1(gp_size, el_max_gauss), xy(2, el_max_gauss), dum(1, 1)
    real(wp) :: kg(2 * nnode, 2 * nnode), ee, pw, err_eps, err_sig, err_j2, ref_state(gp_size), dtan(4, 4)
    real(wp) :: sig_scale, eps_scale, u_scale, err_u, ug(2)
    integer :: conn(8, 2 * ncell * ncell), nel, e, nn, ng, g, a, i, j, k, nfree, info
    integer, allocatable :: free(:), fixed(:), ipiv(:)
    real(wp), allocatable :: kff(:, :), rhs(:, :)
    logical :: used(nnode), boundary(nnode), geometry_ok
    character(len=60) :: label
    character(len=4) :: name
    external :: dgesv

    select case (kind)
    case (el_t3)
      name = 'T3'
    case (el_q4)
      name = 'Q4'
    case (el_q4p0)
      name = 'Q4P0'
    case (el_t6)
      name = 'T6'
    case default
      name = 'Q8'
    end select
    label = trim(name)//merge(' plane strain', ' plane stress', plane == plane_strain)// &
            trim(merge(' quadratic', ' linear   ', quadratic))//trim(merge(' distorted', ' affine   ', distorted))
    call coordinates(distorted, x)
    call connectivity(kind, nel, conn)
    nn = el_nnodes(kind)
    ng = el_ngauss(kind)
    do k = 1, nnode
      call field(quadratic, x(:, k), ug, eps_exact)
      u_exact(2 * k - 1:2 * k) = ug
    end do
    ! Gauss-point strains and stresses; global elastic stiffness.
    used = .false.
    kg = 0.0_wp
    err_eps = 0.0_wp
    err_sig = 0.0_wp
    err_j2 = 0.0_wp
    geometry_ok = .true.
    sig_scale = elastic%young * 1.0e-3_wp
    eps_scale = 1.0e-3_wp
    gp0 = 0.0_wp
    do e = 1, nel
      do a = 1, nn
        xe(:, a) = x(:, conn(a, e))
        ue(2 * a - 1:2 * a) = u_exact(2 * conn(a, e) - 1:2 * conn(a, e))
        used(conn(a, e)) = .true.
      end do
      geometry_ok = geometry_ok .and. el_geometry_ok(kind, xe(:, 1:nn))
      call el_response(kind, xe(:, 1:nn), ue(1:2 * nn), elastic, plane, gp0, gp1, fi, ke, .true., ee, pw)
      call el_gauss_points_xy(kind, xe(:, 1:nn), xy)
      do g = 1, ng
        call field(quadratic, xy(:, g), ug, eps_exact)
        call bulk_update(elastic, plane, [eps_exact, 0.0_wp], gp0(:, g), ref_state, dtan)
        err_eps = max(err_eps, maxval(abs(gp1(gp_strain:gp_strain + 3, g) - ref_state(gp_strain:gp_strain + 3))) &
                      / eps_scale)
        err_sig = max(err_sig, maxval(abs(gp1(gp_stress:gp_stress + 3, g) - ref_state(gp_stress:gp_stress + 3))) &
                      / sig_scale)
      end do
      if (.not. quadratic) then
        ! J2 past yield under the same field scaled by 3: uniform plastic state
        call el_response(kind, xe(:, 1:nn), 3.0_wp * ue(1:2 * nn), steel, plane, gp0, gp1, fi, dum, .false., ee, pw)
        call field(.false., xe(:, 1), ug, eps_exact)
        call bulk_update(steel, plane, [3.0_wp * eps_exact, 0.0_wp], gp0(:, 1), ref_state, dtan)
        do g = 1, ng
          err_j2 = max(err_j2, maxval(abs(gp1(gp_stress:gp_stress + 3, g) - ref_state(gp_stress:gp_stress + 3))) &
                       / steel%yield0, abs(gp1(gp_p, g) - ref_state(gp_p)) / eps_scale)
        end do
        if (e == 1) call check_true(trim(label)//': J2 patch is plastic', ref_state(gp_p) > 0.0_wp)
      end if
      do a = 1, nn
        do i = 1, 2
          do j = 1, nn
            do k = 1, 2
              kg(2 * (conn(a, e) - 1) + i, 2 * (conn(j, e) - 1) + k) = &
                kg(2 * (conn(a, e) - 1) + i, 2 * (conn(j, e) - 1) + k) + ke(2 * (a - 1) + i, 2 * (j - 1) + k)
            end do
          end do
        end do
      end do
    end do
    call check_true(trim(label)//': every element has a positive Jacobian', geometry_ok)
    call check_close(trim(label)//': Gauss-point strain error / 1e-3', err_eps, 0.0_wp, 1.0e-10_wp)
    call check_close(trim(label)//': Gauss-point stress error / (E 1e-3)', err_sig, 0.0_wp, 1.0e-10_wp)
    if (.not. quadratic) call check_close(trim(label)//': J2 Gauss-point stress error / sigma_y0', err_j2, &
                                          0.0_wp, 1.0e-10_wp)

    ! Interior dofs from the boundary values: K_ff u_f = -K_fp u_p.
    boundary = .false.
    do j = 0, nf - 1
      do i = 0, nf - 1
        boundary(node_id(i, j)) = i == 0 .or. j == 0 .or. i == nf - 1 .or. j == nf - 1
      end do
    end do
    free = pack([(k, k = 1, 2 * nnode)], [((used(k) .and. .not. boundary(k), i = 1, 2), k = 1, nnode)])
    fixed = pack([(k, k = 1, 2 * nnode)], [(((.not. used(k)) .or. boundary(k), i = 1, 2), k = 1, nnode)])
    nfree = size(free)
    kff = kg(free, free)
    allocate (rhs(nfree, 1), ipiv(nfree))
    rhs(:, 1) = -matmul(kg(free, fixed), u_exact(fixed))
    call dgesv(nfree, 1, kff, nfree, ipiv, rhs, nfree, info)
    call check_true(trim(label)//': dgesv info = 0', info == 0)
    u_scale = maxval(abs(u_exact))
    err_u = maxval(abs(rhs(:, 1) - u_exact(free))) / u_scale
    call check_close(trim(label)//': interior nodes from the boundary, error / max|u|', err_u, 0.0_wp, 1.0e-10_wp)
  end subroutine patch
end program test_fe_patch
