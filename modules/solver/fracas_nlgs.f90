!> Nonlinear Gauss–Seidel on the contact reactions, "exchange local–global"
!> mode: after each contact update the two bodies' velocities are updated, so
!> each contact sees its neighbours' latest reactions. Convergence is measured
!> with LMGC90's normalised norms (Quad, Maxm, QM/16), computed inside the last
!> sweep of each block, and after convergence with the FCLib natural map.
module fracas_nlgs
  use fracas_kinds, only: wp, i8
  use fracas_ids, only: st_noctc, st_stick, st_slifw, st_slibw, st_cnctc, st_cstck, st_cslfw, st_cslbw
  use fracas_random, only: rng_t, rng_seed, rng_permute
  use fracas_rbdy2, only: rbdy2_t
  use fracas_contacts, only: contacts_t
  use fracas_contact_laws, only: law_t, law_shift, law_friction, law_czm
  use fracas_czm, only: czm_t, czm_beta_power, czm_beta_update, czm_stored_energy
  use fracas_local_solver, only: gs_sweep_2d_packed, pk_size, natural_map_2d, inverse_block
  use fracas_lmgc_norms, only: lmgc_norms_t, lmgc_norms
  implicit none
  private
  public :: nlgs_settings_t, nlgs_report_t, nlgs_t, nlgs_init, nlgs_prepare, nlgs_solve, &
            contact_velocity, nlgs_update_cohesive

  type :: nlgs_settings_t
    character(len=5) :: check = 'Quad '
    real(wp) :: tol = 1.0e-4_wp
    real(wp) :: relax = 1.0_wp
    integer :: sweeps_per_check = 50
    integer :: max_checks = 400
    character(len=8) :: order = 'stored'
    integer :: seed = 1
  end type nlgs_settings_t

  type :: nlgs_report_t
    integer :: sweeps = 0
    logical :: converged = .true.
    real(wp) :: quad_dv = 0.0_wp, maxm_dv = 0.0_wp, quad_dvr = 0.0_wp, maxm_dvr = 0.0_wp
    real(wp) :: mean_dvor = 0.0_wp
    real(wp) :: residual = 0.0_wp        !< natural map ||F|| / ||q||
    real(wp) :: residual_onepq = 0.0_wp  !< ||F|| / (1 + ||q||)
    integer :: nactive = 0               !< contacts with a non-zero reaction
  end type nlgs_report_t

  !> Solver state kept between steps (random stream, work arrays). The sweeps
  !> run on packed copies (gs_sweep_2d_packed), built once per step (per block
  !> of sweeps in shuffled order): the active contacts in sweep order, and the
  !> bodies they touch, numbered in order of first appearance in the stored
  !> (detection, i.e. cell) order so that neighbours are close in memory. The
  !> numbering is internal: the bodies and contacts keep theirs.
  type :: nlgs_t
    type(nlgs_settings_t) :: s
    type(rng_t) :: rng
    integer, allocatable :: order(:)
    real(wp), allocatable :: qfree(:, :)   !< (2,n) free local velocity incl. law shift
    integer :: np = 0                      !< active contacts (packed)
    logical :: any_coh = .false.           !< some packed contact is cohesive
    integer, allocatable :: pidx(:)        !< (np) contact of each packed slot
    real(wp), allocatable :: pc(:, :)      !< (pk_size,np) contact records
    integer, allocatable :: pb(:, :)       !< (2,np) bodies, as slots of bv
    integer, allocatable :: pcoh(:)        !< (np) column of c%coh (0: not cohesive)
    real(wp), allocatable :: pr(:, :)      !< (2,np) impulses
    integer, allocatable :: pst(:)         !< (np) statuses
    integer :: nbp = 0                     !< bodies touched by active contacts
    integer, allocatable :: bslot(:)       !< (nb) slot in bv of each body (0: none)
    integer, allocatable :: blist(:)       !< (nbp) body of each slot
    real(wp), allocatable :: bv(:, :)      !< (6,nbp) velocity and inverse mass
  end type nlgs_t

