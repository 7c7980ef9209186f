!> The rigid body model's own procedures that the scene calls instead of reading its
!> arrays (doc/architecture.md, "The body-model interface"): its energy terms, its state
!> check, its restart state and its DOF.OUT records. References are worked by hand here:
!> two bodies (numbers 5 and 7, masses 2 and 3, radius 0.1), gravity (0, -10), h = 0.01,
!> theta = 0.5.
program test_rbdy2_model
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use, intrinsic :: ieee_exceptions, only: ieee_invalid, ieee_get_halting_mode, ieee_set_halting_mode, ieee_set_flag
  use fracas_kinds, only: wp
  use fracas_deck, only: dof_record_t
  use fracas_energy, only: energy_terms_t
  use fracas_rbdy2, only: rbdy2_t, rbdy2_init, rbdy2_add_step_work, rbdy2_energy_terms, rbdy2_fault, &
                          rbdy2_save_state, rbdy2_restore_state, rbdy2_dof_records
  use fracas_testing, only: check_close, check_true, test_finish
  implicit none
  type(rbdy2_t) :: b, saved
  type(energy_terms_t) :: e
  type(dof_record_t), allocatable :: dofs(:)
  real(wp), parameter :: h = 0.01_wp, theta = 0.5_wp
  real(wp) :: imp(3, 2), work(3)
  real(wp), allocatable :: x(:, :), v(:, :)
  character(len=:), allocatable :: msg
  logical :: halt

  call rbdy2_init(b, [5, 7], reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp], [3, 2]), &
                  [2.0_wp, 3.0_wp], [0.01_wp, 0.015_wp], [0.1_wp, 0.1_wp], [0.0_wp, -10.0_wp])

  ! Energy terms. Body 5 falls from vy = -1 to -1.1: dy = h (vbegin + v) / 2 = -0.0105,
  ! work of gravity m g dy = 2 * 10 * 0.0105 = 0.21. Body 7's x velocity is driven
  ! (1 at the start, 3 at the end) and the contacts push it with impulse 2 along x:
  ! the supports' work is -2 (1 + 3) / 2 = -4; its y dof (vy = 0) does no work.
  b%vbegin(2, 1) = -1.0_wp
  b%v(2, 1) = -1.1_wp
  b%driven(1, 2) = .true.
  b%vbegin(1, 2) = 1.0_wp
  b%v(1, 2) = 3.0_wp
  imp = 0.0_wp
  imp(1, 2) = 2.0_wp
  imp(2, 1) = 5.0_wp        ! on a free dof: no support work
  call rbdy2_add_step_work(b, 0.0_wp, h, theta, imp)
  e = rbdy2_energy_terms(b)
  call check_close('work of gravity', e%work_gravity, 0.21_wp, 1.0e-14_wp)
  call check_close('work of the supports', e%work_supports, -4.0_wp, 1.0e-14_wp)
  call check_close('work of forces (no force drive)', e%work_forces, 0.0_wp, 0.0_wp)
  call check_close('a rigid body stores no elastic energy', e%elastic, 0.0_wp, 0.0_wp)
  call rbdy2_add_step_work(b, 0.0_wp, h, theta, imp)
  e = rbdy2_energy_terms(b)
  call check_close('the terms accumulate over steps', e%work_supports, -8.0_wp, 1.0e-14_wp)

  ! State check: sound, then a non-finite position, then a body beyond what double
  ! precision resolves at its size (1e-3 * 0.1 / eps = 4.5e11).
  call check_true('a sound state', len(rbdy2_fault(b, h)) == 0)
  saved = b
  call ieee_get_halting_mode(ieee_invalid, halt)     ! (debug builds trap: the message prints the NaN)
  call ieee_set_halting_mode(ieee_invalid, .false.)
  b%x(2, 2) = ieee_value(1.0_wp, ieee_quiet_nan)
  msg = rbdy2_fault(b, h)
  call check_true('non-finite position names body 7: '//msg, index(msg, 'body 7 has a non-finite position') == 1)
  call ieee_set_flag(ieee_invalid, .false.)
  call ieee_set_halting_mode(ieee_invalid, halt)
  b = saved
  b%x(1, 1) = 1.0e12_wp
  msg = rbdy2_fault(b, h)
  call check_true('runaway position names body 5: '//msg, index(msg, 'body 5 ran away: it is at 1.00000E+12') == 1)
  b = saved
  b%v(3, 2) = 1.0e16_wp    ! the rim moves 1e16 * 0.1 * h = 1e13 in one step
  msg = rbdy2_fault(b, h)
  call check_true('runaway velocity names body 7: '//msg, index(msg, 'body 7 ran away: its velocity') == 1)
  b = saved

  ! Restart state: what rbdy2_save_state takes, rbdy2_restore_state gives back, the
  ! end of that step being the beginning of the next.
  b%x(:, 1) = [0.1_wp, -0.2_wp, 0.3_wp]
  call rbdy2_save_state(b, x, v, work)
  call check_close('saved work of the supports', work(3), -8.0_wp, 0.0_wp)
  b%x = 0.0_wp; b%v = 0.0_wp; b%work_supports = 0.0_wp; b%work_gravity = 0.0_wp
  call rbdy2_restore_state(b, x, v, work)
  call check_true('restored positions', all(b%x == x) .and. all(b%xbegin == x))
  call check_true('restored velocities', all(b%v == saved%v) .and. all(b%vbegin == saved%v))
  e = rbdy2_energy_terms(b)
  call check_close('restored work of gravity', e%work_gravity, 0.42_wp, 1.0e-14_wp)
  call check_close('restored work of the supports', e%work_supports, -8.0_wp, 0.0_wp)

  ! DOF.OUT records: one RBDY2 block per body, by its BODIES.DAT number.
  dofs = rbdy2_dof_records(b)
  call check_true('two records', size(dofs) == 2)
  call check_true('records are RBDY2 blocks', all(dofs%model == 'RBDY2'))
  call check_true('records carry the body numbers', all(dofs%body == [5, 7]))
  call check_true('record x and v', all(dofs(1)%x == [0.1_wp, -0.2_wp, 0.3_wp]) .and. all(dofs(2)%v == b%v(:, 2)))
  call test_finish()
end program test_rbdy2_model
