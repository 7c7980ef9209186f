!> 2D rigid bodies (x, y, rotation), stored as arrays over bodies. This module
!> knows masses, external forces, driven degrees of freedom and the
!> Moreau–Jean update; it knows nothing about contacts: the solver adds
!> impulses to `v` through the inverse masses.
module fracas_rbdy2
  use fracas_kinds, only: wp, resolvable_length
  use fracas_strings, only: itoa, rtoa, rtoa_list
  use fracas_energy, only: energy_terms_t
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use fracas_deck, only: driven_dof_input_t, dof_record_t
  use fracas_restart_h5, only: restart_state_t, restart_check_real2
  use fracas_drives, only: drive_t, drives_build, drives_begin_step, drives_impose_end, drives_add_work
  implicit none
  private
  public :: rbdy2_t, rbdy2_init, rbdy2_add_drives, rbdy2_add_step_work, rbdy2_begin_step, &
            rbdy2_detection_coor, rbdy2_end_step, rbdy2_kinetic_energy, rbdy2_energy_terms, rbdy2_fault, &
            rbdy2_point_speed, rbdy2_save_state, rbdy2_restore_state, rbdy2_check_restart, rbdy2_dof_records


  type :: rbdy2_t
    integer :: n = 0
    integer, allocatable :: number(:)           !< serial number in BODIES.DAT
    real(wp), allocatable :: ref(:, :)          !< (3,n) reference x, y, angle
    real(wp), allocatable :: x(:, :), xbegin(:, :)   !< displacement from ref
    real(wp), allocatable :: v(:, :), vbegin(:, :), vfree(:, :)
    real(wp), allocatable :: fext(:, :)         !< theta-averaged external force of the step
    real(wp), allocatable :: mass(:, :)         !< (3,n): m, m, I
    real(wp), allocatable :: inv_mass(:, :)     !< 0 on driven dofs
    real(wp), allocatable :: avrd(:)            !< average radius (for outputs)
    logical, allocatable :: driven(:, :)        !< velocity-driven dofs
    logical, allocatable :: clamped(:)          !< every dof velocity-driven
    real(wp) :: gravity(2) = 0.0_wp
    type(drive_t), allocatable :: drives(:)
    logical :: driven_start_imposed = .true.    !< a driven dof starts a step at its imposed value
    ! Energy audit, accumulated over the run (rbdy2_add_step_work).
    real(wp) :: work_gravity = 0.0_wp, work_forces = 0.0_wp, work_supports = 0.0_wp
  end type rbdy2_t

