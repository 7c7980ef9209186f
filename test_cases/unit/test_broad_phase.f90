!> The cell-list broad phase plus fine detection must find exactly the pairs a
!> brute-force double loop finds (gap <= alert), for polydisperse disks, a big
!> disk and walls. Reference: the O(n^2) loop over all pairs.
!> The sparse grid (occupied cells only, used when bodies are far apart) must
!> give the same pairs in the same order as the dense grid; a scene with disks
!> 5e8 and 1e11 away from the others must still find the brute-force contacts;
!> and four disks on a line, two pairs 1e9 apart (a dense grid of 4e9 cells:
!> an integer overflow), exactly their two contacts.
program test_broad_phase
  use fracas_kinds, only: wp
  use fracas_deck, only: body_input_t, see_rule_input_t
  use fracas_contactors, only: tactors_t, tactors_build, tactor_center, tk_disk, tk_jonc
  use fracas_detection, only: detection_t, detection_init, detect_rough, detect_fine
  use fracas_contacts, only: contacts_t
  use fracas_dkdkx, only: dkdkx_geometry
  use fracas_dkjcx, only: dkjcx_geometry
  use fracas_random, only: rng_t, rng_seed, rng_below
  use fracas_testing, only: check_true, check_close, test_finish
  implicit none
  integer, parameter :: nd = 3000
  real(wp), parameter :: alert = 0.05_wp
  type(body_input_t), allocatable :: bodies(:)
  type(see_rule_input_t) :: rules(2)
  type(tactors_t) :: t
  type(detection_t) :: det
  type(contacts_t) :: c
  type(rng_t) :: rng
  real(wp), allocatable :: q(:, :)
  logical, allocatable :: movable(:)
  integer :: i, nb, nbrute, found
  integer, allocatable :: pairs_dense(:, :)
  real(wp) :: gap, n(2), p(2)

  call rng_seed(rng, 11)
  nb = nd + 2
  allocate (bodies(nb), q(3, nb), movable(nb))
  do i = 1, nd
    allocate (bodies(i)%tactors(1))
    bodies(i)%tactors(1)%kind = 'DISKx'
    bodies(i)%tactors(1)%color = 'BLEUx'
    bodies(i)%tactors(1)%radius = 0.5_wp + uniform()
    if (i == 7) bodies(i)%tactors(1)%radius = 30.0_wp     ! one very large disk ("big")
    q(:, i) = [150.0_wp * uniform(), 150.0_wp * uniform(), 0.0_wp]
  end do
  do i = nd + 1, nb       ! two walls: one horizontal, one tilted
    allocate (bodies(i)%tactors(1))
    bodies(i)%tactors(1)%kind = 'JONCx'
    bodies(i)%tactors(1)%color = 'WALLx'
    bodies(i)%tactors(1)%ax1 = 80.0_wp
    bodies(i)%tactors(1)%ax2 = 1.0_wp
  end do
  q(:, nd + 1) = [75.0_wp, 20.0_wp, 0.0_wp]
  q(:, nd + 2) = [75.0_wp, 100.0_wp, 0.7_wp]
  movable = .true.
  rules(1) = rule('DISKx', 'BLEUx', 'DISKx', 'BLEUx')
  rules(2) = rule('DISKx', 'BLEUx', 'JONCx', 'WALLx')
  call tactors_build(bodies, t)
  call detection_init(det, t, rules, ['law01'])
  call detect_rough(det, t, q, movable, 0.0_wp)
  call detect_fine(det, t, q, c)

  call brute_force()
  call check_true('brute force finds contacts', nbrute > 1000)
  call check_close('contacts found by the cell lists', real(c%n, wp), real(nbrute, wp), 0.0_wp)
  call check_close('each brute-force contact found', real(found, wp), real(nbrute, wp), 0.0_wp)

  ! Same scene through the sparse grid: identical pairs, identical order.
  pairs_dense = reshape([det%pair_cd(1:det%npairs), det%pair_an(1:det%npairs)], [det%npairs, 2])
  call detect_rough(det, t, q, movable, 0.0_wp, sparse_grid=.true.)
  call check_close('sparse grid: as many rough pairs', real(det%npairs, wp), real(size(pairs_dense, 1), wp), 0.0_wp)
  if (det%npairs == size(pairs_dense, 1)) &
    call check_true('sparse grid: same pairs in the same order', &
                    all(det%pair_cd(1:det%npairs) == pairs_dense(:, 1)) .and. &
                    all(det%pair_an(1:det%npairs) == pairs_dense(:, 2)))

  ! Far bodies: disk 1 moved 5e8 along x with disk 2 beside it, disk 3 1e11
  ! away along -x with disk 4 touching it.
  q(:, 1) = [5.0e8_wp, 3.0_wp, 0.0_wp]
  q(:, 2) = [5.0e8_wp + t%radius(1) + t%radius(2) + 0.01_wp, 3.0_wp, 0.0_wp]
  q(:, 3) = [-1.0e11_wp, 75.0_wp, 0.0_wp]
  q(:, 4) = [-1.0e11_wp, 75.0_wp + t%radius(3) + t%radius(4), 0.0_wp]
  call detect_rough(det, t, q, movable, 0.0_wp)
  call detect_fine(det, t, q, c)
  call brute_force()
  call check_true('far bodies: brute force finds contacts', nbrute > 1000)
  call check_close('far bodies: contacts found', real(c%n, wp), real(nbrute, wp), 0.0_wp)
  call check_close('far bodies: each brute-force contact found', real(found, wp), real(nbrute, wp), 0.0_wp)
  call check_true('far bodies: the far pairs are found', has_contact(1, 2) .and. has_contact(3, 4))

  call line_scene()
  call test_finish()

