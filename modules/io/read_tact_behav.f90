!> TACT_BEHAV.DAT reader: contact laws ($behav: nickname, law name, law
!> specific parameter lines) and the visibility table ($seety rules with their
!> alert distance and optional '+' global alert line).
!>
!> Parameter lines: the law line and its continuation lines (columns 1-38
!> blank) carry one value (label 41-45, value 46-59) or two values (second
!> label 62-66, value 67-80). How many lines and values per line is fixed per
!> law, as in LMGC90; the table below gives it, '/' separating lines.
module fracas_read_tact_behav
  use fracas_kinds, only: wp
  use fracas_deck, only: law_input_t, see_rule_input_t
  use fracas_errors, only: input_error, warn
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, check_line_end, &
                                is_blank, keyword_of, is_data, get_real, get_word, itoa, rtoa, parse_real
  implicit none
  private
  public :: read_tact_behav, law_param_count, law_param_names, known_laws

  !> The laws of TACT_BEHAV.DAT: the reader reads them all, the solver runs those
  !> marked solver (fracas_contact_laws: law_from_input; its message lists them).
  type :: law_spec_t
    character(len=30) :: name
    character(len=60) :: layout    !< parameter names, '/' between lines
    logical :: solver              !< the solver runs it
  end type law_spec_t

  integer, parameter :: n_specs = 29
  type(law_spec_t), parameter :: specs(n_specs) = [ &
    law_spec_t('IQS_CLB', 'fric', .true.), &
    law_spec_t('IQS_CLB_g0', 'fric', .true.), &
    law_spec_t('GAP_SGR_CLB', 'fric', .true.), &
    law_spec_t('VEL_SGR_CLB', 'fric', .true.), &
    law_spec_t('IQS_DS_CLB', 'dfric sfric', .true.), &
    law_spec_t('GAP_SGR_DS_CLB', 'dfric sfric', .true.), &
    law_spec_t('VEL_SGR_DS_CLB', 'dfric sfric', .false.), &
    law_spec_t('RST_CLB', 'restn restt/fric', .true.), &
    law_spec_t('RST_DS_CLB', 'restn restt/dfric sfric', .true.), &
    law_spec_t('ELASTIC_REPELL_CLB', 'stiff/fric', .true.), &
    law_spec_t('VISCO_ELASTIC_REPELL_CLB', 'stiff etan/fric', .true.), &
    law_spec_t('IQS_WET_DS_CLB', 'cohn coht/wethk/dfric sfric', .false.), &
    law_spec_t('MAC_CZM', 'dfric sfric/cn ct/visco w', .true.), &
    law_spec_t('IQS_MAC_CZM', 'dfric sfric/cn ct/visco w', .true.), &
    law_spec_t('MP_CZM', 'dfric sfric/cn ct/w', .false.), &
    law_spec_t('MP3_CZM', 'dfric sfric/cn ct/smax w', .true.), &
    law_spec_t('MAL_CZM', 'dfric sfric/cn ct/s1 s2/G1 G2', .true.), &
    law_spec_t('IQS_MAL_CZM', 'dfric sfric/cn ct/s1 s2/G1 G2', .true.), &
    law_spec_t('TH_CZM', 'dfric sfric/cn ct/s1 s2/G1 G2/dp1 dp2', .true.), &
    law_spec_t('IQS_TH_CZM', 'dfric sfric/cn ct/s1 s2/G1 G2/dp1 dp2', .true.), &
    law_spec_t('EXPO_CZM', 'dfric sfric/cn ct/s1 s2/G1 G2/eta', .true.), &
    law_spec_t('IQS_EXPO_CZM', 'dfric sfric/cn ct/s1 s2/G1 G2/eta', .true.), &
    law_spec_t('ABP_CZM', 'dfric sfric/cn ct/s1 s2/G1 G2/du1 du2/phi', .true.), &
    law_spec_t('IQS_ABP_CZM', 'dfric sfric/cn ct/s1 s2/G1 G2/du1 du2/phi', .true.), &
    law_spec_t('IQS_STICK', '', .false.), &
    law_spec_t('COUPLED_DOF', '', .true.), &
    law_spec_t('GAP_SGR_STICK', '', .false.), &
    law_spec_t('ER_MAC_CZM', 'dfric sfric/cn ct/visco w', .false.), &
    law_spec_t('postGAP_IQS_MAC_CZM', 'dfric sfric/cn ct/visco w', .false.)]

  integer, parameter :: max_lines = 8

