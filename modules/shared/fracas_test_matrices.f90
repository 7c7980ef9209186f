!> Elasticity-like test matrices for the linear solvers (unit tests and bench/): the
!> iteration matrix A = m I + K of a truss lattice on an nx x ny grid of nodes (2D, two dofs
!> per node) or an nx x ny x nz grid (3D, three dofs per node). Dof c of node id is
!> d (id - 1) + c, id = i + (j - 1) nx + (k - 1) nx ny. Every node is tied to each of its
!> 8 (2D) or 26 (3D) neighbours by a bar of stiffness k along the bar (2d x 2d block
!> k [n n^T, -n n^T; -n n^T, n n^T]); in 2D this is the sparsity of a Q4 mesh (9 nodes per
!> column, x and y coupled), in 3D that of a hexahedral mesh (27 nodes). A is positive
!> definite (K >= 0, m > 0); in 2D cond(A) is about 1 + 8 k/m. Triplets are emitted bar by
!> bar as an FE assembly would, so every off-diagonal position of a node pair and every
!> diagonal block appears several times (duplicates to sum).
module fracas_test_matrices
  use fracas_kinds, only: wp
  use fracas_random, only: rng_t, rng_seed, rng_below
  implicit none
  private
  public :: lattice_triplets

contains

  !> Triplets of A = mass I + K (2 nx ny dofs, or 3 nx ny nz with nz). With seed, each
  !> bar's stiffness is stiffness times a factor in [0.5, 1.5) drawn from that seed (the
  !> same triplet list with other values: a refill).
  subroutine lattice_triplets(nx, ny, mass, stiffness, rows, cols, vals, seed, nz)
    integer, intent(in) :: nx, ny
    real(wp), intent(in) :: mass, stiffness
    integer, allocatable, intent(out) :: rows(:), cols(:)
    real(wp), allocatable, intent(out) :: vals(:)
    integer, intent(in), optional :: seed, nz
    type(rng_t) :: rng
    integer :: offsets(3, 13), noff, d, nzz, ndof, nbars, ntrip, t, i, j, k, o, di, dj, dk, p
    integer :: a, b

    d = 2
    nzz = 1
    if (present(nz)) then
      d = 3
      nzz = nz
    end if
    ! Half of the neighbourhood: offsets whose last nonzero component is positive, so
    ! each bar is met once (2D: (1,0), (-1,1), (0,1), (1,1); 3D: 13 offsets).
    noff = 0
    do dk = 0, merge(1, 0, d == 3)
      do dj = -1, 1
        do di = -1, 1
          if (dk > 0 .or. (dk == 0 .and. (dj > 0 .or. (dj == 0 .and. di > 0)))) then
            noff = noff + 1
            offsets(:, noff) = [di, dj, dk]
          end if
        end do
      end do
    end do
    nbars = 0
    do o = 1, noff
      nbars = nbars + (nx - abs(offsets(1, o))) * (ny - abs(offsets(2, o))) * (nzz - abs(offsets(3, o)))
    end do
    ndof = d * nx * ny * nzz
    ntrip = ndof + (2 * d)**2 * nbars
    allocate (rows(ntrip), cols(ntrip), vals(ntrip))
    if (present(seed)) call rng_seed(rng, seed)
    t = 0
    do p = 1, ndof
      t = t + 1
      rows(t) = p; cols(t) = p; vals(t) = mass
    end do
    do k = 1, nzz
      do j = 1, ny
        do i = 1, nx
          do o = 1, noff
            di = offsets(1, o); dj = offsets(2, o); dk = offsets(3, o)
            if (i + di < 1 .or. i + di > nx .or. j + dj < 1 .or. j + dj > ny .or. k + dk > nzz) cycle
            a = i + (j - 1) * nx + (k - 1) * nx * ny
            b = (i + di) + (j + dj - 1) * nx + (k + dk - 1) * nx * ny
            call bar(a, b, real(offsets(1:d, o), wp) / sqrt(real(di * di + dj * dj + dk * dk, wp)))
          end do
        end do
      end do
    end do

  contains

    subroutine bar(a, b, dir)
      integer, intent(in) :: a, b
      real(wp), intent(in) :: dir(:)
      real(wp) :: kbar
      integer :: dofs(2 * d), p, q
      kbar = stiffness
      if (present(seed)) kbar = stiffness * (0.5_wp + rng_below(rng, 1000000) * 1.0e-6_wp)
      dofs = [(d * (a - 1) + p, p=1, d), (d * (b - 1) + p, p=1, d)]
      do q = 1, 2 * d
        do p = 1, 2 * d
          t = t + 1
          rows(t) = dofs(p); cols(t) = dofs(q)
          vals(t) = kbar * dir(1 + mod(p - 1, d)) * dir(1 + mod(q - 1, d)) * &
                    merge(1.0_wp, -1.0_wp, (p <= d) .eqv. (q <= d))
        end do
      end do
    end subroutine bar
  end subroutine lattice_triplets
end module fracas_test_matrices
