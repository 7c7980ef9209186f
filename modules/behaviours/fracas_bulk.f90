!> Bulk laws of meshed bodies at one Gauss point, small strain: isotropic
!> elasticity (Hooke) and J2 (von Mises) plasticity with linear isotropic
!> hardening sigma_y = yield0 + hardening p (LMGC90's ELAS_PLAS 'isoh linear':
!> SIG0 and K___), integrated by radial return (backward Euler) with its
!> consistent tangent. 2D hypotheses: plane strain (eps_zz imposed, sigma_zz
!> computed) and plane stress (sigma_zz = 0, eps_zz computed by a local Newton
!> on eps_zz around the 3D return; the tangent is the 3D consistent tangent
!> condensed on sigma_zz = 0). See doc/mesh_mechanics.md.
!> Finite strain: the compressible neo-Hookean law of LMGC90's 'mater neoh_'
!> models (MatLib's NEOHOOKEAN), plane strain, stateless:
!>   W(F) = lambda/2 (ln J)^2 - mu ln J + mu/2 (tr C - 3),  C = F'F, J = det F,
!> lambda, mu the Lame constants of (young, poisson); bulk_neohooke gives the
!> first Piola-Kirchhoff stress P = mu F + (lambda ln J - mu) F^-T and dP/dF.
!>
!> API
!>   type(bulk_t): law (bulk_elastic | bulk_j2 | bulk_neohookean), density,
!>                 young, poisson, yield0, hardening
!>   bulk_from_material(m [, model])               -> bulk_t from a BULK_BEHAV.DAT record
!>                                                    and its model's options (finite strain:
!>                                                    neo-Hookean, or J2 of LMGC90's Q4P0x)
!>   bulk_update(mat, plane, eps, state_begin, state_end, dtan)
!>   bulk_neohooke(mat, f, p, a, w [, cauchy, green])  finite strain, plane strain
!>   bulk_yield_stress(mat, p), bulk_plastic_work(mat, p_begin, p_end)
!>   plane_strain, plane_stress; gp_size = 13 and the gp_* index constants.
!>
!> Vectors use LMGC90's GPV.OUT order: stress (xx, yy, xy, zz), strain
!> (xx, yy, gamma_xy = 2 eps_xy, zz). One Gauss-point state holds gp_size = 13
!> reals: stress(4), total strain(4), plastic strain(4, gamma for xy), p.
module fracas_bulk
  use fracas_kinds, only: wp
  use fracas_deck, only: material_input_t, model_input_t, model_finite_strain
  use fracas_errors, only: input_error
  implicit none
  private
  public :: bulk_t, bulk_elastic, bulk_j2, bulk_neohookean, bulk_j2_finite, bulk_neohooke, plane_strain, plane_stress, plane_axisym, plane_names, &
            bulk_from_material, &
            bulk_update, bulk_yield_stress, bulk_plastic_work, bulk_elastic_tangent, &
            gp_size, gp_stress, gp_strain, gp_plastic_strain, gp_p, &
            gp_sxx, gp_syy, gp_sxy, gp_szz, gp_exx, gp_eyy, gp_gxy, gp_ezz, &
            gp_pxx, gp_pyy, gp_pgxy, gp_pzz

  integer, parameter :: bulk_elastic = 1, bulk_j2 = 2, bulk_neohookean = 3, bulk_j2_finite = 4
  !> plane_axisym: x is the radius r, y the axis; quantities per unit angle x 2 pi
  !> (LMGC90's axisymmetry), the hoop component in the zz slot.
  integer, parameter :: plane_strain = 1, plane_stress = 2, plane_axisym = 3
  !> Their run-control words (COMMAND.DAT 'plane').
  character(len=6), parameter :: plane_names(3) = ['strain', 'stress', 'axisym']

  !> Gauss-point state: first index of each block and every component.
  integer, parameter :: gp_size = 13
  integer, parameter :: gp_stress = 1, gp_strain = 5, gp_plastic_strain = 9, gp_p = 13
  integer, parameter :: gp_sxx = 1, gp_syy = 2, gp_sxy = 3, gp_szz = 4
  integer, parameter :: gp_exx = 5, gp_eyy = 6, gp_gxy = 7, gp_ezz = 8
  integer, parameter :: gp_pxx = 9, gp_pyy = 10, gp_pgxy = 11, gp_pzz = 12

  !> One bulk material. Units: Pa, kg/m^3.
  type :: bulk_t
    integer :: law = bulk_elastic
    real(wp) :: density = 0.0_wp
    real(wp) :: young = 0.0_wp, poisson = 0.0_wp
    real(wp) :: yield0 = 0.0_wp       !< initial yield stress (J2)
    real(wp) :: hardening = 0.0_wp    !< linear isotropic hardening modulus H (J2)
  end type bulk_t

  !> Voigt vector of the identity in the (xx, yy, xy, zz) order.
  real(wp), parameter :: unit_m(4) = [1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp]
  !> Symmetric identity in Voigt form with engineering shear strain.
  real(wp), parameter :: sym_diag(4) = [1.0_wp, 1.0_wp, 0.5_wp, 1.0_wp]

contains

  !> The bulk law of a BULK_BEHAV.DAT record: ELAS -> elastic, ELAS_PLAS -> J2;
  !> under a finite-strain model (model_finite_strain) ELAS -> neo-Hookean and
  !> ELAS_PLAS -> finite-strain J2.
  function bulk_from_material(m, model) result(mat)
    type(material_input_t), intent(in) :: m
    type(model_input_t), intent(in), optional :: model
    type(bulk_t) :: mat
    logical :: finite
    finite = .false.
    if (present(model)) finite = model_finite_strain(model)
    select case (trim(m%law))
    case ('ELAS')
      mat%law = merge(bulk_neohookean, bulk_elastic, finite)
    case ('ELAS_PLAS')
      mat%law = merge(bulk_j2_finite, bulk_j2, finite)
      if (m%yield0 <= 0.0_wp) call input_error(m%src%file, m%src%line, 0, &
                                               'ELAS_PLAS '//trim(m%nickname)//': SIG0 must be > 0')
      if (m%hardening < 0.0_wp) call input_error(m%src%file, m%src%line, 0, &
                                                 'ELAS_PLAS '//trim(m%nickname)//': K___ must be >= 0')
    case default
      call input_error(m%src%file, m%src%line, 0, 'material '//trim(m%nickname)//' ('//trim(m%law)// &
                       ') is not a bulk law of meshed bodies (ELAS or ELAS_PLAS)')
    end select
    if (m%young <= 0.0_wp .or. m%poisson <= -1.0_wp .or. m%poisson >= 0.5_wp) &
      call input_error(m%src%file, m%src%line, 0, 'material '//trim(m%nickname)// &
                       ': needs EYng > 0 and -1 < Epss < 0.5')
    mat%density = m%density
    mat%young = m%young
    mat%poisson = m%poisson
    mat%yield0 = m%yield0
    mat%hardening = m%hardening
  end function bulk_from_material

  !> sigma_y(p) = yield0 + hardening p.
  pure real(wp) function bulk_yield_stress(mat, p)
    type(bulk_t), intent(in) :: mat
    real(wp), intent(in) :: p
    bulk_yield_stress = mat%yield0 + mat%hardening * p
  end function bulk_yield_stress

  !> Plastic work density from p_begin to p_end: the integral of sigma_y(p) dp,
  !> = sigma : delta eps_p along a flow at yield (exact for linear hardening,
  !> telescopes over steps: the sum from 0 is yield0 p + hardening p^2 / 2).
  pure real(wp) function bulk_plastic_work(mat, p_begin, p_end)
    type(bulk_t), intent(in) :: mat
    real(wp), intent(in) :: p_begin, p_end
    bulk_plastic_work = (p_end - p_begin) * (mat%yield0 + 0.5_wp * mat%hardening * (p_begin + p_end))
  end function bulk_plastic_work

  !> Elastic tangent on (xx, yy, gamma_xy, zz): plane strain the 3D Hooke
  !> matrix, plane stress the matrix condensed on sigma_zz = 0 (zz row and
  !> column zero).
  pure subroutine bulk_elastic_tangent(mat, plane, dtan)
    type(bulk_t), intent(in) :: mat
    integer, intent(in) :: plane
    real(wp), intent(out) :: dtan(4, 4)
    real(wp) :: kb, g
    integer :: i
    call moduli(mat, kb, g)
    do i = 1, 4
      dtan(:, i) = kb * unit_m * unit_m(i) - (2.0_wp * g / 3.0_wp) * unit_m * unit_m(i)
      dtan(i, i) = dtan(i, i) + 2.0_wp * g * sym_diag(i)
    end do
    if (plane == plane_stress) call condense_zz(dtan)
  end subroutine bulk_elastic_tangent

  !> One step of the bulk law at one Gauss point.
  !> eps(4): total strain (xx, yy, gamma_xy, zz); plane strain uses eps(4) as
  !> the imposed eps_zz (0 for standard elements, non-zero for mean-dilatation
  !> ones); plane stress ignores eps(4) and computes eps_zz.
  !> state_begin/state_end(gp_size): Gauss-point states at the start/end of the step.
  !> dtan(4,4): consistent tangent d sigma(xx,yy,xy,zz) / d eps(xx,yy,gamma,zz);
  !> plane stress: the in-plane 3x3 block condensed on sigma_zz = 0, zz row and
  !> column zero.
  pure subroutine bulk_update(mat, plane, eps, state_begin, state_end, dtan)
    type(bulk_t), intent(in) :: mat
    integer, intent(in) :: plane
    real(wp), intent(in) :: eps(4)
    real(wp), intent(in) :: state_begin(:)
    real(wp), intent(out) :: state_end(:)
    real(wp), intent(out) :: dtan(4, 4)
    real(wp) :: e(4), sig(4), epsp(4), p
    real(wp) :: ezz, f, df, lo, hi, step, scale
    logical :: have_lo, have_hi
    integer :: it
    integer, parameter :: max_newton = 60

    e = eps
    if (plane == plane_stress) then
      ! Start from the elastic plane-stress eps_zz around the old plastic strain.
      e(4) = state_begin(gp_pzz) - mat%poisson / (1.0_wp - mat%poisson) * &
             (eps(1) - state_begin(gp_pxx) + eps(2) - state_begin(gp_pyy))
      if (mat%law == bulk_j2) then
        ! sigma_zz(eps_zz) is increasing (d sigma_zz / d eps_zz = dtan(4,4) > 0):
        ! Newton, kept inside the bracket of the root once one exists.
        scale = max(mat%yield0, mat%young * maxval(abs(eps(1:3))), tiny(1.0_wp))
        have_lo = .false.
        have_hi = .false.
        lo = 0.0_wp
        hi = 0.0_wp
        do it = 1, max_newton
          call return_3d(mat, e, state_begin, sig, epsp, p, dtan)
          f = sig(4)
          if (abs(f) <= 1.0e-14_wp * scale) exit
          if (f < 0.0_wp) then
            lo = e(4)
            have_lo = .true.
          else
            hi = e(4)
            have_hi = .true.
          end if
          df = dtan(4, 4)
          ezz = e(4) - f / df
          if (have_lo .and. have_hi .and. (ezz <= lo .or. ezz >= hi)) ezz = 0.5_wp * (lo + hi)
          step = abs(ezz - e(4))
          e(4) = ezz
          ! A step at round-off, or the last iteration: the state must match e.
          if (step <= 4.0_wp * epsilon(1.0_wp) * max(abs(e(4)), maxval(abs(eps(1:3)))) &
              .or. it == max_newton) then
            call return_3d(mat, e, state_begin, sig, epsp, p, dtan)
            exit
          end if
        end do
      else
        call return_3d(mat, e, state_begin, sig, epsp, p, dtan)
      end if
      sig(4) = 0.0_wp
      call condense_zz(dtan)
    else
      call return_3d(mat, e, state_begin, sig, epsp, p, dtan)
    end if
    state_end(gp_stress:gp_stress + 3) = sig
    state_end(gp_strain:gp_strain + 3) = e
    state_end(gp_plastic_strain:gp_plastic_strain + 3) = epsp
    state_end(gp_p) = p
  end subroutine bulk_update

  !> 3D radial return for the strain e(4) = (xx, yy, gamma_xy, zz) from the
  !> state at the start of the step: stress, plastic strain, p and the
  !> consistent tangent (xx, yy, gamma, zz).
  pure subroutine return_3d(mat, e, state_begin, sig, epsp, p, dtan)
    type(bulk_t), intent(in) :: mat
    real(wp), intent(in) :: e(4), state_begin(:)
    real(wp), intent(out) :: sig(4), epsp(4), p
    real(wp), intent(out) :: dtan(4, 4)
    real(wp) :: kb, g, ee(4), tr, s_trial(4), norm_s, q_trial, yield, dp, beta, gamma_n
    real(wp) :: n_unit(4)
    integer :: i

    call moduli(mat, kb, g)
    epsp = state_begin(gp_plastic_strain:gp_plastic_strain + 3)
    p = state_begin(gp_p)
    ee = e - epsp
    tr = ee(1) + ee(2) + ee(4)
    ! deviatoric trial stress as a tensor (xy = tensor component)
    s_trial = 2.0_wp * g * (sym_diag * ee - unit_m * tr / 3.0_wp)
    norm_s = sqrt(s_trial(1)**2 + s_trial(2)**2 + s_trial(4)**2 + 2.0_wp * s_trial(3)**2)
    q_trial = sqrt(1.5_wp) * norm_s
    call bulk_elastic_tangent(mat, plane_strain, dtan)
    if (mat%law /= bulk_j2) then
      sig = kb * tr * unit_m + s_trial
      return
    end if
    yield = bulk_yield_stress(mat, p)
    if (q_trial <= yield) then
      sig = kb * tr * unit_m + s_trial
      return
    end if
    ! Plastic: one linear equation for dp with linear hardening.
    dp = (q_trial - yield) / (3.0_wp * g + mat%hardening)
    beta = 1.0_wp - 3.0_wp * g * dp / q_trial
    n_unit = s_trial / norm_s
    sig = kb * tr * unit_m + beta * s_trial
    ! delta eps_p = dp * 3/2 s / q (tensor); engineering gamma doubles xy.
    epsp = epsp + dp * sqrt(1.5_wp) * n_unit * [1.0_wp, 1.0_wp, 2.0_wp, 1.0_wp]
    p = p + dp
    ! D = K m m' + 2 G beta I_dev + 6 G^2 (dp / q_trial - 1 / (3G + H)) N N'
    gamma_n = 6.0_wp * g**2 * (dp / q_trial - 1.0_wp / (3.0_wp * g + mat%hardening))
    do i = 1, 4
      dtan(:, i) = kb * unit_m * unit_m(i) - beta * (2.0_wp * g / 3.0_wp) * unit_m * unit_m(i) &
                   + gamma_n * n_unit * n_unit(i)
      dtan(i, i) = dtan(i, i) + 2.0_wp * g * beta * sym_diag(i)
    end do
  end subroutine return_3d

  !> Neo-Hookean law (LMGC90's neoh_, MatLib's NEOHOOKEAN), plane strain
  !> (F_zz = 1): f(4) = (F_xx, F_xy, F_yx, F_yy), F_iJ = d x_i / d X_J, the
  !> order of LMGC90's finite-strain vectors. Returns the first Piola-Kirchhoff
  !> stress p(4) (same order), the tangent a(4,4) = dP/dF (symmetric: second
  !> derivatives of W) and the stored energy density w per unit reference
  !> volume; optionally the Cauchy stress (xx, yy, xy, zz) and the
  !> Green-Lagrange strain (xx, yy, 2 E_xy, zz = 0). J must be > 0 (the caller
  !> checks).
  !>   P = mu F + (lambda ln J - mu) F^-T
  !>   A_iJkL = mu d_ik d_JL + lambda Fi_Ji Fi_Lk - (lambda ln J - mu) Fi_Jk Fi_Li  (Fi = F^-1)
  pure subroutine bulk_neohooke(mat, f, p, a, w, cauchy, green)
    type(bulk_t), intent(in) :: mat
    real(wp), intent(in) :: f(4)
    real(wp), intent(out) :: p(4), a(4, 4), w
    real(wp), intent(out), optional :: cauchy(4), green(4)
    real(wp) :: kb, mu, lam, fm(2, 2), fi(2, 2), jac, lnj, c(2, 2)
    integer :: i, jj, k, l, r, s
    call moduli(mat, kb, mu)
    lam = kb - 2.0_wp * mu / 3.0_wp
    fm = reshape([f(1), f(3), f(2), f(4)], [2, 2])     ! fm(i, J)
    jac = fm(1, 1) * fm(2, 2) - fm(1, 2) * fm(2, 1)
    fi = reshape([fm(2, 2), -fm(2, 1), -fm(1, 2), fm(1, 1)], [2, 2]) / jac   ! fi(J, i) = F^-1
    lnj = log(jac)
    c = matmul(transpose(fm), fm)
    w = 0.5_wp * lam * lnj**2 - mu * lnj + 0.5_wp * mu * (c(1, 1) + c(2, 2) - 2.0_wp)
    do i = 1, 2
      do jj = 1, 2
        p(2 * (i - 1) + jj) = mu * fm(i, jj) + (lam * lnj - mu) * fi(jj, i)
      end do
    end do
    do i = 1, 2
      do jj = 1, 2
        r = 2 * (i - 1) + jj
        do k = 1, 2
          do l = 1, 2
            s = 2 * (k - 1) + l
            a(r, s) = lam * fi(jj, i) * fi(l, k) - (lam * lnj - mu) * fi(jj, k) * fi(l, i)
            if (i == k .and. jj == l) a(r, s) = a(r, s) + mu
          end do
        end do
      end do
    end do
    ! sigma = (mu b + (lambda ln J - mu) I) / J, b = F F'; sigma_zz = lambda ln J / J
    if (present(cauchy)) then
      c = matmul(fm, transpose(fm))
      cauchy = [mu * c(1, 1) + lam * lnj - mu, mu * c(2, 2) + lam * lnj - mu, mu * c(1, 2), lam * lnj] / jac
    end if
    if (present(green)) then
      c = matmul(transpose(fm), fm)
      green = [0.5_wp * (c(1, 1) - 1.0_wp), 0.5_wp * (c(2, 2) - 1.0_wp), c(1, 2), 0.0_wp]
    end if
  end subroutine bulk_neohooke

  !> Static condensation of the zz component (sigma_zz = 0): the in-plane
  !> block becomes D_pp - D_pz D_zp / D_zz; zz row and column set to 0.
  pure subroutine condense_zz(dtan)
    real(wp), intent(inout) :: dtan(4, 4)
    integer :: i, j
    do j = 1, 3
      do i = 1, 3
        dtan(i, j) = dtan(i, j) - dtan(i, 4) * dtan(4, j) / dtan(4, 4)
      end do
    end do
    dtan(4, :) = 0.0_wp
    dtan(:, 4) = 0.0_wp
  end subroutine condense_zz

  !> Bulk and shear moduli.
  pure subroutine moduli(mat, kb, g)
    type(bulk_t), intent(in) :: mat
    real(wp), intent(out) :: kb, g
    kb = mat%young / (3.0_wp * (1.0_wp - 2.0_wp * mat%poisson))
    g = mat%young / (2.0_wp * (1.0_wp + mat%poisson))
  end subroutine moduli
end module fracas_bulk
