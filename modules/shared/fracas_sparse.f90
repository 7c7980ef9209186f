!> Square sparse matrices in compressed sparse column form (CSC, 1-based), as the
!> iteration matrices A = M + h^2 theta^2 K of meshed bodies need them.
!>
!> Storage (`sparse_t`): column j holds rows rowind(colptr(j) : colptr(j+1)-1), sorted
!> ascending and without duplicates, with values val(same range); nnz = colptr(n+1) - 1.
!> A symmetric matrix is stored with both triangles (full pattern): the Cholesky paths of
!> fracas_linear_solver read the upper triangle, LU (UMFPACK) and the products read all.
!>
!> Use:
!>   call sparse_from_triplets(n, rows, cols, vals, a, map)   ! once: pattern + values
!>   call sparse_refill(a, map, new_vals)                     ! same triplet list, new values
!>   call sparse_submatrix(a, keep, a_ff, val_map)            ! A_ff on the free dofs
!>   a_ff%val = a%val(val_map)                                ! refill A_ff after a refill of A
!>   call sparse_matvec(a, x, y)                              ! y = A x
!> The coupling of free to driven dofs, (A x_d) restricted to the free rows, is one
!> sparse_matvec of the full A with x_d (zero on the free dofs).
!>
!> sparse_from_triplets sorts with two counting sorts (by row, then stably by column),
!> so it is linear in the number of triplets (no insertion, no comparison sort).
module fracas_sparse
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal, itoa
  implicit none
  private
  public :: sparse_t, sparse_from_triplets, sparse_refill, sparse_matvec, sparse_submatrix, &
            sparse_to_dense, sparse_transpose, sparse_asymmetry, sparse_nnz, sparse_free

  type :: sparse_t
    integer :: n = 0                  !< rows = columns
    integer, allocatable :: colptr(:) !< (n+1), colptr(1) = 1
    integer, allocatable :: rowind(:) !< (nnz), sorted in each column
    real(wp), allocatable :: val(:)   !< (nnz)
  end type sparse_t

