!> Vloc_Rloc.INI / Vloc_Rloc.OUT.n of 3D interactions, in LMGC90's 3D layout.
!> A record: '$icdan  TYPE  number', a column header line, the id line, then
!> lines of 27 blanks and up to three (2 blanks, 5-character label, D14.7)
!> fields (labels at columns 30-34, 51-55, 72-76, values at 35-48, 56-69, 77-90):
!> the reactions 'rlt/H', 'rln/H', 'rls/H' (forces: impulse / H), the relative
!> velocities 'vlt =', 'vln =', 'vls =', the gap ('gTT =' or 'gapTT'), the
!> contact point 'coo1=' and the frame 't(1)=', 'n(1)=', 's(1)=' (s = t x n),
!> then optional internal values (15-character fields, after a '#' line).
!> LMGC90's 3D modules do not agree on the order of these lines (its
!> mod_SPSPx, SPPLx, CDPLx, SPCDx write s, t, n (rls first) and 'gTT =', its
!> PRPRx, SPPRx t, n, s and 'gapTT', PRPLx rls first and 'gapTT', the frame
!> before or after the point) nor on the id line (CDVER column, iadj); each
!> reads its own order by position. vloc3_layout gives each type's order,
!> which the writer follows; the reader goes by the labels, so it takes every
!> one of those orders (and LMGC90's older files). Not read: the "xxl" id
!> lines (7-digit numbers, more than 99999 contacts).
!> The store keeps (t1, t2, n), right-handed: t1 x t2 = n. LMGC90's (t, n, s)
!> with s = t x n is t = t1, s = -t2 (vloc3_from_store, vloc3_to_store).
module fracas_vloc_rloc_3d
  use fracas_kinds, only: wp
  use fracas_deck, only: source_t
  use fracas_ids, only: status_id
  use fracas_read_vloc_rloc, only: read_internal_values
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, is_blank, &
                                keyword_of, is_data, get_real, get_int, get_word, itoa, get_steps, check_line_end
  implicit none
  private
  public :: contact3_record_t, vloc3_layout_t, vloc3_layout, read_vloc_rloc_3d, write_vloc3_record, &
            vloc3_from_store, vloc3_to_store

  !> One 3D interaction of a Vloc_Rloc file, in LMGC90's terms.
  type :: contact3_record_t
    character(len=5) :: inter = ''           !< 'SPSPx', 'SPPLx', 'PRPLx', 'SPPRx', 'PRPRx', ...
    integer :: number = 0                    !< icdan
    character(len=5) :: cdbdy = 'RBDY3', cdtac = '', anbdy = 'RBDY3', antac = ''
    integer :: icdbdy = 0, icdtac = 0, ianbdy = 0, iantac = 0
    integer :: cdver = 0                     !< CDVER column (PRPRx, PRPLx), 0 if none
    character(len=5) :: behav = ''
    character(len=5) :: status = 'noctc'
    integer :: iadj = 0                      !< trailing column of SPSPx, SPPLx, SPCDx
    real(wp) :: rl(3) = 0.0_wp               !< rlt/H, rln/H, rls/H (forces)
    real(wp) :: vl(3) = 0.0_wp               !< vlt, vln, vls
    real(wp) :: gap = 0.0_wp
    !> point and frame lines read (each optional on reading, as LMGC90)
    logical :: has_coor = .false., has_t = .false., has_n = .false., has_s = .false.
    real(wp) :: coor(3) = 0.0_wp, t(3) = 0.0_wp, n(3) = 0.0_wp, s(3) = 0.0_wp
    real(wp), allocatable :: internals(:)
    type(source_t) :: src
  end type contact3_record_t

  !> How LMGC90 writes one interaction type: the component order of the
  !> reaction and velocity lines (a permutation of t = 1, n = 2, s = 3), the
  !> gap label, the order of the vector lines (c = coo, t, n, s), the CDVER
  !> integer at columns 30-34 (or 9 blanks) and the trailing iadj (79-83).
  type :: vloc3_layout_t
    integer :: order(3) = [3, 1, 2]
    character(len=5) :: gap_label = 'gTT ='
    character(len=4) :: vectors = 'stnc'
    logical :: cdver = .false., iadj = .true., behav_at_30 = .false.
  end type vloc3_layout_t

  character(len=5), parameter :: r_labels(3) = ['rlt/H', 'rln/H', 'rls/H']
  character(len=5), parameter :: v_labels(3) = ['vlt =', 'vln =', 'vls =']
  character(len=*), parameter :: fmt_vals = '(27x,3(2x,a5,d14.7))'

contains

  !> LMGC90's layout of an interaction type (its mod_<TYPE>.f90 writer).
  pure function vloc3_layout(inter) result(lay)
    character(len=*), intent(in) :: inter
    type(vloc3_layout_t) :: lay
    select case (inter)
    case ('PRPRx')
      lay = vloc3_layout_t(order=[1, 2, 3], gap_label='gapTT', vectors='ctns', cdver=.true., iadj=.false.)
    case ('PRPLx')
      lay = vloc3_layout_t(order=[3, 1, 2], gap_label='gapTT', vectors='ctns', cdver=.true., iadj=.false.)
    case ('SPPRx')
      lay = vloc3_layout_t(order=[1, 2, 3], gap_label='gapTT', vectors='ctns', iadj=.false., behav_at_30=.true.)
    case ('SPCDx')
      lay = vloc3_layout_t(vectors='tnsc')
    case ('CDPLx')
      lay = vloc3_layout_t(iadj=.false.)
    case default          ! SPSPx, SPPLx
      lay = vloc3_layout_t()
    end select
  end function vloc3_layout

  !> One record's lines (the '$icdan' line to the blank line after it), written to unit u.
  subroutine write_vloc3_record(u, r)
    integer, intent(in) :: u
    type(contact3_record_t), intent(in) :: r
    type(vloc3_layout_t) :: lay
    character(len=83) :: id
    integer :: k, o(3)
    lay = vloc3_layout(r%inter)
    o = lay%order
    write (u, '(a6,2x,a5,2x,i7)') '$icdan', r%inter, r%number
    if (lay%behav_at_30) then
      write (u, '(a)') ' cdbdy  numbr  cdtac  numbr  behav  anbdy  numbr  antac  numbr  sttus'
      write (id, '(1x,a5,2x,i5,2x,a5,2x,i5,2x,a5,2x,a5,2x,i5,2x,a5,2x,i5,2x,a5)') r%cdbdy, r%icdbdy, r%cdtac, &
        r%icdtac, r%behav, r%anbdy, r%ianbdy, r%antac, r%iantac, r%status
    else
      write (u, '(a)') ' cdbdy  numbr  cdtac  numbr  CDVER  behav  anbdy  numbr  antac  numbr  sttus'
      write (id, '(1x,a5,2x,i5,2x,a5,2x,i5,9x,a5,2x,a5,2x,i5,2x,a5,2x,i5,2x,a5)') r%cdbdy, r%icdbdy, r%cdtac, &
        r%icdtac, r%behav, r%anbdy, r%ianbdy, r%antac, r%iantac, r%status
      if (lay%cdver) write (id(30:34), '(i5)') r%cdver
      if (lay%iadj) write (id(77:83), '(2x,i5)') r%iadj
    end if
    write (u, '(a)') trim(id)
    write (u, fmt_vals) (r_labels(o(k)), r%rl(o(k)), k=1, 3)
    write (u, fmt_vals) (v_labels(o(k)), r%vl(o(k)), k=1, 3)
    write (u, fmt_vals) lay%gap_label, r%gap
    do k = 1, 4
      select case (lay%vectors(k:k))
      case ('c')
        write (u, fmt_vals) 'coo1=', r%coor(1), 'coo2=', r%coor(2), 'coo3=', r%coor(3)
      case ('t')
        write (u, fmt_vals) 't(1)=', r%t(1), 't(2)=', r%t(2), 't(3)=', r%t(3)
      case ('n')
        write (u, fmt_vals) 'n(1)=', r%n(1), 'n(2)=', r%n(2), 'n(3)=', r%n(3)
      case ('s')
        write (u, fmt_vals) 's(1)=', r%s(1), 's(2)=', r%s(2), 's(3)=', r%s(3)
      end select
    end do
  end subroutine write_vloc3_record

  !> Read a 3D Vloc_Rloc file: its step and time, and its records.
  subroutine read_vloc_rloc_3d(path, step, time, records)
    character(len=*), intent(in) :: path
    integer, intent(out) :: step
    real(wp), intent(out) :: time
    type(contact3_record_t), allocatable, intent(out) :: records(:)
    type(text_file_t) :: tf
    integer :: i, n
    call load_text(path, tf)
    step = 0
    time = 0.0_wp
    n = count([(keyword_of(tf%lines(i)) == 'icdan', i=1, tf%n)])
    allocate (records(n))
    n = 0
    i = 1
    do while (i <= tf%n)
      select case (keyword_of(tf%lines(i)))
      case ('steps')
        call get_steps(tf%lines(i), step, time)
        i = i + 1
      case ('icdan')
        n = n + 1
        call read_record(tf, i, records(n))
      case default
        call line_error(tf%lines(i), 1, "unexpected line '"//trim(field(tf%lines(i), 1, 40))// &
                        "' (expected $steps or $icdan)")
      end select
    end do
  end subroutine read_vloc_rloc_3d

  !> One record from its '$icdan' line (tf%lines(i)); i ends at the next record.
  subroutine read_record(tf, i, r)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(contact3_record_t), intent(out) :: r
    type(vloc3_layout_t) :: lay
    integer :: j, k, c0
    real(wp) :: v(3)
    character(len=5) :: label
    associate (ln => tf%lines(i))
      r%inter = get_word(ln, 9, 13, 'interaction type')
      r%number = get_int(ln, 14, max(22, len(ln%text)), 'interaction number')
    end associate
    lay = vloc3_layout(r%inter)
    j = i + 1
    if (is_data(tf, j)) then
      if (index(adjustl(tf%lines(j)%text), 'cdbdy ') == 1) j = j + 1
    end if
    if (.not. is_data(tf, j)) call line_error(tf%lines(j - 1), 1, 'expected the id line (bodies, contactors, ' &
                                              //'law, status) of '//r%inter//' '//itoa(r%number))
    associate (ln => tf%lines(j))
      r%src = ln%src
      r%cdbdy = get_word(ln, 2, 6, 'candidate body model')
      r%icdbdy = get_int(ln, 9, 13, 'candidate body number')
      r%cdtac = get_word(ln, 16, 20, 'candidate contactor type')
      r%icdtac = get_int(ln, 23, 27, 'candidate contactor number')
      c0 = 37
      if (lay%behav_at_30) then
        c0 = 30
      else if (.not. is_blank(ln, 30, 34)) then
        r%cdver = get_int(ln, 30, 34, 'CDVER')
      end if
      r%behav = get_word(ln, c0, c0 + 4, 'contact law nickname')
      r%anbdy = get_word(ln, c0 + 7, c0 + 11, 'antagonist body model')
      r%ianbdy = get_int(ln, c0 + 14, c0 + 18, 'antagonist body number')
      r%antac = get_word(ln, c0 + 21, c0 + 25, 'antagonist contactor type')
      r%iantac = get_int(ln, c0 + 28, c0 + 32, 'antagonist contactor number')
      r%status = get_word(ln, c0 + 35, c0 + 39, 'contact status')
      if (status_id(r%status) == 0) call line_error(ln, c0 + 35, "unknown contact status '"//trim(r%status)//"'")
      if (.not. is_blank(ln, c0 + 42, c0 + 46)) r%iadj = get_int(ln, c0 + 42, c0 + 46, 'iadj')
    end associate
    ! reactions, velocities, gap: by their labels
    j = j + 1
    call labelled(j, r_labels, r%rl, 'reaction')
    call labelled(j + 1, v_labels, r%vl, 'velocity')
    if (.not. is_data(tf, j + 2)) call line_error(tf%lines(j + 1), 1, 'expected the gap line (gTT = or gapTT)')
    label = field(tf%lines(j + 2), 30, 34)
    if (label /= 'gTT =' .and. label /= 'gapTT') call line_error(tf%lines(j + 2), 30, &
                                                                 "expected the gap label 'gTT =' or 'gapTT', found '"//label//"'")
    r%gap = get_real(tf%lines(j + 2), 35, 48, 'gap')
    call check_line_end(tf%lines(j + 2), 48, 'the gap line')
    j = j + 3
    ! point and frame lines, in any order, each optional
    do while (is_data(tf, j))
      label = field(tf%lines(j), 30, 34)
      if (all(label /= ['coo1=', 't(1)=', 'n(1)=', 's(1)='])) exit
      do k = 1, 3
        v(k) = get_real(tf%lines(j), 35 + 21 * (k - 1), 48 + 21 * (k - 1), label(1:1)//' component '//itoa(k))
      end do
      call check_line_end(tf%lines(j), 90, "the '"//label//"' line")
      select case (label(1:1))
      case ('c')
        r%coor = v; r%has_coor = .true.
      case ('t')
        r%t = v; r%has_t = .true.
      case ('n')
        r%n = v; r%has_n = .true.
      case ('s')
        r%s = v; r%has_s = .true.
      end select
      j = j + 1
    end do
    call read_internal_values(tf, j, r%internals)
    i = j

  contains

    !> Line jj: three values, each placed by its label (one of labels, any order).
    subroutine labelled(jj, labels, x, what)
      integer, intent(in) :: jj
      character(len=5), intent(in) :: labels(3)
      real(wp), intent(out) :: x(3)
      character(len=*), intent(in) :: what
      integer :: f, m
      logical :: seen(3)
      if (.not. is_data(tf, jj)) call line_error(tf%lines(jj - 1), 1, 'expected the '//what//' line ('// &
                                                 labels(1)//' '//labels(2)//' '//labels(3)//') of '//r%inter//' '// &
                                                 itoa(r%number))
      seen = .false.
      do f = 0, 2
        label = field(tf%lines(jj), 30 + 21 * f, 34 + 21 * f)
        m = findloc(labels, label, dim=1)
        if (m == 0) call line_error(tf%lines(jj), 30 + 21 * f, 'expected one of '//labels(1)//', '//labels(2)// &
                                    ', '//labels(3)//", found '"//label//"'")
        if (seen(m)) call line_error(tf%lines(jj), 30 + 21 * f, "'"//label//"' given twice")
        seen(m) = .true.
        x(m) = get_real(tf%lines(jj), 35 + 21 * f, 48 + 21 * f, label)
      end do
      call check_line_end(tf%lines(jj), 90, 'the '//what//' line')
    end subroutine labelled
  end subroutine read_record

  !> LMGC90's (t, n, s) from the store's frame (rows t1, t2, n) and a vector
  !> in store order (t1, t2, n): t = t1, s = t x n = -t2.
  pure subroutine vloc3_from_store(frame, x, t, n, s, xtns)
    real(wp), intent(in) :: frame(3, 3), x(3)
    real(wp), intent(out) :: t(3), n(3), s(3), xtns(3)
    t = frame(1, :)
    n = frame(3, :)
    s = -frame(2, :)
    xtns = [x(1), x(3), -x(2)]
  end subroutine vloc3_from_store

  !> The inverse: store frame (rows t1, t2, n) and store-order vector from (t, n, s).
  pure subroutine vloc3_to_store(t, n, s, xtns, frame, x)
    real(wp), intent(in) :: t(3), n(3), s(3), xtns(3)
    real(wp), intent(out) :: frame(3, 3), x(3)
    frame(1, :) = t
    frame(2, :) = -s
    frame(3, :) = n
    x = [xtns(1), -xtns(3), xtns(2)]
  end subroutine vloc3_to_store
end module fracas_vloc_rloc_3d
