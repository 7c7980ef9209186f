!> The contact side of a rigid 3D body (fracas_rbdy3_side) with the body model
!> (fracas_rbdy3), SPPLx (fracas_spplx) and the existing exact 3D Coulomb local
!> solver (fracas_local_solver: coulomb_3d), at the unit level (not the scene):
!> 1. H against a central finite difference of a material point's motion (the
!>    frame turned by the exact rotation; delta = 1e-6, error O(delta^2): 1e-9);
!> 2. W = H M^-1 H^T against an explicit impulse: a unit local impulse e_j as a
!>    global force P at the point, dv = P / m, d omega = I^-1 F^T (r x P), the
!>    point's velocity change projected on the frame (round-off, 1e-12);
!> 3. one step of a sphere resting on a horizontal PLANx under gravity: the
!>    normal impulse / h = m g, tangential 0 (round-off, 1e-10 relative);
!> 4. a sphere rolling down a PLANx inclined by alpha, N = 400 steps (h = 1e-3,
!>    theta = 0.5, IQS-like law: Signorini on u_n + max(0, gap) / h), with a
!>    loop in the test: sticking (mu = 0.5 > 2/7 tan alpha) the centre's
!>    acceleration is 5/7 g sin alpha, the normal force m g cos alpha, the
!>    friction 2/7 m g sin alpha, and the rolling condition holds (the scheme
!>    holds them exactly per step: 1e-9 relative); slipping (alpha = 30 deg,
!>    mu = 0.1 < 2/7 tan alpha = 0.165) a = g (sin alpha - mu cos alpha) and
!>    the angular acceleration 5 mu g cos alpha / (2 R); energy audit of the
!>    rolling (rbdy3_add_step_work): kinetic energy gained = work of gravity
!>    (1e-9 relative: the end velocity of the contact point is 0, so is the
!>    theta-rule work of the contact impulses);
!> 5. a cube (POLYR) face down on the PLANx, PRPLx's 4 points, Gauss-Seidel
!>    over them in the test (until the impulses move < 1e-15 m g h): at rest
!>    the normal forces sum to m g (1e-10 relative, hyperstatic: only the sum
!>    is determined); on a 20 deg incline with mu = 0.5 > tan alpha it sticks
!>    (a = 0, friction m g sin alpha), at 30 deg with mu = 0.3 it slides with
!>    a = g (sin alpha - mu cos alpha) (1e-9 g) without turning;
!> 6. two cubes stacked on a PLANx (the upper one offset and turned): PRPLx
!>    and PRPRx points, Gauss-Seidel: after 1 and 100 steps the plane carries
!>    2 m g and the lower cube m g (1e-9 relative), nothing moves (1e-9 m/s).
!> Planted bugs watched red: the levers as F (r x e_k) instead of F^T (r x e_k)
!> (checks 1 and 2, 10 failures; the rolling is blind to it: a sphere's frame
!> is the identity); the Delassus block without its rotational part (checks 2
!> and 4: a = 2.388 for 2.397, friction 48.3 N for 10.04 N); PRPLx's gap with
!> + a3 (check 5: no contact found); the work of gravity with the end velocity
!> alone (energy audit: 6.7533 for 6.7365); PRPRx's normal reversed when the
!> reference face is the antagonist's (stack: the lower cube carries 0, the
!> upper one falls).
program test_rbdy3_contact
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_deck, only: driven_dof_input_t
  use fracas_rbdy3, only: rbdy3_t, rbdy3_init, rbdy3_add_drives, rbdy3_begin_step, rbdy3_detection_config, &
                          rbdy3_end_step, rbdy3_add_step_work, rbdy3_kinetic_energy
  use fracas_rbdy3_side, only: rigid3_levers, rigid3_add_delassus, rigid3_add_velocity, rigid3_pair_velocity, &
                               rigid3_pair_impulse
  use fracas_contactors_3d, only: tactor3_t, tk3_spher, tk3_planx, body3_mass_properties, box_surface, &
                                  polyr_from_surface, polyr_vertices
  use fracas_spplx, only: spplx_geometry
  use fracas_prplx, only: prplx_contacts
  use fracas_prprx, only: prprx_contacts
  use fracas_frame_3d, only: cross3, rotation_of_vector, local3_to_fclib
  use fracas_local_solver, only: coulomb_3d, inverse_block_3d
  implicit none
  real(wp), parameter :: pi = acos(-1.0_wp), grav = 9.81_wp, radius = 0.1_wp, rho = 2500.0_wp
  ! the test's contact list (contacts_add, gauss_seidel): bodies (candidate,
  ! antagonist), frame, gap, levers, Delassus block
  integer :: cl_body(2, 16)
  real(wp) :: cl_frame(3, 3, 16), cl_gap(16), cl_lever(18, 16), cl_w(9, 16)

  call h_and_delassus()
  call incline('sphere', 0.0_wp, 0.5_wp, 1, 'sphere at rest on a plane')
  call incline('sphere', 20.0_wp * pi / 180.0_wp, 0.5_wp, 400, 'sphere rolling (stick)')
  call incline('sphere', 30.0_wp * pi / 180.0_wp, 0.1_wp, 400, 'sphere sliding')
  call incline('cube', 0.0_wp, 0.5_wp, 1, 'cube at rest on a plane')
  call incline('cube', 20.0_wp * pi / 180.0_wp, 0.5_wp, 200, 'cube sticking')
  call incline('cube', 30.0_wp * pi / 180.0_wp, 0.3_wp, 200, 'cube sliding')
  call stack(1)
  call stack(100)
  call test_finish()

