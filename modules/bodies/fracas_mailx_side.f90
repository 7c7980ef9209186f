!> The contact side of a meshed 2D body (mailx): node weights, G = C H^T and
!> H G, local velocity and impulse of a contact on the body's contact dofs
!> (mailx_side.inc), and the model's part of the sweep kernels' workspace
!> (mesh2_pack_t: the step's active nodes and G blocks, the contact-dof
!> velocities, side records, warm start, the bodies' final velocities). The body
!> model knows no contact: it is given, per contact, each side's model and body
!> (md1/bd1 candidate, md2/bd2 antagonist), the nodes and weights of its meshed
!> sides and the frame, as arrays.
module fracas_mailx_side
  use fracas_kinds, only: wp
  use fracas_ids, only: bm_mesh
  use fracas_grow, only: grow
  use fracas_frame_2d, only: frame2_global
  use fracas_mailx, only: mailx_t, mailx_require_compliance, mailx_compliance_columns, mailx_contact_dofs, &
                          mailx_velocity_from_impulses
  implicit none
  private
  public :: mesh2_add_node, mesh2_point_velocity, mesh2_add_g, mesh2_add_hg, mesh2_add_impulse
  public :: mesh2_pack_t, mesh2_pack_blocks, mesh2_add_delassus, mesh2_pack_load, mesh2_pack_side, &
            mesh2_pack_impulse, mesh2_unpack

  !> The meshed bodies in the sweep kernels' workspace. The step's active nodes
  !> of each body: a dense body's are all its nodes, a large body's the nodes its
  !> contacts touch (its cached compliance may cover more); anodes(abase(b)+1 ..
  !> abase(b)+nact(b)), aslot(node) the node's place in its body's list (0: none).
  !> G blocks of the step (offset goff(s,k) and dofs gm(s,k) of side s of contact
  !> k), and the contact-dof velocities mv of the bodies active contacts touch
  !> (body b's from moff(b)+1, -1 if none).
  type :: mesh2_pack_t
    integer, allocatable :: nact(:), abase(:), anodes(:), aslot(:)
    real(wp), allocatable :: gmat(:)
    integer, allocatable :: goff(:, :), gm(:, :)
    integer, allocatable :: moff(:)
    real(wp), allocatable :: mv(:)
  end type mesh2_pack_t

contains
  include 'mailx_side.inc'

  pure integer function side_of(s, a1, a2)
    integer, intent(in) :: s, a1, a2
    side_of = merge(a1, a2, s == 1)
  end function side_of

  !> G = C H^T of every meshed contact side (the velocity change of its body's
  !> contact dofs per unit impulse (t, n)), after making sure the bodies'
  !> compliance covers the contact nodes; the step's active nodes.
  subroutine mesh2_pack_blocks(p, m, n, md1, md2, bd1, bd2, mnode, mwt, frame)
    type(mesh2_pack_t), intent(inout) :: p
    type(mailx_t), intent(inout) :: m
    integer, intent(in) :: n, md1(:), md2(:), bd1(:), bd2(:), mnode(:, :)
    real(wp), intent(in) :: mwt(:, :), frame(:, :, :)
    integer :: k, s, i, j, nnod, total, mb, g0, node, b, na, nside
    integer, allocatable :: nodes(:)
    real(wp), allocatable :: cols(:, :)
    real(wp) :: t(2), nrm(2), sgn, wgt
    nside = size(mnode, 1) / 2
    allocate (nodes(size(mnode, 1) * n))
    nnod = 0
    do k = 1, n
      do i = 1, 2 * nside
        if (side_of((i - 1) / nside + 1, md1(k), md2(k)) /= bm_mesh) cycle
        nnod = nnod + 1
        nodes(nnod) = mnode(i, k)
      end do
    end do
    call mailx_require_compliance(m, nodes(1:nnod))
    ! Active nodes per body, those of the last call cleared first.
    call clear_active(p)
    call grow(p%aslot, m%nnodes, fill=0)
    call grow(p%nact, m%n)
    call grow(p%abase, m%n)
    p%nact = 0
    do k = 1, nnod
      b = m%node_body(nodes(k))
      if (m%dense(b)) then
        p%nact(b) = m%node_first(b + 1) - m%node_first(b)
      else if (p%aslot(nodes(k)) == 0) then
        p%nact(b) = p%nact(b) + 1
        p%aslot(nodes(k)) = -1          ! counted, placed below
      end if
    end do
    na = 0
    do b = 1, m%n
      p%abase(b) = na
      na = na + p%nact(b)
    end do
    call grow(p%anodes, na)
    p%nact = 0
    do k = 1, nnod
      node = nodes(k)
      b = m%node_body(node)
      if (p%aslot(node) > 0) cycle
      if (m%dense(b)) then
        if (p%nact(b) > 0) cycle
        do j = m%node_first(b), m%node_first(b + 1) - 1
          p%nact(b) = p%nact(b) + 1
          p%anodes(p%abase(b) + p%nact(b)) = j
          p%aslot(j) = p%nact(b)
        end do
      else
        p%nact(b) = p%nact(b) + 1
        p%anodes(p%abase(b) + p%nact(b)) = node
        p%aslot(node) = p%nact(b)
      end if
    end do
    call grow(p%goff, 2, n)
    call grow(p%gm, 2, n)
    total = 0
    do k = 1, n
      do s = 1, 2
        p%goff(s, k) = 0
        p%gm(s, k) = 0
        if (side_of(s, md1(k), md2(k)) /= bm_mesh) cycle
        p%goff(s, k) = total
        p%gm(s, k) = 2 * p%nact(side_of(s, bd1(k), bd2(k)))
        total = total + 2 * p%gm(s, k)
      end do
    end do
    call grow(p%gmat, total)
    do k = 1, n
      nrm = frame(:, 2, k)
      t = [nrm(2), -nrm(1)]
      do s = 1, 2
        if (side_of(s, md1(k), md2(k)) /= bm_mesh) cycle
        sgn = merge(1.0_wp, -1.0_wp, s == 1)
        b = side_of(s, bd1(k), bd2(k))
        mb = p%gm(s, k)
        g0 = p%goff(s, k)
        p%gmat(g0 + 1:g0 + 2 * mb) = 0.0_wp
        if (allocated(cols)) then
          if (size(cols, 1) /= mailx_contact_dofs(m, b)) deallocate (cols)
        end if
        if (.not. allocated(cols)) allocate (cols(mailx_contact_dofs(m, b), 2))
        do i = 2 * s - 1, 2 * s
          node = mnode(i, k)
          wgt = sgn * mwt(i, k)
          if (wgt == 0.0_wp) cycle
          call mailx_compliance_columns(m, node, cols)
          ! rows of the active nodes; (G_t, G_n) interleaved, as the mesh kernel reads them
          do j = 1, p%nact(b)
            associate (r1 => 2 * m%cslot(p%anodes(p%abase(b) + j)) - 1, q => g0 + 4 * j - 4)
              call mesh2_add_g(wgt, t, nrm, cols(r1, 1), cols(r1, 2), cols(r1 + 1, 1), cols(r1 + 1, 2), &
                               p%gmat(q + 1:q + 4))
            end associate
          end do
        end do
      end do
    end do
  end subroutine mesh2_pack_blocks

  !> Clear the active-node marks of the step (aslot is kept zero between steps).
  subroutine clear_active(p)
    type(mesh2_pack_t), intent(inout) :: p
    integer :: b
    if (.not. allocated(p%nact)) return
    do b = 1, size(p%nact)
      p%aslot(p%anodes(p%abase(b) + 1:p%abase(b) + p%nact(b))) = 0
    end do
  end subroutine clear_active

  !> The meshed sides' part of contact k's Delassus block: w += sum over meshed
  !> sides s of H_s G_s' for the meshed sides s' on the same body (both, for a
  !> contact of a body with itself). md(2), bd(2): the sides' models and bodies;
  !> nodes(4), wts(4): candidate's then antagonist's; nrm the normal.
  pure subroutine mesh2_add_delassus(p, k, md, bd, nodes, wts, nrm, w)
    type(mesh2_pack_t), intent(in) :: p
    integer, intent(in) :: k, md(2), bd(2), nodes(4)
    real(wp), intent(in) :: wts(4), nrm(2)
    real(wp), intent(inout) :: w(4)
    integer :: s, s2, i, g0, sl
    real(wp) :: t(2), sgn, ht_g(2), hn_g(2), wgt
    t = [nrm(2), -nrm(1)]
    do s = 1, 2
      if (md(s) /= bm_mesh) cycle
      sgn = merge(1.0_wp, -1.0_wp, s == 1)
      do s2 = 1, 2
        if (md(s2) /= bm_mesh .or. bd(s2) /= bd(s)) cycle
        g0 = p%goff(s2, k)
        ! H_s applied to the two columns of G_s2 (stored interleaved by rows)
        ht_g = 0.0_wp; hn_g = 0.0_wp
        do i = 2 * s - 1, 2 * s
          wgt = sgn * wts(i)
          sl = 2 * p%aslot(nodes(i)) - 1
          call mesh2_add_hg(wgt, t, nrm, p%gmat(g0 + 2 * sl - 1:g0 + 2 * sl), &
                            p%gmat(g0 + 2 * sl + 1:g0 + 2 * sl + 2), ht_g, hn_g)
        end do
        w(1) = w(1) + ht_g(1)
        w(2) = w(2) + ht_g(2)
        w(3) = w(3) + hn_g(1)
        w(4) = w(4) + hn_g(2)
      end do
    end do
  end subroutine mesh2_add_delassus

  !> Contact-dof velocities (from the free velocities) of the meshed bodies that
  !> active contacts touch, numbered in order of first appearance.
  subroutine mesh2_pack_load(p, m, n, active, md1, md2, bd1, bd2)
    type(mesh2_pack_t), intent(inout) :: p
    type(mailx_t), intent(in) :: m
    integer, intent(in) :: n, md1(:), md2(:), bd1(:), bd2(:)
    logical, intent(in) :: active(:)
    integer :: k, sd, bm, total, j
    call grow(p%moff, m%n)
    p%moff = -1
    total = 0
    do k = 1, n
      if (.not. active(k)) cycle
      do sd = 1, 2
        if (side_of(sd, md1(k), md2(k)) /= bm_mesh) cycle
        bm = side_of(sd, bd1(k), bd2(k))
        if (p%moff(bm) >= 0) cycle
        p%moff(bm) = total
        total = total + p%gm(sd, k)
      end do
    end do
    call grow(p%mv, total)
    do bm = 1, m%n
      if (p%moff(bm) < 0) cycle
      do j = 1, p%nact(bm)
        p%mv(p%moff(bm) + 2 * j - 1:p%moff(bm) + 2 * j) = m%vfree(:, p%anodes(p%abase(bm) + j))
      end do
    end do
  end subroutine mesh2_pack_load

  !> The side record of meshed side sd of contact k (body ib, nodes(2), weights
  !> wts(2)) in the mixed kernel (gs_sweep_mesh): kind and G offset, the node
  !> slots in mv, the signed weights, the body's contact dofs and first slot.
  pure subroutine mesh2_pack_side(p, k, sd, ib, nodes, wts, side, slot, wt, gm, first)
    type(mesh2_pack_t), intent(in) :: p
    integer, intent(in) :: k, sd, ib, nodes(2)
    real(wp), intent(in) :: wts(2)
    integer, intent(out) :: side(2), slot(2), gm, first
    real(wp), intent(out) :: wt(2)
    side(1) = bm_mesh
    side(2) = p%goff(sd, k)
    gm = p%gm(sd, k)
    first = p%moff(ib) + 1
    slot(1) = p%moff(ib) + 2 * p%aslot(nodes(1)) - 1
    slot(2) = p%moff(ib) + 2 * p%aslot(nodes(2)) - 1
    wt = merge(1.0_wp, -1.0_wp, sd == 1) * wts
  end subroutine mesh2_pack_side

  !> Impulse (rt, rn) of contact k on its meshed side sd (body ib): mv += G r.
  pure subroutine mesh2_pack_impulse(p, k, sd, ib, rt, rn)
    type(mesh2_pack_t), intent(inout) :: p
    integer, intent(in) :: k, sd, ib
    real(wp), intent(in) :: rt, rn
    call mesh2_add_impulse(p%mv, p%gmat, p%goff(sd, k), p%moff(ib), p%gm(sd, k), rt, rn)
  end subroutine mesh2_pack_impulse

  !> Velocities of the meshed bodies from the contact impulses r on their nodes
  !> (the active contacts' meshed sides).
  subroutine mesh2_unpack(m, n, active, md1, md2, mnode, mwt, frame, r)
    type(mailx_t), intent(inout) :: m
    integer, intent(in) :: n, md1(:), md2(:), mnode(:, :)
    logical, intent(in) :: active(:)
    real(wp), intent(in) :: mwt(:, :), frame(:, :, :), r(:, :)
    integer :: k, sd, i
    real(wp), allocatable :: imp(:, :)
    real(wp) :: q(2), sgn
    allocate (imp(2, m%nnodes))
    imp = 0.0_wp
    do k = 1, n
      if (.not. active(k)) cycle
      call frame2_global(frame(1, 2, k), frame(2, 2, k), r(1, k), r(2, k), q(1), q(2))
      do sd = 1, 2
        if (side_of(sd, md1(k), md2(k)) /= bm_mesh) cycle
        sgn = merge(1.0_wp, -1.0_wp, sd == 1)
        do i = 2 * sd - 1, 2 * sd
          call mesh2_add_node(sgn * mwt(i, k), q(1), q(2), imp(1, mnode(i, k)), imp(2, mnode(i, k)))
        end do
      end do
    end do
    call mailx_velocity_from_impulses(m, imp)
  end subroutine mesh2_unpack
end module fracas_mailx_side
