!> Factorize a square sparse matrix once, solve with it many times: the iteration matrix
!> A = M + h^2 theta^2 K of a meshed body (symmetric positive definite, n from 6 to ~2e5).
!>
!>   call factor_build(f, a, method [, ordering])  ! method 'auto' | 'dense' | 'cholmod' | 'umfpack'
!>   call factor_solve(f, b)                       ! b(n) or b(n, nrhs), overwritten by A^-1 b
!>   call factor_update(f, a)                      ! new values, same pattern: numeric only
!>   print *, factor_method_name(f)                ! e.g. 'CHOLMOD simplicial LL^T, METIS ordering, n = .., nnz(L) = ..'
!>   nnz = factor_nnz(f)                           ! stored entries of the factors (memory: 8 bytes each)
!>   call factor_free(f)
!>   call dense_spd_inverse(c [, ok])              ! c := c^-1 in place (small SPD blocks)
!>
!> Methods:
!> * 'dense': LAPACK Cholesky (dpotrf/dpotrs) of the dense copy (upper triangle read).
!> * 'cholmod': CHOLMOD sparse Cholesky LL^T (upper triangle read), simplicial, or
!>   supernodal when the factorization costs more than 300 flops per entry of L (3D
!>   meshes; 2D meshes up to ~2e5 unknowns stay simplicial, which is faster there with
!>   the reference BLAS), with a fill-reducing ordering: `ordering` = 'best' (default:
!>   METIS and AMD both tried, the one with less fill kept), 'metis' (AMD if METIS
!>   fails) or 'amd'.
!> * 'umfpack': UMFPACK sparse LU (any nonsingular matrix; ordering as above, 'best'
!>   meaning UMFPACK's own choice).
!> * 'auto': dense for n <= auto_dense_max_n (measured: doc/benchmarks.md, "Linear solvers
!>   for meshed bodies"), CHOLMOD above. A matrix that is not symmetric (relative
!>   asymmetry above 1e-10) or whose Cholesky fails goes to LU instead (LAPACK dgetrf /
!>   UMFPACK), with one warning per run; a factor that fell back stays on LU in updates.
!> The Cholesky methods never check symmetry: they read the upper triangle only.
!> Failures (not positive definite, singular, pattern changed) stop the run through
!> fracas_errors with the method's name and what failed.
!>
!> A factor_t owns a C handle: never copy one (pass it by reference), free it with
!> factor_free. The C side (fracas_suitesparse.c) keeps one cholmod_common per factor,
!> so factors do not share state; a factor is not solved from two threads at once.
module fracas_linear_solver
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_double, c_char, &
                                         c_null_char
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal, warn, itoa, status_t, raise
  use fracas_sparse, only: sparse_t, sparse_to_dense, sparse_asymmetry
  implicit none
  private
  public :: factor_t, factor_build, factor_update, factor_solve, factor_method_name, factor_nnz, &
            factor_free, dense_spd_inverse, auto_dense_max_n

  !> 'auto' uses dense LAPACK Cholesky up to this size, CHOLMOD above. Measured with
  !> Debian's reference BLAS (doc/benchmarks.md, "Linear solvers for meshed bodies"):
  !> CHOLMOD solves faster from n ~ 18, refactorizes faster from n ~ 32 and factorizes
  !> faster (ordering included) from n ~ 72-128; solves and refactorizations dominate.
  integer, parameter :: auto_dense_max_n = 32
  !> Largest n for a dense factorization (8 n^2 bytes: 8.6 GB).
  integer, parameter :: dense_limit_n = 32768
  !> Relative asymmetry above which 'auto' takes LU instead of Cholesky.
  real(wp), parameter :: symmetry_tolerance = 1.0e-10_wp

  integer, parameter :: kind_none = 0, kind_dense_cholesky = 1, kind_dense_lu = 2, &
                        kind_cholmod = 3, kind_umfpack = 4
  ! Codes shared with fracas_suitesparse.c.
  integer(c_int), parameter :: fss_cholmod = 1, fss_umfpack = 2
  integer(c_int), parameter :: order_best = 0, order_metis = 1, order_amd = 2
  integer(c_int), parameter :: fss_ok = 0, fss_not_posdef = 1, fss_singular = 2, &
                               fss_pattern_changed = 3

  type :: factor_t
    private
    integer :: n = 0
    integer :: kind = kind_none
    logical :: auto = .false.              !< built with 'auto': may fall back to LU
    integer(c_int) :: ordering = order_best
    real(wp), allocatable :: dense(:, :)   !< dense factors (Cholesky upper or LU)
    integer, allocatable :: ipiv(:)        !< LU pivots
    type(c_ptr) :: handle = c_null_ptr     !< CHOLMOD or UMFPACK factor (C side)
  end type factor_t

  interface factor_solve
    module procedure factor_solve_1, factor_solve_n
  end interface factor_solve

  logical, save :: fallback_reported = .false.

  interface
    function fss_create(kind, n, colptr, rowind, val, ordering, status) result(handle) bind(C, name='fss_create')
      import :: c_ptr, c_int, c_double
      integer(c_int), value :: kind, n, ordering
      integer(c_int), intent(in) :: colptr(*), rowind(*)
      real(c_double), intent(in) :: val(*)
      integer(c_int), intent(out) :: status
      type(c_ptr) :: handle
    end function fss_create
    integer(c_int) function fss_factor(handle, colptr, rowind, val) bind(C, name='fss_factor')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      integer(c_int), intent(in) :: colptr(*), rowind(*)
      real(c_double), intent(in) :: val(*)
    end function fss_factor
    integer(c_int) function fss_solve(handle, b, ldb, nrhs) bind(C, name='fss_solve')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      real(c_double), intent(inout) :: b(*)
      integer(c_int), value :: ldb, nrhs
    end function fss_solve
    subroutine fss_describe(handle, buf, len) bind(C, name='fss_describe')
      import :: c_ptr, c_int, c_char
      type(c_ptr), value :: handle
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_int), value :: len
    end subroutine fss_describe
    subroutine fss_message(handle, buf, len) bind(C, name='fss_message')
      import :: c_ptr, c_int, c_char
      type(c_ptr), value :: handle
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_int), value :: len
    end subroutine fss_message
    real(c_double) function fss_factor_nnz(handle) bind(C, name='fss_factor_nnz')
      import :: c_ptr, c_double
      type(c_ptr), value :: handle
    end function fss_factor_nnz
    subroutine fss_free(handle) bind(C, name='fss_free')
      import :: c_ptr
      type(c_ptr), intent(inout) :: handle
    end subroutine fss_free
  end interface

  interface
    subroutine dpotrf(uplo, n, a, lda, info)
      import :: wp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(wp), intent(inout) :: a(lda, *)
      integer, intent(out) :: info
    end subroutine dpotrf
    subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
      import :: wp
      character, intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb
      real(wp), intent(in) :: a(lda, *)
      real(wp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dpotrs
    subroutine dpotri(uplo, n, a, lda, info)
      import :: wp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(wp), intent(inout) :: a(lda, *)
      integer, intent(out) :: info
    end subroutine dpotri
    subroutine dgetrf(m, n, a, lda, ipiv, info)
      import :: wp
      integer, intent(in) :: m, n, lda
      real(wp), intent(inout) :: a(lda, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgetrf
    subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: wp
      character, intent(in) :: trans
      integer, intent(in) :: n, nrhs, lda, ldb, ipiv(*)
      real(wp), intent(in) :: a(lda, *)
      real(wp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dgetrs
  end interface

contains

  !> Factorize a with the given method (see the module header). f is freed first.
  !> A matrix the method cannot factorize: status (see fracas_errors), or the run stops.
  subroutine factor_build(f, a, method, ordering, status)
    type(factor_t), intent(inout) :: f
    type(sparse_t), intent(in) :: a
    character(len=*), intent(in) :: method
    character(len=*), intent(in), optional :: ordering
    type(status_t), intent(out), optional :: status
    character(len=:), allocatable :: why

    call factor_free(f)
    f%n = a%n
    f%ordering = order_best
    if (present(ordering)) then
      select case (ordering)
      case ('best'); f%ordering = order_best
      case ('metis'); f%ordering = order_metis
      case ('amd'); f%ordering = order_amd
      case default
        call fatal("factor_build: unknown ordering '"//ordering//"' (expected best, metis or amd)")
      end select
    end if
    f%auto = method == 'auto'

    why = ''
    select case (method)
    case ('dense')
      call dense_cholesky(f, a, why)
    case ('cholmod')
      call sparse_factor(f, a, fss_cholmod, why)
    case ('umfpack')
      call sparse_factor(f, a, fss_umfpack, why)
    case ('auto')
      call auto_factor(f, a, why)
    case default
      call fatal("factor_build: unknown method '"//method//"' (expected auto, dense, cholmod or umfpack)")
    end select
    if (len(why) > 0) call raise(status, 'factor_build: '//why)
  end subroutine factor_build

  !> New values of a on the pattern f was built with: numeric refactorization only (the
  !> ordering and symbolic analysis are kept). A failure: status, or the run stops.
  subroutine factor_update(f, a, status)
    type(factor_t), intent(inout) :: f
    type(sparse_t), intent(in) :: a
    type(status_t), intent(out), optional :: status
    character(len=:), allocatable :: why
    integer(c_int) :: fss_status

    if (f%kind == kind_none) call fatal('factor_update: the factor was never built (call factor_build first)')
    if (a%n /= f%n) call fatal('factor_update: matrix of size '//itoa(a%n)//' for a factor of size '//itoa(f%n))
    if (f%auto .and. (f%kind == kind_dense_cholesky .or. f%kind == kind_cholmod)) then
      if (sparse_asymmetry(a) > symmetry_tolerance) then
        call auto_factor(f, a, why)
        if (len(why) > 0) call raise(status, 'factor_update: '//why)
        return
      end if
    end if
    why = ''
    select case (f%kind)
    case (kind_dense_cholesky)
      call dense_cholesky(f, a, why)
      if (len(why) > 0 .and. f%auto) then
        call report_fallback(why, 'LAPACK dgetrf (dense LU)')
        call dense_lu(f, a, why)
      end if
    case (kind_dense_lu)
      call dense_lu(f, a, why)
    case (kind_cholmod, kind_umfpack)
      fss_status = fss_factor(f%handle, a%colptr, a%rowind, a%val)
      if (fss_status == fss_ok) return
      why = sparse_failure(f, fss_status)
      if (fss_status == fss_not_posdef .and. f%auto) then
        call report_fallback(why, 'UMFPACK LU')
        call sparse_factor(f, a, fss_umfpack, why)
      end if
    end select
    if (len(why) > 0) call raise(status, 'factor_update: '//why)
  end subroutine factor_update

  !> b := A^-1 b for one right-hand side. A failure: status, or the run stops.
  subroutine factor_solve_1(f, b, status)
    type(factor_t), intent(inout) :: f
    real(wp), intent(inout), contiguous :: b(:)
    type(status_t), intent(out), optional :: status
    call check_rhs(f, size(b))
    call solve_columns(f, b, 1, status)
  end subroutine factor_solve_1

  !> b := A^-1 b for the columns of b(n, nrhs). A failure: status, or the run stops.
  subroutine factor_solve_n(f, b, status)
    type(factor_t), intent(inout) :: f
    real(wp), intent(inout), contiguous :: b(:, :)
    type(status_t), intent(out), optional :: status
    call check_rhs(f, size(b, 1))
    call solve_columns(f, b, size(b, 2), status)
  end subroutine factor_solve_n

  subroutine check_rhs(f, n)
    type(factor_t), intent(in) :: f
    integer, intent(in) :: n
    if (f%kind == kind_none) call fatal('factor_solve: the factor was never built (call factor_build first)')
    if (n /= f%n) call fatal('factor_solve: right-hand side of length '//itoa(n)//' for a factor of size '//itoa(f%n))
  end subroutine check_rhs

  !> The solve itself on nrhs contiguous columns (one or several, by sequence association).
  subroutine solve_columns(f, b, nrhs, status)
    type(factor_t), intent(inout) :: f
    integer, intent(in) :: nrhs
    real(wp), intent(inout) :: b(f%n, nrhs)
    type(status_t), intent(inout), optional :: status
    integer :: info
    if (f%n == 0 .or. nrhs == 0) return
    select case (f%kind)
    case (kind_dense_cholesky)
      call dpotrs('U', f%n, nrhs, f%dense, f%n, b, f%n, info)
      if (info /= 0) call raise(status, 'factor_solve: LAPACK dpotrs failed (info '//itoa(info)//')')
    case (kind_dense_lu)
      call dgetrs('N', f%n, nrhs, f%dense, f%n, f%ipiv, b, f%n, info)
      if (info /= 0) call raise(status, 'factor_solve: LAPACK dgetrs failed (info '//itoa(info)//')')
    case (kind_cholmod, kind_umfpack)
      if (fss_solve(f%handle, b, int(f%n, c_int), int(nrhs, c_int)) /= fss_ok) &
        call raise(status, 'factor_solve: '//c_text(f%handle, .false.))
    end select
  end subroutine solve_columns

  !> What f is: library, algorithm, ordering, size and fill, e.g.
  !> 'CHOLMOD supernodal LL^T, METIS ordering, n = 20000, nnz(L) = 412345'.
  function factor_method_name(f) result(name)
    type(factor_t), intent(in) :: f
    character(len=:), allocatable :: name
    select case (f%kind)
    case (kind_dense_cholesky)
      name = 'LAPACK dpotrf (dense Cholesky), n = '//itoa(f%n)
    case (kind_dense_lu)
      name = 'LAPACK dgetrf (dense LU), n = '//itoa(f%n)
    case (kind_cholmod, kind_umfpack)
      name = c_text(f%handle, .true.)
    case default
      name = '(no factor)'
    end select
  end function factor_method_name

  !> Entries of the factors: n(n+1)/2 (dense Cholesky), n^2 (dense LU), nnz(L) (CHOLMOD),
  !> nnz(L) + nnz(U) - n (UMFPACK).
  real(wp) function factor_nnz(f)
    type(factor_t), intent(in) :: f
    select case (f%kind)
    case (kind_dense_cholesky)
      factor_nnz = 0.5_wp * real(f%n, wp) * real(f%n + 1, wp)
    case (kind_dense_lu)
      factor_nnz = real(f%n, wp)**2
    case (kind_cholmod, kind_umfpack)
      factor_nnz = real(fss_factor_nnz(f%handle), wp)
    case default
      factor_nnz = 0.0_wp
    end select
  end function factor_nnz

  subroutine factor_free(f)
    type(factor_t), intent(inout) :: f
    if (c_associated(f%handle)) call fss_free(f%handle)
    f%handle = c_null_ptr
    if (allocated(f%dense)) deallocate (f%dense)
    if (allocated(f%ipiv)) deallocate (f%ipiv)
    f%kind = kind_none
    f%n = 0
  end subroutine factor_free

  !> c := c^-1 for a small symmetric positive definite matrix (both triangles returned).
  !> A matrix that is not positive definite: status (c is then left undefined and
  !> minor, if present, is the order of the first leading minor that is not
  !> positive, 0 if the inversion failed after it), or the run stops.
  subroutine dense_spd_inverse(c, status, minor)
    real(wp), intent(inout) :: c(:, :)
    type(status_t), intent(out), optional :: status
    integer, intent(out), optional :: minor
    integer :: n, info, j
    n = size(c, 1)
    if (size(c, 2) /= n) call fatal('dense_spd_inverse: matrix is '//itoa(n)//' x '//itoa(size(c, 2))//', not square')
    if (present(minor)) minor = 0
    if (n == 0) return
    call dpotrf('U', n, c, n, info)
    if (info > 0 .and. present(minor)) minor = info
    if (info == 0) call dpotri('U', n, c, n, info)
    if (info /= 0) then
      call raise(status, 'dense_spd_inverse: LAPACK dpotrf: matrix not positive definite (leading minor '// &
                 itoa(info)//' of '//itoa(n)//')')
      return
    end if
    do j = 1, n - 1
      c(j + 1:n, j) = c(j, j + 1:n)
    end do
  end subroutine dense_spd_inverse

  ! ---------------------------------------------------------------------------------------

  !> 'auto': dense or CHOLMOD by size, LU when not symmetric or Cholesky fails; why
  !> is empty on success, else names the failure of the last method tried.
  subroutine auto_factor(f, a, why)
    type(factor_t), intent(inout) :: f
    type(sparse_t), intent(in) :: a
    character(len=:), allocatable, intent(out) :: why
    real(wp) :: asym
    logical :: small
    integer(c_int) :: ordering

    small = a%n <= auto_dense_max_n
    ordering = f%ordering
    call factor_free(f)
    f%n = a%n
    f%auto = .true.
    f%ordering = ordering
    asym = sparse_asymmetry(a)
    if (asym <= symmetry_tolerance) then
      if (small) then
        call dense_cholesky(f, a, why)
        if (len(why) == 0) return
        call report_fallback(why, 'LAPACK dgetrf (dense LU)')
      else
        call sparse_factor(f, a, fss_cholmod, why)
        if (len(why) == 0) return
        call report_fallback(why, 'UMFPACK LU')
      end if
    else
      why = 'matrix not symmetric (relative asymmetry '//etoa(asym)//')'
      call report_fallback(why, merge('LAPACK dgetrf (dense LU)', 'UMFPACK LU              ', small))
    end if
    if (small) then
      call dense_lu(f, a, why)
    else
      call sparse_factor(f, a, fss_umfpack, why)
    end if
  end subroutine auto_factor

  !> Dense Cholesky of a into f; why is empty on success, else names the failure.
  subroutine dense_cholesky(f, a, why)
    type(factor_t), intent(inout) :: f
    type(sparse_t), intent(in) :: a
    character(len=:), allocatable, intent(out) :: why
    integer :: info
    call check_dense_size(a%n)
    call sparse_to_dense(a, f%dense)
    f%kind = kind_dense_cholesky
    why = ''
    if (a%n == 0) return
    call dpotrf('U', a%n, f%dense, a%n, info)
    if (info > 0) why = 'LAPACK dpotrf (dense Cholesky): matrix not positive definite (leading minor '// &
                        itoa(info)//' of '//itoa(a%n)//')'
  end subroutine dense_cholesky

  subroutine dense_lu(f, a, why)
    type(factor_t), intent(inout) :: f
    type(sparse_t), intent(in) :: a
    character(len=:), allocatable, intent(out) :: why
    integer :: info
    call check_dense_size(a%n)
    call sparse_to_dense(a, f%dense)
    if (allocated(f%ipiv)) deallocate (f%ipiv)
    allocate (f%ipiv(a%n))
    f%kind = kind_dense_lu
    why = ''
    if (a%n == 0) return
    call dgetrf(a%n, a%n, f%dense, a%n, f%ipiv, info)
    if (info > 0) why = 'LAPACK dgetrf (dense LU): matrix singular (zero pivot at column '// &
                        itoa(info)//' of '//itoa(a%n)//')'
  end subroutine dense_lu

  !> A dense copy of n x n doubles above 8 GB is a mistake, not a plan: say so.
  subroutine check_dense_size(n)
    integer, intent(in) :: n
    if (n > dense_limit_n) call fatal('factor_build: a dense factorization of n = '//itoa(n)// &
                                      ' unknowns needs '//itoa(int(8.0_wp * real(n, wp)**2 / 1.0e9_wp))// &
                                      ' GB; use the method cholmod (or auto)')
  end subroutine check_dense_size

  !> Symbolic analysis and numeric factorization through the C shim (CHOLMOD or UMFPACK),
  !> replacing whatever f held.
  subroutine sparse_factor(f, a, which, why)
    type(factor_t), intent(inout) :: f
    type(sparse_t), intent(in) :: a
    integer(c_int), intent(in) :: which
    character(len=:), allocatable, intent(out) :: why
    integer(c_int) :: status

    if (c_associated(f%handle)) call fss_free(f%handle)
    if (allocated(f%dense)) deallocate (f%dense)
    if (allocated(f%ipiv)) deallocate (f%ipiv)
    f%kind = merge(kind_cholmod, kind_umfpack, which == fss_cholmod)
    f%handle = fss_create(which, int(a%n, c_int), a%colptr, a%rowind, a%val, f%ordering, status)
    why = ''
    if (.not. c_associated(f%handle)) then
      why = 'out of memory for a sparse factor'
      return
    end if
    if (status == fss_ok) status = fss_factor(f%handle, a%colptr, a%rowind, a%val)
    if (status /= fss_ok) why = sparse_failure(f, status)
  end subroutine sparse_factor

  !> Message for a failed C-side factorization, naming the library.
  function sparse_failure(f, status) result(why)
    type(factor_t), intent(in) :: f
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: why
    character(len=:), allocatable :: lib
    lib = merge('CHOLMOD Cholesky', 'UMFPACK LU      ', f%kind == kind_cholmod)
    why = trim(lib)//': '//c_text(f%handle, .false.)
    if (status == fss_pattern_changed) why = why//'; call factor_build for a new pattern'
  end function sparse_failure

  !> One warning per run when 'auto' leaves Cholesky for LU.
  subroutine report_fallback(why, instead)
    character(len=*), intent(in) :: why, instead
    if (fallback_reported) return
    fallback_reported = .true.
    call warn('linear solver: '//why//'; using '//trim(instead)//' instead (reported once per run)')
  end subroutine report_fallback

  !> fss_describe (describe = true) or fss_message of a handle, as Fortran text.
  function c_text(handle, describe) result(text)
    type(c_ptr), intent(in) :: handle
    logical, intent(in) :: describe
    character(len=:), allocatable :: text
    character(kind=c_char) :: buf(256)
    integer :: i
    if (describe) then
      call fss_describe(handle, buf, int(size(buf), c_int))
    else
      call fss_message(handle, buf, int(size(buf), c_int))
    end if
    text = ''
    do i = 1, size(buf)
      if (buf(i) == c_null_char) exit
      text = text//buf(i)
    end do
  end function c_text

  function etoa(x) result(s)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write (buf, '(es10.3)') x
    s = trim(adjustl(buf))
  end function etoa
end module fracas_linear_solver
