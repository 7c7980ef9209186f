!> The contact history: exact keys (type, candidate, antagonist, vertex) and the
!> fallback by position that keeps a contact's past when its key changed (roles
!> swapped between steps, or the contact point moved to another vertex).
program test_history
  use fracas_kinds, only: wp
  use fracas_contacts, only: history_t, history_build, history_find, history_find_near, history_knows_pair
  use fracas_testing, only: check_true, check_close, test_finish
  implicit none
  type(history_t) :: h
  integer :: pos
  logical :: swapped
  ! Three past contacts between contactors: 2->1 at two points (vertices 1 and 2), 3->1 at one.
  call history_build(h, 4, cd=[2, 2, 3], an=[1, 1, 1], sub=[1, 2, 4], inter=[5, 5, 5], status=[2, 2, 3], &
                     force=reshape([1.0_wp, 10.0_wp, 2.0_wp, 20.0_wp, 3.0_wp, 30.0_wp], [2, 3]), &
                     point=reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 5.0_wp, 5.0_wp], [2, 3]))
  pos = history_find(h, 5, 2, 1, 2)
  call check_close('exact key finds the second point (force rn 20)', h%force(2, pos), 20.0_wp, 0.0_wp)
  call check_true('a key that was never there is not found', history_find(h, 5, 1, 2, 1) == 0)
  ! Roles swapped (candidate 1, antagonist 2), point near the second past point.
  call history_find_near(h, 5, 1, 2, [0.98_wp, 0.01_wp], 0.25_wp, pos, swapped)
  call check_true('swapped roles found by position', pos > 0 .and. swapped)
  call check_close('... and it is the nearest past point (rn 20)', h%force(2, pos), 20.0_wp, 0.0_wp)
  ! Same roles, vertex renumbered: found, not swapped.
  call history_find_near(h, 5, 3, 1, [5.1_wp, 5.0_wp], 0.25_wp, pos, swapped)
  call check_true('same roles found by position, not swapped', pos > 0 .and. .not. swapped)
  ! Beyond the tolerance: nothing.
  call history_find_near(h, 5, 1, 2, [0.5_wp, 0.0_wp], 0.25_wp, pos, swapped)
  call check_true('no past point within the tolerance', pos == 0)
  call check_true('pair 1-2 known in either role', history_knows_pair(h, 1, 2) .and. history_knows_pair(h, 2, 1))
  call check_true('pair 1-4 unknown', .not. history_knows_pair(h, 1, 4))
  call test_finish()
end program test_history
