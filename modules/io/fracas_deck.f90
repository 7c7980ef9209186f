!> Input data of a case, as the DATBOX readers fill it. Runtime objects (bodies,
!> contactors, laws, run settings) are built from these types; nothing here
!> knows about the solver. Every record keeps the file and line it came from so
!> that later consistency checks can still point at the input.
module fracas_deck
  use fracas_kinds, only: wp
  implicit none
  private
  public :: model_finite_strain
  public :: source_t, tactor_input_t, body_input_t, material_input_t, law_input_t, &
            see_rule_input_t, driven_dof_input_t, dof_record_t, contact_record_t, &
            run_control_t, deck_t, element_input_t, model_input_t, gpv_record_t, postpro_input_t

  !> Where a record was read: file name as given to the reader and line number.
  type :: source_t
    character(len=:), allocatable :: file
    integer :: line = 0
  end type source_t

  !> One contactor of BODIES.DAT, numbered as LMGC90 numbers them in
  !> Vloc_Rloc (rank within the body): each CLxxx line (first or '+') is one
  !> candidate point; an ALpxx line and its '+' lines form one polyline.
  type :: tactor_input_t
    character(len=5) :: kind = ''        !< 'DISKx', 'xKSID', 'JONCx', 'POLYG', 'DISKb', 'CLxxx', 'ALpxx'
    character(len=5) :: color = ''
    real(wp) :: radius = 0.0_wp          !< DISKx/xKSID: byrd
    real(wp) :: ax1 = 0.0_wp, ax2 = 0.0_wp  !< JONCx: half length, half thickness
    real(wp) :: shift(2) = 0.0_wp        !< offset of the contactor from the body node (DISKb)
    real(wp), allocatable :: vertices(:, :)  !< POLYG: (2, nb_vertex), as read
    !> Mesh contactors, node numbers within the body: CLxxx [noda, nodb] (the
    !> point is (1 - apab) x_noda + apab x_nodb); ALpxx the polyline's nodes
    !> in order (segment k joins nodes(k) and nodes(k+1)).
    integer, allocatable :: nodes(:)
    real(wp) :: apab = 0.0_wp
    type(source_t) :: src
  end type tactor_input_t

  !> One element line of a MAILx $blmty block with its 'model ... behav' line.
  type :: element_input_t
    character(len=5) :: kind = ''        !< geometry as written: 'T3xxx', 'Q4xxx', 'T6xxx', 'Q8xxx'
    integer, allocatable :: nodes(:)     !< node numbers within the body
    character(len=5) :: model = ''       !< MODELS.DAT nickname
    character(len=5) :: behav = ''       !< BULK_BEHAV.DAT material nickname
    type(source_t) :: src                !< the element line
    type(source_t) :: model_src          !< its 'model ... behav' line
  end type element_input_t

  !> One $bdyty block of BODIES.DAT: a rigid body (RBDY2) or a meshed body (MAILx).
  type :: body_input_t
    character(len=5) :: model = 'RBDY2'  !< 'RBDY2' or 'MAILx'
    integer :: number = 0                !< number within its model (1-based order of appearance, as LMGC90)
    character(len=5) :: behav = ''       !< RBDY2: material nickname ($blmty PLAIN)
    real(wp) :: avrd = 0.0_wp, gyrd = 0.0_wp  !< 0 means: compute from the contactors
    real(wp) :: coor(3) = 0.0_wp         !< RBDY2: NO3xx reference x, y, angle
    real(wp), allocatable :: node_coor(:, :)  !< MAILx: (2, nnodes) NO2xx reference coordinates
    type(element_input_t), allocatable :: elements(:)  !< MAILx elements
    type(tactor_input_t), allocatable :: tactors(:)
    type(source_t) :: src
  end type body_input_t

  !> One model of MODELS.DAT (MECAx physics), options as LMGC90's
  !> pre-processor writes them.
  type :: model_input_t
    character(len=5) :: nickname = ''
    character(len=5) :: physics = 'MECAx'
    character(len=5) :: element = ''     !< 'T3xxx', 'Q4xxx', 'T6xxx', 'Q8xxx', 'Q4P0x', ...
    character(len=5) :: kinematic = 'small'   !< kine_: small | large
    character(len=5) :: formulation = ''      !< form_: UpdtL | TotaL (large kinematics)
    character(len=5) :: material = ''         !< mater: elas_ | J2iso | ... ('' until given or set from the material)
    character(len=5) :: mass_storage = 'lump_' !< mstrg: lump_ | coher
    character(len=5) :: anisotropy = 'iso__'  !< aniso
    character(len=5) :: external = 'no___'    !< isext
    type(source_t) :: src
  end type model_input_t

  !> One $behav block of BULK_BEHAV.DAT.
  type :: material_input_t
    character(len=5) :: nickname = ''
    character(len=30) :: law = ''        !< 'RIGID', 'ELAS', 'ELAS_PLAS'
    real(wp) :: density = 0.0_wp         !< Umas
    real(wp) :: young = 0.0_wp, poisson = 0.0_wp   !< ELAS, ELAS_PLAS: EYng, Epss
    !> ELAS_PLAS (von Mises, linear isotropic hardening): yield stress
    !> sigma_y = yield0 + hardening p (SIG0, K___), p the cumulative plastic strain.
    real(wp) :: yield0 = 0.0_wp, hardening = 0.0_wp
    type(source_t) :: src
  end type material_input_t

  !> One $behav block of TACT_BEHAV.DAT: a contact law and its parameters in
  !> LMGC90's order (see doc/input_reference.md for the order per law).
  type :: law_input_t
    character(len=5) :: nickname = ''
    character(len=30) :: name = ''       !< e.g. 'IQS_CLB', 'RST_CLB', 'IQS_MAC_CZM'
    real(wp), allocatable :: params(:)
    character(len=5), allocatable :: param_labels(:)  !< labels as written ('fric=' ...)
    integer, allocatable :: param_lines(:), param_cols(:)  !< where each parameter was read
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
    character(len=5) :: model = 'RBDY2'  !< 'RBDY2' or 'MAILx'
    integer :: body = 0                  !< body number within its model
    integer :: node = 0                  !< MAILx: node number within the body (0 for RBDY2)
    integer :: dof = 0                   !< 1..3 for RBDY2, 1..2 for a MAILx node
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
    integer :: body = 0                  !< body number within its model
    real(wp) :: x(3) = 0.0_wp, v(3) = 0.0_wp   !< RBDY2
    !> MAILx: displacement and velocity of every node listed, (2, nnodes), and
    !> the node numbers they belong to.
    integer, allocatable :: nodes(:)
    real(wp), allocatable :: node_x(:, :), node_v(:, :)
    type(source_t) :: src
  end type dof_record_t

  !> Gauss-point values of one element in GPV.INI / GPV.OUT.n: per Gauss point
  !> the lines LMGC90 writes (small strain: stress (xx, yy, xy, zz), strain
  !> (xx, yy, 2 xy, zz); J2 adds a line of internal values).
  type :: gpv_record_t
    integer :: body = 0, element = 0     !< MAILx body number, element rank in the body
    character(len=5) :: kind = ''        !< element geometry as written ('T3xxx', 'Q4xxx', ...)
    real(wp), allocatable :: values(:, :)   !< (values per Gauss point, Gauss points)
    type(source_t) :: src
  end type gpv_record_t

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
    character(len=15) :: internal_name = ''  !< name of a single internal ('': by count, see write_outbox)
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
    character(len=8) :: output_vtk_disks = 'polygons'    !< 'polygons' (filled, as opened) | 'points' (with a radius)
    character(len=6) :: output_vtk_precision = 'single'  !< reals of the .vtu: 'single' | 'double'
    integer :: output_hdf5_every = -1    !< snapshot in fracas.h5 every n steps (0: none; -1: about 100 a run)
    !> restart point in fracas.h5 every n steps, and at the last step (0: the last step only;
    !> -1: with every snapshot)
    integer :: output_restart_every = -1
    character(len=4) :: nlgs_unconverged = 'warn'  !< a step at the sweep limit: 'warn' | 'fail' (exit 3 at the end) | 'stop'
    integer :: progress_every = 0        !< progress line every n steps (0: about 20 lines a run)
    ! Meshed bodies (see doc/input_reference.md)
    character(len=6) :: plane = 'strain'      !< 2D hypothesis of meshed bodies: 'strain' | 'stress' | 'axisym'
    real(wp) :: newton_tolerance = 1.0e-6_wp  !< relative residual of the Newton loop of nonlinear bodies
    integer :: newton_max_iterations = 20
    character(len=7) :: linear_solver = 'auto'  !< 'auto', 'dense', 'cholmod'
    !> Velocity a driven dof has at the start of a step: its imposed value then
    !> ('imposed'), or the previous end-of-step velocity, DOF.INI's at the first
    !> step ('initial'); 'lmgc90': imposed for rigid bodies, initial for mesh
    !> nodes, as LMGC90 does (doc/solver.md).
    character(len=7) :: driven_start = 'lmgc90'
    !> Also make contacts of pairs whose predicted gap (gap + h min(0, u_n), free
    !> velocities) is within the alert distance, not only their gap (doc/solver.md).
    logical :: detection_approach = .true.
    !> NLGS convergence measured as LMGC90 measures it, by a check pass after each
    !> block of sweeps that evaluates without applying (yes), or by the changes of
    !> the block's last sweep (no) (doc/solver.md).
    logical :: nlgs_check_pass = .true.
    !> Cohesive damage: solved with the contacts within each step, so that a crack
    !> costs its fracture energy whatever the step ('implicit', the default; doc/czm.md
    !> §3.2), or LMGC90's update after the step from the start-of-step damage
    !> ('explicit': reproduces LMGC90's outputs).
    character(len=8) :: cohesive_damage = 'implicit'
    !> Time-step control for cracks: a step in which a damaging cohesive zone's
    !> jump changes by more than this many softening lengths is done again in
    !> halves (0: off), at most crack_step_cuts times (doc/czm.md §9).
    real(wp) :: crack_step_limit = 0.0_wp
    integer :: crack_step_cuts = 10
  end type run_control_t

  !> One command of POSTPRO.DAT (LMGC90's post-processing deck): its name as
  !> LMGC90 spells it, its STEP, and the parameter lines after it (kept as
  !> text: each command reads its own; see fracas_read_postpro).
  type :: postpro_input_t
    character(len=30) :: name = ''
    integer :: every = 1                     !< STEP n: every n steps
    character(len=80), allocatable :: params(:)
    integer, allocatable :: param_lines(:)   !< line of each parameter in POSTPRO.DAT
    integer, allocatable :: bodies(:)        !< BODY TRACKING, TORQUE EVOLUTION: RBDY2 numbers
    type(source_t) :: src
  end type postpro_input_t

  !> Everything read from one case directory.
  type :: deck_t
    character(len=:), allocatable :: case_dir, datbox
    real(wp) :: gravity(3) = 0.0_wp
    type(source_t) :: gravity_src                    !< the gravity line of BULK_BEHAV.DAT
    type(body_input_t), allocatable :: bodies(:)     !< in the order of BODIES.DAT, all models
    type(model_input_t), allocatable :: models(:)    !< MODELS.DAT (empty without meshed bodies)
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
    type(gpv_record_t), allocatable :: gpv_ini(:)    !< GPV.INI (empty when absent or '$steps 0' only)
    type(postpro_input_t), allocatable :: postpro(:) !< POSTPRO.DAT commands (empty when absent)
    type(run_control_t) :: run
    !> What the run control was made of: the file read ('' when none) and the --set settings.
    character(len=:), allocatable :: command_file
    character(len=256), allocatable :: settings(:)
  end type deck_t
contains

  !> The model is run at finite strain: 'mater neoh_' (MatLib's neo-Hookean), or
  !> LMGC90's internal finite-strain J2 ('kine_ large', 'mater J2iso', element
  !> Q4P0x, no external library: the only large-strain model of LMGC90's own).
  pure logical function model_finite_strain(model)
    type(model_input_t), intent(in) :: model
    model_finite_strain = model%material == 'neoh_' .or. (model%kinematic == 'large' .and. &
      model%material == 'J2iso' .and. model%element == 'Q4P0x' .and. model%external == 'no___')
  end function model_finite_strain
end module fracas_deck
