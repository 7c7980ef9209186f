!> Contact detection: the see table (which contactor classes meet, with which
!> law and alert distance), the broad phase with cell lists (cost linear in the
!> number of contactors) and the fine detection per interaction type.
module fracas_detection
  use fracas_kinds, only: wp, i8
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use fracas_deck, only: see_rule_input_t
  use fracas_errors, only: input_error
  use fracas_ids, only: i_dkdkx, i_dkjcx, i_dkkdx, i_dkplx, i_plplx, i_pljcx, st_noctc
  use fracas_contactors, only: tactors_t, tactor_center, tactor_vertices, tk_disk, tk_xksid, tk_jonc, tk_polyg
  use fracas_contacts, only: contacts_t, contacts_reserve
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
    real(wp) :: max_alert = 0.0_wp
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
      kname = kind_name(t%kind(k))
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
        if (s%cdbdy /= 'RBDY2' .or. s%anbdy /= 'RBDY2') call input_error(s%src%file, s%src%line, 2, &
          'see rule body model must be RBDY2 (the only body model supported yet)')
        icd = find_cls(s%cdtac, s%cdcol)
        ian = find_cls(s%antac, s%ancol)
        if (icd == 0 .or. ian == 0) cycle   ! no contactor of that class: the rule is unused
        det%rule_law(icd, ian) = ilaw
        det%rule_alert(icd, ian) = s%alert
        det%max_alert = max(det%max_alert, s%alert)
      end associate
    end do
    ! Ordinary disks and polygons go into the cell grid; much larger ones (and
    ! walls, drums) are "big" and tested against all.
    allocate (det%small(t%n))
    radii = pack(t%bound, t%kind == tk_disk .or. t%kind == tk_polyg)
    rmed = 0.0_wp
    if (size(radii) > 0) rmed = median(radii)
    det%small = (t%kind == tk_disk .or. t%kind == tk_polyg) .and. t%bound <= 10.0_wp * rmed
    det%npairs = 0
    allocate (det%pair_cd(0), det%pair_an(0), det%pair_inter(0), det%pair_law(0), det%pair_alert(0))

  contains

    integer function find_cls(kind, color)
      character(len=5), intent(in) :: kind, color
      integer :: i
      find_cls = 0
      do i = 1, det%ncls
        if (cls_kind(i) == kind .and. cls_color(i) == color) find_cls = i
      end do
    end function find_cls

    function kind_name(kind) result(name)
      integer, intent(in) :: kind
      character(len=5) :: name
      select case (kind)
      case (tk_disk); name = 'DISKx'
      case (tk_xksid); name = 'xKSID'
      case (tk_polyg); name = 'POLYG'
      case default; name = 'JONCx'
      end select
    end function kind_name
  end subroutine detection_init

  real(wp) function median(x)
    real(wp), intent(in) :: x(:)
    real(wp), allocatable :: s(:)
    integer :: i, j
    real(wp) :: key
    s = x
    do i = 2, size(s)          ! insertion sort is fine: called once
      key = s(i)
      j = i - 1
      do while (j >= 1)
        if (s(j) <= key) exit
        s(j + 1) = s(j)
        j = j - 1
      end do
      s(j + 1) = key
    end do
    median = s((size(s) + 1) / 2)
  end function median

  !> Broad phase: every pair of contactors of different bodies, allowed by the
  !> see table, whose bounding circles come within alert + margin. Ordinary
  !> disks and polygons are binned in square cells; big contactors are tested
  !> against all. Cells are visited row by row, each against the forward half of
  !> its neighbours, so pairs come in cell order (spatially sorted contacts).
  !> The grid is dense (a counting sort) while it has at most about 4 cells per
  !> contactor; a sparse scene (bodies far apart or one far away) keeps only its
  !> occupied cells, sorted by (row, column): memory stays linear whatever the
  !> distances. With the same cell size both give the same pairs in the same order.
  !> Contactors whose centre is not finite are left out (the run's state check
  !> stops such a run at the end of the step).
  !> movable(b) is false for bodies whose every dof is driven.
  !> sparse_grid forces the sparse cells (tests).
  subroutine detect_rough(det, t, q, movable, margin, sparse_grid)
    type(detection_t), intent(inout) :: det
    type(tactors_t), intent(in) :: t
    real(wp), intent(in) :: q(:, :), margin
    logical, intent(in) :: movable(:)
    logical, intent(in), optional :: sparse_grid
    real(wp), allocatable :: c(:, :)
    integer, allocatable :: cell_of(:), cell_start(:), items(:), fill(:), bigs(:)
    integer(i8), allocatable :: key(:), cell_key(:)
    logical, allocatable :: binned(:), usable(:)
    integer :: k, j, nx, ny, ix, iy, jx, jy, cell, p, nsmall, ib, ncell
    real(wp) :: lo(2), hi(2), size_cell, reach_cell, rmax, cells
    logical :: sparse
    allocate (c(2, t%n))
    do k = 1, t%n
      c(:, k) = tactor_center(t, k, q(:, t%body(k)))
    end do
    usable = ieee_is_finite(c(1, :)) .and. ieee_is_finite(c(2, :))
    binned = det%small .and. usable
    det%npairs = 0
    nsmall = count(binned)
    bigs = pack([(k, k=1, t%n)], .not. det%small .and. usable)
    if (nsmall > 0) then
      rmax = maxval(t%bound, mask=binned)
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
      if (t%body(a) == t%body(b)) return
      if (.not. (movable(t%body(a)) .or. movable(t%body(b)))) return
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
        if (dist + t%bound(icd) < t%radius(ian) - reach) return
      else
        if (dist > t%bound(icd) + t%bound(ian) + reach) return
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

  pure function grow_real(a) result(b)
    real(wp), intent(in) :: a(:)
    real(wp), allocatable :: b(:)
    allocate (b(max(64, 2 * size(a))))
    b(1:size(a)) = a
  end function grow_real


  !> Fine detection of the rough pairs at configuration q: every pair whose gap
  !> is within its alert distance becomes a contact (polygon pairs: up to two)
  !> with its local frame, gap, contact point and lever arms.
  subroutine detect_fine(det, t, q, c)
    type(detection_t), intent(in) :: det
    type(tactors_t), intent(in) :: t
    real(wp), intent(in) :: q(:, :)
    type(contacts_t), intent(inout) :: c
    integer :: p, icd, ian, bcd, ban, iedge, j
    real(wp) :: gap, normal(2), point(2), ccd(2), can(2), len
    real(wp), allocatable :: pcd(:, :), pan(:, :)
    type(polygon_contact_t) :: pc
    call contacts_reserve(c, 2 * det%npairs)
    c%n = 0
    do p = 1, det%npairs
      icd = det%pair_cd(p)
      ian = det%pair_an(p)
      bcd = t%body(icd)
      ban = t%body(ian)
      ccd = tactor_center(t, icd, q(:, bcd))
      can = tactor_center(t, ian, q(:, ban))
      select case (det%pair_inter(p))
      case (i_dkdkx)
        call dkdkx_geometry(ccd, t%radius(icd), can, t%radius(ian), gap, normal, point)
        len = t%radius(icd) * t%radius(ian) / (t%radius(icd) + t%radius(ian))
        if (gap <= det%pair_alert(p)) call add(icd, ian, 0, 0)
      case (i_dkjcx)
        call dkjcx_geometry(ccd, t%radius(icd), can, q(3, ban), t%ax1(ian), t%ax2(ian), gap, normal, point)
        len = t%radius(icd)
        if (gap <= det%pair_alert(p)) call add(icd, ian, 0, 0)
      case (i_dkkdx)
        call dkkdx_geometry(ccd, t%radius(icd), can, t%radius(ian), gap, normal, point)
        len = t%radius(icd)
        if (gap <= det%pair_alert(p)) call add(icd, ian, 0, 0)
      case (i_dkplx)
        pan = tactor_vertices(t, ian, q(:, ban))
        call dkplx_geometry(ccd, t%radius(icd), pan, gap, normal, point, iedge)
        len = t%radius(icd)
        if (gap <= det%pair_alert(p)) call add(icd, ian, 0, iedge)
      case (i_plplx)
        ! The rough pair's first contactor (lower index) is preferred as the
        ! reference face, i.e. the antagonist (as LMGC90 chooses).
        pcd = tactor_vertices(t, icd, q(:, bcd))
        pan = tactor_vertices(t, ian, q(:, ban))
        call polygon_pair(pcd, pan, det%pair_alert(p), .false., pc)
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
        call polygon_pair(wall_rectangle(can, q(3, ban), t%ax1(ian), t%ax2(ian)), pcd, det%pair_alert(p), &
                          .true., pc)
        len = pair_length(pc, t%bound(icd))
        do j = 1, pc%n
          gap = pc%gap(j); normal = pc%normal; point = pc%point(:, j)
          call add(icd, ian, pc%cdver(j), pc%anseg)
        end do
      end select
    end do

  contains

    !> Append a contact; its history key within the pair is the candidate vertex.
    subroutine add(kcd, kan, cdver, anseg)
      integer, intent(in) :: kcd, kan, cdver, anseg
      integer :: k, b1, b2
      real(wp) :: tang(2), rcd(2), ran(2)
      c%n = c%n + 1
      k = c%n
      b1 = t%body(kcd); b2 = t%body(kan)
      c%inter(k) = det%pair_inter(p)
      c%cd(k) = kcd
      c%an(k) = kan
      c%cdb(k) = b1
      c%anb(k) = b2
      c%law(k) = det%pair_law(p)
      c%sub(k) = cdver
      c%cdver(k) = cdver
      c%anseg(k) = anseg
      c%normal(:, k) = normal
      c%point(:, k) = point
      c%gap(k) = gap
      c%length(k) = len
      tang = [normal(2), -normal(1)]
      rcd = point - q(1:2, b1)
      ran = point - q(1:2, b2)
      c%lever(1, k) = cross(rcd, tang)
      c%lever(2, k) = cross(rcd, normal)
      c%lever(3, k) = cross(ran, tang)
      c%lever(4, k) = cross(ran, normal)
      c%status(k) = st_noctc
      c%status_begin(k) = st_noctc
      c%r(:, k) = 0.0_wp
    end subroutine add
  end subroutine detect_fine

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

  pure real(wp) function cross(a, b)
    real(wp), intent(in) :: a(2), b(2)
    cross = a(1) * b(2) - a(2) * b(1)
  end function cross
end module fracas_detection
