!> The contact laws in dimension 3 (fracas_contact_laws: law_shift, law_local_problem,
!> cohesive_elimination, cohesive_end_jump, czm_mode_jump) against closed forms and
!> against the same laws in 2D. A 3D contact whose tangential data all lie along one
!> unit direction e of the tangent plane (e = t1, t2 or at 45 degrees) is the 2D contact
!> (t = e, n) embedded: the laws are isotropic in the tangent plane (Coulomb's disk,
!> K = diag(kt, kt, kn), damage seeing the norm of the tangential jump), so every 3D
!> answer must be the 2D answer along e (relative 1e-12: the 3D elimination inverts
!> 3 x 3 blocks by cofactors, the 2D one its 2 x 2 block in closed form), and the
!> direction perpendicular to e must carry nothing. Blocks are stored by rows, local
!> vectors (t1, t2, n). The 3D local problem then goes to the exact 3D Coulomb solver
!> (fracas_local_solver: coulomb_3d, FCLib order (n, t1, t2), column-major) and must
!> give the 2D solver's reaction along e.
program test_contact_laws_3d
  use fracas_kinds, only: wp
  use fracas_deck, only: law_input_t
  use fracas_contact_laws, only: law_t, law_from_input, law_shift, law_local_problem, cohesive_end_jump, &
                                 czm_mode_jump, coh_size, coh_k, coh_av, coh_wprime, coh_j0, coh_jh, coh_u0, &
                                 n_internals, int_jump, int_beta, law_czm
  use fracas_czm, only: czm_beta_update, czm_stored_energy
  use fracas_local_solver, only: coulomb_2d, coulomb_3d, inverse_block_3d
  use fracas_ids, only: st_stick, st_slifw, st_slibw
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_frame_3d, only: local3_to_fclib
  implicit none
  real(wp), parameter :: h = 1.0e-4_wp, tol = 1.0e-12_wp
  ! a 2D block (t, n) by rows, not symmetric (a cohesive W' is not) but positive definite
  real(wp), parameter :: w2(4) = [2.0e-3_wp, 3.0e-4_wp, 2.5e-4_wp, 1.5e-3_wp]
  real(wp), parameter :: wperp = 1.7e-3_wp          ! the 3D block across e
  type(law_t) :: law
  real(wp) :: e(2), shift2(2), shift3(3), ub2(2), ub3(3)
  logical :: active2, active3
  integer :: idir, imid
  character(len=8), parameter :: dname(3) = ['along t1', 'along t2', 'at 45   ']

  ! ---------------------------------------------------------------- Signorini shifts
  law = make('IQS_CLB', [0.3_wp])
  call law_shift(law, 2.0e-6_wp, h, [0.1_wp, -0.2_wp, -0.3_wp], shift3, active3)
  call check_true('IQS_CLB 3D: shift (0, 0, g/h), active', all(shift3 == [0.0_wp, 0.0_wp, 2.0e-6_wp / h]) .and. active3)
  call law_shift(law, -2.0e-6_wp, h, [0.1_wp, -0.2_wp, -0.3_wp], shift3, active3)
  call check_true('IQS_CLB 3D: an overlap is forgiven (shift 0)', all(shift3 == 0.0_wp))
  law = make('GAP_SGR_CLB', [0.3_wp])
  call law_shift(law, -2.0e-6_wp, h, [0.1_wp, -0.2_wp, -0.3_wp], shift3, active3)
  call check_true('GAP_SGR_CLB 3D: shift (0, 0, g/h)', all(shift3 == [0.0_wp, 0.0_wp, -2.0e-6_wp / h]))
  law = make('RST_CLB', [0.6_wp, 0.2_wp, 0.3_wp])
  call law_shift(law, 0.0_wp, h, [0.1_wp, -0.2_wp, -0.3_wp], shift3, active3)
  call check_true('RST_CLB 3D: shift (et ut1, et ut2, en un) once closed', &
                  all(shift3 == [0.2_wp * 0.1_wp, 0.2_wp * (-0.2_wp), 0.6_wp * (-0.3_wp)]) .and. active3)
  call law_shift(law, 1.0e-3_wp, h, [0.1_wp, -0.2_wp, -0.3_wp], shift3, active3)
  call check_true('RST_CLB 3D: open, no reaction', .not. active3)

  ! ----------------------------------------------- every law along e: 3D = 2D embedded
  do idir = 1, 3
    e = direction(idir)
    ub2 = [0.04_wp, -0.3_wp]
    ub3 = [ub2(1) * e, ub2(2)]
    law = make('RST_CLB', [0.6_wp, 0.2_wp, 0.3_wp])
    call law_shift(law, 0.0_wp, h, ub2, shift2, active2)
    call law_shift(law, 0.0_wp, h, ub3, shift3, active3)
    call same_3d('RST_CLB shift '//dname(idir), shift3, shift2, e)
    call compare_problem('IQS_CLB '//dname(idir), make('IQS_CLB', [0.3_wp]), e, .false.)
    call compare_problem('ELASTIC_REPELL_CLB '//dname(idir), make('ELASTIC_REPELL_CLB', [1.0e7_wp, 0.3_wp]), e, .false.)
    call compare_problem('COUPLED_DOF '//dname(idir), make('COUPLED_DOF', [0.0_wp]), e, .false.)
    do imid = 0, 1
      call compare_problem('IQS_MAC_CZM '//merge('midpoint', 'lmgc90  ', imid == 1)//' '//dname(idir), &
                           make('IQS_MAC_CZM', [0.3_wp, 0.3_wp, 1.0e12_wp, 4.0e11_wp, 0.0_wp, 40.0_wp]), e, imid == 1)
      call compare_problem('IQS_MAL_CZM '//merge('midpoint', 'lmgc90  ', imid == 1)//' '//dname(idir), &
                           make('IQS_MAL_CZM', [0.3_wp, 0.3_wp, 1.0e12_wp, 4.0e11_wp, 3.0e7_wp, 2.0e7_wp, 1.0e3_wp, &
                                                1.5e3_wp]), e, imid == 1)
    end do
  end do
  call test_finish()

contains

  !> The unit tangential directions e tested.
  pure function direction(i) result(d)
    integer, intent(in) :: i
    real(wp) :: d(2)
    select case (i)
    case (1); d = [1.0_wp, 0.0_wp]
    case (2); d = [0.0_wp, 1.0_wp]
    case default; d = [1.0_wp, 1.0_wp] / sqrt(2.0_wp)
    end select
  end function direction

  function make(name, params) result(l)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: params(:)
    type(law_t) :: l
    type(law_input_t) :: inp
    inp%nickname = 'test'
    inp%name = name
    inp%params = params
    inp%src%file = 'test'
    l = law_from_input(inp)
  end function make

  !> The 3D block of the 2D block w2 embedded along e (wperp across e), by rows.
  pure function embed_block(w, e) result(w3)
    real(wp), intent(in) :: w(4), e(2)
    real(wp) :: w3(9), m(3, 3), p(2)
    p = [-e(2), e(1)]
    m(1:2, 1:2) = w(1) * spread(e, 2, 2) * spread(e, 1, 2) + wperp * spread(p, 2, 2) * spread(p, 1, 2)
    m(1:2, 3) = w(2) * e
    m(3, 1:2) = w(3) * e
    m(3, 3) = w(4)
    w3 = reshape(transpose(m), [9])
  end function embed_block

  !> A 3D local vector v3 must be v2 along e (tangential) and v2(2) (normal).
  subroutine same_3d(what, v3, v2, e)
    character(len=*), intent(in) :: what
    real(wp), intent(in) :: v3(3), v2(2), e(2)
    real(wp) :: scale
    scale = max(maxval(abs(v2)), tiny(1.0_wp))
    call check_close(what//': tangential along e', dot_product(v3(1:2), e) / scale, v2(1) / scale, tol)
    call check_close(what//': nothing across e', (v3(2) * e(1) - v3(1) * e(2)) / scale, 0.0_wp, tol)
    call check_close(what//': normal', v3(3) / scale, v2(2) / scale, tol)
  end subroutine same_3d

  !> The 3D block b3 (by rows) seen along e must be the 2D block b2; its part across e
  !> uncoupled from e and n.
  subroutine same_block(what, b3, b2, e)
    character(len=*), intent(in) :: what
    real(wp), intent(in) :: b3(9), b2(4), e(2)
    real(wp) :: m(3, 3), p(2), scale
    m = transpose(reshape(b3, [3, 3]))
    p = [-e(2), e(1)]
    scale = maxval(abs(b2))
    call check_close(what//': (e, e)', dot_product(e, matmul(m(1:2, 1:2), e)) / scale, b2(1) / scale, tol)
    call check_close(what//': (e, n)', dot_product(e, m(1:2, 3)) / scale, b2(2) / scale, tol)
    call check_close(what//': (n, e)', dot_product(m(3, 1:2), e) / scale, b2(3) / scale, tol)
    call check_close(what//': (n, n)', m(3, 3) / scale, b2(4) / scale, tol)
    call check_close(what//': (p, e) = 0', dot_product(p, matmul(m(1:2, 1:2), e)) / scale, 0.0_wp, tol)
    call check_close(what//': (p, n) = 0', dot_product(p, m(1:2, 3)) / scale, 0.0_wp, tol)
  end subroutine same_block

  !> law_local_problem in 2D and in 3D along e (glued interface with a tangential
  !> jump along e, beta 0.8), then the local solution of each (the 3D one by coulomb_3d),
  !> the end-of-step jumps and the damage they give.
  subroutine compare_problem(what, l, e, midpoint)
    character(len=*), intent(in) :: what
    type(law_t), intent(in) :: l
    real(wp), intent(in) :: e(2)
    logical, intent(in) :: midpoint
    real(wp) :: in2(n_internals(2)), in3(n_internals(3)), u2(2), u3(3), sh2(2), sh3(3), mu2, mu3
    real(wp) :: coh2(coh_size(2)), coh3(coh_size(3)), we2(4), we3(9), j2(2), j3(3), q2(2), q3(3)
    real(wp) :: rt, rn, r3(3), wf(9), qf(3), beta2, beta3
    logical :: act2, act3, c2, c3, s2, s3
    integer :: st2, st3, i
    in2 = [0.01_wp, 2.0e-6_wp, 1.0e-6_wp, 0.8_wp, -99.0_wp]
    in3 = 0.0_wp
    in3(1) = in2(1)
    in3(int_jump:int_jump + 1) = in2(int_jump) * e
    in3(int_jump + 2) = in2(int_jump + 1)
    in3(int_beta(3):) = in2(int_beta(2):)
    u2 = [0.05_wp, -0.2_wp]
    u3 = [u2(1) * e, u2(2)]
    call law_local_problem(l, 1.0e-7_wp, h, u2, 0, in2, 0.01_wp, w2, midpoint, 0.5_wp, sh2, mu2, act2, c2, coh2, &
                           we2, s2)
    call law_local_problem(l, 1.0e-7_wp, h, u3, 0, in3, 0.01_wp, embed_block(w2, e), midpoint, 0.5_wp, sh3, mu3, &
                           act3, c3, coh3, we3, s3)
    call check_true(what//': same friction, activity, cohesion, solvability', &
                    mu2 == mu3 .and. (act2 .eqv. act3) .and. (c2 .eqv. c3) .and. (s2 .eqv. s3))
    call same_3d(what//' shift', sh3, sh2, e)
    call same_block(what//' effective block', we3, we2, e)
    if (c2) then
      call same_3d(what//' a', coh3(coh_av(3):coh_av(3) + 2), coh2(coh_av(2):coh_av(2) + 1), e)
      call check_true(what//': K = diag(kt, kt, kn)', all(coh3(coh_k(3):coh_k(3) + 2) == &
                      [coh2(coh_k(2)), coh2(coh_k(2)), coh2(coh_k(2) + 1)]))
      call same_block(what//' A', coh3(1:9), coh2(1:4), e)
      call same_block(what//' W''', coh3(coh_wprime(3):coh_wprime(3) + 8), coh2(coh_wprime(2):coh_wprime(2) + 3), e)
      call same_3d(what//' start jumps', coh3(coh_u0(3):coh_u0(3) + 2), coh2(coh_u0(2):coh_u0(2) + 1), e)
      call check_close(what//': jump factor', coh3(coh_jh(3)), coh2(coh_jh(2)), 0.0_wp)
      ! end jumps at u~ along e, and the damage and energy they give (tangential norm)
      call cohesive_end_jump(2, coh2, [1.0e-3_wp, 2.0e-2_wp], j2)
      call cohesive_end_jump(3, coh3, [1.0e-3_wp * e, 2.0e-2_wp], j3)
      call same_3d(what//' end jumps', j3, j2, e)
      call check_true(what//': end jumps j0 + jh u~', abs(j2(2) - (coh2(coh_j0(2) + 1) + coh2(coh_jh(2)) * 2.0e-2_wp)) &
                      <= 1e-15_wp * abs(j2(2)))
      if (l%kind == law_czm) then      ! (COUPLED_DOF: a stiff spring, no damage)
        ! scaled to a norm of 8e-5, far enough to damage (MAL: softening from about 5e-5)
        j3 = (8.0e-5_wp / norm2(j2)) * j3
        j2 = (8.0e-5_wp / norm2(j2)) * j2
        beta2 = czm_beta_update(l%czm, 0.8_wp, j2(1), j2(2), h)
        q2 = czm_mode_jump(j3)
        beta3 = czm_beta_update(l%czm, 0.8_wp, q2(1), q2(2), h)
        call check_true(what//': the jumps damage', beta2 < 0.8_wp .and. beta2 > 0.0_wp)
        call check_close(what//': beta from the 3D jump = 2D beta', beta3, beta2, tol)
        call check_close(what//': stored energy 3D = 2D', czm_stored_energy(l%czm, beta3, q2(1), q2(2)) / &
                         czm_stored_energy(l%czm, beta2, j2(1), j2(2)), 1.0_wp, tol)
      end if
    end if
    if (.not. s2) return
    ! the local solution on the effective block: 2D enumerative solver against the exact
    ! 3D solver (FCLib order (n, t1, t2), column-major), approaching with a small then a
    ! large tangential velocity (sliding)
    do i = 1, 2
      q2 = [merge(0.0_wp, 30.0_wp, i == 1), -1.0_wp]
      q3 = [q2(1) * e, q2(2)]
      call coulomb_2d(q2(1), q2(2), we2(1), we2(2), we2(3), we2(4), mu2, rt, rn, st2)
      call local3_to_fclib(we3, q3, wf, qf)
      r3 = 0.0_wp
      call coulomb_3d(qf, wf, inverse_block_3d(wf), mu3, r3, st3)
      call check_true(what//': 3D status = 2D status (stick; sliding in any direction)', &
                      st3 == merge(st_stick, st_slifw, st2 == st_stick))
      if (i == 2) call check_true(what//': slides', st2 == st_slifw .or. st2 == st_slibw)
      call same_3d(what//' local solution', [r3(2:3), r3(1)], [rt, rn], e)
    end do
  end subroutine compare_problem
end program test_contact_laws_3d
