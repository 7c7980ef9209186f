!> 3D broad phase: the candidate pairs of 3D contactors (SPHER, PLANx, POLYR,
!> CYLND) whose bounding shapes come within the alert distance, for the fine
!> detection (fracas_spspx, fracas_spplx, fracas_prplx, fracas_spprx,
!> fracas_prprx, fracas_spcdx, fracas_cdplx) to examine.
!> - Each contactor is a bounding sphere (centre, radius: `tactor3_bound`);
!>   a big one (a PLANx, or a sphere much larger than the others:
!>   `broad3_big`) may also carry an oriented box (half lengths, frame), which
!>   it is tested with: a floor's bounding sphere would take in a whole layer.
!> - Ordinary contactors go into a sparse uniform grid of cubic cells of side
!>   2 r_max + alert (r_max: the largest ordinary bound), so two that can meet
!>   are in the same or neighbouring cells. Only occupied cells exist: their
!>   integer coordinates are hashed (open addressing), so memory is linear in
!>   the number of contactors whatever their spread (the lesson of the 2D
!>   detection's sparse grid). Each cell is paired with itself and the forward
!>   half (13) of its 26 neighbours: each pair once.
!> - Big contactors are tested against all the others (big-big pairs once).
!> - Pairs of contactors of one body are left out; contactors whose centre is
!>   not finite are left out (the state check stops such a run).
!> - The pairs come out sorted by (lower index, higher index), so the order
!>   does not depend on the grid or the hashing (a radix sort: linear). Which
!>   of the two is the candidate is the fine detection's business (see table).
module fracas_broad_3d
  use fracas_kinds, only: wp, i8
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use fracas_contactors_3d, only: tactor3_t, tk3_spher, tk3_planx, tk3_polyr, tk3_cylnd
  implicit none
  private
  public :: broad3_t, broad3_pairs, broad3_brute, tactor3_bound, broad3_big

  !> The pairs found: pair(1:2, 1:npairs), pair(1, p) < pair(2, p), sorted.
  type :: broad3_t
    integer :: npairs = 0
    integer, allocatable :: pair(:, :)
    integer :: ncells = 0          !< occupied cells of the last grid (statistics)
  end type broad3_t

  !> Cell coordinates are clamped to [0, 2^21): a key packs three of them in
  !> 63 bits. Clamping moves no two points apart, so neighbours stay neighbours.
  integer(i8), parameter :: side = 2_i8**21

contains

  !> Radius of the sphere about a contactor's centre that holds it.
  pure real(wp) function tactor3_bound(t)
    type(tactor3_t), intent(in) :: t
    select case (t%kind)
    case (tk3_spher)
      tactor3_bound = t%radius
    case (tk3_planx)
      tactor3_bound = norm2(t%axes)
    case (tk3_polyr)
      tactor3_bound = maxval(norm2(t%vert, dim=1))
    case (tk3_cylnd)
      tactor3_bound = t%axes(1) + t%radius
    case default
      tactor3_bound = 0.0_wp
    end select
  end function tactor3_bound

  !> The default split: PLANx are big, and any contactor whose bound exceeds
  !> ten times the mean bound of the non-PLANx ones (a drum, a huge sphere):
  !> kept in the grid, it would make every cell that large.
  pure function broad3_big(kind, bound) result(big)
    integer, intent(in) :: kind(:)
    real(wp), intent(in) :: bound(:)
    logical :: big(size(kind))
    real(wp) :: mean
    integer :: n
    n = count(kind /= tk3_planx)
    mean = 0.0_wp
    if (n > 0) mean = sum(bound, mask=kind /= tk3_planx) / n
    big = kind == tk3_planx .or. bound > 10.0_wp * mean
  end function broad3_big

  !> The pairs (a, b) of contactors of different bodies that may come within
  !> alert: c(3, n) centres, bound(n) bounding radii, body(n) body numbers,
  !> big(n) tested against all; half(3, n) and frame(3, 3, n), if given, an
  !> oriented box (half lengths > 0, axes as columns) a big contactor is tested with.
  subroutine broad3_pairs(b, c, bound, body, alert, big, half, frame)
    type(broad3_t), intent(inout) :: b
    real(wp), intent(in) :: c(:, :), bound(:), alert
    integer, intent(in) :: body(:)
    logical, intent(in) :: big(:)
    real(wp), intent(in), optional :: half(:, :), frame(:, :, :)
    logical, allocatable :: usable(:), binned(:)
    integer(i8), allocatable :: key(:), tkey(:)
    integer, allocatable :: tcell(:), cell_of(:), cell_start(:), items(:), fill(:), lo_hi(:, :)
    integer :: n, k, j, nsmall, m, bits, cell, other, d, p, q, np
    integer(i8) :: ijk(3), nb(3)
    real(wp) :: lo(3), size_cell
    n = size(bound)
    usable = ieee_is_finite(c(1, :)) .and. ieee_is_finite(c(2, :)) .and. ieee_is_finite(c(3, :))
    binned = usable .and. .not. big
    nsmall = count(binned)
    np = 0
    allocate (lo_hi(2, max(64, 8 * n)))
    b%ncells = 0
    if (nsmall > 0) then
      size_cell = 2.0_wp * maxval(bound, mask=binned) + alert
      if (.not. size_cell > 0.0_wp) size_cell = 1.0_wp
      do d = 1, 3
        lo(d) = minval(c(d, :), mask=binned)
      end do
      ! Hash table of the occupied cells: 2^bits >= 2 nsmall slots.
      bits = 1
      do while (2**bits < 2 * nsmall)
        bits = bits + 1
      end do
      m = 2**bits
      allocate (tkey(0:m - 1), tcell(0:m - 1), key(n), cell_of(n))
      tkey = -1_i8
      do k = 1, n
        if (.not. binned(k)) cycle
        do d = 1, 3
          ijk(d) = cell_coordinate(c(d, k) - lo(d))
        end do
        key(k) = pack_key(ijk)
        cell_of(k) = lookup(key(k), .true.)
      end do
      ! Items by cell (counting sort, stable: by index within a cell).
      allocate (cell_start(b%ncells + 1), items(nsmall))
      cell_start = 0
      do k = 1, n
        if (binned(k)) cell_start(cell_of(k) + 1) = cell_start(cell_of(k) + 1) + 1
      end do
      cell_start(1) = 1
      do cell = 1, b%ncells
        cell_start(cell + 1) = cell_start(cell + 1) + cell_start(cell)
      end do
      fill = cell_start(1:b%ncells)
      do k = 1, n
        if (.not. binned(k)) cycle
        items(fill(cell_of(k))) = k
        fill(cell_of(k)) = fill(cell_of(k)) + 1
      end do
      do cell = 1, b%ncells
        k = items(cell_start(cell))
        ijk = unpack_key(key(k))
        do p = cell_start(cell), cell_start(cell + 1) - 1
          do q = p + 1, cell_start(cell + 1) - 1
            call consider(items(p), items(q))
          end do
        end do
        ! forward half of the neighbours: (dz, dy, dx) lexicographically > 0
        do d = 1, 13
          nb = ijk + forward(d)
          if (any(nb < 0_i8 .or. nb >= side)) cycle
          other = lookup(pack_key(nb), .false.)
          if (other == 0) cycle
          do p = cell_start(cell), cell_start(cell + 1) - 1
            do q = cell_start(other), cell_start(other + 1) - 1
              call consider(items(p), items(q))
            end do
          end do
        end do
      end do
    end if
    do k = 1, n
      if (.not. (big(k) .and. usable(k))) cycle
      do j = 1, n
        if (j == k .or. .not. usable(j)) cycle
        if (big(j) .and. j < k) cycle
        call consider(k, j)
      end do
    end do
    call sort_pairs(lo_hi(:, 1:np), n, b)

  contains

    integer(i8) function cell_coordinate(x)
      real(wp), intent(in) :: x
      real(wp) :: s
      s = x / size_cell
      if (s < real(side - 1_i8, wp)) then
        cell_coordinate = int(s, i8)
      else
        cell_coordinate = side - 1_i8
      end if
    end function cell_coordinate

    pure integer(i8) function pack_key(v)
      integer(i8), intent(in) :: v(3)
      pack_key = v(1) + side * (v(2) + side * v(3))
    end function pack_key

    pure function unpack_key(kk) result(v)
      integer(i8), intent(in) :: kk
      integer(i8) :: v(3)
      v(1) = modulo(kk, side)
      v(2) = modulo(kk / side, side)
      v(3) = kk / (side * side)
    end function unpack_key

    !> Cell number of key kk (1..ncells); 0 if unoccupied and not add.
    integer function lookup(kk, add)
      integer(i8), intent(in) :: kk
      logical, intent(in) :: add
      integer :: s
      ! Fibonacci hashing: the top bits of kk times 2^64 / golden ratio (wraps).
      s = int(shiftr(kk * (-7046029254386353131_i8), 64 - bits))
      do
        if (tkey(s) == kk) then
          lookup = tcell(s)
          return
        end if
        if (tkey(s) == -1_i8) exit
        s = iand(s + 1, m - 1)
      end do
      lookup = 0
      if (.not. add) return
      b%ncells = b%ncells + 1
      tkey(s) = kk
      tcell(s) = b%ncells
      lookup = b%ncells
    end function lookup

    subroutine consider(i, j)
      integer, intent(in) :: i, j
      if (near(i, j, c, bound, body, alert, big, half, frame)) call push_pair(lo_hi, np, min(i, j), max(i, j))
    end subroutine consider
  end subroutine broad3_pairs

  !> The 13 forward neighbour offsets (dx, dy, dz): dz = 1 (9), dz = 0 and dy = 1 (3), (1, 0, 0).
  pure function forward(d) result(o)
    integer, intent(in) :: d
    integer(i8) :: o(3)
    if (d <= 9) then
      o = [int(mod(d - 1, 3) - 1, i8), int((d - 1) / 3 - 1, i8), 1_i8]
    else if (d <= 12) then
      o = [int(d - 11, i8), 1_i8, 0_i8]
    else
      o = [1_i8, 0_i8, 0_i8]
    end if
  end function forward

  !> The same pairs by testing every pair (the reference of the grid; small scenes).
  subroutine broad3_brute(b, c, bound, body, alert, big, half, frame)
    type(broad3_t), intent(inout) :: b
    real(wp), intent(in) :: c(:, :), bound(:), alert
    integer, intent(in) :: body(:)
    logical, intent(in) :: big(:)
    real(wp), intent(in), optional :: half(:, :), frame(:, :, :)
    logical, allocatable :: usable(:)
    integer, allocatable :: lo_hi(:, :)
    integer :: i, j, np
    usable = ieee_is_finite(c(1, :)) .and. ieee_is_finite(c(2, :)) .and. ieee_is_finite(c(3, :))
    allocate (lo_hi(2, 64))
    np = 0
    do i = 1, size(bound)
      if (.not. usable(i)) cycle
      do j = i + 1, size(bound)
        if (.not. usable(j)) cycle
        if (near(i, j, c, bound, body, alert, big, half, frame)) call push_pair(lo_hi, np, i, j)
      end do
    end do
    b%ncells = 0
    b%npairs = np
    b%pair = lo_hi(:, 1:np)
  end subroutine broad3_brute

  !> Append the pair (a, b) to lo_hi(:, 1:np), doubling its room when full.
  subroutine push_pair(lo_hi, np, a, b)
    integer, allocatable, intent(inout) :: lo_hi(:, :)
    integer, intent(inout) :: np
    integer, intent(in) :: a, b
    integer, allocatable :: tmp(:, :)
    np = np + 1
    if (np > size(lo_hi, 2)) then
      allocate (tmp(2, 2 * size(lo_hi, 2)))
      tmp(:, 1:np - 1) = lo_hi(:, 1:np - 1)
      call move_alloc(tmp, lo_hi)
    end if
    lo_hi(:, np) = [a, b]
  end subroutine push_pair

  !> May contactors i and j (of different bodies) come within alert? Two
  !> bounding spheres; a big contactor with a box: the other's bounding sphere
  !> against the box (the distance from its centre to the box, in the box's frame).
  pure logical function near(i, j, c, bound, body, alert, big, half, frame)
    integer, intent(in) :: i, j
    real(wp), intent(in) :: c(:, :), bound(:), alert
    integer, intent(in) :: body(:)
    logical, intent(in) :: big(:)
    real(wp), intent(in), optional :: half(:, :), frame(:, :, :)
    near = .false.
    if (body(i) == body(j)) return
    if (has_box(i)) then
      near = box_distance(i, c(:, j)) <= bound(j) + alert
    else if (has_box(j)) then
      near = box_distance(j, c(:, i)) <= bound(i) + alert
    else
      near = norm2(c(:, i) - c(:, j)) <= bound(i) + bound(j) + alert
    end if

  contains

    pure logical function has_box(k)
      integer, intent(in) :: k
      has_box = .false.
      if (.not. (present(half) .and. present(frame))) return
      has_box = big(k) .and. all(half(:, k) > 0.0_wp)
    end function has_box

    pure real(wp) function box_distance(k, x)
      integer, intent(in) :: k
      real(wp), intent(in) :: x(3)
      box_distance = norm2(max(abs(matmul(transpose(frame(:, :, k)), x - c(:, k))) - half(:, k), 0.0_wp))
    end function box_distance
  end function near

  !> Pairs sorted by (first, second) in two stable counting passes (by the
  !> second index, then by the first): linear in pairs + contactors.
  subroutine sort_pairs(pairs, n, b)
    integer, intent(in) :: pairs(:, :), n
    type(broad3_t), intent(inout) :: b
    integer, allocatable :: tmp(:, :)
    integer :: np
    np = size(pairs, 2)
    allocate (tmp(2, np))
    call counting_pass(pairs, tmp, 2)
    if (allocated(b%pair)) deallocate (b%pair)
    allocate (b%pair(2, np))
    call counting_pass(tmp, b%pair, 1)
    b%npairs = np

  contains

    subroutine counting_pass(src, dst, row)
      integer, intent(in) :: src(:, :), row
      integer, intent(out) :: dst(:, :)
      integer :: start(n + 1), p, v
      start = 0
      do p = 1, np
        v = src(row, p)
        start(v + 1) = start(v + 1) + 1
      end do
      start(1) = 1
      do v = 1, n
        start(v + 1) = start(v + 1) + start(v)
      end do
      do p = 1, np
        v = src(row, p)
        dst(:, start(v)) = src(:, p)
        start(v) = start(v) + 1
      end do
    end subroutine counting_pass
  end subroutine sort_pairs
end module fracas_broad_3d
