!> 3D broad-phase benchmark (not a test): time of broad3_pairs against the
!> number N of spheres (radii 0.5..1, a cube filled to a solid fraction of
!> about 0.3, alert 0.1), and of the O(N^2) loop broad3_brute up to 1e4.
!> Prints N, pairs, occupied cells, best of 3 times (s), time / N (us).
program broad3_bench
  use fracas_kinds, only: wp, i8
  use fracas_broad_3d, only: broad3_t, broad3_pairs, broad3_brute
  use fracas_random, only: rng_t, rng_seed, rng_below
  implicit none
  integer, parameter :: sizes(4) = [1000, 10000, 100000, 300000]
  type(rng_t) :: rng
  type(broad3_t) :: b
  real(wp), allocatable :: c(:, :), bound(:)
  integer, allocatable :: body(:)
  logical, allocatable :: big(:)
  real(wp) :: edge, t_grid, t_brute
  integer :: s, n, k
  call rng_seed(rng, 1)
  write (*, '(a)') '        N      pairs      cells    grid (s)  grid/N (us)   brute (s)'
  do s = 1, size(sizes)
    n = sizes(s)
    ! mean sphere volume 4/3 pi <r^3> (r uniform in 0.5..1: <r^3> = 0.46875) at fraction 0.3
    edge = (n * 4.0_wp / 3.0_wp * acos(-1.0_wp) * 0.46875_wp / 0.3_wp)**(1.0_wp / 3.0_wp)
    allocate (c(3, n), bound(n), body(n), big(n))
    do k = 1, n
      c(:, k) = edge * [uniform(), uniform(), uniform()]
      bound(k) = 0.5_wp + 0.5_wp * uniform()
      body(k) = k
    end do
    big = .false.
    t_grid = best_time(.false.)
    write (*, '(i9,2i11,es12.3,f13.3)', advance='no') n, b%npairs, b%ncells, t_grid, 1.0e6_wp * t_grid / n
    if (n <= 10000) then
      t_brute = best_time(.true.)
      write (*, '(es12.3)') t_brute
    else
      write (*, '(a)') '           -'
    end if
    deallocate (c, bound, body, big)
  end do

contains

  real(wp) function uniform()
    uniform = rng_below(rng, 1000000) / 1.0e6_wp
  end function uniform

  real(wp) function best_time(brute)
    logical, intent(in) :: brute
    integer(i8) :: t0, t1, rate
    integer :: rep
    best_time = huge(1.0_wp)
    do rep = 1, 3
      call system_clock(t0, rate)
      if (brute) then
        call broad3_brute(b, c, bound, body, 0.1_wp, big)
      else
        call broad3_pairs(b, c, bound, body, 0.1_wp, big)
      end if
      call system_clock(t1)
      best_time = min(best_time, real(t1 - t0, wp) / rate)
    end do
  end function best_time
end program broad3_bench
