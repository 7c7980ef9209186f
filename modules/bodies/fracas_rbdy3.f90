!> 3D rigid bodies (RBDY3: 3 translations, 3 rotations), stored as arrays over
!> bodies, as LMGC90's RBDY3 keeps them: the translational velocity v(1:3) in
!> the global frame, the rotational velocity v(4:6) in the body's principal
!> inertia frame, the mass diag(m, m, m, I1, I2, I3) in that frame, and the
!> orientation as the frame itself (columns: the principal axes in global
!> coordinates, LMGC90's LocalFrame; contactor geometry is given in it).
!> Knows masses, external forces, drives and the Moreau–Jean update; nothing
!> about contacts: the solver adds impulses to v through the inverse masses
!> (fracas_rbdy3_side).
!>
!> The step (LMGC90's 3D rigid Moreau step): the gyroscopic torque
!> -(omega x I omega) is explicit, at the begin velocity, in fext (as LMGC90's
!> comp_Fext_RBDY3); vfree = vbegin + h M^-1 fext; translations by the theta
!> rule. Rotation: the frame is turned by the rotation vector (1-theta) h
!> omega_begin to the detection configuration, then by theta h omega_end to
!> the end of the step, both in the body frame (LMGC90's default scheme), but
!> each turn is the exact rotation exp([phi]x) (Rodrigues) where LMGC90
!> linearises it and re-orthonormalises (Gram–Schmidt): the frame stays a
!> rotation to round-off whatever the step.
module fracas_rbdy3
  use fracas_kinds, only: wp
  use fracas_deck, only: driven_dof_input_t
  use fracas_deck_3d, only: dof3_record_t
  use fracas_drives, only: drive_t, drives_build, drives_begin_step, drives_impose_end, drives_add_work
  use fracas_frame_3d, only: cross3, rotation_of_vector
  implicit none
  private
  public :: rbdy3_t, rbdy3_init, rbdy3_add_drives, rbdy3_begin_step, rbdy3_detection_config, rbdy3_end_step, &
            rbdy3_kinetic_energy, rbdy3_angular_momentum, gyroscopic_torque, rbdy3_add_step_work, &
            rbdy3_dof_records, rbdy3_set_dof

  type :: rbdy3_t
    integer :: n = 0
    integer, allocatable :: number(:)            !< serial number in BODIES.DAT
    real(wp), allocatable :: ref(:, :)           !< (3,n) reference centre of inertia
    real(wp), allocatable :: x(:, :), xbegin(:, :)        !< (3,n) displacement of the centre from ref
    real(wp), allocatable :: frame(:, :, :), frame_begin(:, :, :)  !< (3,3,n) principal axes (columns)
    real(wp), allocatable :: v(:, :), vbegin(:, :), vfree(:, :)    !< (6,n): global v, body-frame omega
    real(wp), allocatable :: fext(:, :)          !< (6,n) theta-averaged external force, gyroscopic torque
    real(wp), allocatable :: mass(:, :)          !< (6,n): m, m, m, I1, I2, I3
    real(wp), allocatable :: inv_mass(:, :)      !< 0 on velocity-driven dofs
    real(wp), allocatable :: avrd(:)             !< average radius (outputs)
    logical, allocatable :: driven(:, :)
    logical, allocatable :: clamped(:)
    real(wp) :: gravity(3) = 0.0_wp
    type(drive_t), allocatable :: drives(:)
  end type rbdy3_t

contains

  !> Bodies at rest at their reference centres, principal frames frame(:,:,k).
  subroutine rbdy3_init(b, number, ref, frame, mass, inertia, avrd, gravity)
    type(rbdy3_t), intent(out) :: b
    integer, intent(in) :: number(:)
    real(wp), intent(in) :: ref(:, :), frame(:, :, :), mass(:), inertia(:, :), avrd(:), gravity(3)
    b%n = size(number)
    b%number = number
    b%ref = ref
    b%frame = frame
    b%frame_begin = frame
    b%avrd = avrd
    b%gravity = gravity
    b%mass = spread([1.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 2, b%n) * spread(mass, 1, 6)
    b%mass(4:6, :) = inertia
    ! kept finite until a start check refuses a mass whose inverse overflows (as rbdy2)
    b%inv_mass = finite_inverse(b%mass)
    allocate (b%x(3, b%n), b%xbegin(3, b%n), source=0.0_wp)
    allocate (b%v(6, b%n), b%vbegin(6, b%n), b%vfree(6, b%n), b%fext(6, b%n), source=0.0_wp)
    allocate (b%driven(6, b%n), b%clamped(b%n), source=.false.)
    allocate (b%drives(0))
  end subroutine rbdy3_init

  elemental real(wp) function finite_inverse(m) result(inv)
    real(wp), intent(in) :: m
    inv = huge(1.0_wp)
    if (m > 1.0_wp / huge(1.0_wp)) inv = 1.0_wp / m
  end function finite_inverse

  !> The driven dofs of DRV_DOF.DAT (body serial number = index; dofs 1..3 the
  !> global translations, 4..6 the rotations about the principal axes, as LMGC90).
  subroutine rbdy3_add_drives(b, inputs)
    type(rbdy3_t), intent(inout) :: b
    type(driven_dof_input_t), intent(in) :: inputs(:)
    call drives_build(inputs, b%driven, b%inv_mass, b%clamped, b%drives)
  end subroutine rbdy3_add_drives

  !> -(omega x I omega): the torque that, explicit, makes Euler's equations
  !> I omega' = torque - omega x I omega (body frame).
  pure function gyroscopic_torque(inertia, omega) result(tq)
    real(wp), intent(in) :: inertia(3), omega(3)
    real(wp) :: tq(3)
    tq = -cross3(omega, inertia * omega)
  end function gyroscopic_torque

  !> Start of a step [t, t+h]: gravity, the gyroscopic torque at vbegin,
  !> theta-averaged force drives; free velocity; driven velocities (at t at the
  !> start, at t+h at the end, as the 2D rigid model). Sets v = vfree.
  subroutine rbdy3_begin_step(b, t, h, theta)
    type(rbdy3_t), intent(inout) :: b
    real(wp), intent(in) :: t, h, theta
    integer :: i
    do i = 1, b%n
      b%fext(1:3, i) = b%mass(1:3, i) * b%gravity
      b%fext(4:6, i) = gyroscopic_torque(b%mass(4:6, i), b%vbegin(4:6, i))
    end do
    call drives_begin_step(b%drives, t, h, theta, b%fext, b%vbegin)
    b%vfree = b%vbegin + h * b%inv_mass * b%fext
    call drives_impose_end(b%drives, t, h, b%vfree)
    b%v = b%vfree
  end subroutine rbdy3_begin_step

  !> Configuration where contacts are detected: centres ref + xbegin + (1-theta)
  !> h vbegin, frames turned by (1-theta) h omega_begin.
  pure subroutine rbdy3_detection_config(b, h, theta, q, frame_tt)
    type(rbdy3_t), intent(in) :: b
    real(wp), intent(in) :: h, theta
    real(wp), intent(out) :: q(:, :), frame_tt(:, :, :)
    integer :: i
    do i = 1, b%n
      q(:, i) = b%ref(:, i) + b%xbegin(:, i) + (1.0_wp - theta) * h * b%vbegin(1:3, i)
      frame_tt(:, :, i) = matmul(b%frame_begin(:, :, i), rotation_of_vector((1.0_wp - theta) * h * b%vbegin(4:6, i)))
    end do
  end subroutine rbdy3_detection_config

  !> End of a step: theta rule for the centres, the frame turned by theta h
  !> omega from the detection frame; the end state becomes the next begin state.
  subroutine rbdy3_end_step(b, h, theta)
    type(rbdy3_t), intent(inout) :: b
    real(wp), intent(in) :: h, theta
    integer :: i
    do i = 1, b%n
      b%x(:, i) = b%xbegin(:, i) + h * ((1.0_wp - theta) * b%vbegin(1:3, i) + theta * b%v(1:3, i))
      b%frame(:, :, i) = matmul(matmul(b%frame_begin(:, :, i), &
                                       rotation_of_vector((1.0_wp - theta) * h * b%vbegin(4:6, i))), &
                                rotation_of_vector(theta * h * b%v(4:6, i)))
    end do
    b%xbegin = b%x
    b%vbegin = b%v
    b%frame_begin = b%frame
  end subroutine rbdy3_end_step

  !> Work of gravity on the free translations and of the force drives over the
  !> step [t, t+h] (theta rule on the displacement; a torque drive with the
  !> body-frame rotation increment), added to work_gravity and work_forces;
  !> before rbdy3_end_step (it reads vbegin and v).
  pure subroutine rbdy3_add_step_work(b, t, h, theta, work_gravity, work_forces)
    type(rbdy3_t), intent(in) :: b
    real(wp), intent(in) :: t, h, theta
    real(wp), intent(inout) :: work_gravity, work_forces
    integer :: k
    do k = 1, b%n
      work_gravity = work_gravity + h * sum(b%mass(1:3, k) * b%gravity * &
                                            ((1.0_wp - theta) * b%vbegin(1:3, k) + theta * b%v(1:3, k)), &
                                            mask=.not. b%driven(1:3, k))
    end do
    call drives_add_work(b%drives, t, h, theta, b%vbegin, b%v, work_forces)
  end subroutine rbdy3_add_step_work

  !> The bodies' state as DOF.OUT records: X(1:3) the displacement of the
  !> centre, X(4:6) = 0 (as LMGC90: the rotation is the frame), V, the frame.
  pure function rbdy3_dof_records(b) result(r)
    type(rbdy3_t), intent(in) :: b
    type(dof3_record_t) :: r(b%n)
    integer :: k
    do k = 1, b%n
      r(k)%body = b%number(k)
      r(k)%x = [b%x(:, k), 0.0_wp, 0.0_wp, 0.0_wp]
      r(k)%v = b%v(:, k)
      r(k)%frame = b%frame(:, :, k)
    end do
  end function rbdy3_dof_records

  !> Start from a DOF.INI record (body index = its number): displacement,
  !> velocity and frame, as begin and end state.
  pure subroutine rbdy3_set_dof(b, r)
    type(rbdy3_t), intent(inout) :: b
    type(dof3_record_t), intent(in) :: r
    b%x(:, r%body) = r%x(1:3)
    b%xbegin(:, r%body) = r%x(1:3)
    b%v(:, r%body) = r%v
    b%vbegin(:, r%body) = r%v
    b%frame(:, :, r%body) = r%frame
    b%frame_begin(:, :, r%body) = r%frame
  end subroutine rbdy3_set_dof

  !> Kinetic energy of the free (not velocity-driven) dofs.
  pure real(wp) function rbdy3_kinetic_energy(b) result(e)
    type(rbdy3_t), intent(in) :: b
    e = 0.5_wp * sum(b%mass * b%v**2, mask=.not. b%driven)
  end function rbdy3_kinetic_energy

  !> Angular momentum of body i about its centre, in the global frame: F (I omega).
  pure function rbdy3_angular_momentum(b, i) result(l)
    type(rbdy3_t), intent(in) :: b
    integer, intent(in) :: i
    real(wp) :: l(3)
    l = matmul(b%frame(:, :, i), b%mass(4:6, i) * b%v(4:6, i))
  end function rbdy3_angular_momentum
end module fracas_rbdy3
