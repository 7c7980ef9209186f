!> Contact detection: the see table (which contactor classes meet, with which
!> law and alert distance), the broad phase with cell lists (cost linear in the
!> number of contactors) and the fine detection per interaction type.
module fracas_detection
  use fracas_kinds, only: wp, i8
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use fracas_deck, only: see_rule_input_t
  use fracas_errors, only: input_error, fatal, itoa
  use fracas_ids, only: i_dkdkx, i_dkjcx, i_dkkdx, i_dkplx, i_plplx, i_pljcx, i_clalp, i_cljcx, i_dkalp, i_plalp, &
                        st_noctc, bm_rigid, bm_mesh, tactor_kind_id
  use fracas_contactors, only: tactors_t, tactor_center, tactor_vertices, tk_disk, tk_xksid, tk_jonc, tk_polyg, &
                               tk_clxxx, tk_alpxx, cl_point, tactor_kind_name
  use fracas_mesh_pairs, only: point_polyline, point_segment_distance
  use fracas_contacts, only: contacts_t, contacts_reserve
  use fracas_rbdy2_side, only: rigid2_levers, rigid2_point_velocity
  use fracas_mailx_side, only: mesh2_point_velocity
  use fracas_dkdkx, only: dkdkx_geometry
  use fracas_dkjcx, only: dkjcx_geometry
  use fracas_dkkdx, only: dkkdx_geometry
  use fracas_dkplx, only: dkplx_geometry
  use fracas_plplx, only: polygon_pair, polygon_contact_t
  implicit none
  private
  public :: detection_t, detection_init, detect_rough, detect_fine

  type :: detection_t
    integer :: ncls = 0
    integer, allocatable :: cls(:)             !< class (kind, colour) of each contactor
    integer, allocatable :: rule_law(:, :)     !< (cd class, an class) -> law index, 0: none
    real(wp), allocatable :: rule_alert(:, :)  !< alert distance of that rule
    logical, allocatable :: may_meet(:, :)     !< (class, class): some rule pairs them, either way
    real(wp) :: max_alert = 0.0_wp
    real(wp) :: rigid_median = 0.0_wp          !< median bound of disks and polygons
    logical, allocatable :: small(:)           !< binned in the cell grid (ordinary disks)
    ! rough pairs, kept between rough detections (candidate first)
    integer :: npairs = 0
    integer, allocatable :: pair_cd(:), pair_an(:), pair_inter(:), pair_law(:)
    real(wp), allocatable :: pair_alert(:)
  end type detection_t

