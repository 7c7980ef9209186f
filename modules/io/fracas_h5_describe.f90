!> Units and a one-line description on every dataset of a results file.
!> h5_describe_dataset, fracas_h5's dataset hook while a results file is written,
!> gives each dataset as it is created the attributes `units` and `description` of
!> its entry in the table below (found by its path with every number replaced by N, e.g.
!> snapshots/N/contacts/gap). Units name the quantity in the deck's units
!> (the root attribute `units`): length, time, mass, force, energy, ...; '1'
!> is dimensionless, '-' an index, id, flag or name; 's' wall or CPU seconds.
module fracas_h5_describe
  use hdf5, only: hid_t
  use fracas_h5, only: h5_write_attr
  implicit none
  private
  public :: h5_describe_dataset, dataset_info

  character(len=*), parameter :: sep = '|'
  !> 'path|units|description' (path: numbers as N; '*' ends a prefix match).
  character(len=160), parameter :: table(*) = [character(len=160) :: &
    'bodies/number|-|serial number of each rigid body (RBDY2 numbering of BODIES.DAT)', &
    'bodies/mass|mass|mass of each rigid body', &
    'bodies/inertia|mass*length^2|moment of inertia of each rigid body about its centre', &
    'bodies/radius|length|average radius of each rigid body (LMGC90 avrd)', &
    'bodies/reference|length, rad|reference position (x, y, angle) of each rigid body', &
    'contactors/model|-|body model of each contactor (1 RBDY2, 2 MAILx)', &
    'contactors/body|-|body of each contactor (RBDY2 serial number, MAILx body index)', &
    'contactors/rank|-|rank of the contactor within its body', &
    'contactors/kind|-|contactor kind id (kind_names names them)', &
    'contactors/kind_names|-|names of the contactor kind ids 1, 2, ...', &
    'contactors/color|-|colour of each contactor (BODIES.DAT)', &
    'contactors/radius|length|radius of disks and drums (0 otherwise)', &
    'contactors/half_length|length|half length of walls (JONCx axe1)', &
    'contactors/half_thickness|length|half thickness of walls (JONCx axe2)', &
    'contactors/shift|length|offset of the contactor from its body centre, body frame', &
    'contactors/vertex_first|-|first vertex of each polygon in vertices (0-based)', &
    'contactors/vertex_count|-|number of vertices of each polygon', &
    'contactors/vertices|length|polygon vertices in their body frame', &
    'contactors/node_first|-|first node of each mesh contactor in nodes (0-based)', &
    'contactors/node_count|-|number of nodes of each mesh contactor', &
    'contactors/nodes|-|mesh nodes (within the body) of the mesh contactors', &
    'contactors/apab|1|apab of CLxxx contactors (position of the candidate point on its edge)', &
    'help/series_columns|-|names of the /series datasets in column order', &
    'help/status|-|names of the contact status ids 1, 2, ...', &
    'help/inter|-|names of the interaction type ids 1, 2, ...', &
    'help/law|-|names of the contact law ids 1, 2, ... (TACT_BEHAV.DAT nicknames)', &
    'run/settings|-|the --set KEY=VALUE settings, in the order given', &
    'run/control|-|every run-control setting the run used as keyword value (a COMMAND.DAT)', &
    'mesh/reference|length|reference coordinates of the mesh nodes', &
    'mesh/body_first_node|-|first node of each meshed body (1-based; last entry: nodes + 1)', &
    'mesh/body_first_element|-|first element of each meshed body (1-based; last entry: elements + 1)', &
    'mesh/element_vtk_type|-|VTK cell type of each element', &
    'mesh/element_first_node|-|first entry of each element in element_nodes (1-based)', &
    'mesh/element_nodes|-|nodes of the elements (1-based mesh node numbers)', &
    'mesh/element_first_gauss_point|-|first Gauss point of each element (1-based)', &
    'mesh/element_material|-|material index of each element (BULK_BEHAV.DAT order)', &
    'mesh/interface_edge_nodes|-|the two mesh nodes of each cohesive interface edge', &
    'mesh/interface_edge_family|-|interface family of each edge (index in the interface_families attribute)', &
    'mesh/interface_edge_length|length|reference length of each interface edge', &
    'snapshot_index/step|-|step of each snapshot', &
    'snapshot_index/time|time|time of each snapshot', &
    'snapshots/N/bodies/X|length, rad|displacement (x, y, rotation) of each rigid body from bodies/reference', &
    'snapshots/N/bodies/V|length/time, rad/time|velocity (vx, vy, spin) of each rigid body', &
    'snapshots/N/contacts/inter|-|interaction type id of each contact (help/inter)', &
    'snapshots/N/contacts/cd_body|-|candidate body of each contact', &
    'snapshots/N/contacts/an_body|-|antagonist body of each contact', &
    'snapshots/N/contacts/cd_tactor|-|rank of the candidate contactor within its body', &
    'snapshots/N/contacts/an_tactor|-|rank of the antagonist contactor within its body', &
    'snapshots/N/contacts/status|-|status id of each contact (help/status)', &
    'snapshots/N/contacts/law|-|contact law id of each contact (help/law)', &
    'snapshots/N/contacts/normal|1|unit normal (x, y) of each contact', &
    'snapshots/N/contacts/point|length|contact point (x, y)', &
    'snapshots/N/contacts/reaction|force|reaction (rt, rn) of each contact, local frame', &
    'snapshots/N/contacts/velocity|length/time|relative velocity (ut, un) of each contact, local frame', &
    'snapshots/N/contacts/gap|length|predicted end-of-step gap of each contact', &
    'snapshots/N/contacts/internals|-|internal variables of the contact law (cohesive: see doc/czm.md)', &
    'snapshots/N/contacts/broken|-|1 for a cohesive contact whose interface is broken', &
    'snapshots/N/cd_model|-|model of the candidate body of each contact (1 RBDY2, 2 MAILx)', &
    'snapshots/N/an_model|-|model of the antagonist body of each contact (1 RBDY2, 2 MAILx)', &
    'snapshots/N/mesh_X|length|displacement of each mesh node from mesh/reference', &
    'snapshots/N/mesh_V|length/time|velocity of each mesh node', &
    'snapshots/N/mesh_F_support|force|force of the velocity drives on each mesh node', &
    'snapshots/N/mesh_gauss_points|force/length^2, 1|Gauss-point state: stress, strain, plastic strain, p (mesh gauss_point_fields)', &
    'snapshots/N/cracks/points|length|vertices of the crack paths, current configuration', &
    'snapshots/N/cracks/segments|-|the two points (1-based) of each crack segment', &
    'snapshots/N/cracks/segment_crack|-|crack of each segment (1 = the longest)', &
    'snapshots/N/cracks/crack_length|length|length of each crack, longest first', &
    'snapshots/N/cracks/main_origin|length|origin of the longest crack, reference configuration', &
    'snapshots/N/cracks/main_tip|length|tip of the longest crack, reference configuration', &
    'snapshots/N/cracks/broken_length_per_family|length|broken interface length per interface family', &
    'snapshots/N/cracks/damage_per_family|energy|energy dissipated by damage per interface family', &
    'snapshots/N/cracks/edge_broken_step|-|step at which each interface edge broke (0: sound)', &
    'snapshots/N/cracks/edge_beta|1|cohesion beta of each interface edge (1 sound, 0 broken)', &
    'snapshots/N/cracks/fragment_of_body|-|fragment of each meshed body', &
    'snapshots/N/cracks/fragments/bodies|-|meshed bodies in each fragment', &
    'snapshots/N/cracks/fragments/elements|-|elements in each fragment', &
    'snapshots/N/cracks/fragments/mass|mass|mass of each fragment (lumped nodal masses, per unit thickness)', &
    'snapshots/N/cracks/fragments/centre|length|centre of mass (x, y) of each fragment, current configuration', &
    'snapshots/N/cracks/fragments/velocity|length/time|velocity (x, y) of the centre of mass of each fragment', &
    'snapshots/N/cracks/fragments/kinetic_energy|energy|kinetic energy of each fragment', &
    'snapshots/N/cracks/fragments/second_moments|mass*length^2|second moments of mass Jxx, Jyy, Jxy about the centre', &
    'snapshots/N/cracks/fragments/polar_moment|mass*length^2|polar moment of inertia Jxx + Jyy about the centre', &
    'snapshots/N/cracks/fragments/principal_moments|mass*length^2|principal second moments, largest first', &
    'snapshots/N/cracks/fragments/principal_angle|rad|angle of the major principal axis from x', &
    'series/fragments|-|fragments (pieces of meshed bodies held by unbroken interfaces)', &
    'restart/*|-|state for a bit-for-bit restart (doc/restart.md); not a result', &
    'series/step|-|step number', &
    'series/time|time|time at the end of the step', &
    'series/contacts|-|contacts in the step', &
    'series/active_contacts|-|contacts with a nonzero reaction', &
    'series/sweeps|-|NLGS sweeps of the step', &
    'series/converged|-|1 if the NLGS (and the Newton loop of meshes) converged, 0 if not', &
    'series/residual_natural_map|force|worst natural-map residual of the contacts (not the convergence test)', &
    'series/residual_onepq|1|LMGC90 one-plus-q residual', &
    'series/quad_dv|1|LMGC90 Quad norm of the velocity change (the convergence test with nlgs_check Quad)', &
    'series/maxm_dv|1|LMGC90 Maxm norm of the velocity change', &
    'series/mean_dvor|1|LMGC90 mean relative velocity change norm', &
    'series/kinetic_energy|energy|kinetic energy of all bodies', &
    'series/work_gravity|energy|work of gravity since the start', &
    'series/work_forces|energy|work of the imposed forces since the start', &
    'series/work_supports|energy|work of the velocity drives since the start', &
    'series/dissipated|energy|energy dissipated by the contacts since the start', &
    'series/cohesive_energy|energy|elastic energy stored in the cohesive interfaces', &
    'series/damage_dissipated|energy|energy dissipated by cohesive damage since the start', &
    'series/balance_error|energy|energy balance error: stored + dissipated - work - initial', &
    'series/mean_overlap|length|mean overlap of the overlapping contacts', &
    'series/max_overlap|length|largest overlap', &
    'series/solve_time|s|wall seconds of the NLGS', &
    'series/step_time|s|wall seconds of the whole step', &
    'series/elastic_energy|energy|strain energy of the meshed bodies', &
    'series/plastic_work|energy|plastic work of the meshed bodies since the start', &
    'series/newton_iterations|-|Newton iterations of the meshed bodies in the step', &
    'series/crack_length|length|broken interface length', &
    'series/damaged_length|length|damaged (beta < 1) interface length', &
    'series/broken_interfaces|-|broken interface edges', &
    'series/damaged_interfaces|-|damaged interface edges', &
    'series/bodies_time|s|wall seconds of the bodies (free velocities, meshes)', &
    'series/detect_time|s|wall seconds of contact detection', &
    'series/prepare_time|s|wall seconds of preparing the contacts for the NLGS', &
    'series/contact_updates|-|local contact updates of the NLGS in the step', &
    'series/velocity_time|s|wall seconds of the velocity and position update', &
    'series/substeps|-|sub-steps the step was cut into (crack_step_limit; 1: not cut)', &
    'series/rejected_substeps|-|sub-steps done again shorter in the step (crack_step_limit)', &
    'series/crack_increment|1|largest change of a damaging cohesive jump in a (sub-)step, in softening lengths']