contains

  subroutine nlgs_init(solver, settings)
    type(nlgs_t), intent(out) :: solver
    type(nlgs_settings_t), intent(in) :: settings
    solver%s = settings
    call rng_seed(solver%rng, settings%seed)
  end subroutine nlgs_init

  !> Relative velocity (t, n) at contact k for body velocities v.
  pure function contact_velocity(c, k, v) result(u)
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: k
    real(wp), intent(in) :: v(:, :)
    real(wp) :: u(2), dv(2)
    integer :: a, b
    a = c%cdb(k); b = c%anb(k)
    dv = v(1:2, a) - v(1:2, b)
    u(1) = dv(1) * c%normal(2, k) - dv(2) * c%normal(1, k) + v(3, a) * c%lever(1, k) - v(3, b) * c%lever(3, k)
    u(2) = dv(1) * c%normal(1, k) + dv(2) * c%normal(2, k) + v(3, a) * c%lever(2, k) - v(3, b) * c%lever(4, k)
  end function contact_velocity

  !> Component i (1: t, 2: n) of the cohesive impulse a + K u~ of contact k at
  !> its current velocity (0 for a contact without cohesion).
  pure real(wp) function cohesive_impulse(c, k, i) result(rc)
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: k, i
    rc = 0.0_wp
    if (c%cohesive(k)) rc = c%coh(8 + i, k) + c%coh(10 + i, k) * (c%u(i, k) + c%shift(i, k))
  end function cohesive_impulse

  !> After convergence: the jumps, the damage beta and the time damage started
  !> of the cohesive contacts (stored in internals), their statuses relabelled
  !> cohesive, and the energies: stored cohesive energy at the end of the step,
  !> work of the cohesive impulses -r_coh.(u + u_begin)/2 over the step, and the
  !> energy released by damage: the drop of the stored energy when beta falls
  !> at the end-of-step jumps (never negative).
  subroutine nlgs_update_cohesive(c, laws, h, t_end, stored, coh_work, released)
    type(contacts_t), intent(inout) :: c
    type(law_t), intent(in) :: laws(:)
    real(wp), intent(in) :: h, t_end
    real(wp), intent(out) :: stored, coh_work, released
    integer :: k
    real(wp) :: ut, un, beta, rc(2), e_new
    stored = 0.0_wp
    coh_work = 0.0_wp
    released = 0.0_wp
    do k = 1, c%n
      if (laws(c%law(k))%kind /= law_czm) cycle
      associate (z => laws(c%law(k))%czm)
        rc = [cohesive_impulse(c, k, 1), cohesive_impulse(c, k, 2)]
        coh_work = coh_work - 0.5_wp * sum(rc * (c%u(:, k) + c%u_begin(:, k)))
        ut = c%internals(2, k) + h * c%u(1, k)
        un = h * (c%u(2, k) + c%shift(2, k))
        beta = czm_beta_update(z, c%internals(4, k), ut, un, h)
        if (beta < 1.0_wp .and. c%internals(5, k) < 0.0_wp) c%internals(5, k) = t_end
        e_new = c%length(k) * czm_stored_energy(z, beta, ut, un)
        released = released + c%length(k) * czm_stored_energy(z, c%internals(4, k), ut, un) - e_new
        c%internals(1:4, k) = [c%length(k), ut, un, beta]
        stored = stored + e_new
        if (c%cohesive(k)) then
          select case (c%status(k))
          case (st_noctc)
            if (any(c%r(:, k) /= 0.0_wp)) then
              c%status(k) = st_cstck
            else
              c%status(k) = st_cnctc
            end if
          case (st_stick); c%status(k) = st_cstck
          case (st_slifw); c%status(k) = st_cslfw
          case (st_slibw); c%status(k) = st_cslbw
          end select
        end if
      end associate
    end do
  end subroutine nlgs_update_cohesive

  !> Per-contact data of the step: Delassus blocks from the inverse masses and
  !> lever arms, velocities at the beginning of the step, law shifts, friction.
  subroutine nlgs_prepare(c, b, laws, h)
    type(contacts_t), intent(inout) :: c
    type(rbdy2_t), intent(in) :: b
    type(law_t), intent(in) :: laws(:)
    real(wp), intent(in) :: h
    integer :: k, a, o
    real(wp) :: ht(3), hn(3), gt(3), gn(3)
    logical :: active
    do k = 1, c%n
      a = c%cdb(k); o = c%anb(k)
      ht = [c%normal(2, k), -c%normal(1, k), c%lever(1, k)]
      hn = [c%normal(1, k), c%normal(2, k), c%lever(2, k)]
      gt = [c%normal(2, k), -c%normal(1, k), c%lever(3, k)]
      gn = [c%normal(1, k), c%normal(2, k), c%lever(4, k)]
      c%w(1, k) = sum(b%inv_mass(:, a) * ht * ht) + sum(b%inv_mass(:, o) * gt * gt)
      c%w(2, k) = sum(b%inv_mass(:, a) * ht * hn) + sum(b%inv_mass(:, o) * gt * gn)
      c%w(3, k) = c%w(2, k)
      c%w(4, k) = sum(b%inv_mass(:, a) * hn * hn) + sum(b%inv_mass(:, o) * gn * gn)
      ! A nearly rigid tangential direction would make the stick test ill-posed.
      c%w(1, k) = max(c%w(1, k), 1.0e-6_wp * c%w(4, k))
      c%u_begin(:, k) = contact_velocity(c, k, b%vbegin)
      call law_shift(laws(c%law(k)), c%gap(k), h, c%u_begin(:, k), c%shift(:, k), active)
      c%active(k) = active .and. c%w(4, k) > 1.0e-18_wp
      c%mu(k) = law_friction(laws(c%law(k)), c%status_begin(k))
      c%cohesive(k) = .false.
      if (laws(c%law(k))%kind == law_czm) call prepare_cohesive(k, laws(c%law(k))%czm)
      if (.not. c%active(k)) then
        c%r(:, k) = 0.0_wp
        c%status(k) = st_noctc   ! as LMGC90 reports a contact the law leaves open
      else if (c%cohesive(k)) then
        ! Between bodies that cannot move along the normal (both driven) the
        ! cohesive impulse still acts; the contact part then stays zero.
        c%wi(:, k) = 0.0_wp
        if (c%coh(5, k) * c%coh(8, k) - c%coh(6, k) * c%coh(7, k) > 1.0e-30_wp * max(c%coh(8, k), tiny(1.0_wp))**2 &
            .and. c%coh(8, k) > 1.0e-18_wp) &
          c%wi(:, k) = inverse_block(c%coh(5, k), c%coh(6, k), c%coh(7, k), c%coh(8, k), c%mu(k))
      else
        c%wi(:, k) = inverse_block(c%w(1, k), c%w(2, k), c%w(3, k), c%w(4, k), c%mu(k))
      end if
    end do

  contains

    !> Cohesive contact with beta frozen over the step: friction mu (1-beta)^p and
    !> the impulse r_coh = a + K u~ (u~ = u + shift), eliminated locally:
    !> (I - W K) u~ = u~free + W a + W r_c, A = (I - W K)^-1, W' = A W.
    subroutine prepare_cohesive(k, z)
      integer, intent(in) :: k
      type(czm_t), intent(in) :: z
      real(wp) :: beta, e, kt, kn, m(4), det, amat(4), wp_(4), at
      beta = c%internals(4, k)
      c%mu(k) = c%mu(k) * (1.0_wp - beta)**z%friction_power
      if (beta <= 0.0_wp) return
      c%cohesive(k) = .true.
      e = beta**czm_beta_power(z) * c%length(k)
      kt = -h**2 * e * z%ct
      kn = -h**2 * e * z%cn
      at = -h * e * z%ct * c%internals(2, k)     ! tangential jump at the beginning of the step
      m = [1.0_wp - c%w(1, k) * kt, -c%w(2, k) * kn, -c%w(3, k) * kt, 1.0_wp - c%w(4, k) * kn]
      det = m(1) * m(4) - m(2) * m(3)
      amat = [m(4), -m(2), -m(3), m(1)] / det
      wp_(1) = amat(1) * c%w(1, k) + amat(2) * c%w(3, k)
      wp_(2) = amat(1) * c%w(2, k) + amat(2) * c%w(4, k)
      wp_(3) = amat(3) * c%w(1, k) + amat(4) * c%w(3, k)
      wp_(4) = amat(3) * c%w(2, k) + amat(4) * c%w(4, k)
      c%coh(1:4, k) = amat
      c%coh(5:8, k) = wp_
      c%coh(9:10, k) = [at, 0.0_wp]
      c%coh(11:12, k) = [kt, kn]
      ! The tensile cohesive impulse also acts while the gap is open, and
      ! between bodies whose normal motion is driven.
      c%active(k) = .true.
    end subroutine prepare_cohesive
  end subroutine nlgs_prepare

  !> Solve the step's contact problem. On entry b%v = vfree and c%r holds the
  !> warm start; on exit b%v = vfree + M^-1 H^T r and c%u the final local velocities.
  subroutine nlgs_solve(solver, c, b, report)
    type(nlgs_t), intent(inout) :: solver
    type(contacts_t), intent(inout) :: c
    type(rbdy2_t), intent(inout) :: b
    type(nlgs_report_t), intent(out) :: report
    integer :: k, iblock, isweep, n
    real(wp) :: sums(7), maxes(2), fsum, qsum, vscale
    logical :: diverged
    n = c%n
    diverged = .false.
    report%sweeps = 0
    if (allocated(solver%order)) then
      if (size(solver%order) < n) deallocate (solver%order, solver%qfree, solver%pidx, solver%pc, solver%pb, &
                                              solver%pcoh, solver%pr, solver%pst)
    end if
    if (.not. allocated(solver%order)) then
      k = max(n, 16)
      allocate (solver%order(k), solver%qfree(2, k), solver%pidx(k), solver%pc(pk_size, k), solver%pb(2, k), &
                solver%pcoh(k), solver%pr(2, k), solver%pst(k))
    end if
    if (allocated(solver%bslot)) then
      if (size(solver%bslot) /= b%n) deallocate (solver%bslot, solver%blist, solver%bv)
    end if
    if (.not. allocated(solver%bslot)) then
      allocate (solver%bslot(b%n), solver%blist(b%n), solver%bv(6, max(b%n, 1)))
      solver%bslot = 0
    end if
    do k = 1, n
      solver%qfree(:, k) = contact_velocity(c, k, b%v) + c%shift(:, k)
      if (c%active(k)) call inject(k, c%r(1, k), c%r(2, k))
    end do
    ! Velocity scale of the step: free relative velocities and body speeds.
    vscale = 0.0_wp
    do k = 1, n
      vscale = vscale + sum(solver%qfree(:, k)**2) + sum(b%vfree(1:2, c%cdb(k))**2) + sum(b%vfree(1:2, c%anb(k))**2)
    end do
    if (n > 0) vscale = sqrt(vscale / n)
    select case (solver%s%order)
    case ('reversed')
      solver%order(1:n) = [(n + 1 - k, k=1, n)]
    case ('colored')
      call colour_order()
    case default
      solver%order(1:n) = [(k, k=1, n)]
    end select
    call pack_bodies()
    if (solver%s%order /= 'shuffled') call pack_contacts()
    report%converged = n == 0
    if (n > 0) then
      blocks: do iblock = 1, solver%s%max_checks
        if (solver%s%order == 'shuffled') then
          if (iblock > 1) call unpack_contacts()
          call rng_permute(solver%rng, solver%order(1:n))
          call pack_contacts()
        end if
        do isweep = 1, solver%s%sweeps_per_check
          call sweep(isweep == solver%s%sweeps_per_check)
          report%sweeps = report%sweeps + 1
        end do
        call norms(report)
        if (report%converged .or. diverged) exit blocks   ! NaN/Inf: the caller's state check names it
      end do blocks
      call unpack_contacts()
    end if
    call unpack_bodies()
    ! Final local velocities, statuses and the natural-map residual.
    fsum = 0.0_wp; qsum = 0.0_wp
    report%nactive = 0
    do k = 1, n
      c%u(:, k) = contact_velocity(c, k, b%v)
      if (.not. c%active(k)) cycle
      if (c%r(1, k) == 0.0_wp .and. c%r(2, k) == 0.0_wp) then
        c%status(k) = st_noctc
      else
        report%nactive = report%nactive + 1
      end if
      ! The natural map of the contact part (the total minus the cohesive impulse).
      fsum = fsum + natural_map_2d(c%u(1, k) + c%shift(1, k), c%u(2, k) + c%shift(2, k), &
                                   c%r(1, k) - cohesive_impulse(c, k, 1), c%r(2, k) - cohesive_impulse(c, k, 2), c%mu(k))
      qsum = qsum + sum(solver%qfree(:, k)**2)
    end do
    report%residual = 0.0_wp
    if (qsum > 0.0_wp) report%residual = sqrt(fsum / qsum)
    report%residual_onepq = sqrt(fsum) / (1.0_wp + sqrt(qsum))

  contains

    !> Add impulse (dt, dn) of contact k to both bodies' velocities.
    subroutine inject(k, dt, dn)
      integer, intent(in) :: k
      real(wp), intent(in) :: dt, dn
      integer :: a, o
      real(wp) :: p(2)
      a = c%cdb(k); o = c%anb(k)
      p(1) = dt * c%normal(2, k) + dn * c%normal(1, k)
      p(2) = -dt * c%normal(1, k) + dn * c%normal(2, k)
      b%v(1:2, a) = b%v(1:2, a) + b%inv_mass(1:2, a) * p
      b%v(3, a) = b%v(3, a) + b%inv_mass(3, a) * (dt * c%lever(1, k) + dn * c%lever(2, k))
      b%v(1:2, o) = b%v(1:2, o) - b%inv_mass(1:2, o) * p
      b%v(3, o) = b%v(3, o) - b%inv_mass(3, o) * (dt * c%lever(3, k) + dn * c%lever(4, k))
    end subroutine inject

    !> Coloured order: the active contacts in stored order, cut in blocks of
    !> colour_block; in each block, greedy colours (two contacts sharing a body
    !> never share one) and the contacts sorted by colour, stored order inside a
    !> colour. Consecutive updates then touch different bodies, so the core can
    !> overlap them, while a block stays in cache. A contact that finds no free
    !> colour among 64 goes to the last. Inactive contacts follow (not swept).
    subroutine colour_order()
      integer, parameter :: colour_block = 256, ncol = 64
      integer(i8), allocatable :: used(:)
      integer :: blk(colour_block), col(colour_block), cnt(0:ncol), k, m, j, cc, nact
      allocate (used(b%n))
      used = 0_i8
      nact = 0
      m = 0
      do k = 1, n
        if (c%active(k)) then
          m = m + 1
          blk(m) = k
        end if
        if (m == colour_block .or. (k == n .and. m > 0)) then
          cnt = 0
          do j = 1, m
            cc = min(ncol - 1, trailz(not(ior(used(c%cdb(blk(j))), used(c%anb(blk(j)))))))
            col(j) = cc
            cnt(cc + 1) = cnt(cc + 1) + 1
            used(c%cdb(blk(j))) = ibset(used(c%cdb(blk(j))), cc)
            used(c%anb(blk(j))) = ibset(used(c%anb(blk(j))), cc)
          end do
          do cc = 1, ncol
            cnt(cc) = cnt(cc) + cnt(cc - 1)
          end do
          do j = 1, m
            cnt(col(j)) = cnt(col(j)) + 1
            solver%order(nact + cnt(col(j))) = blk(j)
            used(c%cdb(blk(j))) = 0_i8
            used(c%anb(blk(j))) = 0_i8
          end do
          nact = nact + m
          m = 0
        end if
      end do
      do k = 1, n
        if (c%active(k)) cycle
        nact = nact + 1
        solver%order(nact) = k
      end do
    end subroutine colour_order

    !> Slots in bv of the bodies of the active contacts, in order of first
    !> appearance in the stored contact order; their velocities and inverse masses.
    subroutine pack_bodies()
      integer :: k, j, ib
      solver%nbp = 0
      do k = 1, n
        if (.not. c%active(k)) cycle
        do j = 1, 2
          ib = merge(c%cdb(k), c%anb(k), j == 1)
          if (solver%bslot(ib) /= 0) cycle
          solver%nbp = solver%nbp + 1
          solver%bslot(ib) = solver%nbp
          solver%blist(solver%nbp) = ib
        end do
      end do
      do j = 1, solver%nbp
        ib = solver%blist(j)
        solver%bv(1:3, j) = b%v(:, ib)
        solver%bv(4:6, j) = b%inv_mass(:, ib)
      end do
    end subroutine pack_bodies

    !> Velocities back to the bodies; the slot map is cleared for the next step.
    subroutine unpack_bodies()
      integer :: j, ib
      do j = 1, solver%nbp
        ib = solver%blist(j)
        b%v(:, ib) = solver%bv(1:3, j)
        solver%bslot(ib) = 0
      end do
      solver%nbp = 0
    end subroutine unpack_bodies

    !> Records of the active contacts in the current sweep order.
    subroutine pack_contacts()
      integer :: ii, k, j
      j = 0
      do ii = 1, n
        k = solver%order(ii)
        if (.not. c%active(k)) cycle
        j = j + 1
        solver%pidx(j) = k
        solver%pb(1, j) = solver%bslot(c%cdb(k))
        solver%pb(2, j) = solver%bslot(c%anb(k))
        solver%pc(1:2, j) = c%normal(:, k)
        solver%pc(3:6, j) = c%lever(:, k)
        solver%pc(7:10, j) = c%w(:, k)
        solver%pc(11:16, j) = c%wi(:, k)
        solver%pc(17:18, j) = c%shift(:, k)
        solver%pc(19, j) = c%mu(k)
        solver%pc(20, j) = 0.0_wp
        solver%pcoh(j) = 0
        if (c%cohesive(k)) solver%pcoh(j) = k
        solver%pr(:, j) = c%r(:, k)
        solver%pst(j) = c%status(k)
      end do
      solver%np = j
      solver%any_coh = any(solver%pcoh(1:j) /= 0)
    end subroutine pack_contacts

    !> Impulses and statuses back to the contact store.
    subroutine unpack_contacts()
      integer :: j, k
      do j = 1, solver%np
        k = solver%pidx(j)
        c%r(:, k) = solver%pr(:, j)
        c%status(k) = solver%pst(j)
      end do
    end subroutine unpack_contacts

    !> One Gauss–Seidel sweep; with check, LMGC90's norm sums of this sweep.
    subroutine sweep(check)
      logical, intent(in) :: check
      real(wp) :: s6(6)
      integer :: np
      np = solver%np
      call gs_sweep_2d_packed(np, solver%pb, solver%pc, solver%pcoh, solver%any_coh, c%coh, solver%pr, solver%pst, solver%bv, &
                              solver%s%relax, check, s6, maxes)
      if (check) sums(1:6) = s6
    end subroutine sweep

    !> LMGC90's normalised errors from the sums of the last check sweep.
    subroutine norms(rep)
      type(nlgs_report_t), intent(inout) :: rep
      type(lmgc_norms_t) :: nrm
      call lmgc_norms(solver%s%check, solver%s%tol, sums(1:6), maxes, vscale, nrm, rep%converged)
      rep%quad_dv = nrm%quad_dv; rep%maxm_dv = nrm%maxm_dv; rep%quad_dvr = nrm%quad_dvr
      rep%maxm_dvr = nrm%maxm_dvr; rep%mean_dvor = nrm%mean_dvor
      diverged = .not. nrm%finite
    end subroutine norms
  end subroutine nlgs_solve
end module fracas_nlgs
