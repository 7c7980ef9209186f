!> Driven degrees of freedom (DRV_DOF.DAT) of any body model: an imposed
!> velocity or an added force, as a function of time. The body model says what
!> `target` and `dof` index (a rigid body and its dof 1..3, a mesh node and its
!> dof 1..2).
module fracas_drives
  use fracas_kinds, only: wp
  use fracas_deck, only: driven_dof_input_t
  use fracas_errors, only: input_error
  implicit none
  private
  public :: drive_t, drive_from_input, drive_value, drives_build, drives_begin_step, drives_impose_end, drives_add_work

  type :: drive_t
    integer :: body = 0, dof = 0         !< body (rigid) or mesh node, and its dof
    logical :: is_velocity = .true.
    real(wp) :: ct = 0.0_wp, amp = 0.0_wp, omega = 0.0_wp, phi = 0.0_wp, rampi = 0.0_wp, ramp = 0.0_wp
    real(wp), allocatable :: evo_t(:), evo_v(:)   !< evolution table, used if allocated
  end type drive_t

contains

  !> The drive of one DRV_DOF.DAT line, acting on `target` (body or mesh node).
  function drive_from_input(inp, target) result(d)
    type(driven_dof_input_t), intent(in) :: inp
    integer, intent(in) :: target
    type(drive_t) :: d
    d%body = target
    d%dof = inp%dof
    d%is_velocity = inp%kind == 'vlocy'
    d%ct = inp%ct; d%amp = inp%amp; d%omega = inp%omega; d%phi = inp%phi
    d%rampi = inp%rampi; d%ramp = inp%ramp
    if (inp%evolution) then
      d%evo_t = inp%evo_t
      d%evo_v = inp%evo_v
    end if
  end function drive_from_input

  !> Value of a driven dof at time t: (CT + AMP cos(OMEGA t + PHI)) min(1, RAMPI + RAMP t),
  !> or the linear interpolation of its evolution table (end segments extrapolated).
  pure real(wp) function drive_value(d, t) result(val)
    type(drive_t), intent(in) :: d
    real(wp), intent(in) :: t
    integer :: lo, hi, mid, n
    if (allocated(d%evo_t)) then
      n = size(d%evo_t)
      if (n == 1) then
        val = d%evo_v(1)
        return
      end if
      lo = 1; hi = n
      do while (hi - lo > 1)
        mid = (lo + hi) / 2
        if (d%evo_t(mid) <= t) then
          lo = mid
        else
          hi = mid
        end if
      end do
      val = d%evo_v(lo) + (d%evo_v(hi) - d%evo_v(lo)) * (t - d%evo_t(lo)) / (d%evo_t(hi) - d%evo_t(lo))
    else
      val = (d%ct + d%amp * cos(d%omega * t + d%phi)) * min(1.0_wp, d%rampi + d%ramp * t)
    end if
  end function drive_value

  ! The drives of a rigid body model whose dofs are arrays (ndof, nbodies):
  ! rbdy2 and rbdy3.

  !> All the drives of DRV_DOF.DAT (body serial number = index): velocity-driven
  !> dofs marked, their inverse mass 0, a body with every dof driven clamped.
  subroutine drives_build(inputs, driven, inv_mass, clamped, drives)
    type(driven_dof_input_t), intent(in) :: inputs(:)
    logical, intent(inout) :: driven(:, :), clamped(:)
    real(wp), intent(inout) :: inv_mass(:, :)
    type(drive_t), allocatable, intent(out) :: drives(:)
    integer :: k
    allocate (drives(size(inputs)))
    do k = 1, size(inputs)
      associate (inp => inputs(k), d => drives(k))
        if (inp%body < 1 .or. inp%body > size(clamped)) &
          call input_error(inp%src%file, inp%src%line, 9, 'driven body number out of range')
        if (inp%dof < 1 .or. inp%dof > size(driven, 1)) &
          call input_error(inp%src%file, inp%src%line, 9, 'dof index out of range')
        d = drive_from_input(inp, inp%body)
        if (d%is_velocity) then
          driven(d%dof, d%body) = .true.
          inv_mass(d%dof, d%body) = 0.0_wp
          clamped(d%body) = all(driven(:, d%body))
        end if
      end associate
    end do
  end subroutine drives_build

  !> Start of a step [t, t+h]: force drives theta-averaged into fext; a
  !> velocity-driven dof starts at its value at t (unless impose_start is false:
  !> it keeps its previous velocity).
  subroutine drives_begin_step(drives, t, h, theta, fext, vbegin, impose_start)
    type(drive_t), intent(in) :: drives(:)
    real(wp), intent(in) :: t, h, theta
    real(wp), intent(inout) :: fext(:, :), vbegin(:, :)
    logical, intent(in), optional :: impose_start
    integer :: k
    logical :: impose
    impose = .true.
    if (present(impose_start)) impose = impose_start
    do k = 1, size(drives)
      associate (d => drives(k))
        if (d%is_velocity) then
          if (impose) vbegin(d%dof, d%body) = drive_value(d, t)
        else
          fext(d%dof, d%body) = fext(d%dof, d%body) + (1.0_wp - theta) * drive_value(d, t) + &
                                theta * drive_value(d, t + h)
        end if
      end associate
    end do
  end subroutine drives_begin_step

  !> A velocity-driven dof ends the step [t, t+h] at its value at t + h.
  subroutine drives_impose_end(drives, t, h, v)
    type(drive_t), intent(in) :: drives(:)
    real(wp), intent(in) :: t, h
    real(wp), intent(inout) :: v(:, :)
    integer :: k
    do k = 1, size(drives)
      if (drives(k)%is_velocity) v(drives(k)%dof, drives(k)%body) = drive_value(drives(k), t + h)
    end do
  end subroutine drives_impose_end

  !> Work of the force drives over the step [t, t+h] (theta rule on the
  !> displacement of their dofs), added to work.
  pure subroutine drives_add_work(drives, t, h, theta, vbegin, v, work)
    type(drive_t), intent(in) :: drives(:)
    real(wp), intent(in) :: t, h, theta, vbegin(:, :), v(:, :)
    real(wp), intent(inout) :: work
    integer :: k
    do k = 1, size(drives)
      associate (d => drives(k))
        if (d%is_velocity) cycle
        work = work + h * ((1.0_wp - theta) * vbegin(d%dof, d%body) + theta * v(d%dof, d%body)) * &
               ((1.0_wp - theta) * drive_value(d, t) + theta * drive_value(d, t + h))
      end associate
    end do
  end subroutine drives_add_work
end module fracas_drives
