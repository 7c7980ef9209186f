!> Reader of FCLib local problems (HDF5, group /fclib_local) through fracas_h5,
!> and a text writer of reactions that ../shared/fclib/tools/eval_solution.py reads.
!>
!> Layout (reference/fclib_siconos.md §1.1): /fclib_local/spacedim (2 or 3),
!> /fclib_local/W/{m,n,nz,nzmax,p,i,x} in CSparse conventions (nz = -2 CSR:
!> p = row pointers, i = column indices; nz = -1 CSC: p = column pointers,
!> i = row indices; nz >= 0 triplet: i = row, p = column, nz entries),
!> /fclib_local/vectors/q (m) and mu (nc), m = n = spacedim * nc. Every matrix
!> is returned as 1-based triplets (duplicates allowed: they add up). Any
!> deviation stops with "FILE: what was found, what was expected".
module fracas_fclib_io
  use fracas_kinds, only: wp
  use fracas_strings, only: itoa
  use fracas_errors, only: input_error, fatal
  use fracas_files, only: file_exists
  use fracas_h5, only: hid_t, h5_open_file, h5_close_file, h5_exists, h5_read_dataset, h5_dataset_dims
  implicit none
  private
  public :: fclib_local_t, fclib_read_local, fclib_write_reactions, fclib_read_reactions

  !> One local problem: u = W r + q, K* ∋ u + g(u) ⊥ r ∈ K (contact components
  !> in FCLib order: normal first).
  type :: fclib_local_t
    character(len=:), allocatable :: path
    integer :: dim = 0, nc = 0, m = 0
    integer :: storage = 0                  !< nz code of W in the file (-2 CSR, -1 CSC, >= 0 triplet)
    integer, allocatable :: row(:), col(:)  !< 1-based triplets of W
    real(wp), allocatable :: val(:)
    real(wp), allocatable :: q(:), mu(:)
  end type fclib_local_t

