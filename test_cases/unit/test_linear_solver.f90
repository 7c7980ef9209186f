!> Unit tests of fracas_linear_solver on the truss-lattice iteration matrix
!> A = m I + K of fracas_test_matrices (SPD, cond(A) ~ 1 + 8 k/m = 801 here).
!> Reference: a known solution x* (entries in [-1, 1]) and b = A x*; every method must
!> return x with max |x - x*| / max |x*| <= 1e-10 (the bound cond(A) eps ~ 2e-13 with a
!> wide margin). Sizes: 32 dofs (4 x 4 nodes: 'auto' -> LAPACK), 128 dofs (8 x 8:
!> CHOLMOD simplicial), 3200 dofs (40 x 40: CHOLMOD simplicial, UMFPACK, 'auto' -> CHOLMOD)
!> and the 3D lattice on 12 x 12 x 12 nodes (5184 dofs: CHOLMOD supernodal).
!> Also: several right-hand sides, numeric refactorization with new values, an
!> unsymmetric matrix (LU), an indefinite symmetric one ('auto' falls back to LU), the
!> free-dof system A_ff x_f = b_f - A_fd x_d, and explicit inverses of 6..16 blocks.
program test_linear_solver
  use fracas_kinds, only: wp
  use fracas_sparse, only: sparse_t, sparse_from_triplets, sparse_refill, sparse_matvec, sparse_submatrix
  use fracas_linear_solver, only: factor_t, factor_build, factor_update, factor_solve, factor_method_name, &
                                  factor_free, dense_spd_inverse, auto_dense_max_n
  use fracas_test_matrices, only: lattice_triplets
  use fracas_random, only: rng_t, rng_seed, rng_below
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_errors, only: itoa, status_t
  implicit none
  real(wp), parameter :: tol = 1.0e-10_wp, mass = 1.0_wp, stiffness = 100.0_wp
  type(rng_t) :: rng
  type(sparse_t) :: tiny, small, large, cube

  call rng_seed(rng, 2024)
  call lattice(4, 4, tiny)
  call lattice(8, 8, small)
  call lattice(40, 40, large)
  call lattice(12, 12, cube, nz=12)
  call check_true('auto_dense_max_n: 32 dofs dense, 128 sparse', tiny%n <= auto_dense_max_n .and. small%n > auto_dense_max_n)

  call solve_and_check(tiny, 'dense', 'LAPACK dpotrf')
  call solve_and_check(tiny, 'auto', 'LAPACK dpotrf')
  call solve_and_check(small, 'dense', 'LAPACK dpotrf')
  call solve_and_check(small, 'cholmod', 'CHOLMOD simplicial')
  call solve_and_check(small, 'umfpack', 'UMFPACK LU')
  call solve_and_check(small, 'auto', 'CHOLMOD')
  call solve_and_check(large, 'cholmod', 'CHOLMOD simplicial')
  call solve_and_check(cube, 'cholmod', 'CHOLMOD supernodal')
  call solve_and_check(large, 'cholmod', 'METIS ordering', 'metis')
  call solve_and_check(large, 'cholmod', 'AMD ordering', 'amd')
  call solve_and_check(large, 'umfpack', 'UMFPACK LU, symmetric strategy')
  call solve_and_check(large, 'auto', 'CHOLMOD')

  call refactorization('dense', 12, 12)
  call refactorization('cholmod', 40, 40)
  call refactorization('umfpack', 40, 40)
  call refactorization('auto', 4, 4)
  call refactorization('auto', 40, 40)
  call refactorization('cholmod', 12, 12, 12)

  call unsymmetric()
  call indefinite()
  call free_dofs()
  call inverses()
  call singular_status('dense', 8, 'LAPACK dpotrf (dense Cholesky): matrix not positive definite (leading minor 64 of 128)')
  call singular_status('cholmod', 20, 'CHOLMOD Cholesky: matrix not positive definite')
  call singular_status('umfpack', 20, 'UMFPACK LU: matrix singular')
  call singular_status('auto', 4, 'LAPACK dgetrf (dense LU): matrix singular (zero pivot at column 16 of 32)')
  call test_finish()

