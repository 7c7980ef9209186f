!> The exact 2D local Signorini–Coulomb solver and the FCLib natural map. Pure
!> procedures on one contact: shared by the scene NLGS and the FCLib tools.
module fracas_local_solver
  use fracas_kinds, only: wp
  use fracas_small_matrix, only: adjugate_3x3
  use fracas_ids, only: st_noctc, st_stick, st_slifw, st_slibw, bm_rigid, bm_mesh
  use fracas_contact_laws, only: coh_factor, coh_uend, coh_av, coh_k, coh_wprime
  use fracas_contacts, only: wi_size, mesh_side_nodes
  implicit none
  private
  public :: coulomb_2d, coulomb_2d_inv, inverse_block, natural_map_2d, gs_sweep_2d_packed, gs_sweep_mesh
  public :: pk_size

  !> Doubles per contact record of gs_sweep_2d_packed.
  integer, parameter :: pk_size = 20
  public :: coulomb_3d, inverse_block_3d, natural_map_3d

contains

  ! The map H of each body model's contact side and LMGC90's check sums, included
  ! so that the sweeps inline them (the same text as fracas_frame_2d,
  ! fracas_rbdy2_side, fracas_mailx_side and fracas_lmgc_norms).
  include '../shared/frame_2d.inc'
  include '../bodies/rbdy2_side.inc'
  include '../bodies/mailx_side.inc'
  include 'lmgc_sums.inc'

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
    real(wp) :: wi(wi_size(2)), det
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
    real(wp), intent(in) :: uft, ufn, wi(wi_size(2)), mu
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

  !> One nonlinear Gauss–Seidel sweep over 2D rigid contacts (the hot loop of the
  !> scene's NLGS), exchanging with the body velocities after each contact, on
  !> packed data:
  !>   cr(pk_size, n) one record per contact, in sweep order (only the contacts the
  !>     law leaves active): 1:2 n, 3:6 lever arms (cd t, cd n, an t, an n), 7:10 W
  !>     (tt, tn, nt, nn), 11:16 inverse_block of the W the local solver uses,
  !>     17:18 law shift, 19 mu, 20 unused; r(2, n) total impulses, updated in place;
  !>   cb(2, n) the two bodies as indices in bv; icoh(n) the column of coh of a
  !>     cohesive contact (0: none), any_coh: some is. A cohesive contact solves for
  !>     its contact part r_c with W' = A W and u~free' = A (u~free + W a), then
  !>     r = r_c + f (a + K u~) (coh(:,k): fracas_contact_laws, coh_size; f the
  !>     step's spring factor, see cohesive_step);
  !>   bv(6, *) one record per body: v (3) and the inverse mass (3);
  !>   r(2, n), status(n) in sweep order.
  !> With check, statuses are written and the norm sums accumulated: sums(1) sum
  !> du^2, (2) sum du^2 |rbar|^2, (3) sum rbar.du, (4) sum W r.r, (5) sum |W r|^2,
  !> (6) contacts with rbar /= 0; maxes(1) max du^2, (2) max du^2 |rbar|^2
  !> (fracas_lmgc_norms); with evaluate_only too, nothing is applied: LMGC90's
  !> check pass, every contact's local solution computed from the current state and
  !> compared with its current reaction. Sweeps without check and without cohesive
  !> contacts run a lean loop (sweep_plain, the local solver inlined).
  subroutine gs_sweep_2d_packed(n, cb, cr, icoh, any_coh, coh, r, status, bv, relax, check, sums, maxes, evaluate_only)
    integer, intent(in) :: n
    integer, intent(in) :: cb(2, n), icoh(n)
    real(wp), intent(in) :: cr(pk_size, n)
    logical, intent(in) :: any_coh
    !> check passes keep u~ of cohesive contacts (coh_uend); (coh_size(2), *) explicit
    !> cost 0.26 % more instructions in gs_sweep_mesh than this (callgrind, mesh_exploded_beam)
    real(wp), intent(inout), contiguous :: coh(:, :)
    real(wp), intent(inout) :: r(2, n), bv(6, *)
    integer, intent(inout) :: status(n)
    real(wp), intent(in) :: relax
    logical, intent(in) :: check
    real(wp), intent(out) :: sums(6), maxes(2)
    logical, intent(in), optional :: evaluate_only
    logical :: evaluate
    evaluate = .false.
    if (present(evaluate_only)) evaluate = evaluate_only
    if (check .or. any_coh) then
      call sweep_general(n, cb, cr, icoh, coh, r, status, bv, relax, check, sums, maxes, evaluate)
    else
      sums = 0.0_wp
      maxes = 0.0_wp
      call sweep_plain(n, cb, cr, r, bv, relax)
    end if
  end subroutine gs_sweep_2d_packed

  !> The hot loop: no cohesive contact, no statuses, no norm sums.
  subroutine sweep_plain(n, cb, cr, r, bv, relax)
    integer, intent(in) :: n
    integer, intent(in) :: cb(2, n)
    real(wp), intent(in) :: cr(pk_size, n)
    real(wp), intent(inout) :: r(2, n), bv(6, *)
    real(wp), intent(in) :: relax
    integer :: k, a, o
    real(wp) :: n1, n2, ut, un, rt0, rn0, rt, rn, uft, ufn, drt, drn, m, pt, pn, va3, vo3, dvx, dvy, px, py
    do k = 1, n
      a = cb(1, k); o = cb(2, k)
      n1 = cr(1, k); n2 = cr(2, k)
      ! rigid2_pair_velocity and rigid2_pair_impulse written out, omega held from
      ! the gather to the scatter: through the procedures this loop took 1.5 % more
      ! (10.02-10.04 against 9.86-9.89 ns per update on deposit_1000). Bit for bit
      ! the same as sweep_general (unit.test_local_solver checks it).
      va3 = bv(3, a); vo3 = bv(3, o)
      dvx = bv(1, a) - bv(1, o)
      dvy = bv(2, a) - bv(2, o)
      ut = dvx * n2 - dvy * n1 + va3 * cr(3, k) - vo3 * cr(5, k)
      un = dvx * n1 + dvy * n2 + va3 * cr(4, k) - vo3 * cr(6, k)
      rt0 = r(1, k); rn0 = r(2, k)
      uft = ut - (cr(7, k) * rt0 + cr(8, k) * rn0) + cr(17, k)
      ufn = un - (cr(9, k) * rt0 + cr(10, k) * rn0) + cr(18, k)
      ! coulomb_2d_inv inlined (branches: they are well predicted, and cheaper
      ! here than selecting the four cases with merge)
      if (ufn >= 0.0_wp) then
        rt = 0.0_wp; rn = 0.0_wp
      else
        m = cr(19, k)
        pt = -(cr(11, k) * uft + cr(12, k) * ufn)
        pn = -(cr(13, k) * uft + cr(14, k) * ufn)
        if (pt + m * pn < 0.0_wp) then
          rn = -ufn * cr(15, k)
          rt = -m * rn
        else if (pt - m * pn > 0.0_wp) then
          rn = -ufn * cr(16, k)
          rt = m * rn
        else
          rt = pt; rn = pn
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
      bv(1, a) = bv(1, a) + bv(4, a) * px
      bv(2, a) = bv(2, a) + bv(5, a) * py
      bv(3, a) = va3 + bv(6, a) * (drt * cr(3, k) + drn * cr(4, k))
      bv(1, o) = bv(1, o) - bv(4, o) * px
      bv(2, o) = bv(2, o) - bv(5, o) * py
      bv(3, o) = bv(3, o) - bv(6, o) * (drt * cr(5, k) + drn * cr(6, k))
    end do
  end subroutine sweep_plain

  !> Any sweep with cohesive contacts, or a check pass (statuses and LMGC90's
  !> norm sums, nothing applied).
  subroutine sweep_general(n, cb, cr, icoh, coh, r, status, bv, relax, check, sums, maxes, evaluate_only)
    integer, intent(in) :: n
    integer, intent(in) :: cb(2, n), icoh(n)
    real(wp), intent(in) :: cr(pk_size, n)
    real(wp), intent(inout), contiguous :: coh(:, :)
    real(wp), intent(inout) :: r(2, n), bv(6, *)
    integer, intent(inout) :: status(n)
    real(wp), intent(in) :: relax
    logical, intent(in) :: check, evaluate_only
    real(wp), intent(out) :: sums(6), maxes(2)
    integer :: k, a, o
    real(wp) :: n1, n2, ut, un, rt0, rn0, rt, rn, drt, drn, uend(2)
    sums = 0.0_wp
    maxes = 0.0_wp
    do k = 1, n
      a = cb(1, k); o = cb(2, k)
      n1 = cr(1, k); n2 = cr(2, k)
      call rigid2_pair_velocity(bv(1:3, a), bv(1:3, o), n1, n2, cr(3:6, k), ut, un)
      rt0 = r(1, k); rn0 = r(2, k)
      call local_step(ut, un, cr(:, k), icoh(k), coh, rt0, rn0, relax, check, rt, rn, status(k), sums, maxes, uend)
      if (evaluate_only) then         ! a check pass evaluates, it does not apply
        if (icoh(k) /= 0) coh(coh_uend(2):coh_uend(2) + 1, icoh(k)) = uend
        cycle
      end if
      r(1, k) = rt; r(2, k) = rn
      drt = rt - rt0; drn = rn - rn0
      if (drt == 0.0_wp .and. drn == 0.0_wp) cycle
      call rigid2_pair_impulse(bv(:, a), bv(:, o), n1, n2, cr(3:6, k), drt, drn)
    end do
  end subroutine sweep_general

  !> One contact's update from its current relative velocity (ut, un), whatever
  !> bodies it joins: free velocity u - W r0 + shift, exact local solution (a
  !> cohesive contact j > 0 solves for its contact part with W' and adds the
  !> cohesive impulse, see gs_sweep_2d_packed; uend: its u~ at the end of the step),
  !> with check its status and LMGC90's norm sums, then relaxation. cr is the
  !> contact's packed record.
  pure subroutine local_step(ut, un, cr, j, coh, rt0, rn0, relax, check, rt, rn, status, sums, maxes, uend)
    real(wp), intent(in) :: ut, un, cr(pk_size), rt0, rn0, relax
    integer, intent(in) :: j
    real(wp), intent(in) :: coh(:, :)
    logical, intent(in) :: check
    real(wp), intent(out) :: rt, rn, uend(2)
    integer, intent(inout) :: status
    real(wp), intent(inout) :: sums(6), maxes(2)
    integer :: st
    real(wp) :: wtt, wtn, wnt, wnn, uft, ufn
    wtt = cr(7); wtn = cr(8); wnt = cr(9); wnn = cr(10)
    uend = 0.0_wp
    uft = ut - (wtt * rt0 + wtn * rn0) + cr(17)
    ufn = un - (wnt * rt0 + wnn * rn0) + cr(18)
    if (j /= 0) then
      call cohesive_step(uft, ufn, cr, coh(:, j), rt, rn, st, uend(1), uend(2))
    else
      call coulomb_2d_inv(uft, ufn, cr(11:16), cr(19), rt, rn, st)
    end if
    if (check) then
      status = st
      call lmgc_add_sums_2d(wtt, wtn, wnt, wnn, rt0, rn0, rt, rn, sums, maxes)
    end if
    if (relax /= 1.0_wp) then
      rt = relax * rt + (1.0_wp - relax) * rt0
      rn = relax * rn + (1.0_wp - relax) * rn0
    end if
  end subroutine local_step

  !> The local problem of a cohesive contact from its free velocity (uft, ufn): the
  !> total impulse r = r_c + f (a + K u~), f = coh(coh_factor) the step's spring
  !> factor over beta0^k (1 with LMGC90's explicit update; with damage within the
  !> step, set by nlgs between NLGS solves), the contact part r_c by the exact
  !> Signorini–Coulomb solver on the block W' = A W of the eliminated spring, A and W'
  !> (coh(1:8)) and W'^-1 (cr(11:16)) for that factor.
  pure subroutine cohesive_step(uft, ufn, cr, coh, rt, rn, status, ut, un)
    real(wp), intent(in) :: uft, ufn, cr(pk_size), coh(:)
    real(wp), intent(out) :: rt, rn, ut, un
    integer, intent(out) :: status
    real(wp) :: kt, kn, at, an, xt, xn, vt, vn, rct, rcn
    kt = coh(coh_factor(2)) * coh(coh_k(2)); kn = coh(coh_factor(2)) * coh(coh_k(2) + 1)
    at = coh(coh_factor(2)) * coh(coh_av(2)); an = coh(coh_factor(2)) * coh(coh_av(2) + 1)
    xt = uft + cr(7) * at + cr(8) * an
    xn = ufn + cr(9) * at + cr(10) * an
    vt = coh(1) * xt + coh(2) * xn
    vn = coh(3) * xt + coh(4) * xn
    call coulomb_2d_inv(vt, vn, cr(11:16), cr(19), rct, rcn, status)
    ut = vt + coh(coh_wprime(2)) * rct + coh(coh_wprime(2) + 1) * rcn     ! u~ at the end of the step
    un = vn + coh(coh_wprime(2) + 2) * rct + coh(coh_wprime(2) + 3) * rcn
    rt = rct + at + kt * ut
    rn = rcn + an + kn * un
  end subroutine cohesive_step

  !> One Gauss–Seidel sweep over contacts with a meshed side (sweep order), in
  !> exchange with the bodies after each contact like the rigid kernel:
  !>   cr(pk_size, n) packed records as gs_sweep_2d_packed (levers of rigid sides);
  !>   side(4, n): per side s (cd then an), side(2s-1) = its model (bm_rigid, bm_mesh) and
  !>     side(2s) its place: the body's slot in bv (rigid) or the offset of its
  !>     G block in gmat (meshed); gm(2, n) and goff: see below;
  !>   slot(4, n): index in mv of the x velocity of the two nodes of each meshed
  !>     side (2 mesh_side_nodes(2) = 4); wt(4, n) their weights, with the sign of
  !>     the side (an: minus);
  !>   mv: velocities of the bodies' contact dofs; gmat: per meshed side the
  !>     m x 2 block G = C H^T stored by rows (2, m) (m = gm(s, k) contact dofs
  !>     of its body, starting in mv at mfirst(s, k)), so an impulse change dr
  !>     moves mv by G dr.
  !> Statuses and norm sums as gs_sweep_2d_packed: a check pass applies nothing.
  subroutine gs_sweep_mesh(n, cr, side, gm, mfirst, slot, wt, icoh, coh, r, status, bv, mv, gmat, relax, check, &
                           sums, maxes, evaluate_only)
    integer, intent(in) :: n
    real(wp), intent(in) :: cr(pk_size, n), wt(2 * mesh_side_nodes(2), n), gmat(*)
    integer, intent(in) :: side(4, n), gm(2, n), mfirst(2, n), slot(2 * mesh_side_nodes(2), n), icoh(n)
    real(wp), intent(inout), contiguous :: coh(:, :)
    real(wp), intent(inout) :: r(2, n), bv(6, *), mv(*)
    integer, intent(inout) :: status(n)
    real(wp), intent(in) :: relax
    logical, intent(in) :: check, evaluate_only
    real(wp), intent(out) :: sums(6), maxes(2)
    integer :: k, s, i, a
    real(wp) :: n1, n2, vx, vy, ut, un, rt0, rn0, rt, rn, drt, drn, sgn, uend(2)
    sums = 0.0_wp
    maxes = 0.0_wp
    do k = 1, n
      n1 = cr(1, k); n2 = cr(2, k)
      ! Relative velocity of the contact point: candidate minus antagonist
      ! (the antagonist's weights carry the minus sign).
      if (side(1, k) == bm_mesh .and. side(3, k) == bm_mesh) then
        ! (mesh, mesh): the four weighted node velocities of mesh2_add_node in
        ! one expression (the same sum; 1 % fewer instructions in this kernel)
        vx = wt(1, k) * mv(slot(1, k)) + wt(2, k) * mv(slot(2, k)) + wt(3, k) * mv(slot(3, k)) + &
             wt(4, k) * mv(slot(4, k))
        vy = wt(1, k) * mv(slot(1, k) + 1) + wt(2, k) * mv(slot(2, k) + 1) + wt(3, k) * mv(slot(3, k) + 1) + &
             wt(4, k) * mv(slot(4, k) + 1)
        call frame2_local(n1, n2, vx, vy, ut, un)
      else
        vx = 0.0_wp; vy = 0.0_wp
        ut = 0.0_wp; un = 0.0_wp
        do s = 1, 2
          if (side(2 * s - 1, k) == bm_rigid) then
            a = side(2 * s, k)
            sgn = merge(1.0_wp, -1.0_wp, s == 1)
            call rigid2_add_velocity(sgn, bv(1:3, a), cr(2 * s + 1:2 * s + 2, k), vx, vy, ut, un)
          else
            do i = 2 * s - 1, 2 * s
              call mesh2_add_node(wt(i, k), mv(slot(i, k)), mv(slot(i, k) + 1), vx, vy)
            end do
          end if
        end do
        call frame2_add_local(n1, n2, vx, vy, ut, un)
      end if
      rt0 = r(1, k); rn0 = r(2, k)
      call local_step(ut, un, cr(:, k), icoh(k), coh, rt0, rn0, relax, check, rt, rn, status(k), sums, maxes, uend)
      if (evaluate_only) then         ! a check pass evaluates, it does not apply
        if (icoh(k) /= 0) coh(coh_uend(2):coh_uend(2) + 1, icoh(k)) = uend
        cycle
      end if
      r(1, k) = rt; r(2, k) = rn
      drt = rt - rt0; drn = rn - rn0
      if (drt == 0.0_wp .and. drn == 0.0_wp) cycle
      do s = 1, 2
        if (side(2 * s - 1, k) == bm_rigid) then
          sgn = merge(1.0_wp, -1.0_wp, s == 1)
          call rigid2_side_impulse(bv(:, side(2 * s, k)), sgn, n1, n2, cr(2 * s + 1:2 * s + 2, k), drt, drn)
        else
          call mesh2_add_impulse(mv, gmat, side(2 * s, k), mfirst(s, k) - 1, gm(s, k), drt, drn)
        end if
      end do
    end do
  end subroutine gs_sweep_mesh
  ! ====================================================================== 3D
  ! 3D blocks are in FCLib order (n, t1, t2), stored column-major in w(9):
  ! w(1) = Wnn, w(2) = Wt1n, w(3) = Wt2n, w(4) = Wnt1, ..., w(9) = Wt2t2.

  !> Inverse of a 3x3 block (column-major, see above). A (nearly) singular
  !> block gets a diagonal shift of 1e-10 of its largest diagonal term first,
  !> so the stick trial stays finite.
  pure function inverse_block_3d(w) result(wi)
    real(wp), intent(in) :: w(9)
    real(wp) :: wi(9), a(3, 3), adj(3, 3), det, scale
    integer :: attempt, i
    a = reshape(w, [3, 3])
    scale = max(abs(w(1)), abs(w(5)), abs(w(9)), tiny(1.0_wp))
    do attempt = 1, 2
      call adjugate_3x3(a, adj, det)
      if (abs(det) > 1.0e-13_wp * scale**3) exit
      do i = 1, 3
        a(i, i) = a(i, i) + 1.0e-10_wp * scale
      end do
    end do
    wi = reshape(adj, [9]) / det
  end function inverse_block_3d

  !> Exact local solver of one 3D Signorini–Coulomb contact: u = qf + W r,
  !> K* ∋ u + mu |u_T| e_n ⊥ r ∈ K = {|r_T| <= mu r_n} (the FCLib local problem
  !> with one contact). Tries in turn no contact (qf_n >= 0), sticking
  !> (r = -W^-1 qf inside the cone) and sliding. Sliding is r = rho (1, -mu d),
  !> |d| = 1, u_n = 0 and u_T = lambda d with lambda >= 0: rho follows from d
  !> in closed form and d solves one scalar equation on the unit circle
  !> (u_T x d = 0), by Newton from the previous sliding direction (warm start
  !> in r), then from the stick trial's, then by bisection of the sign changes
  !> among 64 directions (nearest first) until a root with lambda >= 0 is
  !> found. w is the block, wi = inverse_block_3d(w).
  !> status: st_noctc, st_stick, st_slifw (sliding, any direction), or
  !> -st_slifw when no sliding solution was found (r is then an approximation:
  !> sliding along the initial direction, or the projected stick trial).
  pure subroutine coulomb_3d(qf, w, wi, mu, r, status)
    real(wp), intent(in) :: qf(3), w(9), wi(9), mu
    real(wp), intent(inout) :: r(3)
    integer, intent(out) :: status
    integer, parameter :: nsample = 64
    real(wp), parameter :: cs = cos(2.0_wp * 3.14159265358979323846_wp / nsample), &
                           sn = sin(2.0_wp * 3.14159265358979323846_wp / nsample)
    real(wp) :: qn, s1, s2, s3, d1, d2, t1, t2, rho, g, lam, dg, nrm, gscale
    real(wp) :: gs(0:nsample), ds(2, 0:nsample), lo(2), hi(2), glo, dm(2)
    logical :: ok, vs(0:nsample), found
    integer :: it, k, kk
    qn = qf(1)
    if (qn >= 0.0_wp) then
      r = 0.0_wp
      status = st_noctc
      return
    end if
    ! stick trial
    s1 = -(wi(1) * qf(1) + wi(4) * qf(2) + wi(7) * qf(3))
    s2 = -(wi(2) * qf(1) + wi(5) * qf(2) + wi(8) * qf(3))
    s3 = -(wi(3) * qf(1) + wi(6) * qf(2) + wi(9) * qf(3))
    if (s1 > 0.0_wp .and. s2**2 + s3**2 <= (mu * s1)**2) then
      r = [s1, s2, s3]
      status = st_stick
      return
    end if
    if (mu == 0.0_wp .or. w(1) <= 0.0_wp) then
      ! frictionless (or a block without normal stiffness: best effort)
      r = [max(0.0_wp, -qn / max(w(1), tiny(1.0_wp))), 0.0_wp, 0.0_wp]
      status = merge(st_slifw, -st_slifw, w(1) > 0.0_wp)
      return
    end if
    gscale = abs(qf(2)) + abs(qf(3)) + abs(qn) * (abs(w(2)) + abs(w(3)) + mu * (abs(w(5)) + abs(w(6)) + &
             abs(w(8)) + abs(w(9)))) / w(1)
    ! the stick trial's direction (reversed)
    nrm = sqrt(s2**2 + s3**2)
    if (nrm > 0.0_wp) then
      t1 = -s2 / nrm; t2 = -s3 / nrm
    else
      t1 = 1.0_wp; t2 = 0.0_wp
    end if
    ! Newton from the previous sliding direction if r was sliding, then from the stick trial's
    found = .false.
    nrm = sqrt(r(2)**2 + r(3)**2)
    if (r(1) > 0.0_wp .and. nrm >= 0.999_wp * mu * r(1) .and. nrm > 0.0_wp) then
      d1 = -r(2) / nrm; d2 = -r(3) / nrm
      call newton(d1, d2, found, rho)
    end if
    if (.not. found) then
      d1 = t1; d2 = t2
      call newton(d1, d2, found, rho)
    end if
    if (.not. found) then
      ! Sample the circle from the stick trial's direction; bisect the brackets
      ! (sign changes of g) nearest first until one holds a root with lambda >= 0.
      ds(:, 0) = [t1, t2]
      call slide(t1, t2, vs(0), rho, gs(0), lam, dg)
      do k = 1, nsample
        ds(:, k) = [cs * ds(1, k - 1) - sn * ds(2, k - 1), sn * ds(1, k - 1) + cs * ds(2, k - 1)]
        call slide(ds(1, k), ds(2, k), vs(k), rho, gs(k), lam, dg)
      end do
      do kk = 0, nsample - 1
        ! nearest first: 0, nsample-1, 1, nsample-2, ...
        k = merge(kk / 2, nsample - 1 - kk / 2, mod(kk, 2) == 0)
        if (.not. (vs(k) .and. vs(k + 1))) cycle
        if (gs(k) * gs(k + 1) > 0.0_wp) cycle
        lo = ds(:, k); hi = ds(:, k + 1); glo = gs(k)
        dm = lo
        do it = 1, 60
          dm = lo + hi
          dm = dm / sqrt(dm(1)**2 + dm(2)**2)
          call slide(dm(1), dm(2), ok, rho, g, lam, dg)
          if (.not. ok) exit
          if (abs(g) <= 1.0e-15_wp * gscale) exit
          if (sign(1.0_wp, g) == sign(1.0_wp, glo)) then
            lo = dm; glo = g
          else
            hi = dm
          end if
        end do
        d1 = dm(1); d2 = dm(2)
        call slide(d1, d2, ok, rho, g, lam, dg)
        found = ok .and. lam >= -1.0e-12_wp * gscale
        if (found) exit
      end do
    end if
    if (found) then
      r = [rho, -mu * rho * d1, -mu * rho * d2]
      status = st_slifw
    else
      ! no sliding solution found: the projected stick trial
      call project_cone_3d(s1, s2, s3, mu, r)
      status = -st_slifw
    end if

  contains

    !> Newton on the angle from d (a rotation by atan(delta) per step); found
    !> if it converges to a root with lambda >= 0 (d, rho then hold it).
    pure subroutine newton(d1, d2, found, rho)
      real(wp), intent(inout) :: d1, d2
      logical, intent(out) :: found
      real(wp), intent(out) :: rho
      real(wp) :: e1, e2, delta, nrm2, g, lam, dg
      logical :: ok
      integer :: iter
      found = .false.
      do iter = 1, 30
        call slide(d1, d2, ok, rho, g, lam, dg)
        if (.not. ok .or. dg == 0.0_wp) return
        delta = max(-1.0_wp, min(1.0_wp, -g / dg))
        e1 = d1 - delta * d2
        e2 = d2 + delta * d1
        nrm2 = 1.0_wp / sqrt(e1**2 + e2**2)
        d1 = e1 * nrm2; d2 = e2 * nrm2
        if (abs(delta) <= 1.0e-12_wp .or. abs(g) <= 1.0e-15_wp * gscale) then
          call slide(d1, d2, ok, rho, g, lam, dg)
          found = ok .and. lam >= -1.0e-12_wp * gscale
          return
        end if
      end do
    end subroutine newton

    !> Sliding along d: rho from u_n = 0, g = d_perp . u_T, lam = d . u_T and dg/dtheta.
    pure subroutine slide(d1, d2, ok, rho, g, lam, dg)
      real(wp), intent(in) :: d1, d2
      logical, intent(out) :: ok
      real(wp), intent(out) :: rho, g, lam, dg
      real(wp) :: p1, p2, bd, bp, den, v1, v2, ap1, ap2, u1, u2, drho, du1, du2
      p1 = -d2; p2 = d1
      bd = w(4) * d1 + w(7) * d2
      bp = w(4) * p1 + w(7) * p2
      den = w(1) - mu * bd
      ok = den > 0.0_wp
      if (.not. ok) then
        rho = 0.0_wp; g = 0.0_wp; lam = 0.0_wp; dg = 0.0_wp
        return
      end if
      rho = -qn / den
      v1 = w(2) - mu * (w(5) * d1 + w(8) * d2)
      v2 = w(3) - mu * (w(6) * d1 + w(9) * d2)
      ap1 = w(5) * p1 + w(8) * p2
      ap2 = w(6) * p1 + w(9) * p2
      u1 = qf(2) + rho * v1
      u2 = qf(3) + rho * v2
      g = p1 * u1 + p2 * u2
      lam = d1 * u1 + d2 * u2
      drho = rho * mu * bp / den
      du1 = drho * v1 - mu * rho * ap1
      du2 = drho * v2 - mu * rho * ap2
      dg = -lam + p1 * du1 + p2 * du2
    end subroutine slide
  end subroutine coulomb_3d

  !> Projection of x = (xn, xt1, xt2) on K = {|x_T| <= mu x_n}.
  pure subroutine project_cone_3d(xn, xt1, xt2, mu, p)
    real(wp), intent(in) :: xn, xt1, xt2, mu
    real(wp), intent(out) :: p(3)
    real(wp) :: nt, pn
    nt = sqrt(xt1**2 + xt2**2)
    if (mu * nt <= -xn) then
      p = 0.0_wp
    else if (nt <= mu * xn) then
      p = [xn, xt1, xt2]
    else
      pn = (mu * nt + xn) / (1.0_wp + mu**2)
      p = [pn, mu * pn * xt1 / nt, mu * pn * xt2 / nt]
    end if
  end subroutine project_cone_3d

  !> FCLib natural map of one 3D contact (order n, t1, t2): F = r - P_K(r - u~),
  !> u~ = u + mu |u_T| e_n. Returns |F|^2.
  pure real(wp) function natural_map_3d(u, r, mu) result(f2)
    real(wp), intent(in) :: u(3), r(3), mu
    real(wp) :: p(3)
    call project_cone_3d(r(1) - u(1) - mu * sqrt(u(2)**2 + u(3)**2), r(2) - u(2), r(3) - u(3), mu, p)
    f2 = (r(1) - p(1))**2 + (r(2) - p(2))**2 + (r(3) - p(3))**2
  end function natural_map_3d
end module fracas_local_solver
