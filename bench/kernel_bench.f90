!> Kernel micro-benchmark: NLGS contact updates per second on one core, exchange
!> local–global mode, on lattices built in memory (reference/nscd_validation.md §4.2,
!> Appendix B):
!>   2D: triangular lattice of disks under gravity, bottom row fixed; the solver's own
!>       kernel gs_sweep_2d_packed (the scene NLGS calls it; no copy here), reported as
!>       scene_packed;
!>   3D: simple-cubic lattice of spheres under gravity, bottom layer fixed; a 3D
!>       exchange sweep with the exact local solver coulomb_3d.
!> Contacts are in lattice order ("ordered": neighbours close in memory) or randomly
!> permuted ("shuffled"), or in blocked colour order ("coloured", see colour_order).
!> Each figure is the best of 5 timed chunks (other jobs on the machine only slow
!> a chunk down). Prints one line per run, and with --csv FILE writes them.
!>   fracas-kernel-bench [--quick] [--csv FILE]
module kernel_bench_kernels
  use fracas_kinds, only: wp
  use fracas_local_solver, only: coulomb_3d
  implicit none
  private
  public :: gs3d

contains

  !> One 3D exchange sweep over sphere contacts. b(12, nb) = (v(3), w(3), 1/m,
  !> 1/I (isotropic), pad); frame(9, k) = (n, t1, t2) columns; lever(6, k) =
  !> contact point minus centre for the candidate (1:3) and antagonist (4:6);
  !> w(9, k) the Delassus block (order n, t1, t2), wi(9, k) its inverse.
  subroutine gs3d(order, body, frame, lever, w, wi, qs, mu, r, b)
    integer, intent(in) :: order(:), body(:, :)
    real(wp), intent(in) :: frame(:, :), lever(:, :), w(:, :), wi(:, :), qs(:, :), mu(:)
    real(wp), intent(inout) :: r(:, :), b(:, :)
    integer :: ii, k, a, o, st
    real(wp) :: va(3), vo(3), dv(3), f(9), la(3), lo(3), u(3), r0(3), r1(3), q(3), dr(3), p(3), ta(3), to(3)
    do ii = 1, size(order)
      k = order(ii)
      a = body(1, k); o = body(2, k)
      f = frame(:, k)
      la = lever(1:3, k); lo = lever(4:6, k)
      ! velocity of each body at the contact point: v + w x l
      va = b(1:3, a) + cross(b(4:6, a), la)
      vo = b(1:3, o) + cross(b(4:6, o), lo)
      dv = va - vo
      u(1) = f(1) * dv(1) + f(2) * dv(2) + f(3) * dv(3)
      u(2) = f(4) * dv(1) + f(5) * dv(2) + f(6) * dv(3)
      u(3) = f(7) * dv(1) + f(8) * dv(2) + f(9) * dv(3)
      r0 = r(:, k)
      q(1) = u(1) - (w(1, k) * r0(1) + w(4, k) * r0(2) + w(7, k) * r0(3)) + qs(1, k)
      q(2) = u(2) - (w(2, k) * r0(1) + w(5, k) * r0(2) + w(8, k) * r0(3)) + qs(2, k)
      q(3) = u(3) - (w(3, k) * r0(1) + w(6, k) * r0(2) + w(9, k) * r0(3)) + qs(3, k)
      r1 = r0
      call coulomb_3d(q, w(:, k), wi(:, k), mu(k), r1, st)
      r(:, k) = r1
      dr = r1 - r0
      p = f(1:3) * dr(1) + f(4:6) * dr(2) + f(7:9) * dr(3)
      ta = cross(la, p)
      to = cross(lo, p)
      b(1:3, a) = b(1:3, a) + b(7, a) * p
      b(4:6, a) = b(4:6, a) + b(8, a) * ta
      b(1:3, o) = b(1:3, o) - b(7, o) * p
      b(4:6, o) = b(4:6, o) - b(8, o) * to
    end do
  end subroutine gs3d

  pure function cross(x, y) result(z)
    real(wp), intent(in) :: x(3), y(3)
    real(wp) :: z(3)
    z = [x(2) * y(3) - x(3) * y(2), x(3) * y(1) - x(1) * y(3), x(1) * y(2) - x(2) * y(1)]
  end function cross
