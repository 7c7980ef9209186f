!> Vloc_Rloc.INI / Vloc_Rloc.OUT.n reader, and the column layouts of the
!> interaction id lines shared with the writer (fracas_write_outbox).
!>
!> A record: '$icdan  TYPE  number', a column header line, the id line
!> (bodies, contactors, law, status), the rlt/H rln/H line, the vlt vln line,
!> the gapTT line, optional n(1)= and coo1= lines (label at columns 30-34),
!> then optional lines of internal values, 15-character fields.
module fracas_read_vloc_rloc
  use fracas_kinds, only: wp
  use fracas_ids, only: inter_id, inter_names, n_inter, status_id, status_names, n_status, &
                        i_plplx, i_pljcx, i_dkplx, i_clalp, i_dkalp, i_plalp
  use fracas_deck, only: contact_record_t, body_input_t, law_input_t
  use fracas_read_bodies, only: body_lookup_t, body_lookup, find_body, no_such_body
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, is_blank, check_line_end, &
                                keyword_of, is_data, get_real, get_int, get_word, itoa, get_steps
  implicit none
  private
  public :: read_vloc_rloc_file, vloc_layout_t, vloc_layout, internals_per_line, read_internal_values

  !> Start columns of the fields of an id line (0: field absent). Words and
  !> integers are 5 wide except iadj (w_iadj). cdver/anseg columns hold the
  !> vertex / segment numbers, preceded by the labels 'CDVER' / 'ANSEG' when
  !> cdver_label / anseg_label > 0 (the ALpxx segment of CLALp, DKALp and
  !> PLALp has no label).
  type :: vloc_layout_t
    integer :: cdbdy = 2, icdbdy = 9, cdtac = 16, icdtac = 23
    integer :: cdver_label = 0, cdver = 0
    integer :: behav = 30, anbdy = 37, ianbdy = 44, antac = 51, iantac = 58
    integer :: anseg_label = 0, anseg = 0
    integer :: status = 65, iadj = 72, w_iadj = 5
    integer :: width = 76                   !< length of the id line
    character(len=103) :: header = ' cdbdy  numbr  cdtac  numbr  behav  anbdy  numbr  antac  numbr  sttus   iadj'
    integer :: header_len = 76
    character(len=5) :: rls_label = 'rls/H'
  end type vloc_layout_t

  integer, parameter :: internals_per_line = 6

