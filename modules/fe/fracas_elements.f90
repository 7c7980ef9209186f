!> Reference finite elements of 2D meshed bodies (small strain, unit
!> thickness): T3, Q4, T6, Q8 and Q4P0 (Q4 with mean dilatation, for decks
!> naming LMGC90's Q4P0x). Shape functions, Gauss rules, mass, and the element
!> response (internal force, consistent tangent, energies) through the bulk
!> laws of fracas_bulk. See doc/mesh_mechanics.md.
!>
!> Conventions (LMGC90's): node order counter-clockwise, for T6/Q8 corners then
!> mid-sides (T6: 4 on 1-2, 5 on 2-3, 6 on 3-1; Q8: 5 on 1-2, 6 on 2-3, 7 on
!> 3-4, 8 on 4-1). Reference cells: triangle (0,0) (1,0) (0,1), square [-1,1]^2.
!> Gauss points (stiffness and Gauss-point output):
!>   T3  1 point (1/3, 1/3). LMGC90 prints 3 identical points in GPV.OUT:
!>       el_ngauss_gpv gives the printed count, each printed point is point 1.
!>   T6  3 points (1/6,1/6) (2/3,1/6) (1/6,2/3)
!>   Q4  2x2, xi running fastest: (-a,-a) (a,-a) (-a,a) (a,a), a = 1/sqrt(3)
!>       (checked against LMGC90's GPV.OUT of mesh_block_drop)
!>   Q8  3x3, xi running fastest, xi and eta in (-b, 0, b), b = sqrt(3/5)
!> Degrees of freedom are interleaved: u(2a-1) = u_x, u(2a) = u_y of node a.
!> Nodal coordinates x(2, nn) are the reference (initial) positions.
!>
!> API (kinds el_t3, el_q4, el_t6, el_q8, el_q4p0; bounds el_max_nodes,
!> el_max_dofs, el_max_gauss):
!>   el_kind_of(name) el_nnodes(kind) el_ngauss(kind) el_ngauss_gpv(kind)
!>   el_nedges(kind) el_edges(kind) el_edge_midnodes(kind)
!>   el_vtk_type(kind) el_vtk_order(kind)
!>   el_shape(kind, xi, n, dn)          el_gauss_rule(kind, xi, w)
!>   el_gauss_points_xy(kind, x, xy)    el_area(kind, x)   el_geometry_ok(kind, x)
!>   el_mass(kind, x, rho, lumped, m)
!>   el_response(kind, x, u, mat, plane, gp_begin, gp_end, fi, ke, want_tangent,
!>               elastic_energy, plastic_work)
module fracas_elements
  use fracas_kinds, only: wp
  use fracas_bulk, only: bulk_t, bulk_update, bulk_plastic_work, gp_size, gp_stress, gp_strain, &
                         gp_plastic_strain, gp_p, plane_strain, bulk_neohookean, bulk_neohooke, &
                         bulk_j2_finite, bulk_yield_stress, plane_axisym
  implicit none
  private
  public :: el_t3, el_q4, el_t6, el_q8, el_q4p0, el_max_nodes, el_max_dofs, el_max_gauss, &
            el_kind_of, el_nnodes, el_ngauss, el_ngauss_gpv, el_nedges, el_edges, el_edge_midnodes, &
            el_vtk_type, el_vtk_order, el_shape, el_gauss_rule, el_gauss_points_xy, el_area, &
            el_geometry_ok, el_mass, el_response, el_name

  integer, parameter :: el_t3 = 1, el_q4 = 2, el_t6 = 3, el_q8 = 4, el_q4p0 = 5
  integer, parameter :: el_max_nodes = 8, el_max_dofs = 16, el_max_gauss = 9

  real(wp), parameter :: one_third = 1.0_wp / 3.0_wp, one_sixth = 1.0_wp / 6.0_wp
  real(wp), parameter :: gauss2 = 0.57735026918962576451_wp        ! 1/sqrt(3)
  real(wp), parameter :: gauss3 = 0.77459666924148337704_wp        ! sqrt(3/5)
  real(wp), parameter :: w3(3) = [5.0_wp / 9.0_wp, 8.0_wp / 9.0_wp, 5.0_wp / 9.0_wp]
  real(wp), parameter :: x3(3) = [-gauss3, 0.0_wp, gauss3]
  ! Degree-4 six-point triangle rule (Dunavant), for the T6 mass.
  real(wp), parameter :: tri6_a = 0.44594849091596488632_wp, tri6_b = 0.09157621350977074346_wp
  real(wp), parameter :: tri6_wa = 0.5_wp * 0.22338158967801146570_wp
  real(wp), parameter :: tri6_wb = 0.5_wp * 0.10995174365532186764_wp
  ! Q4/Q8 corner signs in the reference square; Q8 mid-side positions.
  real(wp), parameter :: q_xi(8) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp]
  real(wp), parameter :: q_eta(8) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp]

  integer, parameter :: rule_stiffness = 1, rule_mass = 2

contains

  !> Element kind of an LMGC90 element name, 0 if unknown.
  pure integer function el_kind_of(name) result(kind)
    character(len=*), intent(in) :: name
    select case (name)
    case ('T3xxx')
      kind = el_t3
    case ('Q4xxx')
      kind = el_q4
    case ('T6xxx')
      kind = el_t6
    case ('Q8xxx')
      kind = el_q8
    case ('Q4P0x')
      kind = el_q4p0
    case default
      kind = 0
    end select
  end function el_kind_of

  !> The element's geometry name as BODIES.DAT and GPV.OUT write it (Q4P0x
  !> is a model on Q4xxx geometry).
  pure function el_name(kind) result(name)
    integer, intent(in) :: kind
    character(len=5) :: name
    select case (kind)
    case (el_t3); name = 'T3xxx'
    case (el_t6); name = 'T6xxx'
    case (el_q8); name = 'Q8xxx'
    case default; name = 'Q4xxx'
    end select
  end function el_name

  pure integer function el_nnodes(kind) result(n)
    integer, intent(in) :: kind
    select case (kind)
    case (el_t3)
      n = 3
    case (el_q4, el_q4p0)
      n = 4
    case (el_t6)
      n = 6
    case (el_q8)
      n = 8
    case default
      n = 0
    end select
  end function el_nnodes

  !> Gauss points of the stiffness rule (the Gauss-point states of an element).
  pure integer function el_ngauss(kind) result(n)
    integer, intent(in) :: kind
    select case (kind)
    case (el_t3)
      n = 1
    case (el_q4, el_q4p0)
      n = 4
    case (el_t6)
      n = 3
    case (el_q8)
      n = 9
    case default
      n = 0
    end select
  end function el_ngauss

  !> Gauss points LMGC90 prints per element in GPV.OUT: 3 for T3 (the one
  !> point repeated), el_ngauss otherwise.
  pure integer function el_ngauss_gpv(kind) result(n)
    integer, intent(in) :: kind
    n = merge(3, el_ngauss(kind), kind == el_t3)
  end function el_ngauss_gpv

  pure integer function el_nedges(kind) result(n)
    integer, intent(in) :: kind
    select case (kind)
    case (el_t3, el_t6)
      n = 3
    case (el_q4, el_q4p0, el_q8)
      n = 4
    case default
      n = 0
    end select
  end function el_nedges

  !> Boundary edges as pairs of corner nodes, counter-clockwise (the interior
  !> on the left of first -> second).
  pure function el_edges(kind) result(edges)
    integer, intent(in) :: kind
    integer :: edges(2, el_nedges(kind))
    integer :: i, nc
    nc = size(edges, 2)
    do i = 1, nc
      edges(:, i) = [i, modulo(i, nc) + 1]
    end do
  end function el_edges

  !> Mid-side node of each edge of el_edges (0 for linear elements).
  pure function el_edge_midnodes(kind) result(mid)
    integer, intent(in) :: kind
    integer :: mid(el_nedges(kind))
    integer :: i
    do i = 1, size(mid)
      mid(i) = merge(size(mid) + i, 0, kind == el_t6 .or. kind == el_q8)
    end do
  end function el_edge_midnodes

  !> VTK cell type: VTK_TRIANGLE 5, VTK_QUAD 9, VTK_QUADRATIC_TRIANGLE 22,
  !> VTK_QUADRATIC_QUAD 23.
  pure integer function el_vtk_type(kind) result(t)
    integer, intent(in) :: kind
    select case (kind)
    case (el_t3)
      t = 5
    case (el_q4, el_q4p0)
      t = 9
    case (el_t6)
      t = 22
    case (el_q8)
      t = 23
    case default
      t = 0
    end select
  end function el_vtk_type

  !> Local node written at each VTK connectivity position. VTK's quadratic
  !> cells also list corners then mid-sides (0-1, 1-2, ...), so the order is
  !> LMGC90's: the identity.
  pure function el_vtk_order(kind) result(order)
    integer, intent(in) :: kind
    integer :: order(el_nnodes(kind))
    integer :: i
    order = [(i, i = 1, size(order))]
  end function el_vtk_order

  !> Shape functions n(nn) and their reference derivatives dn(2, nn) at xi(2).
  pure subroutine el_shape(kind, xi, n, dn)
    integer, intent(in) :: kind
    real(wp), intent(in) :: xi(2)
    real(wp), intent(out) :: n(:), dn(:, :)
    real(wp) :: l(3), dl(2, 3), s, t, sa, ta
    integer :: a
    select case (kind)
    case (el_t3, el_t6)
      l = [1.0_wp - xi(1) - xi(2), xi(1), xi(2)]
      dl(:, 1) = [-1.0_wp, -1.0_wp]
      dl(:, 2) = [1.0_wp, 0.0_wp]
      dl(:, 3) = [0.0_wp, 1.0_wp]
      if (kind == el_t3) then
        n(1:3) = l
        dn(:, 1:3) = dl
      else
        do a = 1, 3
          n(a) = l(a) * (2.0_wp * l(a) - 1.0_wp)
          dn(:, a) = (4.0_wp * l(a) - 1.0_wp) * dl(:, a)
        end do
        n(4) = 4.0_wp * l(1) * l(2)
        n(5) = 4.0_wp * l(2) * l(3)
        n(6) = 4.0_wp * l(3) * l(1)
        dn(:, 4) = 4.0_wp * (l(1) * dl(:, 2) + l(2) * dl(:, 1))
        dn(:, 5) = 4.0_wp * (l(2) * dl(:, 3) + l(3) * dl(:, 2))
        dn(:, 6) = 4.0_wp * (l(3) * dl(:, 1) + l(1) * dl(:, 3))
      end if
    case (el_q4, el_q4p0)
      do a = 1, 4
        n(a) = 0.25_wp * (1.0_wp + q_xi(a) * xi(1)) * (1.0_wp + q_eta(a) * xi(2))
        dn(1, a) = 0.25_wp * q_xi(a) * (1.0_wp + q_eta(a) * xi(2))
        dn(2, a) = 0.25_wp * q_eta(a) * (1.0_wp + q_xi(a) * xi(1))
      end do
    case (el_q8)
      s = xi(1)
      t = xi(2)
      do a = 1, 4
        sa = q_xi(a)
        ta = q_eta(a)
        n(a) = 0.25_wp * (1.0_wp + sa * s) * (1.0_wp + ta * t) * (sa * s + ta * t - 1.0_wp)
        dn(1, a) = 0.25_wp * sa * (1.0_wp + ta * t) * (2.0_wp * sa * s + ta * t)
        dn(2, a) = 0.25_wp * ta * (1.0_wp + sa * s) * (sa * s + 2.0_wp * ta * t)
      end do
      do a = 5, 8
        sa = q_xi(a)
        ta = q_eta(a)
        if (sa == 0.0_wp) then
          n(a) = 0.5_wp * (1.0_wp - s**2) * (1.0_wp + ta * t)
          dn(1, a) = -s * (1.0_wp + ta * t)
          dn(2, a) = 0.5_wp * ta * (1.0_wp - s**2)
        else
          n(a) = 0.5_wp * (1.0_wp + sa * s) * (1.0_wp - t**2)
          dn(1, a) = 0.5_wp * sa * (1.0_wp - t**2)
          dn(2, a) = -t * (1.0_wp + sa * s)
        end if
      end do
    end select
  end subroutine el_shape

  !> Gauss rule of the element's stiffness (its Gauss-point states), in
  !> LMGC90's order: xi(2, el_ngauss(kind)), weights w(el_ngauss(kind)).
  pure subroutine el_gauss_rule(kind, xi, w)
    integer, intent(in) :: kind
    real(wp), intent(out) :: xi(:, :), w(:)
    integer :: ng
    call quadrature(kind, rule_stiffness, ng, xi, w)
  end subroutine el_gauss_rule

  !> Quadrature rules: stiffness (LMGC90's) and mass (exact for the consistent
  !> mass of straight-sided elements: T3 3 points, T6 6 points, Q4 2x2, Q8 3x3).
  pure subroutine quadrature(kind, purpose, ng, xi, w)
    integer, intent(in) :: kind, purpose
    integer, intent(out) :: ng
    real(wp), intent(out) :: xi(:, :), w(:)
    integer :: i, j
    select case (kind)
    case (el_t3, el_t6)
      if (kind == el_t3 .and. purpose == rule_stiffness) then
        ng = 1
        xi(:, 1) = [one_third, one_third]
        w(1) = 0.5_wp
      else if (kind == el_t6 .and. purpose == rule_mass) then
        ng = 6
        xi(:, 1) = [tri6_a, tri6_a]
        xi(:, 2) = [1.0_wp - 2.0_wp * tri6_a, tri6_a]
        xi(:, 3) = [tri6_a, 1.0_wp - 2.0_wp * tri6_a]
        xi(:, 4) = [tri6_b, tri6_b]
        xi(:, 5) = [1.0_wp - 2.0_wp * tri6_b, tri6_b]
        xi(:, 6) = [tri6_b, 1.0_wp - 2.0_wp * tri6_b]
        w(1:3) = tri6_wa
        w(4:6) = tri6_wb
      else
        ng = 3
        xi(:, 1) = [one_sixth, one_sixth]
        xi(:, 2) = [4.0_wp * one_sixth, one_sixth]
        xi(:, 3) = [one_sixth, 4.0_wp * one_sixth]
        w(1:3) = one_sixth
      end if
    case (el_q4, el_q4p0)
      ng = 4
      do j = 1, 2
        do i = 1, 2
          xi(:, i + 2 * (j - 1)) = [merge(-gauss2, gauss2, i == 1), merge(-gauss2, gauss2, j == 1)]
        end do
      end do
      w(1:4) = 1.0_wp
    case (el_q8)
      ng = 9
      do j = 1, 3
        do i = 1, 3
          xi(:, i + 3 * (j - 1)) = [x3(i), x3(j)]
          w(i + 3 * (j - 1)) = w3(i) * w3(j)
        end do
      end do
    case default
      ng = 0
    end select
  end subroutine quadrature

  !> Jacobian determinant and physical derivatives dnx(2, nn) from the
  !> reference derivatives dn(2, nn); J(i,j) = d x_j / d xi_i.
  pure subroutine physical_derivatives(nn, x, dn, dnx, det)
    integer, intent(in) :: nn
    real(wp), intent(in) :: x(:, :), dn(:, :)
    real(wp), intent(out) :: dnx(:, :), det
    real(wp) :: jac(2, 2)
    integer :: a
    jac = 0.0_wp
    do a = 1, nn
      jac(:, 1) = jac(:, 1) + dn(:, a) * x(1, a)
      jac(:, 2) = jac(:, 2) + dn(:, a) * x(2, a)
    end do
    det = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
    do a = 1, nn
      dnx(1, a) = (jac(2, 2) * dn(1, a) - jac(1, 2) * dn(2, a)) / det
      dnx(2, a) = (-jac(2, 1) * dn(1, a) + jac(1, 1) * dn(2, a)) / det
    end do
  end subroutine physical_derivatives

  !> Physical coordinates xy(2, el_ngauss(kind)) of the Gauss points.
  pure subroutine el_gauss_points_xy(kind, x, xy)
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: xy(:, :)
    real(wp) :: xi(2, el_max_gauss), w(el_max_gauss), n(el_max_nodes), dn(2, el_max_nodes)
    integer :: ng, g, nn, a
    nn = el_nnodes(kind)
    call quadrature(kind, rule_stiffness, ng, xi, w)
    do g = 1, ng
      call el_shape(kind, xi(:, g), n, dn)
      xy(:, g) = 0.0_wp
      do a = 1, nn
        xy(:, g) = xy(:, g) + n(a) * x(:, a)
      end do
    end do
  end subroutine el_gauss_points_xy

  !> Area of the element (exact for straight-sided elements).
  pure real(wp) function el_area(kind, x) result(area)
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:, :)
    real(wp) :: xi(2, el_max_gauss), w(el_max_gauss), n(el_max_nodes), dn(2, el_max_nodes)
    real(wp) :: dnx(2, el_max_nodes), det
    integer :: ng, g, nn
    nn = el_nnodes(kind)
    call quadrature(kind, rule_mass, ng, xi, w)
    area = 0.0_wp
    do g = 1, ng
      call el_shape(kind, xi(:, g), n, dn)
      call physical_derivatives(nn, x, dn, dnx, det)
      area = area + w(g) * det
    end do
  end function el_area

  !> True when the Jacobian is positive at every node and every Gauss point
  !> (counter-clockwise, not inverted). For T3 and Q4 this is exact.
  pure logical function el_geometry_ok(kind, x) result(ok)
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:, :)
    real(wp) :: xi(2, el_max_gauss), w(el_max_gauss), n(el_max_nodes), dn(2, el_max_nodes)
    real(wp) :: dnx(2, el_max_nodes), det, node_xi(2)
    integer :: ng, g, nn, a
    nn = el_nnodes(kind)
    ok = nn > 0
    if (.not. ok) return
    call quadrature(kind, rule_mass, ng, xi, w)
    do g = 1, ng + nn
      if (g <= ng) then
        node_xi = xi(:, g)
      else
        a = g - ng
        node_xi = reference_node(kind, a)
      end if
      call el_shape(kind, node_xi, n, dn)
      call physical_derivatives(nn, x, dn, dnx, det)
      ok = ok .and. det > 0.0_wp
    end do
  end function el_geometry_ok

  !> Reference coordinates of local node a.
  pure function reference_node(kind, a) result(xi)
    integer, intent(in) :: kind, a
    real(wp) :: xi(2)
    real(wp), parameter :: t_xi(6) = [0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, 0.5_wp, 0.0_wp]
    real(wp), parameter :: t_eta(6) = [0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, 0.5_wp]
    if (kind == el_t3 .or. kind == el_t6) then
      xi = [t_xi(a), t_eta(a)]
    else
      xi = [q_xi(a), q_eta(a)]
    end if
  end function reference_node

  !> Element mass m(2nn, 2nn), density rho, unit thickness. Consistent:
  !> rho * integral of N_a N_b on both directions. Lumped (diagonal): row sums
  !> for T3/Q4, HRZ for T6/Q8 (the consistent diagonal scaled to the total
  !> mass; row sums would give zero or negative corner masses there).
  pure subroutine el_mass(kind, x, rho, lumped, m, axisym)
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:, :), rho
    logical, intent(in) :: lumped
    real(wp), intent(out) :: m(:, :)
    logical, intent(in), optional :: axisym   !< x is the radius: the density integrated over 2 pi r dA
    real(wp) :: xi(2, el_max_gauss), w(el_max_gauss), n(el_max_nodes), dn(2, el_max_nodes)
    real(wp) :: dnx(2, el_max_nodes), det, ms(el_max_nodes, el_max_nodes), diag(el_max_nodes), total
    integer :: ng, g, nn, a, b
    nn = el_nnodes(kind)
    call quadrature(kind, rule_mass, ng, xi, w)
    ms = 0.0_wp
    do g = 1, ng
      call el_shape(kind, xi(:, g), n, dn)
      call physical_derivatives(nn, x, dn, dnx, det)
      if (present(axisym)) then
        if (axisym) det = det * 6.28318530717958647692_wp * dot_product(n(1:nn), x(1, 1:nn))
      end if
      ! (n_a n_b) first: the matrix comes out exactly symmetric
      do b = 1, nn
        ms(1:nn, b) = ms(1:nn, b) + (rho * w(g) * det) * (n(1:nn) * n(b))
      end do
    end do
    m(1:2 * nn, 1:2 * nn) = 0.0_wp
    if (lumped) then
      if (kind == el_t6 .or. kind == el_q8) then
        total = sum(ms(1:nn, 1:nn))
        do a = 1, nn
          diag(a) = ms(a, a)
        end do
        diag(1:nn) = diag(1:nn) * total / sum(diag(1:nn))
      else
        diag(1:nn) = sum(ms(1:nn, 1:nn), dim=2)
      end if
      do a = 1, nn
        m(2 * a - 1, 2 * a - 1) = diag(a)
        m(2 * a, 2 * a) = diag(a)
      end do
    else
      do b = 1, nn
        do a = 1, nn
          m(2 * a - 1, 2 * b - 1) = ms(a, b)
          m(2 * a, 2 * b) = ms(a, b)
        end do
      end do
    end if
  end subroutine el_mass

  !> Small-strain response of one element.
  !>   x(2, nn) reference coordinates, u(2nn) nodal displacements (interleaved);
  !>   gp_begin(gp_size, ng) Gauss-point states at the start of the step,
  !>   gp_end(gp_size, ng) at the end (stress, strain, plastic strain, p);
  !>   fi(2nn) = integral of B' sigma; ke(2nn, 2nn) = integral of B' D_tan B,
  !>   the consistent tangent, when want_tangent (else set to 0);
  !>   elastic_energy = integral of 1/2 sigma : eps_e at the end of the step;
  !>   plastic_work = integral of the plastic work over the step.
  !> el_q4p0 in plane strain uses the mean-dilatation B-bar: the volumetric
  !> strain at each Gauss point is replaced by its element mean (3D trace,
  !> eps_zz then non-zero at a Gauss point); in plane stress it is a Q4.
  !> For an elastic material fi = ke u.
  !> A neo-Hookean material (finite strain) is integrated in the total
  !> Lagrangian way, as LMGC90 does with its MatLib models: at each Gauss point
  !> F = I + du/dX (reference derivatives), fi = integral of G' P, ke = integral
  !> of G' (dP/dF) G (G: u -> du/dX, rows F_xx, F_xy, F_yx, F_yy), over the
  !> reference element; el_q4p0 is then a plain Q4 (LMGC90's MatLib path uses
  !> the full gradient on every Gauss point), plane strain only. The states get
  !> the Cauchy stress and the Green-Lagrange strain (xx, yy, 2 xy, zz);
  !> elastic_energy is the integral of W. An element turned inside out (J <= 0
  !> at a Gauss point) gives fi = huge: the caller's Newton loop fails.
  pure subroutine el_response(kind, x, u, mat, plane, gp_begin, gp_end, fi, ke, want_tangent, &
                              elastic_energy, plastic_work)
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:, :), u(:)
    type(bulk_t), intent(in) :: mat
    integer, intent(in) :: plane
    real(wp), intent(in) :: gp_begin(:, :)
    real(wp), intent(out) :: gp_end(:, :)
    real(wp), intent(out) :: fi(:), ke(:, :)
    logical, intent(in) :: want_tangent
    real(wp), intent(out) :: elastic_energy, plastic_work
    real(wp) :: xi(2, el_max_gauss), w(el_max_gauss), n(el_max_nodes), dn(2, el_max_nodes)
    real(wp) :: dnx(2, el_max_nodes, el_max_gauss), wdet(el_max_gauss), det
    real(wp) :: bmat(4, el_max_dofs), bvol_mean(el_max_dofs), db(4, el_max_dofs)
    real(wp) :: eps(4), dtan(4, 4), sig(4), eps_e(4)
    integer :: ng, g, nn, nd, a, nrow, i, j, r
    logical :: bbar

    nn = el_nnodes(kind)
    nd = 2 * nn
    if (mat%law == bulk_neohookean) then
      call response_finite(kind, x, u, mat, gp_end, fi, ke, want_tangent, elastic_energy)
      plastic_work = 0.0_wp
      return
    end if
    if (mat%law == bulk_j2_finite) then
      call response_j2_finite(kind, x, u, mat, plane == plane_axisym, gp_begin, gp_end, fi, ke, want_tangent, &
                              elastic_energy, plastic_work)
      return
    end if
    bbar = kind == el_q4p0 .and. plane == plane_strain
    nrow = merge(4, 3, bbar)
    call quadrature(kind, rule_stiffness, ng, xi, w)
    bvol_mean = 0.0_wp
    do g = 1, ng
      call el_shape(kind, xi(:, g), n, dn)
      call physical_derivatives(nn, x, dn, dnx(:, :, g), det)
      wdet(g) = w(g) * det
      if (bbar) then
        do a = 1, nn
          bvol_mean(2 * a - 1) = bvol_mean(2 * a - 1) + wdet(g) * dnx(1, a, g)
          bvol_mean(2 * a) = bvol_mean(2 * a) + wdet(g) * dnx(2, a, g)
        end do
      end if
    end do
    if (bbar) bvol_mean(1:nd) = bvol_mean(1:nd) / sum(wdet(1:ng))

    call zero_response(nd, want_tangent, fi, ke)
    elastic_energy = 0.0_wp
    plastic_work = 0.0_wp
    do g = 1, ng
      bmat(:, 1:nd) = 0.0_wp
      do a = 1, nn
        bmat(1, 2 * a - 1) = dnx(1, a, g)
        bmat(2, 2 * a) = dnx(2, a, g)
        bmat(3, 2 * a - 1) = dnx(2, a, g)
        bmat(3, 2 * a) = dnx(1, a, g)
      end do
      if (bbar) then
        ! eps_ii += (mean trace - trace) / 3 for ii = xx, yy, zz
        do a = 1, nn
          bmat(4, 2 * a - 1) = one_third * (bvol_mean(2 * a - 1) - dnx(1, a, g))
          bmat(4, 2 * a) = one_third * (bvol_mean(2 * a) - dnx(2, a, g))
        end do
        bmat(1, 1:nd) = bmat(1, 1:nd) + bmat(4, 1:nd)
        bmat(2, 1:nd) = bmat(2, 1:nd) + bmat(4, 1:nd)
      end if
      eps = 0.0_wp
      do j = 1, nd
        eps = eps + bmat(:, j) * u(j)
      end do
      call bulk_update(mat, plane, eps, gp_begin(:, g), gp_end(:, g), dtan)
      sig = gp_end(gp_stress:gp_stress + 3, g)
      do j = 1, nd
        fi(j) = fi(j) + wdet(g) * dot_product(sig(1:nrow), bmat(1:nrow, j))
      end do
      if (want_tangent) then
        ! ke += wdet B' (D B)
        do j = 1, nd
          do r = 1, nrow
            db(r, j) = dot_product(dtan(r, 1:nrow), bmat(1:nrow, j))
          end do
        end do
        do j = 1, nd
          do i = 1, nd
            ke(i, j) = ke(i, j) + wdet(g) * dot_product(bmat(1:nrow, i), db(1:nrow, j))
          end do
        end do
      end if
      eps_e = gp_end(gp_strain:gp_strain + 3, g) - gp_end(gp_plastic_strain:gp_plastic_strain + 3, g)
      elastic_energy = elastic_energy + 0.5_wp * wdet(g) * dot_product(sig, eps_e)
      plastic_work = plastic_work + wdet(g) * bulk_plastic_work(mat, gp_begin(gp_p, g), gp_end(gp_p, g))
    end do
  end subroutine el_response

  !> fi(1:nd) = 0 and the tangent ke(1:nd, 1:nd) = 0; without a tangent the caller
  !> may pass any (small) ke, set to 0 whole.
  pure subroutine zero_response(nd, want_tangent, fi, ke)
    integer, intent(in) :: nd
    logical, intent(in) :: want_tangent
    real(wp), intent(out) :: fi(:)
    real(wp), intent(inout) :: ke(:, :)
    fi(1:nd) = 0.0_wp
    if (want_tangent) then
      ke(1:nd, 1:nd) = 0.0_wp
    else
      ke = 0.0_wp
    end if
  end subroutine zero_response

  !> Total Lagrangian response of a neo-Hookean element (see el_response).
  pure subroutine response_finite(kind, x, u, mat, gp_end, fi, ke, want_tangent, energy)
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:, :), u(:)
    type(bulk_t), intent(in) :: mat
    real(wp), intent(out) :: gp_end(:, :), fi(:), ke(:, :)
    logical, intent(in) :: want_tangent
    real(wp), intent(out) :: energy
    real(wp) :: xi(2, el_max_gauss), w(el_max_gauss), n(el_max_nodes), dn(2, el_max_nodes)
    real(wp) :: dnx(2, el_max_nodes), det, gmat(4, el_max_dofs), ag(4, el_max_dofs)
    real(wp) :: f(4), p(4), a(4, 4), wd, sig(4), green(4)
    integer :: ng, g, nn, nd, c, i, j
    nn = el_nnodes(kind)
    nd = 2 * nn
    call quadrature(kind, rule_stiffness, ng, xi, w)
    call zero_response(nd, want_tangent, fi, ke)
    energy = 0.0_wp
    do g = 1, ng
      call el_shape(kind, xi(:, g), n, dn)
      call physical_derivatives(nn, x, dn, dnx, det)
      ! G: row 2(i-1)+J of du_i/dX_J; node c's dof i is column 2(c-1)+i
      gmat(:, 1:nd) = 0.0_wp
      do c = 1, nn
        gmat(1:2, 2 * c - 1) = dnx(:, c)
        gmat(3:4, 2 * c) = dnx(:, c)
      end do
      f = [1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp] + matmul(gmat(:, 1:nd), u(1:nd))
      if (f(1) * f(4) - f(2) * f(3) <= 0.0_wp) then
        fi(1:nd) = huge(1.0_wp)
        gp_end(:, g:ng) = 0.0_wp
        return
      end if
      call bulk_neohooke(mat, f, p, a, wd, sig, green)
      gp_end(:, g) = 0.0_wp
      gp_end(gp_stress:gp_stress + 3, g) = sig
      gp_end(gp_strain:gp_strain + 3, g) = green
      fi(1:nd) = fi(1:nd) + (w(g) * det) * matmul(p, gmat(:, 1:nd))
      energy = energy + w(g) * det * wd
      if (want_tangent) then
        ag(:, 1:nd) = matmul(a, gmat(:, 1:nd))
        do j = 1, nd
          do i = 1, nd
            ke(i, j) = ke(i, j) + (w(g) * det) * dot_product(gmat(:, i), ag(:, j))
          end do
        end do
      end if
    end do
  end subroutine response_finite

  !> LMGC90's internal finite-strain J2 element (its Q4P0x with kine_ large;
  !> doc/mesh_mechanics.md §7): multiplicative plasticity on the isochoric
  !> elastic Finger tensor (Simo), the deviatoric Kirchhoff stress mu dev(b_e^)
  !> at each Gauss point, one pressure per element from the element's volume
  !> ratio Jm = V / V0, p = K/2 (Jm - 1/Jm), radial return with mu^ = mu tr(b_e^)/3
  !> and linear hardening; the new b_e keeps the element mean of the trial
  !> traces (as LMGC90). State: Cauchy stress, Green-Lagrange strain, Cp^-1 - I
  !> (xx, yy, xy, zz) in the plastic-strain slots, p the cumulative plastic
  !> strain. Internal forces: integral of B(x)' sigma over the current element.
  !> The tangent is the central difference of fi (symmetrized). Axisymmetric
  !> (x the radius r): F_zz = 1 + u_r / r, the hoop stress in the zz slot, volumes
  !> 2 pi r dA (LMGC90's).
  pure subroutine response_j2_finite(kind, x, u, mat, axisym, gp_begin, gp_end, fi, ke, want_tangent, energy, &
                                     plastic_work)
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:, :), u(:), gp_begin(:, :)
    type(bulk_t), intent(in) :: mat
    logical, intent(in) :: axisym
    real(wp), intent(out) :: gp_end(:, :), fi(:), ke(:, :)
    logical, intent(in) :: want_tangent
    real(wp), intent(out) :: energy, plastic_work
    real(wp) :: up(el_max_dofs), fp(el_max_dofs), fm(el_max_dofs), scratch(gp_size, el_max_gauss)
    real(wp) :: h, e1, e2
    integer :: nd, j
    nd = 2 * el_nnodes(kind)
    call j2_finite_forces(kind, x, u, mat, axisym, gp_begin, gp_end, fi, energy, plastic_work)
    call zero_response(nd, want_tangent, fp, ke)
    if (.not. want_tangent) return
    ! step: 1e-7 of the element's size, a displacement well resolved in double
    h = 1.0e-7_wp * sqrt(max(el_area(kind, x), tiny(1.0_wp)))
    up(1:nd) = u(1:nd)
    do j = 1, nd
      up(j) = u(j) + h
      call j2_finite_forces(kind, x, up, mat, axisym, gp_begin, scratch, fp, e1, e2)
      up(j) = u(j) - h
      call j2_finite_forces(kind, x, up, mat, axisym, gp_begin, scratch, fm, e1, e2)
      up(j) = u(j)
      ke(1:nd, j) = (fp(1:nd) - fm(1:nd)) / (2.0_wp * h)
    end do
    ke(1:nd, 1:nd) = 0.5_wp * (ke(1:nd, 1:nd) + transpose(ke(1:nd, 1:nd)))
  end subroutine response_j2_finite

  !> Internal forces and states of response_j2_finite.
  pure subroutine j2_finite_forces(kind, x, u, mat, axisym, gp_begin, gp_end, fi, energy, plastic_work)
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:, :), u(:), gp_begin(:, :)
    type(bulk_t), intent(in) :: mat
    logical, intent(in) :: axisym
    real(wp), intent(out) :: gp_end(:, :), fi(:), energy, plastic_work
    real(wp) :: xi(2, el_max_gauss), w(el_max_gauss), n(el_max_nodes), dn(2, el_max_nodes)
    real(wp) :: dnx(2, el_max_nodes, el_max_gauss), dv0(el_max_gauss), det
    real(wp) :: f(2, 2, el_max_gauss), jac(el_max_gauss), tf(el_max_gauss), dev(4, el_max_gauss)
    real(wp) :: cpi(2, 2), be(2, 2), be33, s(4), nrm, q, sy, dgam, mub, finv(2, 2), bn(2, 2)
    real(wp) :: kb, mu, v0, v, jm, pres, trabe, sig(4), dndx(2), pnew(el_max_gauss), c(2, 2)
    real(wp) :: f33(el_max_gauss), nsh(el_max_nodes, el_max_gauss), rcur
    real(wp), parameter :: two_pi = 6.28318530717958647692_wp
    logical :: plastic(el_max_gauss)
    integer :: ng, g, nn, nd, a
    nn = el_nnodes(kind)
    nd = 2 * nn
    kb = mat%young / (3.0_wp * (1.0_wp - 2.0_wp * mat%poisson))
    mu = mat%young / (2.0_wp * (1.0_wp + mat%poisson))
    call quadrature(kind, rule_stiffness, ng, xi, w)
    fi(1:nd) = 0.0_wp
    energy = 0.0_wp
    plastic_work = 0.0_wp
    v0 = 0.0_wp
    v = 0.0_wp
    trabe = 0.0_wp
    do g = 1, ng
      call el_shape(kind, xi(:, g), n, dn)
      call physical_derivatives(nn, x, dn, dnx(:, :, g), det)
      nsh(1:nn, g) = n(1:nn)
      dv0(g) = w(g) * det
      f(:, :, g) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 2])
      f33(g) = 1.0_wp
      do a = 1, nn
        f(1, :, g) = f(1, :, g) + u(2 * a - 1) * dnx(:, a, g)
        f(2, :, g) = f(2, :, g) + u(2 * a) * dnx(:, a, g)
      end do
      if (axisym) then
        ! r at the Gauss point; hoop stretch (r + u_r) / r
        dv0(g) = dv0(g) * two_pi * dot_product(n(1:nn), x(1, 1:nn))
        f33(g) = 1.0_wp + dot_product(n(1:nn), u(1:nd:2)) / dot_product(n(1:nn), x(1, 1:nn))
      end if
      jac(g) = (f(1, 1, g) * f(2, 2, g) - f(1, 2, g) * f(2, 1, g)) * f33(g)
      if (jac(g) <= 0.0_wp) then
        fi(1:nd) = huge(1.0_wp)
        gp_end(:, 1:ng) = 0.0_wp
        return
      end if
      v0 = v0 + dv0(g)
      v = v + jac(g) * dv0(g)
      ! trial isochoric elastic Finger tensor from Cp^-1 at the start of the step
      cpi = reshape([gp_begin(gp_plastic_strain, g) + 1.0_wp, gp_begin(gp_plastic_strain + 2, g), &
                     gp_begin(gp_plastic_strain + 2, g), gp_begin(gp_plastic_strain + 1, g) + 1.0_wp], [2, 2])
      be = matmul(f(:, :, g), matmul(cpi, transpose(f(:, :, g)))) * jac(g)**(-2.0_wp / 3.0_wp)
      be33 = (gp_begin(gp_plastic_strain + 3, g) + 1.0_wp) * f33(g)**2 * jac(g)**(-2.0_wp / 3.0_wp)
      tf(g) = (be(1, 1) + be(2, 2) + be33) / 3.0_wp
      trabe = trabe + tf(g)
      dev(:, g) = [be(1, 1) - tf(g), be(2, 2) - tf(g), be(1, 2), be33 - tf(g)]
      s = mu * dev(:, g)
      nrm = sqrt(s(1)**2 + s(2)**2 + s(4)**2 + 2.0_wp * s(3)**2)
      q = sqrt(1.5_wp) * nrm
      sy = bulk_yield_stress(mat, gp_begin(gp_p, g))
      plastic(g) = q > sy
      pnew(g) = gp_begin(gp_p, g)
      if (plastic(g)) then
        mub = mu * tf(g)
        dgam = (q - sy) / (sqrt(6.0_wp) * mub + sqrt(2.0_wp / 3.0_wp) * mat%hardening)
        s = s - 2.0_wp * mub * dgam * s / nrm
        dev(:, g) = s / mu
        pnew(g) = gp_begin(gp_p, g) + sqrt(2.0_wp / 3.0_wp) * dgam
      end if
    end do
    jm = v / v0
    pres = 0.5_wp * kb * (jm - 1.0_wp / jm)
    trabe = trabe / ng
    do g = 1, ng
      finv = reshape([f(2, 2, g), -f(2, 1, g), -f(1, 2, g), f(1, 1, g)], [2, 2]) / (jac(g) / f33(g))
      sig = mu * dev(:, g) / jac(g) + pres * [1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp]
      gp_end(:, g) = 0.0_wp
      gp_end(gp_stress:gp_stress + 3, g) = sig
      c = matmul(transpose(f(:, :, g)), f(:, :, g))
      gp_end(gp_strain:gp_strain + 3, g) = [0.5_wp * (c(1, 1) - 1.0_wp), 0.5_wp * (c(2, 2) - 1.0_wp), c(1, 2), &
                                            0.5_wp * (f33(g)**2 - 1.0_wp)]
      gp_end(gp_plastic_strain:gp_plastic_strain + 3, g) = gp_begin(gp_plastic_strain:gp_plastic_strain + 3, g)
      if (plastic(g)) then
        ! b_e = J^(2/3) (dev + mean trace), pulled back: Cp^-1 = F^-1 b_e F^-T
        bn = reshape([dev(1, g) + trabe, dev(3, g), dev(3, g), dev(2, g) + trabe], [2, 2]) * &
             jac(g)**(2.0_wp / 3.0_wp)
        cpi = matmul(finv, matmul(bn, transpose(finv)))
        gp_end(gp_plastic_strain:gp_plastic_strain + 3, g) = [cpi(1, 1) - 1.0_wp, cpi(2, 2) - 1.0_wp, cpi(1, 2), &
          (dev(4, g) + trabe) * jac(g)**(2.0_wp / 3.0_wp) / f33(g)**2 - 1.0_wp]
      end if
      gp_end(gp_p, g) = pnew(g)
      ! fi_a = integral over the current element of sigma . grad_x N_a
      rcur = 0.0_wp
      if (axisym) rcur = dot_product(nsh(1:nn, g), x(1, 1:nn) + u(1:nd:2))
      do a = 1, nn
        dndx = matmul(dnx(:, a, g), finv)
        fi(2 * a - 1) = fi(2 * a - 1) + jac(g) * dv0(g) * (sig(1) * dndx(1) + sig(3) * dndx(2))
        fi(2 * a) = fi(2 * a) + jac(g) * dv0(g) * (sig(3) * dndx(1) + sig(2) * dndx(2))
        ! hoop term sigma_tt N_a / r
        if (axisym) fi(2 * a - 1) = fi(2 * a - 1) + jac(g) * dv0(g) * sig(4) * nsh(a, g) / rcur
      end do
      energy = energy + dv0(g) * 0.5_wp * mu * (3.0_wp * tf(g) - 3.0_wp)
      plastic_work = plastic_work + dv0(g) * bulk_plastic_work(mat, gp_begin(gp_p, g), pnew(g))
    end do
    energy = energy + v0 * 0.5_wp * kb * (0.5_wp * (jm**2 - 1.0_wp) - log(jm))
  end subroutine j2_finite_forces
end module fracas_elements