end module kernel_bench_kernels

program kernel_bench
  use, intrinsic :: iso_fortran_env, only: output_unit, int64
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal
  use fracas_random, only: rng_t, rng_seed, rng_permute
  use fracas_local_solver, only: gs_sweep_2d_packed, pk_size, inverse_block, inverse_block_3d
  use fracas_contact_laws, only: coh_size
  use fracas_ids, only: st_stick, st_slifw, st_slibw, st_noctc
  use kernel_bench_kernels, only: gs3d
  implicit none
  character(len=256) :: arg, csv
  integer :: i, u, n2d(4), n3d(4), nsz
  integer, parameter :: nrep = 5
  logical :: quick, to_csv
  quick = .false.
  csv = ''
  i = 0
  do while (i < command_argument_count())
    i = i + 1
    call get_command_argument(i, arg)
    select case (trim(arg))
    case ('--quick')
      quick = .true.
    case ('--csv')
      i = i + 1
      call get_command_argument(i, csv)
    case default
      call fatal('usage: fracas-kernel-bench [--quick] [--csv FILE]')
    end select
  end do
  ! contacts ~ 3 per body in both lattices
  n2d = [1000, 10000, 100000, 1000000]
  n3d = [1000, 10000, 100000, 400000]
  nsz = merge(2, 4, quick)
  u = -1
  to_csv = len_trim(csv) > 0
  if (to_csv) then
    open (newunit=u, file=trim(csv), status='replace', action='write')
    write (u, '(a)') 'dim,kernel,order,bodies,contacts,sweeps,seconds,ns_per_update,updates_per_s,data_mb'
  end if
  write (output_unit, '(a)') 'dim kernel        order     bodies   contacts  sweeps   ns/update  updates/s  data(MB)'
  do i = 1, nsz
    call bench_2d(n2d(i))
  end do
  do i = 1, nsz
    call bench_3d(n3d(i))
  end do
  if (to_csv) close (u)

