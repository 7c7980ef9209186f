!> The finite-strain neo-Hookean law (fracas_bulk: bulk_neohooke, LMGC90's
!> 'mater neoh_', MatLib's NEOHOOKEAN: W = lambda/2 (ln J)^2 - mu ln J +
!> mu/2 (tr C - 3), plane strain) and its total Lagrangian element response
!> (fracas_elements: el_response), against closed forms:
!> 1. W(F) = 0, P = 0 and Cauchy stress 0 for rigid rotations of any angle
!>    (objectivity), to 1e-12 of mu;
!> 2. rotated stretch F = R U: P(RU) = R P(U), sigma(RU) = R sigma(U) R' (1e-12);
!> 3. equibiaxial stretch F = a I: P = (mu a + (lambda ln a^2 - mu) / a) I,
!>    sigma_zz = lambda ln a^2 / a^2, W = lambda/2 (ln a^2)^2 - mu ln a^2 + mu (a^2 - 1)
!>    (the formula at J = a^2, written out by hand);
!> 4. small strain: F = I + grad u with |grad u| = 1e-7 gives Hooke's plane-strain
!>    stress lambda tr(eps) + 2 mu eps to 1e-6 relative (second-order terms);
!> 5. P = dW/dF and dP/dF (the tangent) against central differences, at a
!>    large strain with shear (1e-7 relative);
!> 6. elements (T3, Q4, T6, Q8, Q4P0x; distorted): a rigid rotation of the
!>    nodes by 0.7 rad and by pi/2 leaves fi = 0 and no energy (1e-9 of
!>    mu x size), where the small-strain element gives forces of order mu;
!>    a homogeneous deformation gives energy W(F) x area and the Gauss-point
!>    Cauchy stress of the law; the element tangent against central differences
!>    of fi (1e-6); ke symmetric.
program test_neohooke
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_bulk, only: bulk_t, bulk_neohookean, bulk_elastic, bulk_neohooke, gp_size, plane_strain
  use fracas_elements, only: el_t3, el_q4, el_t6, el_q8, el_q4p0, el_nnodes, el_ngauss, el_response, el_area
  implicit none

  real(wp), parameter :: young = 1.0e7_wp, nu = 0.3_wp
  real(wp), parameter :: mu = young / (2.0_wp * (1.0_wp + nu))
  real(wp), parameter :: lam = young * nu / ((1.0_wp + nu) * (1.0_wp - 2.0_wp * nu))
  real(wp), parameter :: pi = 3.14159265358979323846_wp
  type(bulk_t) :: rubber

  rubber = bulk_t(law=bulk_neohookean, density=1000.0_wp, young=young, poisson=nu)
  call rotations()
  call rotated_stretch()
  call equibiaxial()
  call small_strain()
  call derivatives()
  call elements()
  call test_finish()

