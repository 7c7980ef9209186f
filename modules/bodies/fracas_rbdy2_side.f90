!> The contact side of a rigid 2D body (rbdy2): H rows, Delassus part, local
!> velocity and impulse of a contact on the body's dofs (rbdy2_side.inc), and the
!> model's part of the sweep kernels' workspace (rigid2_pack_t: the bodies the
!> active contacts touch, their side records, warm start, unpacking). The body
!> model knows no contact: it is given the frame, lever arms and body numbers.
module fracas_rbdy2_side
  use fracas_kinds, only: wp
  use fracas_ids, only: bm_rigid
  use fracas_grow, only: grow
  use fracas_frame_2d, only: frame2_local, frame2_global
  use fracas_rbdy2, only: rbdy2_t
  implicit none
  private
  public :: rigid2_h_rows, rigid2_add_delassus, rigid2_add_spin, rigid2_pair_velocity, rigid2_moment, &
            rigid2_add_impulse, rigid2_point_velocity, rigid2_add_velocity, rigid2_side_impulse, &
            rigid2_pair_impulse, rigid2_levers
  public :: rigid2_pack_t, rigid2_pack_reserve, rigid2_pack_add, rigid2_pack_load, rigid2_pack_side, &
            rigid2_pack_impulse, rigid2_unpack

  !> The rigid bodies in the sweep kernels' workspace: those the active contacts
  !> touch, numbered in the order they are added (first appearance in the stored
  !> contact order, so that neighbours are close in memory), one record
  !> rec = (v(3), inverse mass(3)) each.
  type :: rigid2_pack_t
    integer :: n = 0                         !< bodies packed
    integer, allocatable :: slot(:)          !< (nb) slot of each body in rec (0: none; kept zero between packs)
    integer, allocatable :: list(:)          !< (n) body of each slot
    real(wp), allocatable :: rec(:, :)       !< (6,n) velocity and inverse mass
  end type rigid2_pack_t

contains
  include 'rbdy2_side.inc'

  !> Room for every body of b (the slot map starts empty).
  subroutine rigid2_pack_reserve(p, b)
    type(rigid2_pack_t), intent(inout) :: p
    type(rbdy2_t), intent(in) :: b
    call grow(p%slot, b%n, fill=0)     ! kept zero between packs (rigid2_unpack)
    call grow(p%list, b%n)
    call grow(p%rec, 6, b%n)
  end subroutine rigid2_pack_reserve

  !> Body ib in the workspace (a slot if it has none yet).
  subroutine rigid2_pack_add(p, ib)
    type(rigid2_pack_t), intent(inout) :: p
    integer, intent(in) :: ib
    if (p%slot(ib) /= 0) return
    p%n = p%n + 1
    p%slot(ib) = p%n
    p%list(p%n) = ib
  end subroutine rigid2_pack_add

  !> The packed bodies' records from their velocities and inverse masses.
  subroutine rigid2_pack_load(p, b)
    type(rigid2_pack_t), intent(inout) :: p
    type(rbdy2_t), intent(in) :: b
    integer :: j, ib
    do j = 1, p%n
      ib = p%list(j)
      p%rec(1:3, j) = b%v(:, ib)
      p%rec(4:6, j) = b%inv_mass(:, ib)
    end do
  end subroutine rigid2_pack_load

  !> The side record of a rigid side of body ib in the mixed kernel
  !> (gs_sweep_mesh): its kind and slot; no nodes.
  pure subroutine rigid2_pack_side(p, ib, side, slot, wt, gm, first)
    type(rigid2_pack_t), intent(in) :: p
    integer, intent(in) :: ib
    integer, intent(out) :: side(2), slot(2), gm, first
    real(wp), intent(out) :: wt(2)
    side(1) = bm_rigid
    side(2) = p%slot(ib)
    slot = 0
    wt = 0.0_wp
    gm = 0
    first = 0
  end subroutine rigid2_pack_side

  !> Impulse (rt, rn) on a rigid side of body ib (sign sgn, lever arms lev), in
  !> the packed record.
  subroutine rigid2_pack_impulse(p, ib, sgn, n1, n2, lev, rt, rn)
    type(rigid2_pack_t), intent(inout) :: p
    integer, intent(in) :: ib
    real(wp), intent(in) :: sgn, n1, n2, lev(2), rt, rn
    call rigid2_side_impulse(p%rec(:, p%slot(ib)), sgn, n1, n2, lev, rt, rn)
  end subroutine rigid2_pack_impulse

  !> Velocities back to the bodies; the slot map is cleared for the next pack.
  subroutine rigid2_unpack(p, b)
    type(rigid2_pack_t), intent(inout) :: p
    type(rbdy2_t), intent(inout) :: b
    integer :: j, ib
    do j = 1, p%n
      ib = p%list(j)
      b%v(:, ib) = p%rec(1:3, j)
      p%slot(ib) = 0
    end do
    p%n = 0
  end subroutine rigid2_unpack
end module fracas_rbdy2_side
