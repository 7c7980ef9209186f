!> The contact store shared by all interaction types: flat arrays over
!> contacts (structure of arrays), filled by the detection and read by the
!> solver. Also the history of the previous step (warm start, statuses),
!> indexed by candidate contactor so a new contact finds its past in O(1).
module fracas_contacts
  use fracas_kinds, only: wp
  use fracas_contact_laws, only: coh_size
  implicit none
  private
  public :: contacts_t, history_t, contacts_reserve, contacts_clear, history_from_contacts, &
            history_find, history_find_near, history_build, history_knows_pair, n_internals

  integer, parameter :: n_internals = 5   !< L, ut, un, beta, TPSini (2D cohesive laws)

  type :: contacts_t
    integer :: n = 0
    logical :: with_cohesion = .false.       !< cohesive laws (or IQS_CLB_g0) in the scene: internals and coh are allocated
    integer, allocatable :: inter(:)         !< interaction type id (fracas_ids)
    integer, allocatable :: cd(:), an(:)     !< candidate / antagonist contactor
    integer, allocatable :: cdb(:), anb(:)   !< their bodies (index within their model)
    integer, allocatable :: cdm(:), anm(:)   !< their body models (bm_rigid, bm_mesh)
    integer, allocatable :: law(:)           !< index in the law table
    integer, allocatable :: sub(:)           !< key of the contact within its pair (candidate polygon vertex, else 0)
    integer, allocatable :: cdver(:), anseg(:)  !< polygon vertex / edge involved (0 if none)
    integer, allocatable :: status(:), status_begin(:)
    real(wp), allocatable :: normal(:, :)    !< (2,n), from antagonist to candidate; t = (n2, -n1)
    real(wp), allocatable :: point(:, :)     !< (2,n) contact point (detection configuration)
    real(wp), allocatable :: gap(:)          !< gap at the detection configuration
    real(wp), allocatable :: lever(:, :)     !< (4,n): (P-c_cd)x t, (P-c_cd)x n, (P-c_an)x t, (P-c_an)x n
    real(wp), allocatable :: w(:, :)         !< (4,n) Delassus block: tt, tn, nt, nn
    real(wp), allocatable :: shift(:, :)     !< (2,n) law shift of the local velocity
    real(wp), allocatable :: mu(:)           !< friction this step
    logical, allocatable :: active(:)        !< .false.: no reaction this step (open RST contact)
    real(wp), allocatable :: r(:, :)         !< (2,n) impulses (t, n)
    real(wp), allocatable :: u(:, :)         !< (2,n) relative velocity at the end of the step
    real(wp), allocatable :: u_begin(:, :)   !< (2,n) relative velocity at the beginning
    real(wp), allocatable :: wi(:, :)        !< (6,n) what the local solver needs of its (effective) W
    real(wp), allocatable :: length(:)       !< length carried by the contact point (cohesive laws)
    ! Cohesive contacts: internals (L, ut, un, beta, time damage started) as
    ! LMGC90 writes them, and the step data of the cohesive impulse eliminated
    ! locally (fracas_contact_laws: coh_size).
    real(wp), allocatable :: internals(:, :) !< (n_internals,n)
    logical, allocatable :: cohesive(:)
    real(wp), allocatable :: coh(:, :)       !< (coh_size,n)
    ! Meshed sides (scenes with meshes only): the nodes (mesh node numbers)
    ! and weights that give the velocity of the contact point on each side:
    ! v = mwt(1) v(mnode(1)) + mwt(2) v(mnode(2)) for the candidate, 3:4 for
    ! the antagonist; 0 nodes on a rigid side.
    logical :: with_mesh = .false.
    integer, allocatable :: mnode(:, :)      !< (4,n)
    real(wp), allocatable :: mwt(:, :)       !< (4,n)
  end type contacts_t

  !> Contacts of the previous step, grouped by candidate contactor.
  type :: history_t
    integer :: n = 0
    integer, allocatable :: first(:)         !< (ntactors+1) offsets into the lists
    integer, allocatable :: inter(:), an(:), sub(:), status(:)
    real(wp), allocatable :: force(:, :)     !< (2,n) reaction / time step
    real(wp), allocatable :: point(:, :)     !< (2,n) contact point
    real(wp), allocatable :: internals(:, :) !< (n_internals,n)
  end type history_t

contains

  !> Make room for at least n contacts (keeps nothing: the store is refilled each step).
  subroutine contacts_reserve(c, n)
    type(contacts_t), intent(inout) :: c
    integer, intent(in) :: n
    integer :: cap
    if (allocated(c%inter)) then
      if (size(c%inter) >= n) return
      call free_all()
    end if
    cap = max(16, n + n / 2)
    allocate (c%inter(cap), c%cd(cap), c%an(cap), c%cdb(cap), c%anb(cap), c%cdm(cap), c%anm(cap), c%law(cap), c%sub(cap), &
              c%cdver(cap), c%anseg(cap), c%status(cap), &
              c%status_begin(cap), c%normal(2, cap), c%point(2, cap), c%gap(cap), c%lever(4, cap), &
              c%w(4, cap), c%shift(2, cap), c%mu(cap), c%active(cap), c%r(2, cap), c%u(2, cap), &
              c%u_begin(2, cap), c%wi(6, cap), c%length(cap), c%cohesive(cap))
    ! Only a scene with cohesive laws pays for their per-contact state.
    if (c%with_cohesion) then
      allocate (c%internals(n_internals, cap), c%coh(coh_size, cap))
    else
      allocate (c%internals(n_internals, 0), c%coh(coh_size, 0))
    end if
    if (c%with_mesh) then
      allocate (c%mnode(4, cap), c%mwt(4, cap))
    else
      allocate (c%mnode(4, 0), c%mwt(4, 0))
    end if
  contains
    subroutine free_all()
      deallocate (c%inter, c%cd, c%an, c%cdb, c%anb, c%cdm, c%anm, c%law, c%sub, c%cdver, c%anseg, c%status, &
                  c%status_begin, c%normal, &
                  c%point, c%gap, c%lever, c%w, c%shift, c%mu, c%active, c%r, c%u, c%u_begin, c%wi, &
                  c%length, c%internals, c%cohesive, c%coh, c%mnode, c%mwt)
    end subroutine free_all
  end subroutine contacts_reserve

  subroutine contacts_clear(c)
    type(contacts_t), intent(inout) :: c
    c%n = 0
  end subroutine contacts_clear

  !> Group records (cd, an, sub, inter, status, force) by candidate contactor.
  !> internals (n_internals, n) only for scenes with cohesive laws.
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
              hist%force(2, n), hist%point(2, n))
    if (present(internals)) allocate (hist%internals(n_internals, n))
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
    real(wp), intent(in) :: point(2), tol
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
