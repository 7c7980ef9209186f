!> LMGC90's post-processing files: the commands of DATBOX/POSTPRO.DAT written
!> to POSTPRO/ in LMGC90's names and formats (time ES15.8, values 1X,ES14.7,
!> counts 1X,I8), one line per command every STEP n steps (n divides the step
!> number, as in LMGC90). Carried out:
!>
!>   SOLVER INFORMATIONS  SOLVER_INFORMATIONS.DAT: t, NLGS sweeps, MeanDVoR,
!>                        QuadDV, QuadDVR (MaxmDV, MaxmDVR for a Maxm check),
!>                        number of contacts
!>   BODY TRACKING        BODY_nnnnnnn.DAT: t, coor(3) = reference + X, X(3), V(3)
!>   TORQUE EVOLUTION     TORQUE_nnnnnnn.DAT: t, contact force on the body
!>                        (impulse / H, 3), external force (theta average over the step, 3)
!>   DISSIPATED ENERGY    DISSIPATED_ENERGY.DAT: t, the sum of the last column
!>                        so far, -sum over contacts of r.(u_begin + u)/2 in the step
!>                        (r impulses; as LMGC90, the sum runs over the written
!>                        steps only: with STEP 1 it is the dissipation since the start)
!>
!> Every other command is reported once, with its line, and skipped. The
!> meshed-body commands (NEW MECAx SETS, Dep EVOLUTION, Fint EVOLUTION) are
!> recognised; a kind is added here with its reader of the parameter lines
!> (postpro_input_t%params) and its writer in postpro_step.
module fracas_postpro
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal, warn
  use fracas_deck, only: postpro_input_t
  use fracas_files, only: make_dir
  use fracas_ids, only: st_noctc
  use fracas_datbox_text, only: itoa
  use fracas_scene, only: scene_t, step_report_t, scene_body_impulses
  implicit none
  private
  public :: postpro_t, postpro_open, postpro_step, postpro_flush, postpro_close, postpro_owns

  integer, parameter :: pp_solver = 1, pp_body = 2, pp_torque = 3, pp_dissipated = 4

  type :: pp_command_t
    integer :: kind = 0
    integer :: every = 1
    integer, allocatable :: bodies(:)   !< body index in the scene (= RBDY2 number)
    integer, allocatable :: units(:)    !< one file per body, or one file
  end type pp_command_t

  type :: postpro_t
    logical :: active = .false.
    character(len=:), allocatable :: dir
    type(pp_command_t), allocatable :: cmds(:)
    real(wp) :: dissipated = 0.0_wp      !< DISSIPATED ENERGY's running sum
    character(len=5) :: check = 'Quad '
  end type postpro_t

