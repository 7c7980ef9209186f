!> mesh_probe CASE_DIR OUT_FILE [EVERY]
!>
!> Runs CASE_DIR through the library as the fracas driver does (read_deck,
!> scene_build, scene_step for every step of COMMAND.DAT) and writes the state
!> of its meshed bodies at full precision every EVERY steps (default: the last
!> step only): the OUTBOX records hold 7 digits, the validation checks of
!> test_cases/validation_meshes need 1e-10. Text, one record per written step:
!>   step <n> <time>
!>   energy <kinetic> <elastic> <plastic work>      (meshed bodies, per unit thickness)
!>   nodes <count>                                  then per node: ref x y, X x y, V x y
!>   gauss <count> <values per point>               then per Gauss point its state
!>                                                  (fracas_bulk: stress xx yy xy zz,
!>                                                  strain xx yy gamma_xy zz,
!>                                                  plastic strain (4), p)
program mesh_probe
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal
  use fracas_deck, only: deck_t
  use fracas_read_deck, only: read_deck
  use fracas_scene, only: scene_t, step_report_t, scene_build, scene_step
  use fracas_mailx, only: mailx_gauss_values, mailx_kinetic_energy
  use fracas_bulk, only: gp_size
  implicit none
  type(deck_t) :: deck
  type(scene_t) :: sc
  type(step_report_t) :: rep
  character(len=4096) :: case_dir, out_file, arg
  integer :: every, istep, nsteps, u

  if (command_argument_count() < 2) call fatal('usage: mesh_probe CASE_DIR OUT_FILE [EVERY]')
  call get_command_argument(1, case_dir)
  call get_command_argument(2, out_file)
  every = 0
  if (command_argument_count() >= 3) then
    call get_command_argument(3, arg)
    read (arg, *) every
  end if
  call read_deck(trim(case_dir), deck)
  call scene_build(deck, sc)
  nsteps = deck%run%number_of_steps
  open (newunit=u, file=trim(out_file), status='replace', action='write')
  if (every > 0) call write_state(0)
  do istep = 1, nsteps
    call scene_step(sc, rep)
    if (.not. rep%nlgs%converged) call fatal('NLGS did not converge')
    if (istep == nsteps .or. (every > 0 .and. mod(istep, max(every, 1)) == 0)) call write_state(istep)
  end do
  close (u)

contains

  subroutine write_state(istep)
    integer, intent(in) :: istep
    real(wp), allocatable :: gp(:, :)
    integer :: j
    write (u, '(a,1x,i0,1x,es24.16e3)') 'step', istep, sc%time
    write (u, '(a,3(1x,es24.16e3))') 'energy', mailx_kinetic_energy(sc%meshes), sc%meshes%elastic, sc%meshes%plastic_work
    write (u, '(a,1x,i0)') 'nodes', sc%meshes%nnodes
    do j = 1, sc%meshes%nnodes
      write (u, '(6(1x,es24.16e3))') sc%meshes%ref(:, j), sc%meshes%x(:, j), sc%meshes%v(:, j)
    end do
    allocate (gp(gp_size, sc%meshes%ngp))
    call mailx_gauss_values(sc%meshes, gp)
    write (u, '(a,1x,i0,1x,i0)') 'gauss', sc%meshes%ngp, gp_size
    do j = 1, sc%meshes%ngp
      write (u, '(*(1x,es24.16e3))') gp(:, j)
    end do
  end subroutine write_state
end program mesh_probe