contains

  subroutine push(body, nc, i1, i2)
    integer, intent(inout) :: body(:, :), nc
    integer, intent(in) :: i1, i2
    nc = nc + 1
    body(:, nc) = [i1, i2]
  end subroutine push

  subroutine reset_v2(v, im, vy)
    real(wp), intent(inout) :: v(:, :)
    real(wp), intent(in) :: im(:, :), vy
    integer :: q
    do q = 1, size(v, 2)
      v(:, q) = 0.0_wp
      if (im(1, q) /= 0.0_wp) v(2, q) = -vy
    end do
  end subroutine reset_v2

  !> "Blocked colour" order: greedy colours of the contacts in stored order (two
  !> contacts sharing a body never share a colour), then, block by block of
  !> nblk stored contacts, the contacts sorted by colour. Consecutive updates
  !> then touch different bodies (no store-to-load chain through a body's
  !> velocity) while a block stays in cache.
  subroutine colour_order(body, nb, nblk, order)
    integer, intent(in) :: body(:, :), nb, nblk
    integer, intent(out) :: order(:)
    integer, allocatable :: used(:), col(:)
    integer :: k, c, nc, k0, k1, j, ncol
    nc = size(order)
    allocate (used(nb), col(nc))
    used = 0
    do k = 1, nc
      c = 0
      do while (btest(ior(used(body(1, k)), used(body(2, k))), c))
        c = c + 1
      end do
      col(k) = c
      used(body(1, k)) = ibset(used(body(1, k)), c)
      used(body(2, k)) = ibset(used(body(2, k)), c)
    end do
    ncol = maxval(col) + 1
    j = 0
    do k0 = 1, nc, nblk
      k1 = min(nc, k0 + nblk - 1)
      do c = 0, ncol - 1
        do k = k0, k1
          if (col(k) == c) then
            j = j + 1
            order(j) = k
          end if
        end do
      end do
    end do
  end subroutine colour_order

  real(wp) function now()
    integer(int64) :: c, rate
    call system_clock(c, rate)
    now = real(c, wp) / real(rate, wp)
  end function now

  subroutine report(dim, kernel, order, nb, nc, nsw, sec, mb)
    integer, intent(in) :: dim, nb, nc, nsw
    character(len=*), intent(in) :: kernel, order
    real(wp), intent(in) :: sec, mb
    real(wp) :: ns, ups
    ns = sec / (real(nc, wp) * nsw) * 1.0e9_wp
    ups = real(nc, wp) * nsw / sec
    write (output_unit, '(i2,1x,a12,1x,a9,i9,i11,i8,f12.2,es11.3,f10.1)') dim, kernel, order, nb, nc, nsw, ns, ups, mb
    if (to_csv) write (u, '(i0,a,a,a,a,a,i0,a,i0,a,i0,a,es12.5,a,f0.3,a,es12.5,a,f0.2)') dim, ',', trim(kernel), &
      ',', trim(order), ',', nb, ',', nc, ',', nsw, ',', sec, ',', ns, ',', ups, ',', mb
  end subroutine report

  !> Sweeps per timed chunk (the best of nrep chunks is kept, against other
  !> load on the machine): about 6e6 updates ordered, 6e5 shuffled (at least 1).
  integer function sweeps_for(nc, shuffled)
    integer, intent(in) :: nc
    logical, intent(in) :: shuffled
    sweeps_for = max(1, nint(merge(6.0e5_wp, 6.0e6_wp, shuffled) / nc))
    if (quick) sweeps_for = max(2, sweeps_for / 10)
  end function sweeps_for

  !> Triangular lattice of nx x ny disks (radius 1, touching), row 1 fixed, gravity.
  subroutine bench_2d(target_contacts)
    integer, intent(in) :: target_contacts
    integer :: nx, ny, nb, nc, ix, iy, k, a, o, j, nsw, pass, kk
    integer, allocatable :: body(:, :), order(:), bod(:, :)
    real(wp), allocatable :: x(:, :), v(:, :), im(:, :), geo(:, :), w(:, :), wi(:, :), shift(:, :), mu(:)
    real(wp), allocatable :: bb(:, :), rr(:, :), coh(:, :), pcr(:, :)
    integer, allocatable :: picoh(:), pst(:)
    real(wp) :: rad, h, g, n1, n2, ht(3), hn(3), gt(3), gn(3), t0, sums(6), maxes(2), best
    integer :: rep
    type(rng_t) :: rng
    logical :: shuffled
    character(len=8) :: oname
    rad = 1.0_wp; h = 1.0e-3_wp; g = 9.81_wp
    nx = max(4, nint(sqrt(target_contacts / 3.0_wp)))
    ny = max(4, nint(real(target_contacts, wp) / (3.0_wp * nx)))
    nb = nx * ny
    allocate (x(2, nb), v(3, nb), im(3, nb))
    do iy = 1, ny
      do ix = 1, nx
        k = ix + (iy - 1) * nx
        x(1, k) = 2.0_wp * rad * (ix - 1) + merge(rad, 0.0_wp, mod(iy, 2) == 0)
        x(2, k) = sqrt(3.0_wp) * rad * (iy - 1)
        im(:, k) = [1.0_wp, 1.0_wp, 2.0_wp] / [1.0_wp, 1.0_wp, rad**2]   ! m = 1, I = m r^2 / 2
        if (iy == 1) im(:, k) = 0.0_wp
        v(:, k) = [0.0_wp, -g * h, 0.0_wp]
        if (iy == 1) v(:, k) = 0.0_wp
      end do
    end do
    ! contacts: right neighbour and the two upper neighbours, in body order
    allocate (body(2, 3 * nb))
    nc = 0
    do iy = 1, ny
      do ix = 1, nx
        k = ix + (iy - 1) * nx
        if (ix < nx .and. iy > 1) call push(body, nc, k + 1, k)   ! no contact between two fixed disks
        if (iy < ny) then
          if (mod(iy, 2) == 1) then
            if (ix > 1) call push(body, nc, k + nx - 1, k)
            call push(body, nc, k + nx, k)
          else
            call push(body, nc, k + nx, k)
            if (ix < nx) call push(body, nc, k + nx + 1, k)
          end if
        end if
      end do
    end do
    allocate (geo(6, nc), w(4, nc), wi(6, nc), shift(2, nc), mu(nc), order(nc))
    do k = 1, nc
      a = body(1, k); o = body(2, k)
      n1 = (x(1, a) - x(1, o)) / (2.0_wp * rad); n2 = (x(2, a) - x(2, o)) / (2.0_wp * rad)
      geo(:, k) = [n1, n2, rad, 0.0_wp, -rad, 0.0_wp]
      ht = [n2, -n1, geo(3, k)]; hn = [n1, n2, geo(4, k)]
      gt = [n2, -n1, geo(5, k)]; gn = [n1, n2, geo(6, k)]
      w(1, k) = sum(im(:, a) * ht * ht) + sum(im(:, o) * gt * gt)
      w(2, k) = sum(im(:, a) * ht * hn) + sum(im(:, o) * gt * gn)
      w(3, k) = w(2, k)
      w(4, k) = sum(im(:, a) * hn * hn) + sum(im(:, o) * gn * gn)
      mu(k) = 0.3_wp
      wi(:, k) = inverse_block(w(1, k), w(2, k), w(3, k), w(4, k), mu(k))
      shift(:, k) = 0.0_wp
    end do
    allocate (coh(coh_size(2), 1))
    coh = 0.0_wp
    allocate (bb(6, nb), rr(2, nc), bod(2, nc), pcr(pk_size, nc), picoh(nc), pst(nc))
    picoh = 0
    call rng_seed(rng, 42)
    do pass = 1, 3
      shuffled = pass == 3
      order = [(j, j=1, nc)]
      if (pass == 2) call colour_order(body(:, 1:nc), nb, 256, order)
      if (shuffled) call rng_permute(rng, order)
      oname = trim(merge('ordered ', 'coloured', pass == 1))
      if (shuffled) oname = 'shuffled'
      nsw = sweeps_for(nc, shuffled)
      ! the solver's kernel on its packed records, contacts in sweep order
      do kk = 1, nc
        k = order(kk)
        bod(:, kk) = body(:, k)
        pcr(:, kk) = [geo(:, k), w(:, k), wi(:, k), shift(:, k), mu(k), 0.0_wp]
      end do
      rr = 0.0_wp
      call reset_v2(v, im, g * h)
      bb(1:3, :) = v; bb(4:6, :) = im
      call gs_sweep_2d_packed(nc, bod, pcr, picoh, .false., coh, rr, pst, bb, 1.0_wp, .true., sums, maxes)
      if (pass == 1) write (output_unit, '(a,3(i0,a),es10.3)') '#  statuses after a check sweep: ', &
        count(pst == st_stick), ' stick, ', count(pst == st_slifw .or. pst == st_slibw), ' slide, ', &
        count(pst == st_noctc), ' open; max |r| ', maxval(abs(rr))
      best = huge(1.0_wp)
      do rep = 1, nrep
        t0 = now()
        do j = 1, nsw
          call gs_sweep_2d_packed(nc, bod, pcr, picoh, .false., coh, rr, pst, bb, 1.0_wp, .false., sums, maxes)
        end do
        best = min(best, now() - t0)
      end do
      call report(2, 'scene_packed', oname, nb, nc, nsw, best, &
                  real(nc, wp) * (4 + 8 + 8 * (pk_size + 2)) / 1.0e6_wp + real(nb, wp) * 48 / 1.0e6_wp)
    end do

  end subroutine bench_2d

  !> Simple-cubic lattice of spheres (radius 1, touching), bottom layer fixed, gravity.
  subroutine bench_3d(target_contacts)
    integer, intent(in) :: target_contacts
    integer :: nl, nb, nc, ix, iy, iz, k, a, o, j, nsw, pass, d
    integer, allocatable :: body(:, :), order(:)
    real(wp), allocatable :: x(:, :), b(:, :), frame(:, :), lever(:, :), w(:, :), wi(:, :), qs(:, :), mu(:), r(:, :)
    real(wp) :: rad, h, g, nv(3), t1(3), t2(3), hm(3, 3), t0, mb, ima, imo, iia, iio, best
    integer :: rep
    type(rng_t) :: rng
    logical :: shuffled
    character(len=8) :: oname
    rad = 1.0_wp; h = 1.0e-3_wp; g = 9.81_wp
    nl = max(3, nint((target_contacts / 3.0_wp)**(1.0_wp / 3.0_wp)))
    nb = nl**3
    allocate (x(3, nb), b(12, nb))
    b = 0.0_wp
    do iz = 1, nl
      do iy = 1, nl
        do ix = 1, nl
          k = ix + (iy - 1) * nl + (iz - 1) * nl * nl
          x(:, k) = 2.0_wp * rad * [ix - 1, iy - 1, iz - 1]
          b(7, k) = 1.0_wp; b(8, k) = 2.5_wp / rad**2   ! m = 1, I = 2/5 m r^2
          if (iz == 1) b(7:8, k) = 0.0_wp
        end do
      end do
    end do
    allocate (body(2, 3 * nb))
    nc = 0
    do iz = 1, nl
      do iy = 1, nl
        do ix = 1, nl
          k = ix + (iy - 1) * nl + (iz - 1) * nl * nl
          if (ix < nl .and. iz > 1) call push(body, nc, k + 1, k)   ! no contact between two fixed spheres
          if (iy < nl .and. iz > 1) call push(body, nc, k + nl, k)
          if (iz < nl) call push(body, nc, k + nl * nl, k)
        end do
      end do
    end do
    allocate (frame(9, nc), lever(6, nc), w(9, nc), wi(9, nc), qs(3, nc), mu(nc), r(3, nc), order(nc))
    do k = 1, nc
      a = body(1, k); o = body(2, k)
      nv = (x(:, a) - x(:, o)) / (2.0_wp * rad)
      if (abs(nv(1)) < 0.9_wp) then
        t1 = [0.0_wp, nv(3), -nv(2)]
      else
        t1 = [-nv(3), 0.0_wp, nv(1)]
      end if
      t1 = t1 / norm2(t1)
      t2 = [nv(2) * t1(3) - nv(3) * t1(2), nv(3) * t1(1) - nv(1) * t1(3), nv(1) * t1(2) - nv(2) * t1(1)]
      frame(:, k) = [nv, t1, t2]
      lever(:, k) = [-rad * nv, rad * nv]
      ! W = H^T M^-1 H: for a sphere, the lever is along n, so rotation acts on t only
      hm(:, 1) = nv; hm(:, 2) = t1; hm(:, 3) = t2
      ima = b(7, a); imo = b(7, o); iia = b(8, a); iio = b(8, o)
      w(:, k) = 0.0_wp
      do d = 1, 3
        w(d + 3 * (d - 1), k) = ima + imo + merge(0.0_wp, (iia + iio) * rad**2, d == 1)
      end do
      wi(:, k) = inverse_block_3d(w(:, k))
      mu(k) = 0.3_wp
      qs(:, k) = 0.0_wp
    end do
    mb = real(nc, wp) * (8 + 8 * (9 + 6 + 9 + 9 + 3 + 1 + 3) + 4) / 1.0e6_wp + real(nb, wp) * 96 / 1.0e6_wp
    call rng_seed(rng, 42)
    do pass = 1, 3
      shuffled = pass == 3
      order = [(j, j=1, nc)]
      if (pass == 2) call colour_order(body(:, 1:nc), nb, 256, order)
      if (shuffled) call rng_permute(rng, order)
      oname = trim(merge('ordered ', 'coloured', pass == 1))
      if (shuffled) oname = 'shuffled'
      nsw = max(1, sweeps_for(nc, shuffled) / 4)
      r = 0.0_wp
      b(1:6, :) = 0.0_wp
      where (b(7, :) > 0.0_wp) b(3, :) = -g * h
      call gs3d(order, body, frame, lever, w, wi, qs, mu, r, b)
      best = huge(1.0_wp)
      do rep = 1, nrep
        t0 = now()
        do j = 1, nsw
          call gs3d(order, body, frame, lever, w, wi, qs, mu, r, b)
        end do
        best = min(best, now() - t0)
      end do
      call report(3, 'gs3d', oname, nb, nc, nsw, best, mb)
    end do

  end subroutine bench_3d
end program kernel_bench