contains

  !> nbrute: pairs within the alert distance by the O(n^2) loop; found: those among c.
  subroutine brute_force()
    integer :: i, j
    nbrute = 0
    found = 0
    do i = 1, t%n
      do j = i + 1, t%n
        if (t%kind(i) == tk_disk .and. t%kind(j) == tk_disk) then
          call dkdkx_geometry(tactor_center(t, i, q(:, i)), t%radius(i), tactor_center(t, j, q(:, j)), &
                              t%radius(j), gap, n, p)
        else if (t%kind(i) == tk_disk .and. t%kind(j) == tk_jonc) then
          call dkjcx_geometry(tactor_center(t, i, q(:, i)), t%radius(i), q(1:2, j), q(3, j), t%ax1(j), &
                              t%ax2(j), gap, n, p)
        else
          cycle
        end if
        if (gap <= alert) then
          nbrute = nbrute + 1
          if (has_contact(i, j)) found = found + 1
        end if
      end do
    end do
  end subroutine brute_force

  !> Four disks of radius 0.1 on the x axis: (0, 0.2) and (1e9, 1e9 + 0.2).
  subroutine line_scene()
    type(body_input_t) :: line(4)
    type(tactors_t) :: tl
    type(detection_t) :: dl
    type(contacts_t) :: cl
    real(wp) :: ql(3, 4)
    integer :: k
    do k = 1, 4
      allocate (line(k)%tactors(1))
      line(k)%tactors(1)%kind = 'DISKx'
      line(k)%tactors(1)%color = 'BLEUx'
      line(k)%tactors(1)%radius = 0.1_wp
    end do
    ql(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp]
    ql(:, 2) = [0.2_wp, 0.0_wp, 0.0_wp]
    ql(:, 3) = [1.0e9_wp, 0.0_wp, 0.0_wp]
    ql(:, 4) = [1.0e9_wp + 0.2_wp, 0.0_wp, 0.0_wp]
    call tactors_build(line, tl)
    call detection_init(dl, tl, rules(1:1), ['law01'])
    call detect_rough(dl, tl, ql, [.true., .true., .true., .true.], 0.0_wp)
    call detect_fine(dl, tl, ql, cl)
    call check_close('line 1e9 long: contacts', real(cl%n, wp), 2.0_wp, 0.0_wp)
  end subroutine line_scene

  logical function has_contact(a, b)
    integer, intent(in) :: a, b
    integer :: k
    has_contact = .false.
    do k = 1, c%n
      if ((c%cd(k) == a .and. c%an(k) == b) .or. (c%cd(k) == b .and. c%an(k) == a)) has_contact = .true.
    end do
  end function has_contact

  type(see_rule_input_t) function rule(cdtac, cdcol, antac, ancol)
    character(len=5), intent(in) :: cdtac, cdcol, antac, ancol
    rule%cdbdy = 'RBDY2'; rule%anbdy = 'RBDY2'
    rule%cdtac = cdtac; rule%cdcol = cdcol; rule%antac = antac; rule%ancol = ancol
    rule%behav = 'law01'
    rule%alert = alert
  end function rule

  real(wp) function uniform()
    uniform = real(rng_below(rng, 1000000), wp) / 1.0e6_wp
  end function uniform
end program test_broad_phase
