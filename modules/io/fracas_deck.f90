!> Input data of a case, as the DATBOX readers fill it. Runtime objects (bodies,
!> contactors, laws, run settings) are built from these types; nothing here
!> knows about the solver. Every record keeps the file and line it came from so
!> that later consistency checks can still point at the input.
module fracas_deck
  use fracas_kinds, only: wp
  implicit none
  private
  public :: source_t, tactor_input_t, body_input_t, material_input_t, law_input_t, &
            see_rule_input_t, driven_dof_input_t, dof_record_t, contact_record_t, &
            run_control_t, deck_t

  !> Where a record was read: file name as given to the reader and line number.
  type :: source_t
    character(len=:), allocatable :: file
    integer :: line = 0
  end type source_t

  !> One $tacty line of BODIES.DAT.
  type :: tactor_input_t
    character(len=5) :: kind = ''        !< 'DISKx', 'xKSID', 'JONCx', 'POLYG'
    character(len=5) :: color = ''
    real(wp) :: radius = 0.0_wp          !< DISKx/xKSID: byrd
    real(wp) :: ax1 = 0.0_wp, ax2 = 0.0_wp  !< JONCx: half length, half thickness
    real(wp) :: shift(2) = 0.0_wp        !< offset of the contactor from the body node (DISKb)
    real(wp), allocatable :: vertices(:, :)  !< POLYG: (2, nb_vertex), as read
    type(source_t) :: src
  end type tactor_input_t

  !> One $bdyty block of BODIES.DAT (RBDY2 only for now).
  type :: body_input_t
    character(len=5) :: model = 'RBDY2'
    integer :: number = 0                !< serial number = order of appearance (1-based)
    character(len=5) :: behav = ''       !< material nickname ($blmty PLAIN)
    real(wp) :: avrd = 0.0_wp, gyrd = 0.0_wp  !< 0 means: compute from the contactors
    real(wp) :: coor(3) = 0.0_wp         !< NO3xx reference x, y, angle
    type(tactor_input_t), allocatable :: tactors(:)
    type(source_t) :: src
  end type body_input_t

  !> One $behav block of BULK_BEHAV.DAT.
  type :: material_input_t
    character(len=5) :: nickname = ''
    character(len=30) :: law = ''        !< 'RIGID' for rigid bodies
    real(wp) :: density = 0.0_wp         !< Umas
    type(source_t) :: src
  end type material_input_t

  !> One $behav block of TACT_BEHAV.DAT: a contact law and its parameters in
  !> LMGC90's order (see doc/input_reference.md for the order per law).
  type :: law_input_t
    character(len=5) :: nickname = ''
    character(len=30) :: name = ''       !< e.g. 'IQS_CLB', 'RST_CLB', 'IQS_MAC_CZM'
    real(wp), allocatable :: params(:)
    character(len=5), allocatable :: param_labels(:)  !< labels as written ('fric=' ...)
    type(source_t) :: src
  end type law_input_t

  !> One $seety rule of TACT_BEHAV.DAT.
  type :: see_rule_input_t
    character(len=5) :: cdbdy = '', cdtac = '', cdcol = '', behav = ''
    character(len=5) :: anbdy = '', antac = '', ancol = ''
    real(wp) :: alert = 0.0_wp
    real(wp) :: global_alert = 0.0_wp    !< optional '+' line; 0 when absent
    type(source_t) :: src
  end type see_rule_input_t

  !> One vlocy/force line of DRV_DOF.DAT. value(t) is either
  !> (ct + amp*cos(omega*t + phi)) * min(1, rampi + ramp*t), or the piecewise
  !> linear interpolation of an evolution file (t, value).
  type :: driven_dof_input_t
    integer :: body = 0                  !< body serial number
    integer :: dof = 0                   !< 1..3 for RBDY2
    character(len=5) :: kind = ''        !< 'vlocy' or 'force'
    real(wp) :: ct = 0.0_wp, amp = 0.0_wp, omega = 0.0_wp, phi = 0.0_wp
    real(wp) :: rampi = 0.0_wp, ramp = 0.0_wp
    logical :: evolution = .false.
    character(len=:), allocatable :: evolution_file   !< name as written in DRV_DOF.DAT
    real(wp), allocatable :: evo_t(:), evo_v(:)       !< strictly increasing evo_t
    type(source_t) :: src
  end type driven_dof_input_t

  !> State of one body in DOF.INI / DOF.OUT.n: displacement from the reference
  !> configuration (x, y, rotation) and velocity.
  type :: dof_record_t
    character(len=5) :: model = 'RBDY2'
    integer :: body = 0
    real(wp) :: x(3) = 0.0_wp, v(3) = 0.0_wp
    type(source_t) :: src
  end type dof_record_t

  !> One $icdan block of Vloc_Rloc.INI / Vloc_Rloc.OUT.n. Reactions are stored
  !> as forces (impulse / time step), as LMGC90 writes them.
  type :: contact_record_t
    character(len=5) :: inter = ''       !< 'DKDKx', 'DKJCx', 'DKKDx', 'PLPLx', ...
    integer :: number = 0                !< icdan, numbering within its type
    character(len=5) :: cdbdy = 'RBDY2', cdtac = '', anbdy = 'RBDY2', antac = ''
    integer :: icdbdy = 0, icdtac = 0, ianbdy = 0, iantac = 0  !< body serial, contactor rank in body
    integer :: cdver = 0, anseg = 0      !< polygon vertex / segment (PLPLx ...), 0 if none
    character(len=5) :: behav = ''
    character(len=5) :: status = 'noctc'
    integer :: iadj = 0
    real(wp) :: rlt = 0.0_wp, rln = 0.0_wp   !< forces (rlt/H, rln/H)
    real(wp) :: vlt = 0.0_wp, vln = 0.0_wp
    real(wp) :: gap = 0.0_wp                 !< gapTT
    real(wp) :: normal(2) = 0.0_wp, coor(2) = 0.0_wp
    logical :: has_geometry = .false.        !< n(..)= and coo..= lines present
    real(wp), allocatable :: internals(:)    !< law internal variables, may be empty
    type(source_t) :: src
  end type contact_record_t

  !> Run control from DATBOX/COMMAND.DAT (our own keyword deck); the defaults
  !> below are documented in doc/input_reference.md.
  type :: run_control_t
    real(wp) :: time_step = 0.0_wp       !< required
    integer :: number_of_steps = 0       !< number_of_steps or final_time is required
    real(wp) :: final_time = -1.0_wp
    real(wp) :: theta = 0.5_wp
    integer :: detection_frequency = 1   !< rough (cell-list) detection every n steps
    character(len=5) :: nlgs_check = 'Quad '  !< 'Quad ', 'Maxm ', 'QM/16'
    real(wp) :: nlgs_tolerance = 1.0e-4_wp
    real(wp) :: nlgs_relaxation = 1.0_wp
    integer :: nlgs_sweeps_per_check = 50
    integer :: nlgs_max_checks = 400
    character(len=8) :: nlgs_order = 'stored' !< 'stored', 'reversed', 'shuffled', 'colored'
    integer :: nlgs_seed = 1
    integer :: output_dof_every = 0      !< DOF.OUT.n / Vloc_Rloc.OUT.n every n steps (0: last step only)
    integer :: output_vtk_every = 0      !< DISPLAY/*.vtu every n steps (0: none)
    integer :: output_hdf5_every = 10    !< snapshot in fracas.h5 every n steps (0: none)
    integer :: progress_every = 0        !< progress line every n steps (0: about 20 lines a run)
  end type run_control_t

  !> Everything read from one case directory.
  type :: deck_t
    character(len=:), allocatable :: case_dir, datbox
    real(wp) :: gravity(3) = 0.0_wp
    type(body_input_t), allocatable :: bodies(:)
    type(material_input_t), allocatable :: materials(:)
    type(law_input_t), allocatable :: laws(:)
    type(see_rule_input_t), allocatable :: see_rules(:)
    type(driven_dof_input_t), allocatable :: driven(:)
    integer :: dof_step = 0              !< $steps of DOF.INI
    real(wp) :: dof_time = 0.0_wp
    type(dof_record_t), allocatable :: dof_ini(:)
    integer :: vloc_step = 0
    real(wp) :: vloc_time = 0.0_wp
    type(contact_record_t), allocatable :: vloc_ini(:)
    type(run_control_t) :: run
  end type deck_t
end module fracas_deck
