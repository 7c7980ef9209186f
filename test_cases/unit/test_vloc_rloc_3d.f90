!> 3D Vloc_Rloc files (fracas_vloc_rloc_3d, write_vloc_rloc_file_3d).
!> 1. Round trip: four records (SPSPx with internals, PRPRx with CDVER,
!>    SPPRx, PRPLx) written and read back: words and integers exact, every
!>    real to the printed precision (D14.7: 7 significant digits, relative
!>    5e-7); written again, the file is the same byte for byte.
!> 2. The lines written against LMGC90's formats, typed by hand from its
!>    mod_PRPRx / mod_SPSPx / mod_SPPRx writers: id lines (CDVER at 30-34,
!>    iadj at 79-83, SPPRx's law at 30-34), the order of the reaction line
!>    (PRPRx t, n, s; SPSPx s, t, n), the gap labels.
!> 3. Hand-written LMGC90-format records (numbers ours): a PRPLx in the layout
!>    of LMGC90's examples (rls first, gapTT, coo, t, n, s, CDVER 3) and an
!>    SPSPx (gTT =, s, t, n, coo, iadj, a '#' line and internals): each value
!>    where its label says.
!> 4. Store order (t1, t2, n) <-> LMGC90's (t, n, s): s = t x n (1e-15), the
!>    inverse exact.
!> Planted (each went red): PRPRx written in SPSPx's order (s, t, n); the
!> reader taking the reaction line by position (t, n, s); the CDVER column
!> written at 31-35; the 'gTT =' label on PRPRx.
program test_vloc_rloc_3d
  use fracas_kinds, only: wp
  use fracas_vloc_rloc_3d, only: contact3_record_t, read_vloc_rloc_3d, vloc3_from_store, vloc3_to_store
  use fracas_write_outbox, only: write_vloc_rloc_file_3d
  use fracas_frame_3d, only: tangents_of_normal, cross3
  use fracas_files, only: executable_dir
  use fracas_testing, only: check_true, check_close, test_finish
  implicit none
  type(contact3_record_t) :: recs(4)
  type(contact3_record_t), allocatable :: back(:), hand(:)
  character(len=:), allocatable :: p1, p2, p3
  character(len=120), allocatable :: lines(:)
  integer :: step, k
  real(wp) :: time, err

  p1 = executable_dir()//'test_vloc_rloc_3d_1.OUT'
  p2 = executable_dir()//'test_vloc_rloc_3d_2.OUT'
  p3 = executable_dir()//'test_vloc_rloc_3d_hand.INI'

  ! 1. round trip
  recs(1) = record('SPSPx', 1, 'SPHER', 3, 'SPHER', 0, 1, [12.3456789_wp, -2345.6789_wp, 3.456789e-5_wp])
  recs(1)%internals = [0.125_wp, -7.654321e-3_wp, 1.0e-12_wp, 2.0_wp, 3.0_wp, 4.0_wp, 5.0_wp]
  recs(2) = record('PRPRx', 12, 'POLYR', 5, 'POLYR', 3, 0, [-1.0e-3_wp, 4.6702234e3_wp, -1.081087e3_wp])
  recs(3) = record('SPPRx', 2, 'SPHER', 1, 'POLYR', 0, 0, [0.0_wp, 9.87654321_wp, 0.5_wp])
  recs(4) = record('PRPLx', 4, 'POLYR', 7, 'PLANx', 4, 0, [1.5_wp, 2.5_wp, -3.5_wp])
  call write_vloc_rloc_file_3d(p1, 17, 0.0425_wp, recs)
  call read_vloc_rloc_3d(p1, step, time, back)
  call check_true('round trip: step 17, 4 records', step == 17 .and. size(back) == 4)
  call check_close('round trip: time', time, 0.0425_wp, 5.0e-7_wp * 0.0425_wp)
  do k = 1, min(4, size(back))
    call check_true('round trip '//recs(k)%inter//': words and integers', same_ids(recs(k), back(k)))
    err = max(rel(back(k)%rl, recs(k)%rl), rel(back(k)%vl, recs(k)%vl), rel([back(k)%gap], [recs(k)%gap]), &
              rel(back(k)%coor, recs(k)%coor), rel(back(k)%t, recs(k)%t), rel(back(k)%n, recs(k)%n), &
              rel(back(k)%s, recs(k)%s))
    call check_close('round trip '//recs(k)%inter//': largest relative error of the reals', err, 0.0_wp, 5.0e-7_wp)
    call check_true('round trip '//recs(k)%inter//': point and frame lines read', &
                    back(k)%has_coor .and. back(k)%has_t .and. back(k)%has_n .and. back(k)%has_s)
  end do
  call check_true('round trip SPSPx: 7 internals', size(back(1)%internals) == 7)
  call check_close('round trip SPSPx: internal 2', back(1)%internals(2), -7.654321e-3_wp, 5.0e-7_wp * 7.7e-3_wp)
  call check_true('round trip PRPRx: CDVER 3', back(2)%cdver == 3)
  call write_vloc_rloc_file_3d(p2, 17, 0.0425_wp, back)
  call check_true('written again: the same file byte for byte', same_file(p1, p2))

  ! 2. the lines as LMGC90 writes them
  lines = file_lines(p1)
  call check_line(9, ' RBDY3      1  SPHER      3         iqsc0  RBDY3      2  SPHER      1  stick      1')
  call check_line(10, '                             rls/H 0.3456789D-04  rlt/H 0.1234568D+02  rln/H-0.2345679D+04')
  call check_line(12, '                             gTT = 0.1000000D-08')
  call check_line(13, '                             s(1)= 0.0000000D+00  s(2)=-0.6000000D+00  s(3)= 0.8000000D+00')
  call check_line(17, '#internal(1)    internal(2)    internal(3)    internal(4)    internal(5)    internal(6)    ' &
                  //'internal(7)')
  call check_line(21, '$icdan  PRPRx       12')
  call check_line(22, ' cdbdy  numbr  cdtac  numbr  CDVER  behav  anbdy  numbr  antac  numbr  sttus')
  call check_line(23, ' RBDY3      1  POLYR      5      3  iqsc0  RBDY3      2  POLYR      1  stick')
  call check_line(24, '                             rlt/H-0.1000000D-02  rln/H 0.4670223D+04  rls/H-0.1081087D+04')
  call check_line(26, '                             gapTT 0.1000000D-08')
  call check_line(27, '                             coo1= 0.1000000D+01  coo2= 0.2000000D+01  coo3= 0.3000000D+01')
  call check_line(33, ' cdbdy  numbr  cdtac  numbr  behav  anbdy  numbr  antac  numbr  sttus')
  call check_line(34, ' RBDY3      1  SPHER      1  iqsc0  RBDY3      2  POLYR      1  stick')

  ! 3. hand-written LMGC90-format records
  call write_text(p3, [character(len=100) :: &
    '! Vloc_Rloc', '$steps      3               time= 0.3000000D-02', &
    '!-----------------------------------------------------------------------', &
    '$icdan  PRPLx        1', &
    ' cdbdy  numbr  cdtac  numbr  CDVER  behav  anbdy  numbr  antac  numbr  sttus', &
    ' RBDY3      3  POLYR      1      3  iqsc0  RBDY3      9  PLANx      1  stick', &
    '                             rls/H-0.2500000D+00  rlt/H-0.1250000D+02  rln/H 0.1750000D+02', &
    '                             vls =-0.1000000D-19  vlt = 0.2000000D-19  vln =-0.3000000D-19', &
    '                             gapTT-0.5000000D-10', &
    '                             coo1= 0.4000000D+00  coo2= 0.1000000D+00  coo3=-0.1000000D-05', &
    '                             t(1)= 0.1000000D+01  t(2)= 0.0000000D+00  t(3)= 0.0000000D+00', &
    '                             n(1)= 0.0000000D+00  n(2)= 0.0000000D+00  n(3)= 0.1000000D+01', &
    '                             s(1)= 0.0000000D+00  s(2)=-0.1000000D+01  s(3)= 0.0000000D+00', &
    ' ', &
    '$icdan  SPSPx        2', &
    ' cdbdy  numbr  cdtac  numbr  CDVER  behav  anbdy  numbr  antac  numbr  sttus', &
    ' RBDY3     10  SPHER      1         czm01  RBDY3     11  SPHER      1  slifw      4', &
    '                             rls/H 0.1000000D+01  rlt/H 0.2000000D+01  rln/H 0.3000000D+01', &
    '                             vls = 0.4000000D+01  vlt = 0.5000000D+01  vln = 0.6000000D+01', &
    '                             gTT = 0.7000000D+01', &
    '                             s(1)= 0.0000000D+00  s(2)= 0.0000000D+00  s(3)=-0.1000000D+01', &
    '                             t(1)= 0.1000000D+01  t(2)= 0.0000000D+00  t(3)= 0.0000000D+00', &
    '                             n(1)= 0.0000000D+00  n(2)= 0.1000000D+01  n(3)= 0.0000000D+00', &
    '                             coo1= 0.1100000D+01  coo2= 0.1200000D+01  coo3= 0.1300000D+01', &
    '#taille_ele     saut_de_ut     saut_de_un', &
    '  0.2500000D+00  0.1000000D-02 -0.2000000D-02'])
  call read_vloc_rloc_3d(p3, step, time, hand)
  call check_true('hand-written: step 3, 2 records', step == 3 .and. size(hand) == 2)
  call check_close('hand-written: time', time, 3.0e-3_wp, 1.0e-18_wp)
  if (size(hand) == 2) then
    associate (a => hand(1), b => hand(2))
      call check_true('hand PRPLx: RBDY3 3 POLYR 1 CDVER 3 iqsc0 RBDY3 9 PLANx 1 stick', &
                      a%inter == 'PRPLx' .and. a%icdbdy == 3 .and. a%cdtac == 'POLYR' .and. a%icdtac == 1 .and. &
                      a%cdver == 3 .and. a%behav == 'iqsc0' .and. a%ianbdy == 9 .and. a%antac == 'PLANx' .and. &
                      a%status == 'stick' .and. a%iadj == 0)
      call check_close('hand PRPLx: rlt', a%rl(1), -12.5_wp, 0.0_wp)
      call check_close('hand PRPLx: rln', a%rl(2), 17.5_wp, 0.0_wp)
      call check_close('hand PRPLx: rls', a%rl(3), -0.25_wp, 0.0_wp)
      call check_close('hand PRPLx: vln', a%vl(2), -3.0e-20_wp, 1.0e-35_wp)
      call check_close('hand PRPLx: gap', a%gap, -5.0e-11_wp, 1.0e-26_wp)
      call check_close('hand PRPLx: coo3', a%coor(3), -1.0e-6_wp, 1.0e-21_wp)
      call check_close('hand PRPLx: s = t x n', maxval(abs(a%s - cross3(a%t, a%n))), 0.0_wp, 0.0_wp)
      call check_true('hand SPSPx: slifw, law czm01, iadj 4, bodies 10 and 11', b%status == 'slifw' .and. &
                      b%behav == 'czm01' .and. b%iadj == 4 .and. b%icdbdy == 10 .and. b%ianbdy == 11 .and. b%cdver == 0)
      call check_close('hand SPSPx: rlt (second field)', b%rl(1), 2.0_wp, 0.0_wp)
      call check_close('hand SPSPx: rln (third field)', b%rl(2), 3.0_wp, 0.0_wp)
      call check_close('hand SPSPx: rls (first field)', b%rl(3), 1.0_wp, 0.0_wp)
      call check_close('hand SPSPx: vls (first field)', b%vl(3), 4.0_wp, 0.0_wp)
      call check_close('hand SPSPx: gap (gTT =)', b%gap, 7.0_wp, 0.0_wp)
      call check_close('hand SPSPx: n(2)', b%n(2), 1.0_wp, 0.0_wp)
      call check_close('hand SPSPx: coo2', b%coor(2), 1.2_wp, 1.0e-16_wp)
      call check_true('hand SPSPx: 3 internals after the # line', size(b%internals) == 3)
      if (size(b%internals) == 3) call check_close('hand SPSPx: internal 3', b%internals(3), -2.0e-3_wp, 1.0e-18_wp)
    end associate
  end if

  ! 4. store order <-> (t, n, s)
  block
    real(wp) :: fr(3, 3), t1(3), t2(3), n(3), t(3), nn(3), s(3), x(3), xtns(3), fr2(3, 3), x2(3)
    n = [0.36_wp, -0.48_wp, 0.8_wp]
    call tangents_of_normal(n, t1, t2)
    fr(1, :) = t1; fr(2, :) = t2; fr(3, :) = n
    x = [1.0_wp, 2.0_wp, 3.0_wp]
    call vloc3_from_store(fr, x, t, nn, s, xtns)
    call check_close('from store: s = t x n', maxval(abs(s - cross3(t, nn))), 0.0_wp, 1.0e-15_wp)
    call check_close('from store: r.t = r_t1 (x . t in both bases)', &
                     dot_product(xtns, [dot_product(t, matmul(x, fr)), dot_product(nn, matmul(x, fr)), &
                                        dot_product(s, matmul(x, fr))]) - dot_product(x, x), 0.0_wp, 1.0e-14_wp)
    call vloc3_to_store(t, nn, s, xtns, fr2, x2)
    call check_true('to store: the inverse, exact', all(fr2 == fr) .and. all(x2 == x))
  end block
  call test_finish()

contains

  !> A record with a frame from n = (0, 0.8, 0.6) (t = e1, s = t x n).
  function record(inter, number, cdtac, icdtac, antac, cdver, iadj, rl) result(r)
    character(len=5), intent(in) :: inter, cdtac, antac
    integer, intent(in) :: number, icdtac, cdver, iadj
    real(wp), intent(in) :: rl(3)
    type(contact3_record_t) :: r
    r%inter = inter; r%number = number
    r%icdbdy = 1; r%cdtac = cdtac; r%icdtac = icdtac
    r%ianbdy = 2; r%antac = antac; r%iantac = 1
    r%cdver = cdver; r%iadj = iadj
    r%behav = 'iqsc0'; r%status = 'stick'
    r%rl = rl
    r%vl = [-1.0e-19_wp, 2.2e-5_wp, 0.333333333_wp]
    r%gap = 1.0e-9_wp
    r%coor = [1.0_wp, 2.0_wp, 3.0_wp]
    r%t = [1.0_wp, 0.0_wp, 0.0_wp]
    r%n = [0.0_wp, 0.8_wp, 0.6_wp]
    r%s = cross3(r%t, r%n)
  end function record

  logical function same_ids(a, b)
    type(contact3_record_t), intent(in) :: a, b
    same_ids = a%inter == b%inter .and. a%number == b%number .and. a%cdbdy == b%cdbdy .and. a%icdbdy == b%icdbdy &
               .and. a%cdtac == b%cdtac .and. a%icdtac == b%icdtac .and. a%anbdy == b%anbdy .and. &
               a%ianbdy == b%ianbdy .and. a%antac == b%antac .and. a%iantac == b%iantac .and. &
               a%cdver == b%cdver .and. a%iadj == b%iadj .and. a%behav == b%behav .and. a%status == b%status
  end function same_ids

  !> Largest |x - ref| / |ref| over the nonzero ref (|x| for a zero ref).
  real(wp) function rel(x, ref)
    real(wp), intent(in) :: x(:), ref(:)
    integer :: i
    rel = 0.0_wp
    do i = 1, size(x)
      if (ref(i) == 0.0_wp) then
        rel = max(rel, abs(x(i)))
      else
        rel = max(rel, abs(x(i) - ref(i)) / abs(ref(i)))
      end if
    end do
  end function rel

  function file_lines(path) result(l)
    character(len=*), intent(in) :: path
    character(len=120), allocatable :: l(:)
    character(len=120) :: buf
    integer :: u, ios
    allocate (l(0))
    open (newunit=u, file=path, status='old', action='read')
    do
      read (u, '(a)', iostat=ios) buf
      if (ios /= 0) exit
      l = [character(len=120) :: l, buf]
    end do
    close (u)
  end function file_lines

  logical function same_file(a, b)
    character(len=*), intent(in) :: a, b
    character(len=120), allocatable :: la(:), lb(:)
    la = file_lines(a)
    lb = file_lines(b)
    same_file = size(la) == size(lb)
    if (same_file) same_file = all(la == lb)
  end function same_file

  subroutine check_line(k, expected)
    integer, intent(in) :: k
    character(len=*), intent(in) :: expected
    character(len=16) :: label
    write (label, '(a,i0)') 'line ', k
    if (k > size(lines)) then
      call check_true(trim(label)//' exists', .false.)
      return
    end if
    if (trim(lines(k)) /= expected) write (*, '(a/a)') '  got: '//trim(lines(k)), '  ref: '//expected
    call check_true(trim(label)//' as LMGC90 writes it: '//expected(1:min(len(expected), 40)), &
                    trim(lines(k)) == expected)
  end subroutine check_line

  subroutine write_text(path, text)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: text(:)
    integer :: u, i
    open (newunit=u, file=path, status='replace', action='write')
    do i = 1, size(text)
      write (u, '(a)') trim(text(i))
    end do
    close (u)
  end subroutine write_text
end program test_vloc_rloc_3d
