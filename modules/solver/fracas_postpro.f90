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
!>   NEW MECAx SETS       node sets of meshed bodies: the number of sets; per set
!>                        the number of groups; per group 'body n' (MAILx number,
!>                        node count) then n node numbers, one per line
!>   Dep EVOLUTION        Dep_nnnnnnn.DAT per set: t, mean displacement (2), mean
!>                        velocity (2) over the set's entries
!>   Fint EVOLUTION       Fint_nnnnnnn.DAT per set: t, Reac(2) (contact impulse / H),
!>                        Fint(2) (internal force at the end of the step, +K u),
!>                        Finert(2) (M (V - V_begin) / H), Fext(2), Res(2) = Fint +
!>                        Finert - Reac - Fext (the force driven dofs apply), summed
!>                        over the set's entries (LMGC90's mod_postpro_2D layout)
!>
!> Every other command is reported once, with its line, and skipped. A kind is
!> added here with its reader of the parameter lines (postpro_input_t%params)
!> and its writer in postpro_step.
module fracas_postpro
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal, warn, input_error
  use fracas_deck, only: postpro_input_t
  use fracas_files, only: make_dir, check_written, close_written
  use fracas_ids, only: st_noctc
  use fracas_datbox_text, only: itoa, parse_int
  use fracas_scene, only: scene_t, step_report_t, scene_body_impulses
  use fracas_mailx, only: mailx_t
  implicit none
  private
  public :: postpro_t, postpro_prepare, postpro_open, postpro_step, postpro_flush, postpro_close, postpro_owns, &
            postpro_sums, postpro_restore_sums

  integer, parameter :: pp_solver = 1, pp_body = 2, pp_torque = 3, pp_dissipated = 4, pp_dep = 5, pp_fint = 6

  !> A node set of NEW MECAx SETS: its entries as mesh node indices (a node
  !> listed twice counts twice, as in LMGC90).
  type :: node_set_t
    integer, allocatable :: nodes(:)
  end type node_set_t

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
    type(node_set_t), allocatable :: sets(:)
  end type postpro_t

