!> The 2D contact sides: where the scene NLGS (fracas_nlgs) meets the body models,
!> and the only place it does. Each model's part is its side module's (rigid:
!> fracas_rbdy2_side, meshed: fracas_mailx_side): its workspace in the sweep
!> kernels, the side record of a contact, its part of the Delassus block, the warm
!> start, the unpacking of the impulses, the local velocity. Here each operation
!> selects that part by the side's model (an integer, bm_* of fracas_ids) when the
!> contacts are prepared or packed, never in a sweep, and each contact goes to the
!> sweep kernel of its pair of side models (fracas_local_solver: rigid-rigid to the
!> packed rigid kernel, the others to the mixed kernel). A new 2D body model is
!> registered here: its member of sides2_t and its case in each select (the list
!> is in doc/architecture.md, "Adding a body model").
module fracas_sides_2d
  use fracas_kinds, only: wp, i8
  use fracas_ids, only: bm_rigid, bm_mesh
  use fracas_grow, only: grow
  use fracas_rbdy2, only: rbdy2_t
  use fracas_rbdy2_side, only: rigid2_pack_t, rigid2_pack_reserve, rigid2_pack_add, rigid2_pack_load, &
                               rigid2_pack_side, rigid2_pack_impulse, rigid2_unpack
  use fracas_mailx, only: mailx_t
  use fracas_mailx_side, only: mesh2_pack_t, mesh2_pack_blocks, mesh2_add_delassus, mesh2_pack_load, &
                               mesh2_pack_side, mesh2_pack_impulse, mesh2_unpack
  use fracas_contacts, only: contacts_t, mesh_side_nodes
  use fracas_local_solver, only: gs_sweep_2d_packed, gs_sweep_mesh, pk_size
  implicit none
  private
  public :: bodies2_t, sides2_t, contact_velocity, rigid_pair, sides2_prepare, sides2_delassus, &
            sides2_begin_velocities, sides2_reserve, sides2_pack_bodies, sides2_pack_contacts, sides2_unpack_contacts, &
            sides2_sweep, sides2_unpack_bodies, sides2_local_velocities, sides2_restart_velocities, sides2_rigid_bodies

  !> The scene's 2D body models as the NLGS sees them: one pointer per model
  !> (the scene's own objects), so that the NLGS passes them on without naming
  !> them.
  type :: bodies2_t
    type(rbdy2_t), pointer :: rbdy2 => null()
    type(mailx_t), pointer :: mailx => null()
  end type bodies2_t

  !> The sweep kernels' workspace: each body model's part, and the contacts packed
  !> for each kernel in the current sweep order. Packed rigid kernel (two rigid
  !> sides): contact pidx(j), record pc(:, j), bodies pb(:, j) (slots of
  !> rigid%rec), column pcoh(j) of c%coh (0: not cohesive), impulse pr, status pst.
  !> Mixed kernel (a meshed side): the same in g*, and per side s the side record
  !> gside(2s-1:2s) (model, place), gslot/gwt (node slots, signed weights),
  !> ggm/gfirst (the body's contact dofs) (see gs_sweep_mesh).
  type :: sides2_t
    type(rigid2_pack_t) :: rigid
    type(mesh2_pack_t) :: mesh
    integer :: np = 0
    logical :: any_coh = .false.           !< some contact of the packed rigid kernel is cohesive
    integer, allocatable :: pidx(:), pb(:, :), pcoh(:), pst(:)
    real(wp), allocatable :: pc(:, :), pr(:, :)
    integer :: ng = 0
    integer, allocatable :: gidx(:), gside(:, :), ggm(:, :), gfirst(:, :), gslot(:, :), gcoh(:), gst(:)
    real(wp), allocatable :: gc(:, :), gwt(:, :), gr(:, :)
  end type sides2_t

contains

  ! The body models' contact sides, included (as in fracas_local_solver) so that the
  ! per-contact loops here inline them: contact_velocity runs for every contact
  ! twice per solve, and out of line it cost 2 % of deposit_1000's solve time.
  include '../shared/frame_2d.inc'
  include '../bodies/rbdy2_side.inc'
  include '../bodies/mailx_side.inc'

  pure integer function side_model(c, k, s)
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: k, s
    side_model = merge(c%cdm(k), c%anm(k), s == 1)
  end function side_model

  pure integer function side_body(c, k, s)
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: k, s
    side_body = merge(c%cdb(k), c%anb(k), s == 1)
  end function side_body

  !> Contact k goes to the packed rigid kernel (two rigid sides).
  pure logical function rigid_pair(c, k)
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: k
    rigid_pair = c%cdm(k) == bm_rigid .and. c%anm(k) == bm_rigid
  end function rigid_pair

  !> Relative velocity (t, n) at contact k for rigid body velocities v and
  !> mesh node velocities vm: the sides' point velocities (candidate minus
  !> antagonist) in the frame, then the rigid sides' spin.
  pure function contact_velocity(c, k, v, vm) result(u)
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: k
    real(wp), intent(in) :: v(:, :), vm(:, :)
    real(wp) :: u(2), dv(2), p(2)
    integer :: sd
    do sd = 1, 2
      select case (side_model(c, k, sd))
      case (bm_rigid)
        p = v(1:2, side_body(c, k, sd))
      case (bm_mesh)
        p = mesh2_point_velocity(vm(:, c%mnode(2 * sd - 1, k)), vm(:, c%mnode(2 * sd, k)), c%mwt(2 * sd - 1, k), &
                                 c%mwt(2 * sd, k))
      end select
      if (sd == 1) then
        dv = p
      else
        dv = dv - p
      end if
    end do
    call frame2_local(c%frame(1, 2, k), c%frame(2, 2, k), dv(1), dv(2), u(1), u(2))
    do sd = 1, 2
      select case (side_model(c, k, sd))
      case (bm_rigid)
        call rigid2_add_spin(merge(1.0_wp, -1.0_wp, sd == 1), v(3, side_body(c, k, sd)), c%lever(2 * sd - 1, k), &
                             c%lever(2 * sd, k), u(1), u(2))
      end select
    end do
  end function contact_velocity

  !> u(:, k) = the local velocity of every contact for the bodies' velocities at
  !> the beginning of the step (begin) or now.
  subroutine sides2_local_velocities(c, bd, begin, u)
    type(contacts_t), intent(in) :: c
    type(bodies2_t), intent(in) :: bd
    logical, intent(in) :: begin
    real(wp), intent(inout) :: u(:, :)
    integer :: k
    if (begin) then
      do k = 1, c%n
        u(:, k) = contact_velocity(c, k, bd%rbdy2%vbegin, bd%mailx%vbegin)
      end do
    else
      do k = 1, c%n
        u(:, k) = contact_velocity(c, k, bd%rbdy2%v, bd%mailx%v)
      end do
    end if
  end subroutine sides2_local_velocities

  !> The bodies back at their free velocities (a solve started again; the
  !> meshes' velocities follow from the impulses at unpacking).
  subroutine sides2_restart_velocities(bd)
    type(bodies2_t), intent(in) :: bd
    bd%rbdy2%v = bd%rbdy2%vfree
  end subroutine sides2_restart_velocities

  !> The number of bodies the packed rigid kernel's contacts index (c%cdb, c%anb).
  pure integer function sides2_rigid_bodies(bd) result(n)
    type(bodies2_t), intent(in) :: bd
    n = bd%rbdy2%n
  end function sides2_rigid_bodies

  !> The models' data of the step's contacts (meshes: active nodes, G = C H^T).
  subroutine sides2_prepare(ws, c, bd)
    type(sides2_t), intent(inout) :: ws
    type(contacts_t), intent(in) :: c
    type(bodies2_t), intent(in) :: bd
    if (c%with_mesh) call mesh2_pack_blocks(ws%mesh, bd%mailx, c%n, c%cdm, c%anm, c%cdb, c%anb, c%mnode, c%mwt, c%frame)
  end subroutine sides2_prepare

  !> Contact k's Delassus block c%w(:, k) = sum over its sides of H M~^-1 H^T
  !> (rigid sides from the inverse masses and lever arms; meshed sides H G, with
  !> the cross terms of a contact of a body with itself).
  subroutine sides2_delassus(ws, c, k, bd)
    type(sides2_t), intent(in) :: ws
    type(contacts_t), intent(inout) :: c
    integer, intent(in) :: k
    type(bodies2_t), intent(in) :: bd
    integer :: sd
    c%w(:, k) = 0.0_wp
    do sd = 1, 2
      select case (side_model(c, k, sd))
      case (bm_rigid)
        call rigid2_add_delassus(bd%rbdy2%inv_mass(:, side_body(c, k, sd)), c%frame(1, 2, k), c%frame(2, 2, k), &
                                 c%lever(2 * sd - 1, k), c%lever(2 * sd, k), c%w(:, k))
      end select
    end do
    c%w(3, k) = c%w(2, k)
    if (c%cdm(k) == bm_mesh .or. c%anm(k) == bm_mesh) &
      call mesh2_add_delassus(ws%mesh, k, [c%cdm(k), c%anm(k)], [c%cdb(k), c%anb(k)], c%mnode(:, k), c%mwt(:, k), &
                              c%frame(:, 2, k), c%w(:, k))
  end subroutine sides2_delassus

  !> Room for n contacts and the bodies of bd in the workspace.
  subroutine sides2_reserve(ws, n, bd)
    type(sides2_t), intent(inout) :: ws
    integer, intent(in) :: n
    type(bodies2_t), intent(in) :: bd
    call grow(ws%pidx, n)
    call grow(ws%pc, pk_size, n)
    call grow(ws%pb, 2, n)
    call grow(ws%pcoh, n)
    call grow(ws%pr, 2, n)
    call grow(ws%pst, n)
    call rigid2_pack_reserve(ws%rigid, bd%rbdy2)
  end subroutine sides2_reserve

  !> Free local velocities qfree = u(v) + shift, with the warm start of the rigid
  !> pairs added to the bodies contact by contact (each contact's qfree sees the
  !> impulses of the contacts before it, as it always has), and the velocity scale
  !> of the step from qfree and the rigid sides' free speeds.
  subroutine sides2_begin_velocities(c, bd, qfree, vscale)
    type(contacts_t), intent(in) :: c
    type(bodies2_t), intent(in) :: bd
    real(wp), intent(inout) :: qfree(:, :)
    real(wp), intent(out) :: vscale
    integer :: k, sd
    real(wp) :: px, py
    associate (b => bd%rbdy2, m => bd%mailx)
    do k = 1, c%n
      qfree(:, k) = contact_velocity(c, k, b%v, m%vfree) + c%shift(:, k)
      if (c%active(k) .and. rigid_pair(c, k)) then
        call frame2_global(c%frame(1, 2, k), c%frame(2, 2, k), c%r(1, k), c%r(2, k), px, py)
        call rigid2_add_impulse(b%v(:, c%cdb(k)), b%inv_mass(:, c%cdb(k)), 1.0_wp, px, py, &
                                rigid2_moment(c%r(1, k), c%r(2, k), c%lever(1, k), c%lever(2, k)))
        call rigid2_add_impulse(b%v(:, c%anb(k)), b%inv_mass(:, c%anb(k)), -1.0_wp, px, py, &
                                rigid2_moment(c%r(1, k), c%r(2, k), c%lever(3, k), c%lever(4, k)))
      end if
    end do
    vscale = 0.0_wp
    do k = 1, c%n
      vscale = vscale + sum(qfree(:, k)**2)
      do sd = 1, 2
        select case (side_model(c, k, sd))
        case (bm_rigid)
          vscale = vscale + sum(b%vfree(1:2, side_body(c, k, sd))**2)
        end select
      end do
    end do
    if (c%n > 0) vscale = sqrt(vscale / c%n)
    end associate
  end subroutine sides2_begin_velocities

  !> The bodies the active contacts touch into the workspace, in order of first
  !> appearance in the stored contact order (rigid: velocity and inverse mass;
  !> meshes: the contact-dof free velocities), then the warm-start impulses of the
  !> contacts of the mixed kernel on their sides (the rigid pairs' are in the
  !> bodies already: sides2_begin_velocities).
  subroutine sides2_pack_bodies(ws, c, bd)
    type(sides2_t), intent(inout) :: ws
    type(contacts_t), intent(in) :: c
    type(bodies2_t), intent(in) :: bd
    integer :: k, sd, n
    n = c%n
    ws%rigid%n = 0
    do k = 1, n
      if (.not. c%active(k)) cycle
      do sd = 1, 2
        select case (side_model(c, k, sd))
        case (bm_rigid)
          call rigid2_pack_add(ws%rigid, side_body(c, k, sd))
        end select
      end do
    end do
    call rigid2_pack_load(ws%rigid, bd%rbdy2)
    if (.not. c%with_mesh) return
    call mesh2_pack_load(ws%mesh, bd%mailx, n, c%active, c%cdm, c%anm, c%cdb, c%anb)
    call grow(ws%gidx, n)
    call grow(ws%gside, 4, n)
    call grow(ws%ggm, 2, n)
    call grow(ws%gfirst, 2, n)
    call grow(ws%gslot, 2 * mesh_side_nodes(2), n)
    call grow(ws%gcoh, n)
    call grow(ws%gst, n)
    call grow(ws%gc, pk_size, n)
    call grow(ws%gwt, 2 * mesh_side_nodes(2), n)
    call grow(ws%gr, 2, n)
    do k = 1, n
      if (.not. c%active(k) .or. rigid_pair(c, k)) cycle
      if (all(c%r(:, k) == 0.0_wp)) cycle
      do sd = 1, 2
        select case (side_model(c, k, sd))
        case (bm_rigid)
          call rigid2_pack_impulse(ws%rigid, side_body(c, k, sd), merge(1.0_wp, -1.0_wp, sd == 1), &
                                   c%frame(1, 2, k), c%frame(2, 2, k), c%lever(2 * sd - 1:2 * sd, k), c%r(1, k), c%r(2, k))
        case (bm_mesh)
          call mesh2_pack_impulse(ws%mesh, k, sd, side_body(c, k, sd), c%r(1, k), c%r(2, k))
        end select
      end do
    end do
  end subroutine sides2_pack_bodies

  !> Records of the active contacts in the sweep order order(:): rigid pairs
  !> for the packed kernel, contacts with a meshed side for the mixed kernel.
  subroutine sides2_pack_contacts(ws, c, order)
    type(sides2_t), intent(inout) :: ws
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: order(:)
    integer :: ii, k, j, jg, sd
    j = 0
    jg = 0
    do ii = 1, size(order)
      k = order(ii)
      if (.not. c%active(k)) cycle
      if (rigid_pair(c, k)) then
        j = j + 1
        ws%pidx(j) = k
        ws%pb(1, j) = ws%rigid%slot(c%cdb(k))
        ws%pb(2, j) = ws%rigid%slot(c%anb(k))
        call record(c, k, ws%pc(:, j), ws%pcoh(j))
        ws%pr(:, j) = c%r(:, k)
        ws%pst(j) = c%status(k)
      else
        jg = jg + 1
        ws%gidx(jg) = k
        call record(c, k, ws%gc(:, jg), ws%gcoh(jg))
        ws%gr(:, jg) = c%r(:, k)
        ws%gst(jg) = c%status(k)
        do sd = 1, 2
          associate (side => ws%gside(2 * sd - 1:2 * sd, jg), slot => ws%gslot(2 * sd - 1:2 * sd, jg), &
                     wt => ws%gwt(2 * sd - 1:2 * sd, jg))
            select case (side_model(c, k, sd))
            case (bm_rigid)
              call rigid2_pack_side(ws%rigid, side_body(c, k, sd), side, slot, wt, ws%ggm(sd, jg), ws%gfirst(sd, jg))
            case (bm_mesh)
              call mesh2_pack_side(ws%mesh, k, sd, side_body(c, k, sd), c%mnode(2 * sd - 1:2 * sd, k), &
                                   c%mwt(2 * sd - 1:2 * sd, k), side, slot, wt, ws%ggm(sd, jg), ws%gfirst(sd, jg))
            end select
          end associate
        end do
      end if
    end do
    ws%np = j
    ws%ng = jg
    ws%any_coh = any(ws%pcoh(1:j) /= 0)
  end subroutine sides2_pack_contacts

  !> The packed record of contact k (see gs_sweep_2d_packed) and its column of c%coh.
  subroutine record(c, k, rec, icoh)
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: k
    real(wp), intent(out) :: rec(pk_size)
    integer, intent(out) :: icoh
    rec(1:2) = c%frame(:, 2, k)
    rec(3:6) = c%lever(:, k)
    rec(7:10) = c%w(:, k)
    rec(11:16) = c%wi(:, k)
    rec(17:18) = c%shift(:, k)
    rec(19) = c%mu(k)
    rec(20) = 0.0_wp
    icoh = 0
    if (c%cohesive(k)) icoh = k
  end subroutine record

  !> Impulses and statuses back to the contact store.
  subroutine sides2_unpack_contacts(ws, c)
    type(sides2_t), intent(in) :: ws
    type(contacts_t), intent(inout) :: c
    integer :: j, k
    do j = 1, ws%np
      k = ws%pidx(j)
      c%r(:, k) = ws%pr(:, j)
      c%status(k) = ws%pst(j)
    end do
    do j = 1, ws%ng
      k = ws%gidx(j)
      c%r(:, k) = ws%gr(:, j)
      c%status(k) = ws%gst(j)
    end do
  end subroutine sides2_unpack_contacts

  !> One Gauss–Seidel sweep over the packed contacts, each kernel in turn; with
  !> check, LMGC90's norm sums of this sweep (sums, maxes).
  subroutine sides2_sweep(ws, c, relax, check, evaluate_only, sums, maxes)
    type(sides2_t), intent(inout) :: ws
    type(contacts_t), intent(inout) :: c
    real(wp), intent(in) :: relax
    logical, intent(in) :: check, evaluate_only
    real(wp), intent(out) :: sums(6), maxes(2)
    real(wp) :: g6(6), gmax(2)
    call gs_sweep_2d_packed(ws%np, ws%pb, ws%pc, ws%pcoh, ws%any_coh, c%coh, ws%pr, ws%pst, ws%rigid%rec, &
                            relax, check, sums, maxes, evaluate_only)
    if (ws%ng > 0) then
      call gs_sweep_mesh(ws%ng, ws%gc, ws%gside, ws%ggm, ws%gfirst, ws%gslot, ws%gwt, &
                         ws%gcoh, c%coh, ws%gr, ws%gst, ws%rigid%rec, ws%mesh%mv, ws%mesh%gmat, &
                         relax, check, g6, gmax, evaluate_only)
      sums = sums + g6
      maxes = max(maxes, gmax)
    end if
  end subroutine sides2_sweep

  !> The bodies' velocities from the workspace (rigid) and from the contact
  !> impulses (meshes: one solve per body; seconds its wall time).
  subroutine sides2_unpack_bodies(ws, c, bd, seconds)
    type(sides2_t), intent(inout) :: ws
    type(contacts_t), intent(in) :: c
    type(bodies2_t), intent(in) :: bd
    real(wp), intent(out) :: seconds
    integer(i8) :: t0, t1, rate
    call rigid2_unpack(ws%rigid, bd%rbdy2)
    seconds = 0.0_wp
    if (.not. c%with_mesh) return
    call system_clock(t0, rate)
    call mesh2_unpack(bd%mailx, c%n, c%active, c%cdm, c%anm, c%mnode, c%mwt, c%frame, c%r)
    call system_clock(t1)
    seconds = real(t1 - t0, wp) / real(rate, wp)
  end subroutine sides2_unpack_bodies
end module fracas_sides_2d
