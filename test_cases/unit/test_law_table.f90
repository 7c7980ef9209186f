!> One list of the contact laws: the reader's table (fracas_read_tact_behav) marks
!> the laws the solver runs, and the solver's refusal message is built from it.
!> Here every law so marked must be built by law_from_input (a law marked but
!> unknown to the solver stops this program with its input error), with its name,
!> and the marked list is a strict subset of the laws read. Parameters: friction
!> 0.3, restitutions 0.3, cn = ct = 1e12, then 0.5 for the rest (visco, w, smax,
!> s1, s2, G1, G2, dp1, dp2, eta: each within its accepted range).
program test_law_table
  use fracas_kinds, only: wp
  use fracas_deck, only: law_input_t
  use fracas_read_tact_behav, only: known_laws, law_param_count
  use fracas_contact_laws, only: law_t, law_from_input
  use fracas_testing, only: check_true, test_finish
  implicit none
  character(len=:), allocatable :: list, name
  type(law_input_t) :: inp
  type(law_t) :: law
  integer :: p, q

  list = known_laws(solver=.true.)
  call check_true('solver laws listed', len(list) > 0)
  call check_true('solver laws are fewer than the laws read', len(list) < len(known_laws()))
  p = 1
  do while (p <= len(list))
    q = index(list(p:), ', ')
    if (q == 0) then
      name = list(p:)
      p = len(list) + 1
    else
      name = list(p:p + q - 2)
      p = p + q + 1
    end if
    inp%nickname = 'law01'
    inp%name = name
    inp%params = [0.3_wp, 0.3_wp, 1.0e12_wp, 1.0e12_wp, 0.5_wp, 0.5_wp, 0.5_wp, 0.5_wp, 0.5_wp, 0.5_wp]
    if (name(1:4) == 'RST_') inp%params(3:4) = 0.3_wp
    ! ABP: du1 du2 phi, corners that make its tri-linear envelope (area G)
    if (index(name, 'ABP_CZM') > 0) inp%params = [inp%params, 0.2_wp]
    call check_true(name//': read by the reader', law_param_count(name) >= 0)
    law = law_from_input(inp)
    call check_true(name//': built by the solver', trim(law%name) == name .and. law%kind /= 0)
  end do
  call test_finish()
end program test_law_table
