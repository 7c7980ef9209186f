!> Linear-solver benchmark (not a test): factorization and solve times of the iteration
!> matrix of a meshed body against its size, for each method of fracas_linear_solver.
!> Matrix: the truss lattice of fracas_test_matrices on nx x nx nodes (n = 2 nx^2 dofs,
!> Q4 sparsity, A = I + K with bar stiffness 100: the shape of M + h^2 theta^2 K).
!> Methods: dense LAPACK Cholesky, CHOLMOD with METIS, with AMD, with 'best' (both tried,
!> the default of 'auto' above the dense limit), UMFPACK LU. Per size and method:
!>   build   symbolic analysis + numeric factorization (factor_build)
!>   update  numeric refactorization with new values (factor_update)
!>   solve1  one right-hand side; solve10: ten right-hand sides at once (time per rhs)
!> and the relative error of the solution against a known x*. Also the triplet assembly
!> (sparse_from_triplets) and the refill (sparse_refill) of the matrix.
!> Times are CPU times of this process (the machine is shared: waiting for a core is not
!> counted; run with OMP_NUM_THREADS=1), per call, the best of batches of calls (each
!> batch >= 2 ms; at least 3 batches and 0.3 s, at most 200 batches, 2 once 2 s are spent).
!>   fracas-linear-solver-bench [--min-n N] [--max-n N] [--dense-max-n N] [--csv FILE]
program linear_solver_bench
  use fracas_kinds, only: wp
  use fracas_sparse, only: sparse_t, sparse_from_triplets, sparse_refill, sparse_matvec, sparse_nnz
  use fracas_linear_solver, only: factor_t, factor_build, factor_update, factor_solve, factor_method_name, &
                                  factor_nnz, factor_free, auto_dense_max_n
  use fracas_test_matrices, only: lattice_triplets
  use fracas_command_line, only: argument_value
  use fracas_errors, only: fatal
  implicit none
  integer, parameter :: sides(*) = [2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 14, 16, 20, 25, 32, 40, 50, 64, 80, 100, &
                                    130, 160, 200, 250, 316]
  character(len=*), parameter :: methods(5) = ['dense        ', 'cholmod-metis', 'cholmod-amd  ', &
                                               'cholmod-best ', 'umfpack      ']
  real(wp), parameter :: budget = 0.3_wp, long_budget = 2.0_wp
  integer, parameter :: task_assemble = 1, task_refill = 2, task_build = 3, task_update = 4, task_solve1 = 5, &
                        task_solve10 = 6
  integer :: min_n = 0, max_n = 200000, dense_max_n = 2048, csv_unit = 0
  integer :: s, m, nx, n, i, k
  character(len=:), allocatable :: arg, csv
  type(sparse_t) :: a
  integer, allocatable :: rows(:), cols(:), map(:)
  real(wp), allocatable :: vals(:), vals2(:), xstar(:, :), b(:, :), b1(:)
  real(wp) :: t_assemble, t_refill, t_build, t_update, t_solve1, t_solve10, err
  type(factor_t) :: f
  character(len=:), allocatable :: name

  i = 1
  do while (i <= command_argument_count())
    arg = argument_value(i, 'argument')
    select case (arg)
    case ('--min-n')
      arg = argument_value(i + 1, arg); read (arg, *) min_n; i = i + 1
    case ('--max-n')
      arg = argument_value(i + 1, arg); read (arg, *) max_n; i = i + 1
    case ('--dense-max-n')
      arg = argument_value(i + 1, arg); read (arg, *) dense_max_n; i = i + 1
    case ('--csv')
      csv = argument_value(i + 1, arg); i = i + 1
      open (newunit=csv_unit, file=csv, status='replace', action='write')
      write (csv_unit, '(a)') 'method,nx,n,nnz_a,triplets,t_assemble,t_refill,t_build,t_update,t_solve1,'// &
                              't_solve10_per_rhs,nnz_factor,rel_error,name'
    case default
      call fatal('fracas-linear-solver-bench: unknown argument '//arg// &
                 ' (expected --min-n N, --max-n N, --dense-max-n N, --csv FILE)')
    end select
    i = i + 1
  end do
  write (*, '(a,i0)') '# auto_dense_max_n = ', auto_dense_max_n
  write (*, '(a)') '# method         n       nnz(A)   assemble   refill     build      update     solve1     '// &
                   'solve10/rhs nnz(factor)  error     name'

  do s = 1, size(sides)
    nx = sides(s)
    n = 2 * nx * nx
    if (n > max_n) exit
    if (n < min_n) cycle
    call lattice_triplets(nx, nx, 1.0_wp, 100.0_wp, rows, cols, vals, seed=1)
    call lattice_triplets(nx, nx, 1.0_wp, 100.0_wp, rows, cols, vals2, seed=2)
    t_assemble = best_time(task_assemble)
    call sparse_from_triplets(n, rows, cols, vals, a, map)
    t_refill = best_time(task_refill)
    call sparse_refill(a, map, vals)
    if (allocated(xstar)) deallocate (xstar, b, b1)
    allocate (xstar(n, 10), b(n, 10), b1(n))
    do k = 1, 10
      do i = 1, n
        xstar(i, k) = sin(real(i * k, wp))
      end do
    end do
    do m = 1, size(methods)
      if (trim(methods(m)) == 'dense' .and. n > dense_max_n) cycle
      t_build = best_time(task_build)
      call build(f)
      name = factor_method_name(f)
      t_update = best_time(task_update)
      t_solve1 = best_time(task_solve1)
      t_solve10 = best_time(task_solve10) / 10
      ! Error of the last solve10 (b = A x*).
      do k = 1, 10
        call sparse_matvec(a, xstar(:, k), b(:, k))
      end do
      call factor_solve(f, b)
      err = maxval(abs(b - xstar)) / maxval(abs(xstar))
      write (*, '(a13,i9,i11,6es11.3,es12.4,es10.2,2x,a)') methods(m), n, sparse_nnz(a), t_assemble, t_refill, &
        t_build, t_update, t_solve1, t_solve10, factor_nnz(f), err, name
      if (csv_unit /= 0) then
        write (csv_unit, '(a,",",i0,",",i0,",",i0,",",i0,6(",",es12.5),",",es12.5,",",es10.3,",""",a,"""")') &
          trim(methods(m)), nx, n, sparse_nnz(a), size(rows), t_assemble, t_refill, t_build, t_update, t_solve1, &
          t_solve10, factor_nnz(f), err, name
        flush (csv_unit)
      end if
      call factor_free(f)
    end do
  end do
  if (csv_unit /= 0) close (csv_unit)