contains

  !> Open OUT_DIR/POSTPRO/ and its files for the commands of POSTPRO.DAT
  !> (none: nothing is written). check: the NLGS norm (Quad, Maxm, QM/16).
  subroutine postpro_open(pp, commands, out_dir, check)
    type(postpro_t), intent(out) :: pp
    type(postpro_input_t), intent(in) :: commands(:)
    character(len=*), intent(in) :: out_dir, check
    type(pp_command_t), allocatable :: cmds(:)
    integer :: k, n, j
    character(len=:), allocatable :: where
    pp%check = check
    allocate (cmds(size(commands)))
    n = 0
    do k = 1, size(commands)
      associate (c => commands(k))
        where = ''
        if (allocated(c%src%file)) where = c%src%file//':'//itoa(c%src%line)//': '
        select case (trim(c%name))
        case ('SOLVER INFORMATIONS')
          n = n + 1
          cmds(n)%kind = pp_solver
        case ('BODY TRACKING')
          n = n + 1
          cmds(n)%kind = pp_body
          cmds(n)%bodies = c%bodies
        case ('TORQUE EVOLUTION')
          n = n + 1
          cmds(n)%kind = pp_torque
          cmds(n)%bodies = c%bodies
        case ('DISSIPATED ENERGY')
          n = n + 1
          cmds(n)%kind = pp_dissipated
        case ('NEW MECAx SETS', 'Dep EVOLUTION', 'Fint EVOLUTION')
          call warn(where//"POSTPRO command '"//trim(c%name)//"' (meshed bodies) is not carried out yet: skipped")
          cycle
        case default
          call warn(where//"POSTPRO command '"//trim(c%name)//"' is not carried out by Fracas: skipped "// &
                    '(supported: SOLVER INFORMATIONS, BODY TRACKING, TORQUE EVOLUTION, DISSIPATED ENERGY)')
          cycle
        end select
        cmds(n)%every = c%every
      end associate
    end do
    pp%cmds = cmds(1:n)
    pp%active = n > 0
    if (.not. pp%active) return
    pp%dir = trim(out_dir)//'/POSTPRO'
    call make_dir(pp%dir, parents=.true.)
    do k = 1, n
      associate (c => pp%cmds(k))
        select case (c%kind)
        case (pp_solver)
          c%units = [open_file('SOLVER_INFORMATIONS.DAT')]
        case (pp_dissipated)
          c%units = [open_file('DISSIPATED_ENERGY.DAT')]
        case (pp_body, pp_torque)
          allocate (c%units(size(c%bodies)))
          do j = 1, size(c%bodies)
            c%units(j) = open_file(trim(merge('BODY_  ', 'TORQUE_', c%kind == pp_body))//seven(c%bodies(j))//'.DAT')
          end do
        end select
      end associate
    end do

  contains

    integer function open_file(name) result(u)
      character(len=*), intent(in) :: name
      integer :: ios
      open (newunit=u, file=pp%dir//'/'//trim(name), status='replace', action='write', iostat=ios)
      if (ios /= 0) call fatal('cannot open '//pp%dir//'/'//trim(name)//' for writing')
    end function open_file
  end subroutine postpro_open

  !> Write the lines of the commands due at this step (after scene_step).
  subroutine postpro_step(pp, sc, rep)
    type(postpro_t), intent(inout) :: pp
    type(scene_t), intent(in) :: sc
    type(step_report_t), intent(in) :: rep
    real(wp), allocatable :: imp(:, :)
    real(wp) :: e1, e2, e3, energy
    integer :: k, j, ib
    character(len=*), parameter :: f_body = '(es15.8,9(1x,es14.7))', f_torque = '(es15.8,6(1x,es14.7))'
    if (.not. pp%active) return
    do k = 1, size(pp%cmds)
      associate (c => pp%cmds(k), b => sc%bodies)
        if (mod(sc%step, c%every) /= 0) cycle
        select case (c%kind)
        case (pp_solver)
          ! LMGC90 reports the norms of its last check, scaled by the tolerance
          ! (converged below 1); a Maxm check reports the Maxm norms.
          e1 = rep%nlgs%mean_dvor
          e2 = rep%nlgs%quad_dv
          e3 = rep%nlgs%quad_dvr
          if (pp%check == 'Maxm ') then
            e2 = rep%nlgs%maxm_dv
            e3 = rep%nlgs%maxm_dvr
          end if
          write (c%units(1), '(es15.8,1x,i8,3(1x,es14.7),1x,i8)') sc%time, rep%nlgs%sweeps, e1, e2, e3, rep%contacts
        case (pp_body)
          do j = 1, size(c%bodies)
            ib = c%bodies(j)
            write (c%units(j), f_body) sc%time, b%ref(:, ib) + b%x(:, ib), b%x(:, ib), b%v(:, ib)
          end do
        case (pp_torque)
          if (.not. allocated(imp)) call scene_body_impulses(sc, imp)
          do j = 1, size(c%bodies)
            ib = c%bodies(j)
            write (c%units(j), f_torque) sc%time, imp(:, ib) / sc%h, b%fext(:, ib)
          end do
        case (pp_dissipated)
          energy = step_dissipation(sc)
          pp%dissipated = pp%dissipated + energy
          write (c%units(1), '(es15.8,2(1x,es14.7))') sc%time, pp%dissipated, energy
        end select
      end associate
    end do
  end subroutine postpro_step

  !> Energy dissipated by the contacts in the step just done: -r.(u_begin + u)/2
  !> summed over the contacts in contact (r impulses).
  real(wp) function step_dissipation(sc) result(e)
    type(scene_t), intent(in) :: sc
    integer :: k
    e = 0.0_wp
    associate (c => sc%contacts)
      do k = 1, c%n
        if (c%status(k) == st_noctc .or. .not. c%active(k)) cycle
        e = e - 0.5_wp * sum(c%r(:, k) * (c%u_begin(:, k) + c%u(:, k)))
      end do
    end associate
  end function step_dissipation

  !> Hand the lines written so far to the system (a killed run keeps them).
  subroutine postpro_flush(pp)
    type(postpro_t), intent(inout) :: pp
    integer :: k, j
    if (.not. pp%active) return
    do k = 1, size(pp%cmds)
      do j = 1, size(pp%cmds(k)%units)
        flush (pp%cmds(k)%units(j))
      end do
    end do
  end subroutine postpro_flush

  subroutine postpro_close(pp)
    type(postpro_t), intent(inout) :: pp
    integer :: k, j
    if (.not. pp%active) return
    do k = 1, size(pp%cmds)
      do j = 1, size(pp%cmds(k)%units)
        close (pp%cmds(k)%units(j))
      end do
    end do
    pp%active = .false.
  end subroutine postpro_close

  !> True for the names of the files a run may write in POSTPRO/ (for
  !> clearing or refusing the results of an earlier run).
  logical function postpro_owns(name)
    character(len=*), intent(in) :: name
    postpro_owns = name == 'SOLVER_INFORMATIONS.DAT' .or. name == 'DISSIPATED_ENERGY.DAT' .or. &
                   numbered(name, 'BODY_') .or. numbered(name, 'TORQUE_')
  end function postpro_owns

  !> NAME is PREFIX, seven digits, '.DAT'.
  logical function numbered(name, prefix)
    character(len=*), intent(in) :: name, prefix
    integer :: n
    n = len(prefix)
    numbered = .false.
    if (len(name) /= n + 11) return
    numbered = name(1:n) == prefix .and. verify(name(n + 1:n + 7), '0123456789') == 0 .and. name(n + 8:) == '.DAT'
  end function numbered

  !> Seven digits, zero-padded (LMGC90's I7.7).
  function seven(i) result(s)
    integer, intent(in) :: i
    character(len=7) :: s
    write (s, '(i7.7)') i
  end function seven
end module fracas_postpro
