!> Contactors: the shapes attached to bodies, as one flat list over all bodies.
!> On rigid bodies (DISKx, xKSID, JONCx, POLYG) the geometry is given in the
!> body frame and placed with the body's configuration; on meshed bodies
!> (CLxxx candidate points on an edge, ALpxx polylines) it is given by mesh
!> nodes and placed with their coordinates. A contactor maps to its body.
module fracas_contactors
  use fracas_kinds, only: wp
  use fracas_deck, only: body_input_t, tactor_input_t
  use fracas_errors, only: input_error
  use fracas_ids, only: bm_rigid, bm_mesh, tk_disk, tk_xksid, tk_jonc, tk_polyg, tk_clxxx, tk_alpxx, &
                        n_tactor_kinds, tactor_kind_names, tactor_kind_id
  implicit none
  private
  public :: tactors_t, tactors_build, tactor_center, tactor_kind_name, body_area_inertia, &
            polygon_area_moments, tactor_vertices, tk_disk, tk_xksid, tk_jonc, tk_polyg, &
            tk_clxxx, tk_alpxx, cl_point

  real(wp), parameter :: pi = acos(-1.0_wp)

  type :: tactors_t
    integer :: n = 0
    integer, allocatable :: kind(:)        !< tk_*
    integer, allocatable :: model(:)       !< body model (bm_rigid, bm_mesh)
    integer, allocatable :: body(:)        !< owning body, index within its model
    integer, allocatable :: rank(:)        !< rank of the contactor within its body (1-based)
    integer, allocatable :: kind_index(:)  !< index among the contactors of the same kind
    character(len=5), allocatable :: color(:)
    real(wp), allocatable :: radius(:)     !< DISKx, xKSID radius
    real(wp), allocatable :: ax1(:), ax2(:) !< JONCx half length, half thickness
    real(wp), allocatable :: shift(:, :)   !< (2,n) offset in the body frame
    real(wp), allocatable :: bound(:)      !< radius of a circle around the contactor centre holding it
    integer, allocatable :: vfirst(:)      !< (n+1) POLYG: vertices vfirst(k) .. vfirst(k+1)-1 of vert
    real(wp), allocatable :: vert(:, :)    !< (2,*) POLYG vertices in the body frame, counter-clockwise
    ! Mesh contactors: nodes nfirst(k) .. nfirst(k+1)-1 of `nodes` (mesh node
    ! numbers over all meshed bodies). CLxxx: the edge (noda, nodb), the point
    ! at (1 - apab) x_noda + apab x_nodb; ALpxx: the polyline's nodes in order.
    integer, allocatable :: nfirst(:)      !< (n+1)
    integer, allocatable :: nodes(:)
    real(wp), allocatable :: apab(:)
  end type tactors_t

