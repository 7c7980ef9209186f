!> Cracks as results: the state of the cohesive interfaces of meshed bodies
!> (an interface edge carries the CLxxx candidate points of one mesh edge glued
!> to the facing ALpxx), followed step by step, and from it the crack paths
!> (broken edges joined into polylines), their lengths per interface family,
!> the main crack's tip, and the fragments (pieces still held together).
!>
!> A point is glued when a cohesive contact holds it at the start of the run;
!> its damage is the β of that contact; a glued point whose contact is lost
!> (separated beyond the alert distance) counts as broken. An edge is broken
!> when all its glued points are, damaged when one of them is. The family of
!> an edge is the colour of its candidate contactor (the deck builder names
!> interface families by colour, see doc/fracture.md). The damage energy
!> released on the glued points (as the solver books it in damage_dissipated)
!> is summed per family.
module fracas_cracks
  use fracas_kinds, only: wp
  use fracas_contactors, only: tactors_t, tk_clxxx
  use fracas_contacts, only: contacts_t
  use fracas_contact_laws, only: law_t, law_czm, coh_released, int_beta
  use fracas_mailx, only: mailx_t
  use fracas_ids, only: bm_mesh
  implicit none
  private
  public :: cracks_t, cracks_init, cracks_update, cracks_lengths, cracks_edge_beta, crack_paths_t, cracks_paths, cracks_fragments, &
            fragments_t, cracks_fragment_stats

  type :: cracks_t
    integer :: npts = 0, nedges = 0, nfamilies = 0
    integer, allocatable :: tactor_pt(:)        !< (ntactors) interface point of a CLxxx contactor, 0 if none
    integer, allocatable :: pt_edge(:)          !< (npts)
    real(wp), allocatable :: pt_beta(:)         !< (npts) damage, 1 sound .. 0 broken
    logical, allocatable :: pt_glued(:), pt_seen(:)
    integer, allocatable :: pt_partner(:)       !< (npts) meshed body glued to the point (0: none)
    integer, allocatable :: pt_an(:)            !< (npts) antagonist contactor of the glued contact
    integer, allocatable :: edge_first(:)       !< (nedges+1) points edge_pts(edge_first(e) ..) of edge e
    integer, allocatable :: edge_pts(:)
    integer, allocatable :: edge_nodes(:, :)    !< (2,nedges) mesh nodes of the candidate edge
    integer, allocatable :: edge_body(:), edge_family(:), edge_broken_step(:)
    real(wp), allocatable :: edge_length(:)     !< reference length
    character(len=5), allocatable :: family_names(:)
    real(wp), allocatable :: family_damage(:)   !< (nfamilies) damage energy released so far, per family
  end type cracks_t

  !> Crack paths at one time: broken edges joined into connected cracks.
  type :: crack_paths_t
    integer :: ncracks = 0
    real(wp), allocatable :: points(:, :)       !< (2,np) vertices (current configuration)
    integer, allocatable :: seg(:, :)           !< (2,nseg) segments as vertex pairs
    integer, allocatable :: seg_crack(:)        !< crack of each segment (1 = longest)
    real(wp), allocatable :: crack_length(:)    !< (ncracks) reference length of each crack
    real(wp) :: tip(2) = 0.0_wp                 !< main crack's tip (reference configuration)
    real(wp) :: origin(2) = 0.0_wp              !< where the main crack started (first broken edge)
  end type crack_paths_t

  !> Per fragment (cracks_fragment_stats): meshed bodies and elements, mass,
  !> centre of mass (2), velocity of the centre (2), kinetic energy, second
  !> moments about the centre (Jxx, Jyy, Jxy), polar moment, principal moments
  !> (largest first) and the major axis' angle from x (rad).
  type :: fragments_t
    integer, allocatable :: bodies(:), elements(:)
    real(wp), allocatable :: mass(:), centre(:, :), velocity(:, :), kinetic(:), moments(:, :), polar(:), &
                             principal(:, :), angle(:)
  end type fragments_t

