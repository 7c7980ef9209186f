!> Elasticity-like test matrices for the linear solvers (unit tests and bench/): the
!> iteration matrix A = m I + K of a 2D truss lattice on an nx x ny grid of nodes, two
!> dofs per node (dof 2 id - 1 along x, 2 id along y, id = i + (j - 1) nx). Every node is
!> tied to its right, upper and two diagonal neighbours by a bar of stiffness k along the
!> bar (4 x 4 block k [n n^T, -n n^T; -n n^T, n n^T]), which gives the sparsity of a Q4 mesh
!> (9 nodes per column, x and y coupled) and a positive definite A (K >= 0, m > 0);
!> cond(A) is about 1 + 8 k/m. Triplets are emitted bar by bar as an FE assembly would,
!> so every off-diagonal position of a node pair and every diagonal block appears several
!> times (duplicates to sum).
module fracas_test_matrices
  use fracas_kinds, only: wp
  use fracas_random, only: rng_t, rng_seed, rng_below
  implicit none
  private
  public :: lattice_triplets, lattice_bar_count

contains

  !> Number of bars of the nx x ny lattice.
  pure integer function lattice_bar_count(nx, ny)
    integer, intent(in) :: nx, ny
    lattice_bar_count = (nx - 1) * ny + nx * (ny - 1) + 2 * (nx - 1) * (ny - 1)
  end function lattice_bar_count

  !> Triplets of A = mass I + K (2 nx ny dofs). With seed, each bar's stiffness is
  !> stiffness times a factor in [0.5, 1.5) drawn from that seed (the same triplet list
  !> with other values: a refill).
  subroutine lattice_triplets(nx, ny, mass, stiffness, rows, cols, vals, seed)
    integer, intent(in) :: nx, ny
    real(wp), intent(in) :: mass, stiffness
    integer, allocatable, intent(out) :: rows(:), cols(:)
    real(wp), allocatable, intent(out) :: vals(:)
    integer, intent(in), optional :: seed
    type(rng_t) :: rng
    integer :: i, j, t, ndof, d, ntrip
    real(wp), parameter :: s = 0.70710678118654752440_wp

    ndof = 2 * nx * ny
    ntrip = ndof + 16 * lattice_bar_count(nx, ny)
    allocate (rows(ntrip), cols(ntrip), vals(ntrip))
    if (present(seed)) call rng_seed(rng, seed)
    t = 0
    do d = 1, ndof
      t = t + 1
      rows(t) = d; cols(t) = d; vals(t) = mass
    end do
    do j = 1, ny
      do i = 1, nx
        if (i < nx) call bar(node(i, j), node(i + 1, j), 1.0_wp, 0.0_wp)
        if (j < ny) call bar(node(i, j), node(i, j + 1), 0.0_wp, 1.0_wp)
        if (i < nx .and. j < ny) then
          call bar(node(i, j), node(i + 1, j + 1), s, s)
          call bar(node(i + 1, j), node(i, j + 1), -s, s)
        end if
      end do
    end do

  contains

    pure integer function node(i, j)
      integer, intent(in) :: i, j
      node = i + (j - 1) * nx
    end function node

    subroutine bar(a, b, nx_, ny_)
      integer, intent(in) :: a, b
      real(wp), intent(in) :: nx_, ny_
      real(wp) :: k, dir(2)
      integer :: dofs(4), p, q
      k = stiffness
      if (present(seed)) k = stiffness * (0.5_wp + rng_below(rng, 1000000) * 1.0e-6_wp)
      dir = [nx_, ny_]
      dofs = [2 * a - 1, 2 * a, 2 * b - 1, 2 * b]
      do q = 1, 4
        do p = 1, 4
          t = t + 1
          rows(t) = dofs(p); cols(t) = dofs(q)
          vals(t) = k * dir(1 + mod(p - 1, 2)) * dir(1 + mod(q - 1, 2)) * merge(1.0_wp, -1.0_wp, (p <= 2) .eqv. (q <= 2))
        end do
      end do
    end subroutine bar
  end subroutine lattice_triplets
end module fracas_test_matrices
