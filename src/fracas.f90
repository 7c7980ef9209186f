!> fracas CASE_DIR: the driver (placeholder until the solver lands).
program fracas
  implicit none
  print '(a)', 'fracas: not built yet'
end program fracas
