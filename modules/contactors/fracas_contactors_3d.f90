!> 3D contactors of rigid bodies (RBDY3): SPHER (sphere, radius) and PLANx
!> (flat box: half lengths a1, a2 along its first two axes, half thickness a3
!> along its third, the plane's normal), their volume and inertia per unit
!> density, and a body's mass properties assembled from its contactors as
!> LMGC90's RBDY3 reader does:
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
  use fracas_frame_3d, only: symmetric_eigen_3x3
  use fracas_deck_3d, only: tactor3_input_t
  implicit none
  private
  public :: tactor3_t, tk3_spher, tk3_planx, sphere_volume_inertia, planx_volume_inertia, &
            body3_mass_properties, tactor3_place, tactors3_from_input

  integer, parameter :: tk3_spher = 1, tk3_planx = 2
  real(wp), parameter :: pi = acos(-1.0_wp)

  !> One 3D contactor of a rigid body. Read: shift and frame in the deck's
  !> global axes (frame: columns alpha, beta, gamma); after
  !> body3_mass_properties: in the body's principal frame.
  type :: tactor3_t
    integer :: kind = 0                  !< tk3_spher, tk3_planx
    character(len=5) :: color = ''
    real(wp) :: radius = 0.0_wp          !< SPHER
    real(wp) :: axes(3) = 0.0_wp         !< PLANx half lengths a1, a2, half thickness a3
    real(wp) :: shift(3) = 0.0_wp        !< offset of the contactor centre
    real(wp) :: frame(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
  end type tactor3_t

contains

  !> The contactors of one body as read (fracas_read_bodies_3d): SPHER and
  !> SPHEb (a sphere with an offset) are spheres.
  pure function tactors3_from_input(inp) result(t)
    type(tactor3_input_t), intent(in) :: inp(:)
    type(tactor3_t) :: t(size(inp))
    integer :: k
    do k = 1, size(inp)
      t(k)%kind = merge(tk3_planx, tk3_spher, inp(k)%kind == 'PLANx')
      t(k)%color = inp(k)%color
      t(k)%radius = inp(k)%radius
      t(k)%axes = inp(k)%axes
      t(k)%shift = inp(k)%shift
      t(k)%frame = inp(k)%frame
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

  pure subroutine tactor_volume_inertia(t, vol, inertia)
    type(tactor3_t), intent(in) :: t
    real(wp), intent(out) :: vol, inertia(3)
    if (t%kind == tk3_spher) then
      call sphere_volume_inertia(t%radius, vol, inertia)
    else
      call planx_volume_inertia(t%axes, vol, inertia)
    end if
  end subroutine tactor_volume_inertia

  !> Mass properties of one body from its contactors (see the module note).
  !> node: the node's coordinates; avrd: the PLAIN line's (0: computed, and
  !> returned). Out: centre, principal frame (columns), mass and principal
  !> inertia; the contactors' shift and frame turned into the principal frame.
  pure subroutine body3_mass_properties(t, node, density, avrd, centre, frame, mass, inertia)
    type(tactor3_t), intent(inout) :: t(:)
    real(wp), intent(in) :: node(3), density
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
      t(1)%frame = identity()
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

  pure function identity() result(m)
    real(wp) :: m(3, 3)
    m = 0.0_wp
    m(1, 1) = 1.0_wp; m(2, 2) = 1.0_wp; m(3, 3) = 1.0_wp
  end function identity
end module fracas_contactors_3d
