!> The energy terms a body model adds to the scene's energy audit (J per unit
!> thickness, accumulated over the run): each model reports its own
!> (rbdy2_energy_terms, mailx_energy_terms) and the scene adds them up
!> (scene_energy_terms). The kinetic energy is each model's *_kinetic_energy.
module fracas_energy
  use fracas_kinds, only: wp
  implicit none
  private
  public :: energy_terms_t, energy_add

  type :: energy_terms_t
    real(wp) :: work_gravity = 0.0_wp    !< work of gravity on the free dofs
    real(wp) :: work_forces = 0.0_wp     !< work of the force drives
    real(wp) :: work_supports = 0.0_wp   !< work of the velocity-driven dofs through the contacts
    real(wp) :: elastic = 0.0_wp         !< strain energy stored now
    real(wp) :: plastic = 0.0_wp         !< plastic work
  end type energy_terms_t

contains

  !> e += t, term by term.
  pure subroutine energy_add(e, t)
    type(energy_terms_t), intent(inout) :: e
    type(energy_terms_t), intent(in) :: t
    e%work_gravity = e%work_gravity + t%work_gravity
    e%work_forces = e%work_forces + t%work_forces
    e%work_supports = e%work_supports + t%work_supports
    e%elastic = e%elastic + t%elastic
    e%plastic = e%plastic + t%plastic
  end subroutine energy_add
end module fracas_energy