contains

  subroutine build(g)
    type(factor_t), intent(inout) :: g
    select case (trim(methods(m)))
    case ('dense'); call factor_build(g, a, 'dense')
    case ('cholmod-metis'); call factor_build(g, a, 'cholmod', 'metis')
    case ('cholmod-amd'); call factor_build(g, a, 'cholmod', 'amd')
    case ('cholmod-best'); call factor_build(g, a, 'cholmod', 'best')
    case ('umfpack'); call factor_build(g, a, 'umfpack')
    end select
  end subroutine build

  !> One call of the timed task (a task code, not a procedure argument: internal
  !> procedures passed as arguments would need an executable stack).
  subroutine run_task(task)
    integer, intent(in) :: task
    type(sparse_t) :: tmp
    type(factor_t) :: g
    select case (task)
    case (task_assemble)
      call sparse_from_triplets(n, rows, cols, vals, tmp, map)
    case (task_refill)
      call sparse_refill(a, map, vals2)
    case (task_build)
      call build(g)
      call factor_free(g)
    case (task_update)
      call factor_update(f, a)
    case (task_solve1)
      b1 = xstar(:, 1)
      call factor_solve(f, b1)
    case (task_solve10)
      b = xstar
      call factor_solve(f, b)
    end select
  end subroutine run_task

  !> Best CPU time per call of the task (see the header): calls are timed in batches long
  !> enough for the clock (>= 2 ms), the best batch is kept.
  real(wp) function best_time(task) result(best)
    integer, intent(in) :: task
    real(wp) :: spent, t0, t1, t
    integer :: batches, reps, r
    call cpu_time(t0)
    call run_task(task)
    call cpu_time(t1)
    best = t1 - t0
    spent = best
    reps = max(1, min(100000, int(2.0e-3_wp / max(best, 1.0e-8_wp))))
    batches = 1
    do while ((batches < 3 .or. spent < budget) .and. batches < 200 .and. .not. (batches >= 2 .and. spent > long_budget))
      call cpu_time(t0)
      do r = 1, reps
        call run_task(task)
      end do
      call cpu_time(t1)
      t = (t1 - t0) / reps
      best = min(best, t)
      spent = spent + (t1 - t0)
      batches = batches + 1
    end do
  end function best_time
end program linear_solver_bench