contains

  !> Write the attributes units and description of the table's entry for PATH on dset
  !> (fracas_h5's dataset hook: called as each dataset is created).
  subroutine h5_describe_dataset(dset, path)
    integer(hid_t), intent(in) :: dset
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: units, descr
    call dataset_info(path, units, descr)
    call h5_write_attr(dset, 'units', units)
    call h5_write_attr(dset, 'description', descr)
  end subroutine h5_describe_dataset

  !> Units and description of the dataset at PATH ('units unknown' and
  !> 'undocumented' when the table has no entry: tools/tests/test_results.py fails then).
  subroutine dataset_info(path, units, description)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: units, description
    character(len=:), allocatable :: key, entry
    integer :: i, a, b, n
    key = generic(path)
    units = 'unknown'
    description = 'undocumented'
    do i = 1, size(table)
      entry = trim(table(i))
      a = index(entry, sep)
      b = a + index(entry(a + 1:), sep)
      n = index(entry(1:a - 1), '*') - 1
      if (n < 0) then
        if (entry(1:a - 1) /= key) cycle
      else
        if (len(key) < n) cycle
        if (key(1:n) /= entry(1:n)) cycle
      end if
      units = entry(a + 1:b - 1)
      description = entry(b + 1:)
      return
    end do
  end subroutine dataset_info

  !> PATH with every all-digit component replaced by N.
  pure function generic(path) result(g)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: g, part
    integer :: i, j
    g = ''
    i = 1
    do while (i <= len(path))
      j = index(path(i:), '/')
      if (j == 0) then
        j = len(path) + 1
      else
        j = i + j - 1
      end if
      part = path(i:j - 1)
      if (len(part) > 0 .and. verify(part, '0123456789') == 0) part = 'N'
      if (len(g) > 0) g = g//'/'
      g = g//part
      i = j + 1
    end do
  end function generic
end module fracas_h5_describe
