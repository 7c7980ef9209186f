!> The exact 2D local Signorini–Coulomb solver and the FCLib natural map. Pure
!> procedures on one contact: shared by the scene NLGS and the FCLib tools.
module fracas_local_solver
  use fracas_kinds, only: wp
  use fracas_ids, only: st_noctc, st_stick, st_slifw, st_slibw
  implicit none
  private
  public :: coulomb_2d, natural_map_2d

contains

  !> Solve u = uf + W r, Signorini (un >= 0, rn >= 0, un rn = 0) and Coulomb
  !> (|rt| <= mu rn, sliding opposite to ut) on one contact, by enumeration of
  !> the four cases (no contact, stick, slide forward, slide backward).
  !> W = [wtt wtn; wnt wnn] must be positive definite.
  pure subroutine coulomb_2d(uft, ufn, wtt, wtn, wnt, wnn, mu, rt, rn, status)
    real(wp), intent(in) :: uft, ufn, wtt, wtn, wnt, wnn, mu
    real(wp), intent(out) :: rt, rn
    integer, intent(out) :: status
    real(wp) :: det, pt, pn, forward, backward
    if (ufn >= 0.0_wp) then
      rt = 0.0_wp; rn = 0.0_wp
      status = st_noctc
      return
    end if
    ! Sticking reaction: W r = -uf.
    det = wtt * wnn - wtn * wnt
    pt = -(wnn * uft - wtn * ufn) / det
    pn = -(wtt * ufn - wnt * uft) / det
    if (pt + mu * pn < 0.0_wp) then
      ! slides with ut > 0: rt = -mu rn, un = ufn + (wnn - mu wnt) rn = 0
      forward = wnn - mu * wnt
      rn = -ufn / forward
      rt = -mu * rn
      status = st_slifw
    else if (pt - mu * pn > 0.0_wp) then
      backward = wnn + mu * wnt
      rn = -ufn / backward
      rt = mu * rn
      status = st_slibw
    else
      rt = pt; rn = pn
      status = st_stick
    end if
  end subroutine coulomb_2d

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
end module fracas_local_solver
