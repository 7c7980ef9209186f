!> Nonlinear Gauss–Seidel in stored-Delassus mode (LMGC90's "Stored_Delassus_Loops",
!> the form of FCLib local problems): u = W r + q with W given explicitly as
!> dim x dim blocks, the diagonal block of each contact and the off-diagonal
!> blocks as a block-sparse (block CSR) matrix. Each contact in turn gathers
!> q_a + sum_b W_ab r_b over its off-diagonal blocks and solves its local
!> problem exactly (2D: coulomb_2d_inv; 3D: coulomb_3d).
!>
!> Stopping: LMGC90's norms (Quad, Maxm, QM/16, as the scene NLGS) and/or the
!> FCLib natural-map error ||F(r)|| / ||q|| (reference/fclib_siconos.md §2.1).
!> The natural map is estimated for free inside each check sweep: each contact's
!> F of its reaction before the update, with the velocity it sees then (the
!> Gauss–Seidel residual); when the estimate meets the tolerance the exact
!> error is computed (one product W r) and decides.
module fracas_sdl
  use, intrinsic :: iso_fortran_env, only: int64
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal, warn, status_t, raise
  use fracas_random, only: rng_t, rng_seed, rng_permute
  use fracas_lmgc_norms, only: lmgc_norms_t, lmgc_norms, lmgc_add_sums
  use fracas_local_solver, only: coulomb_2d_inv, inverse_block, natural_map_2d, coulomb_3d, inverse_block_3d, &
                                 natural_map_3d
  implicit none
  private
  public :: sdl_problem_t, sdl_settings_t, sdl_report_t, sdl_history_t
  public :: sdl_build, sdl_solve, sdl_error, sdl_velocity, sdl_history_points

  !> A local problem in block form. Components of a contact: normal first
  !> (FCLib order). Blocks are stored column-major (dim*dim values).
  type :: sdl_problem_t
    integer :: dim = 0, nc = 0, nblocks = 0
    real(wp), allocatable :: q(:, :)      !< (dim, nc)
    real(wp), allocatable :: mu(:)        !< (nc)
    real(wp), allocatable :: wd(:, :)     !< (dim*dim, nc) diagonal blocks
    real(wp), allocatable :: wdi(:, :)    !< 2D: inverse_block (6, nc), 3D: inverse_block_3d (9, nc)
    integer, allocatable :: bptr(:)       !< (nc+1) first off-diagonal block of each block row
    integer, allocatable :: bcol(:)       !< (nblocks) block column
    real(wp), allocatable :: bval(:, :)   !< (dim*dim, nblocks)
    real(wp) :: norm_q = 0.0_wp
    integer :: regularised = 0            !< diagonal blocks shifted to be invertible
  end type sdl_problem_t

  type :: sdl_settings_t
    character(len=5) :: check = 'none '     !< LMGC90 norm: Quad, Maxm, QM/16, or none
    real(wp) :: tol = 1.0e-4_wp             !< tolerance of the LMGC90 norm
    real(wp) :: err_tol = 1.0e-8_wp         !< stop on ||F||/||q|| <= err_tol (0: off)
    real(wp) :: relax = 1.0_wp
    integer :: sweeps_per_check = 1
    integer :: max_sweeps = 100000
    character(len=8) :: order = 'stored'    !< stored, reversed, shuffled
    integer :: seed = 1
    real(wp) :: time_limit = huge(1.0_wp)   !< seconds of solve time
    integer :: accel = 10                   !< Anderson acceleration memory (0: plain NLGS)
  end type sdl_settings_t

  !> Anderson acceleration of the sweep map r -> G(r) (Walker & Ni 2011, type II,
  !> memory m): r <- G(r) - dG gamma with gamma the least-squares fit of the
  !> last sweep change f = G(r) - r by the m previous changes of f, then each
  !> contact projected on its cone. The history restarts when |f| exceeds twice
  !> its smallest value since the last restart. A step costs about 2m dot
  !> products and m updates of length dim*nc: it follows every sweep when that
  !> is cheaper than ~1.5 sweeps, else every 4 sweeps (acceleration of G^4);
  !> if the Gauss–Seidel residual estimate has not halved in 300 sweeps the
  !> period switches (1 <-> 4) and the history restarts.
  type :: aa_t
    integer :: m = 0, k = 0, next = 1, every = 1
    real(wp) :: restart = 2.0_wp
    logical :: have_prev = .false.
    integer :: window = 300, mark_sweep = 0, switches = 0
    real(wp) :: mark = huge(1.0_wp)
    real(wp) :: fmin = huge(1.0_wp)
    real(wp), allocatable :: df(:, :), dg(:, :), f(:), fprev(:), gprev(:), h(:, :)
  end type aa_t

  type :: sdl_report_t
    integer :: sweeps = 0
    logical :: converged = .false.
    real(wp) :: time = 0.0_wp            !< solve wall time (s), history evaluations excluded
    real(wp) :: err_abs = 0.0_wp         !< ||F(r)||
    real(wp) :: err_paper = 0.0_wp       !< ||F|| / ||q|| (||F|| if ||q|| <= eps)
    real(wp) :: err_onepq = 0.0_wp       !< ||F|| / (1 + ||q||)
    integer :: exact_checks = 0          !< products W r done to confirm the stop
    integer :: local_failures = 0        !< 3D local solves without an exact sliding solution
    real(wp) :: quad_dv = 0.0_wp, maxm_dv = 0.0_wp, quad_dvr = 0.0_wp, maxm_dvr = 0.0_wp, mean_dvor = 0.0_wp
  end type sdl_report_t

  !> Error after chosen sweep counts (error-versus-time curves); the
  !> evaluations are not counted in the times.
  type :: sdl_history_t
    integer, allocatable :: at(:)         !< sweep counts to record (increasing)
    integer :: n = 0                      !< records filled
    integer, allocatable :: sweeps(:)
    real(wp), allocatable :: time(:), err_paper(:), err_onepq(:)
  end type sdl_history_t

