!> The contact store shared by all interaction types: flat arrays over
!> contacts (structure of arrays), filled by the detection and read by the
!> solver. Also the history of the previous step (warm start, statuses),
!> indexed by candidate contactor so a new contact finds its past in O(1).
module fracas_contacts
  use fracas_kinds, only: wp
  use fracas_contact_laws, only: coh_size, n_internals
  implicit none
  private
  public :: contacts_t, history_t, contacts_reserve, contacts_clear, history_from_contacts, &
            history_find, history_find_near, history_build, history_knows_pair, &
            rigid_lever_size, mesh_side_nodes, wi_size

  ! Per-contact sizes in dimension nd (arrays indexed by nd, so a 2D kernel's sizes
  ! are constants): what a side model keeps per contact side, and what the local
  ! solver keeps of the block it solves with.
  !> A rigid side: (P - c) x each frame vector, for each rotation dof (1 in 2D, 3 in 3D).
  integer, parameter :: rigid_lever_size(2:3) = [2, 9]
  !> A meshed side: the nodes (and weights) that give its point (an edge's 2 in 2D,
  !> a face's up to 4 in 3D).
  integer, parameter :: mesh_side_nodes(2:3) = [2, 4]
  !> The local solver's precomputed inverse (fracas_local_solver: inverse_block in 2D,
  !> inverse_block_3d in 3D).
  integer, parameter :: wi_size(2:3) = [6, 9]

  !> Contacts of one scene, all of one dimension nd (2 or 3). Local vectors are
  !> ordered tangential part first, normal last ((t, n); (t1, t2, n)) and local
  !> blocks stored by rows (fracas_contact_laws).
  type :: contacts_t
    integer :: n = 0
    integer :: nd = 2                        !< dimension; set before contacts_reserve
    logical :: with_cohesion = .false.       !< cohesive laws (or IQS_CLB_g0) in the scene: internals and coh are allocated
    integer, allocatable :: inter(:)         !< interaction type id (fracas_ids)
    integer, allocatable :: cd(:), an(:)     !< candidate / antagonist contactor
    integer, allocatable :: cdb(:), anb(:)   !< their bodies (index within their model)
    integer, allocatable :: cdm(:), anm(:)   !< their body models (bm_rigid, bm_mesh)
    integer, allocatable :: law(:)           !< index in the law table
    integer, allocatable :: sub(:)           !< key of the contact within its pair (candidate polygon vertex, else 0)
    integer, allocatable :: cdver(:), anseg(:)  !< polygon vertex / edge involved (0 if none)
    integer, allocatable :: status(:), status_begin(:)
    !> (nd,nd,n) local frame, columns the tangent(s) then the normal n (from antagonist
    !> to candidate); 2D: (t, n), t = (n2, -n1)
    real(wp), allocatable :: frame(:, :, :)
    real(wp), allocatable :: point(:, :)     !< (nd,n) contact point (detection configuration)
    real(wp), allocatable :: gap(:)          !< gap at the detection configuration
    !> (2 rigid_lever_size(nd), n) lever arms of the rigid sides, candidate then
    !> antagonist; 2D: (P-c_cd)x t, (P-c_cd)x n, (P-c_an)x t, (P-c_an)x n
    real(wp), allocatable :: lever(:, :)
    real(wp), allocatable :: w(:, :)         !< (nd*nd,n) Delassus block by rows (2D: tt, tn, nt, nn)
    real(wp), allocatable :: shift(:, :)     !< (nd,n) law shift of the local velocity
    real(wp), allocatable :: mu(:)           !< friction this step
    logical, allocatable :: active(:)        !< .false.: no reaction this step (open RST contact)
    real(wp), allocatable :: r(:, :)         !< (nd,n) impulses (t, n)
    real(wp), allocatable :: u(:, :)         !< (nd,n) relative velocity at the end of the step
    real(wp), allocatable :: u_begin(:, :)   !< (nd,n) relative velocity at the beginning
    real(wp), allocatable :: wi(:, :)        !< (wi_size(nd),n) what the local solver needs of its (effective) W
    real(wp), allocatable :: length(:)       !< length carried by the contact point (cohesive laws)
    ! Cohesive contacts: internals (L, the jumps, beta, time damage started) as
    ! LMGC90 writes them, and the step data of the cohesive impulse eliminated
    ! locally (fracas_contact_laws: n_internals, coh_size).
    real(wp), allocatable :: internals(:, :) !< (n_internals(nd),n)
    logical, allocatable :: cohesive(:)
    real(wp), allocatable :: coh(:, :)       !< (coh_size(nd),n)
    ! Meshed sides (scenes with meshes only): the nodes (mesh node numbers)
    ! and weights that give the velocity of the contact point on each side:
    ! 2D: v = mwt(1) v(mnode(1)) + mwt(2) v(mnode(2)) for the candidate, 3:4 for
    ! the antagonist; 0 nodes on a rigid side.
    logical :: with_mesh = .false.
    integer, allocatable :: mnode(:, :)      !< (2 mesh_side_nodes(nd),n)
    real(wp), allocatable :: mwt(:, :)       !< (2 mesh_side_nodes(nd),n)
  end type contacts_t

  !> Contacts of the previous step, grouped by candidate contactor.
  type :: history_t
    integer :: n = 0
    integer, allocatable :: first(:)         !< (ntactors+1) offsets into the lists
    integer, allocatable :: inter(:), an(:), sub(:), status(:)
    real(wp), allocatable :: force(:, :)     !< (nd,n) reaction / time step
    real(wp), allocatable :: point(:, :)     !< (nd,n) contact point
    real(wp), allocatable :: internals(:, :) !< (n_internals(nd),n)
  end type history_t

