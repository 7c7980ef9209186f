!> LMGC90's normalised NLGS convergence norms (Quad, Maxm, QM/16), one
!> procedure for both Gauss–Seidel solvers (the scene's exchange local–global
!> NLGS and the stored-Delassus solver). The sweep kernels accumulate the sums
!> during the last sweep of a check block; lmgc_norms turns them into the
!> normalised errors and the verdict (doc/solver.md, LMGC90's formulas).
module fracas_lmgc_norms
  use fracas_kinds, only: wp
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none
  private
  public :: lmgc_norms_t, lmgc_norms, lmgc_add_sums

  !> The normalised errors of a check sweep (each < 1 means converged).
  type :: lmgc_norms_t
    real(wp) :: quad_dv = 0.0_wp, maxm_dv = 0.0_wp, quad_dvr = 0.0_wp, maxm_dvr = 0.0_wp
    real(wp) :: mean_dvor = 0.0_wp
    logical :: finite = .true.      !< .false.: the sums hold NaN or Inf (the iteration diverged)
  end type lmgc_norms_t

contains

  include 'lmgc_sums.inc'

  !> LMGC90's verdict on one check sweep. sums as the sweep kernels accumulate
  !> them over contacts (du = W (r_old - r_new), rbar the mean reaction):
  !> (1) du^2, (2) du^2 rbar^2, (3) rbar.du, (4) r.W r, (5) |W r|^2, (6) the
  !> contacts counted; maxes: the largest du^2 and du^2 rbar^2.
  !> check: 'Quad ', 'Maxm ' or 'QM/16'.
  !> vscale is the velocity scale of the problem (free velocities): reactions
  !> whose W r stays at round-off against it (bodies merely touching) count as
  !> converged, as does a sweep without reactions.
  subroutine lmgc_norms(check, tol, sums, maxes, vscale, nrm, converged)
    character(len=5), intent(in) :: check
    real(wp), intent(in) :: tol, sums(6), maxes(2), vscale
    type(lmgc_norms_t), intent(out) :: nrm
    logical, intent(out) :: converged
    real(wp) :: nact, quad_wr, mean_wrr
    nact = sums(6)
    if (.not. (all(ieee_is_finite(sums)) .and. all(ieee_is_finite(maxes)))) then
      nrm%finite = .false.
      converged = .false.
      return
    end if
    if (nact < 1.0_wp .or. sums(4) <= 0.0_wp .or. sqrt(sums(5) / max(nact, 1.0_wp)) <= 1.0e-12_wp * vscale) then
      converged = .true.
      return
    end if
    quad_wr = sqrt(sums(5) / nact)
    mean_wrr = sums(4) / nact
    nrm%quad_dv = sqrt(sums(1) / nact) / (quad_wr * tol)
    nrm%maxm_dv = sqrt(maxes(1)) / (quad_wr * tol)
    nrm%quad_dvr = sqrt(sums(2) / nact) / (mean_wrr * tol)
    nrm%maxm_dvr = sqrt(maxes(2)) / (mean_wrr * tol)
    nrm%mean_dvor = sums(3) / (sums(4) * tol)
    select case (check)
    case ('Maxm ')
      converged = abs(nrm%mean_dvor) < 1.0_wp .and. nrm%maxm_dv < 1.0_wp .and. nrm%maxm_dvr < 1.0_wp
    case ('QM/16')
      converged = abs(nrm%mean_dvor) < 1.0_wp .and. nrm%quad_dv < 1.0_wp .and. &
                  nrm%quad_dvr < 1.0_wp .and. nrm%maxm_dv < 16.666_wp .and. nrm%maxm_dvr < 16.666_wp
    case default
      converged = abs(nrm%mean_dvor) < 1.0_wp .and. nrm%quad_dv < 1.0_wp .and. nrm%quad_dvr < 1.0_wp
    end select
  end subroutine lmgc_norms
end module fracas_lmgc_norms
