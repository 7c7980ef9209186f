!> The exact 2D local Signorini–Coulomb solver and the FCLib natural map. Pure
!> procedures on one contact: shared by the scene NLGS and the FCLib tools.
module fracas_local_solver
  use fracas_kinds, only: wp
  use fracas_ids, only: st_noctc, st_stick, st_slifw, st_slibw
  implicit none
  private
  public :: coulomb_2d, coulomb_2d_inv, inverse_block, natural_map_2d, gs_sweep_2d

contains

  !> Solve u = uf + W r, Signorini (un >= 0, rn >= 0, un rn = 0) and Coulomb
  !> (|rt| <= mu rn, sliding opposite to ut) on one contact, by enumeration of
  !> the four cases (no contact, stick, slide forward, slide backward).
  !> W = [wtt wtn; wnt wnn] must be positive definite.
  pure subroutine coulomb_2d(uft, ufn, wtt, wtn, wnt, wnn, mu, rt, rn, status)
    real(wp), intent(in) :: uft, ufn, wtt, wtn, wnt, wnn, mu
    real(wp), intent(out) :: rt, rn
    integer, intent(out) :: status
    call coulomb_2d_inv(uft, ufn, inverse_block(wtt, wtn, wnt, wnn, mu), mu, rt, rn, status)
  end subroutine coulomb_2d

  !> What the local solver needs of W, computed once per contact and step:
  !> W^-1 (tt, tn, nt, nn), 1/(wnn - mu wnt) and 1/(wnn + mu wnt) (sliding forward
  !> and backward), so that a sweep does no division.
  pure function inverse_block(wtt, wtn, wnt, wnn, mu) result(wi)
    real(wp), intent(in) :: wtt, wtn, wnt, wnn, mu
    real(wp) :: wi(6), det
    det = wtt * wnn - wtn * wnt
    wi(1) = wnn / det
    wi(2) = -wtn / det
    wi(3) = -wnt / det
    wi(4) = wtt / det
    wi(5) = 1.0_wp / (wnn - mu * wnt)
    wi(6) = 1.0_wp / (wnn + mu * wnt)
  end function inverse_block

  !> The enumerative local solver on precomputed inverses wi (see inverse_block).
  pure subroutine coulomb_2d_inv(uft, ufn, wi, mu, rt, rn, status)
    real(wp), intent(in) :: uft, ufn, wi(6), mu
    real(wp), intent(out) :: rt, rn
    integer, intent(out) :: status
    real(wp) :: pt, pn
    if (ufn >= 0.0_wp) then
      rt = 0.0_wp; rn = 0.0_wp
      status = st_noctc
      return
    end if
    ! Sticking reaction: W r = -uf.
    pt = -(wi(1) * uft + wi(2) * ufn)
    pn = -(wi(3) * uft + wi(4) * ufn)
    if (pt + mu * pn < 0.0_wp) then
      ! slides with ut > 0: rt = -mu rn, un = ufn + (wnn - mu wnt) rn = 0
      rn = -ufn * wi(5)
      rt = -mu * rn
      status = st_slifw
    else if (pt - mu * pn > 0.0_wp) then
      rn = -ufn * wi(6)
      rt = mu * rn
      status = st_slibw
    else
      rt = pt; rn = pn
      status = st_stick
    end if
  end subroutine coulomb_2d_inv

  !> FCLib natural map of one 2D contact: F = r - P_K(r - u~), with the
  !> De Saxcé shift u~n = un + mu |ut| and K = {|xt| <= mu xn}. Returns |F|^2.
  pure real(wp) function natural_map_2d(ut, un, rt, rn, mu) result(f2)
    real(wp), intent(in) :: ut, un, rt, rn, mu
    real(wp) :: xt, xn, pt, pn, at
    xt = rt - ut
    xn = rn - (un + mu * abs(ut))
    at = abs(xt)
    if (mu * at <= -xn) then
      pt = 0.0_wp; pn = 0.0_wp
    else if (at <= mu * xn) then
      pt = xt; pn = xn
    else
      pn = (mu * at + xn) / (1.0_wp + mu**2)
      pt = mu * pn * sign(1.0_wp, xt)
    end if
    f2 = (rt - pt)**2 + (rn - pn)**2
  end function natural_map_2d

  !> One nonlinear Gauss–Seidel sweep over 2D rigid contacts, exchanging with
  !> the body velocities v (3,nb) after each contact (the hot loop of NLGS).
  !> body(1:2,k): candidate and antagonist bodies; geo(1:6,k): n1, n2 and the
  !> lever arms (cd t, cd n, an t, an n); w(4,k) the Delassus block (tt, tn, nt,
  !> nn) and wi(6,k) its inverse_block; shift(2,k) the law shift; r(2,k)
  !> impulses, updated in place.
  !> With check, the sums of LMGC90's norms are returned: sums(1) sum du^2,
  !> (2) sum du^2 |rbar|^2, (3) sum rbar.du, (4) sum W r.r, (5) sum |W r|^2,
  !> (6) contacts with rbar /= 0; maxes(1) max du^2, (2) max du^2 |rbar|^2.
  subroutine gs_sweep_2d(order, active, body, geo, w, wi, shift, mu, r, status, v, inv_mass, relax, check, &
                         sums, maxes)
    integer, intent(in), contiguous :: order(:), body(:, :)
    logical, intent(in), contiguous :: active(:)
    logical, intent(in) :: check
    real(wp), intent(in), contiguous :: geo(:, :), w(:, :), wi(:, :), shift(:, :), mu(:), inv_mass(:, :)
    real(wp), intent(in) :: relax
    real(wp), intent(inout), contiguous :: r(:, :), v(:, :)
    integer, intent(inout), contiguous :: status(:)
    real(wp), intent(out) :: sums(6), maxes(2)
    integer :: ii, k, a, o, st
    real(wp) :: n1, n2, l1, l2, l3, l4, wtt, wtn, wnt, wnn, dvx, dvy, ut, un, rt0, rn0, rt, rn
    real(wp) :: uft, ufn, drt, drn, px, py, dut, dun, du2, rbt, rbn, rb2
    sums = 0.0_wp
    maxes = 0.0_wp
    do ii = 1, size(order)
      k = order(ii)
      if (.not. active(k)) cycle
      a = body(1, k); o = body(2, k)
      n1 = geo(1, k); n2 = geo(2, k)
      l1 = geo(3, k); l2 = geo(4, k); l3 = geo(5, k); l4 = geo(6, k)
      wtt = w(1, k); wtn = w(2, k); wnt = w(3, k); wnn = w(4, k)
      dvx = v(1, a) - v(1, o)
      dvy = v(2, a) - v(2, o)
      ut = dvx * n2 - dvy * n1 + v(3, a) * l1 - v(3, o) * l3
      un = dvx * n1 + dvy * n2 + v(3, a) * l2 - v(3, o) * l4
      rt0 = r(1, k); rn0 = r(2, k)
      uft = ut - (wtt * rt0 + wtn * rn0) + shift(1, k)
      ufn = un - (wnt * rt0 + wnn * rn0) + shift(2, k)
      call coulomb_2d_inv(uft, ufn, wi(:, k), mu(k), rt, rn, st)
      status(k) = st
      if (check) then
        ! du = W (r_old - r_new), rbar = mean reaction (LMGC90's check quantities)
        dut = wtt * (rt0 - rt) + wtn * (rn0 - rn)
        dun = wnt * (rt0 - rt) + wnn * (rn0 - rn)
        rbt = 0.5_wp * (rt0 + rt); rbn = 0.5_wp * (rn0 + rn)
        if (rbt /= 0.0_wp .or. rbn /= 0.0_wp) then
          du2 = dut**2 + dun**2
          rb2 = rbt**2 + rbn**2
          sums(1) = sums(1) + du2
          sums(2) = sums(2) + du2 * rb2
          sums(3) = sums(3) + rbt * dut + rbn * dun
          sums(4) = sums(4) + 0.5_wp * ((wtt * rt0 + wtn * rn0) * rt0 + (wnt * rt0 + wnn * rn0) * rn0 + &
                                        (wtt * rt + wtn * rn) * rt + (wnt * rt + wnn * rn) * rn)
          sums(5) = sums(5) + 0.5_wp * ((wtt * rt0 + wtn * rn0)**2 + (wnt * rt0 + wnn * rn0)**2 + &
                                        (wtt * rt + wtn * rn)**2 + (wnt * rt + wnn * rn)**2)
          sums(6) = sums(6) + 1.0_wp
          maxes(1) = max(maxes(1), du2)
          maxes(2) = max(maxes(2), du2 * rb2)
        end if
      end if
      if (relax /= 1.0_wp) then
        rt = relax * rt + (1.0_wp - relax) * rt0
        rn = relax * rn + (1.0_wp - relax) * rn0
      end if
      r(1, k) = rt; r(2, k) = rn
      drt = rt - rt0; drn = rn - rn0
      if (drt == 0.0_wp .and. drn == 0.0_wp) cycle
      px = drt * n2 + drn * n1
      py = -drt * n1 + drn * n2
      v(1, a) = v(1, a) + inv_mass(1, a) * px
      v(2, a) = v(2, a) + inv_mass(2, a) * py
      v(3, a) = v(3, a) + inv_mass(3, a) * (drt * l1 + drn * l2)
      v(1, o) = v(1, o) - inv_mass(1, o) * px
      v(2, o) = v(2, o) - inv_mass(2, o) * py
      v(3, o) = v(3, o) - inv_mass(3, o) * (drt * l3 + drn * l4)
    end do
  end subroutine gs_sweep_2d
end module fracas_local_solver
