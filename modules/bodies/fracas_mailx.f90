!> Meshed 2D bodies (LMGC90's MAILx with MECAx models), stored as arrays over
!> all meshed bodies: nodes (2 dofs each), elements, Gauss-point states. This
!> module knows masses, stiffness, the θ-scheme and driven dofs; it knows
!> nothing about contacts: the solver reads the free velocities and the contact
!> compliance C = A_ff⁻¹ restricted to the nodes it needs, and gives back nodal
!> impulses (doc/architecture.md).
!>
!> The step on [t, t+h], for velocities V (end of step) and displacements X
!> from the reference configuration, is the θ-scheme
!>   M (V - Vb) = h Fext_θ - h ((1-θ) Fi(Xb) + θ Fi(X)) + r,  X = Xb + h((1-θ) Vb + θ V)
!> with Fi the internal force and r the contact impulses. It is solved by Newton
!> iterations on V (one for linear bodies): with the residual
!>   R(V) = h Fext_θ - M (V - Vb) - h ((1-θ) Fi_b + θ Fi(X(V)))
!> and A = M + h²θ² K_t (K_t the tangent stiffness at X(V)), an iteration is
!> V <- V_free + A_ff⁻¹ r, V_free = V + A_ff⁻¹ R(V), on the free dofs; a
!> velocity-driven dof holds its imposed end-of-step value throughout and
!> starts the step at its imposed value (run control driven_start).
module fracas_mailx
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use fracas_kinds, only: wp, ik, resolvable_length
  use fracas_h5, only: hid_t, h5_write_attr, h5_write_dataset
  use fracas_restart_h5, only: restart_state_t, restart_bad, restart_check_real1, restart_check_real2
  use fracas_errors, only: fatal, input_error, status_t, raise, failed
  use fracas_strings, only: itoa, rtoa, rtoa_list
  use fracas_energy, only: energy_terms_t
  use fracas_deck, only: deck_t, element_input_t, model_input_t, source_t, model_finite_strain, dof_record_t
  use fracas_drives, only: drive_t, drive_from_input, drive_value
  use fracas_elements, only: el_kind_of, el_nnodes, el_ngauss, el_mass, el_response, el_geometry_ok, el_area, &
                             el_vtk_type
  use fracas_bulk, only: bulk_t, bulk_j2, bulk_j2_finite, bulk_elastic, plane_strain, &
                         plane_stress, plane_axisym, gp_size, bulk_from_material, &
                         gp_pxx, gp_pzz, gp_p, gp_stress, gp_strain, gp_plastic_strain, plane_names
  use fracas_sparse, only: sparse_t, sparse_from_triplets, sparse_matvec
  use fracas_linear_solver, only: factor_t, factor_build, factor_update, factor_solve, factor_free, &
                                  factor_method_name, dense_spd_inverse
  implicit none
  private
  public :: mailx_t, mailx_build, mailx_free, mailx_save_state, mailx_restore_state, mailx_check_restart, mailx_set_time_step, mailx_begin_step, mailx_iterate, mailx_detection_coor, &
            mailx_velocity_from_impulses, mailx_converged, mailx_end_step, mailx_kinetic_energy, &
            mailx_require_compliance, mailx_compliance_columns, mailx_contact_set, mailx_contact_dofs, mailx_set_contact_hint, mailx_solver_summary, &
            mailx_dense_max, mailx_gauss_values, mailx_radius, mailx_energy_terms, mailx_fault, &
            mailx_dof_records, mailx_write_static, mailx_write_snapshot

  !> Bodies with at most this many dofs keep a dense inverse of A_ff (exploded
  !> elements, small meshes: the inverse is the contact compliance); larger
  !> ones a sparse factorization (see mailx_t%method).
  integer, parameter :: mailx_dense_max = 64
  !> A large body's contact compliance is computed at once on all the nodes its
  !> contactors hold when they are at most this many (a 2000 x 2000 matrix).
  integer, parameter :: compliance_cap = 1000

  !> A large body: its element-matrix triplets (pattern fixed), stiffness and
  !> consistent mass for products, the factorization of A_ff, and the contact
  !> compliance cached on a set of its nodes.
  type :: big_body_t
    integer, allocatable :: ti(:), tj(:)   !< body dofs of each element-matrix entry
    real(wp), allocatable :: kv(:), mv(:)  !< K (or tangent) and consistent M entries
    type(sparse_t) :: k, mass
    integer, allocatable :: free_of(:)     !< (ndof) index among the free dofs, 0 if driven
    type(factor_t) :: f
    logical :: factored = .false.
    real(wp), allocatable :: c(:, :)       !< compliance on its contact set (2 ns x 2 ns)
    integer, allocatable :: cnodes(:)      !< the contact set (mesh nodes), slot s <-> cnodes(s)
  end type big_body_t

  type :: mailx_t
    integer :: n = 0, nnodes = 0, nelem = 0, ngp = 0
    integer :: plane = plane_strain
    real(wp) :: h = 0.0_wp, theta = 0.5_wp, time = 0.0_wp
    real(wp) :: gravity(2) = 0.0_wp
    integer, allocatable :: node_first(:)      !< (n+1) nodes of body b: node_first(b) .. node_first(b+1)-1
    integer, allocatable :: node_body(:)       !< (nnodes)
    integer, allocatable :: elem_first(:)      !< (n+1) elements of body b
    real(wp), allocatable :: ref(:, :)         !< (2,nnodes) reference coordinates
    real(wp), allocatable :: x(:, :), xbegin(:, :)          !< displacements
    real(wp), allocatable :: v(:, :), vbegin(:, :), vfree(:, :)
    logical, allocatable :: driven(:, :)       !< (2,nnodes) velocity-driven dofs
    logical, allocatable :: movable(:)         !< (n) some dof is free
    type(drive_t), allocatable :: drives(:)    !< drive%body is the mesh node
    ! Elements: kind, material (BULK_BEHAV.DAT), bulk law (index in mats),
    ! nodes (mesh node numbers), Gauss points.
    integer, allocatable :: el_kind(:), el_mat(:), el_bulk(:), el_first(:), el_nodes(:), el_gp(:)
    !> Bulk laws: mats(k) the law of material k, mats(nmat + k) material k under
    !> a finite-strain (neoh_) model.
    type(bulk_t), allocatable :: mats(:)
    real(wp), allocatable :: gp(:, :), gp_begin(:, :)   !< (gp_size, ngp) Gauss-point states
    logical, allocatable :: nonlinear(:)       !< (n) some element is J2 or neo-Hookean: Newton iterations
    logical :: any_nonlinear = .false.
    logical, allocatable :: lumped(:)          !< (n) lumped mass
    real(wp), allocatable :: mdiag(:, :)       !< (2,nnodes) lumped mass (row sums if consistent)
    ! Forces of the step (2,nnodes): external (θ-average), internal at the start
    ! of the step and at the current iterate, Newton residual, contact impulses
    ! of the last solve, force applied by the velocity drives (end of step),
    ! inertia force M (V - V_begin) / h of the last step.
    real(wp), allocatable :: fext(:, :), fint_begin(:, :), fint(:, :), res(:, :), imp(:, :), fsupport(:, :)
    real(wp), allocatable :: finert(:, :)
    real(wp), allocatable :: tmp(:, :)         !< (2,nnodes) scratch of the body-by-body products
    ! Linear algebra per body: small bodies dense (K, consistent M, A_ff⁻¹ with
    ! zero rows and columns on driven dofs, ndof² each from dfirst(b)), large
    ! ones sparse.
    character(len=:), allocatable :: method    !< 'auto', 'dense', 'cholmod'
    logical, allocatable :: dense(:)
    integer, allocatable :: dfirst(:)
    real(wp), allocatable :: dk(:), dm(:), dinv(:)
    type(big_body_t), allocatable :: big(:)
    ! Contact compliance sets: the slot of a node in its body's set (0: none).
    ! A dense body's set is all its nodes in order and its compliance is dinv;
    ! a large body's set is big(b)%cnodes and its compliance big(b)%c.
    integer, allocatable :: cslot(:)
    logical, allocatable :: contact_hint(:)    !< (nnodes) a contactor holds the node
    real(wp), allocatable :: eel(:), wpl(:)    !< (n) elastic energy and plastic work of the last element loop
    ! Energy (per unit thickness)
    real(wp) :: kinetic0 = 0.0_wp, elastic = 0.0_wp, plastic_work = 0.0_wp
    real(wp) :: work_gravity = 0.0_wp, work_forces = 0.0_wp, work_supports = 0.0_wp
    integer :: iterations = 0                  !< Newton iterations of the last step
    logical :: newton_converged = .true.       !< the last step's Newton loop met its tolerance
    logical :: driven_start_imposed = .true.   !< a driven dof starts a step at its imposed value
  end type mailx_t

contains

  !> Build the meshed bodies of the deck (model 'MAILx', numbered in deck order)
  !> in their initial state (DOF.INI), factorize their iteration matrices.
  subroutine mailx_build(deck, m, h, theta)
    type(deck_t), intent(in) :: deck
    type(mailx_t), intent(out) :: m
    real(wp), intent(in) :: h, theta
    integer :: ib, b, nn, ne, ie, k, j, nel_nodes, ng, imat, kind, node, nlaw
    logical, allocatable :: used(:)
    real(wp) :: extent
    m%h = h
    m%theta = theta
    m%time = deck%dof_time
    m%gravity = deck%gravity(1:2)
    select case (deck%run%plane)
    case ('stress')
      m%plane = plane_stress
    case ('axisym')
      m%plane = plane_axisym
    case default
      m%plane = plane_strain
    end select
    m%method = trim(deck%run%linear_solver)
    ! LMGC90 starts a driven node of a mesh from its previous velocity (lmgc90):
    ! its examples' driven nodes move theta h v in the first step (4T3 exploded).
    m%driven_start_imposed = deck%run%driven_start == 'imposed'
    m%n = count(deck%bodies%model == 'MAILx')
    allocate (m%node_first(m%n + 1), m%elem_first(m%n + 1))
    nn = 0; ne = 0; nel_nodes = 0; ng = 0; b = 0
    m%node_first(1) = 1
    m%elem_first(1) = 1
    do ib = 1, size(deck%bodies)
      associate (bd => deck%bodies(ib))
        if (bd%model /= 'MAILx') cycle
        b = b + 1
        nn = nn + size(bd%node_coor, 2)
        ne = ne + size(bd%elements)
        do ie = 1, size(bd%elements)
          kind = element_kind(deck, bd%elements(ie))
          nel_nodes = nel_nodes + el_nnodes(kind)
          ng = ng + el_ngauss(kind)
        end do
        m%node_first(b + 1) = nn + 1
        m%elem_first(b + 1) = ne + 1
      end associate
    end do
    m%nnodes = nn; m%nelem = ne; m%ngp = ng
    allocate (m%node_body(nn), m%ref(2, nn), m%x(2, nn), m%xbegin(2, nn), m%v(2, nn), m%vbegin(2, nn), &
              m%vfree(2, nn), m%driven(2, nn), m%movable(m%n), m%el_kind(ne), m%el_mat(ne), m%el_bulk(ne), &
              m%el_first(ne + 1), &
              m%el_nodes(nel_nodes), m%el_gp(ne + 1), m%gp(gp_size, ng), m%gp_begin(gp_size, ng), &
              m%nonlinear(m%n), m%lumped(m%n), m%mdiag(2, nn), m%fext(2, nn), m%fint_begin(2, nn), &
              m%fint(2, nn), m%res(2, nn), m%imp(2, nn), m%fsupport(2, nn), m%finert(2, nn), m%tmp(2, nn))
    m%x = 0.0_wp; m%v = 0.0_wp; m%vfree = 0.0_wp
    m%driven = .false.
    m%gp = 0.0_wp
    m%fext = 0.0_wp; m%fint = 0.0_wp; m%res = 0.0_wp; m%imp = 0.0_wp; m%fsupport = 0.0_wp; m%finert = 0.0_wp
    ! Bulk laws of the materials meshes use (others may be RIGID).
    allocate (m%mats(2 * size(deck%materials)), used(2 * size(deck%materials)))
    used = .false.
    b = 0
    ne = 0
    m%el_first(1) = 1
    m%el_gp(1) = 1
    do ib = 1, size(deck%bodies)
      associate (bd => deck%bodies(ib))
        if (bd%model /= 'MAILx') cycle
        b = b + 1
        m%node_body(m%node_first(b):m%node_first(b + 1) - 1) = b
        m%ref(:, m%node_first(b):m%node_first(b + 1) - 1) = bd%node_coor
        m%nonlinear(b) = .false.
        m%lumped(b) = .true.
        extent = norm2(maxval(bd%node_coor, dim=2) - minval(bd%node_coor, dim=2))
        do ie = 1, size(bd%elements)
          ne = ne + 1
          associate (el => bd%elements(ie))
            m%el_kind(ne) = element_kind(deck, el)
            imat = 0
            do k = 1, size(deck%materials)
              if (deck%materials(k)%nickname == el%behav) imat = k
            end do
            if (imat == 0) call input_error(el%src%file, el%src%line, 37, "material '"//el%behav// &
              "' is not defined in BULK_BEHAV.DAT")
            m%el_mat(ne) = imat
            k = model_index(deck%models, el%model)
            if (deck%models(k)%mass_storage == 'coher') m%lumped(b) = .false.
            ! A material's law under a finite-strain model is kept apart.
            nlaw = imat
            if (model_finite_strain(deck%models(k))) then
              nlaw = imat + size(deck%materials)
              if (m%plane == plane_stress) call input_error(deck%models(k)%src%file, deck%models(k)%src%line, 2, &
                "model '"//trim(deck%models(k)%nickname)//"' (mater "//deck%models(k)%material// &
                ', finite strain) runs in plane strain only, as in LMGC90; the run control asks for plane stress')
            end if
            if (.not. used(nlaw)) m%mats(nlaw) = bulk_from_material(deck%materials(imat), deck%models(k))
            ! Axisymmetry: LMGC90's finite-strain J2 (Q4P0x) only so far, and no mesh contactors.
            if (m%plane == plane_axisym .and. m%mats(nlaw)%law /= bulk_j2_finite) call input_error(el%src%file, &
              el%src%line, 23, "run control 'plane axisym': Fracas runs axisymmetric meshes with LMGC90's "// &
              "finite-strain J2 model only (kine_ large, mater J2iso, Q4P0x); model '"//trim(el%model)//"' is not")
            if (m%plane == plane_axisym .and. size(bd%tactors) > 0) call input_error(bd%src%file, bd%src%line, 0, &
              "run control 'plane axisym': axisymmetric meshes with contactors are not supported (contacts are "// &
              'planar)')
            used(nlaw) = .true.
            m%el_bulk(ne) = nlaw
            if (m%mats(nlaw)%law /= bulk_elastic) m%nonlinear(b) = .true.
            if (size(el%nodes) /= el_nnodes(m%el_kind(ne))) call input_error(el%src%file, el%src%line, 16, &
              'element has the wrong number of nodes for its type')
            do j = 1, size(el%nodes)
              if (el%nodes(j) < 1 .or. el%nodes(j) > size(bd%node_coor, 2)) call input_error(el%src%file, &
                el%src%line, 16, 'element node number out of range for this body')
            end do
            call check_element_geometry(m%el_kind(ne), bd%node_coor(:, el%nodes), extent, el%src%file, el%src%line)
            m%el_nodes(m%el_first(ne):m%el_first(ne) + size(el%nodes) - 1) = m%node_first(b) - 1 + el%nodes
            m%el_first(ne + 1) = m%el_first(ne) + size(el%nodes)
            m%el_gp(ne + 1) = m%el_gp(ne) + el_ngauss(m%el_kind(ne))
          end associate
        end do
      end associate
    end do
    m%any_nonlinear = any(m%nonlinear)
    ! Drives on mesh nodes
    allocate (m%drives(count(deck%driven%model == 'MAILx')))
    j = 0
    do k = 1, size(deck%driven)
      associate (d => deck%driven(k))
        if (d%model /= 'MAILx') cycle
        node = mesh_node(d%body, d%node, d%src%file, d%src%line)
        if (d%dof < 1 .or. d%dof > 2) call input_error(d%src%file, d%src%line, 9, 'a mesh node has dofs 1 and 2')
        j = j + 1
        m%drives(j) = drive_from_input(d, node)
        if (d%kind == 'vlocy') m%driven(d%dof, node) = .true.
      end associate
    end do
    do b = 1, m%n
      m%movable(b) = .not. all(m%driven(:, m%node_first(b):m%node_first(b + 1) - 1))
    end do
    ! Initial state from DOF.INI (nodes not listed start at rest).
    m%xbegin = 0.0_wp
    m%vbegin = 0.0_wp
    do k = 1, size(deck%dof_ini)
      associate (d => deck%dof_ini(k))
        if (d%model /= 'MAILx') cycle
        do j = 1, size(d%nodes)
          node = mesh_node(d%body, d%nodes(j), d%src%file, d%src%line)
          m%xbegin(:, node) = d%node_x(:, j)
          m%vbegin(:, node) = d%node_v(:, j)
        end do
      end associate
    end do
    m%x = m%xbegin
    m%v = m%vbegin
    ! Mass, stiffness and internal forces at the initial displacement, from the
    ! plastic state of GPV.INI (elastic bodies need none: their stresses follow
    ! from the displacements).
    m%gp_begin = 0.0_wp
    call restore_plastic_state(m, deck)
    call assemble_all(m)
    m%fint_begin = m%fint
    m%gp_begin = m%gp
    m%elastic = elastic_energy(m)
    m%kinetic0 = mailx_kinetic_energy(m)
    b = 0
    do ib = 1, size(deck%bodies)
      if (deck%bodies(ib)%model /= 'MAILx') cycle
      b = b + 1
      ! Coordinates, material values or a time step beyond double precision make
      ! M + h²θ²K overflow: say so at the body rather than as a failed factorization.
      if (.not. iteration_matrix_finite(m, b)) call input_error(deck%bodies(ib)%src%file, &
        deck%bodies(ib)%src%line, 0, 'MAILx body '//itoa(b)//': its iteration matrix M + (h theta)^2 K '// &
        'is not finite (node coordinates, density, Young''s modulus or time step beyond double precision)')
      ! A free node of no element has a zero row in M + (h theta)^2 K: singular.
      node = orphan_node(b)
      if (node > 0) call input_error(deck%bodies(ib)%src%file, deck%bodies(ib)%src%line, 0, 'MAILx body '// &
        itoa(b)//': node '//itoa(node)//' belongs to no element and is not driven: it has no mass and no '// &
        'stiffness (its row of the iteration matrix is zero); give it an element, drive both its dofs or remove it')
      call factorize_body(m, b, deck%bodies(ib)%src)
    end do
    call compliance_sets_init(m)

  contains

    !> The first node (numbered in its body) of body b with a free dof that no element uses, 0 if none.
    integer function orphan_node(b)
      integer, intent(in) :: b
      logical, allocatable :: in_element(:)
      integer :: e, n1, k
      n1 = m%node_first(b)
      allocate (in_element(n1:m%node_first(b + 1) - 1))
      in_element = .false.
      do e = m%elem_first(b), m%elem_first(b + 1) - 1
        in_element(m%el_nodes(m%el_first(e):m%el_first(e + 1) - 1)) = .true.
      end do
      orphan_node = 0
      do k = n1, m%node_first(b + 1) - 1
        if (.not. in_element(k) .and. .not. all(m%driven(:, k))) then
          orphan_node = k - n1 + 1
          return
        end if
      end do
    end function orphan_node

    !> Mesh node number of node `node` of MAILx body `body`, or an input error.
    integer function mesh_node(body, node, file, line)
      integer, intent(in) :: body, node, line
      character(len=*), intent(in) :: file
      if (body < 1 .or. body > m%n) call input_error(file, line, 9, 'MAILx body number out of range')
      mesh_node = m%node_first(body) - 1 + node
      if (node < 1 .or. mesh_node >= m%node_first(body + 1)) &
        call input_error(file, line, 9, 'node number out of range for this MAILx body')
    end function mesh_node
  end subroutine mailx_build

  !> Plastic strain and cumulative plastic strain of J2 elements from GPV.INI:
  !> the internals line Fracas writes (plastic strain xx, yy, γxy, zz, p, von
  !> Mises), or LMGC90's Q4P0x line (Cp⁻¹ 11, 22, 12, 33, p, von Mises), whose
  !> finite-strain Cp⁻¹ ≈ I − 2 ε_p is taken to first order by small-strain J2;
  !> finite-strain J2 keeps Cp⁻¹ (as Cp⁻¹ − I).
  subroutine restore_plastic_state(m, deck)
    type(mailx_t), intent(inout) :: m
    type(deck_t), intent(in) :: deck
    integer :: k, e, g, ng, law
    real(wp) :: v(6)
    do k = 1, size(deck%gpv_ini)
      associate (r => deck%gpv_ini(k))
        if (r%body < 1 .or. r%body > m%n) call input_error(r%src%file, r%src%line, 9, &
          'GPV.INI: MAILx body number out of range')
        e = m%elem_first(r%body) - 1 + r%element
        if (r%element < 1 .or. e >= m%elem_first(r%body + 1)) call input_error(r%src%file, r%src%line, 9, &
          'GPV.INI: element number out of range for this MAILx body')
        law = m%mats(m%el_bulk(e))%law
        if ((law /= bulk_j2 .and. law /= bulk_j2_finite) .or. size(r%values, 1) < 14) cycle
        ng = m%el_gp(e + 1) - m%el_gp(e)
        do g = 1, ng
          v = r%values(9:14, min(g, size(r%values, 2)))
          if (law == bulk_j2_finite) then
            ! Cp^-1 itself, kept as Cp^-1 - I (a zero state is the virgin one)
            v(1:4) = v(1:4) - [1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp]
          else if (abs(v(1) - 1.0_wp) < 0.5_wp .and. abs(v(2) - 1.0_wp) < 0.5_wp) then   ! LMGC90's Cp^-1
            v(1:4) = [0.5_wp * (1.0_wp - v(1)), 0.5_wp * (1.0_wp - v(2)), -v(3), 0.5_wp * (1.0_wp - v(4))]
          end if
          m%gp_begin(gp_pxx:gp_pzz, m%el_gp(e) + g - 1) = v(1:4)
          m%gp_begin(gp_p, m%el_gp(e) + g - 1) = v(5)
        end do
      end associate
    end do
  end subroutine restore_plastic_state

  !> Element kind of an element line: its model may name the element (LMGC90
  !> writes Q4xxx geometry with a Q4P0x model).
  integer function element_kind(deck, el)
    type(deck_t), intent(in) :: deck
    type(element_input_t), intent(in) :: el
    integer :: imod
    imod = model_index(deck%models, el%model)
    if (imod == 0) call input_error(el%src%file, el%src%line, 23, "model '"//el%model// &
      "' is not defined in MODELS.DAT")
    element_kind = el_kind_of(deck%models(imod)%element)
    if (element_kind == 0) element_kind = el_kind_of(el%kind)
    if (element_kind == 0) call input_error(el%src%file, el%src%line, 2, "element type '"//el%kind// &
      "' is not supported (T3xxx, Q4xxx, T6xxx, Q8xxx; model element Q4P0x)")
  end function element_kind

  integer function model_index(models, name)
    type(model_input_t), intent(in) :: models(:)
    character(len=*), intent(in) :: name
    integer :: k
    model_index = 0
    do k = 1, size(models)
      if (models(k)%nickname == name) model_index = k
    end do
  end function model_index


  !> Size of body b as a rigid body's radius: half the diagonal of the box
  !> around its reference nodes (the state guard's scale for what double
  !> precision resolves at the body).
  pure real(wp) function mailx_radius(m, b) result(r)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: b
    associate (x => m%ref(:, m%node_first(b):m%node_first(b + 1) - 1))
      r = 0.5_wp * norm2(maxval(x, dim=2) - minval(x, dim=2))
    end associate
  end function mailx_radius

  !> Degrees of freedom of body b: 2 per node (x, y), in node order.
  pure integer function body_ndof(m, b)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: b
    body_ndof = 2 * (m%node_first(b + 1) - m%node_first(b))
  end function body_ndof

  !> Storage of each body (dense if small, see method), mass, stiffness and
  !> internal forces at the initial displacements.
  subroutine assemble_all(m)
    type(mailx_t), intent(inout) :: m
    integer :: b, nd, total
    allocate (m%dense(m%n), m%dfirst(m%n + 1), m%big(m%n), m%eel(m%n), m%wpl(m%n))
    total = 0
    do b = 1, m%n
      nd = body_ndof(m, b)
      select case (m%method)
      case ('dense')
        m%dense(b) = .true.
      case ('cholmod')
        m%dense(b) = .false.
      case default
        m%dense(b) = nd <= mailx_dense_max
      end select
      m%dfirst(b) = total
      if (m%dense(b)) total = total + nd * nd
    end do
    m%dfirst(m%n + 1) = total
    allocate (m%dk(total), m%dm(total), m%dinv(total))
    m%dm = 0.0_wp
    m%dinv = 0.0_wp
    m%mdiag = 0.0_wp
    do b = 1, m%n
      call assemble_body(m, b, m%xbegin, with_mass=.true.)
    end do
  end subroutine assemble_all

  !> Element loop of body b at displacements u: stiffness or tangent (and with
  !> with_mass the mass), internal forces m%fint and Gauss-point states m%gp
  !> (from m%gp_begin) of the body.
  subroutine assemble_body(m, b, u, with_mass, status)
    type(mailx_t), intent(inout) :: m
    integer, intent(in) :: b
    real(wp), intent(in) :: u(:, :)
    logical, intent(in) :: with_mass
    type(status_t), intent(inout), optional :: status   !< an element turned inside out
    integer :: e, nn, nd, i, j, k, cnt, base
    real(wp), allocatable :: me(:, :), ke(:, :), fi(:), xe(:, :), ue(:)
    integer, allocatable :: dofs(:)
    real(wp) :: eel, wpl
    nd = body_ndof(m, b)
    base = m%dfirst(b)
    if (m%dense(b)) then
      m%dk(base + 1:base + nd * nd) = 0.0_wp
    else
      cnt = 0
      do e = m%elem_first(b), m%elem_first(b + 1) - 1
        cnt = cnt + (2 * el_nnodes(m%el_kind(e)))**2
      end do
      associate (bb => m%big(b))
        if (.not. allocated(bb%ti)) allocate (bb%ti(cnt), bb%tj(cnt), bb%kv(cnt), bb%mv(cnt))
        bb%kv = 0.0_wp
        if (with_mass) bb%mv = 0.0_wp
      end associate
      cnt = 0
    end if
    m%fint(:, m%node_first(b):m%node_first(b + 1) - 1) = 0.0_wp
    m%eel(b) = 0.0_wp
    m%wpl(b) = 0.0_wp
    do e = m%elem_first(b), m%elem_first(b + 1) - 1
      nn = el_nnodes(m%el_kind(e))
      call element_data(m, e, b, u, xe, ue, dofs)
      allocate (ke(2 * nn, 2 * nn), fi(2 * nn), me(2 * nn, 2 * nn))
      call el_response(m%el_kind(e), xe, ue, m%mats(m%el_bulk(e)), m%plane, &
                       m%gp_begin(:, m%el_gp(e):m%el_gp(e + 1) - 1), m%gp(:, m%el_gp(e):m%el_gp(e + 1) - 1), &
                       fi, ke, .true., eel, wpl)
      ! finite-strain elements say J <= 0 at a Gauss point with fi = huge
      if (any(fi >= huge(1.0_wp))) then
        call raise(status, 'MAILx body '//itoa(b)//': element '//itoa(e - m%elem_first(b) + 1)// &
                   ' turned inside out (det F <= 0 at a Gauss point): the step is too large for this deformation')
        return
      end if
      m%eel(b) = m%eel(b) + eel
      m%wpl(b) = m%wpl(b) + wpl
      do i = 1, nn
        k = m%el_nodes(m%el_first(e) + i - 1)
        m%fint(:, k) = m%fint(:, k) + fi(2 * i - 1:2 * i)
      end do
      me = 0.0_wp
      if (with_mass) then
        call el_mass(m%el_kind(e), xe, m%mats(m%el_bulk(e))%density, m%lumped(b), me, m%plane == plane_axisym)
        do i = 1, nn
          k = m%el_nodes(m%el_first(e) + i - 1)
          m%mdiag(1, k) = m%mdiag(1, k) + sum(me(2 * i - 1, :))
          m%mdiag(2, k) = m%mdiag(2, k) + sum(me(2 * i, :))
        end do
      end if
      do j = 1, 2 * nn
        do i = 1, 2 * nn
          if (m%dense(b)) then
            k = base + dofs(i) + nd * (dofs(j) - 1)
            m%dk(k) = m%dk(k) + ke(i, j)
            if (with_mass .and. .not. m%lumped(b)) m%dm(k) = m%dm(k) + me(i, j)
          else
            cnt = cnt + 1
            m%big(b)%ti(cnt) = dofs(i)
            m%big(b)%tj(cnt) = dofs(j)
            m%big(b)%kv(cnt) = ke(i, j)
            if (with_mass) m%big(b)%mv(cnt) = me(i, j)
          end if
        end do
      end do
      deallocate (ke, fi, me)
    end do
    if (.not. m%dense(b)) then
      associate (bb => m%big(b))
        call sparse_from_triplets(nd, bb%ti, bb%tj, bb%kv, bb%k)
        if (with_mass .and. .not. m%lumped(b)) call sparse_from_triplets(nd, bb%ti, bb%tj, bb%mv, bb%mass)
      end associate
    end if
  end subroutine assemble_body

  !> Coordinates, displacements and dof numbers within body b of element e.
  subroutine element_data(m, e, b, u, xe, ue, dofs)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: e, b
    real(wp), intent(in) :: u(:, :)
    real(wp), allocatable, intent(out) :: xe(:, :), ue(:)
    integer, allocatable, intent(out) :: dofs(:)
    integer :: nn, i, k, n0
    nn = el_nnodes(m%el_kind(e))
    n0 = m%node_first(b) - 1
    allocate (xe(2, nn), ue(2 * nn), dofs(2 * nn))
    do i = 1, nn
      k = m%el_nodes(m%el_first(e) + i - 1)
      xe(:, i) = m%ref(:, k)
      ue(2 * i - 1:2 * i) = u(:, k)
      dofs(2 * i - 1) = 2 * (k - n0) - 1
      dofs(2 * i) = 2 * (k - n0)
    end do
  end subroutine element_data

  !> m%fint = internal forces at displacements u: linear bodies by their stored
  !> stiffness, nonlinear ones by their elements (Gauss-point states in m%gp,
  !> tangent reassembled and A_ff refactorized).
  subroutine internal_forces(m, u, status)
    type(mailx_t), intent(inout) :: m
    real(wp), intent(in) :: u(:, :)
    type(status_t), intent(inout), optional :: status
    integer :: b, i1, i2
    do b = 1, m%n
      i1 = m%node_first(b); i2 = m%node_first(b + 1) - 1
      if (m%nonlinear(b)) then
        call assemble_body(m, b, u, with_mass=.false., status=status)
        if (failed(status)) return
        call factorize_body(m, b, status=status)
        if (failed(status)) return
      else
        call body_k_times(m, b, 2 * (i2 - i1 + 1), u(:, i1:i2), m%fint(:, i1:i2))
      end if
    end do
  end subroutine internal_forces

  !> y = K u on body b (u, y: its nodes' (x, y) pairs, nd = 2 x nodes; the
  !> callers pass columns of the node arrays, contiguous: no copies).
  subroutine body_k_times(m, b, nd, u, y)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: b, nd
    real(wp), intent(in) :: u(nd)
    real(wp), intent(out) :: y(nd)
    if (m%dense(b)) then
      call dense_times(m%dk(m%dfirst(b) + 1), nd, u, y)
    else
      call sparse_matvec(m%big(b)%k, u, y)
    end if
  end subroutine body_k_times

  !> y = M v on body b (as body_k_times).
  subroutine body_m_times(m, b, nd, v, y)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: b, nd
    real(wp), intent(in) :: v(nd)
    real(wp), intent(out) :: y(nd)
    integer :: i, n0
    if (m%lumped(b)) then
      n0 = m%node_first(b) - 1
      do i = 1, nd
        y(i) = m%mdiag(2 - mod(i, 2), n0 + (i + 1) / 2) * v(i)
      end do
    else if (m%dense(b)) then
      call dense_times(m%dm(m%dfirst(b) + 1), nd, v, y)
    else
      call sparse_matvec(m%big(b)%mass, v, y)
    end if
  end subroutine body_m_times

  pure subroutine dense_times(a, n, x, y)
    integer, intent(in) :: n
    real(wp), intent(in) :: a(n, n), x(n)
    real(wp), intent(out) :: y(n)
    integer :: j
    y = 0.0_wp
    do j = 1, n
      y = y + a(:, j) * x(j)
    end do
  end subroutine dense_times

  !> Factorize A_ff = M_ff + h²θ² K_ff of body b: the dense inverse, or the
  !> sparse factorization (numeric refactorization once the pattern is known).
  !> A matrix that does not factorize: status (the message names the body), or
  !> the run stops.
  subroutine factorize_body(m, b, src, status)
    type(mailx_t), intent(inout) :: m
    integer, intent(in) :: b
    type(source_t), intent(in), optional :: src   !< the body's deck line: a failure there is an input error
    type(status_t), intent(inout), optional :: status
    integer :: nd, nf, i, j, k, n0, minor
    character(len=:), allocatable :: at
    integer, allocatable :: fidx(:), ti(:), tj(:)
    real(wp), allocatable :: a(:, :), ai(:, :), av(:)
    type(sparse_t) :: aff
    real(wp) :: c2
    type(status_t) :: st
    nd = body_ndof(m, b)
    n0 = m%node_first(b)
    fidx = pack([(i, i=1, nd)], .not. reshape(m%driven(:, n0:m%node_first(b + 1) - 1), [nd]))
    nf = size(fidx)
    c2 = (m%h * m%theta)**2
    if (nf > 0 .and. all(m%mdiag(:, n0:m%node_first(b + 1) - 1) == 0.0_wp)) call check_massless_held(m, b, src)
    if (m%dense(b)) then
      a = c2 * reshape(m%dk(m%dfirst(b) + 1:m%dfirst(b) + nd * nd), [nd, nd])
      if (m%lumped(b)) then
        do i = 1, nd
          a(i, i) = a(i, i) + m%mdiag(2 - mod(i, 2), n0 + (i - 1) / 2)
        end do
      else
        a = a + reshape(m%dm(m%dfirst(b) + 1:m%dfirst(b) + nd * nd), [nd, nd])
      end if
      m%dinv(m%dfirst(b) + 1:m%dfirst(b) + nd * nd) = 0.0_wp
      if (nf > 0) then
        ai = a(fidx, fidx)
        call dense_spd_inverse(ai, st, minor)
        if (.not. st%ok) then
          at = ''
          if (minor > 0) at = ' at node '//itoa((fidx(minor) - 1) / 2 + 1)//' dof '//itoa(2 - mod(fidx(minor), 2))// &
                                 ' (leading minor '//itoa(minor)//' of '//itoa(nf)//')'
          at = 'MAILx body '//itoa(b)//': its iteration matrix M + (h theta)^2 K is not positive definite'// &
               at//' (a density, Young''s modulus or time step out of proportion with the others?)'
          if (present(src)) call input_error(src%file, src%line, 0, at)
          call raise(status, at)
          return
        end if
        do j = 1, nf
          do i = 1, nf
            m%dinv(m%dfirst(b) + fidx(i) + nd * (fidx(j) - 1)) = ai(i, j)
          end do
        end do
      end if
      return
    end if
    associate (bb => m%big(b))
      if (.not. allocated(bb%free_of)) then
        allocate (bb%free_of(nd))
        bb%free_of = 0
        do i = 1, nf
          bb%free_of(fidx(i)) = i
        end do
      end if
      ! A_ff from the element triplets restricted to the free dofs, plus the
      ! lumped mass on the diagonal.
      allocate (ti(size(bb%ti) + nf), tj(size(bb%ti) + nf), av(size(bb%ti) + nf))
      k = 0
      do i = 1, size(bb%ti)
        if (bb%free_of(bb%ti(i)) == 0 .or. bb%free_of(bb%tj(i)) == 0) cycle
        k = k + 1
        ti(k) = bb%free_of(bb%ti(i)); tj(k) = bb%free_of(bb%tj(i))
        av(k) = c2 * bb%kv(i)
        if (.not. m%lumped(b)) av(k) = av(k) + bb%mv(i)
      end do
      do i = 1, nf
        k = k + 1
        ti(k) = i; tj(k) = i
        av(k) = 0.0_wp
        if (m%lumped(b)) av(k) = m%mdiag(2 - mod(fidx(i), 2), n0 + (fidx(i) - 1) / 2)
      end do
      call sparse_from_triplets(nf, ti(1:k), tj(1:k), av(1:k), aff)
      if (bb%factored) then
        call factor_update(bb%f, aff, st)
      else
        call factor_build(bb%f, aff, merge('cholmod', 'auto   ', m%method == 'cholmod'), status=st)
        bb%factored = .true.
      end if
      if (.not. st%ok) then
        call raise(status, 'MAILx body '//itoa(b)//' (iteration matrix M + (h theta)^2 K): '//st%message)
        return
      end if
      ! The cached compliance is stale once A changes.
      if (allocated(bb%c)) deallocate (bb%c)
    end associate
  end subroutine factorize_body

  !> A massless (quasi-static) body is solved by its stiffness alone: its driven
  !> dofs must hold its three rigid motions (two translations, the rotation), else
  !> K_ff is singular (a Cholesky of round-off pivots would pass silently).
  subroutine check_massless_held(m, b, src)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: b
    type(source_t), intent(in), optional :: src
    real(wp) :: g(3, 3), r(3), c(2), d(2), scale, det
    integer :: k, j
    character(len=:), allocatable :: msg
    c = sum(m%ref(:, m%node_first(b):m%node_first(b + 1) - 1), dim=2) / (m%node_first(b + 1) - m%node_first(b))
    scale = 0.0_wp
    g = 0.0_wp
    do k = m%node_first(b), m%node_first(b + 1) - 1
      d = m%ref(:, k) - c
      scale = max(scale, norm2(d))
      do j = 1, 2
        if (.not. m%driven(j, k)) cycle
        ! the driven dof's value in the rigid modes x-translation, y-translation, rotation
        r = [merge(1.0_wp, 0.0_wp, j == 1), merge(1.0_wp, 0.0_wp, j == 2), merge(-d(2), d(1), j == 1)]
        g = g + spread(r, 2, 3) * spread(r, 1, 3)
      end do
    end do
    if (scale > 0.0_wp) then
      g(3, :) = g(3, :) / scale; g(:, 3) = g(:, 3) / scale
    end if
    det = g(1, 1) * (g(2, 2) * g(3, 3) - g(2, 3) * g(3, 2)) - g(1, 2) * (g(2, 1) * g(3, 3) - g(2, 3) * g(3, 1)) + &
          g(1, 3) * (g(2, 1) * g(3, 2) - g(2, 2) * g(3, 1))
    if (det > 1.0e-10_wp * max(g(1, 1) * g(2, 2) * g(3, 3), tiny(1.0_wp))) return
    msg = 'MAILx body '//itoa(b)//' is massless (density 0: quasi-static) and its driven dofs leave a rigid '// &
          'motion free: drive enough dofs to hold both translations and the rotation'
    if (present(src)) call input_error(src%file, src%line, 0, msg)
    call fatal(msg)
  end subroutine check_massless_held

  !> An element must be counter-clockwise with a positive Jacobian everywhere,
  !> and not so small against its body's extent that double precision cannot
  !> resolve it (its size below 1e-10 of the extent: node coordinates then
  !> carry fewer than 6 significant digits of the element).
  subroutine check_element_geometry(kind, x, extent, file, line)
    integer, intent(in) :: kind, line
    real(wp), intent(in) :: x(:, :), extent
    character(len=*), intent(in) :: file
    real(wp) :: size_el
    if (.not. all(ieee_is_finite(x))) call input_error(file, line, 0, 'element has non-finite node coordinates')
    if (.not. el_geometry_ok(kind, x)) call input_error(file, line, 0, 'element is inverted or degenerate '// &
      '(its Jacobian is not positive everywhere): list its nodes counter-clockwise, corners first')
    size_el = sqrt(el_area(kind, x))
    if (.not. (size_el >= 1.0e-10_wp * extent)) call input_error(file, line, 0, 'element of size '// &
      rtoa(size_el)//' in a body '//rtoa(extent)//' across: beyond what double precision resolves '// &
      '(a node far from the others?)')
  end subroutine check_element_geometry

  !> Are the entries of body b's iteration matrix M + (h θ)² K all finite? Decided
  !> on magnitudes (in logarithms), so the test itself never overflows.
  logical function iteration_matrix_finite(m, b) result(ok)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: b
    real(wp) :: kmax, mmax, limit
    ok = all(ieee_is_finite(m%mdiag(:, m%node_first(b):m%node_first(b + 1) - 1)))
    if (m%dense(b)) then
      ok = ok .and. all(ieee_is_finite(m%dk(m%dfirst(b) + 1:m%dfirst(b + 1)))) .and. &
           all(ieee_is_finite(m%dm(m%dfirst(b) + 1:m%dfirst(b + 1))))
      if (.not. ok) return
      kmax = max(0.0_wp, maxval(abs(m%dk(m%dfirst(b) + 1:m%dfirst(b + 1)))))
      mmax = max(0.0_wp, maxval(abs(m%dm(m%dfirst(b) + 1:m%dfirst(b + 1)))))
    else
      ok = ok .and. all(ieee_is_finite(m%big(b)%kv)) .and. all(ieee_is_finite(m%big(b)%mv))
      if (.not. ok) return
      kmax = max(0.0_wp, maxval(abs(m%big(b)%kv)))
      mmax = max(0.0_wp, maxval(abs(m%big(b)%mv)))
    end if
    mmax = max(mmax, max(0.0_wp, maxval(m%mdiag(:, m%node_first(b):m%node_first(b + 1) - 1))))
    ! (h θ)² kmax + mmax < huge, with a factor 4 of room for the sums of the solves.
    limit = log(huge(1.0_wp)) - log(4.0_wp)
    ok = log(max(mmax, tiny(1.0_wp))) < limit
    if (kmax > 0.0_wp) ok = ok .and. 2.0_wp * log(m%h * m%theta) + log(kmax) < limit
  end function iteration_matrix_finite

  !> x := A_ff⁻¹ x on body b (x as in body_k_times; driven dofs of x are
  !> ignored on input and zero on output).
  subroutine body_solve(m, b, nd, x, status)
    type(mailx_t), intent(inout) :: m
    integer, intent(in) :: b, nd
    real(wp), intent(inout) :: x(nd)
    type(status_t), intent(inout), optional :: status
    integer :: i
    real(wp) :: y(nd)
    real(wp), allocatable :: xf(:)
    type(status_t) :: st
    if (m%dense(b)) then
      call dense_times(m%dinv(m%dfirst(b) + 1), nd, x, y)
      x = y
    else
      associate (bb => m%big(b))
        xf = pack(x, bb%free_of > 0)
        call factor_solve(m%big(b)%f, xf, st)
        if (.not. st%ok) then
          call raise(status, 'MAILx body '//itoa(b)//': '//st%message)
          return
        end if
        do i = 1, nd
          x(i) = 0.0_wp
          if (bb%free_of(i) > 0) x(i) = xf(bb%free_of(i))
        end do
      end associate
    end if
  end subroutine body_solve

  !> Start of a step [t, t+h]: external forces (gravity, θ-averaged driven
  !> forces), the first iterate (begin velocities, driven dofs at their imposed
  !> end value) and its free velocity. A body whose matrix does not factorize:
  !> status, or the run stops.
  subroutine mailx_begin_step(m, t, status)
    type(mailx_t), intent(inout) :: m
    real(wp), intent(in) :: t
    type(status_t), intent(inout), optional :: status
    integer :: k, b, i1, i2
    real(wp) :: e_before
    logical :: jump
    m%time = t
    m%iterations = 0
    m%tmp(1, :) = m%gravity(1)
    m%tmp(2, :) = m%gravity(2)
    do b = 1, m%n
      i1 = m%node_first(b); i2 = m%node_first(b + 1) - 1
      call body_m_times(m, b, 2 * (i2 - i1 + 1), m%tmp(:, i1:i2), m%fext(:, i1:i2))
    end do
    jump = .false.
    do k = 1, size(m%drives)
      associate (d => m%drives(k))
        if (d%is_velocity) jump = jump .or. m%vbegin(d%dof, d%body) /= drive_value(d, t)
      end associate
    end do
    if (m%driven_start_imposed .and. jump) then
      ! The supports set a driven dof to its imposed value at the start of the step
      ! (LMGC90's rule; usually it is there already): the kinetic energy that adds
      ! is work of the supports.
      m%v = m%vbegin
      e_before = mailx_kinetic_energy(m)
      do k = 1, size(m%drives)
        associate (d => m%drives(k))
          if (d%is_velocity) m%vbegin(d%dof, d%body) = drive_value(d, t)
        end associate
      end do
      m%v = m%vbegin
      m%work_supports = m%work_supports + mailx_kinetic_energy(m) - e_before
    end if
    m%v = m%vbegin
    do k = 1, size(m%drives)
      associate (d => m%drives(k))
        if (d%is_velocity) then
          m%v(d%dof, d%body) = drive_value(d, t + m%h)
        else
          m%fext(d%dof, d%body) = m%fext(d%dof, d%body) + &
            (1.0_wp - m%theta) * drive_value(d, t) + m%theta * drive_value(d, t + m%h)
        end if
      end associate
    end do
    m%imp = 0.0_wp
    call mailx_iterate(m, status)
  end subroutine mailx_begin_step

  !> Newton iterate at the current velocities m%v: the residual R(V), and the
  !> free velocity m%vfree = V + A_ff⁻¹ R (A refactorized for nonlinear bodies).
  subroutine mailx_iterate(m, status)
    type(mailx_t), intent(inout) :: m
    type(status_t), intent(inout), optional :: status
    integer :: b, i1, i2
    m%iterations = m%iterations + 1
    call residual(m, status)
    if (failed(status)) return
    m%vfree = m%res
    do b = 1, m%n
      i1 = m%node_first(b); i2 = m%node_first(b + 1) - 1
      call body_solve(m, b, 2 * (i2 - i1 + 1), m%vfree(:, i1:i2), status)
      if (failed(status)) return
    end do
    m%vfree = m%v + m%vfree
  end subroutine mailx_iterate

  !> m%res = R(V) = h Fext - M (V - Vb) - h ((1-θ) Fi_b + θ Fi(X(V))).
  subroutine residual(m, status)
    type(mailx_t), intent(inout) :: m
    type(status_t), intent(inout), optional :: status
    integer :: b, i1, i2
    m%x = m%xbegin + m%h * ((1.0_wp - m%theta) * m%vbegin + m%theta * m%v)
    call internal_forces(m, m%x, status)
    if (failed(status)) return
    m%tmp = m%v - m%vbegin
    do b = 1, m%n
      i1 = m%node_first(b); i2 = m%node_first(b + 1) - 1
      call body_m_times(m, b, 2 * (i2 - i1 + 1), m%tmp(:, i1:i2), m%res(:, i1:i2))
    end do
    m%res = m%h * m%fext - m%res - m%h * ((1.0_wp - m%theta) * m%fint_begin + m%theta * m%fint)
  end subroutine residual

  !> Velocities from the contact impulses imp (2, nnodes) on the nodes:
  !> V = V_free + A_ff⁻¹ imp, body by body (bodies without impulse: V_free).
  subroutine mailx_velocity_from_impulses(m, imp)
    type(mailx_t), intent(inout) :: m
    real(wp), intent(in) :: imp(:, :)
    integer :: b, i1, i2
    m%imp = imp
    m%tmp = imp
    do b = 1, m%n
      i1 = m%node_first(b); i2 = m%node_first(b + 1) - 1
      if (all(imp(:, i1:i2) == 0.0_wp)) cycle
      call body_solve(m, b, 2 * (i2 - i1 + 1), m%tmp(:, i1:i2))
    end do
    m%v = m%vfree + m%tmp
  end subroutine mailx_velocity_from_impulses

  !> After a contact solve: is the step's Newton loop converged? Linear scenes
  !> are after one iteration. Otherwise the next iterate is prepared (residual
  !> and free velocity at the new velocities) and the unbalanced force on the
  !> free dofs |R + r| is compared with tol times the force scale of the step.
  !> The internal forces count with the larger of their start and end values: the
  !> end stresses are the start ones plus increments, so their round-off is
  !> relative to both (a J2 body unloading through zero stress has Fi ~ 0 at the
  !> step end, and a scale of the end forces alone was out of reach of round-off:
  !> newton_max_iterations reached at every such step).
  logical function mailx_converged(m, tol, max_iterations, status) result(done)
    type(mailx_t), intent(inout) :: m
    real(wp), intent(in) :: tol
    integer, intent(in) :: max_iterations
    type(status_t), intent(inout), optional :: status   !< a tangent that does not factorize (done is then true)
    real(wp) :: unbalanced, scale
    done = .true.
    m%newton_converged = .true.
    if (.not. m%any_nonlinear) return
    call mailx_iterate(m, status)
    if (failed(status)) return
    unbalanced = sqrt(sum((m%res + m%imp)**2, mask=.not. m%driven))
    scale = sqrt(sum((m%h * m%fext)**2)) + m%h * max(sqrt(sum(m%fint**2)), sqrt(sum(m%fint_begin**2))) + &
            sqrt(sum(m%imp**2)) + sqrt(sum((m%mdiag * (m%v - m%vbegin))**2))
    m%newton_converged = unbalanced <= tol * max(scale, tiny(1.0_wp))
    done = m%newton_converged .or. m%iterations > max_iterations
  end function mailx_converged

  !> Change the time step: every body's iteration matrix M + (h theta)^2 K is
  !> factorized again (nonlinear bodies at their current tangent). A matrix that
  !> does not factorize: status, or the run stops.
  subroutine mailx_set_time_step(m, h, status)
    type(mailx_t), intent(inout) :: m
    real(wp), intent(in) :: h
    type(status_t), intent(inout), optional :: status
    integer :: b
    if (h == m%h) return
    m%h = h
    do b = 1, m%n
      call factorize_body(m, b, status=status)
      if (failed(status)) return
    end do
  end subroutine mailx_set_time_step

  !> Free the factorizations of the large bodies (their C handles: CHOLMOD,
  !> UMFPACK); the bodies' arrays go with m. Call before m is dropped or rebuilt.
  subroutine mailx_free(m)
    type(mailx_t), intent(inout) :: m
    integer :: b
    if (.not. allocated(m%big)) return
    do b = 1, size(m%big)
      call factor_free(m%big(b)%f)
      m%big(b)%factored = .false.
    end do
  end subroutine mailx_free

  !> Detection configuration of the nodes: X_b + (1-θ) h V_b from the reference.
  pure subroutine mailx_detection_coor(m, xn)
    type(mailx_t), intent(in) :: m
    real(wp), intent(out) :: xn(:, :)
    xn = m%ref + m%xbegin + (1.0_wp - m%theta) * m%h * m%vbegin
  end subroutine mailx_detection_coor

  !> End of a converged step: displacements, Gauss-point states and internal
  !> forces become the start of the next step; energy audit of the step.
  subroutine mailx_end_step(m)
    type(mailx_t), intent(inout) :: m
    real(wp), allocatable :: dx(:, :), fstep(:, :)
    integer :: k
    m%x = m%xbegin + m%h * ((1.0_wp - m%theta) * m%vbegin + m%theta * m%v)
    if (.not. m%any_nonlinear) call internal_forces(m, m%x)
    dx = m%x - m%xbegin
    ! Force of the drives on the driven dofs from their equation of motion:
    ! M (V - Vb) = h Fext_θ - h Fi_θ + r + h F_support.
    call residual_at_end()
    m%work_supports = m%work_supports + sum(m%fsupport * dx, mask=m%driven)
    fstep = spread(m%gravity, 2, m%nnodes)
    m%work_gravity = m%work_gravity + sum(m%mdiag * fstep * dx)
    do k = 1, size(m%drives)
      associate (d => m%drives(k))
        if (d%is_velocity) cycle
        m%work_forces = m%work_forces + dx(d%dof, d%body) * ((1.0_wp - m%theta) * drive_value(d, m%time) + &
                                                             m%theta * drive_value(d, m%time + m%h))
      end associate
    end do
    m%plastic_work = m%plastic_work + sum(m%wpl, mask=m%nonlinear)
    m%gp_begin = m%gp
    m%fint_begin = m%fint
    m%xbegin = m%x
    m%vbegin = m%v
    m%elastic = elastic_energy(m)
  contains
    subroutine residual_at_end()
      integer :: b, i1, i2
      m%tmp = m%v - m%vbegin
      do b = 1, m%n
        i1 = m%node_first(b); i2 = m%node_first(b + 1) - 1
        call body_m_times(m, b, 2 * (i2 - i1 + 1), m%tmp(:, i1:i2), m%fsupport(:, i1:i2))
      end do
      m%finert = m%fsupport / m%h
      ! the drives' force closes the equation of motion of their dofs
      where (m%driven)
        m%fsupport = -(m%h * m%fext - m%fsupport - m%h * ((1.0_wp - m%theta) * m%fint_begin + m%theta * m%fint) &
                       + m%imp) / m%h
      elsewhere
        m%fsupport = 0.0_wp
      end where
    end subroutine residual_at_end
  end subroutine mailx_end_step

  !> The meshes' end-of-step state for a restart point (what mailx_restore_state
  !> takes back).
  subroutine mailx_save_state(m, x, v, gp, fint, energies)
    type(mailx_t), intent(in) :: m
    real(wp), allocatable, intent(out) :: x(:, :), v(:, :), gp(:, :), fint(:, :), energies(:)
    x = m%x
    v = m%v
    gp = m%gp
    fint = m%fint
    energies = [m%kinetic0, m%work_gravity, m%work_forces, m%work_supports, m%plastic_work]
  end subroutine mailx_save_state

  !> The meshes' datasets of a restart point read from a file (mesh/X, V, gp, fint,
  !> energies): shapes and finite values, before any is used.
  subroutine mailx_check_restart(m, st)
    type(mailx_t), intent(in) :: m
    type(restart_state_t), intent(in) :: st
    call restart_check_real2(st, 'mesh/X', st%mesh_x, 2, m%nnodes)
    call restart_check_real2(st, 'mesh/V', st%mesh_v, 2, m%nnodes)
    call restart_check_real2(st, 'mesh/gp', st%mesh_gp, gp_size, m%ngp)
    ! Gauss-point values are squared (von Mises, energies): beyond sqrt(huge) they overflow.
    if (any(abs(st%mesh_gp) > sqrt(huge(1.0_wp)))) call restart_bad(st, 'mesh/gp', 'a value beyond '// &
      rtoa(sqrt(huge(1.0_wp)))//' (its square overflows double precision)')
    call restart_check_real2(st, 'mesh/fint', st%mesh_fint, 2, m%nnodes)
    call restart_check_real1(st, 'mesh/energies', st%mesh_energies, 5)
  end subroutine mailx_check_restart

  !> Put the meshes into a saved end-of-step state (exact restart): nodal
  !> displacements x and velocities v, Gauss-point states gp, internal forces
  !> fint, and the energy accumulators energies = [kinetic0, work_gravity,
  !> work_forces, work_supports, plastic_work]. Nonlinear bodies get their
  !> tangent and factorization back from that state, as their next step would.
  subroutine mailx_restore_state(m, x, v, gp, fint, energies)
    type(mailx_t), intent(inout) :: m
    real(wp), intent(in) :: x(:, :), v(:, :), gp(:, :), fint(:, :), energies(5)
    integer :: b
    m%xbegin = x; m%x = x
    m%vbegin = v; m%v = v
    m%gp_begin = gp; m%gp = gp
    do b = 1, m%n
      if (.not. m%nonlinear(b)) cycle
      call assemble_body(m, b, m%xbegin, with_mass=.false.)
      call factorize_body(m, b)
    end do
    m%gp = gp
    m%fint_begin = fint; m%fint = fint
    m%kinetic0 = energies(1); m%work_gravity = energies(2); m%work_forces = energies(3)
    m%work_supports = energies(4); m%plastic_work = energies(5)
    m%elastic = elastic_energy(m)
  end subroutine mailx_restore_state

  !> Kinetic energy 1/2 V^T M V of all dofs (driven ones too: the drives' work
  !> is booked through the force they apply).
  real(wp) function mailx_kinetic_energy(m) result(e)
    type(mailx_t), intent(in) :: m
    integer :: b, i1, i2
    real(wp), allocatable :: mv(:, :)
    allocate (mv(2, m%nnodes))
    do b = 1, m%n
      i1 = m%node_first(b); i2 = m%node_first(b + 1) - 1
      call body_m_times(m, b, 2 * (i2 - i1 + 1), m%v(:, i1:i2), mv(:, i1:i2))
    end do
    e = 0.5_wp * sum(mv * m%v)
  end function mailx_kinetic_energy

  !> Stored elastic energy: 1/2 X^T K X for linear bodies, the Gauss-point
  !> integral of 1/2 σ:ε_e for nonlinear ones (their last element loop, at the
  !> final iterate of the step).
  real(wp) function elastic_energy(m) result(e)
    type(mailx_t), intent(in) :: m
    integer :: b, i1, i2
    real(wp), allocatable :: kx(:, :)
    allocate (kx(2, m%nnodes))
    e = 0.0_wp
    do b = 1, m%n
      i1 = m%node_first(b); i2 = m%node_first(b + 1) - 1
      if (m%nonlinear(b)) then
        e = e + m%eel(b)
      else
        call body_k_times(m, b, 2 * (i2 - i1 + 1), m%x(:, i1:i2), kx(:, i1:i2))
        e = e + 0.5_wp * sum(kx(:, i1:i2) * m%x(:, i1:i2))
      end if
    end do
  end function elastic_energy

  !> Gauss-point states at the current displacements, for output: computed
  !> for linear bodies (their states are not kept during the run), the last
  !> converged ones for nonlinear bodies.
  subroutine mailx_gauss_values(m, gp)
    type(mailx_t), intent(in) :: m
    real(wp), intent(out) :: gp(:, :)
    integer :: b, ie
    real(wp), allocatable :: xe(:, :), ue(:), fi(:), ke(:, :)
    integer, allocatable :: dofs(:)
    real(wp) :: eel, wpl
    gp = m%gp
    do b = 1, m%n
      if (m%nonlinear(b)) cycle
      do ie = m%elem_first(b), m%elem_first(b + 1) - 1
        call element_data(m, ie, b, m%x, xe, ue, dofs)
        allocate (fi(size(ue)), ke(size(ue), size(ue)))
        call el_response(m%el_kind(ie), xe, ue, m%mats(m%el_bulk(ie)), m%plane, &
                         m%gp_begin(:, m%el_gp(ie):m%el_gp(ie + 1) - 1), gp(:, m%el_gp(ie):m%el_gp(ie + 1) - 1), &
                         fi, ke, .false., eel, wpl)
        deallocate (fi, ke)
      end do
    end do
  end subroutine mailx_gauss_values

  !> Compliance sets at the start: a dense body's set is all its nodes; a
  !> large body's is built when contacts ask for it.
  subroutine compliance_sets_init(m)
    type(mailx_t), intent(inout) :: m
    integer :: b, j
    allocate (m%cslot(m%nnodes), m%contact_hint(m%nnodes))
    m%cslot = 0
    m%contact_hint = .false.
    do b = 1, m%n
      if (.not. m%dense(b)) cycle
      do j = m%node_first(b), m%node_first(b + 1) - 1
        m%cslot(j) = j - m%node_first(b) + 1
      end do
    end do
  end subroutine compliance_sets_init

  !> Number of contact dofs of body b (twice the nodes of its contact set).
  pure integer function mailx_contact_dofs(m, b) result(nd)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: b
    nd = 0
    if (m%dense(b)) then
      nd = body_ndof(m, b)
    else if (allocated(m%big(b)%cnodes)) then
      nd = 2 * size(m%big(b)%cnodes)
    end if
  end function mailx_contact_dofs

  !> The contact set of body b (mesh nodes; slot s is set(s)).
  function mailx_contact_set(m, b) result(set)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: b
    integer, allocatable :: set(:)
    integer :: j
    if (m%dense(b)) then
      set = [(j, j=m%node_first(b), m%node_first(b + 1) - 1)]
    else if (allocated(m%big(b)%cnodes)) then
      set = m%big(b)%cnodes
    else
      allocate (set(0))
    end if
  end function mailx_contact_set

  !> Make sure the compliance of every listed node's body covers that node:
  !> a large body whose set lacks a node gets a new set, the old one and the
  !> new nodes and, once, every node the contacts may touch (contact_hint, up
  !> to compliance_cap nodes), and its compliance by solves with the
  !> factorization (all columns at once). A linear body so computes it once.
  subroutine mailx_require_compliance(m, nodes)
    type(mailx_t), intent(inout) :: m
    integer, intent(in) :: nodes(:)
    integer :: k, b, j, ncand
    logical, allocatable :: grow(:), wanted(:)
    integer, allocatable :: newset(:)
    allocate (grow(m%n))
    grow = .false.
    do k = 1, size(nodes)
      b = m%node_body(nodes(k))
      if (m%dense(b)) cycle
      if (m%cslot(nodes(k)) == 0 .or. .not. allocated(m%big(b)%c)) grow(b) = .true.
    end do
    if (.not. any(grow)) return
    allocate (wanted(m%nnodes))
    wanted = .false.
    wanted(nodes) = .true.
    do b = 1, m%n
      if (.not. grow(b)) cycle
      ncand = count(m%contact_hint(m%node_first(b):m%node_first(b + 1) - 1))
      newset = pack([(j, j=m%node_first(b), m%node_first(b + 1) - 1)], &
                     m%cslot(m%node_first(b):m%node_first(b + 1) - 1) > 0 .or. &
                     wanted(m%node_first(b):m%node_first(b + 1) - 1) .or. &
                     (m%contact_hint(m%node_first(b):m%node_first(b + 1) - 1) .and. ncand <= compliance_cap))
      call set_compliance(m, b, newset)
    end do
  contains
    subroutine set_compliance(m, b, set)
      type(mailx_t), intent(inout) :: m
      integer, intent(in) :: b, set(:)
      ! Unit impulses at the set's dofs solved on the free dofs, a block of columns at
      ! a time, keeping only the set's rows: all columns of a large body with many
      ! contact nodes at once would not fit in memory (2e5 dofs x 900 columns: 1.4 GB
      ! per copy).
      integer, parameter :: block = 64
      integer :: i, d, ns, n0, nf, c1, c2, j
      integer, allocatable :: frow(:)
      real(wp), allocatable :: ef(:, :)
      ns = size(set)
      n0 = m%node_first(b) - 1
      m%cslot(n0 + 1:n0 + body_ndof(m, b) / 2) = 0
      do i = 1, ns
        m%cslot(set(i)) = i
      end do
      associate (bb => m%big(b))
        nf = count(bb%free_of > 0)
        allocate (frow(2 * ns))          ! free index of each set dof (0: driven)
        do i = 1, ns
          do d = 1, 2
            frow(2 * (i - 1) + d) = bb%free_of(2 * (set(i) - n0 - 1) + d)
          end do
        end do
        if (allocated(bb%c)) deallocate (bb%c)
        allocate (bb%c(2 * ns, 2 * ns))
        do c1 = 1, 2 * ns, block
          c2 = min(2 * ns, c1 + block - 1)
          allocate (ef(nf, c2 - c1 + 1))
          ef = 0.0_wp
          do j = c1, c2
            if (frow(j) > 0) ef(frow(j), j - c1 + 1) = 1.0_wp
          end do
          call factor_solve(bb%f, ef)
          do j = 1, 2 * ns
            bb%c(j, c1:c2) = 0.0_wp
            if (frow(j) > 0) bb%c(j, c1:c2) = ef(frow(j), :)
          end do
          deallocate (ef)
        end do
        bb%cnodes = set
      end associate
    end subroutine set_compliance
  end subroutine mailx_require_compliance

  !> Mark the nodes contacts may touch (the nodes of the meshes' contactors):
  !> a large body's compliance then covers them all from the first contact.
  subroutine mailx_set_contact_hint(m, nodes)
    type(mailx_t), intent(inout) :: m
    integer, intent(in) :: nodes(:)
    m%contact_hint = .false.
    m%contact_hint(nodes) = .true.
  end subroutine mailx_set_contact_hint

  !> The contact dofs of body b: the number of nodes of its compliance set.
  !> Columns 2s-1 and 2s of its compliance matrix (x and y impulse at the
  !> node of slot s) are returned by mailx_compliance_columns.
  subroutine mailx_compliance_columns(m, node, cols)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: node
    real(wp), intent(out) :: cols(:, :)
    integer :: b, s, nd, base
    b = m%node_body(node)
    s = m%cslot(node)
    if (m%dense(b)) then
      nd = body_ndof(m, b)
      base = m%dfirst(b)
      cols(:, 1) = m%dinv(base + nd * (2 * s - 2) + 1:base + nd * (2 * s - 1))
      cols(:, 2) = m%dinv(base + nd * (2 * s - 1) + 1:base + nd * (2 * s))
    else
      cols(:, 1) = m%big(b)%c(:, 2 * s - 1)
      cols(:, 2) = m%big(b)%c(:, 2 * s)
    end if
  end subroutine mailx_compliance_columns

  !> How the bodies' iteration matrices are solved, in one line: the dense
  !> inverses, and the sparse factorization of each large body (first three).
  function mailx_solver_summary(m) result(s)
    type(mailx_t), intent(in) :: m
    character(len=:), allocatable :: s
    integer :: b, shown
    character(len=32) :: buf
    write (buf, '(i0)') count(m%dense)
    s = trim(buf)//' dense inverses (LAPACK)'
    shown = 0
    do b = 1, m%n
      if (m%dense(b)) cycle
      shown = shown + 1
      write (buf, '(i0)') b
      if (shown <= 3) s = s//'; body '//trim(buf)//': '//factor_method_name(m%big(b)%f)
    end do
    if (shown > 3) then
      write (buf, '(i0)') shown - 3
      s = s//'; and '//trim(buf)//' more sparse bodies'
    end if
  end function mailx_solver_summary

  !> The bodies' records of DOF.OUT (LMGC90's MAILx blocks: every node's
  !> displacement and velocity).
  function mailx_dof_records(m) result(dofs)
    type(mailx_t), intent(in) :: m
    type(dof_record_t) :: dofs(m%n)
    integer :: k, it
    do k = 1, m%n
      associate (d => dofs(k), i1 => m%node_first(k), i2 => m%node_first(k + 1) - 1)
        d%model = 'MAILx'
        d%body = k
        d%nodes = [(it, it=1, i2 - i1 + 1)]
        d%node_x = m%x(:, i1:i2)
        d%node_v = m%v(:, i1:i2)
      end associate
    end do
  end function mailx_dof_records

  !> The meshes' fixed description into the open group g of fracas.h5 (/mesh):
  !> reference node coordinates, node and element ranges of each body, element
  !> kinds (VTK cell types), connectivity (1-based mesh node numbers), materials.
  subroutine mailx_write_static(m, g)
    type(mailx_t), intent(in) :: m
    integer(hid_t), intent(in) :: g
    integer :: e
    integer(ik), allocatable :: vtk(:)
    allocate (vtk(m%nelem))
    do e = 1, m%nelem
      vtk(e) = int(el_vtk_type(m%el_kind(e)), ik)
    end do
    call h5_write_attr(g, 'plane', plane_names(m%plane))
    call h5_write_attr(g, 'gauss_point_fields', 'sxx syy sxy szz exx eyy gxy ezz pxx pyy pgxy pzz p')
    call h5_write_dataset(g, 'reference', m%ref)
    call h5_write_dataset(g, 'body_first_node', int(m%node_first, ik))
    call h5_write_dataset(g, 'body_first_element', int(m%elem_first, ik))
    call h5_write_dataset(g, 'element_vtk_type', vtk)
    call h5_write_dataset(g, 'element_first_node', int(m%el_first, ik))
    call h5_write_dataset(g, 'element_nodes', int(m%el_nodes, ik))
    call h5_write_dataset(g, 'element_first_gauss_point', int(m%el_gp, ik))
    call h5_write_dataset(g, 'element_material', int(m%el_mat, ik))
  end subroutine mailx_write_static

  !> The meshes' state into the open snapshot group g: nodal displacements and
  !> velocities (2, nodes), the force of the velocity drives on their nodes
  !> (2, nodes; when some dof is driven), Gauss-point states (13, Gauss points:
  !> stress, strain, plastic strain, p; see /mesh/gauss_point_fields).
  subroutine mailx_write_snapshot(m, g)
    type(mailx_t), intent(in) :: m
    integer(hid_t), intent(in) :: g
    real(wp), allocatable :: gp(:, :)
    allocate (gp(size(m%gp, 1), size(m%gp, 2)))
    call mailx_gauss_values(m, gp)
    call h5_write_dataset(g, 'mesh_X', m%x)
    call h5_write_dataset(g, 'mesh_V', m%v)
    ! Force of the velocity drives on their nodes (reactions; zero on free dofs).
    if (any(m%driven)) call h5_write_dataset(g, 'mesh_F_support', m%fsupport)
    call h5_write_dataset(g, 'mesh_gauss_points', gp)
  end subroutine mailx_write_snapshot

  !> The model's terms of the energy audit.
  pure type(energy_terms_t) function mailx_energy_terms(m) result(e)
    type(mailx_t), intent(in) :: m
    e%work_gravity = m%work_gravity
    e%work_forces = m%work_forces
    e%work_supports = m%work_supports
    e%elastic = m%elastic
    e%plastic = m%plastic_work
  end function mailx_energy_terms

  !> The state check of the meshed bodies after a step of length h: '' if
  !> sound, else what is wrong, naming the body (by rank), node or Gauss point:
  !> a non-finite node or Gauss-point state, a node beyond what double precision
  !> resolves at its body's size (mailx_radius), in place or in one step, or an
  !> overflowed energy audit.
  function mailx_fault(m, h) result(msg)
    type(mailx_t), intent(in) :: m
    real(wp), intent(in) :: h
    character(len=:), allocatable :: msg
    integer :: k, ib
    real(wp) :: lim, pos, moved
    msg = ''
    if (m%nnodes == 0) return
    if (.not. (all(ieee_is_finite(m%x)) .and. all(ieee_is_finite(m%v)))) then
      do k = 1, m%nnodes
        if (.not. (all(ieee_is_finite(m%x(:, k))) .and. all(ieee_is_finite(m%v(:, k))))) then
          msg = 'MAILx body '//itoa(m%node_body(k))//' has a non-finite displacement or velocity at node '// &
                itoa(k - m%node_first(m%node_body(k)) + 1)//' (X '//rtoa_list(m%x(:, k))//', V '// &
                rtoa_list(m%v(:, k))//')'
          return
        end if
      end do
    end if
    if (.not. all(ieee_is_finite(m%gp))) then
      msg = gauss_point_fault()
      return
    end if
    do ib = 1, m%n
      lim = resolvable_length(mailx_radius(m, ib))
      do k = m%node_first(ib), m%node_first(ib + 1) - 1
        pos = maxval(abs(m%ref(:, k) + m%x(:, k)))
        moved = h * maxval(abs(m%v(:, k)))
        if (pos > lim) then
          msg = 'MAILx body '//itoa(ib)//' ran away: node '//itoa(k - m%node_first(ib) + 1)//' is at '// &
                rtoa(pos)//' from the origin (displacement '//rtoa_list(m%x(:, k))//'), beyond '//rtoa(lim)// &
                ' (what double precision resolves at the body''s size, '//rtoa(mailx_radius(m, ib))//')'
          return
        end if
        if (moved > lim) then
          msg = 'MAILx body '//itoa(ib)//' ran away: the velocity of node '//itoa(k - m%node_first(ib) + 1)// &
                ' ('//rtoa_list(m%v(:, k))//') moves it by '//rtoa(moved)//' in one step, beyond '//rtoa(lim)// &
                ' (what double precision resolves at the body''s size, '//rtoa(mailx_radius(m, ib))//')'
          return
        end if
      end do
    end do
    if (.not. all(ieee_is_finite([m%elastic, m%plastic_work, m%work_gravity, m%work_forces, m%work_supports]))) then
      msg = 'the energy audit of the meshes overflowed (elastic '//rtoa(m%elastic)//', plastic work '// &
            rtoa(m%plastic_work)//', work of supports '//rtoa(m%work_supports)//')'
      return
    end if

  contains

    !> The first Gauss point with a non-finite state: body, element, point and quantity.
    function gauss_point_fault() result(s)
      character(len=:), allocatable :: s
      integer :: b, e, g
      character(len=*), parameter :: names(4) = [character(len=26) :: 'stress', 'strain', 'plastic strain', &
                                                 'cumulative plastic strain']
      integer, parameter :: first(4) = [gp_stress, gp_strain, gp_plastic_strain, gp_p]
      integer :: q
      s = 'a MAILx body has a non-finite Gauss-point state'
      do b = 1, m%n
        do e = m%elem_first(b), m%elem_first(b + 1) - 1
          do g = m%el_gp(e), m%el_gp(e + 1) - 1
            if (all(ieee_is_finite(m%gp(:, g)))) cycle
            do q = 4, 1, -1
              if (.not. all(ieee_is_finite(m%gp(first(q):merge(first(q), first(q) + 3, q == 4), g)))) &
                s = 'MAILx body '//itoa(b)//' has a non-finite '//trim(names(q))//' at Gauss point '// &
                    itoa(g - m%el_gp(e) + 1)//' of its element '//itoa(e - m%elem_first(b) + 1)//' ('// &
                    rtoa_list(m%gp(first(q):merge(first(q), first(q) + 3, q == 4), g))//')'
            end do
            return
          end do
        end do
      end do
    end function gauss_point_fault
  end function mailx_fault
end module fracas_mailx
