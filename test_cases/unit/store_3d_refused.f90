!> A 3D contact store given to the scene NLGS (whose kernels are 2D) must stop with a
!> message naming the dimension, not run a 2D kernel on 3D arrays (no silent stub):
!> ctest checks the message (unit.store_3d_refused).
program store_3d_refused
  use fracas_kinds, only: wp
  use fracas_contacts, only: contacts_t
  use fracas_nlgs, only: nlgs_t, nlgs_settings_t, nlgs_init, nlgs_prepare
  use fracas_sides_2d, only: bodies2_t
  use fracas_rbdy2, only: rbdy2_t
  use fracas_mailx, only: mailx_t
  use fracas_contact_laws, only: law_t
  implicit none
  type(contacts_t) :: c
  type(nlgs_t) :: solver
  type(nlgs_settings_t) :: settings
  type(rbdy2_t), target :: b
  type(mailx_t), target :: m
  type(bodies2_t) :: bd
  type(law_t) :: laws(1)
  c%nd = 3
  call nlgs_init(solver, settings)
  bd%rbdy2 => b
  bd%mailx => m
  call nlgs_prepare(solver, c, bd, laws, 1.0e-3_wp)
  print '(a)', 'not refused'
end program store_3d_refused