contains

  !> Bodies at rest in their reference configuration.
  subroutine rbdy2_init(b, number, ref, mass, inertia, avrd, gravity)
    type(rbdy2_t), intent(out) :: b
    integer, intent(in) :: number(:)
    real(wp), intent(in) :: ref(:, :), mass(:), inertia(:), avrd(:), gravity(2)
    integer :: n
    n = size(number)
    b%n = n
    b%number = number
    b%ref = ref
    b%avrd = avrd
    b%gravity = gravity
    allocate (b%x(3, n), b%xbegin(3, n), b%v(3, n), b%vbegin(3, n), b%vfree(3, n), b%fext(3, n), &
              b%mass(3, n), b%inv_mass(3, n), b%driven(3, n), b%clamped(n))
    b%x = 0.0_wp; b%xbegin = 0.0_wp; b%v = 0.0_wp; b%vbegin = 0.0_wp; b%vfree = 0.0_wp; b%fext = 0.0_wp
    b%mass(1, :) = mass
    b%mass(2, :) = mass
    b%mass(3, :) = inertia
    ! A mass whose inverse overflows is refused by the start check (fracas_state_guard);
    ! keep the inverse finite until then.
    where (b%mass > 1.0_wp / huge(1.0_wp))
      b%inv_mass = 1.0_wp / b%mass
    elsewhere
      b%inv_mass = huge(1.0_wp)
    end where
    b%driven = .false.
    b%clamped = .false.
    allocate (b%drives(0))
  end subroutine rbdy2_init

  !> The driven dofs read from DRV_DOF.DAT (body serial number = index), all at once.
  subroutine rbdy2_add_drives(b, inputs)
    type(rbdy2_t), intent(inout) :: b
    type(driven_dof_input_t), intent(in) :: inputs(:)
    call drives_build(inputs, b%driven, b%inv_mass, b%clamped, b%drives)
  end subroutine rbdy2_add_drives

  !> Start of a step [t, t+h]: external forces (gravity, theta-averaged driven
  !> forces), free velocity, imposed velocities at t+h. Sets v = vfree.
  subroutine rbdy2_begin_step(b, t, h, theta)
    type(rbdy2_t), intent(inout) :: b
    real(wp), intent(in) :: t, h, theta
    integer :: i
    do i = 1, b%n
      b%fext(1, i) = b%mass(1, i) * b%gravity(1)
      b%fext(2, i) = b%mass(2, i) * b%gravity(2)
      b%fext(3, i) = 0.0_wp
    end do
    ! A driven dof starts the step at its imposed value (LMGC90's RBDY2, whatever
    ! DOF.INI said), or from its previous velocity; it ends at its imposed value.
    call drives_begin_step(b%drives, t, h, theta, b%fext, b%vbegin, impose_start=b%driven_start_imposed)
    b%vfree = b%vbegin + h * b%inv_mass * b%fext
    call drives_impose_end(b%drives, t, h, b%vfree)
    b%v = b%vfree
  end subroutine rbdy2_begin_step

  !> The step's work, added to the audit: of gravity on the free dofs and of the
  !> force drives over [t, t+h] (theta rule on the displacement), and of the
  !> velocity-driven dofs through the contact impulses imp(3, n) on the bodies
  !> (minus the impulse times the mean velocity); before rbdy2_end_step (it reads
  !> vbegin and v).
  subroutine rbdy2_add_step_work(b, t, h, theta, imp)
    type(rbdy2_t), intent(inout) :: b
    real(wp), intent(in) :: t, h, theta, imp(:, :)
    integer :: k
    real(wp) :: dx(3)
    do k = 1, b%n
      dx = h * ((1.0_wp - theta) * b%vbegin(:, k) + theta * b%v(:, k))
      if (.not. b%driven(1, k)) b%work_gravity = b%work_gravity + b%mass(1, k) * b%gravity(1) * dx(1)
      if (.not. b%driven(2, k)) b%work_gravity = b%work_gravity + b%mass(2, k) * b%gravity(2) * dx(2)
    end do
    call drives_add_work(b%drives, t, h, theta, b%vbegin, b%v, b%work_forces)
    b%work_supports = b%work_supports + (-0.5_wp * sum(imp * (b%v + b%vbegin), mask=b%driven))
  end subroutine rbdy2_add_step_work

  !> The bodies' records of DOF.OUT (LMGC90's RBDY2 blocks: x, v).
  pure function rbdy2_dof_records(b) result(dofs)
    type(rbdy2_t), intent(in) :: b
    type(dof_record_t) :: dofs(b%n)
    integer :: k
    do k = 1, b%n
      dofs(k)%model = 'RBDY2'     ! set, not left to the result's default initialisation
      dofs(k)%body = b%number(k)
      dofs(k)%x = b%x(:, k)
      dofs(k)%v = b%v(:, k)
    end do
  end function rbdy2_dof_records

  !> The bodies' end-of-step state for a restart point: positions x, velocities
  !> v and the audit's work terms (gravity, forces, supports).
  subroutine rbdy2_save_state(b, x, v, work)
    type(rbdy2_t), intent(in) :: b
    real(wp), allocatable, intent(out) :: x(:, :), v(:, :)
    real(wp), intent(out) :: work(3)
    x = b%x
    v = b%v
    work = [b%work_gravity, b%work_forces, b%work_supports]
  end subroutine rbdy2_save_state

  !> The bodies' datasets of a restart point read from a file (X, V): shapes and
  !> finite values, before any is used (the run stops naming the dataset).
  subroutine rbdy2_check_restart(b, st)
    type(rbdy2_t), intent(in) :: b
    type(restart_state_t), intent(in) :: st
    call restart_check_real2(st, 'X', st%x, 3, b%n)
    call restart_check_real2(st, 'V', st%v, 3, b%n)
  end subroutine rbdy2_check_restart

  !> Put the bodies into a state rbdy2_save_state took: the end of that step is
  !> the beginning of the next (rbdy2_end_step).
  subroutine rbdy2_restore_state(b, x, v, work)
    type(rbdy2_t), intent(inout) :: b
    real(wp), intent(in) :: x(:, :), v(:, :), work(3)
    b%x = x
    b%xbegin = x
    b%v = v
    b%vbegin = v
    b%work_gravity = work(1)
    b%work_forces = work(2)
    b%work_supports = work(3)
  end subroutine rbdy2_restore_state

  !> The model's terms of the energy audit (rigid bodies store no energy).
  pure type(energy_terms_t) function rbdy2_energy_terms(b) result(e)
    type(rbdy2_t), intent(in) :: b
    e%work_gravity = b%work_gravity
    e%work_forces = b%work_forces
    e%work_supports = b%work_supports
  end function rbdy2_energy_terms

  !> Configuration where contacts are detected: ref + xbegin + (1-theta) h vbegin.
  pure subroutine rbdy2_detection_coor(b, h, theta, q)
    type(rbdy2_t), intent(in) :: b
    real(wp), intent(in) :: h, theta
    real(wp), intent(out) :: q(:, :)
    q = b%ref + b%xbegin + (1.0_wp - theta) * h * b%vbegin
  end subroutine rbdy2_detection_coor

  !> End of a step: theta rule for the positions, then the end state becomes the
  !> begin state of the next step.
  subroutine rbdy2_end_step(b, h, theta)
    type(rbdy2_t), intent(inout) :: b
    real(wp), intent(in) :: h, theta
    b%x = b%xbegin + h * ((1.0_wp - theta) * b%vbegin + theta * b%v)
    b%xbegin = b%x
    b%vbegin = b%v
  end subroutine rbdy2_end_step

  !> Kinetic energy of the free (not velocity-driven) dofs.
  pure real(wp) function rbdy2_kinetic_energy(b) result(e)
    type(rbdy2_t), intent(in) :: b
    e = 0.5_wp * sum(b%mass * b%v**2, mask=.not. b%driven)
  end function rbdy2_kinetic_energy

  !> Largest speed of a point of a rigid body of radius r: |v| + |omega| r.
  pure real(wp) function rbdy2_point_speed(v, r) result(s)
    real(wp), intent(in) :: v(3), r
    s = max(abs(v(1)), abs(v(2))) + abs(v(3)) * r
  end function rbdy2_point_speed

  !> The state check of the bodies after a step of length h: '' if sound, else
  !> what is wrong with the first faulty body (by its BODIES.DAT number): a
  !> non-finite position or velocity, or a body beyond what double precision
  !> resolves at its size (resolvable_length), in place or in one step.
  function rbdy2_fault(b, h) result(msg)
    type(rbdy2_t), intent(in) :: b
    real(wp), intent(in) :: h
    character(len=:), allocatable :: msg
    integer :: k
    real(wp) :: lim, pos, moved
    msg = ''
    if (.not. (all(ieee_is_finite(b%x)) .and. all(ieee_is_finite(b%v)))) then
      do k = 1, b%n
        if (.not. all(ieee_is_finite(b%x(:, k)))) then
          msg = 'body '//itoa(b%number(k))//' has a non-finite position ('//rtoa_list(b%x(:, k))//')'
          return
        end if
        if (.not. all(ieee_is_finite(b%v(:, k)))) then
          msg = 'body '//itoa(b%number(k))//' has a non-finite velocity ('//rtoa_list(b%v(:, k))//')'
          return
        end if
      end do
    end if
    do k = 1, b%n
      lim = resolvable_length(b%avrd(k))
      pos = max(abs(b%ref(1, k) + b%x(1, k)), abs(b%ref(2, k) + b%x(2, k)))
      moved = h * rbdy2_point_speed(b%v(:, k), b%avrd(k))
      if (pos > lim) then
        msg = 'body '//itoa(b%number(k))//' ran away: it is at '//rtoa(pos)//' from the origin, beyond '//rtoa(lim)// &
              ' (what double precision resolves at its size)'
        return
      end if
      if (moved > lim) then
        msg = 'body '//itoa(b%number(k))//' ran away: its velocity ('//rtoa_list(b%v(:, k))//') moves it by '// &
              rtoa(moved)//' in one step, beyond '//rtoa(lim)//' (what double precision resolves at its size)'
        return
      end if
    end do
  end function rbdy2_fault
end module fracas_rbdy2