contains

  !> Read and check the commands of POSTPRO.DAT against the scene (errors at
  !> their lines; run by --check too, before anything is written). check: the
  !> NLGS norm (Quad, Maxm, QM/16); meshes: the meshed bodies (for the node sets).
  subroutine postpro_prepare(pp, commands, check, meshes)
    type(postpro_t), intent(out) :: pp
    type(postpro_input_t), intent(in) :: commands(:)
    character(len=*), intent(in) :: check
    type(mailx_t), intent(in) :: meshes
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
        case ('NEW MECAx SETS')
          call read_node_sets(c, meshes, pp%sets)
          cycle
        case ('Dep EVOLUTION', 'Fint EVOLUTION')
          n = n + 1
          cmds(n)%kind = merge(pp_dep, pp_fint, trim(c%name) == 'Dep EVOLUTION')
        case default
          call warn(where//"POSTPRO command '"//trim(c%name)//"' is not carried out by Fracas: skipped "// &
                    '(supported: SOLVER INFORMATIONS, BODY TRACKING, TORQUE EVOLUTION, DISSIPATED ENERGY, '// &
                    'NEW MECAx SETS, Dep EVOLUTION, Fint EVOLUTION)')
          cycle
        end select
        cmds(n)%every = c%every
      end associate
    end do
    if (.not. allocated(pp%sets)) allocate (pp%sets(0))
    ! LMGC90 writes one Dep_/Fint_ file per node set: without sets there is nothing to write
    if (size(pp%sets) == 0 .and. any(cmds(1:n)%kind == pp_dep .or. cmds(1:n)%kind == pp_fint)) then
      call warn("POSTPRO.DAT: Dep EVOLUTION and Fint EVOLUTION without node sets ('NEW MECAx SETS'): "// &
                'nothing to write, skipped')
      j = count(cmds(1:n)%kind /= pp_dep .and. cmds(1:n)%kind /= pp_fint)
      cmds(1:j) = pack(cmds(1:n), cmds(1:n)%kind /= pp_dep .and. cmds(1:n)%kind /= pp_fint)
      n = j
    end if
    pp%cmds = cmds(1:n)
  end subroutine postpro_prepare

  !> Open OUT_DIR/POSTPRO/ and the files of the prepared commands (none:
  !> nothing is written).
  subroutine postpro_open(pp, out_dir)
    type(postpro_t), intent(inout) :: pp
    character(len=*), intent(in) :: out_dir
    integer :: k, j, n
    n = size(pp%cmds)
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
        case (pp_dep, pp_fint)
          allocate (c%units(size(pp%sets)))
          do j = 1, size(pp%sets)
            c%units(j) = open_file(trim(merge('Dep_ ', 'Fint_', c%kind == pp_dep))//seven(j)//'.DAT')
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
    real(wp) :: e1, e2, e3, energy, f(2, 5)
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
        case (pp_dep)
          do j = 1, size(pp%sets)
            associate (nodes => pp%sets(j)%nodes, m => sc%meshes)
              write (c%units(j), '(es15.8,4(1x,es14.7))') sc%time, sum(m%x(:, nodes), dim=2) / size(nodes), &
                sum(m%v(:, nodes), dim=2) / size(nodes)
            end associate
          end do
        case (pp_fint)
          do j = 1, size(pp%sets)
            associate (nodes => pp%sets(j)%nodes, m => sc%meshes)
              f(:, 1) = sum(m%imp(:, nodes), dim=2) / sc%h
              f(:, 2) = sum(m%fint(:, nodes), dim=2)
              f(:, 3) = sum(m%finert(:, nodes), dim=2)
              f(:, 4) = sum(m%fext(:, nodes), dim=2)
              f(:, 5) = f(:, 2) + f(:, 3) - f(:, 1) - f(:, 4)
              write (c%units(j), '(es15.8,10(1x,es14.7))') sc%time, f
            end associate
          end do
        end select
      end associate
    end do
  end subroutine postpro_step

  !> NEW MECAx SETS: the sets as mesh node indices, checked against the meshes.
  subroutine read_node_sets(c, m, sets)
    type(postpro_input_t), intent(in) :: c
    type(mailx_t), intent(in) :: m
    type(node_set_t), allocatable, intent(out) :: sets(:)
    integer :: line, nsets, ngroups, is, ig, ib, nn, j, node, ios
    integer, allocatable :: nodes(:)
    line = 0
    nsets = next_int('the number of sets', 1)
    allocate (sets(nsets))
    do is = 1, nsets
      allocate (nodes(0))
      ngroups = next_int('the number of groups of set '//itoa(is), 1)
      do ig = 1, ngroups
        call next_line('a MAILx body number and its node count')
        read (c%params(line), *, iostat=ios) ib, nn
        if (ios /= 0) call input_error(c%src%file, c%param_lines(line), 1, &
          "NEW MECAx SETS: expected 'body nodes' (two integers), found '"//trim(c%params(line))//"'")
        if (ib < 1 .or. ib > m%n) call input_error(c%src%file, c%param_lines(line), 1, 'NEW MECAx SETS: MAILx body '// &
          itoa(ib)//' does not exist (1 to '//itoa(m%n)//')')
        do j = 1, nn
          node = next_int('a node number of MAILx body '//itoa(ib), 1)
          if (node > m%node_first(ib + 1) - m%node_first(ib)) call input_error(c%src%file, c%param_lines(line), 1, &
            'NEW MECAx SETS: MAILx body '//itoa(ib)//' has no node '//itoa(node))
          nodes = [nodes, m%node_first(ib) + node - 1]
        end do
      end do
      if (size(nodes) == 0) call input_error(c%src%file, c%src%line, 1, 'NEW MECAx SETS: set '//itoa(is)//' is empty')
      call move_alloc(nodes, sets(is)%nodes)
    end do
    if (line < size(c%params)) call input_error(c%src%file, c%param_lines(line + 1), 1, &
      'NEW MECAx SETS: '//itoa(nsets)//' sets announced, more lines follow')

  contains

    subroutine next_line(what)
      character(len=*), intent(in) :: what
      line = line + 1
      ! Located at the command's last line (the set count promised more lines).
      if (line > size(c%params)) then
        if (size(c%params) == 0) call input_error(c%src%file, c%src%line, 1, 'NEW MECAx SETS: expected '//what// &
                                                  ' after this command')
        call input_error(c%src%file, c%param_lines(size(c%params)), 1, 'NEW MECAx SETS: expected '//what// &
                         ' after this line (the sets counted at line '//itoa(c%param_lines(1))//' need more)')
      end if
    end subroutine next_line

    integer function next_int(what, lowest) result(v)
      character(len=*), intent(in) :: what
      integer, intent(in) :: lowest
      character(len=:), allocatable :: msg
      call next_line(what)
      if (.not. parse_int(c%params(line), v, msg) .or. v < lowest) call input_error(c%src%file, &
        c%param_lines(line), 1, 'NEW MECAx SETS: expected '//what//' (an integer >= '//itoa(lowest)// &
        "), found '"//trim(c%params(line))//"'")
    end function next_int
  end subroutine read_node_sets

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

  !> The running sums of the commands (DISSIPATED ENERGY's cumulative column),
  !> for restart points.
  function postpro_sums(pp) result(s)
    type(postpro_t), intent(in) :: pp
    real(wp), allocatable :: s(:)
    s = [pp%dissipated]
  end function postpro_sums

  !> Continue the running sums of a restart point (none in files written before
  !> they were kept: the sums start again from 0, as they did).
  subroutine postpro_restore_sums(pp, s)
    type(postpro_t), intent(inout) :: pp
    real(wp), intent(in) :: s(:)
    if (size(s) >= 1) pp%dissipated = s(1)
  end subroutine postpro_restore_sums

  !> Hand the lines written so far to the system (a killed run keeps them),
  !> and stop the run if they did not reach the disk (fracas_files).
  subroutine postpro_flush(pp)
    type(postpro_t), intent(inout) :: pp
    integer :: k, j
    if (.not. pp%active) return
    do k = 1, size(pp%cmds)
      do j = 1, size(pp%cmds(k)%units)
        call check_written(pp%cmds(k)%units(j), unit_file(pp%cmds(k)%units(j)))
      end do
    end do
  end subroutine postpro_flush

  subroutine postpro_close(pp)
    type(postpro_t), intent(inout) :: pp
    integer :: k, j
    if (.not. pp%active) return
    pp%active = .false.   ! first: a write error stops the run, whose clean-up closes again
    do k = 1, size(pp%cmds)
      do j = 1, size(pp%cmds(k)%units)
        call close_written(pp%cmds(k)%units(j), unit_file(pp%cmds(k)%units(j)))
      end do
    end do
  end subroutine postpro_close

  !> The file open on unit u.
  function unit_file(u) result(path)
    integer, intent(in) :: u
    character(len=:), allocatable :: path
    character(len=4096) :: name
    inquire (unit=u, name=name)
    path = trim(name)
  end function unit_file

  !> True for the names of the files a run may write in POSTPRO/ (for
  !> clearing or refusing the results of an earlier run).
  logical function postpro_owns(name)
    character(len=*), intent(in) :: name
    postpro_owns = name == 'SOLVER_INFORMATIONS.DAT' .or. name == 'DISSIPATED_ENERGY.DAT' .or. &
                   numbered(name, 'BODY_') .or. numbered(name, 'TORQUE_') .or. numbered(name, 'Dep_') .or. &
                   numbered(name, 'Fint_')
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