contains

  !> Comma separated names of the laws read (with solver: those the solver runs).
  function known_laws(solver) result(s)
    logical, intent(in), optional :: solver
    character(len=:), allocatable :: s
    integer :: k
    logical :: only_solver
    only_solver = .false.
    if (present(solver)) only_solver = solver
    s = ''
    do k = 1, n_specs
      if (only_solver .and. .not. specs(k)%solver) cycle
      if (len(s) > 0) s = s//', '
      s = s//trim(specs(k)%name)
    end do
  end function known_laws

  integer function spec_index(name)
    character(len=*), intent(in) :: name
    integer :: k
    spec_index = 0
    do k = 1, n_specs
      if (trim(specs(k)%name) == trim(name)) spec_index = k
    end do
  end function spec_index

  !> Number of parameters of a law, -1 if the law is unknown.
  integer function law_param_count(name)
    character(len=*), intent(in) :: name
    integer :: k, nl, per(max_lines)
    k = spec_index(name)
    law_param_count = -1
    if (k == 0) return
    call split_layout(specs(k)%layout, nl, per)
    law_param_count = sum(per(1:nl))
  end function law_param_count

  !> Parameter names of a law in order (e.g. 'dfric sfric cn ct visco w'),
  !> '' for an unknown law or a law without parameters.
  function law_param_names(name) result(s)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: s
    integer :: k, j
    s = ''
    k = spec_index(name)
    if (k == 0) return
    s = trim(specs(k)%layout)
    do j = 1, len(s)
      if (s(j:j) == '/') s(j:j) = ' '
    end do
  end function law_param_names

  !> Number of lines and values per line of a layout string.
  pure subroutine split_layout(layout, nl, per)
    character(len=*), intent(in) :: layout
    integer, intent(out) :: nl, per(max_lines)
    integer :: j
    logical :: in_word
    per = 0
    nl = 0
    if (len_trim(layout) == 0) return
    nl = 1
    in_word = .false.
    do j = 1, len_trim(layout)
      select case (layout(j:j))
      case ('/')
        nl = nl + 1
        in_word = .false.
      case (' ')
        in_word = .false.
      case default
        if (.not. in_word) per(nl) = per(nl) + 1
        in_word = .true.
      end select
    end do
  end subroutine split_layout

  !> The k-th blank/'/' separated name of a layout.
  function layout_word(layout, k) result(w)
    character(len=*), intent(in) :: layout
    integer, intent(in) :: k
    character(len=:), allocatable :: w
    integer :: j, n, start
    logical :: in_word
    n = 0
    w = '?'
    in_word = .false.
    start = 1
    do j = 1, len_trim(layout) + 1
      if (j <= len_trim(layout)) then
        if (layout(j:j) /= ' ' .and. layout(j:j) /= '/') then
          if (.not. in_word) start = j
          in_word = .true.
          cycle
        end if
      end if
      if (in_word) then
        n = n + 1
        if (n == k) then
          w = layout(start:j - 1)
          return
        end if
      end if
      in_word = .false.
    end do
  end function layout_word

  subroutine read_tact_behav(path, laws, see_rules)
    character(len=*), intent(in) :: path
    type(law_input_t), allocatable, intent(out) :: laws(:)
    type(see_rule_input_t), allocatable, intent(out) :: see_rules(:)
    type(text_file_t) :: tf
    integer :: i, j, nl, ns, k, m
    character(len=5) :: kw
    logical :: found

    call load_text(path, tf)
    nl = 0
    ns = 0
    do i = 1, tf%n
      kw = keyword_of(tf%lines(i))
      if (kw == 'behav') nl = nl + 1
      if (kw == 'seety') ns = ns + count_rule_lines(tf, i)
    end do
    allocate (laws(nl), see_rules(ns))
    nl = 0
    ns = 0
    i = 1
    do while (i <= tf%n)
      kw = keyword_of(tf%lines(i))
      select case (kw)
      case ('behav')
        if (.not. is_data(tf, i + 1)) &
          call line_error(tf%lines(i), 1, "'$behav' must be followed by a law line (nickname, law name, parameters)")
        i = i + 1
        ! LMGC90 reads a law no see rule uses without complaint (its example decks
        ! carry such laws unknown here or in an older layout): skip it, say so.
        if (.not. used(field(tf%lines(i), 2, 6)) .and. .not. readable(tf, i)) then
          call warn(tf%lines(i)%src%file//':'//itoa(tf%lines(i)%src%line)//": contact law '"// &
                    trim(field(tf%lines(i), 2, 6))//"' ("//trim(field(tf%lines(i), 9, 38))// &
                    ") is used by no see rule and not in a layout Fracas reads: skipped")
          do while (is_data(tf, i))
            i = i + 1
          end do
          cycle
        end if
        nl = nl + 1
        j = i
        call read_law(tf, i, laws(nl))
        do k = 1, nl - 1
          if (laws(k)%nickname == laws(nl)%nickname) &
            call line_error(tf%lines(j), 2, "contact law nickname '"//trim(laws(nl)%nickname)// &
                            "' is defined twice (first at line "//itoa(laws(k)%src%line)//')')
        end do
      case ('seety')
        i = i + 1
        if (i <= tf%n) then
          if (field(tf%lines(i), 2, 6) == 'cdbdy') i = i + 1
        end if
        do while (is_data(tf, i))
          if (tf%lines(i)%text(1:1) == '+') then
            if (ns == 0) call line_error(tf%lines(i), 1, "a '+' global alert line must follow a $seety rule")
            see_rules(ns)%global_alert = get_real(tf%lines(i), 55, 68, 'global alert distance')
            call check_line_end(tf%lines(i), 68, "the '+' global alert line")
            if (see_rules(ns)%global_alert < 0.0_wp) call line_error(tf%lines(i), 55, &
                                        'the global alert distance must be >= 0, found '//rtoa(see_rules(ns)%global_alert))
          else
            ns = ns + 1
            call read_rule(tf%lines(i), see_rules(ns))
          end if
          i = i + 1
        end do
      case default
        if (tf%lines(i)%text(1:1) == '$') then
          call line_error(tf%lines(i), 1, "unknown keyword '"//trim(field(tf%lines(i), 1, 6))// &
                          "' (expected $behav or $seety)")
        else
          call line_error(tf%lines(i), 1, "expected '$behav' or '$seety', found '"// &
                          trim(field(tf%lines(i), 1, 40))//"'")
        end if
      end select
    end do
    laws = laws(1:nl)

    ! Every rule names a law of this file; no rule given twice.
    do j = 1, ns
      found = .false.
      do k = 1, nl
        if (laws(k)%nickname == see_rules(j)%behav) found = .true.
      end do
      if (.not. found) call input_error(see_rules(j)%src%file, see_rules(j)%src%line, 23, &
                                           "see rule names contact law '"//trim(see_rules(j)%behav)// &
                                           "', which no $behav of this file defines (defined: "//nick_list(laws)//')')
      do m = 1, j - 1
        if (same_pair(see_rules(m), see_rules(j))) &
          call input_error(see_rules(j)%src%file, see_rules(j)%src%line, 2, &
                              'this see rule repeats the one at line '//itoa(see_rules(m)%src%line)// &
                              ' (same candidate and antagonist)')
      end do
    end do
  contains

    !> Some $seety rule of the file names the law nickname nick.
    logical function used(nick)
      character(len=*), intent(in) :: nick
      integer :: l
      used = .false.
      do l = 1, tf%n
        if (keyword_of(tf%lines(l)) /= 'seety') cycle
        do m = l + 1, tf%n
          if (.not. is_data(tf, m)) exit
          if (field(tf%lines(m), 23, 27) == nick .and. field(tf%lines(m), 2, 6) /= 'cdbdy') used = .true.
        end do
      end do
    end function used
  end subroutine read_tact_behav

  !> The law at line i is one read_law reads without error: a known law, its
  !> parameter lines (as many as it takes) with a number in each value field
  !> and nothing past the last one.
  logical function readable(tf, i)
    type(text_file_t), intent(in) :: tf
    integer, intent(in) :: i
    integer :: k, nlines, per(max_lines), l
    real(wp) :: x
    character(len=:), allocatable :: msg
    readable = .false.
    k = spec_index(field(tf%lines(i), 9, 38))
    if (k == 0) return
    call split_layout(specs(k)%layout, nlines, per)
    do l = 1, max(nlines, 1)
      if (.not. is_data(tf, i + l - 1)) return
    end do
    if (is_data(tf, i + max(nlines, 1))) return
    do l = 1, nlines
      associate (pl => tf%lines(i + l - 1))
        if (l > 1 .and. .not. is_blank(pl, 1, 38)) return
        if (.not. parse_real(field(pl, 46, 59), x, msg)) return
        if (per(l) == 2) then
          if (.not. parse_real(field(pl, 67, 80), x, msg)) return
        end if
        if (len_trim(pl%text) > merge(80, 59, per(l) == 2)) return
      end associate
    end do
    readable = .true.
  end function readable

  logical function same_pair(a, b)
    type(see_rule_input_t), intent(in) :: a, b
    same_pair = a%cdbdy == b%cdbdy .and. a%cdtac == b%cdtac .and. a%cdcol == b%cdcol .and. &
                a%anbdy == b%anbdy .and. a%antac == b%antac .and. a%ancol == b%ancol
  end function same_pair

  function nick_list(laws) result(s)
    type(law_input_t), intent(in) :: laws(:)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, size(laws)
      if (k > 1) s = s//', '
      s = s//trim(laws(k)%nickname)
    end do
    if (len(s) == 0) s = 'none'
  end function nick_list

  !> Number of rule lines (not header, not '+') after the $seety line i.
  integer function count_rule_lines(tf, i) result(n)
    type(text_file_t), intent(in) :: tf
    integer, intent(in) :: i
    integer :: j
    n = 0
    j = i + 1
    if (j <= tf%n) then
      if (field(tf%lines(j), 2, 6) == 'cdbdy') j = j + 1
    end if
    do while (is_data(tf, j))
      if (tf%lines(j)%text(1:1) /= '+') n = n + 1
      j = j + 1
    end do
  end function count_rule_lines

  !> The law line is tf%lines(i); i ends at the line after its parameters.
  subroutine read_law(tf, i, law)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(law_input_t), intent(out) :: law
    integer :: k, nlines, per(max_lines), l, np, ip
    character(len=:), allocatable :: desc

    associate (ln => tf%lines(i))
      law%src = ln%src
      law%nickname = get_word(ln, 2, 6, 'contact law nickname')
      law%name = get_word(ln, 9, 38, 'contact law name')
      k = spec_index(law%name)
      if (k == 0) call line_error(ln, 9, "unknown contact law '"//trim(law%name)//"' (known: "//known_laws()//')')
      call split_layout(specs(k)%layout, nlines, per)
      np = sum(per(1:nlines))
      desc = trim(law%name)//' takes '//itoa(nlines)//' parameter line(s): '//trim(specs(k)%layout)
      allocate (law%params(np), law%param_labels(np), law%param_lines(np), law%param_cols(np))
      law%param_labels = ''
      ip = 0
      do l = 1, nlines
        if (l > 1) then
          if (.not. is_data(tf, i + l - 1)) call line_error(ln, 9, desc//'; found '//itoa(l - 1))
          if (.not. is_blank(tf%lines(i + l - 1), 1, 38)) call line_error(tf%lines(i + l - 1), 1, &
                                  'expected a parameter continuation line of '//trim(law%name)//' (columns 1-38 blank)')
        end if
        associate (pl => tf%lines(i + l - 1))
          ip = ip + 1
          law%param_labels(ip) = field(pl, 41, 45)
          law%params(ip) = get_real(pl, 46, 59, "parameter '"//layout_word(specs(k)%layout, ip)//"' of "//trim(law%name))
          law%param_lines(ip) = pl%src%line
          law%param_cols(ip) = 46
          if (per(l) == 2) then
            ip = ip + 1
            law%param_labels(ip) = field(pl, 62, 66)
            law%params(ip) = get_real(pl, 67, 80, "parameter '"//layout_word(specs(k)%layout, ip)//"' of "// &
                                      trim(law%name))
            law%param_lines(ip) = pl%src%line
            law%param_cols(ip) = 67
          end if
          call check_line_end(pl, merge(80, 59, per(l) == 2), 'a parameter line of '//trim(law%name))
        end associate
      end do
      i = i + max(nlines, 1)
      if (is_data(tf, i)) call line_error(tf%lines(i), 1, 'unexpected line after the parameters of law '// &
                                          trim(law%nickname)//' ('//desc//')')
    end associate
  end subroutine read_law

  subroutine read_rule(ln, r)
    type(text_line_t), intent(in) :: ln
    type(see_rule_input_t), intent(out) :: r
    r%src = ln%src
    r%cdbdy = get_word(ln, 2, 6, 'candidate body model (cdbdy)')
    r%cdtac = get_word(ln, 9, 13, 'candidate contactor type (cdtac)')
    r%cdcol = get_word(ln, 16, 20, 'candidate colour (cdcol)')
    r%behav = get_word(ln, 23, 27, 'contact law nickname (behav)')
    r%anbdy = get_word(ln, 30, 34, 'antagonist body model (anbdy)')
    r%antac = get_word(ln, 37, 41, 'antagonist contactor type (antac)')
    r%ancol = get_word(ln, 44, 48, 'antagonist colour (ancol)')
    r%alert = get_real(ln, 55, 68, 'alert distance')
    call check_line_end(ln, 68, 'the see rule')
    if (r%alert < 0.0_wp) call line_error(ln, 55, 'the alert distance must be >= 0, found '//rtoa(r%alert))
  end subroutine read_rule
end module fracas_read_tact_behav
