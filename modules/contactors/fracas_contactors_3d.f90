!> 3D contactors of rigid bodies (RBDY3): SPHER (sphere, radius), PLANx
!> (flat box: half lengths a1, a2 along its first two axes, half thickness a3
!> along its third, the plane's normal) and POLYR (convex polyhedron: vertices
!> and outward triangles), their volume and inertia per unit density, and a
!> body's mass properties assembled from its contactors as LMGC90's RBDY3
!> reader does. A POLYR is given its own frame when built from the input (its
!> centroid as offset, its principal axes as frame, its vertices in them), as
!> LMGC90 does on reading; then it is placed like the others.
!> Assembly:
!> - one contactor: the body's principal frame is the contactor's own frame
!>   (a PLANx's axes, the global axes for a SPHER), its centre the node's
!>   coordinates plus the contactor's offset; the inertia is the contactor's;
!>   the volume the contactor's if avrd = 0, else that of the sphere of radius
!>   avrd (LMGC90 keeps a given avrd for the mass);
!> - several: centre = volume-weighted mean of the contactor centres, inertia
!>   tensor = sum of the contactors' (turned to global) plus the parallel-axis
!>   terms, diagonalised: principal moments ascending, axes right-handed;
!>   offsets and PLANx frames re-expressed in that frame.
!> Mass = density x volume, inertia = density x (volume inertia).
module fracas_contactors_3d
  use fracas_kinds, only: wp
  use fracas_frame_3d, only: symmetric_eigen_3x3, polyhedron_volume_inertia, identity3
  use fracas_deck_3d, only: tactor3_input_t
  implicit none
  private
  public :: tactor3_t, tk3_spher, tk3_planx, tk3_polyr, sphere_volume_inertia, planx_volume_inertia, &
            polyr_from_surface, body3_mass_properties, tactor3_place, tactors3_from_input, &
            polyr_vertices, box_surface, tk3_cylnd, cylnd_volume_inertia

  integer, parameter :: tk3_spher = 1, tk3_planx = 2, tk3_polyr = 3
  !> CYLND (LMGC90's): radius byrd, axes(1) = High, the half length of its axis
  !> segment, along the frame's third axis; for contact a capsule (fracas_spcdx, fracas_cdplx).
  integer, parameter :: tk3_cylnd = 4
  real(wp), parameter :: pi = acos(-1.0_wp)

  !> One 3D contactor of a rigid body. Read: shift and frame in the deck's
  !> global axes (frame: columns alpha, beta, gamma); after
  !> body3_mass_properties: in the body's principal frame.
  type :: tactor3_t
    integer :: kind = 0                  !< tk3_spher, tk3_planx, tk3_polyr
    character(len=5) :: color = ''
    real(wp) :: radius = 0.0_wp          !< SPHER
    real(wp) :: axes(3) = 0.0_wp         !< PLANx half lengths a1, a2, half thickness a3
    real(wp) :: shift(3) = 0.0_wp        !< offset of the contactor centre
    real(wp) :: frame(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
    ! POLYR: vertices in the contactor's frame (principal, origin at the centroid),
    ! outward triangles (vertex indices), volume and principal moments per unit density
    real(wp), allocatable :: vert(:, :)
    integer, allocatable :: faces(:, :)
    real(wp) :: volume = 0.0_wp, moments(3) = 0.0_wp
  end type tactor3_t

contains

  !> The contactors of one body as read (fracas_read_bodies_3d): SPHER and
  !> SPHEb (a sphere with an offset) are spheres; a CYLND keeps High in axes(1).
  pure function tactors3_from_input(inp) result(t)
    type(tactor3_input_t), intent(in) :: inp(:)
    type(tactor3_t) :: t(size(inp))
    integer :: k
    do k = 1, size(inp)
      t(k)%kind = merge(tk3_planx, tk3_spher, inp(k)%kind == 'PLANx')
      if (inp(k)%kind == 'CYLND') t(k)%kind = tk3_cylnd
      t(k)%color = inp(k)%color
      t(k)%radius = inp(k)%radius
      t(k)%axes = inp(k)%axes
      t(k)%shift = inp(k)%shift
      t(k)%frame = inp(k)%frame
      if (inp(k)%kind == 'POLYR') then
        t(k) = polyr_from_surface(inp(k)%vert, inp(k)%faces)
        t(k)%color = inp(k)%color
      end if
    end do
  end function tactors3_from_input

  !> Volume and principal inertia per unit density of a sphere: I = 2/5 r^2 V.
  pure subroutine sphere_volume_inertia(r, vol, inertia)
    real(wp), intent(in) :: r
    real(wp), intent(out) :: vol, inertia(3)
    vol = 4.0_wp / 3.0_wp * pi * r**3
    inertia = 0.4_wp * r**2 * vol
  end subroutine sphere_volume_inertia

  !> Volume and principal inertia per unit density of a box of half lengths a:
  !> V = 8 a1 a2 a3, I1 = V (a2^2 + a3^2) / 3, ...
  pure subroutine planx_volume_inertia(a, vol, inertia)
    real(wp), intent(in) :: a(3)
    real(wp), intent(out) :: vol, inertia(3)
    vol = 8.0_wp * a(1) * a(2) * a(3)
    inertia = vol / 3.0_wp * [a(2)**2 + a(3)**2, a(1)**2 + a(3)**2, a(1)**2 + a(2)**2]
  end subroutine planx_volume_inertia

  !> Volume and principal inertia per unit density of a CYLND of half length h
  !> and radius r as LMGC90 computes them (its a_BDARY_CYLND reader): a plain
  !> cylinder, the caps left out: V = 2 pi r^2 h, I1 = I2 = (r^2/4 + h^2/3) V
  !> about the transverse axes, I3 = r^2/2 V about its axis.
  pure subroutine cylnd_volume_inertia(h, r, vol, inertia)
    real(wp), intent(in) :: h, r
    real(wp), intent(out) :: vol, inertia(3)
    vol = 2.0_wp * pi * r**2 * h
    inertia(1:2) = (0.25_wp * r**2 + h**2 / 3.0_wp) * vol
    inertia(3) = 0.5_wp * r**2 * vol
  end subroutine cylnd_volume_inertia

  !> A POLYR from its vertices (given in the body's deck axes, relative to the
  !> node) and outward triangles: offset = centroid, frame = principal axes,
  !> vertices re-expressed in them (LMGC90 does the same on reading). A
  !> non-positive volume (inward or open surface) is returned as volume <= 0.
  pure function polyr_from_surface(vert, faces) result(t)
    real(wp), intent(in) :: vert(:, :)
    integer, intent(in) :: faces(:, :)
    type(tactor3_t) :: t
    real(wp) :: tens(3, 3)
    integer :: k
    t%kind = tk3_polyr
    t%faces = faces
    call polyhedron_volume_inertia(vert, faces, t%volume, t%shift, tens)
    call symmetric_eigen_3x3(tens, t%moments, t%frame)
    allocate (t%vert(3, size(vert, 2)))
    do k = 1, size(vert, 2)
      t%vert(:, k) = matmul(vert(:, k) - t%shift, t%frame)
    end do
  end function polyr_from_surface

  pure subroutine tactor_volume_inertia(t, vol, inertia)
    type(tactor3_t), intent(in) :: t
    real(wp), intent(out) :: vol, inertia(3)
    select case (t%kind)
    case (tk3_spher)
      call sphere_volume_inertia(t%radius, vol, inertia)
    case (tk3_planx)
      call planx_volume_inertia(t%axes, vol, inertia)
    case (tk3_cylnd)
      call cylnd_volume_inertia(t%axes(1), t%radius, vol, inertia)
    case default
      vol = t%volume
      inertia = t%moments
    end select
  end subroutine tactor_volume_inertia

  !> Mass properties of one body from its contactors (see the module note).
  !> node: the node's coordinates; avrd: the PLAIN line's (0: computed, and
  !> returned). Out: centre, principal frame (columns), mass and principal
  !> inertia; the contactors' shift and frame turned into the principal frame.
  !> given: the PLAIN line's I1 I2 I3 (per unit density): for several
  !> contactors, non-zero ones are kept with the global axes as frame (LMGC90
  !> then expects the frame from DOF.INI); one contactor ignores them (LMGC90
  !> takes the contactor's).
  pure subroutine body3_mass_properties(t, node, density, avrd, centre, frame, mass, inertia, given)
    type(tactor3_t), intent(inout) :: t(:)
    real(wp), intent(in) :: node(3), density
    real(wp), intent(in), optional :: given(3)
    real(wp), intent(inout) :: avrd
    real(wp), intent(out) :: centre(3), frame(3, 3), mass, inertia(3)
    real(wp) :: vol, vi, ii(3), og(3), tens(3, 3), d(3)
    integer :: k, i
    if (size(t) == 1) then
      call tactor_volume_inertia(t(1), vol, inertia)
      if (avrd == 0.0_wp) then
        avrd = (0.75_wp * vol / pi)**(1.0_wp / 3.0_wp)
      else
        vol = 4.0_wp / 3.0_wp * pi * avrd**3
      end if
      centre = node + t(1)%shift
      frame = t(1)%frame
      t(1)%shift = 0.0_wp
      t(1)%frame = identity3()
    else
      og = 0.0_wp
      vol = 0.0_wp
      do k = 1, size(t)
        call tactor_volume_inertia(t(k), vi, ii)
        og = og + vi * t(k)%shift
        vol = vol + vi
      end do
      og = og / vol
      if (avrd == 0.0_wp) avrd = (0.75_wp * vol / pi)**(1.0_wp / 3.0_wp)
      tens = 0.0_wp
      do k = 1, size(t)
        call tactor_volume_inertia(t(k), vi, ii)
        t(k)%shift = t(k)%shift - og
        d = t(k)%shift
        ! the contactor's tensor in global axes, then the parallel-axis term vi (|d|^2 I - d d^T)
        tens = tens + matmul(t(k)%frame, spread(ii, 2, 3) * transpose(t(k)%frame))
        do i = 1, 3
          tens(:, i) = tens(:, i) - vi * d * d(i)
          tens(i, i) = tens(i, i) + vi * sum(d**2)
        end do
      end do
      call symmetric_eigen_3x3(tens, inertia, frame)
      centre = node + og
      if (present(given)) then
        if (any(given /= 0.0_wp)) then
          inertia = given
          frame = identity3()
        end if
      end if
      do k = 1, size(t)
        t(k)%shift = matmul(t(k)%shift, frame)
        t(k)%frame = matmul(transpose(frame), t(k)%frame)
      end do
    end if
    mass = density * vol
    inertia = density * inertia
  end subroutine body3_mass_properties

  !> Where a contactor is: centre c + F shift, frame F tframe (global).
  pure subroutine tactor3_place(t, c, f, at, tframe)
    type(tactor3_t), intent(in) :: t
    real(wp), intent(in) :: c(3), f(3, 3)
    real(wp), intent(out) :: at(3), tframe(3, 3)
    at = c + matmul(f, t%shift)
    tframe = matmul(f, t%frame)
  end subroutine tactor3_place

  !> The surface of a box of half lengths a (centred, axes along x, y, z) as
  !> a POLYR takes it: 8 vertices and 12 outward triangles.
  pure subroutine box_surface(a, vert, faces)
    real(wp), intent(in) :: a(3)
    real(wp), intent(out) :: vert(3, 8)
    integer, intent(out) :: faces(3, 12)
    integer :: k
    do k = 1, 8   ! bottom face counter-clockwise seen from above, then the top face
      vert(:, k) = a * [merge(1.0_wp, -1.0_wp, any(mod(k - 1, 4) == [1, 2])), merge(1.0_wp, -1.0_wp, mod(k - 1, 4) >= 2), &
                        merge(1.0_wp, -1.0_wp, k > 4)]
    end do
    faces = reshape([1, 3, 2, 1, 4, 3, 5, 6, 7, 5, 7, 8, 1, 2, 6, 1, 6, 5, 4, 8, 7, 4, 7, 3, 1, 5, 8, 1, 8, 4, &
                     2, 3, 7, 2, 7, 6], [3, 12])
  end subroutine box_surface

  !> A POLYR's vertices (global) on a body at centre c with frame f.
  pure function polyr_vertices(t, c, f) result(v)
    type(tactor3_t), intent(in) :: t
    real(wp), intent(in) :: c(3), f(3, 3)
    real(wp) :: v(3, size(t%vert, 2)), at(3), tf(3, 3)
    integer :: k
    call tactor3_place(t, c, f, at, tf)
    do k = 1, size(t%vert, 2)
      v(:, k) = at + matmul(tf, t%vert(:, k))
    end do
  end function polyr_vertices
end module fracas_contactors_3d