contains

  !> Read the local problem of PATH into p.
  subroutine fclib_read_local(path, p)
    character(len=*), intent(in) :: path
    type(fclib_local_t), intent(out) :: p
    integer(hid_t) :: fid
    integer, allocatable :: iv(:), ip(:), ii(:)
    real(wp), allocatable :: x(:)
    integer :: m, n, nz, nnz, k, j
    p%path = trim(path)
    if (.not. file_exists(path)) call input_error(path, 0, 0, 'no such file (expected an FCLib HDF5 problem)')
    if (.not. is_hdf5(path)) call input_error(path, 0, 0, 'not an HDF5 file (expected an FCLib problem, '// &
                                              'HDF5 with a group /fclib_local)')
    call h5_open_file(path, fid)
    if (.not. h5_exists(fid, 'fclib_local')) then
      if (h5_exists(fid, 'fclib_global') .or. h5_exists(fid, 'fclib_global_rolling')) then
        call input_error(path, 0, 0, 'a global FCLib problem (/fclib_global): fracas-fclib solves local problems '// &
                         '(/fclib_local); condense it first (../shared/fclib/tools/make_local.py)')
      end if
      call input_error(path, 0, 0, 'no group /fclib_local (expected an FCLib local problem)')
    end if
    p%dim = scalar('fclib_local/spacedim')
    if (p%dim /= 2 .and. p%dim /= 3) &
      call input_error(path, 0, 0, '/fclib_local/spacedim is '//itoa(p%dim)//', expected 2 or 3')
    call real_vector('fclib_local/vectors/q', p%q)
    call real_vector('fclib_local/vectors/mu', p%mu)
    p%nc = size(p%mu)
    p%m = p%dim * p%nc
    if (size(p%q) /= p%m) call input_error(path, 0, 0, '/fclib_local/vectors/q has '//itoa(size(p%q))// &
                                           ' entries, expected spacedim * size(mu) = '//itoa(p%m))
    if (any(p%mu < 0.0_wp) .or. any(p%mu /= p%mu)) &
      call input_error(path, 0, 0, '/fclib_local/vectors/mu: expected friction coefficients >= 0')
    if (any(p%q /= p%q)) call input_error(path, 0, 0, '/fclib_local/vectors/q holds NaN')
    if (h5_exists(fid, 'fclib_local/V') .or. h5_exists(fid, 'fclib_local/R')) &
      call input_error(path, 0, 0, 'problem with equality constraints (/fclib_local/V, R): not supported')
    m = scalar('fclib_local/W/m')
    n = scalar('fclib_local/W/n')
    nz = scalar('fclib_local/W/nz')
    p%storage = nz
    if (m /= p%m .or. n /= p%m) call input_error(path, 0, 0, '/fclib_local/W is '//itoa(m)//' x '//itoa(n)// &
                                                 ', expected '//itoa(p%m)//' x '//itoa(p%m)//' (spacedim * size(mu))')
    call int_vector('fclib_local/W/p', ip)
    call int_vector('fclib_local/W/i', ii)
    call real_vector('fclib_local/W/x', x)
    select case (nz)
    case (-2, -1)
      ! compressed: p has m+1 (CSR) or n+1 (CSC) pointers, 0-based, nondecreasing
      if (size(ip) /= m + 1) call input_error(path, 0, 0, '/fclib_local/W/p has '//itoa(size(ip))// &
                                              ' entries, expected '//itoa(m + 1)//' pointers ('// &
                                              trim(merge('CSR', 'CSC', nz == -2))//')')
      nnz = ip(m + 1)
      if (ip(1) /= 0 .or. any(ip(2:) < ip(:m)) .or. nnz > size(ii) .or. nnz > size(x)) &
        call input_error(path, 0, 0, '/fclib_local/W/p: expected nondecreasing 0-based pointers from 0 to at '// &
                         'most size(i) = size(x)')
      allocate (p%row(nnz), p%col(nnz))
      do j = 1, m
        do k = ip(j) + 1, ip(j + 1)
          if (nz == -2) then
            p%row(k) = j; p%col(k) = ii(k) + 1
          else
            p%col(k) = j; p%row(k) = ii(k) + 1
          end if
        end do
      end do
      p%val = x(1:nnz)
    case (0:)
      ! triplet, CSparse convention: i = row, p = column
      if (size(ip) < nz .or. size(ii) < nz .or. size(x) < nz) &
        call input_error(path, 0, 0, '/fclib_local/W (triplet, nz = '//itoa(nz)//'): expected at least nz '// &
                         'entries in p, i and x')
      p%row = ii(1:nz) + 1
      p%col = ip(1:nz) + 1
      p%val = x(1:nz)
    case default
      call input_error(path, 0, 0, '/fclib_local/W/nz is '//itoa(nz)//', expected -2 (CSR), -1 (CSC) or >= 0 (triplet)')
    end select
    if (any(p%row < 1) .or. any(p%row > m) .or. any(p%col < 1) .or. any(p%col > n)) &
      call input_error(path, 0, 0, '/fclib_local/W: an index is out of range (expected 0-based indices < '// &
                       itoa(m)//')')
    if (any(p%val /= p%val)) call input_error(path, 0, 0, '/fclib_local/W/x holds NaN')
    call h5_close_file(fid)

  contains

    !> An integer stored as a 1-element (or scalar) dataset.
    integer function scalar(name)
      character(len=*), intent(in) :: name
      integer, allocatable :: dims(:)
      call require(name)
      call h5_dataset_dims(fid, name, dims)
      if (size(dims) > 1) call input_error(path, 0, 0, '/'//name//': expected an integer (1-element dataset)')
      if (size(dims) == 1) then
        if (dims(1) /= 1) call input_error(path, 0, 0, '/'//name//' has '//itoa(dims(1))// &
                                           ' entries, expected one integer')
        call h5_read_dataset(fid, name, iv)
        scalar = iv(1)
      else
        call input_error(path, 0, 0, '/'//name//': a scalar dataset, expected a 1-element array')
      end if
    end function scalar

    subroutine int_vector(name, v)
      character(len=*), intent(in) :: name
      integer, allocatable, intent(out) :: v(:)
      integer, allocatable :: dims(:)
      call require(name)
      call h5_dataset_dims(fid, name, dims)
      if (size(dims) /= 1) call input_error(path, 0, 0, '/'//name//' has rank '//itoa(size(dims))// &
                                            ', expected a 1-D integer array')
      call h5_read_dataset(fid, name, v)
    end subroutine int_vector

    subroutine real_vector(name, v)
      character(len=*), intent(in) :: name
      real(wp), allocatable, intent(out) :: v(:)
      integer, allocatable :: dims(:)
      call require(name)
      call h5_dataset_dims(fid, name, dims)
      if (size(dims) /= 1) call input_error(path, 0, 0, '/'//name//' has rank '//itoa(size(dims))// &
                                            ', expected a 1-D real array')
      call h5_read_dataset(fid, name, v)
    end subroutine real_vector

    subroutine require(name)
      character(len=*), intent(in) :: name
      if (.not. h5_exists(fid, name)) call input_error(path, 0, 0, 'no dataset /'//name// &
                                                       ' (expected in an FCLib local problem)')
    end subroutine require
  end subroutine fclib_read_local

  !> True if PATH starts with the HDF5 signature (checked before HDF5 opens it,
  !> so a text file gets a clear message).
  logical function is_hdf5(path)
    character(len=*), intent(in) :: path
    character(len=8) :: sig
    integer :: u, ios
    is_hdf5 = .false.
    open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read', iostat=ios)
    if (ios /= 0) return
    read (u, iostat=ios) sig
    close (u)
    is_hdf5 = ios == 0 .and. sig == char(137)//'HDF'//char(13)//char(10)//char(26)//char(10)
  end function is_hdf5

  !> Write r (dim, nc) as text, one contact per line (normal first), full precision.
  subroutine fclib_write_reactions(path, r)
    character(len=*), intent(in) :: path
    real(wp), intent(in) :: r(:, :)
    integer :: u, ios, k
    open (newunit=u, file=path, status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write '//trim(path))
    write (u, '(a,i0,a,i0,a)') '# FCLib reactions r (', size(r, 1), ' per contact, normal first), ', &
      size(r, 2), ' contacts'
    do k = 1, size(r, 2)
      write (u, '(*(es25.17e3,:,1x))') r(:, k)
    end do
    close (u)
  end subroutine fclib_write_reactions

  !> Read reactions written as text (any whitespace, '#' comment lines) into r(dim, nc).
  subroutine fclib_read_reactions(path, r)
    character(len=*), intent(in) :: path
    real(wp), intent(inout) :: r(:, :)
    integer :: u, ios, n, line, need
    character(len=4096) :: buf
    real(wp), allocatable :: flat(:)
    need = size(r)
    allocate (flat(need))
    open (newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) call input_error(path, 0, 0, 'cannot open (expected a text file of reactions)')
    n = 0; line = 0
    do
      read (u, '(a)', iostat=ios) buf
      if (ios /= 0) exit
      line = line + 1
      buf = adjustl(buf)
      if (len_trim(buf) == 0 .or. buf(1:1) == '#') cycle
      call parse_line(trim(buf))
    end do
    close (u)
    if (n /= need) call input_error(path, 0, 0, 'holds '//itoa(n)//' numbers, expected '//itoa(need)// &
                                    ' (spacedim * contacts)')
    r = reshape(flat, shape(r))

  contains

    subroutine parse_line(s)
      character(len=*), intent(in) :: s
      integer :: a, b
      real(wp) :: x
      a = 1
      do while (a <= len(s))
        if (s(a:a) == ' ' .or. s(a:a) == char(9) .or. s(a:a) == ',') then
          a = a + 1
          cycle
        end if
        b = a
        do while (b < len(s))
          if (s(b + 1:b + 1) == ' ' .or. s(b + 1:b + 1) == char(9) .or. s(b + 1:b + 1) == ',') exit
          b = b + 1
        end do
        read (s(a:b), *, iostat=ios) x
        if (ios /= 0) call input_error(path, line, a, "'"//s(a:b)//"' is not a number")
        n = n + 1
        if (n > need) call input_error(path, line, a, 'more than '//itoa(need)//' numbers (spacedim * contacts)')
        flat(n) = x
        a = b + 1
      end do
    end subroutine parse_line
  end subroutine fclib_read_reactions

end module fracas_fclib_io