contains

  !> The name of a contactor kind id (fracas_ids' table), '?????' if none.
  pure function tactor_kind_name(kind) result(name)
    integer, intent(in) :: kind
    character(len=5) :: name
    name = '?????'
    if (kind >= 1 .and. kind <= n_tactor_kinds) name = tactor_kind_names(kind)
  end function tactor_kind_name

  !> The contactor kind names, comma separated.
  function names() result(s)
    character(len=:), allocatable :: s
    integer :: i
    s = tactor_kind_names(1)
    do i = 2, n_tactor_kinds
      s = s//', '//tactor_kind_names(i)
    end do
  end function names

  !> Flatten the contactors of all bodies into one list. Bodies are numbered
  !> within their model in the order given; mesh nodes over all meshed bodies
  !> in the same order (body b's node i is the i-th after the nodes of the
  !> meshed bodies before it).
  subroutine tactors_build(bodies, t)
    type(body_input_t), intent(in) :: bodies(:)
    type(tactors_t), intent(out) :: t
    integer :: ib, it, k, n, counts(6), nv, nnod, nrigid, nmesh, node_offset
    n = 0
    nv = 0
    nnod = 0
    do ib = 1, size(bodies)
      if (.not. allocated(bodies(ib)%tactors)) cycle
      n = n + size(bodies(ib)%tactors)
      do it = 1, size(bodies(ib)%tactors)
        if (allocated(bodies(ib)%tactors(it)%vertices)) nv = nv + size(bodies(ib)%tactors(it)%vertices, 2)
        if (allocated(bodies(ib)%tactors(it)%nodes)) nnod = nnod + size(bodies(ib)%tactors(it)%nodes)
      end do
    end do
    t%n = n
    allocate (t%kind(n), t%model(n), t%body(n), t%rank(n), t%kind_index(n), t%color(n), t%radius(n), t%ax1(n), &
              t%ax2(n), t%shift(2, n), t%bound(n), t%vfirst(n + 1), t%vert(2, nv), t%nfirst(n + 1), &
              t%nodes(nnod), t%apab(n))
    t%vfirst(1) = 1
    t%nfirst(1) = 1
    k = 0
    counts = 0
    nrigid = 0
    nmesh = 0
    node_offset = 0
    do ib = 1, size(bodies)
      if (bodies(ib)%model == 'MAILx') then
        nmesh = nmesh + 1
      else
        nrigid = nrigid + 1
      end if
      if (allocated(bodies(ib)%tactors)) then
        do it = 1, size(bodies(ib)%tactors)
          k = k + 1
          call add_tactor(bodies(ib), bodies(ib)%tactors(it), it)
        end do
      end if
      if (bodies(ib)%model == 'MAILx') node_offset = node_offset + size(bodies(ib)%node_coor, 2)
    end do

  contains

    subroutine add_tactor(bd, inp, rank)
      type(body_input_t), intent(in) :: bd
      type(tactor_input_t), intent(in) :: inp
      integer, intent(in) :: rank
      integer :: nn
      t%kind(k) = tactor_kind_id(inp%kind)
      if (t%kind(k) == 0) call input_error(inp%src%file, inp%src%line, 2, "contactor '"//inp%kind// &
        "' is read but not supported by the solver yet (supported: DISKb and "//names()//")")
      counts(t%kind(k)) = counts(t%kind(k)) + 1
      t%kind_index(k) = counts(t%kind(k))
      if (bd%model == 'MAILx') then
        t%model(k) = bm_mesh
        t%body(k) = nmesh
      else
        t%model(k) = bm_rigid
        t%body(k) = nrigid
      end if
      t%rank(k) = rank
      t%color(k) = inp%color
      t%radius(k) = inp%radius
      t%ax1(k) = inp%ax1
      t%ax2(k) = inp%ax2
      t%shift(:, k) = inp%shift
      t%apab(k) = inp%apab
      t%vfirst(k + 1) = t%vfirst(k)
      t%nfirst(k + 1) = t%nfirst(k)
      select case (t%kind(k))
      case (tk_jonc)
        t%bound(k) = inp%ax1 + inp%ax2
      case (tk_polyg)
        ! Vertices stay in the body frame; the contactor centre is the body node.
        nv = size(inp%vertices, 2)
        t%vert(:, t%vfirst(k):t%vfirst(k) + nv - 1) = inp%vertices
        t%vfirst(k + 1) = t%vfirst(k) + nv
        t%bound(k) = sqrt(maxval(sum(inp%vertices**2, dim=1)))
      case (tk_clxxx, tk_alpxx)
        ! Placed from the nodes at each detection (bound set then).
        nn = size(inp%nodes)
        t%nodes(t%nfirst(k):t%nfirst(k) + nn - 1) = node_offset + inp%nodes
        t%nfirst(k + 1) = t%nfirst(k) + nn
        t%bound(k) = 0.0_wp
      case default
        t%bound(k) = inp%radius
      end select
    end subroutine add_tactor
  end subroutine tactors_build

  !> Position of CLxxx point k for mesh node coordinates xn(2, nodes).
  pure function cl_point(t, k, xn) result(p)
    type(tactors_t), intent(in) :: t
    integer, intent(in) :: k
    real(wp), intent(in) :: xn(:, :)
    real(wp) :: p(2)
    associate (a => t%nodes(t%nfirst(k)), b => t%nodes(t%nfirst(k) + 1))
      p = (1.0_wp - t%apab(k)) * xn(:, a) + t%apab(k) * xn(:, b)
    end associate
  end function cl_point

  !> Centre of contactor k for a body configuration q = (x, y, angle).
  pure function tactor_center(t, k, q) result(c)
    type(tactors_t), intent(in) :: t
    integer, intent(in) :: k
    real(wp), intent(in) :: q(3)
    real(wp) :: c(2), cs, sn
    cs = cos(q(3)); sn = sin(q(3))
    c(1) = q(1) + cs * t%shift(1, k) - sn * t%shift(2, k)
    c(2) = q(2) + sn * t%shift(1, k) + cs * t%shift(2, k)
  end function tactor_center

  !> Vertices of POLYG contactor k placed with the body configuration q.
  pure function tactor_vertices(t, k, q) result(p)
    type(tactors_t), intent(in) :: t
    integer, intent(in) :: k
    real(wp), intent(in) :: q(3)
    real(wp), allocatable :: p(:, :)
    real(wp) :: cs, sn
    integer :: j, i
    cs = cos(q(3)); sn = sin(q(3))
    allocate (p(2, t%vfirst(k + 1) - t%vfirst(k)))
    do j = t%vfirst(k), t%vfirst(k + 1) - 1
      i = j - t%vfirst(k) + 1
      p(1, i) = q(1) + cs * t%vert(1, j) - sn * t%vert(2, j)
      p(2, i) = q(2) + sn * t%vert(1, j) + cs * t%vert(2, j)
    end do
  end function tactor_vertices

  !> Area, centroid and polar second moment about the origin of a simple
  !> polygon (counter-clockwise vertices), by the shoelace formulas.
  pure subroutine polygon_area_moments(v, area, centroid, polar)
    real(wp), intent(in) :: v(:, :)
    real(wp), intent(out) :: area, centroid(2), polar
    integer :: i, j, n
    real(wp) :: cr
    n = size(v, 2)
    area = 0.0_wp; centroid = 0.0_wp; polar = 0.0_wp
    do i = 1, n
      j = mod(i, n) + 1
      cr = v(1, i) * v(2, j) - v(1, j) * v(2, i)
      area = area + cr
      centroid = centroid + cr * (v(:, i) + v(:, j))
      polar = polar + cr * (v(1, i)**2 + v(1, i) * v(1, j) + v(1, j)**2 + &
                            v(2, i)**2 + v(2, i) * v(2, j) + v(2, j)**2)
    end do
    area = 0.5_wp * area
    centroid = centroid / (6.0_wp * area)
    polar = polar / 12.0_wp
  end subroutine polygon_area_moments

  !> Area and polar second moment (about the body node) of a body's contactors,
  !> per unit density and unit thickness; used when avrd/gyrd are given as 0.
  subroutine body_area_inertia(body, area, inertia)
    type(body_input_t), intent(in) :: body
    real(wp), intent(out) :: area, inertia
    integer :: it
    real(wp) :: a, i0, arect, acap, d, e, cen(2)
    area = 0.0_wp
    inertia = 0.0_wp
    if (.not. allocated(body%tactors)) return
    do it = 1, size(body%tactors)
      associate (tc => body%tactors(it))
        select case (tc%kind)
        case ('JONCx')
          ! Rectangle 2ax1 x 2ax2 plus two half disks of radius ax2 at the ends.
          arect = 4.0_wp * tc%ax1 * tc%ax2
          acap = 0.5_wp * pi * tc%ax2**2
          d = tc%ax1
          e = 4.0_wp * tc%ax2 / (3.0_wp * pi)       ! centroid offset of a half disk
          a = arect + 2.0_wp * acap
          i0 = arect * (tc%ax1**2 + tc%ax2**2) / 3.0_wp + &
               2.0_wp * (acap * 0.5_wp * tc%ax2**2 + acap * (d**2 + 2.0_wp * d * e))
        case ('POLYG')
          ! Vertices are already in the body frame: the moment is about the node.
          call polygon_area_moments(tc%vertices, a, cen, i0)
          area = area + a
          inertia = inertia + i0
          cycle
        case default   ! DISKx, xKSID: a full disk
          a = pi * tc%radius**2
          i0 = 0.5_wp * a * tc%radius**2
        end select
        area = area + a
        inertia = inertia + i0 + a * sum(tc%shift**2)
      end associate
    end do
  end subroutine body_area_inertia
end module fracas_contactors