contains

  pure function rot(t) result(r)
    real(wp), intent(in) :: t
    real(wp) :: r(2, 2)
    r = reshape([cos(t), sin(t), -sin(t), cos(t)], [2, 2])
  end function rot

  !> (F_xx, F_xy, F_yx, F_yy) of a 2x2 matrix and back.
  pure function vec(m) result(v)
    real(wp), intent(in) :: m(2, 2)
    real(wp) :: v(4)
    v = [m(1, 1), m(1, 2), m(2, 1), m(2, 2)]
  end function vec

  pure function mat2(v) result(m)
    real(wp), intent(in) :: v(4)
    real(wp) :: m(2, 2)
    m = reshape([v(1), v(3), v(2), v(4)], [2, 2])
  end function mat2

  subroutine rotations()
    real(wp) :: p(4), a(4, 4), w, sig(4), green(4)
    real(wp), parameter :: angles(5) = [0.3_wp, 1.2_wp, 0.5_wp * pi, pi, -2.5_wp]
    integer :: k
    do k = 1, size(angles)
      call bulk_neohooke(rubber, vec(rot(angles(k))), p, a, w, sig, green)
      call check_close('rotation: max |P| / mu', maxval(abs(p)) / mu, 0.0_wp, 1.0e-12_wp)
      call check_close('rotation: max |sigma| / mu', maxval(abs(sig)) / mu, 0.0_wp, 1.0e-12_wp)
      call check_close('rotation: W / mu', w / mu, 0.0_wp, 1.0e-12_wp)
      call check_close('rotation: max |E|', maxval(abs(green)), 0.0_wp, 1.0e-14_wp)
    end do
  end subroutine rotations

  subroutine rotated_stretch()
    real(wp) :: u(2, 2), r(2, 2), p0(4), p1(4), a(4, 4), w0, w1, s0(4), s1(4), sm0(2, 2), sm1(2, 2)
    u = reshape([1.4_wp, 0.15_wp, 0.15_wp, 0.8_wp], [2, 2])
    r = rot(0.9_wp)
    call bulk_neohooke(rubber, vec(u), p0, a, w0, s0)
    call bulk_neohooke(rubber, vec(matmul(r, u)), p1, a, w1, s1)
    call check_close('R U: max |P(RU) - R P(U)| / mu', maxval(abs(mat2(p1) - matmul(r, mat2(p0)))) / mu, &
                     0.0_wp, 1.0e-12_wp)
    sm0 = reshape([s0(1), s0(3), s0(3), s0(2)], [2, 2])
    sm1 = reshape([s1(1), s1(3), s1(3), s1(2)], [2, 2])
    call check_close('R U: max |sigma(RU) - R sigma R''| / mu', &
                     maxval(abs(sm1 - matmul(r, matmul(sm0, transpose(r))))) / mu, 0.0_wp, 1.0e-12_wp)
    call check_close('R U: sigma_zz unchanged / mu', (s1(4) - s0(4)) / mu, 0.0_wp, 1.0e-12_wp)
    call check_close('R U: W unchanged / mu', (w1 - w0) / mu, 0.0_wp, 1.0e-12_wp)
  end subroutine rotated_stretch

  subroutine equibiaxial()
    real(wp) :: p(4), a(4, 4), w, sig(4), st, lnj
    real(wp), parameter :: stretches(3) = [0.7_wp, 1.0_wp, 1.6_wp]
    integer :: k
    do k = 1, size(stretches)
      st = stretches(k)
      lnj = log(st**2)
      call bulk_neohooke(rubber, [st, 0.0_wp, 0.0_wp, st], p, a, w, sig)
      call check_close('a I: P_xx / mu', p(1) / mu, (mu * st + (lam * lnj - mu) / st) / mu, 1.0e-12_wp)
      call check_close('a I: P_yy / mu', p(4) / mu, (mu * st + (lam * lnj - mu) / st) / mu, 1.0e-12_wp)
      call check_close('a I: P_xy, P_yx / mu', max(abs(p(2)), abs(p(3))) / mu, 0.0_wp, 1.0e-14_wp)
      call check_close('a I: sigma_zz / mu', sig(4) / mu, lam * lnj / st**2 / mu, 1.0e-12_wp)
      call check_close('a I: W / mu', w / mu, (0.5_wp * lam * lnj**2 - mu * lnj + mu * (st**2 - 1.0_wp)) / mu, &
                       1.0e-12_wp)
    end do
  end subroutine equibiaxial

  subroutine small_strain()
    real(wp) :: p(4), a(4, 4), w, sig(4), hg(2, 2), eps(2, 2), ref(4), tr
    hg = 1.0e-7_wp * reshape([1.0_wp, -0.4_wp, 0.7_wp, -0.6_wp], [2, 2])
    eps = 0.5_wp * (hg + transpose(hg))
    tr = eps(1, 1) + eps(2, 2)
    ref = [lam * tr + 2.0_wp * mu * eps(1, 1), lam * tr + 2.0_wp * mu * eps(2, 2), 2.0_wp * mu * eps(1, 2), &
           lam * tr]
    call bulk_neohooke(rubber, vec(reshape([1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 2]) + hg), p, a, w, sig)
    call check_close('small strain: max |sigma - Hooke| / max |Hooke|', maxval(abs(sig - ref)) / maxval(abs(ref)), &
                     0.0_wp, 1.0e-6_wp)
  end subroutine small_strain

  subroutine derivatives()
    real(wp) :: f(4), p(4), a(4, 4), w, pp(4), pm(4), ap(4, 4), wp_, wm, h, err_p, err_a
    integer :: k
    f = [1.5_wp, 0.3_wp, -0.2_wp, 0.7_wp]
    call bulk_neohooke(rubber, f, p, a, w)
    err_p = 0.0_wp
    err_a = 0.0_wp
    do k = 1, 4
      h = 1.0e-6_wp
      call bulk_neohooke(rubber, f + h * unit(k), pp, ap, wp_)
      call bulk_neohooke(rubber, f - h * unit(k), pm, ap, wm)
      err_p = max(err_p, abs((wp_ - wm) / (2.0_wp * h) - p(k)) / maxval(abs(p)))
      err_a = max(err_a, maxval(abs((pp - pm) / (2.0_wp * h) - a(:, k))) / maxval(abs(a)))
    end do
    call check_close('P = dW/dF (central differences)', err_p, 0.0_wp, 1.0e-7_wp)
    call check_close('A = dP/dF (central differences)', err_a, 0.0_wp, 1.0e-7_wp)
    call check_close('A symmetric', maxval(abs(a - transpose(a))) / maxval(abs(a)), 0.0_wp, 1.0e-15_wp)
  end subroutine derivatives

  pure function unit(k) result(e)
    integer, intent(in) :: k
    real(wp) :: e(4)
    e = 0.0_wp
    e(k) = 1.0_wp
  end function unit

  !> Reference nodes of a distorted element of each kind (about 1 m across).
  function nodes_of(kind) result(x)
    integer, intent(in) :: kind
    real(wp), allocatable :: x(:, :)
    select case (kind)
    case (el_t3)
      x = reshape([0.1_wp, 0.0_wp, 1.2_wp, 0.2_wp, 0.3_wp, 0.9_wp], [2, 3])
    case (el_t6)
      x = reshape([0.1_wp, 0.0_wp, 1.2_wp, 0.2_wp, 0.3_wp, 0.9_wp, 0.65_wp, 0.1_wp, 0.75_wp, 0.55_wp, &
                   0.2_wp, 0.45_wp], [2, 6])
    case (el_q8)
      x = reshape([0.0_wp, 0.0_wp, 1.1_wp, 0.1_wp, 1.0_wp, 0.9_wp, -0.1_wp, 1.0_wp, 0.55_wp, 0.05_wp, &
                   1.05_wp, 0.5_wp, 0.45_wp, 0.95_wp, -0.05_wp, 0.5_wp], [2, 8])
    case default
      x = reshape([0.0_wp, 0.0_wp, 1.1_wp, 0.1_wp, 1.0_wp, 0.9_wp, -0.1_wp, 1.0_wp], [2, 4])
    end select
  end function nodes_of

  subroutine elements()
    integer, parameter :: kinds(5) = [el_t3, el_q4, el_t6, el_q8, el_q4p0]
    character(len=5), parameter :: names(5) = ['T3   ', 'Q4   ', 'T6   ', 'Q8   ', 'Q4P0x']
    real(wp), allocatable :: x(:, :), u(:), fi(:), ke(:, :), gp0(:, :), gp1(:, :), fp(:), fm(:), kd(:, :), xr(:, :)
    real(wp) :: ee, wpl, p(4), a(4, 4), w, sig(4), fmat(2, 2), c(2), err, h, kdum(1, 1)
    real(wp), parameter :: angles(2) = [0.7_wp, 0.5_wp * pi]
    type(bulk_t) :: linear
    integer :: k, nn, ng, j, i
    linear = bulk_t(law=bulk_elastic, density=1000.0_wp, young=young, poisson=nu)
    do k = 1, size(kinds)
      x = nodes_of(kinds(k))
      nn = el_nnodes(kinds(k))
      ng = el_ngauss(kinds(k))
      allocate (u(2 * nn), fi(2 * nn), ke(2 * nn, 2 * nn), gp0(gp_size, ng), gp1(gp_size, ng), fp(2 * nn), &
                fm(2 * nn), kd(2 * nn, 2 * nn))
      gp0 = 0.0_wp
      c = [0.3_wp, -0.2_wp]
      do j = 1, size(angles)
        ! rigid rotation about c: u = (R - I)(X - c) + a translation
        xr = matmul(rot(angles(j)), x - spread(c, 2, nn)) + spread(c + [0.5_wp, 2.0_wp], 2, nn)
        u = reshape(xr - x, [2 * nn])
        call el_response(kinds(k), x, u, rubber, plane_strain, gp0, gp1, fi, ke, .true., ee, wpl)
        call check_close(trim(names(k))//' rigid rotation: max |fi| / mu', maxval(abs(fi)) / mu, 0.0_wp, 1.0e-9_wp)
        call check_close(trim(names(k))//' rigid rotation: energy / mu', ee / mu, 0.0_wp, 1.0e-9_wp)
        call check_close(trim(names(k))//' rigid rotation: max |sigma| / mu', maxval(abs(gp1(1:4, :))) / mu, &
                         0.0_wp, 1.0e-9_wp)
        if (j == 2) then
          call el_response(kinds(k), x, u, linear, plane_strain, gp0, gp1, fi, ke, .true., ee, wpl)
          call check_true(trim(names(k))//' small strain under the same rotation: max |fi| > 0.1 mu', &
                          maxval(abs(fi)) > 0.1_wp * mu)
        end if
      end do
      ! homogeneous deformation: energy W(F) area, Gauss-point Cauchy stress of the law
      fmat = reshape([1.3_wp, 0.1_wp, 0.25_wp, 0.85_wp], [2, 2])
      u = reshape(matmul(fmat, x) - x, [2 * nn])
      call el_response(kinds(k), x, u, rubber, plane_strain, gp0, gp1, fi, ke, .true., ee, wpl)
      call bulk_neohooke(rubber, vec(fmat), p, a, w, sig)
      call check_close(trim(names(k))//' homogeneous F: energy / (W area)', ee / (w * el_area(kinds(k), x)), &
                       1.0_wp, 1.0e-12_wp)
      call check_close(trim(names(k))//' homogeneous F: max |sigma_gp - sigma(F)| / mu', &
                       maxval(abs(gp1(1:4, :) - spread(sig, 2, ng))) / mu, 0.0_wp, 1.0e-12_wp)
      ! tangent: central differences of fi at a general state
      u = u + 0.05_wp * sin([(real(i, wp), i=1, 2 * nn)])
      call el_response(kinds(k), x, u, rubber, plane_strain, gp0, gp1, fi, ke, .true., ee, wpl)
      h = 1.0e-6_wp
      do i = 1, 2 * nn
        u(i) = u(i) + h
        call el_response(kinds(k), x, u, rubber, plane_strain, gp0, gp1, fp, kdum, .false., ee, wpl)
        u(i) = u(i) - 2.0_wp * h
        call el_response(kinds(k), x, u, rubber, plane_strain, gp0, gp1, fm, kdum, .false., ee, wpl)
        u(i) = u(i) + h
        kd(:, i) = (fp - fm) / (2.0_wp * h)
      end do
      err = maxval(abs(kd - ke)) / maxval(abs(ke))
      call check_close(trim(names(k))//' tangent vs central differences of fi', err, 0.0_wp, 1.0e-6_wp)
      call check_close(trim(names(k))//' ke symmetric', maxval(abs(ke - transpose(ke))) / maxval(abs(ke)), 0.0_wp, &
                       1.0e-14_wp)
      deallocate (u, fi, ke, gp0, gp1, fp, fm, kd)
    end do
  end subroutine elements
end program test_neohooke