contains

  !> Build the block form from 1-based triplets (row, col, val) of W (m = dim*nc
  !> square; duplicates add up), q (m) and mu (nc).
  subroutine sdl_build(dim, nc, row, col, val, q, mu, p)
    integer, intent(in) :: dim, nc
    integer, intent(in) :: row(:), col(:)
    real(wp), intent(in) :: val(:), q(:), mu(:)
    type(sdl_problem_t), intent(out) :: p
    integer, allocatable :: cnt(:), start(:), perm(:), pos(:), fill(:)
    integer :: k, a, b, i, j, nb, e, d2
    real(wp) :: det, scale, wl(4)
    p%dim = dim; p%nc = nc
    d2 = dim * dim
    p%q = reshape(q, [dim, nc])
    p%mu = mu
    p%norm_q = sqrt(sum(q**2))
    allocate (p%wd(d2, nc), source=0.0_wp)
    ! bucket entries by block row
    allocate (cnt(nc), source=0)
    do k = 1, size(row)
      a = (row(k) - 1) / dim + 1
      cnt(a) = cnt(a) + 1
    end do
    allocate (start(nc + 1))
    start(1) = 1
    do a = 1, nc
      start(a + 1) = start(a) + cnt(a)
    end do
    allocate (perm(size(row)), fill(nc))
    fill = start(1:nc)
    do k = 1, size(row)
      a = (row(k) - 1) / dim + 1
      perm(fill(a)) = k
      fill(a) = fill(a) + 1
    end do
    ! count distinct off-diagonal block columns per block row
    allocate (pos(nc), source=0)
    allocate (p%bptr(nc + 1))
    p%bptr(1) = 1
    nb = 0
    do a = 1, nc
      do e = start(a), start(a + 1) - 1
        b = (col(perm(e)) - 1) / dim + 1
        if (b /= a .and. pos(b) /= a) then
          pos(b) = a
          nb = nb + 1
        end if
      end do
      p%bptr(a + 1) = nb + 1
    end do
    p%nblocks = nb
    allocate (p%bcol(nb), p%bval(d2, nb))
    p%bval = 0.0_wp
    pos = 0
    nb = 0
    do a = 1, nc
      ! pos(b) = index of block (a,b) while row a is assembled (block columns sorted later)
      do e = start(a), start(a + 1) - 1
        k = perm(e)
        b = (col(k) - 1) / dim + 1
        i = row(k) - (a - 1) * dim
        j = col(k) - (b - 1) * dim
        if (b == a) then
          p%wd(i + dim * (j - 1), a) = p%wd(i + dim * (j - 1), a) + val(k)
        else
          if (pos(b) == 0) then
            nb = nb + 1
            pos(b) = nb
            p%bcol(nb) = b
          end if
          p%bval(i + dim * (j - 1), pos(b)) = p%bval(i + dim * (j - 1), pos(b)) + val(k)
        end if
      end do
      do e = p%bptr(a), p%bptr(a + 1) - 1
        pos(p%bcol(e)) = 0
      end do
      call sort_row(p%bptr(a), p%bptr(a + 1) - 1)
    end do
    ! local-solver data of the diagonal blocks
    p%regularised = 0
    if (dim == 2) then
      allocate (p%wdi(6, nc))
      do a = 1, nc
        ! FCLib (n, t) -> coulomb_2d's (t, n): wtt = W(2,2), wtn = W(2,1), wnt = W(1,2), wnn = W(1,1)
        ! (a copy is shifted if singular: W itself stays as read, for the error)
        wl = p%wd(:, a)
        scale = max(abs(wl(1)), abs(wl(4)), tiny(1.0_wp))
        det = wl(4) * wl(1) - wl(2) * wl(3)
        if (det <= 1.0e-13_wp * scale**2 .or. wl(1) - p%mu(a) * abs(wl(3)) <= 1.0e-13_wp * scale) then
          wl(1) = wl(1) + 1.0e-10_wp * scale
          wl(4) = wl(4) + 1.0e-10_wp * scale
          p%regularised = p%regularised + 1
        end if
        p%wdi(:, a) = inverse_block(wl(4), wl(2), wl(3), wl(1), p%mu(a))
      end do
    else if (dim == 3) then
      allocate (p%wdi(9, nc))
      do a = 1, nc
        p%wdi(:, a) = inverse_block_3d(p%wd(:, a))
      end do
    else
      call fatal('sdl_build: dimension must be 2 or 3')
    end if
    if (p%regularised > 0) call warn('stored-Delassus NLGS: shifted the diagonal of singular 2x2 blocks')

  contains

    !> Insertion sort of the blocks e1..e2 by column (rows are short).
    subroutine sort_row(e1, e2)
      integer, intent(in) :: e1, e2
      integer :: x, y, c
      real(wp) :: v(d2)
      do x = e1 + 1, e2
        c = p%bcol(x); v = p%bval(:, x)
        y = x - 1
        do while (y >= e1)
          if (p%bcol(y) <= c) exit
          p%bcol(y + 1) = p%bcol(y); p%bval(:, y + 1) = p%bval(:, y)
          y = y - 1
        end do
        p%bcol(y + 1) = c; p%bval(:, y + 1) = v
      end do
    end subroutine sort_row
  end subroutine sdl_build

  !> u = W r + q.
  subroutine sdl_velocity(p, r, u)
    type(sdl_problem_t), intent(in) :: p
    real(wp), intent(in) :: r(:, :)
    real(wp), intent(out) :: u(:, :)
    integer :: a, e, b, i, j, d
    d = p%dim
    do a = 1, p%nc
      u(:, a) = p%q(:, a)
      do j = 1, d
        do i = 1, d
          u(i, a) = u(i, a) + p%wd(i + d * (j - 1), a) * r(j, a)
        end do
      end do
      do e = p%bptr(a), p%bptr(a + 1) - 1
        b = p%bcol(e)
        do j = 1, d
          do i = 1, d
            u(i, a) = u(i, a) + p%bval(i + d * (j - 1), e) * r(j, b)
          end do
        end do
      end do
    end do
  end subroutine sdl_velocity

  !> Our evaluator of the FCLib natural-map error of r: ||F||, ||F||/||q||
  !> (||F|| when ||q|| <= eps, as eval_solution.py) and ||F||/(1+||q||).
  subroutine sdl_error(p, r, err_abs, err_paper, err_onepq)
    type(sdl_problem_t), intent(in) :: p
    real(wp), intent(in) :: r(:, :)
    real(wp), intent(out) :: err_abs, err_paper, err_onepq
    real(wp), allocatable :: u(:, :)
    real(wp) :: f2
    integer :: a
    allocate (u(p%dim, p%nc))
    call sdl_velocity(p, r, u)
    f2 = 0.0_wp
    if (p%dim == 2) then
      do a = 1, p%nc
        f2 = f2 + natural_map_2d(u(2, a), u(1, a), r(2, a), r(1, a), p%mu(a))
      end do
    else
      do a = 1, p%nc
        f2 = f2 + natural_map_3d(u(:, a), r(:, a), p%mu(a))
      end do
    end if
    err_abs = sqrt(f2)
    err_paper = err_abs / qnorm(p)
    err_onepq = err_abs / (1.0_wp + p%norm_q)
  end subroutine sdl_error

  pure real(wp) function qnorm(p)
    type(sdl_problem_t), intent(in) :: p
    qnorm = p%norm_q
    if (qnorm <= epsilon(1.0_wp)) qnorm = 1.0_wp
  end function qnorm

  !> About ten sweep counts per decade, 1 .. nmax (for sdl_history_t%at).
  function sdl_history_points(nmax) result(at)
    integer, intent(in) :: nmax
    integer, allocatable :: at(:)
    integer :: i, k, last
    allocate (at(0))
    last = 0
    i = 0
    do
      k = nint(10.0_wp**(real(i, wp) / 10.0_wp))
      i = i + 1
      if (k > nmax) exit
      if (k > last) then
        at = [at, k]
        last = k
      end if
    end do
  end function sdl_history_points

  !> Solve from the warm start r (dim, nc); r is the last iterate on return.
  !> An iteration that diverges (NaN or Inf in LMGC90's norms): status, or the
  !> run stops.
  subroutine sdl_solve(p, s, r, rep, hist, status)
    type(sdl_problem_t), intent(in) :: p
    type(sdl_settings_t), intent(in) :: s
    real(wp), intent(inout) :: r(:, :)
    type(sdl_report_t), intent(out) :: rep
    type(sdl_history_t), intent(inout), optional :: hist
    type(status_t), intent(out), optional :: status
    integer, allocatable :: order(:)
    type(rng_t) :: rng
    integer :: n, k, ih, spc, nfail
    integer(int64) :: t0, t1, rate, paused
    type(aa_t) :: aa
    real(wp), allocatable :: xprev(:, :)
    real(wp) :: tol_light, fsum, sums(6), maxes(2), e_est, ea, ep, eo
    logical :: check, est, lmgc, conv, have_exact, finite
    n = p%nc
    spc = max(1, s%sweeps_per_check)
    allocate (order(n))
    select case (s%order)
    case ('reversed')
      order = [(n + 1 - k, k=1, n)]
    case default
      order = [(k, k=1, n)]
    end select
    call rng_seed(rng, s%seed)
    if (s%accel > 0) then
      aa%m = s%accel
      ! accelerate every sweep when a step costs less than ~1.5 sweeps, else every 4
      if (2.0_wp * aa%m * p%dim * n > 1.5_wp * (p%dim**2 * (p%nblocks + n))) aa%every = 4
      allocate (aa%df(p%dim * n, aa%m), aa%dg(p%dim * n, aa%m), aa%f(p%dim * n), aa%fprev(p%dim * n), &
                aa%gprev(p%dim * n), aa%h(aa%m, aa%m), xprev(p%dim, n))
    end if
    ih = 1
    if (present(hist)) then
      hist%n = 0
      k = size(hist%at)
      if (allocated(hist%sweeps)) deallocate (hist%sweeps, hist%time, hist%err_paper, hist%err_onepq)
      allocate (hist%sweeps(k), hist%time(k), hist%err_paper(k), hist%err_onepq(k))
    end if
    rep%sweeps = 0
    rep%converged = .false.
    rep%exact_checks = 0
    rep%local_failures = 0
    have_exact = .false.
    tol_light = s%err_tol
    paused = 0
    call system_clock(t0, rate)
    ! the start may already be a solution (q = 0, or a converged warm start)
    if (s%err_tol > 0.0_wp .and. s%check == 'none') then
      call sdl_error(p, r, ea, ep, eo)
      rep%exact_checks = 1
      have_exact = .true.
      rep%converged = ep <= s%err_tol
    end if
    if (n == 0) rep%converged = .true.
    do while (.not. rep%converged .and. rep%sweeps < s%max_sweeps)
      if (s%order == 'shuffled' .and. mod(rep%sweeps, spc) == 0) call rng_permute(rng, order)
      check = mod(rep%sweeps + 1, spc) == 0
      est = check .and. s%err_tol > 0.0_wp
      lmgc = check .and. s%check /= 'none'
      if (s%accel > 0 .and. mod(rep%sweeps, aa%every) == 0) xprev = r
      if (p%dim == 2) then
        call sweep_2d(p, order, s%relax, r, est, lmgc, fsum, sums, maxes)
      else
        call sweep_3d(p, order, s%relax, r, est, lmgc, fsum, sums, maxes, nfail)
        rep%local_failures = rep%local_failures + nfail
      end if
      if (s%accel > 0 .and. mod(rep%sweeps + 1, aa%every) == 0) call aa_step(aa, p, xprev, r)
      rep%sweeps = rep%sweeps + 1
      have_exact = .false.
      if (present(hist)) then
        if (ih <= size(hist%at)) then
          if (rep%sweeps == hist%at(ih)) then
            call record()
            ih = ih + 1
          end if
        end if
      end if
      if (check) then
        ! no criterion at all (err_tol = 0, check none): run max_sweeps
        conv = lmgc .or. s%err_tol > 0.0_wp
        if (lmgc) then
          conv = lmgc_converged(p, s, sums, maxes, rep, finite)
          if (.not. finite) then
            call raise(status, 'stored-Delassus NLGS diverged (NaN or Inf in the reactions)')
            return
          end if
        end if
        if (est) then
          e_est = sqrt(fsum) / qnorm(p)
          if (s%accel > 0) call aa_watch(aa, e_est, rep%sweeps)
        end if
        if (conv .and. s%err_tol > 0.0_wp) then
          conv = e_est <= tol_light
          if (conv) then
            call sdl_error(p, r, ea, ep, eo)
            rep%exact_checks = rep%exact_checks + 1
            have_exact = .true.
            conv = ep <= s%err_tol
            ! the estimate was optimistic: ask it for more next time
            if (.not. conv) tol_light = min(tol_light, 0.5_wp * e_est * s%err_tol / max(ep, tiny(1.0_wp)))
          end if
        end if
        rep%converged = conv
        call system_clock(t1)
        if (real(t1 - t0 - paused, wp) / real(rate, wp) > s%time_limit) exit
      end if
    end do
    call system_clock(t1)
    rep%time = real(t1 - t0 - paused, wp) / real(rate, wp)
    if (.not. have_exact) call sdl_error(p, r, ea, ep, eo)
    rep%err_abs = ea; rep%err_paper = ep; rep%err_onepq = eo
    if (present(hist)) then
      if (hist%n == 0 .or. hist%sweeps(max(1, hist%n)) /= rep%sweeps) then
        if (hist%n == size(hist%sweeps)) then
          hist%sweeps = [hist%sweeps, 0]; hist%time = [hist%time, 0.0_wp]
          hist%err_paper = [hist%err_paper, 0.0_wp]; hist%err_onepq = [hist%err_onepq, 0.0_wp]
        end if
        hist%n = hist%n + 1
        hist%sweeps(hist%n) = rep%sweeps; hist%time(hist%n) = rep%time
        hist%err_paper(hist%n) = ep; hist%err_onepq(hist%n) = eo
      end if
    end if

  contains

    !> Record the exact error now; the time spent here is not counted.
    subroutine record()
      integer(int64) :: ta, tb
      real(wp) :: a1, a2, a3
      call system_clock(ta)
      call sdl_error(p, r, a1, a2, a3)
      hist%n = hist%n + 1
      hist%sweeps(hist%n) = rep%sweeps
      hist%time(hist%n) = real(ta - t0 - paused, wp) / real(rate, wp)
      hist%err_paper(hist%n) = a2
      hist%err_onepq(hist%n) = a3
      call system_clock(tb)
      paused = paused + (tb - ta)
    end subroutine record
  end subroutine sdl_solve

  !> One Anderson step: x the iterate before the sweep, r = G(x) on entry and
  !> the accelerated (projected) iterate on return.
  subroutine aa_step(aa, p, x, r)
    type(aa_t), intent(inout) :: aa
    type(sdl_problem_t), intent(in) :: p
    real(wp), intent(in), target, contiguous :: x(:, :)
    real(wp), intent(inout), target, contiguous :: r(:, :)
    real(wp), pointer :: xv(:), gv(:)
    real(wp) :: b(aa%m), a(aa%m, aa%m), gam(aa%m)
    real(wp) :: fn, reg, s1, s2, fi
    integer :: n, i, j, c, k, info
    n = size(r)
    xv(1:n) => x
    gv(1:n) => r
    do i = 1, n
      aa%f(i) = gv(i) - xv(i)
    end do
    call dot2(aa%f, aa%f, aa%f, fn, fi)
    fn = sqrt(fn)
    c = 0
    if (aa%have_prev) then
      if (fn > aa%fmin .and. fn / aa%restart > aa%fmin) then
        ! the sweep change grew: forget the history
        aa%k = 0; aa%next = 1; aa%fmin = fn
      else
        c = aa%next
        aa%k = min(aa%k + 1, aa%m)
        aa%next = mod(c, aa%m) + 1
      end if
    end if
    ! new difference column (if any) and the previous f, g in one pass
    if (c > 0) then
      do i = 1, n
        aa%df(i, c) = aa%f(i) - aa%fprev(i)
        aa%dg(i, c) = gv(i) - aa%gprev(i)
        aa%fprev(i) = aa%f(i)
        aa%gprev(i) = gv(i)
      end do
    else
      aa%fprev = aa%f
      aa%gprev = gv
    end if
    aa%fmin = min(aa%fmin, fn)
    aa%have_prev = .true.
    k = aa%k
    if (k == 0) return
    ! Gram row of the new column and right-hand side, one pass per column
    do j = 1, k
      if (c > 0) then
        call dot2(aa%df(:, j), aa%df(:, c), aa%f, s1, s2)
        aa%h(c, j) = s1
        aa%h(j, c) = s1
      else
        call dot2(aa%df(:, j), aa%f, aa%f, s2, s1)
      end if
      b(j) = s2
    end do
    a(1:k, 1:k) = aa%h(1:k, 1:k)
    reg = 0.0_wp
    do j = 1, k
      reg = max(reg, a(j, j))
    end do
    reg = 1.0e-10_wp * max(tiny(1.0_wp), reg)
    do j = 1, k
      a(j, j) = a(j, j) + reg
    end do
    call solve_small(a(1:k, 1:k), b(1:k), gam(1:k), info)
    if (info /= 0) then
      aa%k = 0; aa%next = 1
      return
    end if
    do j = 1, k
      gv = gv - gam(j) * aa%dg(:, j)
    end do
    call project_all(p, r)
  end subroutine aa_step

  !> s1 = x.y and s2 = x.z with four partial sums each (the reductions
  !> vectorise without reassociation flags).
  pure subroutine dot2(x, y, z, s1, s2)
    real(wp), intent(in) :: x(:), y(:), z(:)
    real(wp), intent(out) :: s1, s2
    real(wp) :: a(4), b(4)
    integer :: i, n, n4
    n = size(x)
    n4 = n - mod(n, 4)
    a = 0.0_wp; b = 0.0_wp
    do i = 1, n4, 4
      a = a + x(i:i + 3) * y(i:i + 3)
      b = b + x(i:i + 3) * z(i:i + 3)
    end do
    do i = n4 + 1, n
      a(1) = a(1) + x(i) * y(i)
      b(1) = b(1) + x(i) * z(i)
    end do
    s1 = (a(1) + a(2)) + (a(3) + a(4))
    s2 = (b(1) + b(2)) + (b(3) + b(4))
  end subroutine dot2

  !> Stall watch: if the Gauss–Seidel residual estimate has not halved over
  !> aa%window sweeps, switch the acceleration between every sweep and every
  !> 4 sweeps (the map G or G^4) and restart its history.
  subroutine aa_watch(aa, e, sweeps)
    type(aa_t), intent(inout) :: aa
    real(wp), intent(in) :: e
    integer, intent(in) :: sweeps
    if (e < 0.5_wp * aa%mark) then
      aa%mark = e
      aa%mark_sweep = sweeps
    else if (sweeps - aa%mark_sweep >= aa%window) then
      aa%every = merge(4, 1, aa%every == 1)
      aa%k = 0; aa%next = 1; aa%have_prev = .false.; aa%fmin = huge(1.0_wp)
      aa%mark = e
      aa%mark_sweep = sweeps
      aa%switches = aa%switches + 1
    end if
  end subroutine aa_watch

  !> Gaussian elimination with partial pivoting on a small system; info /= 0 if singular.
  pure subroutine solve_small(a, b, x, info)
    real(wp), intent(inout) :: a(:, :), b(:)
    real(wp), intent(out) :: x(:)
    integer, intent(out) :: info
    integer :: n, i, j, piv
    real(wp) :: t, rowt(size(a, 2))
    n = size(b)
    info = 0
    x = 0.0_wp
    do i = 1, n
      piv = i - 1 + maxloc(abs(a(i:n, i)), 1)
      if (a(piv, i) == 0.0_wp) then
        info = 1
        return
      end if
      if (piv /= i) then
        rowt = a(i, :); a(i, :) = a(piv, :); a(piv, :) = rowt
        t = b(i); b(i) = b(piv); b(piv) = t
      end if
      do j = i + 1, n
        t = a(j, i) / a(i, i)
        a(j, i:n) = a(j, i:n) - t * a(i, i:n)
        b(j) = b(j) - t * b(i)
      end do
    end do
    do i = n, 1, -1
      x(i) = (b(i) - sum(a(i, i + 1:n) * x(i + 1:n))) / a(i, i)
    end do
  end subroutine solve_small

  !> Project every contact's reaction on its cone K = {|r_T| <= mu r_n}.
  subroutine project_all(p, r)
    type(sdl_problem_t), intent(in) :: p
    real(wp), intent(inout) :: r(:, :)
    integer :: a
    real(wp) :: nt, pn, mu
    do a = 1, p%nc
      mu = p%mu(a)
      if (p%dim == 2) then
        nt = abs(r(2, a))
      else
        nt = sqrt(r(2, a)**2 + r(3, a)**2)
      end if
      if (mu * nt <= -r(1, a)) then
        r(:, a) = 0.0_wp
      else if (nt > mu * r(1, a)) then
        pn = (mu * nt + r(1, a)) / (1.0_wp + mu**2)
        r(2:, a) = mu * pn * r(2:, a) / nt
        r(1, a) = pn
      end if
    end do
  end subroutine project_all

  !> LMGC90's normalised norms from the sums of a check sweep (the scene NLGS's
  !> procedure; the velocity scale is the RMS of q over the contacts). finite:
  !> the sums hold no NaN or Inf.
  logical function lmgc_converged(p, s, sums, maxes, rep, finite) result(conv)
    type(sdl_problem_t), intent(in) :: p
    type(sdl_settings_t), intent(in) :: s
    real(wp), intent(in) :: sums(6), maxes(2)
    type(sdl_report_t), intent(inout) :: rep
    logical, intent(out) :: finite
    type(lmgc_norms_t) :: nrm
    call lmgc_norms(s%check, s%tol, sums, maxes, p%norm_q / sqrt(real(max(p%nc, 1), wp)), nrm, conv)
    finite = nrm%finite
    rep%quad_dv = nrm%quad_dv; rep%maxm_dv = nrm%maxm_dv; rep%quad_dvr = nrm%quad_dvr
    rep%maxm_dvr = nrm%maxm_dvr; rep%mean_dvor = nrm%mean_dvor
  end function lmgc_converged

  !> One 2D sweep. est: accumulate in fsum each contact's |F|^2 before its update; lmgc: LMGC90 sums.
  subroutine sweep_2d(p, order, relax, r, est, lmgc, fsum, sums, maxes)
    type(sdl_problem_t), intent(in) :: p
    integer, intent(in) :: order(:)
    real(wp), intent(in) :: relax
    real(wp), intent(inout) :: r(:, :)
    logical, intent(in) :: est, lmgc
    real(wp), intent(out) :: fsum, sums(6), maxes(2)
    integer :: ii, a, e, b, st
    real(wp) :: sn, stg, rn0, rt0, rn, rt, un, ut
    fsum = 0.0_wp; sums = 0.0_wp; maxes = 0.0_wp
    do ii = 1, size(order)
      a = order(ii)
      sn = p%q(1, a); stg = p%q(2, a)
      do e = p%bptr(a), p%bptr(a + 1) - 1
        b = p%bcol(e)
        sn = sn + p%bval(1, e) * r(1, b) + p%bval(3, e) * r(2, b)
        stg = stg + p%bval(2, e) * r(1, b) + p%bval(4, e) * r(2, b)
      end do
      rn0 = r(1, a); rt0 = r(2, a)
      if (est) then
        un = sn + p%wd(1, a) * rn0 + p%wd(3, a) * rt0
        ut = stg + p%wd(2, a) * rn0 + p%wd(4, a) * rt0
        fsum = fsum + natural_map_2d(ut, un, rt0, rn0, p%mu(a))
      end if
      call coulomb_2d_inv(stg, sn, p%wdi(:, a), p%mu(a), rt, rn, st)
      if (relax /= 1.0_wp) then
        rt = relax * rt + (1.0_wp - relax) * rt0
        rn = relax * rn + (1.0_wp - relax) * rn0
      end if
      r(1, a) = rn; r(2, a) = rt
      if (lmgc) call lmgc_add_sums(2, p%wd(:, a), [rn0, rt0], [rn, rt], sums, maxes)
    end do
  end subroutine sweep_2d

  !> One 3D sweep (see sweep_2d); nfail counts local solves without an exact answer.
  subroutine sweep_3d(p, order, relax, r, est, lmgc, fsum, sums, maxes, nfail)
    type(sdl_problem_t), intent(in) :: p
    integer, intent(in) :: order(:)
    real(wp), intent(in) :: relax
    real(wp), intent(inout) :: r(:, :)
    logical, intent(in) :: est, lmgc
    real(wp), intent(out) :: fsum, sums(6), maxes(2)
    integer, intent(out) :: nfail
    integer :: ii, a, e, b, st
    real(wp) :: s(3), r0(3), r1(3), u(3), x1, x2, x3
    fsum = 0.0_wp; sums = 0.0_wp; maxes = 0.0_wp
    nfail = 0
    do ii = 1, size(order)
      a = order(ii)
      s = p%q(:, a)
      do e = p%bptr(a), p%bptr(a + 1) - 1
        b = p%bcol(e)
        x1 = r(1, b); x2 = r(2, b); x3 = r(3, b)
        s(1) = s(1) + p%bval(1, e) * x1 + p%bval(4, e) * x2 + p%bval(7, e) * x3
        s(2) = s(2) + p%bval(2, e) * x1 + p%bval(5, e) * x2 + p%bval(8, e) * x3
        s(3) = s(3) + p%bval(3, e) * x1 + p%bval(6, e) * x2 + p%bval(9, e) * x3
      end do
      r0 = r(:, a)
      if (est) then
        u(1) = s(1) + p%wd(1, a) * r0(1) + p%wd(4, a) * r0(2) + p%wd(7, a) * r0(3)
        u(2) = s(2) + p%wd(2, a) * r0(1) + p%wd(5, a) * r0(2) + p%wd(8, a) * r0(3)
        u(3) = s(3) + p%wd(3, a) * r0(1) + p%wd(6, a) * r0(2) + p%wd(9, a) * r0(3)
        fsum = fsum + natural_map_3d(u, r0, p%mu(a))
      end if
      r1 = r0
      call coulomb_3d(s, p%wd(:, a), p%wdi(:, a), p%mu(a), r1, st)
      if (st < 0) nfail = nfail + 1
      if (relax /= 1.0_wp) r1 = relax * r1 + (1.0_wp - relax) * r0
      r(:, a) = r1
      if (lmgc) call lmgc_add_sums(3, p%wd(:, a), r0, r1, sums, maxes)
    end do
  end subroutine sweep_3d
end module fracas_sdl
