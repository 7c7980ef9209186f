!> Time-step control for cracks (run control crack_step_limit, doc/czm.md §9):
!> a step in which a damaging cohesive zone's jump changes by more than
!> crack_step_limit softening lengths is done again in halves, down to
!> time_step / 2^crack_step_cuts, and the step is grown back (doubled) once the
!> increments fall below a quarter of the limit. Sub-steps stay inside the run's
!> steps: a step of time_step is cut into 2^k sub-steps that end exactly on it,
!> so output, restart points and step numbers are those of the uncut run. With
!> the limit 0 (the default) a step is one scene_step, nothing else.
module fracas_stepping
  use fracas_kinds, only: wp, i8
  use fracas_errors, only: status_t, failed
  use fracas_scene, only: scene_t, step_report_t, scene_step
  use fracas_mailx, only: mailx_set_time_step
  use fracas_restart_h5, only: restart_state_t
  use fracas_restart, only: scene_capture, scene_restore
  implicit none
  private
  public :: stepping_t, scene_advance

  !> Settings, and what the control did over the run (for the end of run summary).
  type :: stepping_t
    real(wp) :: limit = 0.0_wp         !< crack_step_limit, softening lengths per step (0: off)
    integer :: max_cuts = 10           !< crack_step_cuts: at most this many halvings
    integer :: cut_steps = 0           !< steps done in more than one sub-step
    integer(i8) :: substeps = 0        !< sub-steps of those steps
    integer(i8) :: rejected = 0        !< sub-steps done again shorter
    integer :: unmet = 0               !< sub-steps over the limit at the shortest step
    integer :: deepest = 0             !< most halvings used
  end type stepping_t

contains

  !> One step of the run (sc%h_step), cut into sub-steps as the control asks.
  !> rep: the last sub-step's state, the work (sweeps, updates, times, Newton
  !> iterations) of all sub-steps tried, converged if every kept one did.
  subroutine scene_advance(sc, ctl, rep, status)
    type(scene_t), intent(inout) :: sc
    type(stepping_t), intent(inout) :: ctl
    type(step_report_t), intent(out) :: rep
    type(status_t), intent(out) :: status
    type(step_report_t) :: sub
    type(restart_state_t) :: start
    integer(i8) :: pos, whole, span
    integer :: level, substep
    real(wp) :: t_start
    logical :: last, nlgs_converged, newton_converged
    if (ctl%limit <= 0.0_wp) then
      call scene_step(sc, rep, status)
      return
    end if
    t_start = sc%time
    whole = 2_i8**ctl%max_cuts
    pos = 0
    level = min(sc%step_level, ctl%max_cuts)
    nlgs_converged = .true.
    newton_converged = .true.
    rep%substeps = 0
    do
      span = 2_i8**(ctl%max_cuts - level)
      last = pos + span == whole
      substep = sc%substep
      ! The state to come back to, unless the step cannot be cut any further.
      if (level < ctl%max_cuts) call scene_capture(sc, start)
      ctl%deepest = max(ctl%deepest, level)
      call set_time_step(sc, sc%h_step / real(2_i8**level, wp), status)
      if (failed(status)) return
      call scene_step(sc, sub, status, finishes_step=last)
      if (failed(status)) return
      call add_work(rep, sub)
      if (sub%crack_increment > ctl%limit .and. level < ctl%max_cuts) then
        ! Too long for the crack: the same sub-step again, in halves.
        call scene_restore(sc, start, checked=.false.)
        sc%substep = substep
        level = level + 1
        ctl%rejected = ctl%rejected + 1
        rep%rejected = rep%rejected + 1
        cycle
      end if
      if (sub%crack_increment > ctl%limit) ctl%unmet = ctl%unmet + 1
      call keep_state(rep, sub)
      nlgs_converged = nlgs_converged .and. sub%nlgs%converged
      newton_converged = newton_converged .and. sub%newton_converged
      rep%crack_increment = max(rep%crack_increment, sub%crack_increment)
      pos = pos + span
      ! Grow back once the crack has slowed, where the longer step fits.
      if (level > 0 .and. sub%crack_increment < 0.25_wp * ctl%limit .and. mod(pos, 2_i8 * span) == 0) &
        level = level - 1
      if (pos == whole) exit
    end do
    rep%nlgs%converged = nlgs_converged
    rep%newton_converged = newton_converged
    ! The step ends on the run's time grid, as an uncut step does.
    if (rep%substeps > 1) sc%time = t_start + sc%h_step
    sc%step_level = level
    if (rep%substeps > 1) then
      ctl%cut_steps = ctl%cut_steps + 1
      ctl%substeps = ctl%substeps + rep%substeps
    end if
  contains

    !> The work of sub-step s (kept or not) added to the step's.
    subroutine add_work(r, s)
      type(step_report_t), intent(inout) :: r
      type(step_report_t), intent(in) :: s
      r%nlgs%sweeps = r%nlgs%sweeps + s%nlgs%sweeps
      r%nlgs%updates = r%nlgs%updates + s%nlgs%updates
      r%nlgs%velocity_seconds = r%nlgs%velocity_seconds + s%nlgs%velocity_seconds
      r%newton_iterations = r%newton_iterations + s%newton_iterations
      r%bodies_seconds = r%bodies_seconds + s%bodies_seconds
      r%detect_seconds = r%detect_seconds + s%detect_seconds
      r%prepare_seconds = r%prepare_seconds + s%prepare_seconds
      r%solve_seconds = r%solve_seconds + s%solve_seconds
      r%velocity_seconds = r%velocity_seconds + s%velocity_seconds
      r%step_seconds = r%step_seconds + s%step_seconds
    end subroutine add_work

    !> A kept sub-step: its end state is the step's so far.
    subroutine keep_state(r, s)
      type(step_report_t), intent(inout) :: r
      type(step_report_t), intent(in) :: s
      r%substeps = r%substeps + 1
      r%contacts = s%contacts
      r%kinetic = s%kinetic
      r%mean_overlap = s%mean_overlap
      r%max_overlap = max(r%max_overlap, s%max_overlap)
      r%late_contacts = r%late_contacts + s%late_contacts
      r%late_overlap = max(r%late_overlap, s%late_overlap)
      r%nlgs%residual = max(r%nlgs%residual, s%nlgs%residual)
      r%nlgs%residual_onepq = max(r%nlgs%residual_onepq, s%nlgs%residual_onepq)
      r%nlgs%quad_dv = s%nlgs%quad_dv
      r%nlgs%maxm_dv = s%nlgs%maxm_dv
      r%nlgs%quad_dvr = s%nlgs%quad_dvr
      r%nlgs%maxm_dvr = s%nlgs%maxm_dvr
      r%nlgs%mean_dvor = s%nlgs%mean_dvor
      r%nlgs%nactive = s%nlgs%nactive
    end subroutine keep_state
  end subroutine scene_advance

  !> Sub-steps of length h (the meshes' iteration matrices follow).
  subroutine set_time_step(sc, h, status)
    type(scene_t), intent(inout) :: sc
    real(wp), intent(in) :: h
    type(status_t), intent(inout) :: status
    sc%h = h
    if (sc%meshes%n > 0) call mailx_set_time_step(sc%meshes, h, status)
  end subroutine set_time_step
end module fracas_stepping
