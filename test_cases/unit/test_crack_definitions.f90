!> The definitions behind the crack results (fracas_cracks, doc/fracture.md), pinned on
!> a hand-made interface: two edges of two glued points each (lengths 2 and 3).
!> * a point is glued when its cohesive contact has beta > 0 at the first step;
!> * an edge is broken when ALL its glued points are broken (beta = 0, or their
!>   contact lost), damaged when some point has beta < 1: one broken point of two
!>   leaves the edge damaged, not broken (a rule "any point broken" is caught here);
!> * the broken length is the sum of the broken edges' lengths, the damaged length that
!>   of the damaged edges not broken;
!> * each point's released damage energy (coh_released of its contact, as the solver
!>   books it) goes to its edge's family when its beta drops.
program test_crack_definitions
  use fracas_kinds, only: wp
  use fracas_cracks, only: cracks_t, cracks_update, cracks_lengths
  use fracas_contacts, only: contacts_t, contacts_reserve
  use fracas_contact_laws, only: law_t, law_czm, coh_released
  use fracas_ids, only: bm_rigid
  use fracas_testing, only: check_close, check_true, test_finish
  implicit none
  type(cracks_t) :: cr
  type(contacts_t) :: c
  type(law_t) :: laws(1)
  real(wp) :: broken, damaged, fam(1)
  integer :: nbroken, ndamaged

  cr%npts = 4; cr%nedges = 2; cr%nfamilies = 1
  cr%tactor_pt = [1, 2, 3, 4]                 ! contactors 1..4 are the candidate points
  cr%pt_edge = [1, 1, 2, 2]
  cr%pt_beta = [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp]
  cr%pt_glued = [.false., .false., .false., .false.]
  cr%pt_seen = cr%pt_glued
  cr%pt_partner = [0, 0, 0, 0]
  cr%pt_an = [0, 0, 0, 0]
  cr%edge_first = [1, 3, 5]
  cr%edge_pts = [1, 2, 3, 4]
  cr%edge_length = [2.0_wp, 3.0_wp]
  cr%edge_family = [1, 1]
  cr%edge_broken_step = [0, 0]
  cr%family_damage = [0.0_wp]
  laws(1)%kind = law_czm

  c%with_cohesion = .true.
  call contacts_reserve(c, 4)
  c%n = 4
  c%cd(1:4) = [1, 2, 3, 4]
  c%an(1:4) = [10, 10, 11, 11]
  c%anm(1:4) = bm_rigid
  c%law(1:4) = 1
  c%internals(:, 1:4) = 0.0_wp
  c%internals(4, 1:4) = 1.0_wp
  c%coh(coh_released(2), 1:4) = 0.0_wp

  ! Step 1: every point glued, nothing damaged.
  call cracks_update(cr, c, laws, .true., 1)
  call check_true('all four points glued at the first step', all(cr%pt_glued))
  call cracks_lengths(cr, broken, damaged, fam, nbroken, ndamaged)
  call check_close('step 1: broken length', broken, 0.0_wp, 0.0_wp)

  ! Step 2: edge 1 has one broken point and one at beta 0.5; edge 2 both broken.
  c%internals(4, 1:4) = [0.0_wp, 0.5_wp, 0.0_wp, 0.0_wp]
  c%coh(coh_released(2), 1:4) = [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp]
  call cracks_update(cr, c, laws, .false., 2)
  call check_true('edge 1 (one point of two broken) is not broken', cr%edge_broken_step(1) == 0)
  call check_true('edge 2 (both points broken) broken at step 2', cr%edge_broken_step(2) == 2)
  call cracks_lengths(cr, broken, damaged, fam, nbroken, ndamaged)
  call check_close('step 2: broken length = length of edge 2', broken, 3.0_wp, 0.0_wp)
  call check_close('step 2: damaged length = length of edge 1', damaged, 2.0_wp, 0.0_wp)
  call check_true('step 2: one broken, one damaged edge', nbroken == 1 .and. ndamaged == 1)
  call check_close('step 2: family damage = sum of the released energies', cr%family_damage(1), 10.0_wp, 0.0_wp)

  ! Step 3: point 2's contact is lost (separated beyond the alert distance): broken.
  c%n = 3
  c%cd(1:3) = [1, 3, 4]
  c%an(1:3) = [10, 11, 11]
  c%internals(4, 1:3) = 0.0_wp
  c%coh(coh_released(2), 1:3) = 0.0_wp
  call cracks_update(cr, c, laws, .false., 3)
  call check_true('edge 1 broken at step 3 (its last glued point lost)', cr%edge_broken_step(1) == 3)
  call cracks_lengths(cr, broken, damaged, fam, nbroken, ndamaged)
  call check_close('step 3: broken length = 2 + 3', broken, 5.0_wp, 0.0_wp)
  call check_close('step 3: broken length of the family', fam(1), 5.0_wp, 0.0_wp)
  call test_finish()
end program test_crack_definitions
