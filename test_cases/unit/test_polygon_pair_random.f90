!> Random convex polygon pairs: whenever their true clearance (the smallest
!> vertex-to-edge distance, both ways) is within the alert distance, the pair
!> must give at least one contact, and the smallest gap reported must not
!> exceed the alert. Separated pairs must not report a negative gap.
!> Reference: the brute-force distance between the two boundaries.
program test_polygon_pair_random
  use fracas_kinds, only: wp
  use fracas_plplx, only: polygon_pair, polygon_contact_t
  use fracas_random, only: rng_t, rng_seed, rng_below
  use fracas_testing, only: check_close, test_finish
  implicit none
  type(rng_t) :: rng
  type(polygon_contact_t) :: pc
  real(wp), allocatable :: a(:, :), b(:, :), bb(:, :)
  real(wp) :: alert, dist, ang, target, lo, hi, mid
  integer :: trial, missed, negative, tried, it
  real(wp), parameter :: pi = acos(-1.0_wp)

  call rng_seed(rng, 5)
  alert = 0.05_wp
  missed = 0; negative = 0; tried = 0
  do trial = 1, 5000
    a = random_polygon(3 + rng_below(rng, 5))
    b = random_polygon(3 + rng_below(rng, 5))
    ! Place b along a random direction at a clearance drawn in [0, alert], by
    ! bisection on the distance of the move.
    ang = 2.0_wp * pi * uniform()
    target = alert * uniform()
    lo = 0.0_wp; hi = 3.0_wp
    do it = 1, 60
      mid = 0.5_wp * (lo + hi)
      bb = b
      bb(1, :) = bb(1, :) + mid * cos(ang)
      bb(2, :) = bb(2, :) + mid * sin(ang)
      if (overlapping(a, bb)) then
        lo = mid
      else if (clearance(a, bb) < target) then
        lo = mid
      else
        hi = mid
      end if
    end do
    b(1, :) = b(1, :) + hi * cos(ang)
    b(2, :) = b(2, :) + hi * sin(ang)
    dist = clearance(a, b)
    if (dist > alert .or. overlapping(a, b)) cycle
    tried = tried + 1
    call polygon_pair(a, b, alert, .false., pc)
    if (pc%n == 0) then
      missed = missed + 1
    else if (minval(pc%gap(1:pc%n)) < -1e-12_wp) then
      negative = negative + 1
    end if
  end do
  write (*, '(a,i0,a)') 'separated pairs within the alert distance: ', tried, ' tried'
  call check_close('most placements tried', real(min(tried, 4000), wp), 4000.0_wp, 0.0_wp)
  call check_close('pairs within alert without a contact', real(missed, wp), 0.0_wp, 0.0_wp)
  call check_close('separated pairs reported overlapping', real(negative, wp), 0.0_wp, 0.0_wp)
  call test_finish()

contains

  real(wp) function uniform()
    uniform = real(rng_below(rng, 1000000), wp) / 1.0e6_wp
  end function uniform

  !> A convex polygon: sorted random angles on an ellipse of radii ~1.
  function random_polygon(n) result(p)
    integer, intent(in) :: n
    real(wp) :: p(2, n), th(n), rx, ry, rot, x, y, tmp
    integer :: i, j
    do i = 1, n
      th(i) = 2.0_wp * pi * uniform()
    end do
    do i = 2, n
      tmp = th(i); j = i - 1
      do while (j >= 1)
        if (th(j) <= tmp) exit
        th(j + 1) = th(j); j = j - 1
      end do
      th(j + 1) = tmp
    end do
    rx = 0.5_wp + 0.5_wp * uniform(); ry = 0.5_wp + 0.5_wp * uniform(); rot = 2.0_wp * pi * uniform()
    do i = 1, n
      x = rx * cos(th(i)); y = ry * sin(th(i))
      p(:, i) = [x * cos(rot) - y * sin(rot), x * sin(rot) + y * cos(rot)]
    end do
  end function random_polygon

  real(wp) function point_segment(q, p0, p1)
    real(wp), intent(in) :: q(2), p0(2), p1(2)
    real(wp) :: e(2), t
    e = p1 - p0
    t = max(0.0_wp, min(1.0_wp, dot_product(q - p0, e) / dot_product(e, e)))
    point_segment = norm2(q - (p0 + t * e))
  end function point_segment

  real(wp) function clearance(p, q)
    real(wp), intent(in) :: p(:, :), q(:, :)
    integer :: i, j
    clearance = huge(1.0_wp)
    do i = 1, size(p, 2)
      do j = 1, size(q, 2)
        clearance = min(clearance, point_segment(p(:, i), q(:, j), q(:, 1 + mod(j, size(q, 2)))))
      end do
    end do
    do i = 1, size(q, 2)
      do j = 1, size(p, 2)
        clearance = min(clearance, point_segment(q(:, i), p(:, j), p(:, 1 + mod(j, size(p, 2)))))
      end do
    end do
  end function clearance

  !> True if some vertex of one lies inside the other, or two edges cross
  !> (thin shapes can overlap with no vertex inside the other).
  logical function overlapping(p, q)
    real(wp), intent(in) :: p(:, :), q(:, :)
    integer :: i, j
    overlapping = any_inside(p, q) .or. any_inside(q, p)
    do i = 1, size(p, 2)
      do j = 1, size(q, 2)
        if (crossing(p(:, i), p(:, 1 + mod(i, size(p, 2))), q(:, j), q(:, 1 + mod(j, size(q, 2))))) &
          overlapping = .true.
      end do
    end do
  end function overlapping

  logical function crossing(p0, p1, q0, q1)
    real(wp), intent(in) :: p0(2), p1(2), q0(2), q1(2)
    crossing = side(p0, p1, q0) * side(p0, p1, q1) < 0.0_wp .and. side(q0, q1, p0) * side(q0, q1, p1) < 0.0_wp
  end function crossing

  real(wp) function side(a0, a1, x)
    real(wp), intent(in) :: a0(2), a1(2), x(2)
    side = (a1(1) - a0(1)) * (x(2) - a0(2)) - (a1(2) - a0(2)) * (x(1) - a0(1))
  end function side

  logical function any_inside(p, q)
    real(wp), intent(in) :: p(:, :), q(:, :)
    integer :: i, j
    logical :: inside
    real(wp) :: e(2)
    any_inside = .false.
    do i = 1, size(p, 2)
      inside = .true.
      do j = 1, size(q, 2)
        e = q(:, 1 + mod(j, size(q, 2))) - q(:, j)
        if (e(1) * (p(2, i) - q(2, j)) - e(2) * (p(1, i) - q(1, j)) < 0.0_wp) inside = .false.
      end do
      if (inside) any_inside = .true.
    end do
  end function any_inside
end program test_polygon_pair_random