contains

  subroutine h_and_delassus()
    real(wp) :: f(3, 3), cf(3, 3), r(3), inv(6), lev(9), w(9), u(3), v(6), dv(3), dom(3), du(3), p(3), pp(3), pm(3)
    real(wp), parameter :: delta = 1.0e-6_wp
    integer :: j, k
    f = rotation_of_vector([0.4_wp, -0.9_wp, 1.3_wp])       ! body frame
    cf = rotation_of_vector([-1.2_wp, 0.3_wp, 0.5_wp])      ! contact frame (t1, t2, n)
    r = [0.3_wp, -0.7_wp, 0.2_wp]                           ! point - centre
    inv = 1.0_wp / [2.0_wp, 2.0_wp, 2.0_wp, 0.3_wp, 0.5_wp, 0.8_wp]
    lev = rigid3_levers(r, cf, f)
    ! 1. H v against the finite difference of the point's motion
    v = [0.2_wp, -0.1_wp, 0.4_wp, 1.5_wp, -0.8_wp, 0.6_wp]
    u = 0.0_wp
    call rigid3_add_velocity(1.0_wp, v, cf, lev, u)
    pp = delta * v(1:3) + matmul(f, matmul(rotation_of_vector(delta * v(4:6)), matmul(transpose(f), r)))
    pm = -delta * v(1:3) + matmul(f, matmul(rotation_of_vector(-delta * v(4:6)), matmul(transpose(f), r)))
    p = matmul((pp - pm) / (2.0_wp * delta), cf)
    call check_close('H v = finite difference of the point motion (frame components)', norm2(u - p), 0.0_wp, 1.0e-9_wp)
    ! 2. W against explicit impulses
    w = 0.0_wp
    call rigid3_add_delassus(inv, cf, lev, w)
    do j = 1, 3
      dv = inv(1:3) * cf(:, j)
      dom = inv(4:6) * matmul(cross3(r, cf(:, j)), f)
      du = matmul(dv + cross3(matmul(f, dom), r), cf)
      do k = 1, 3
        call check_close('W(k,j) = explicit impulse response', w(3 * (k - 1) + j), du(k), 1.0e-12_wp)
      end do
    end do
  end subroutine h_and_delassus

  !> A sphere (radius 0.1) or a cube (POLYR, half side 0.1, face down) as body
  !> 1 on a PLANx (body 2, every dof held at 0 by DRV_DOF-like drives) inclined
  !> by alpha about x; starts at rest, touching (gap 0). Each step: detection
  !> (SPPLx, or PRPLx: 4 points), then Gauss-Seidel over the contacts with the
  !> exact local solver until the impulses move by less than 1e-15 m g h.
  subroutine incline(shape, alpha, mu, nstep, name)
    character(len=*), intent(in) :: shape, name
    real(wp), intent(in) :: alpha, mu
    integer, intent(in) :: nstep
    real(wp), parameter :: h = 1.0e-3_wp, theta = 0.5_wp, half = 0.1_wp
    type(rbdy3_t) :: b
    type(tactor3_t) :: ts(1), tp(1)
    real(wp) :: cs(3), fs(3, 3), ms, is(3), cp(3), fp(3, 3), mp, ip(3), avrd, q(3, 2), ftt(3, 3, 2), vert(3, 8)
    real(wp) :: gap(4), pt(3, 4), cf(3, 3), rl(3, 8), rsum(3), down(3), t, a, aref
    real(wp) :: omega_dot, wg, wf, ke0
    integer :: faces(3, 12), iv(4), k, np, nc
    logical :: found, cube
    cube = shape == 'cube'
    tp(1)%kind = tk3_planx
    tp(1)%axes = [10.0_wp, 10.0_wp, 0.05_wp]
    tp(1)%frame = rotation_of_vector([alpha, 0.0_wp, 0.0_wp])
    avrd = 0.0_wp
    call body3_mass_properties(tp, [0.0_wp, 0.0_wp, 0.0_wp], rho, avrd, cp, fp, mp, ip)
    if (cube) then
      call box_surface([half, half, half], vert, faces)
      vert = matmul(fp, vert)      ! face down on the incline
      ts(1) = polyr_from_surface(vert, faces)
    else
      ts(1)%kind = tk3_spher
      ts(1)%radius = radius
    end if
    avrd = 0.0_wp
    call body3_mass_properties(ts, cp + (0.05_wp + half) * fp(:, 3), rho, avrd, cs, fs, ms, is)
    call rbdy3_init(b, [1, 2], reshape([cs, cp], [3, 2]), reshape([fs, fp], [3, 3, 2]), [ms, mp], &
                    reshape([is, ip], [3, 2]), [avrd, 1.0_wp], [0.0_wp, 0.0_wp, -grav])
    call hold_body(b, 2)
    down = -fp(:, 2)
    rl = 0.0_wp
    t = 0.0_wp
    found = .true.
    wg = 0.0_wp; wf = 0.0_wp
    ke0 = rbdy3_kinetic_energy(b)
    do k = 1, nstep
      call rbdy3_begin_step(b, t, h, theta)
      call rbdy3_detection_config(b, h, theta, q, ftt)
      if (cube) then
        call prplx_contacts(polyr_vertices(ts(1), q(:, 1), ftt(:, :, 1)), q(:, 1), q(:, 2), ftt(:, :, 2), tp(1)%axes, &
                            1.0e-3_wp, np, iv, gap, pt, cf)
        found = found .and. np == 4
      else
        call spplx_geometry(q(:, 1), radius, q(:, 2), ftt(:, :, 2), tp(1)%axes, 1.0e-3_wp, found, gap(1), pt(:, 1), cf)
        np = merge(1, 0, found)
      end if
      if (np == 0) exit
      nc = 0
      call contacts_add(b, q, ftt, 1, 2, np, pt, cf, gap, nc)
      call gauss_seidel(b, nc, h, mu, 1.0e-15_wp * ms * grav * h, rl)
      call rbdy3_add_step_work(b, t, h, theta, wg, wf)
      call rbdy3_end_step(b, h, theta)
      t = k * h
    end do
    call check_true(name//': in contact every step', found)
    if (.not. found) return
    rsum = sum(rl(:, 1:nc), dim=2) / h
    if (nstep == 1) then
      call check_close(name//': normal force = m g', rsum(3), ms * grav, 1.0e-10_wp * ms * grav)
      call check_close(name//': no friction', norm2(rsum(1:2)), 0.0_wp, 1.0e-10_wp * ms * grav)
      call check_close(name//': velocity after the step', norm2(b%v(:, 1)), 0.0_wp, 1.0e-12_wp)
      return
    end if
    a = dot_product(b%v(1:3, 1), down) / t
    call check_close(name//': normal force = m g cos alpha', rsum(3), ms * grav * cos(alpha), 1.0e-9_wp * ms * grav)
    call check_close(name//': no motion off the slope', abs(dot_product(b%v(1:3, 1), fp(:, 1))) + &
                     abs(dot_product(b%v(1:3, 1), fp(:, 3))), 0.0_wp, 1.0e-9_wp)
    omega_dot = norm2(matmul(b%frame(:, :, 1), b%v(4:6, 1))) / t
    if (cube) then
      if (mu > tan(alpha)) then
        aref = 0.0_wp
        call check_close(name//': friction = m g sin alpha', norm2(rsum(1:2)), ms * grav * sin(alpha), 1.0e-9_wp * ms * grav)
      else
        aref = grav * (sin(alpha) - mu * cos(alpha))
        call check_close(name//': friction = mu N', norm2(rsum(1:2)), mu * rsum(3), 1.0e-9_wp * ms * grav)
      end if
      call check_close(name//': a (0 sticking, g (sin alpha - mu cos alpha) sliding)', a, aref, 1.0e-9_wp * grav)
      call check_close(name//': no rotation', omega_dot, 0.0_wp, 1.0e-9_wp * grav / half)
    else if (mu > 2.0_wp / 7.0_wp * tan(alpha)) then
      aref = 5.0_wp / 7.0_wp * grav * sin(alpha)
      call check_close(name//': a = 5/7 g sin alpha', a, aref, 1.0e-9_wp * aref)
      call check_close(name//': friction = 2/7 m g sin alpha', norm2(rsum(1:2)), 2.0_wp / 7.0_wp * ms * grav * sin(alpha), &
                       1.0e-9_wp * ms * grav)
      call check_close(name//': rolling, omega R = v', omega_dot * radius, a, 1.0e-9_wp * aref)
      call check_close(name//': energy audit, kinetic energy gained = work of gravity (rolling dissipates nothing)', &
                       rbdy3_kinetic_energy(b) - ke0, wg, 1.0e-9_wp * wg)
    else
      aref = grav * (sin(alpha) - mu * cos(alpha))
      call check_close(name//': a = g (sin alpha - mu cos alpha)', a, aref, 1.0e-9_wp * aref)
      call check_close(name//': friction = mu N', norm2(rsum(1:2)), mu * rsum(3), 1.0e-9_wp * ms * grav)
      call check_close(name//': angular acceleration 5 mu g cos alpha / (2 R)', omega_dot, &
                       5.0_wp * mu * grav * cos(alpha) / (2.0_wp * radius), 1.0e-9_wp * grav / radius)
      call check_true(name//': slipping (omega R < v)', omega_dot * radius < 0.9_wp * a)
    end if
    write (*, '(a,a,2es24.16)') name, ': a, reference ', a, aref
  end subroutine incline

  !> Two cubes (half side 0.1) stacked on a horizontal PLANx (held), the upper
  !> one offset by (0.03, 0.02) and turned 0.3 rad about z; PRPLx (4 points)
  !> and PRPRx (4 of the octagon-like overlap), Gauss-Seidel: after nstep
  !> steps the plane carries 2 m g and the lower cube m g (1e-9 relative;
  !> hyperstatic: only the sums are determined), nothing moves (1e-9 m/s).
  subroutine stack(nstep)
    integer, intent(in) :: nstep
    real(wp), parameter :: h = 1.0e-3_wp, theta = 0.5_wp, half = 0.1_wp
    type(rbdy3_t) :: b
    type(tactor3_t) :: tc(1, 2), tp(1)
    real(wp) :: vert(3, 8), c(3, 3), f(3, 3, 3), m(3), ii(3, 3), avrd, q(3, 3), ftt(3, 3, 3), gap(4), pt(3, 4), cf(3, 3)
    real(wp) :: rl(3, 8), wplane, wcube
    integer :: faces(3, 12), iv(4), k, np, nc, nplane
    character(len=16) :: name
    write (name, '(a,i0,a)') 'stack ', nstep, ' steps'
    tp(1)%kind = tk3_planx
    tp(1)%axes = [1.0_wp, 1.0_wp, 0.05_wp]
    avrd = 0.0_wp
    call body3_mass_properties(tp, [0.0_wp, 0.0_wp, -0.05_wp], rho, avrd, c(:, 3), f(:, :, 3), m(3), ii(:, 3))
    call box_surface([half, half, half], vert, faces)
    tc(1, 1) = polyr_from_surface(vert, faces)
    tc(1, 2) = polyr_from_surface(matmul(rotation_of_vector([0.0_wp, 0.0_wp, 0.3_wp]), vert), faces)
    do k = 1, 2
      avrd = 0.0_wp
      call body3_mass_properties(tc(:, k), [0.03_wp * (k - 1), 0.02_wp * (k - 1), half * (2 * k - 1)], rho, avrd, &
                                 c(:, k), f(:, :, k), m(k), ii(:, k))
    end do
    call rbdy3_init(b, [1, 2, 3], c, f, m, ii, [half, half, 1.0_wp], [0.0_wp, 0.0_wp, -grav])
    call hold_body(b, 3)
    rl = 0.0_wp
    do k = 1, nstep
      call rbdy3_begin_step(b, (k - 1) * h, h, theta)
      call rbdy3_detection_config(b, h, theta, q, ftt)
      nc = 0
      call prplx_contacts(polyr_vertices(tc(1, 1), q(:, 1), ftt(:, :, 1)), q(:, 1), q(:, 3), ftt(:, :, 3), tp(1)%axes, &
                          1.0e-3_wp, np, iv, gap, pt, cf)
      call contacts_add(b, q, ftt, 1, 3, np, pt, cf, gap, nc)
      nplane = nc
      call prprx_contacts(polyr_vertices(tc(1, 2), q(:, 2), ftt(:, :, 2)), tc(1, 2)%faces, &
                          polyr_vertices(tc(1, 1), q(:, 1), ftt(:, :, 1)), tc(1, 1)%faces, 1.0e-3_wp, np, gap, pt, cf)
      call contacts_add(b, q, ftt, 2, 1, np, pt, cf, gap, nc)
      call gauss_seidel(b, nc, h, 0.5_wp, 1.0e-15_wp * m(1) * grav * h, rl)
      call rbdy3_end_step(b, h, theta)
    end do
    call check_true(trim(name)//': 4 points on the plane, 4 between the cubes', nplane == 4 .and. nc == 8)
    wplane = sum(rl(3, 1:nplane)) / h
    wcube = sum(rl(3, nplane + 1:nc)) / h
    call check_close(trim(name)//': the plane carries 2 m g', wplane, 2.0_wp * m(1) * grav, 1.0e-9_wp * m(1) * grav)
    call check_close(trim(name)//': the lower cube carries m g', wcube, m(2) * grav, 1.0e-9_wp * m(1) * grav)
    call check_close(trim(name)//': nothing moves', maxval(abs(b%v(:, 1:2))), 0.0_wp, 1.0e-9_wp)
  end subroutine stack

  !> Every dof of body ib held at 0 (velocity drives, as DRV_DOF.DAT's).
  subroutine hold_body(b, ib)
    type(rbdy3_t), intent(inout) :: b
    integer, intent(in) :: ib
    type(driven_dof_input_t) :: hold(6)
    integer :: k
    do k = 1, 6
      hold(k)%kind = 'vlocy'
      hold(k)%body = ib
      hold(k)%dof = k
    end do
    call rbdy3_add_drives(b, hold)
  end subroutine hold_body

  !> Add np contacts between bodies ib (candidate) and jb (antagonist) of b, at
  !> the points pt with frame cf and gaps gap, to the test's contact list
  !> (levers at the detection configuration q, ftt; Delassus blocks).
  subroutine contacts_add(b, q, ftt, ib, jb, np, pt, cf, gap, nc)
    type(rbdy3_t), intent(in) :: b
    real(wp), intent(in) :: q(:, :), ftt(:, :, :), pt(:, :), cf(3, 3), gap(:)
    integer, intent(in) :: ib, jb, np
    integer, intent(inout) :: nc
    integer :: j
    do j = 1, np
      nc = nc + 1
      cl_body(:, nc) = [ib, jb]
      cl_frame(:, :, nc) = cf
      cl_gap(nc) = gap(j)
      cl_lever(1:9, nc) = rigid3_levers(pt(:, j) - q(:, ib), cf, ftt(:, :, ib))
      cl_lever(10:18, nc) = rigid3_levers(pt(:, j) - q(:, jb), cf, ftt(:, :, jb))
      cl_w(:, nc) = 0.0_wp
      call rigid3_add_delassus(b%inv_mass(:, ib), cf, cl_lever(1:9, nc), cl_w(:, nc))
      call rigid3_add_delassus(b%inv_mass(:, jb), cf, cl_lever(10:18, nc), cl_w(:, nc))
    end do
  end subroutine contacts_add

  !> Gauss-Seidel over the nc contacts of the list with the exact local solver
  !> (IQS-like: Signorini on u_n + max(0, gap) / h), from the impulses rl
  !> (injected first), until no impulse moves by more than tol.
  subroutine gauss_seidel(b, nc, h, mu, tol, rl)
    type(rbdy3_t), intent(inout) :: b
    integer, intent(in) :: nc
    real(wp), intent(in) :: h, mu, tol
    real(wp), intent(inout) :: rl(:, :)
    real(wp) :: uf(3), rnew(3), dmax
    integer :: j, it, st, i
    do j = 1, nc
      call pair_impulse(b, j, rl(:, j))
    end do
    do it = 1, 100000
      dmax = 0.0_wp
      do j = 1, nc
        associate (c => cl_body(:, j))
          uf = rigid3_pair_velocity(b%v(:, c(1)), b%v(:, c(2)), cl_frame(:, :, j), cl_lever(:, j)) - &
               [(dot_product(cl_w(3 * i - 2:3 * i, j), rl(:, j)), i=1, 3)]
        end associate
        uf(3) = uf(3) + max(0.0_wp, cl_gap(j)) / h
        rnew = rl(:, j)
        call solve(uf, cl_w(:, j), mu, rnew, st)
        call pair_impulse(b, j, rnew - rl(:, j))
        dmax = max(dmax, maxval(abs(rnew - rl(:, j))))
        rl(:, j) = rnew
      end do
      if (dmax <= tol) exit
    end do
  end subroutine gauss_seidel

  !> The bodies of contact j of the list += M^-1 H^T dr (candidate), -= (antagonist).
  subroutine pair_impulse(b, j, dr)
    type(rbdy3_t), intent(inout) :: b
    integer, intent(in) :: j
    real(wp), intent(in) :: dr(3)
    associate (c => cl_body(:, j))
      call rigid3_pair_impulse(b%v(:, c(1)), b%inv_mass(:, c(1)), b%v(:, c(2)), b%inv_mass(:, c(2)), &
                               cl_frame(:, :, j), cl_lever(:, j), dr)
    end associate
  end subroutine pair_impulse

  !> One contact with the exact 3D local solver, which takes FCLib's order
  !> (n, t1, t2), the block column-major; the store's order is (t1, t2, n),
  !> the block by rows.
  subroutine solve(uf, w, mu, r, status)
    real(wp), intent(in) :: uf(3), w(9), mu
    real(wp), intent(inout) :: r(3)
    integer, intent(out) :: status
    real(wp) :: wf(9), qf(3), rf(3)
    call local3_to_fclib(w, uf, wf, qf)
    call local3_to_fclib(w, r, wf, rf)
    call coulomb_3d(qf, wf, inverse_block_3d(wf), mu, rf, status)
    r([3, 1, 2]) = rf
  end subroutine solve
end program test_rbdy3_contact
