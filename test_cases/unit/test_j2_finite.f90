!> LMGC90's internal finite-strain J2 element (fracas_elements: el_response with a
!> bulk_j2_finite law, LMGC90's Q4P0x with kine_ large; doc/mesh_mechanics.md §7),
!> on one distorted Q4 under homogeneous deformations, against closed forms:
!> 1. a rigid rotation (0.9 rad, about an off-centre point) of the virgin element:
!>    fi = 0, stress 0, p = 0, Cp^-1 = I (1e-12 of mu);
!> 2. an elastic homogeneous F (stretch and shear below yield), plane strain: Cauchy
!>    stress mu dev(J^(-2/3) F F') / J + K/2 (J - 1/J) I at every Gauss point (1e-12);
!> 3. axisymmetric, elastic: u_r = e_r r, u_z = e_z z, F = diag(1 + e_r, 1 + e_z,
!>    1 + e_r): the same closed form with the hoop stretch, hoop stress in zz (1e-12);
!> 4. an isochoric plane-strain stretch F = diag(a, 1/a) past yield in one step from
!>    the virgin state (a radial path): after the return the Kirchhoff von Mises
!>    stress equals yield0 + H p (1e-12), with p = sqrt(2/3) (q* - yield0) /
!>    (sqrt(6) mu^ + sqrt(2/3) H), q* = sqrt(3/2) mu |dev b^|, mu^ = mu tr(b^)/3;
!>    det Cp^-1 = det(beta dev b^ + tr(b^)/3 I), beta = 1 - 2 mu^ dgamma / |s*|: LMGC90
!>    keeps the trial trace of b^ (not Simo-Miehe's det b^ = 1 correction, which its
!>    source leaves commented out), so det Cp^-1 = 1.0095 here, not 1 (1e-12);
!> 5. the same stretch followed by a rotation R: sigma(RF) = R sigma(F) R', p and
!>    Cp^-1 unchanged (objectivity of the plastic step, 1e-12).
program test_j2_finite
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, test_finish
  use fracas_bulk, only: bulk_t, bulk_j2_finite, gp_size, gp_p, gp_plastic_strain, plane_strain, plane_axisym
  use fracas_elements, only: el_q4p0, el_response
  implicit none

  real(wp), parameter :: young = 1.17e11_wp, nu = 0.35_wp, sy0 = 4.0e8_wp, hard = 1.0e9_wp
  real(wp), parameter :: mu = young / (2.0_wp * (1.0_wp + nu)), kb = young / (3.0_wp * (1.0_wp - 2.0_wp * nu))
  type(bulk_t) :: copper
  real(wp) :: x(2, 4), xa(2, 4), gp0(gp_size, 4), gp1(gp_size, 4), fi(8), ke(8, 8), ee, wpl
  real(wp) :: f(2, 2), r(2, 2), sig(4), sr(2, 2), s1(2, 2), a, q, tf, pex, b(3), cp(4), p1(4), p_ref, szz_ref
  integer :: g

  copper = bulk_t(law=bulk_j2_finite, density=8930.0_wp, young=young, poisson=nu, yield0=sy0, hardening=hard)
  x = reshape([0.0_wp, 0.0_wp, 1.1e-3_wp, 0.1e-3_wp, 1.0e-3_wp, 0.9e-3_wp, -0.1e-3_wp, 1.0e-3_wp], [2, 4])
  gp0 = 0.0_wp

  ! 1. rigid rotation
  r = rot(0.9_wp)
  call respond(matmul(r, x - 3.0e-4_wp) + 3.0e-4_wp - x, plane_strain)
  call check_close('rigid rotation: max |fi| / (mu area)', maxval(abs(fi)) / (mu * 1.0e-6_wp), 0.0_wp, 1.0e-12_wp)
  call check_close('rigid rotation: max |sigma| / mu', maxval(abs(gp1(1:4, :))) / mu, 0.0_wp, 1.0e-12_wp)
  call check_close('rigid rotation: max p, |Cp^-1 - I|', maxval(abs(gp1(gp_plastic_strain:gp_p, :))), 0.0_wp, &
                   1.0e-12_wp)

  ! 2. elastic homogeneous F, plane strain
  f = reshape([1.001_wp, 0.0004_wp, 0.0007_wp, 0.9985_wp], [2, 2])
  call respond(matmul(f, x) - x, plane_strain)
  sig = elastic_cauchy(f, 1.0_wp)
  call check_close('elastic F: max |sigma - closed form| / |sigma|', &
                   maxval(abs(gp1(1:4, :) - spread(sig, 2, 4))) / maxval(abs(sig)), 0.0_wp, 1.0e-12_wp)
  call check_close('elastic F: p', maxval(gp1(gp_p, :)), 0.0_wp, 0.0_wp)

  ! 3. axisymmetric elastic expansion (the element off the axis: r from 1 mm)
  xa = x + spread([1.0e-3_wp, 0.0_wp], 2, 4)
  f = reshape([1.0008_wp, 0.0_wp, 0.0_wp, 0.9991_wp], [2, 2])
  call respond(matmul(f, xa) - xa, plane_axisym, xa)
  sig = elastic_cauchy(f, 1.0008_wp)
  call check_close('axisym e_r, e_z: max |sigma - closed form| / |sigma|', &
                   maxval(abs(gp1(1:4, :) - spread(sig, 2, 4))) / maxval(abs(sig)), 0.0_wp, 1.0e-12_wp)

  ! 4. isochoric stretch past yield, one step
  a = 1.05_wp
  f = reshape([a, 0.0_wp, 0.0_wp, 1.0_wp / a], [2, 2])
  call respond(matmul(f, x) - x, plane_strain)
  b = [a**2, a**(-2), 1.0_wp]
  tf = sum(b) / 3.0_wp
  q = sqrt(1.5_wp) * mu * norm2(b - tf)
  pex = sqrt(2.0_wp / 3.0_wp) * (q - sy0) / (sqrt(6.0_wp) * mu * tf + sqrt(2.0_wp / 3.0_wp) * hard)
  call check_close('isochoric stretch: p / closed form', gp1(gp_p, 1) / pex, 1.0_wp, 1.0e-12_wp)
  do g = 1, 4
    sig = gp1(1:4, g) - (gp1(1, g) + gp1(2, g) + gp1(4, g)) / 3.0_wp * [1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp]
    call check_close('isochoric stretch: Kirchhoff von Mises / (yield0 + H p)', &
                     sqrt(1.5_wp * (sig(1)**2 + sig(2)**2 + sig(4)**2 + 2.0_wp * sig(3)**2)) * jac_of(f) / &
                     (sy0 + hard * gp1(gp_p, g)), 1.0_wp, 1.0e-12_wp)
    cp = gp1(gp_plastic_strain:gp_plastic_strain + 3, g) + [1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp]
    call check_close('isochoric stretch: det Cp^-1 / det(beta dev b^ + tf I)', (cp(1) * cp(2) - cp(3)**2) * cp(4) / &
                     product((1.0_wp - 2.0_wp * mu * tf * sqrt(1.5_wp) * pex / (mu * norm2(b - tf))) * (b - tf) + tf), &
                     1.0_wp, 1.0e-12_wp)
  end do
  s1 = reshape([gp1(1, 1), gp1(3, 1), gp1(3, 1), gp1(2, 1)], [2, 2])
  p1 = gp1(gp_plastic_strain:gp_p - 1, 1)
  p_ref = gp1(gp_p, 1)
  szz_ref = gp1(4, 1)

  ! 5. the same stretch, then a rotation
  r = rot(-1.3_wp)
  call respond(matmul(matmul(r, f), x) - x, plane_strain)
  sr = reshape([gp1(1, 1), gp1(3, 1), gp1(3, 1), gp1(2, 1)], [2, 2])
  call check_close('R F: max |sigma(RF) - R sigma R''| / |sigma|', &
                   maxval(abs(sr - matmul(r, matmul(s1, transpose(r))))) / maxval(abs(s1)), 0.0_wp, 1.0e-12_wp)
  call check_close('R F: sigma_zz, p unchanged', max(abs(gp1(4, 1) - szz_ref) / abs(szz_ref), &
                   abs(gp1(gp_p, 1) - p_ref) / p_ref), 0.0_wp, 1.0e-12_wp)
  call check_close('R F: Cp^-1 unchanged', maxval(abs(gp1(gp_plastic_strain:gp_p - 1, 1) - p1)), 0.0_wp, 1.0e-12_wp)
  call test_finish()

contains

  pure real(wp) function jac_of(m)
    real(wp), intent(in) :: m(2, 2)
    jac_of = m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)
  end function jac_of

  pure function rot(t) result(m)
    real(wp), intent(in) :: t
    real(wp) :: m(2, 2)
    m = reshape([cos(t), sin(t), -sin(t), cos(t)], [2, 2])
  end function rot

  subroutine respond(du, plane, xref)
    real(wp), intent(in) :: du(2, 4)
    integer, intent(in) :: plane
    real(wp), intent(in), optional :: xref(2, 4)
    if (present(xref)) then
      call el_response(el_q4p0, xref, reshape(du, [8]), copper, plane, gp0, gp1, fi, ke, .true., ee, wpl)
    else
      call el_response(el_q4p0, x, reshape(du, [8]), copper, plane, gp0, gp1, fi, ke, .true., ee, wpl)
    end if
  end subroutine respond

  !> Cauchy stress (xx, yy, xy, zz) of the elastic law at a homogeneous F (F_zz = f33).
  function elastic_cauchy(f, f33) result(s)
    real(wp), intent(in) :: f(2, 2), f33
    real(wp) :: s(4), bb(2, 2), j, tr, dev(4)
    j = (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)) * f33
    bb = matmul(f, transpose(f)) * j**(-2.0_wp / 3.0_wp)
    tr = (bb(1, 1) + bb(2, 2) + f33**2 * j**(-2.0_wp / 3.0_wp)) / 3.0_wp
    dev = [bb(1, 1) - tr, bb(2, 2) - tr, bb(1, 2), f33**2 * j**(-2.0_wp / 3.0_wp) - tr]
    s = mu * dev / j + 0.5_wp * kb * (j - 1.0_wp / j) * [1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp]
  end function elastic_cauchy
end program test_j2_finite