contains

  !> Number of stored entries.
  pure integer function sparse_nnz(a)
    type(sparse_t), intent(in) :: a
    sparse_nnz = 0
    if (allocated(a%colptr)) sparse_nnz = a%colptr(a%n + 1) - 1
  end function sparse_nnz

  !> Assemble a from triplets (rows(k), cols(k), vals(k)), k = 1..size(rows): duplicates are
  !> summed, rows sorted in each column; explicit zeros are kept (the pattern is the set of
  !> triplet positions, so refills keep it). map(k), if present, is the position of triplet
  !> k in a%val, for sparse_refill.
  subroutine sparse_from_triplets(n, rows, cols, vals, a, map)
    integer, intent(in) :: n
    integer, intent(in) :: rows(:), cols(:)
    real(wp), intent(in) :: vals(:)
    type(sparse_t), intent(out) :: a
    integer, allocatable, intent(out), optional :: map(:)
    integer, allocatable :: start(:), by_row(:), by_col(:), pos(:)
    integer :: ntrip, k, t, i, j, nnz, last_row

    ntrip = size(rows)
    if (size(cols) /= ntrip .or. size(vals) /= ntrip) &
      call fatal('sparse_from_triplets: rows, cols and vals differ in length ('//itoa(ntrip)//', '// &
                 itoa(size(cols))//', '//itoa(size(vals))//')')
    if (n < 0) call fatal('sparse_from_triplets: negative size '//itoa(n))
    do k = 1, ntrip
      if (rows(k) < 1 .or. rows(k) > n .or. cols(k) < 1 .or. cols(k) > n) &
        call fatal('sparse_from_triplets: triplet '//itoa(k)//' at ('//itoa(rows(k))//', '// &
                   itoa(cols(k))//') outside 1..'//itoa(n))
    end do

    ! Counting sort by row, then a stable counting sort by column: each column's
    ! triplets come out in ascending row order.
    allocate (start(n + 1), by_row(ntrip))
    call bucket_starts(rows, n, start)
    do k = 1, ntrip
      by_row(start(rows(k))) = k
      start(rows(k)) = start(rows(k)) + 1
    end do
    allocate (by_col(ntrip))
    call bucket_starts(cols, n, start)
    do t = 1, ntrip
      k = by_row(t)
      by_col(start(cols(k))) = k
      start(cols(k)) = start(cols(k)) + 1
    end do
    deallocate (by_row)

    ! Merge equal rows inside each column; pos(k) = entry of triplet k.
    allocate (a%colptr(n + 1), pos(ntrip))
    a%n = n
    nnz = 0
    t = 1
    do j = 1, n
      a%colptr(j) = nnz + 1
      last_row = 0
      do while (t <= ntrip)
        k = by_col(t)
        if (cols(k) /= j) exit
        i = rows(k)
        if (i /= last_row) then
          nnz = nnz + 1
          last_row = i
        end if
        pos(k) = nnz
        t = t + 1
      end do
    end do
    a%colptr(n + 1) = nnz + 1
    allocate (a%rowind(nnz), a%val(nnz))
    a%val = 0.0_wp
    do k = 1, ntrip
      a%rowind(pos(k)) = rows(k)
      a%val(pos(k)) = a%val(pos(k)) + vals(k)
    end do
    if (present(map)) call move_alloc(pos, map)
  end subroutine sparse_from_triplets

  !> New values for the same triplet list (same pattern): a%val(map(k)) sums vals(k).
  subroutine sparse_refill(a, map, vals)
    type(sparse_t), intent(inout) :: a
    integer, intent(in) :: map(:)
    real(wp), intent(in) :: vals(:)
    integer :: k
    if (size(map) /= size(vals)) &
      call fatal('sparse_refill: '//itoa(size(vals))//' values for a map of '//itoa(size(map))//' triplets')
    if (.not. allocated(a%val)) call fatal('sparse_refill: the matrix was never assembled (sparse_from_triplets first)')
    a%val = 0.0_wp
    do k = 1, size(map)
      a%val(map(k)) = a%val(map(k)) + vals(k)
    end do
  end subroutine sparse_refill

  !> y = A x.
  subroutine sparse_matvec(a, x, y)
    type(sparse_t), intent(in) :: a
    real(wp), intent(in) :: x(:)
    real(wp), intent(out) :: y(:)
    integer :: j, p
    if (size(x) /= a%n .or. size(y) /= a%n) &
      call fatal('sparse_matvec: vectors of length '//itoa(size(x))//' and '//itoa(size(y))// &
                 ' for a matrix of size '//itoa(a%n))
    y = 0.0_wp
    do j = 1, a%n
      do p = a%colptr(j), a%colptr(j + 1) - 1
        y(a%rowind(p)) = y(a%rowind(p)) + a%val(p) * x(j)
      end do
    end do
  end subroutine sparse_matvec

  !> sub = A(keep, keep): the rows and columns where keep is true (the free dofs), in their
  !> order. val_map(q), if present, is the position in a%val of sub%val(q), so that after
  !> new values in a, sub%val = a%val(val_map) refills sub. new_of_old(i), if present, is the
  !> index of dof i in sub (0 for a dropped dof).
  subroutine sparse_submatrix(a, keep, sub, val_map, new_of_old)
    type(sparse_t), intent(in) :: a
    logical, intent(in) :: keep(:)
    type(sparse_t), intent(out) :: sub
    integer, allocatable, intent(out), optional :: val_map(:)
    integer, allocatable, intent(out), optional :: new_of_old(:)
    integer, allocatable :: renum(:), vmap(:)
    integer :: i, j, p, nnz, nsub

    if (size(keep) /= a%n) &
      call fatal('sparse_submatrix: mask of length '//itoa(size(keep))//' for a matrix of size '//itoa(a%n))
    allocate (renum(a%n))
    nsub = 0
    do i = 1, a%n
      renum(i) = 0
      if (keep(i)) then
        nsub = nsub + 1
        renum(i) = nsub
      end if
    end do
    nnz = 0
    do j = 1, a%n
      if (.not. keep(j)) cycle
      do p = a%colptr(j), a%colptr(j + 1) - 1
        if (keep(a%rowind(p))) nnz = nnz + 1
      end do
    end do
    sub%n = nsub
    allocate (sub%colptr(nsub + 1), sub%rowind(nnz), sub%val(nnz), vmap(nnz))
    nnz = 0
    do j = 1, a%n
      if (.not. keep(j)) cycle
      sub%colptr(renum(j)) = nnz + 1
      do p = a%colptr(j), a%colptr(j + 1) - 1
        i = a%rowind(p)
        if (.not. keep(i)) cycle
        nnz = nnz + 1
        sub%rowind(nnz) = renum(i)   ! renumbering keeps the order: rows stay sorted
        sub%val(nnz) = a%val(p)
        vmap(nnz) = p
      end do
    end do
    sub%colptr(nsub + 1) = nnz + 1
    if (present(val_map)) call move_alloc(vmap, val_map)
    if (present(new_of_old)) call move_alloc(renum, new_of_old)
  end subroutine sparse_submatrix

  !> Dense copy d(n, n) of a (for small matrices and tests).
  subroutine sparse_to_dense(a, d)
    type(sparse_t), intent(in) :: a
    real(wp), allocatable, intent(out) :: d(:, :)
    integer :: j, p
    allocate (d(a%n, a%n))
    d = 0.0_wp
    do j = 1, a%n
      do p = a%colptr(j), a%colptr(j + 1) - 1
        d(a%rowind(p), j) = a%val(p)
      end do
    end do
  end subroutine sparse_to_dense

  !> at = A^T (rows sorted in each column, by construction).
  subroutine sparse_transpose(a, at)
    type(sparse_t), intent(in) :: a
    type(sparse_t), intent(out) :: at
    integer :: j, p, q, nnz
    nnz = sparse_nnz(a)
    at%n = a%n
    allocate (at%colptr(a%n + 1), at%rowind(nnz), at%val(nnz))
    call bucket_starts(a%rowind(1:nnz), a%n, at%colptr)
    do j = 1, a%n
      do p = a%colptr(j), a%colptr(j + 1) - 1
        q = at%colptr(a%rowind(p))
        at%rowind(q) = j
        at%val(q) = a%val(p)
        at%colptr(a%rowind(p)) = q + 1
      end do
    end do
    ! The scatter advanced each start to the next column's start: shift back.
    at%colptr(2:a%n + 1) = at%colptr(1:a%n)
    at%colptr(1) = 1
  end subroutine sparse_transpose

  !> max |a_ij - a_ji| / max |a_ij| (0 for a symmetric matrix; an entry missing on one
  !> side counts as zero there). Costs one transpose.
  real(wp) function sparse_asymmetry(a) result(asym)
    type(sparse_t), intent(in) :: a
    type(sparse_t) :: at
    integer :: j, p, q, pend, qend
    real(wp) :: amax
    asym = 0.0_wp
    if (sparse_nnz(a) == 0) return
    amax = maxval(abs(a%val))
    if (amax == 0.0_wp) return
    call sparse_transpose(a, at)
    ! Merge the two sorted row lists of column j of A and of A^T.
    do j = 1, a%n
      p = a%colptr(j); pend = a%colptr(j + 1) - 1
      q = at%colptr(j); qend = at%colptr(j + 1) - 1
      do while (p <= pend .or. q <= qend)
        if (q > qend) then
          asym = max(asym, abs(a%val(p))); p = p + 1
        else if (p > pend) then
          asym = max(asym, abs(at%val(q))); q = q + 1
        else if (a%rowind(p) < at%rowind(q)) then
          asym = max(asym, abs(a%val(p))); p = p + 1
        else if (a%rowind(p) > at%rowind(q)) then
          asym = max(asym, abs(at%val(q))); q = q + 1
        else
          asym = max(asym, abs(a%val(p) - at%val(q))); p = p + 1; q = q + 1
        end if
      end do
    end do
    asym = asym / amax
  end function sparse_asymmetry

  subroutine sparse_free(a)
    type(sparse_t), intent(inout) :: a
    if (allocated(a%colptr)) deallocate (a%colptr)
    if (allocated(a%rowind)) deallocate (a%rowind)
    if (allocated(a%val)) deallocate (a%val)
    a%n = 0
  end subroutine sparse_free

  !> start(i) = first slot of bucket i when keys(:) in 1..n are counted into buckets;
  !> start(n+1) = size(keys) + 1.
  subroutine bucket_starts(keys, n, start)
    integer, intent(in) :: keys(:), n
    integer, intent(out) :: start(:)
    integer :: k, i, count_i, next
    start = 0
    do k = 1, size(keys)
      start(keys(k)) = start(keys(k)) + 1
    end do
    next = 1
    do i = 1, n + 1
      count_i = start(i)
      start(i) = next
      next = next + count_i
    end do
  end subroutine bucket_starts
end module fracas_sparse