contains

  !> Interface points and edges from the CLxxx contactors of the scene.
  subroutine cracks_init(cr, t, m)
    type(cracks_t), intent(out) :: cr
    type(tactors_t), intent(in) :: t
    type(mailx_t), intent(in) :: m
    integer :: k, j, p, e, a, b
    integer, allocatable :: pts(:), key(:, :), order(:)
    allocate (cr%tactor_pt(t%n))
    cr%tactor_pt = 0
    pts = pack([(k, k=1, t%n)], t%kind(1:t%n) == tk_clxxx)
    cr%npts = size(pts)
    allocate (key(3, cr%npts))
    do p = 1, cr%npts
      k = pts(p)
      a = t%nodes(t%nfirst(k)); b = t%nodes(t%nfirst(k) + 1)
      key(:, p) = [t%body(k), min(a, b), max(a, b)]
    end do
    order = sort_keys(key)
    allocate (cr%pt_edge(cr%npts), cr%pt_beta(cr%npts), cr%pt_glued(cr%npts), cr%pt_seen(cr%npts), &
              cr%pt_partner(cr%npts), cr%pt_an(cr%npts))
    cr%pt_partner = 0
    cr%pt_an = 0
    cr%pt_beta = 1.0_wp
    cr%pt_glued = .false.
    cr%pt_seen = .false.
    ! Points with the same (body, edge) make one edge.
    e = 0
    do j = 1, cr%npts
      p = order(j)
      if (j == 1) then
        e = 1
      else if (any(key(:, p) /= key(:, order(j - 1)))) then
        e = e + 1
      end if
      cr%pt_edge(p) = e
      cr%tactor_pt(pts(p)) = p
    end do
    cr%nedges = e
    ! points in edge order
    allocate (cr%edge_first(e + 1))
    cr%edge_pts = order
    cr%edge_first(1) = 1
    do j = 2, cr%npts
      if (cr%pt_edge(order(j)) /= cr%pt_edge(order(j - 1))) cr%edge_first(cr%pt_edge(order(j))) = j
    end do
    cr%edge_first(e + 1) = cr%npts + 1
    allocate (cr%edge_nodes(2, e), cr%edge_body(e), cr%edge_family(e), cr%edge_broken_step(e), &
              cr%edge_length(e), cr%family_names(0))
    cr%edge_broken_step = 0
    do p = 1, cr%npts
      e = cr%pt_edge(p)
      k = pts(p)
      cr%edge_nodes(:, e) = [t%nodes(t%nfirst(k)), t%nodes(t%nfirst(k) + 1)]
      cr%edge_body(e) = t%body(k)
      cr%edge_length(e) = norm2(m%ref(:, cr%edge_nodes(2, e)) - m%ref(:, cr%edge_nodes(1, e)))
      cr%edge_family(e) = family_index(t%color(k))
    end do
    cr%nfamilies = size(cr%family_names)
    allocate (cr%family_damage(cr%nfamilies))
    cr%family_damage = 0.0_wp

  contains

    integer function family_index(color)
      character(len=5), intent(in) :: color
      integer :: i
      do i = 1, size(cr%family_names)
        if (cr%family_names(i) == color) then
          family_index = i
          return
        end if
      end do
      cr%family_names = [character(len=5) :: cr%family_names, color]
      family_index = size(cr%family_names)
    end function family_index
  end subroutine cracks_init

  !> After a step: the interface points' damage from the cohesive contacts.
  !> Points glued at the start are those with a cohesive contact of beta > 0
  !> after the run's first step (first); a glued point without a contact has
  !> separated beyond the alert distance: broken. Only the contact that glued
  !> a point (same antagonist contactor) speaks for it: a point may later see
  !> another antagonist within the alert distance (a new contact, without
  !> cohesion), which says nothing about its interface. step numbers the step.
  !> The energy a glued point's contact released in the step (the solver's
  !> damage_dissipated, coh(coh_released)) goes to its family.
  subroutine cracks_update(cr, c, laws, first, step)
    type(cracks_t), intent(inout) :: cr
    type(contacts_t), intent(in) :: c
    type(law_t), intent(in) :: laws(:)
    logical, intent(in) :: first
    integer, intent(in) :: step
    integer :: k, p, e
    logical, allocatable :: present_now(:)
    if (cr%npts == 0) return
    allocate (present_now(cr%npts))
    present_now = .false.
    do k = 1, c%n
      if (laws(c%law(k))%kind /= law_czm) cycle
      p = cr%tactor_pt(c%cd(k))
      if (p == 0) cycle
      if (.not. cr%pt_seen(p)) then
        cr%pt_seen(p) = .true.
        cr%pt_glued(p) = first .and. c%internals(int_beta(c%nd), k) > 0.0_wp
        if (.not. cr%pt_glued(p)) cycle
        cr%pt_an(p) = c%an(k)
        if (c%anm(k) == bm_mesh) cr%pt_partner(p) = c%anb(k)
      end if
      if (.not. cr%pt_glued(p) .or. c%an(k) /= cr%pt_an(p)) cycle
      present_now(p) = .true.
      if (c%internals(int_beta(c%nd), k) < cr%pt_beta(p)) then
        associate (f => cr%edge_family(cr%pt_edge(p)))
          cr%family_damage(f) = cr%family_damage(f) + c%coh(coh_released(c%nd), k)
        end associate
        cr%pt_beta(p) = c%internals(int_beta(c%nd), k)
      end if
    end do
    where (cr%pt_glued .and. .not. present_now) cr%pt_beta = 0.0_wp
    do e = 1, cr%nedges
      if (cr%edge_broken_step(e) > 0) cycle
      if (edge_broken(cr, e)) cr%edge_broken_step(e) = step
    end do
  end subroutine cracks_update

  !> An edge is broken when it has glued points and all of them are broken.
  logical function edge_broken(cr, e)
    type(cracks_t), intent(in) :: cr
    integer, intent(in) :: e
    associate (pts => cr%edge_pts(cr%edge_first(e):cr%edge_first(e + 1) - 1))
      edge_broken = any(cr%pt_glued(pts)) .and. .not. any(cr%pt_glued(pts) .and. cr%pt_beta(pts) > 0.0_wp)
    end associate
  end function edge_broken

  !> Damage of each edge: the lowest beta of its glued points (0 when none is glued).
  function cracks_edge_beta(cr) result(beta)
    type(cracks_t), intent(in) :: cr
    real(wp) :: beta(cr%nedges)
    integer :: e
    do e = 1, cr%nedges
      associate (p => cr%edge_pts(cr%edge_first(e):cr%edge_first(e + 1) - 1))
        beta(e) = 0.0_wp
        if (any(cr%pt_glued(p))) beta(e) = minval(cr%pt_beta(p), mask=cr%pt_glued(p), dim=1)
      end associate
    end do
  end function cracks_edge_beta

  !> Broken and damaged interface lengths (reference configuration), in all
  !> and per family, and the counts of broken and damaged edges.
  subroutine cracks_lengths(cr, broken, damaged, broken_family, nbroken, ndamaged)
    type(cracks_t), intent(in) :: cr
    real(wp), intent(out) :: broken, damaged
    real(wp), intent(out) :: broken_family(:)
    integer, intent(out) :: nbroken, ndamaged
    logical, allocatable :: dmg(:)
    integer :: p, e
    allocate (dmg(cr%nedges))
    dmg = .false.
    do p = 1, cr%npts
      if (cr%pt_glued(p) .and. cr%pt_beta(p) < 1.0_wp) dmg(cr%pt_edge(p)) = .true.
    end do
    broken = 0.0_wp; damaged = 0.0_wp; broken_family = 0.0_wp
    nbroken = 0; ndamaged = 0
    do e = 1, cr%nedges
      if (cr%edge_broken_step(e) > 0) then
        broken = broken + cr%edge_length(e)
        broken_family(cr%edge_family(e)) = broken_family(cr%edge_family(e)) + cr%edge_length(e)
        nbroken = nbroken + 1
      else if (dmg(e)) then
        damaged = damaged + cr%edge_length(e)
        ndamaged = ndamaged + 1
      end if
    end do
  end subroutine cracks_lengths

  !> The broken edges joined into cracks: edges whose end points coincide in
  !> the reference configuration belong to the same crack. Cracks are numbered
  !> by decreasing length; the main crack's origin is the middle of its first
  !> broken edge and its tip the crack end farthest from that origin.
  subroutine cracks_paths(cr, m, paths)
    type(cracks_t), intent(in) :: cr
    type(mailx_t), intent(in) :: m
    type(crack_paths_t), intent(out) :: paths
    integer, allocatable :: edges(:), vert(:, :), parent(:), comp(:), rank_of(:), degree(:), order(:)
    real(wp), allocatable :: refp(:, :), curp(:, :), clen(:)
    integer :: nb, i, j, nv, c, e, first_e, v
    real(wp) :: tol, best, d
    edges = pack([(e, e=1, cr%nedges)], cr%edge_broken_step > 0)
    nb = size(edges)
    allocate (paths%seg(2, nb), paths%seg_crack(nb))
    if (nb == 0) then
      allocate (paths%points(2, 0), paths%crack_length(0))
      return
    end if
    ! End points, identified by their reference position (nodes are copied
    ! per element in an exploded mesh).
    allocate (refp(2, 2 * nb), curp(2, 2 * nb))
    do i = 1, nb
      do j = 1, 2
        refp(:, 2 * i - 2 + j) = m%ref(:, cr%edge_nodes(j, edges(i)))
        curp(:, 2 * i - 2 + j) = m%ref(:, cr%edge_nodes(j, edges(i))) + m%x(:, cr%edge_nodes(j, edges(i)))
      end do
    end do
    tol = 1.0e-6_wp * max(maxval(cr%edge_length), tiny(1.0_wp))
    call merge_points(refp, tol, vert, nv)
    allocate (paths%points(2, nv), degree(nv), parent(nv))
    do i = 1, 2 * nb
      paths%points(:, vert(1, i)) = curp(:, i)
    end do
    degree = 0
    parent = [(i, i=1, nv)]
    do i = 1, nb
      paths%seg(:, i) = [vert(1, 2 * i - 1), vert(1, 2 * i)]
      degree(paths%seg(:, i)) = degree(paths%seg(:, i)) + 1
      call unite(parent, paths%seg(1, i), paths%seg(2, i))
    end do
    ! Components, numbered by decreasing length
    allocate (comp(nv))
    comp = 0
    c = 0
    do v = 1, nv
      if (comp(find(parent, v)) == 0) then
        c = c + 1
        comp(find(parent, v)) = c
      end if
    end do
    allocate (clen(c))
    clen = 0.0_wp
    do i = 1, nb
      j = comp(find(parent, paths%seg(1, i)))
      clen(j) = clen(j) + cr%edge_length(edges(i))
    end do
    order = sort_decreasing(clen)
    allocate (rank_of(c))
    rank_of(order) = [(i, i=1, c)]
    paths%ncracks = c
    paths%crack_length = clen(order)
    do i = 1, nb
      paths%seg_crack(i) = rank_of(comp(find(parent, paths%seg(1, i))))
    end do
    ! Main crack: origin at its first broken edge, tip the farthest end.
    first_e = 0
    do i = 1, nb
      if (paths%seg_crack(i) /= 1) cycle
      if (first_e == 0) then
        first_e = i
      else if (cr%edge_broken_step(edges(i)) < cr%edge_broken_step(edges(first_e))) then
        first_e = i
      end if
    end do
    paths%origin = 0.5_wp * (m%ref(:, cr%edge_nodes(1, edges(first_e))) + m%ref(:, cr%edge_nodes(2, edges(first_e))))
    best = -1.0_wp
    do i = 1, 2 * nb
      v = vert(1, i)
      if (paths%seg_crack((i + 1) / 2) /= 1) cycle
      if (degree(v) /= 1 .and. any(degree == 1)) cycle
      d = norm2(refp(:, i) - paths%origin)
      if (d > best) then
        best = d
        paths%tip = refp(:, i)
      end if
    end do
  end subroutine cracks_paths

  !> Fragments: the meshed bodies still held together through glued points
  !> that are not broken, as connected pieces; piece(b) numbers the fragment
  !> of body b (1..nfrag).
  subroutine cracks_fragments(cr, m, piece, nfrag)
    type(cracks_t), intent(in) :: cr
    type(mailx_t), intent(in) :: m
    integer, allocatable, intent(out) :: piece(:)
    integer, intent(out) :: nfrag
    integer, allocatable :: parent(:), root_id(:)
    integer :: p, b, r
    allocate (parent(m%n), piece(m%n), root_id(m%n))
    parent = [(b, b=1, m%n)]
    do p = 1, cr%npts
      if (.not. cr%pt_glued(p) .or. cr%pt_beta(p) <= 0.0_wp .or. cr%pt_partner(p) == 0) cycle
      call unite(parent, cr%edge_body(cr%pt_edge(p)), cr%pt_partner(p))
    end do
    root_id = 0
    nfrag = 0
    do b = 1, m%n
      r = find(parent, b)
      if (root_id(r) == 0) then
        nfrag = nfrag + 1
        root_id(r) = nfrag
      end if
      piece(b) = root_id(r)
    end do
  end subroutine cracks_fragments

  !> Fragments as bodies (from the lumped nodal masses of the meshes, per unit
  !> thickness): counts of meshed bodies and elements, mass, centre of mass,
  !> velocity of the centre (momentum / mass), kinetic energy (1/2 sum m v^2),
  !> second moments of mass about the centre (Jxx, Jyy, Jxy), polar moment
  !> (Jxx + Jyy: the inertia of the fragment turning in the plane) and the
  !> principal moments (largest first) with the angle of the major axis from x.
  subroutine cracks_fragment_stats(m, piece, nfrag, f)
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: piece(:), nfrag
    type(fragments_t), intent(out) :: f
    real(wp) :: x(2), mn, d(2), half, rad
    integer :: b, k, i
    allocate (f%bodies(nfrag), f%elements(nfrag), f%mass(nfrag), f%centre(2, nfrag), f%velocity(2, nfrag), &
              f%kinetic(nfrag), f%moments(3, nfrag), f%polar(nfrag), f%principal(2, nfrag), f%angle(nfrag))
    f%bodies = 0; f%elements = 0; f%mass = 0.0_wp; f%centre = 0.0_wp; f%velocity = 0.0_wp
    f%kinetic = 0.0_wp; f%moments = 0.0_wp
    do b = 1, m%n
      k = piece(b)
      f%bodies(k) = f%bodies(k) + 1
      f%elements(k) = f%elements(k) + m%elem_first(b + 1) - m%elem_first(b)
      do i = m%node_first(b), m%node_first(b + 1) - 1
        mn = m%mdiag(1, i)
        x = m%ref(:, i) + m%x(:, i)
        f%mass(k) = f%mass(k) + mn
        f%centre(:, k) = f%centre(:, k) + mn * x
        f%velocity(:, k) = f%velocity(:, k) + mn * m%v(:, i)
        f%kinetic(k) = f%kinetic(k) + 0.5_wp * mn * sum(m%v(:, i)**2)
      end do
    end do
    do k = 1, nfrag
      if (f%mass(k) > 0.0_wp) then
        f%centre(:, k) = f%centre(:, k) / f%mass(k)
        f%velocity(:, k) = f%velocity(:, k) / f%mass(k)
      end if
    end do
    do b = 1, m%n          ! second moments about the centres, once these are known
      k = piece(b)
      do i = m%node_first(b), m%node_first(b + 1) - 1
        d = m%ref(:, i) + m%x(:, i) - f%centre(:, k)
        f%moments(:, k) = f%moments(:, k) + m%mdiag(1, i) * [d(1)**2, d(2)**2, d(1) * d(2)]
      end do
    end do
    do k = 1, nfrag
      associate (j => f%moments(:, k))
        f%polar(k) = j(1) + j(2)
        half = 0.5_wp * (j(1) + j(2))
        rad = sqrt((0.5_wp * (j(1) - j(2)))**2 + j(3)**2)
        f%principal(:, k) = [half + rad, half - rad]
        f%angle(k) = 0.5_wp * atan2(2.0_wp * j(3), j(1) - j(2))
      end associate
    end do
  end subroutine cracks_fragment_stats

  ! ---- small helpers: union-find, sorting, merging coincident points ----

  recursive integer function find(parent, i) result(r)
    integer, intent(inout) :: parent(:)
    integer, intent(in) :: i
    if (parent(i) == i) then
      r = i
    else
      r = find(parent, parent(i))
      parent(i) = r
    end if
  end function find

  subroutine unite(parent, a, b)
    integer, intent(inout) :: parent(:)
    integer, intent(in) :: a, b
    integer :: ra, rb
    ra = find(parent, a); rb = find(parent, b)
    if (ra /= rb) parent(max(ra, rb)) = min(ra, rb)
  end subroutine unite

  !> Order of integer keys (3, n) in lexicographic order (merge sort, stable).
  function sort_keys(key) result(order)
    integer, intent(in) :: key(:, :)
    integer, allocatable :: order(:)
    integer :: n, i
    n = size(key, 2)
    order = [(i, i=1, n)]
    call msort(order)
  contains
    recursive subroutine msort(a)
      integer, intent(inout) :: a(:)
      integer :: mid, i, j, k
      integer, allocatable :: l(:), r(:)
      if (size(a) < 2) return
      mid = size(a) / 2
      l = a(1:mid); r = a(mid + 1:)
      call msort(l); call msort(r)
      i = 1; j = 1; k = 1
      do while (i <= size(l) .and. j <= size(r))
        if (.not. less(key(:, r(j)), key(:, l(i)))) then
          a(k) = l(i); i = i + 1
        else
          a(k) = r(j); j = j + 1
        end if
        k = k + 1
      end do
      a(k:) = [l(i:), r(j:)]
    end subroutine msort
    pure logical function less(x, y)
      integer, intent(in) :: x(:), y(:)
      integer :: q
      less = .false.
      do q = 1, size(x)
        if (x(q) /= y(q)) then
          less = x(q) < y(q)
          return
        end if
      end do
    end function less
  end function sort_keys

  !> Order of the values from the largest down.
  function sort_decreasing(x) result(order)
    real(wp), intent(in) :: x(:)
    integer, allocatable :: order(:)
    integer :: i
    ! selection sort: crack counts are small
    order = [(i, i=1, size(x))]
    do i = 1, size(x) - 1
      call swap_max(i)
    end do
  contains
    subroutine swap_max(i)
      integer, intent(in) :: i
      integer :: j, tmp
      j = i - 1 + maxloc(x(order(i:)), dim=1)
      tmp = order(i); order(i) = order(j); order(j) = tmp
    end subroutine swap_max
  end function sort_decreasing

  !> Vertex ids for points (2, n): points equal after rounding to the grid tol
  !> share an id (an exploded mesh copies its nodes exactly).
  subroutine merge_points(p, tol, vert, nv)
    real(wp), intent(in) :: p(:, :), tol
    integer, allocatable, intent(out) :: vert(:, :)
    integer, intent(out) :: nv
    integer, allocatable :: key(:, :), order(:)
    integer :: i, n
    n = size(p, 2)
    allocate (key(3, n), vert(1, n))
    do i = 1, n
      key(:, i) = [nint(p(1, i) / tol), nint(p(2, i) / tol), 0]
    end do
    order = sort_keys(key)
    nv = 0
    do i = 1, n
      if (i == 1) then
        nv = 1
      else if (any(key(1:2, order(i)) /= key(1:2, order(i - 1)))) then
        nv = nv + 1
      end if
      vert(1, order(i)) = nv
    end do
  end subroutine merge_points
end module fracas_cracks