contains

  !> Make room for at least n contacts (keeps nothing: the store is refilled each step),
  !> each array with the extents of dimension c%nd.
  subroutine contacts_reserve(c, n)
    type(contacts_t), intent(inout) :: c
    integer, intent(in) :: n
    integer :: cap, nd
    if (allocated(c%inter)) then
      if (size(c%inter) >= n) return
      call free_all()
    end if
    cap = max(16, n + n / 2)
    nd = c%nd
    allocate (c%inter(cap), c%cd(cap), c%an(cap), c%cdb(cap), c%anb(cap), c%cdm(cap), c%anm(cap), c%law(cap), c%sub(cap), &
              c%cdver(cap), c%anseg(cap), c%status(cap), &
              c%status_begin(cap), c%frame(nd, nd, cap), c%point(nd, cap), c%gap(cap), &
              c%lever(2 * rigid_lever_size(nd), cap), c%w(nd * nd, cap), c%shift(nd, cap), c%mu(cap), c%active(cap), &
              c%r(nd, cap), c%u(nd, cap), c%u_begin(nd, cap), c%wi(wi_size(nd), cap), c%length(cap), c%cohesive(cap))
    ! Only a scene with cohesive laws pays for their per-contact state.
    if (c%with_cohesion) then
      allocate (c%internals(n_internals(nd), cap), c%coh(coh_size(nd), cap))
    else
      allocate (c%internals(n_internals(nd), 0), c%coh(coh_size(nd), 0))
    end if
    if (c%with_mesh) then
      allocate (c%mnode(2 * mesh_side_nodes(nd), cap), c%mwt(2 * mesh_side_nodes(nd), cap))
    else
      allocate (c%mnode(2 * mesh_side_nodes(nd), 0), c%mwt(2 * mesh_side_nodes(nd), 0))
    end if
  contains
    subroutine free_all()
      deallocate (c%inter, c%cd, c%an, c%cdb, c%anb, c%cdm, c%anm, c%law, c%sub, c%cdver, c%anseg, c%status, &
                  c%status_begin, c%frame, &
                  c%point, c%gap, c%lever, c%w, c%shift, c%mu, c%active, c%r, c%u, c%u_begin, c%wi, &
                  c%length, c%internals, c%cohesive, c%coh, c%mnode, c%mwt)
    end subroutine free_all
  end subroutine contacts_reserve

  subroutine contacts_clear(c)
    type(contacts_t), intent(inout) :: c
    c%n = 0
  end subroutine contacts_clear

  !> Group records (cd, an, sub, inter, status, force) by candidate contactor.
  !> force and point (nd, n); internals (n_internals(nd), n) only for scenes with
  !> cohesive laws.
  subroutine history_build(hist, ntactors, cd, an, sub, inter, status, force, point, internals)
    type(history_t), intent(out) :: hist
    integer, intent(in) :: ntactors, cd(:), an(:), sub(:), inter(:), status(:)
    real(wp), intent(in) :: force(:, :), point(:, :)
    real(wp), intent(in), optional :: internals(:, :)
    integer :: k, n, pos
    integer, allocatable :: fill(:)
    n = size(cd)
    hist%n = n
    allocate (hist%first(ntactors + 1), hist%inter(n), hist%an(n), hist%sub(n), hist%status(n), &
              hist%force(size(force, 1), n), hist%point(size(point, 1), n))
    if (present(internals)) allocate (hist%internals(size(internals, 1), n))
    hist%first = 0
    do k = 1, n
      hist%first(cd(k) + 1) = hist%first(cd(k) + 1) + 1
    end do
    hist%first(1) = 1
    do k = 1, ntactors
      hist%first(k + 1) = hist%first(k + 1) + hist%first(k)
    end do
    fill = hist%first(1:ntactors)
    do k = 1, n
      pos = fill(cd(k))
      fill(cd(k)) = pos + 1
      hist%inter(pos) = inter(k)
      hist%an(pos) = an(k)
      hist%sub(pos) = sub(k)
      hist%status(pos) = status(k)
      hist%force(:, pos) = force(:, k)
      hist%point(:, pos) = point(:, k)
      if (present(internals)) hist%internals(:, pos) = internals(:, k)
    end do
  end subroutine history_build

  !> History of the current contacts: reactions stored as forces (impulse / h).
  subroutine history_from_contacts(hist, c, ntactors, h)
    type(history_t), intent(out) :: hist
    type(contacts_t), intent(in) :: c
    integer, intent(in) :: ntactors
    real(wp), intent(in) :: h
    integer :: n
    n = c%n
    if (c%with_cohesion) then
      call history_build(hist, ntactors, c%cd(1:n), c%an(1:n), c%sub(1:n), c%inter(1:n), c%status(1:n), &
                         c%r(:, 1:n) / h, c%point(:, 1:n), c%internals(:, 1:n))
    else
      call history_build(hist, ntactors, c%cd(1:n), c%an(1:n), c%sub(1:n), c%inter(1:n), c%status(1:n), &
                         c%r(:, 1:n) / h, c%point(:, 1:n))
    end if
  end subroutine history_from_contacts

  !> True if contactors a and b were in contact at the previous step, in either
  !> role and at any point of the pair.
  pure logical function history_knows_pair(hist, a, b) result(known)
    type(history_t), intent(in) :: hist
    integer, intent(in) :: a, b
    known = has(a, b) .or. has(b, a)
  contains
    pure logical function has(cd, an)
      integer, intent(in) :: cd, an
      integer :: k
      has = .false.
      if (.not. allocated(hist%first)) return
      if (cd + 1 > size(hist%first)) return
      do k = hist%first(cd), hist%first(cd + 1) - 1
        if (hist%an(k) == an) has = .true.
      end do
    end function has
  end function history_knows_pair

  !> The past contact of the same type between contactors a and b, in either
  !> role, whose point is nearest to `point` and closer than tol; 0 if none.
  !> swapped tells that the past contact had a as antagonist (its tangential
  !> direction, reaction and jump then change sign). This keeps the history of
  !> a contact whose key changed: roles swapped or contact point moved to
  !> another vertex (LMGC90 matches by position for the same reason).
  pure subroutine history_find_near(hist, inter, a, b, point, tol, pos, swapped)
    type(history_t), intent(in) :: hist
    integer, intent(in) :: inter, a, b
    real(wp), intent(in) :: point(:), tol
    integer, intent(out) :: pos
    logical, intent(out) :: swapped
    real(wp) :: best, d
    integer :: k, side, cd, an
    pos = 0
    swapped = .false.
    best = tol
    if (.not. allocated(hist%first)) return
    do side = 1, 2
      cd = merge(a, b, side == 1)
      an = merge(b, a, side == 1)
      if (cd + 1 > size(hist%first)) cycle
      do k = hist%first(cd), hist%first(cd + 1) - 1
        if (hist%an(k) /= an .or. hist%inter(k) /= inter) cycle
        d = norm2(hist%point(:, k) - point)
        if (d < best) then
          best = d
          pos = k
          swapped = side == 2
        end if
      end do
    end do
  end subroutine history_find_near

  !> Index of the past contact (inter, cd, an, sub), 0 if there is none.
  pure integer function history_find(hist, inter, cd, an, sub) result(pos)
    type(history_t), intent(in) :: hist
    integer, intent(in) :: inter, cd, an, sub
    integer :: k
    pos = 0
    if (.not. allocated(hist%first)) return
    if (cd + 1 > size(hist%first)) return
    do k = hist%first(cd), hist%first(cd + 1) - 1
      if (hist%an(k) == an .and. hist%inter(k) == inter .and. hist%sub(k) == sub) then
        pos = k
        return
      end if
    end do
  end function history_find
end module fracas_contacts