contains

  subroutine lattice(nx, ny, a, map, seed, m, nz)
    integer, intent(in) :: nx, ny
    integer, intent(in), optional :: nz
    type(sparse_t), intent(out) :: a
    integer, allocatable, intent(out), optional :: map(:)
    integer, intent(in), optional :: seed
    real(wp), intent(in), optional :: m
    integer, allocatable :: rows(:), cols(:)
    real(wp), allocatable :: vals(:)
    real(wp) :: m_
    m_ = mass
    if (present(m)) m_ = m
    call lattice_triplets(nx, ny, m_, stiffness, rows, cols, vals, seed, nz)
    call sparse_from_triplets(maxval(rows), rows, cols, vals, a, map)
  end subroutine lattice

  subroutine random_vector(x)
    real(wp), intent(out) :: x(:)
    integer :: i
    do i = 1, size(x)
      x(i) = real(rng_below(rng, 2000001) - 1000000, wp) * 1.0e-6_wp
    end do
  end subroutine random_vector

  real(wp) function rel_error(x, xref)
    real(wp), intent(in) :: x(:), xref(:)
    rel_error = maxval(abs(x - xref)) / maxval(abs(xref))
  end function rel_error

  !> One and four right-hand sides with method (and ordering); the method name must
  !> contain expect.
  subroutine solve_and_check(a, method, expect, ordering)
    type(sparse_t), intent(in) :: a
    character(len=*), intent(in) :: method, expect
    character(len=*), intent(in), optional :: ordering
    type(factor_t) :: f
    real(wp), allocatable :: xstar(:, :), b(:, :), b1(:)
    character(len=:), allocatable :: name, label
    integer :: k
    allocate (xstar(a%n, 4), b(a%n, 4))
    do k = 1, 4
      call random_vector(xstar(:, k))
      call sparse_matvec(a, xstar(:, k), b(:, k))
    end do
    call factor_build(f, a, method, ordering)
    name = factor_method_name(f)
    label = method//' n='//itoa(a%n)
    if (present(ordering)) label = label//' '//ordering
    write (*, '(a)') '  '//label//': '//name
    call check_true(label//': method name has "'//expect//'"', index(name, expect) > 0)
    b1 = b(:, 1)
    call factor_solve(f, b1)
    call check_close(label//': one rhs, max |x - x*| / max |x*|', rel_error(b1, xstar(:, 1)), 0.0_wp, tol)
    call factor_solve(f, b)
    call check_close(label//': 4 rhs, max |x - x*| / max |x*|', &
                     maxval([(rel_error(b(:, k), xstar(:, k)), k=1, 4)]), 0.0_wp, tol)
    call check_close(label//': column 1 of 4 rhs = single solve', maxval(abs(b(:, 1) - b1)), 0.0_wp, 1.0e-14_wp)
    call factor_free(f)
  end subroutine solve_and_check

  !> Factor with the seed-1 bar stiffnesses, refill with seed 2 on the same triplet list,
  !> factor_update, solve: the answer matches the new matrix, not the old one.
  subroutine refactorization(method, nx, ny, nz)
    character(len=*), intent(in) :: method
    integer, intent(in) :: nx, ny
    integer, intent(in), optional :: nz
    type(sparse_t) :: a
    type(factor_t) :: f
    integer, allocatable :: map(:), rows(:), cols(:)
    real(wp), allocatable :: vals(:), xstar(:), b(:), x_old(:)
    character(len=:), allocatable :: name, label
    call lattice(nx, ny, a, map, seed=1, nz=nz)
    label = 'update '//method//' n='//itoa(a%n)
    call factor_build(f, a, method)
    name = factor_method_name(f)
    call lattice_triplets(nx, ny, 3.0_wp, stiffness, rows, cols, vals, seed=2, nz=nz)
    call sparse_refill(a, map, vals)
    allocate (xstar(a%n), b(a%n))
    call random_vector(xstar)
    call sparse_matvec(a, xstar, b)
    x_old = b
    call factor_solve(f, x_old)
    call factor_update(f, a)
    call factor_solve(f, b)
    call check_close(label//': max |x - x*| / max |x*| after factor_update', rel_error(b, xstar), 0.0_wp, tol)
    call check_true(label//': the old factor gave another answer (> 1e-3)', rel_error(x_old, xstar) > 1.0e-3_wp)
    ! UMFPACK's fill depends on the pivots of the numeric phase: compare up to ', nnz'.
    if (method == 'umfpack') name = name(1:index(name, ', nnz') - 1)
    call check_true(label//': same method after the update ('//name//')', index(factor_method_name(f), name) == 1)
    call factor_free(f)
  end subroutine refactorization

  !> A + S + U: S skew (convection-like, +-0.3 k on the x-coupling of horizontal
  !> neighbours), U one-sided (-0.2 k from each x-dof to the x-dof two nodes to the right,
  !> outside the symmetric pattern).
  subroutine unsymmetric()
    integer :: sizes(2), s, nx, i, j, a_dof, b_dof, t
    integer, allocatable :: rows(:), cols(:)
    real(wp), allocatable :: vals(:), xstar(:), b(:)
    type(sparse_t) :: a
    type(factor_t) :: f
    character(len=16) :: method
    character(len=:), allocatable :: expect
    integer :: m
    sizes = [4, 40]
    do s = 1, 2
      nx = sizes(s)
      call lattice_triplets(nx, nx, mass, stiffness, rows, cols, vals)
      t = size(rows)
      rows = [rows, [(0, i=1, 2 * (nx - 1) * nx)]]
      cols = [cols, [(0, i=1, 2 * (nx - 1) * nx)]]
      vals = [vals, [(0.0_wp, i=1, 2 * (nx - 1) * nx)]]
      do j = 1, nx
        do i = 1, nx - 1
          a_dof = 2 * (i + (j - 1) * nx) - 1
          b_dof = a_dof + 2
          rows(t + 1) = a_dof; cols(t + 1) = b_dof; vals(t + 1) = 0.3_wp * stiffness
          rows(t + 2) = b_dof; cols(t + 2) = a_dof; vals(t + 2) = -0.3_wp * stiffness
          t = t + 2
        end do
      end do
      ! One-sided entries (x-dof to the x-dof two nodes right): the pattern is unsymmetric too.
      do j = 1, nx
        do i = 1, nx - 2
          a_dof = 2 * (i + (j - 1) * nx) - 1
          rows = [rows, a_dof]; cols = [cols, a_dof + 4]; vals = [vals, -0.2_wp * stiffness]
        end do
      end do
      call sparse_from_triplets(2 * nx * nx, rows, cols, vals, a)
      allocate (xstar(a%n), b(a%n))
      do m = 1, 2
        method = merge('umfpack', 'auto   ', m == 1)
        expect = 'UMFPACK LU'
        if (m == 2 .and. a%n <= auto_dense_max_n) expect = 'LAPACK dgetrf'
        call random_vector(xstar)
        call sparse_matvec(a, xstar, b)
        call factor_build(f, a, trim(method))
        write (*, '(a)') '  unsymmetric '//trim(method)//': '//factor_method_name(f)
        call factor_solve(f, b)
        call check_close('unsymmetric '//trim(method)//' n='//itoa(a%n)//': max |x - x*| / max |x*|', &
                         rel_error(b, xstar), 0.0_wp, tol)
        call check_true('unsymmetric '//trim(method)//' n='//itoa(a%n)//': uses '//expect, &
                        index(factor_method_name(f), expect) == 1)
        call factor_free(f)
      end do
      deallocate (xstar, b)
    end do
  end subroutine unsymmetric

  !> K - 1e-4 k I: symmetric, 3 negative eigenvalues (the lattice's rigid modes), the
  !> others >= ~1e-3 k, so cond ~ 8e4 and the bound cond eps ~ 2e-11. 'auto' must leave
  !> Cholesky for LU (dense dgetrf, UMFPACK) and still solve.
  subroutine indefinite()
    type(sparse_t) :: a
    type(factor_t) :: f
    real(wp), allocatable :: xstar(:), b(:)
    integer :: s, nx
    character(len=:), allocatable :: expect
    do s = 1, 2
      nx = merge(4, 40, s == 1)
      call lattice(nx, nx, a, m=-1.0e-4_wp * stiffness)
      expect = merge('LAPACK dgetrf', 'UMFPACK LU   ', s == 1)
      allocate (xstar(a%n), b(a%n))
      call random_vector(xstar)
      call sparse_matvec(a, xstar, b)
      call factor_build(f, a, 'auto')
      write (*, '(a)') '  indefinite auto: '//factor_method_name(f)
      call check_true('indefinite auto n='//itoa(a%n)//': falls back to '//trim(expect), &
                      index(factor_method_name(f), trim(expect)) == 1)
      call factor_solve(f, b)
      call check_close('indefinite auto n='//itoa(a%n)//': max |x - x*| / max |x*| (cond ~ 8e4)', &
                       rel_error(b, xstar), 0.0_wp, 1.0e-9_wp)
      call factor_free(f)
      deallocate (xstar, b)
    end do
  end subroutine indefinite

  !> Bottom row of nodes driven: A_ff x_f = b_f - (A x_d)_f with b = A x*, x_d = x* on the
  !> driven dofs (0 elsewhere), gives x_f = x*_f.
  subroutine free_dofs()
    type(sparse_t) :: a, aff
    type(factor_t) :: f
    logical, allocatable :: free(:)
    real(wp), allocatable :: xstar(:), b(:), xd(:), axd(:), bf(:)
    integer :: i, nx
    nx = 40
    call lattice(nx, nx, a, seed=5, m=0.01_wp)
    allocate (free(a%n), xstar(a%n), b(a%n), axd(a%n))
    free = [(i > 2 * nx, i=1, a%n)]
    call random_vector(xstar)
    call sparse_matvec(a, xstar, b)
    xd = merge(0.0_wp, xstar, free)
    call sparse_matvec(a, xd, axd)
    bf = pack(b - axd, free)
    call sparse_submatrix(a, free, aff)
    call factor_build(f, aff, 'auto')
    write (*, '(a)') '  free dofs: '//factor_method_name(f)
    call factor_solve(f, bf)
    call check_true('free dofs: A_ff has n - 2 nx rows', aff%n == a%n - 2 * nx)
    call check_close('free dofs: max |x_f - x*_f| / max |x*_f|', rel_error(bf, pack(xstar, free)), 0.0_wp, tol)
    call factor_free(f)
  end subroutine free_dofs

  !> C = B^T B + n I (6..16): C^-1 C = I, C^-1 symmetric; an indefinite block gives ok = false.
  subroutine inverses()
    real(wp), allocatable :: bmat(:, :), c(:, :), cinv(:, :), eye(:, :)
    integer :: n, i, j
    logical :: ok
    type(status_t) :: st
    real(wp) :: worst, asym
    worst = 0.0_wp
    asym = 0.0_wp
    do n = 6, 16
      allocate (bmat(n, n), eye(n, n))
      do j = 1, n
        call random_vector(bmat(:, j))
      end do
      eye = 0.0_wp
      do i = 1, n
        eye(i, i) = 1.0_wp
      end do
      c = matmul(transpose(bmat), bmat) + n * eye
      cinv = c
      call dense_spd_inverse(cinv)
      worst = max(worst, maxval(abs(matmul(cinv, c) - eye)))
      asym = max(asym, maxval(abs(cinv - transpose(cinv))))
      deallocate (bmat, eye)
    end do
    call check_close('dense_spd_inverse 6..16: max |C^-1 C - I|', worst, 0.0_wp, 1.0e-13_wp)
    call check_close('dense_spd_inverse 6..16: C^-1 exactly symmetric', asym, 0.0_wp, 0.0_wp)
    c = reshape([2.0_wp, 1.0_wp, 1.0_wp, -3.0_wp], [2, 2])
    call dense_spd_inverse(c, st)
    ok = st%ok
    call check_true('dense_spd_inverse: indefinite [2 1; 1 -3] gives ok = false', .not. ok)
  end subroutine inverses

  !> Errors as status: the singular lattice of singular_matrix_check (one dof cut
  !> off) given to factor_build and factor_update with a status: the failure comes
  !> back in it (the program goes on) with the message the run would stop with
  !> (unit.singular.*, without a status), and a solve with a good matrix still works.
  subroutine singular_status(method, nx, expect)
    character(len=*), intent(in) :: method, expect
    integer, intent(in) :: nx
    type(sparse_t) :: a, good
    type(factor_t) :: f
    type(status_t) :: st
    integer, allocatable :: rows(:), cols(:)
    real(wp), allocatable :: vals(:), b(:)
    character(len=:), allocatable :: label
    label = 'status, '//method//' on '//itoa(2 * nx * nx)//' dofs'
    call lattice_triplets(nx, nx, 1.0_wp, 100.0_wp, rows, cols, vals)
    call sparse_from_triplets(2 * nx * nx, rows, cols, vals, good)
    where (rows == nx * nx .or. cols == nx * nx) vals = 0.0_wp
    call sparse_from_triplets(2 * nx * nx, rows, cols, vals, a)
    call factor_build(f, a, method, status=st)
    call check_true(label//': factor_build reports the failure', .not. st%ok)
    if (.not. st%ok) call check_true(label//': message "factor_build: '//expect//'"', &
                                     index(st%message, 'factor_build: '//expect) == 1)
    call factor_build(f, good, method, status=st)
    call check_true(label//': then a good matrix factorizes', st%ok)
    call factor_update(f, a, st)
    call check_true(label//': factor_update reports the failure', .not. st%ok)
    if (.not. st%ok) call check_true(label//': message "factor_update: '//expect//'"', &
                                     index(st%message, 'factor_update: '//expect) == 1)
    call factor_update(f, good, st)
    allocate (b(good%n))
    b = 1.0_wp
    call factor_solve(f, b, st)
    call check_true(label//': refactorized good matrix solves', st%ok .and. all(b > 0.0_wp))
    call factor_free(f)
  end subroutine singular_status
end program test_linear_solver