contains

  !> Layout of the id line of an interaction type (LMGC90's, per type).
  function vloc_layout(inter) result(lay)
    character(len=*), intent(in) :: inter
    type(vloc_layout_t) :: lay
    select case (inter_id(inter))
    case (i_plplx)       ! candidate vertex and antagonist segment
      lay = vloc_layout_t(cdver_label=30, cdver=37, behav=44, anbdy=51, ianbdy=58, antac=65, iantac=72, &
                          anseg_label=79, anseg=86, status=93, iadj=98, w_iadj=6, width=103, &
                          header=' cdbdy  numbr  cdtac  numbr  vertx  numbr  behav  anbdy  numbr  antac  numbr' &
                          //'  segmt  numbr', header_len=90)
    case (i_pljcx)       ! candidate vertex
      lay = vloc_layout_t(cdver_label=30, cdver=37, behav=44, anbdy=51, ianbdy=58, antac=65, iantac=72, &
                          status=93, iadj=98, w_iadj=6, width=103, &
                          header=' cdbdy  numbr  cdtac  numbr  vertx  numbr  behav  anbdy  numbr  antac  numbr' &
                          //'                sttus iadj ', header_len=103)
    case (i_dkplx)       ! vertex number after the antagonist
      lay = vloc_layout_t(cdver_label=65, cdver=72, status=93, iadj=98, w_iadj=6, width=103, &
                          header=' cdbdy  numbr  cdtac  numbr  behav  anbdy  numbr  antac  numbr  vertx  numbr' &
                          //'                sttus iadj ', header_len=103)
    case (i_clalp)       ! antagonist segment (polyline of a mesh)
      lay = vloc_layout_t(anseg=65, status=72, iadj=79, width=83, &
                          header=' cdbdy  numbr  cdtac  numbr  behav  anbdy  numbr  antac  numbr  segmt  sttus   iadj', &
                          header_len=83)
    case (i_dkalp)       ! antagonist segment, status and iadj shifted as in PLJCx
      lay = vloc_layout_t(anseg=65, status=79, iadj=84, w_iadj=6, width=89, &
                          header=' cdbdy  numbr  cdtac  numbr  behav  anbdy  numbr  antac  numbr' &
                          //'                sttus iadj ', header_len=89)
    case (i_plalp)       ! candidate vertex and antagonist segment
      lay = vloc_layout_t(cdver_label=30, cdver=37, behav=44, anbdy=51, ianbdy=58, antac=65, iantac=72, &
                          anseg=79, status=93, iadj=98, w_iadj=6, width=103, &
                          header=' cdbdy  numbr  cdtac  numbr  vertx  numbr  behav  anbdy  numbr  antac  numbr' &
                          //'                sttus iadj ', header_len=103)
    case default         ! DKDKx, DKJCx, DKKDx, CLJCx
      lay = vloc_layout_t()
      if (inter == 'DKKDx') lay%rls_label = 'rls ='
    end select
  end function vloc_layout

  !> Read PATH. If BODIES / LAWS are given, body numbers, contactor ranks and
  !> types and law nicknames are checked against them (error at the id line).
  !> STEPS_LINE returns the line number of '$steps' (0 if absent).
  subroutine read_vloc_rloc_file(path, step, time, records, bodies, laws, steps_line)
    character(len=*), intent(in) :: path
    integer, intent(out) :: step
    real(wp), intent(out) :: time
    type(contact_record_t), allocatable, intent(out) :: records(:)
    type(body_input_t), intent(in), optional :: bodies(:)
    type(law_input_t), intent(in), optional :: laws(:)
    integer, intent(out), optional :: steps_line
    type(text_file_t) :: tf
    type(body_lookup_t) :: lookup
    integer :: i, n
    character(len=5) :: kw

    call load_text(path, tf)
    if (present(bodies)) lookup = body_lookup(bodies)
    step = 0
    time = 0.0_wp
    if (present(steps_line)) steps_line = 0
    n = 0
    do i = 1, tf%n
      if (keyword_of(tf%lines(i)) == 'icdan') n = n + 1
    end do
    allocate (records(n))
    n = 0
    i = 1
    do while (i <= tf%n)
      kw = keyword_of(tf%lines(i))
      select case (kw)
      case ('steps')
        if (present(steps_line)) steps_line = tf%lines(i)%src%line
        call get_steps(tf%lines(i), step, time)
        i = i + 1
      case ('icdan')
        n = n + 1
        call read_record(tf, i, records(n), lookup, bodies, laws)
      case default
        if (tf%lines(i)%text(1:1) == '$') then
          call line_error(tf%lines(i), 1, "unknown keyword '"//trim(field(tf%lines(i), 1, 6))// &
                          "' (expected $steps or $icdan)")
        else
          call line_error(tf%lines(i), 1, "unexpected line: '"//trim(field(tf%lines(i), 1, 40))//"'")
        end if
      end select
    end do
  end subroutine read_vloc_rloc_file

  !> One record from its '$icdan' line (tf%lines(i)); i ends at the next record.
  subroutine read_record(tf, i, r, lookup, bodies, laws)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(contact_record_t), intent(out) :: r
    type(body_lookup_t), intent(in) :: lookup
    type(body_input_t), intent(in), optional :: bodies(:)
    type(law_input_t), intent(in), optional :: laws(:)
    type(vloc_layout_t) :: lay
    integer :: j

    associate (ln => tf%lines(i))
      r%inter = get_word(ln, 9, 13, 'interaction type')
      if (inter_id(r%inter) == 0) call line_error(ln, 9, "unknown interaction type '"//trim(r%inter)// &
                                                  "' (supported: "//name_list(inter_names, n_inter)//')')
      r%number = get_int(ln, 14, max(22, len(ln%text)), 'interaction number')
      lay = vloc_layout(r%inter)
      ! Header line, then the id line.
      if (.not. is_data(tf, i + 1)) call line_error(ln, 1, "expected the column header line (' cdbdy  numbr ...') " &
                                                    //'after $icdan')
      j = i + 1
      ! (indented in LMGC90's older files, e.g. examples/Pre/wall2D/cisaillement_mur)
      if (index(adjustl(tf%lines(j)%text), 'cdbdy ') == 1) j = j + 1
      if (.not. is_data(tf, j)) call line_error(ln, 1, 'expected the id line (bodies, contactors, law, status) of ' &
                                                //trim(r%inter)//' '//itoa(r%number))
    end associate
    associate (ln => tf%lines(j))
      r%src = ln%src
      r%cdbdy = get_word(ln, lay%cdbdy, lay%cdbdy + 4, 'candidate body model')
      r%icdbdy = get_int(ln, lay%icdbdy, lay%icdbdy + 4, 'candidate body number')
      r%cdtac = get_word(ln, lay%cdtac, lay%cdtac + 4, 'candidate contactor type')
      r%icdtac = get_int(ln, lay%icdtac, lay%icdtac + 4, 'candidate contactor number')
      if (lay%cdver > 0) r%cdver = get_int(ln, lay%cdver, lay%cdver + 4, 'vertex number')
      r%behav = get_word(ln, lay%behav, lay%behav + 4, 'contact law nickname')
      r%anbdy = get_word(ln, lay%anbdy, lay%anbdy + 4, 'antagonist body model')
      r%ianbdy = get_int(ln, lay%ianbdy, lay%ianbdy + 4, 'antagonist body number')
      r%antac = get_word(ln, lay%antac, lay%antac + 4, 'antagonist contactor type')
      r%iantac = get_int(ln, lay%iantac, lay%iantac + 4, 'antagonist contactor number')
      if (lay%anseg > 0) r%anseg = get_int(ln, lay%anseg, lay%anseg + 4, 'segment number')
      r%status = get_word(ln, lay%status, lay%status + 4, 'contact status')
      if (status_id(r%status) == 0) call line_error(ln, lay%status, "unknown contact status '"//trim(r%status)// &
                                                    "' (known: "//name_list(status_names, n_status)//')')
      r%iadj = get_int(ln, lay%iadj, lay%iadj + lay%w_iadj - 1, 'iadj')
      if (present(bodies)) call check_bodies(ln, r, bodies, lookup)
      if (present(laws)) call check_law(ln, r, laws)
    end associate
    ! rlt/H rln/H, vlt vln, gapTT.
    j = j + 1
    call need_values(tf, j, 3, r)
    r%rlt = get_real(tf%lines(j), 35, 48, "tangential reaction 'rlt/H'")
    r%rln = get_real(tf%lines(j), 56, 69, "normal reaction 'rln/H'")
    r%vlt = get_real(tf%lines(j + 1), 35, 48, "tangential velocity 'vlt ='")
    r%vln = get_real(tf%lines(j + 1), 56, 69, "normal velocity 'vln ='")
    r%gap = get_real(tf%lines(j + 2), 35, 48, "gap 'gapTT'")
    call check_line_end(tf%lines(j), 90, "the 'rlt/H' line")
    call check_line_end(tf%lines(j + 1), 90, "the 'vlt =' line")
    call check_line_end(tf%lines(j + 2), 48, "the 'gapTT' line")
    j = j + 3
    ! Optional normal and point.
    r%has_geometry = .false.
    if (is_data(tf, j)) then
      if (field(tf%lines(j), 30, 34) == 'n(1)=') then
        r%has_geometry = .true.
        r%normal(1) = get_real(tf%lines(j), 35, 48, "normal 'n(1)='")
        r%normal(2) = get_real(tf%lines(j), 56, 69, "normal 'n(2)='")
        call check_line_end(tf%lines(j), 90, "the 'n(1)=' line")
        j = j + 1
        if (.not. is_data(tf, j)) call line_error(tf%lines(j - 1), 30, "expected the 'coo1=' line after 'n(1)='")
        if (field(tf%lines(j), 30, 34) /= 'coo1=') call line_error(tf%lines(j), 30, &
                                                                 "expected the 'coo1=' line after 'n(1)='")
        r%coor(1) = get_real(tf%lines(j), 35, 48, "contact point 'coo1='")
        r%coor(2) = get_real(tf%lines(j), 56, 69, "contact point 'coo2='")
        call check_line_end(tf%lines(j), 90, "the 'coo1=' line")
        j = j + 1
      end if
    end if
    call read_internal_values(tf, j, r%internals)
    i = j
  end subroutine read_record

  !> The internal values of a record, 15-character fields, from line j up to
  !> the next keyword line (where j ends).
  subroutine read_internal_values(tf, j, values)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: j
    real(wp), allocatable, intent(out) :: values(:)
    real(wp) :: buf(1000)
    integer :: k, n
    n = 0
    do while (is_data(tf, j))
      do k = 1, (len(tf%lines(j)%text) + 14) / 15
        if (is_blank(tf%lines(j), 15 * (k - 1) + 1, 15 * k)) cycle
        n = n + 1
        if (n > size(buf)) call line_error(tf%lines(j), 1, 'too many internal values')
        buf(n) = get_real(tf%lines(j), 15 * (k - 1) + 1, 15 * k, 'internal value '//itoa(n))
      end do
      j = j + 1
    end do
    values = buf(1:n)
  end subroutine read_internal_values

  !> The n lines from j on must be data lines.
  subroutine need_values(tf, j, n, r)
    type(text_file_t), intent(in) :: tf
    integer, intent(in) :: j, n
    type(contact_record_t), intent(in) :: r
    integer :: k
    do k = 0, n - 1
      if (.not. is_data(tf, j + k)) call line_error(tf%lines(j - 1), 1, trim(r%inter)//' '//itoa(r%number)// &
                                                    ': expected the rlt/H, vlt and gapTT lines after the id line')
    end do
  end subroutine need_values

  function name_list(names, n) result(s)
    integer, intent(in) :: n
    character(len=*), intent(in) :: names(n)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, n
      if (k > 1) s = s//', '
      s = s//trim(names(k))
    end do
  end function name_list

  !> Bodies, contactor ranks and types, vertex/segment numbers exist.
  subroutine check_bodies(ln, r, bodies, lookup)
    type(text_line_t), intent(in) :: ln
    type(contact_record_t), intent(in) :: r
    type(body_input_t), intent(in) :: bodies(:)
    type(body_lookup_t), intent(in) :: lookup
    type(vloc_layout_t) :: lay
    integer :: nv, icd, ian
    lay = vloc_layout(r%inter)
    icd = check_side(r%cdbdy, r%icdbdy, r%cdtac, r%icdtac, lay%cdbdy, lay%icdbdy, lay%cdtac, lay%icdtac, 'candidate')
    ian = check_side(r%anbdy, r%ianbdy, r%antac, r%iantac, lay%anbdy, lay%ianbdy, lay%antac, lay%iantac, 'antagonist')
    if (lay%cdver > 0) then
      ! PLPLx/PLJCx/PLALp: a vertex of the candidate polygon; DKPLx: of the antagonist.
      if (r%inter == 'DKPLx') then
        nv = nvert(ian, r%iantac)
      else
        nv = nvert(icd, r%icdtac)
      end if
      if (r%cdver < 0 .or. r%cdver > nv) call line_error(ln, lay%cdver, 'vertex number '//itoa(r%cdver)// &
                                                         ' out of range 0..'//itoa(nv))
    end if
    if (lay%anseg > 0) then
      if (r%antac == 'ALpxx') then
        ! A segment of the antagonist polyline: 1..(nodes - 1).
        nv = size(bodies(ian)%tactors(r%iantac)%nodes) - 1
        if (r%anseg < 1 .or. r%anseg > nv) call line_error(ln, lay%anseg, 'segment number '//itoa(r%anseg)// &
                                                           ' out of range 1..'//itoa(nv)//' (the ALpxx has ' &
                                                           //itoa(nv)//' segments)')
      else
        nv = nvert(ian, r%iantac)
        if (r%anseg < 0 .or. r%anseg > nv) call line_error(ln, lay%anseg, 'segment number '//itoa(r%anseg)// &
                                                           ' out of range 0..'//itoa(nv))
      end if
    end if

  contains

    !> The index in BODIES of one side's body, after checking it and its contactor.
    integer function check_side(model, ib, tac, it, c_model, c_ib, c_tac, c_it, side) result(k)
      character(len=*), intent(in) :: model, tac, side
      integer, intent(in) :: ib, it, c_model, c_ib, c_tac, c_it
      character(len=:), allocatable :: name
      if (model /= 'RBDY2' .and. model /= 'MAILx') call line_error(ln, c_model, side//" body model '"// &
                                                                   trim(model)//"' is not supported (supported: " &
                                                                   //'RBDY2, MAILx)')
      k = find_body(lookup, model, ib)
      if (k == 0) call line_error(ln, c_ib, side//' '//no_such_body(bodies, model, ib))
      name = 'body '//itoa(ib)
      if (.not. all(bodies%model == 'RBDY2')) name = trim(model)//' '//name
      if (it < 1 .or. it > size(bodies(k)%tactors)) &
        call line_error(ln, c_it, side//' contactor '//itoa(it)//' does not exist ('//name//' has ' &
                        //itoa(size(bodies(k)%tactors))//' contactors)')
      if (bodies(k)%tactors(it)%kind /= tac) &
        call line_error(ln, c_tac, side//' contactor '//itoa(it)//' of '//name//' is a ' &
                        //trim(bodies(k)%tactors(it)%kind)//', not a '//trim(tac))
    end function check_side

    integer function nvert(ib, it)
      integer, intent(in) :: ib, it
      nvert = 0
      if (allocated(bodies(ib)%tactors(it)%vertices)) nvert = size(bodies(ib)%tactors(it)%vertices, 2)
    end function nvert
  end subroutine check_bodies

  subroutine check_law(ln, r, laws)
    type(text_line_t), intent(in) :: ln
    type(contact_record_t), intent(in) :: r
    type(law_input_t), intent(in) :: laws(:)
    integer :: k
    type(vloc_layout_t) :: lay
    do k = 1, size(laws)
      if (laws(k)%nickname == r%behav) return
    end do
    lay = vloc_layout(r%inter)
    call line_error(ln, lay%behav, "contact law '"//trim(r%behav)// &
                    "' is not defined in TACT_BEHAV.DAT")
  end subroutine check_law

end module fracas_read_vloc_rloc