contains

  !> Interaction type for a (candidate kind, antagonist kind), 0 if none.
  pure integer function inter_of(kcd, kan)
    integer, intent(in) :: kcd, kan
    inter_of = 0
    if (kcd == tk_disk .and. kan == tk_disk) inter_of = i_dkdkx
    if (kcd == tk_disk .and. kan == tk_jonc) inter_of = i_dkjcx
    if (kcd == tk_disk .and. kan == tk_xksid) inter_of = i_dkkdx
    if (kcd == tk_disk .and. kan == tk_polyg) inter_of = i_dkplx
    if (kcd == tk_polyg .and. kan == tk_polyg) inter_of = i_plplx
    if (kcd == tk_polyg .and. kan == tk_jonc) inter_of = i_pljcx
    if (kcd == tk_clxxx .and. kan == tk_alpxx) inter_of = i_clalp
    if (kcd == tk_clxxx .and. kan == tk_jonc) inter_of = i_cljcx
    if (kcd == tk_disk .and. kan == tk_alpxx) inter_of = i_dkalp
    if (kcd == tk_polyg .and. kan == tk_alpxx) inter_of = i_plalp
  end function inter_of

  !> Build the see table from the $seety rules. law_nicknames(i) names law i.
  subroutine detection_init(det, t, rules, law_nicknames)
    type(detection_t), intent(out) :: det
    type(tactors_t), intent(in) :: t
    type(see_rule_input_t), intent(in) :: rules(:)
    character(len=5), intent(in) :: law_nicknames(:)
    character(len=5), allocatable :: cls_kind(:), cls_color(:)
    character(len=5) :: kname
    integer :: k, j, r, icd, ian, ilaw
    real(wp) :: rmed
    real(wp), allocatable :: radii(:)
    allocate (det%cls(t%n), cls_kind(0), cls_color(0))
    do k = 1, t%n
      kname = tactor_kind_name(t%kind(k))
      det%cls(k) = 0
      do j = 1, size(cls_kind)
        if (cls_kind(j) == kname .and. cls_color(j) == t%color(k)) det%cls(k) = j
      end do
      if (det%cls(k) == 0) then
        cls_kind = [character(len=5) :: cls_kind, kname]
        cls_color = [character(len=5) :: cls_color, t%color(k)]
        det%cls(k) = size(cls_kind)
      end if
    end do
    det%ncls = size(cls_kind)
    allocate (det%rule_law(det%ncls, det%ncls), det%rule_alert(det%ncls, det%ncls))
    det%rule_law = 0
    det%rule_alert = 0.0_wp
    do r = 1, size(rules)
      associate (s => rules(r))
        ilaw = 0
        do j = 1, size(law_nicknames)
          if (law_nicknames(j) == s%behav) ilaw = j
        end do
        if (ilaw == 0) call input_error(s%src%file, s%src%line, 23, "see rule names law '"// &
          s%behav//"' that TACT_BEHAV.DAT does not define")
        if (s%alert < 0.0_wp) call input_error(s%src%file, s%src%line, 55, &
          'alert distance must be >= 0')
        icd = find_cls(s%cdtac, s%cdcol)
        ian = find_cls(s%antac, s%ancol)
        ! No contactor of that class: the rule is unused (LMGC90's old decks
        ! carry rules in an older layout, e.g. 'DISKx  BDARY', that match nothing).
        if (icd == 0 .or. ian == 0) cycle
        call check_body_model(s, s%cdbdy, s%cdtac, 2)
        call check_body_model(s, s%anbdy, s%antac, 44)
        det%rule_law(icd, ian) = ilaw
        det%rule_alert(icd, ian) = s%alert
        det%max_alert = max(det%max_alert, s%alert)
      end associate
    end do
    ! The broad phase rejects most pairs (two points, two segments) at once.
    allocate (det%may_meet(det%ncls, det%ncls))
    do j = 1, det%ncls
      do k = 1, det%ncls
        det%may_meet(k, j) = (det%rule_law(k, j) /= 0 .and. inter_of(tactor_kind_id(cls_kind(k)), &
                                                                    tactor_kind_id(cls_kind(j))) /= 0) .or. &
                             (det%rule_law(j, k) /= 0 .and. inter_of(tactor_kind_id(cls_kind(j)), &
                                                                    tactor_kind_id(cls_kind(k))) /= 0)
      end do
    end do
    ! Ordinary disks and polygons go into the cell grid; much larger ones (and
    ! walls, drums) are "big" and tested against all. Mesh contactors are
    ! sorted at each rough detection (their size follows the mesh).
    allocate (det%small(t%n))
    radii = pack(t%bound, t%kind == tk_disk .or. t%kind == tk_polyg)
    rmed = 0.0_wp
    if (size(radii) > 0) rmed = median(radii)
    det%rigid_median = rmed
    det%small = (t%kind == tk_disk .or. t%kind == tk_polyg) .and. t%bound <= 10.0_wp * rmed
    det%npairs = 0
    allocate (det%pair_cd(0), det%pair_an(0), det%pair_inter(0), det%pair_law(0), det%pair_alert(0))

  contains

    !> A see rule's body model must be the one its contactor type lives on.
    subroutine check_body_model(rule, bdy, tac, col)
      type(see_rule_input_t), intent(in) :: rule
      character(len=5), intent(in) :: bdy, tac
      integer, intent(in) :: col
      character(len=5) :: expected
      expected = 'RBDY2'
      if (tac == 'CLxxx' .or. tac == 'ALpxx') expected = 'MAILx'
      if (bdy /= expected) call input_error(rule%src%file, rule%src%line, col, "see rule: contactor '"//tac// &
        "' belongs to body model "//expected//", found '"//bdy//"'")
    end subroutine check_body_model

    integer function find_cls(kind, color)
      character(len=5), intent(in) :: kind, color
      integer :: i
      find_cls = 0
      do i = 1, det%ncls
        if (cls_kind(i) == kind .and. cls_color(i) == color) find_cls = i
      end do
    end function find_cls
  end subroutine detection_init

  !> Median (upper median for an even count) by quickselect: linear on average.
  real(wp) function median(x)
    real(wp), intent(in) :: x(:)
    real(wp), allocatable :: s(:)
    integer :: lo, hi, i, j, k
    real(wp) :: pivot, tmp
    s = x
    k = (size(s) + 1) / 2
    lo = 1; hi = size(s)
    do while (lo < hi)
      pivot = s((lo + hi) / 2)
      i = lo; j = hi
      do while (i <= j)
        do while (s(i) < pivot)
          i = i + 1
        end do
        do while (s(j) > pivot)
          j = j - 1
        end do
        if (i <= j) then
          tmp = s(i); s(i) = s(j); s(j) = tmp
          i = i + 1; j = j - 1
        end if
      end do
      if (k <= j) then
        hi = j
      else if (k >= i) then
        lo = i
      else
        exit
      end if
    end do
    median = s(k)
  end function median

  !> Broad phase: every pair of contactors of different bodies, allowed by the
  !> see table, whose bounding circles come within alert + margin. Ordinary
  !> disks, polygons and mesh contactors are binned in square cells; big
  !> contactors are tested against all. Cells are visited row by row, each
  !> against the forward half of its neighbours, so pairs come in cell order
  !> (spatially sorted contacts). The grid is dense (a counting sort) while it
  !> has at most about 4 cells per contactor; a sparse scene (bodies far apart or
  !> one far away) keeps only its occupied cells, sorted by (row, column): memory
  !> stays linear whatever the distances. With the same cell size both give the
  !> same pairs in the same order. Contactors whose centre is not finite are left
  !> out (the run's state check stops such a run at the end of the step).
  !> q(3, rigid bodies) places rigid contactors, xn(2, mesh nodes) mesh ones.
  !> movable / mesh_movable: false for bodies whose every dof is driven.
  !> sparse_grid forces the sparse cells (tests).
  subroutine detect_rough(det, t, q, movable, margin, xn, mesh_movable, sparse_grid)
    type(detection_t), intent(inout) :: det
    type(tactors_t), intent(in) :: t
    real(wp), intent(in) :: q(:, :), margin
    logical, intent(in) :: movable(:)
    real(wp), intent(in), optional :: xn(:, :)
    logical, intent(in), optional :: mesh_movable(:)
    logical, intent(in), optional :: sparse_grid
    real(wp), allocatable :: c(:, :), bound(:)
    integer, allocatable :: cell_of(:), cell_start(:), items(:), fill(:), bigs(:)
    integer(i8), allocatable :: key(:), cell_key(:)
    logical, allocatable :: binned(:), usable(:)
    integer :: k, j, nx, ny, ix, iy, jx, jy, cell, p, nsmall, ib, ncell
    real(wp) :: lo(2), hi(2), size_cell, reach_cell, rmax, cells
    logical :: sparse
    allocate (c(2, t%n), bound(t%n))
    do k = 1, t%n
      call placement(t, k, q, xn, c(:, k), bound(k))
      ! Mesh contactors join the grid unless much larger than the rigid ones
      ! (a long polyline is tested against all, as a wall).
      if (t%model(k) == bm_mesh) det%small(k) = t%kind(k) == tk_clxxx .or. &
        det%rigid_median <= 0.0_wp .or. bound(k) <= 10.0_wp * det%rigid_median
    end do
    usable = ieee_is_finite(c(1, :)) .and. ieee_is_finite(c(2, :))
    binned = det%small .and. usable
    det%npairs = 0
    nsmall = count(binned)
    bigs = pack([(k, k=1, t%n)], .not. det%small .and. usable)
    if (nsmall > 0) then
      rmax = maxval(bound, mask=binned)
      reach_cell = 2.0_wp * rmax + det%max_alert + margin
      lo = [minval(c(1, :), mask=binned), minval(c(2, :), mask=binned)]
      hi = [maxval(c(1, :), mask=binned), maxval(c(2, :), mask=binned)]
      ! Dense grid: cells enlarged to about 4 per disk for thin scenes; if it
      ! would still have more, the sparse grid with the smallest cells.
      size_cell = max(reach_cell, sqrt(max((hi(1) - lo(1)) * (hi(2) - lo(2)), tiny(1.0_wp)) / (4.0_wp * nsmall)))
      cells = ((hi(1) - lo(1)) / size_cell + 1.0_wp) * ((hi(2) - lo(2)) / size_cell + 1.0_wp)
      sparse = .not. (cells <= 4.0_wp * nsmall + 64.0_wp)
      if (present(sparse_grid)) sparse = sparse .or. sparse_grid
      if (sparse) size_cell = reach_cell
      allocate (cell_of(t%n), items(nsmall))
      if (.not. sparse) then
        nx = max(1, int((hi(1) - lo(1)) / size_cell) + 1)
        ny = max(1, int((hi(2) - lo(2)) / size_cell) + 1)
        allocate (cell_start(nx * ny + 1))
        cell_start = 0
        do k = 1, t%n
          if (.not. binned(k)) cycle
          ix = min(nx - 1, int((c(1, k) - lo(1)) / size_cell))
          iy = min(ny - 1, int((c(2, k) - lo(2)) / size_cell))
          cell_of(k) = 1 + ix + nx * iy
          cell_start(cell_of(k) + 1) = cell_start(cell_of(k) + 1) + 1
        end do
        cell_start(1) = 1
        do k = 1, nx * ny
          cell_start(k + 1) = cell_start(k + 1) + cell_start(k)
        end do
        fill = cell_start(1:nx * ny)
        do k = 1, t%n
          if (.not. binned(k)) cycle
          items(fill(cell_of(k))) = k
          fill(cell_of(k)) = fill(cell_of(k)) + 1
        end do
        ! Each pair once: j > k within a cell, all of the forward half-stencil of neighbour cells.
        do cell = 1, nx * ny
          ix = mod(cell - 1, nx)
          iy = (cell - 1) / nx
          do p = cell_start(cell), cell_start(cell + 1) - 1
            k = items(p)
            do jy = iy, min(ny - 1, iy + 1)
              do jx = max(0, ix - 1), min(nx - 1, ix + 1)
                if (jy == iy .and. jx < ix) cycle
                call scan_cell(k, 1 + jx + nx * jy, jx == ix .and. jy == iy, p)
              end do
            end do
          end do
        end do
      else
        ! Occupied cells only: key = row * 2^31 + column (indices clamped to
        ! 2^30; clamping keeps neighbours neighbours), sorted stably.
        allocate (key(nsmall))
        j = 0
        do k = 1, t%n
          if (.not. binned(k)) cycle
          j = j + 1
          items(j) = k
          key(j) = cell_index(c(2, k) - lo(2)) * 2_i8**31 + cell_index(c(1, k) - lo(1))
        end do
        call sort_by_key(key, items)
        ncell = 0
        allocate (cell_key(nsmall), cell_start(nsmall + 1))
        do j = 1, nsmall
          if (j > 1) then
            if (key(j) == key(j - 1)) cycle
          end if
          ncell = ncell + 1
          cell_key(ncell) = key(j)
          cell_start(ncell) = j
        end do
        cell_start(ncell + 1) = nsmall + 1
        do cell = 1, ncell
          do p = cell_start(cell), cell_start(cell + 1) - 1
            k = items(p)
            call scan_cell(k, cell, .true., p)
            call scan_key(k, cell_key(cell) + 1_i8)
            call scan_key(k, cell_key(cell) + 2_i8**31 - 1_i8)
            call scan_key(k, cell_key(cell) + 2_i8**31)
            call scan_key(k, cell_key(cell) + 2_i8**31 + 1_i8)
          end do
        end do
      end if
    end if
    do ib = 1, size(bigs)
      k = bigs(ib)
      do j = 1, t%n
        if (j == k .or. .not. usable(j)) cycle
        if (.not. det%small(j) .and. j < k) cycle    ! big-big pairs once
        call consider(k, j)
      end do
    end do

  contains

    subroutine scan_cell(k, other, same, p)
      integer, intent(in) :: k, other, p
      logical, intent(in) :: same
      integer :: i, first
      first = cell_start(other)
      if (same) first = p + 1
      do i = first, cell_start(other + 1) - 1
        call consider(k, items(i))
      end do
    end subroutine scan_cell

    !> Sparse grid: scan the occupied cell of key kk, if any (binary search).
    !> Keys of a column overflow (column -1 or 2^30) are never occupied.
    subroutine scan_key(k, kk)
      integer, intent(in) :: k
      integer(i8), intent(in) :: kk
      integer :: a, b, m
      a = 1; b = ncell
      do while (a <= b)
        m = (a + b) / 2
        if (cell_key(m) == kk) then
          call scan_cell(k, m, .false., 0)
          return
        else if (cell_key(m) < kk) then
          a = m + 1
        else
          b = m - 1
        end if
      end do
    end subroutine scan_key

    !> Cell index of a coordinate offset from the grid origin, clamped to [0, 2^30 - 1].
    integer(i8) function cell_index(d)
      real(wp), intent(in) :: d
      real(wp) :: x
      x = d / size_cell
      if (x < 2.0_wp**30) then
        cell_index = int(x, i8)
      else
        cell_index = 2_i8**30 - 1_i8
      end if
    end function cell_index

    !> Keep (a, b) if the see table allows it and the bounding shapes are close.
    subroutine consider(a, b)
      integer, intent(in) :: a, b
      integer :: icd, ian, inter, law
      real(wp) :: alert, dist, reach
      if (.not. det%may_meet(det%cls(a), det%cls(b))) return
      ! Most pairs of neighbouring cells are far apart: reject them first.
      if (t%kind(a) /= tk_xksid .and. t%kind(b) /= tk_xksid) then
        reach = bound(a) + bound(b) + det%max_alert + margin
        if ((c(1, a) - c(1, b))**2 + (c(2, a) - c(2, b))**2 > reach**2) return
      end if
      if (t%body(a) == t%body(b) .and. t%model(a) == t%model(b)) return
      ! Bodies whose every dof is driven still interact (a cohesive interface
      ! tested by driving both sides): LMGC90 keeps their contacts too.
      ! Orientation: the interaction type decides which side is the candidate;
      ! for two disks the lower index is the candidate unless only the reverse rule exists.
      icd = a; ian = b
      if (inter_of(t%kind(a), t%kind(b)) == 0 .or. &
          (t%kind(a) == t%kind(b) .and. a > b)) then
        icd = b; ian = a
      end if
      inter = inter_of(t%kind(icd), t%kind(ian))
      if (inter == 0) return
      law = det%rule_law(det%cls(icd), det%cls(ian))
      alert = det%rule_alert(det%cls(icd), det%cls(ian))
      if (law == 0 .and. t%kind(icd) == t%kind(ian)) then
        law = det%rule_law(det%cls(ian), det%cls(icd))
        alert = det%rule_alert(det%cls(ian), det%cls(icd))
        if (law /= 0) then
          p_swap: block
            integer :: tmp
            tmp = icd; icd = ian; ian = tmp
          end block p_swap
        end if
      end if
      if (law == 0) return
      dist = norm2(c(:, icd) - c(:, ian))
      reach = alert + margin
      if (t%kind(ian) == tk_xksid) then
        if (dist + bound(icd) < t%radius(ian) - reach) return
      else
        if (dist > bound(icd) + bound(ian) + reach) return
      end if
      call push_pair(icd, ian, inter, law, alert)
    end subroutine consider


    subroutine push_pair(icd, ian, inter, law, alert)
      integer, intent(in) :: icd, ian, inter, law
      real(wp), intent(in) :: alert
      integer :: np
      np = det%npairs + 1
      if (np > size(det%pair_cd)) then
        det%pair_cd = grow_int(det%pair_cd)
        det%pair_an = grow_int(det%pair_an)
        det%pair_inter = grow_int(det%pair_inter)
        det%pair_law = grow_int(det%pair_law)
        det%pair_alert = grow_real(det%pair_alert)
      end if
      det%pair_cd(np) = icd
      det%pair_an(np) = ian
      det%pair_inter(np) = inter
      det%pair_law(np) = law
      det%pair_alert(np) = alert
      det%npairs = np
    end subroutine push_pair
  end subroutine detect_rough

  pure function grow_int(a) result(b)
    integer, intent(in) :: a(:)
    integer, allocatable :: b(:)
    allocate (b(max(64, 2 * size(a))))
    b(1:size(a)) = a
  end function grow_int

  !> Stable merge sort of (key, item) pairs by key.
  subroutine sort_by_key(key, item)
    integer(i8), intent(inout) :: key(:)
    integer, intent(inout) :: item(:)
    integer(i8), allocatable :: kt(:)
    integer, allocatable :: it(:)
    integer :: n, width, a, m, b, i, j, o
    n = size(key)
    allocate (kt(n), it(n))
    width = 1
    do while (width < n)
      a = 1
      do while (a <= n)
        m = min(a + width, n + 1)
        b = min(a + 2 * width, n + 1)
        i = a; j = m; o = a
        do while (i < m .and. j < b)
          if (key(j) < key(i)) then
            kt(o) = key(j); it(o) = item(j); j = j + 1
          else
            kt(o) = key(i); it(o) = item(i); i = i + 1
          end if
          o = o + 1
        end do
        do while (i < m)
          kt(o) = key(i); it(o) = item(i); i = i + 1; o = o + 1
        end do
        do while (j < b)
          kt(o) = key(j); it(o) = item(j); j = j + 1; o = o + 1
        end do
        a = b
      end do
      key = kt
      item = it
      width = 2 * width
    end do
  end subroutine sort_by_key
  !> Centre and bounding radius of contactor k: rigid shapes from their body's
  !> configuration q, mesh contactors from the node coordinates xn.
  subroutine placement(t, k, q, xn, centre, bound)
    type(tactors_t), intent(in) :: t
    integer, intent(in) :: k
    real(wp), intent(in) :: q(:, :)
    real(wp), intent(in), optional :: xn(:, :)
    real(wp), intent(out) :: centre(2), bound
    real(wp) :: lo(2), hi(2)
    integer :: j
    select case (t%kind(k))
    case (tk_clxxx)
      centre = cl_point(t, k, xn)
      bound = 0.0_wp
    case (tk_alpxx)
      lo = huge(1.0_wp); hi = -huge(1.0_wp)
      do j = t%nfirst(k), t%nfirst(k + 1) - 1
        lo = min(lo, xn(:, t%nodes(j)))
        hi = max(hi, xn(:, t%nodes(j)))
      end do
      centre = 0.5_wp * (lo + hi)
      bound = 0.5_wp * norm2(hi - lo)
    case default
      centre = tactor_center(t, k, q(:, t%body(k)))
      bound = t%bound(k)
    end select
  end subroutine placement

  pure function grow_real(a) result(b)
    real(wp), intent(in) :: a(:)
    real(wp), allocatable :: b(:)
    allocate (b(max(64, 2 * size(a))))
    b(1:size(a)) = a
  end function grow_real


  !> Fine detection of the rough pairs at configuration q (rigid bodies) and
  !> xn (mesh nodes): every pair whose gap is within its alert distance becomes
  !> a contact (polygon pairs: up to two; a disk against a polyline: one per
  !> segment within the alert distance) with its local frame, gap, contact
  !> point, and lever arms (rigid sides) or nodes and weights (mesh sides).
  !> With the step's free velocities (vq rigid, vm mesh nodes) and time step h,
  !> a pair is also a contact when its predicted gap, gap + h min(0, u_n), is
  !> within the alert distance: bodies approaching faster than alert / h are
  !> caught before they overlap (doc/solver.md).
  subroutine detect_fine(det, t, q, c, xn, vq, vm, h)
    type(detection_t), intent(in) :: det
    type(tactors_t), intent(in) :: t
    real(wp), intent(in) :: q(:, :)
    type(contacts_t), intent(inout) :: c
    real(wp), intent(in), optional :: xn(:, :), vq(:, :), vm(:, :), h
    integer :: p, icd, ian, bcd, ban, iedge, j, nmax, seg, na, nb
    real(wp) :: gap, normal(2), point(2), ccd(2), can(2), len, s, pcl(2), reach, alert
    real(wp), allocatable :: pcd(:, :), pan(:, :)
    integer :: mnode(4)
    real(wp) :: mwt(4)
    logical :: found
    type(polygon_contact_t) :: pc
    ! CLALp: the contact kept so far for each candidate point (0: none). As
    ! LMGC90, a candidate point makes one contact, against the antagonist
    ! segment nearest to it over all the antagonists it sees: in an exploded
    ! mesh a point near a corner lies within the alert distance of the edges
    ! of several neighbouring elements, and gluing it to all of them binds
    ! it at their initial gaps.
    integer, allocatable :: cl_kept(:)
    ! A point that only reaches an antagonist past its polyline's end (within
    ! the end tolerance) is kept there only if no antagonist has it over a
    ! segment: LMGC90 takes no projection past a polyline's end, so at a joint
    ! between two bricks the point goes to the brick it lies over.
    logical, allocatable :: cl_beyond(:)
    logical :: beyond
    ! At most two contacts per pair, one per segment (disk) or vertex (polygon) against a polyline.
    nmax = 0
    do p = 1, det%npairs
      select case (det%pair_inter(p))
      case (i_dkalp)
        nmax = nmax + t%nfirst(det%pair_an(p) + 1) - t%nfirst(det%pair_an(p))
      case (i_plalp)
        nmax = nmax + t%vfirst(det%pair_cd(p) + 1) - t%vfirst(det%pair_cd(p))
      case default
        nmax = nmax + 2
      end select
    end do
    ! The pairs here are 2D (3D contactors and pairs: issue 21).
    if (c%nd /= 2) call fatal('detection: the contact store is '//itoa(c%nd)//'D; only 2D pairs are detected')
    call contacts_reserve(c, nmax)
    c%n = 0
    allocate (cl_kept(t%n), source=0)
    allocate (cl_beyond(t%n), source=.false.)
    do p = 1, det%npairs
      icd = det%pair_cd(p)
      ian = det%pair_an(p)
      bcd = t%body(icd)
      ban = t%body(ian)
      mnode = 0
      mwt = 0.0_wp
      ! Candidates are looked for up to reach; add keeps those whose gap, or
      ! predicted gap, is within the alert distance.
      alert = det%pair_alert(p)
      reach = alert
      if (present(h)) reach = alert + h * (speed(icd) + speed(ian))
      if (t%model(icd) == bm_rigid) ccd = tactor_center(t, icd, q(:, bcd))
      if (t%model(ian) == bm_rigid) can = tactor_center(t, ian, q(:, ban))
      select case (det%pair_inter(p))
      case (i_dkdkx)
        call dkdkx_geometry(ccd, t%radius(icd), can, t%radius(ian), gap, normal, point)
        len = t%radius(icd) * t%radius(ian) / (t%radius(icd) + t%radius(ian))
        call add(icd, ian, 0, 0)
      case (i_dkjcx)
        call dkjcx_geometry(ccd, t%radius(icd), can, q(3, ban), t%ax1(ian), t%ax2(ian), gap, normal, point)
        len = t%radius(icd)
        call add(icd, ian, 0, 0)
      case (i_dkkdx)
        call dkkdx_geometry(ccd, t%radius(icd), can, t%radius(ian), gap, normal, point)
        len = t%radius(icd)
        call add(icd, ian, 0, 0)
      case (i_dkplx)
        pan = tactor_vertices(t, ian, q(:, ban))
        call dkplx_geometry(ccd, t%radius(icd), pan, gap, normal, point, iedge)
        len = t%radius(icd)
        call add(icd, ian, 0, iedge)
      case (i_plplx)
        ! The rough pair's first contactor (lower index) is preferred as the
        ! reference face, i.e. the antagonist (as LMGC90 chooses).
        pcd = tactor_vertices(t, icd, q(:, bcd))
        pan = tactor_vertices(t, ian, q(:, ban))
        call polygon_pair(pcd, pan, reach, .false., pc)
        len = pair_length(pc, t%bound(icd) * t%bound(ian) / (t%bound(icd) + t%bound(ian)))
        do j = 1, pc%n
          gap = pc%gap(j); normal = pc%normal; point = pc%point(:, j)
          if (pc%ref_is_a) then
            call add(ian, icd, pc%cdver(j), pc%anseg)
          else
            call add(icd, ian, pc%cdver(j), pc%anseg)
          end if
        end do
      case (i_pljcx)
        pcd = tactor_vertices(t, icd, q(:, bcd))
        call polygon_pair(wall_rectangle(can, q(3, ban), t%ax1(ian), t%ax2(ian)), pcd, reach, &
                          .true., pc)
        len = pair_length(pc, t%bound(icd))
        do j = 1, pc%n
          gap = pc%gap(j); normal = pc%normal; point = pc%point(:, j)
          call add(icd, ian, pc%cdver(j), pc%anseg)
        end do
      case (i_clalp)
        ! A candidate point against the nearest facing segment of the polyline;
        ! the candidate's edge must face the segment (outward normals opposed).
        na = t%nodes(t%nfirst(icd)); nb = t%nodes(t%nfirst(icd) + 1)
        point = cl_point(t, icd, xn)
        call point_polyline(point, xn, t%nodes(t%nfirst(ian):t%nfirst(ian + 1) - 1), reach, alert, &
                            edge_normal(xn(:, na), xn(:, nb)), found, seg, s, gap, normal, beyond)
        if (found .and. cl_kept(icd) > 0) then
          if (beyond .neqv. cl_beyond(icd)) then
            found = .not. beyond
          else
            found = abs(gap) < abs(c%gap(cl_kept(icd)))
          end if
        end if
        if (found) then
          cl_beyond(icd) = beyond
          point = point - gap * normal        ! on the antagonist, as LMGC90 reports it
          len = 0.5_wp * norm2(xn(:, nb) - xn(:, na))
          call mesh_side(1, na, nb, t%apab(icd))
          call mesh_side(3, t%nodes(t%nfirst(ian) + seg - 1), t%nodes(t%nfirst(ian) + seg), s)
          call add(icd, ian, 0, seg, cl_kept(icd))
        end if
      case (i_cljcx)
        na = t%nodes(t%nfirst(icd)); nb = t%nodes(t%nfirst(icd) + 1)
        pcl = cl_point(t, icd, xn)
        call dkjcx_geometry(pcl, 0.0_wp, can, q(3, ban), t%ax1(ian), t%ax2(ian), gap, normal, point)
        normal = normal + 0.0_wp            ! no signed zeros in the outputs
        ! The point on the wall's surface, as LMGC90 reports it.
        point = can + dot_product(pcl - can, [cos(q(3, ban)), sin(q(3, ban))]) * [cos(q(3, ban)), sin(q(3, ban))] + &
                t%ax2(ian) * normal
        len = 0.5_wp * norm2(xn(:, nb) - xn(:, na))
        call mesh_side(1, na, nb, t%apab(icd))
        call add(icd, ian, 0, 0)
      case (i_dkalp)
        ! LMGC90's DKALp: one contact per segment within the alert distance,
        ! normal from the segment's nearest point to the disk centre; the
        ! contact point is that nearest point. (LMGC90 writes a zero length.)
        len = 0.0_wp
        do seg = 1, t%nfirst(ian + 1) - t%nfirst(ian) - 1
          na = t%nodes(t%nfirst(ian) + seg - 1); nb = t%nodes(t%nfirst(ian) + seg)
          call point_segment_distance(ccd, xn(:, na), xn(:, nb), s, gap, normal, point)
          gap = gap - t%radius(icd)
          if (gap > reach) cycle
          call mesh_side(3, na, nb, s)
          call add(icd, ian, seg, seg)
        end do
      case (i_plalp)
        ! Each polygon vertex against the nearest facing segment of the polyline.
        pcd = tactor_vertices(t, icd, q(:, bcd))
        len = 0.0_wp
        do j = 1, size(pcd, 2)
          call point_polyline(pcd(:, j), xn, t%nodes(t%nfirst(ian):t%nfirst(ian + 1) - 1), reach, alert, &
                              vertex_normal(pcd, j), found, seg, s, gap, normal)
          if (.not. found) cycle
          point = pcd(:, j) - gap * normal
          call mesh_side(3, t%nodes(t%nfirst(ian) + seg - 1), t%nodes(t%nfirst(ian) + seg), s)
          call add(icd, ian, j, seg)
        end do
      end select
    end do

  contains

    !> Bound on the speed of contactor k's points over the step.
    real(wp) function speed(k)
      integer, intent(in) :: k
      integer :: j
      speed = 0.0_wp
      if (t%model(k) == bm_mesh) then
        do j = t%nfirst(k), t%nfirst(k + 1) - 1
          speed = max(speed, norm2(vm(:, t%nodes(j))))
        end do
      else
        speed = norm2(vq(1:2, t%body(k))) + abs(vq(3, t%body(k))) * (t%bound(k) + norm2(t%shift(:, k)))
      end if
    end function speed

    !> Normal relative velocity (candidate minus antagonist) of the current
    !> contact point over the step, from the free velocities.
    real(wp) function approach(kcd, kan)
      integer, intent(in) :: kcd, kan
      approach = dot_product(point_velocity(kcd, 1) - point_velocity(kan, 3), normal)
    end function approach

    function point_velocity(k, first) result(v)
      integer, intent(in) :: k, first
      real(wp) :: v(2), r(2)
      integer :: b
      if (t%model(k) == bm_mesh) then
        v = mesh2_point_velocity(vm(:, mnode(first)), vm(:, mnode(first + 1)), mwt(first), mwt(first + 1))
      else
        b = t%body(k)
        r = point - q(1:2, b)
        v = rigid2_point_velocity(vq(:, b), r(1), r(2))
      end if
    end function point_velocity

    !> Nodes and weights of a mesh side (first = 1: candidate, 3: antagonist):
    !> the point at (1 - s) x_a + s x_b.
    subroutine mesh_side(first, a, b, s)
      integer, intent(in) :: first, a, b
      real(wp), intent(in) :: s
      mnode(first:first + 1) = [a, b]
      mwt(first:first + 1) = [1.0_wp - s, s]
    end subroutine mesh_side

    !> Append a contact; its history key within the pair is the candidate vertex
    !> (polygons) or the antagonist segment (a disk against a polyline).
    !> With slot: the contact replaces contact slot (0: appended), and slot
    !> returns where it went.
    subroutine add(kcd, kan, cdver, anseg, slot)
      integer, intent(in) :: kcd, kan, cdver, anseg
      integer, intent(inout), optional :: slot
      integer :: k, b1, b2
      if (gap > alert) then
        if (.not. present(h)) return
        if (gap + h * min(0.0_wp, approach(kcd, kan)) > alert) return
      end if
      if (present(slot)) then
        if (slot == 0) then
          c%n = c%n + 1
          slot = c%n
        end if
        k = slot
      else
        c%n = c%n + 1
        k = c%n
      end if
      b1 = t%body(kcd); b2 = t%body(kan)
      c%inter(k) = det%pair_inter(p)
      c%cd(k) = kcd
      c%an(k) = kan
      c%cdb(k) = b1
      c%anb(k) = b2
      c%cdm(k) = t%model(kcd)
      c%anm(k) = t%model(kan)
      c%law(k) = det%pair_law(p)
      c%sub(k) = cdver
      c%cdver(k) = cdver
      c%anseg(k) = anseg
      c%frame(:, 1, k) = [normal(2), -normal(1)]   ! (t, n), 2D
      c%frame(:, 2, k) = normal
      c%point(:, k) = point
      c%gap(k) = gap
      c%length(k) = len
      ! Rigid sides: lever arms from the body node to the contact point.
      c%lever(:, k) = 0.0_wp
      if (c%cdm(k) == bm_rigid) c%lever(1:2, k) = rigid2_levers(point - q(1:2, b1), normal(1), normal(2))
      if (c%anm(k) == bm_rigid) c%lever(3:4, k) = rigid2_levers(point - q(1:2, b2), normal(1), normal(2))
      if (c%with_mesh) then
        c%mnode(:, k) = mnode
        c%mwt(:, k) = mwt
      end if
      c%status(k) = st_noctc
      c%status_begin(k) = st_noctc
      c%r(:, k) = 0.0_wp
    end subroutine add
  end subroutine detect_fine

  !> Outward normal of a mesh edge walked from a to b (the body on its right).
  pure function edge_normal(a, b) result(n)
    real(wp), intent(in) :: a(2), b(2)
    real(wp) :: n(2), d(2)
    d = b - a
    n = [-d(2), d(1)] / max(norm2(d), tiny(1.0_wp))
  end function edge_normal

  !> Outward direction at vertex j of a counter-clockwise polygon (bisector of
  !> its two edges' outward normals).
  pure function vertex_normal(v, j) result(n)
    real(wp), intent(in) :: v(:, :)
    integer, intent(in) :: j
    real(wp) :: n(2)
    integer :: jp, jn
    jp = merge(size(v, 2), j - 1, j == 1)
    jn = merge(1, j + 1, j == size(v, 2))
    ! Counter-clockwise: the outward normal of edge a->b is (d2, -d1).
    n = -edge_normal(v(:, jp), v(:, j)) - edge_normal(v(:, j), v(:, jn))
    n = n / max(norm2(n), tiny(1.0_wp))
  end function vertex_normal

  !> Length carried by each point of a polygon pair: half the distance between
  !> the two points of a face-to-face pair, else reff pi/18 (as LMGC90).
  pure real(wp) function pair_length(pc, reff)
    type(polygon_contact_t), intent(in) :: pc
    real(wp), intent(in) :: reff
    if (pc%n == 2) then
      pair_length = 0.5_wp * norm2(pc%point(:, 1) - pc%point(:, 2))
    else
      pair_length = reff * acos(-1.0_wp) / 18.0_wp
    end if
  end function pair_length

  !> A JONCx wall as the rectangle of its flat part (counter-clockwise).
  pure function wall_rectangle(c, angle, ax1, ax2) result(v)
    real(wp), intent(in) :: c(2), angle, ax1, ax2
    real(wp) :: v(2, 4), cs, sn
    integer :: i
    real(wp), parameter :: sx(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp], sy(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
    cs = cos(angle); sn = sin(angle)
    do i = 1, 4
      v(1, i) = c(1) + cs * sx(i) * ax1 - sn * sy(i) * ax2
      v(2, i) = c(2) + sn * sx(i) * ax1 + cs * sy(i) * ax2
    end do
  end function wall_rectangle
end module fracas_detection
