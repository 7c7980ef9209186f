!> Expected to fail (test_cases/unit/CMakeLists.txt: singular.*): factorizes the truss-lattice
!> matrix of fracas_test_matrices with one dof cut off (its row and column zero, as for a
!> node no element touches) with the method given as the first argument ('dense',
!> 'cholmod', 'umfpack', 'auto') on nx x nx nodes (second argument). Each must stop with
!> a message naming the method and the failure; reaching the end prints "no error".
program singular_matrix_check
  use fracas_kinds, only: wp
  use fracas_sparse, only: sparse_t, sparse_from_triplets
  use fracas_linear_solver, only: factor_t, factor_build, factor_method_name
  use fracas_test_matrices, only: lattice_triplets
  use fracas_command_line, only: argument_value
  implicit none
  type(sparse_t) :: a
  type(factor_t) :: f
  integer, allocatable :: rows(:), cols(:)
  real(wp), allocatable :: vals(:)
  integer :: nx, cut
  character(len=:), allocatable :: method, nx_text

  method = argument_value(1, 'method')
  nx_text = argument_value(2, 'nx')
  read (nx_text, *) nx
  call lattice_triplets(nx, nx, 1.0_wp, 100.0_wp, rows, cols, vals)
  cut = nx * nx   ! a dof in the middle of the numbering
  where (rows == cut .or. cols == cut) vals = 0.0_wp
  call sparse_from_triplets(2 * nx * nx, rows, cols, vals, a)
  call factor_build(f, a, method)
  write (*, '(a)') 'no error: '//factor_method_name(f)
end program singular_matrix_check
