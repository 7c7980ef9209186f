!> What the 3D DATBOX readers return (fracas_read_bodies_3d), kept apart from
!> the 2D deck (fracas_deck) until the scene runs 3D decks: RBDY3 bodies with
!> their SPHER / PLANx contactors, and their DOF.INI records.
module fracas_deck_3d
  use fracas_kinds, only: wp
  use fracas_deck, only: source_t
  implicit none
  private
  public :: tactor3_input_t, body3_input_t, dof3_record_t

  !> One $tacty line of an RBDY3 (and its continuation lines).
  type :: tactor3_input_t
    character(len=5) :: kind = ''        !< 'SPHER', 'SPHEb' (a sphere with an offset), 'PLANx', 'POLYR' or 'CYLND'
    character(len=5) :: color = ''
    real(wp) :: radius = 0.0_wp          !< SPHER, CYLND byrd=
    real(wp) :: axes(3) = 0.0_wp         !< PLANx axe1= axe2= axe3= (half lengths, half thickness); CYLND High= in axes(1)
    !> PLANx 'localframe' block: axes alpha, beta, gamma (columns), global; identity if absent
    real(wp) :: frame(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
    real(wp) :: shift(3) = 0.0_wp        !< offset from the node (SPHEb's line, PLANx's 'localframe' block)
    real(wp), allocatable :: vert(:, :)  !< POLYR (3, nb_vertex) vertices, relative to the node
    integer, allocatable :: faces(:, :)  !< POLYR (3, nb_faces) triangles (vertex numbers)
    type(source_t) :: src
  end type tactor3_input_t

  !> One RBDY3 of BODIES.DAT.
  type :: body3_input_t
    integer :: number = 0                !< 1-based order of appearance (as LMGC90)
    character(len=5) :: behav = ''       !< material nickname ($blmty PLAIN)
    real(wp) :: avrd = 0.0_wp            !< 0: computed from the contactors
    real(wp) :: inertia(3) = 0.0_wp      !< PLAIN's I1 I2 I3 line (0: computed)
    real(wp) :: coor(6) = 0.0_wp         !< NO6xx coo1..coo6
    type(tactor3_input_t), allocatable :: tactors(:)
    type(source_t) :: src
  end type body3_input_t

  !> One RBDY3 of DOF.INI: X(1..6), V(1..6) (V(4..6) in the body's principal
  !> frame) and the frame (alpha, beta, gamma lines: its columns).
  type :: dof3_record_t
    integer :: body = 0
    real(wp) :: x(6) = 0.0_wp, v(6) = 0.0_wp
    real(wp) :: frame(3, 3) = 0.0_wp
    type(source_t) :: src
  end type dof3_record_t
end module fracas_deck_3d
