!> Unit tests of fracas_sparse (compressed sparse column matrices).
!> References: the dense matrix accumulated directly from the same triplets
!> (D(r, c) += v for each triplet), dense products and dense submatrices of it.
!> Matrices: the truss-lattice iteration matrix of fracas_test_matrices (duplicates as in
!> an FE assembly), its triplets shuffled, with per-bar stiffness drawn from a seed.
program test_sparse
  use fracas_kinds, only: wp
  use fracas_sparse, only: sparse_t, sparse_from_triplets, sparse_refill, sparse_matvec, sparse_submatrix, &
                           sparse_to_dense, sparse_transpose, sparse_asymmetry, sparse_nnz
  use fracas_test_matrices, only: lattice_triplets
  use fracas_random, only: rng_t, rng_seed, rng_permute, rng_below
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_errors, only: itoa
  implicit none
  integer, parameter :: nx = 5, ny = 4, n = 2 * nx * ny
  type(sparse_t) :: a, a2, at, sub, sub2
  type(rng_t) :: rng
  integer, allocatable :: rows(:), cols(:), order(:), map(:), map2(:), val_map(:), new_of_old(:)
  real(wp), allocatable :: vals(:), vals2(:), d(:, :), dref(:, :), x(:), y(:), dsub(:, :)
  logical, allocatable :: seen(:, :)
  logical :: keep(n), sorted
  integer :: k, j, p, nfree, distinct

  ! ---------------------------------------------------------------- triplet assembly
  call lattice_triplets(nx, ny, 1.0_wp, 100.0_wp, rows, cols, vals, seed=7)
  call rng_seed(rng, 11)
  order = [(k, k=1, size(rows))]
  call rng_permute(rng, order)
  rows = rows(order); cols = cols(order); vals = vals(order)
  allocate (dref(n, n), seen(n, n))
  dref = 0.0_wp
  seen = .false.
  do k = 1, size(rows)
    dref(rows(k), cols(k)) = dref(rows(k), cols(k)) + vals(k)
    seen(rows(k), cols(k)) = .true.
  end do
  distinct = count(seen)
  call sparse_from_triplets(n, rows, cols, vals, a, map)
  call sparse_to_dense(a, d)
  call check_close('triplets: max |A - dense sum of triplets| / max |A|', maxval(abs(d - dref)) / maxval(abs(dref)), &
                   0.0_wp, 4 * epsilon(1.0_wp))
  call check_true('triplets: nnz = number of distinct positions ('//itoa(distinct)//')', sparse_nnz(a) == distinct)
  call check_true('triplets: colptr(1) = 1 and colptr(n+1) = nnz + 1', a%colptr(1) == 1 .and. a%colptr(n + 1) == distinct + 1)
  sorted = .true.
  do j = 1, n
    do p = a%colptr(j), a%colptr(j + 1) - 2
      if (a%rowind(p) >= a%rowind(p + 1)) sorted = .false.
    end do
    do p = a%colptr(j), a%colptr(j + 1) - 1
      if (.not. seen(a%rowind(p), j)) sorted = .false.
    end do
  end do
  call check_true('triplets: rows strictly increasing in every column, each a triplet position', sorted)
  call check_true('triplets: map(k) points at the entry of (rows(k), cols(k))', &
                  all([(a%rowind(map(k)) == rows(k) .and. map(k) >= a%colptr(cols(k)) .and. &
                        map(k) < a%colptr(cols(k) + 1), k=1, size(rows))]))

  ! Empty columns and a triplet list in reverse order.
  call sparse_from_triplets(6, [5, 2, 5, 2], [4, 4, 1, 4], [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp], a2)
  call check_true('triplets: empty columns keep colptr flat', all(a2%colptr == [1, 2, 2, 2, 4, 4, 4]))
  call check_true('triplets: column 4 = rows (2, 5), duplicates summed', &
                  all(a2%rowind == [5, 2, 5]) .and. all(a2%val == [3.0_wp, 6.0_wp, 1.0_wp]))

  ! ---------------------------------------------------------------- refill
  call lattice_triplets(nx, ny, 2.0_wp, 30.0_wp, rows, cols, vals2, seed=8)
  vals2 = vals2(order)
  call sparse_refill(a, map, vals2)
  call sparse_from_triplets(n, rows(order), cols(order), vals2, a2, map2)
  call check_true('refill: same pattern as a fresh assembly', all(a%colptr == a2%colptr) .and. all(a%rowind == a2%rowind))
  call check_close('refill: max |values - fresh assembly| (same summation order: exact)', &
                   maxval(abs(a%val - a2%val)), 0.0_wp, 0.0_wp)
  call check_true('refill: the values did change', maxval(abs(vals2 - vals)) > 1.0_wp)
  call sparse_to_dense(a, dref)

  ! ---------------------------------------------------------------- matvec
  allocate (x(n), y(n))
  do k = 1, n
    x(k) = real(rng_below(rng, 2001) - 1000, wp) / 1000.0_wp
  end do
  call sparse_matvec(a, x, y)
  call check_close('matvec: max |A x - dense A x| / max |dense A x|', &
                   maxval(abs(y - matmul(dref, x))) / maxval(abs(matmul(dref, x))), 0.0_wp, 1.0e-14_wp)

  ! ---------------------------------------------------------------- free-dof submatrix
  keep = [(mod(k, 3) /= 0 .and. k > 4, k=1, n)]   ! dofs 1-4 (the first two nodes) and every 3rd driven
  nfree = count(keep)
  call sparse_submatrix(a, keep, sub, val_map, new_of_old)
  call sparse_to_dense(sub, dsub)
  call check_true('submatrix: size = free dofs ('//itoa(nfree)//')', sub%n == nfree)
  call check_close('submatrix: max |A_ff - dense A(free, free)|', &
                   maxval(abs(dsub - dref(pack([(k, k=1, n)], keep), pack([(k, k=1, n)], keep)))), 0.0_wp, 0.0_wp)
  call check_true('submatrix: new_of_old numbers the free dofs in order, 0 for driven', &
                  all(pack(new_of_old, keep) == [(k, k=1, nfree)]) .and. all(pack(new_of_old, .not. keep) == 0))
  call sparse_refill(a, map, vals)        ! back to the first values
  sub%val = a%val(val_map)
  call sparse_submatrix(a, keep, sub2)
  call check_close('submatrix: refill through val_map = fresh extraction', maxval(abs(sub%val - sub2%val)), 0.0_wp, 0.0_wp)

  ! ---------------------------------------------------------------- transpose, symmetry
  call sparse_transpose(a, at)
  call sparse_to_dense(at, d)
  call sparse_to_dense(a, dref)
  call check_close('transpose: max |A^T - dense transpose|', maxval(abs(d - transpose(dref))), 0.0_wp, 0.0_wp)
  call check_close('asymmetry of the lattice matrix (rounding only)', sparse_asymmetry(a), 0.0_wp, 4 * epsilon(1.0_wp))
  call sparse_from_triplets(3, [1, 2, 3, 1, 3], [1, 2, 3, 3, 1], [4.0_wp, 4.0_wp, 4.0_wp, 1.0_wp, 0.5_wp], a2)
  call check_close('asymmetry of [4 0 1; 0 4 0; 0.5 0 4] = 0.5/4', sparse_asymmetry(a2), 0.125_wp, 1.0e-15_wp)
  call sparse_from_triplets(3, [1, 2, 3, 1], [1, 2, 3, 3], [4.0_wp, 4.0_wp, 4.0_wp, 2.0_wp], a2)
  call check_close('asymmetry with a one-sided entry 2: 2/4', sparse_asymmetry(a2), 0.5_wp, 1.0e-15_wp)

  call test_finish()
end program test_sparse
