!> The one text layer under every DATBOX reader: a file is loaded into memory
!> as its data lines (LMGC90 comment lines, '!' or '#' in column 1, and blank
!> lines are dropped) with their line numbers; values are taken from fixed
!> columns by get_real / get_int / get_word, which stop the run with
!> "FILE:LINE:COL: expected ..." on bad input. parse_real / parse_int are the
!> underlying number parsers, also used for free-format files.
module fracas_datbox_text
  use fracas_kinds, only: wp
  use fracas_errors, only: input_error
  use fracas_deck, only: source_t
  use fracas_files, only: file_exists
  use fracas_strings, only: lower, upper, itoa, rtoa
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: ieee_exceptions, only: ieee_overflow, ieee_get_halting_mode, ieee_set_halting_mode, &
                                           ieee_set_flag
  implicit none
  private
  public :: text_line_t, text_file_t, load_text, line_error, &
            field, is_blank, keyword_of, is_data, get_real, get_int, get_word, &
            parse_real, parse_int, lower, upper, itoa, rtoa, cols, get_steps, check_line_end, edit_distance

  !> One data line: its text (trailing blanks removed) and where it was read.
  type :: text_line_t
    character(len=:), allocatable :: text
    type(source_t) :: src
  end type text_line_t

  !> A loaded file: path as given (used in messages) and its data lines.
  type :: text_file_t
    character(len=:), allocatable :: path
    integer :: n = 0
    type(text_line_t), allocatable :: lines(:)
  end type text_file_t

contains

  !> Load PATH. With keep_comments, '!'/'#' lines are kept (free-format files
  !> handle their own comments); blank lines are always dropped.
  !> A missing or unreadable file is an input error naming the path.
  subroutine load_text(path, tf, keep_comments)
    character(len=*), intent(in) :: path
    type(text_file_t), intent(out) :: tf
    logical, intent(in), optional :: keep_comments
    character(len=:), allocatable :: buf
    integer :: unit, ios, fsize, i, start, stop_, lnum, n
    logical :: keep
    character(len=256) :: iomsg

    keep = .false.
    if (present(keep_comments)) keep = keep_comments
    tf%path = path
    if (.not. file_exists(path)) call input_error(path, 0, 0, 'file not found')
    open (newunit=unit, file=path, access='stream', form='unformatted', status='old', &
          action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) call input_error(path, 0, 0, 'cannot open file: '//trim(iomsg))
    inquire (unit=unit, size=fsize)
    if (fsize < 0) fsize = 0
    allocate (character(len=fsize) :: buf)
    if (fsize > 0) then
      read (unit, iostat=ios, iomsg=iomsg) buf
      if (ios /= 0) call input_error(path, 0, 0, 'cannot read file: '//trim(iomsg))
    end if
    close (unit)

    ! Count lines, then store the data lines.
    n = 0
    do i = 1, fsize
      if (buf(i:i) == achar(10)) n = n + 1
    end do
    allocate (tf%lines(n + 1))
    start = 1
    lnum = 0
    do while (start <= fsize)
      stop_ = index(buf(start:), achar(10))
      if (stop_ == 0) then
        stop_ = fsize + 1
      else
        stop_ = start + stop_ - 1
      end if
      lnum = lnum + 1
      call add_line(buf(start:stop_ - 1), lnum)
      start = stop_ + 1
    end do
    tf%lines = tf%lines(1:tf%n)

  contains

    subroutine add_line(raw, num)
      character(len=*), intent(in) :: raw
      integer, intent(in) :: num
      character(len=:), allocatable :: t
      integer :: last, k
      last = len(raw)
      ! Drop a carriage return (CRLF files) and turn tabs into blanks.
      if (last > 0) then
        if (raw(last:last) == achar(13)) last = last - 1
      end if
      t = raw(1:last)
      do k = 1, len(t)
        if (t(k:k) == achar(9)) t(k:k) = ' '
      end do
      if (len_trim(t) == 0) return
      if (.not. keep .and. (t(1:1) == '!' .or. t(1:1) == '#')) return
      ! LMGC90's example decks also indent comments ('  ! ...').
      k = verify(t, ' ')
      if (.not. keep .and. t(k:k) == '!') return
      tf%n = tf%n + 1
      tf%lines(tf%n)%text = trim(t)
      tf%lines(tf%n)%src%file = path
      tf%lines(tf%n)%src%line = num
    end subroutine add_line
  end subroutine load_text

  !> Stop with "FILE:LINE:COL: message" for this line.
  subroutine line_error(ln, col, message)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: col
    character(len=*), intent(in) :: message
    call input_error(ln%src%file, ln%src%line, col, message)
  end subroutine line_error

  !> Columns c1..c2 of the line; columns past its end read as blanks.
  pure function field(ln, c1, c2) result(s)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: c1, c2
    character(len=max(0, c2 - c1 + 1)) :: s
    integer :: n
    s = ''
    n = len(ln%text)
    if (c1 <= n) s = ln%text(c1:min(c2, n))
  end function field

  pure logical function is_blank(ln, c1, c2)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: c1, c2
    is_blank = len_trim(field(ln, c1, c2)) == 0
  end function is_blank

  !> The keyword of a '$' line (columns 2-6, e.g. 'bdyty', '$$$$$'), '' otherwise.
  pure function keyword_of(ln) result(k)
    type(text_line_t), intent(in) :: ln
    character(len=5) :: k
    k = ''
    if (len(ln%text) >= 1) then
      if (ln%text(1:1) == '$') k = field(ln, 2, 6)
    end if
  end function keyword_of

  !> Line i of the file exists and is a data line (not a '$' keyword line).
  logical function is_data(tf, i)
    type(text_file_t), intent(in) :: tf
    integer, intent(in) :: i
    is_data = .false.
    if (i >= 1 .and. i <= tf%n) is_data = tf%lines(i)%text(1:1) /= '$'
  end function is_data

  !> "columns c1-c2"
  function cols(c1, c2) result(s)
    integer, intent(in) :: c1, c2
    character(len=:), allocatable :: s
    s = 'columns '//itoa(c1)//'-'//itoa(c2)
  end function cols

  !> A real number from columns c1..c2; WHAT names the value in messages.
  function get_real(ln, c1, c2, what) result(x)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: c1, c2
    character(len=*), intent(in) :: what
    real(wp) :: x
    character(len=:), allocatable :: msg
    if (.not. parse_real(field(ln, c1, c2), x, msg)) &
      call line_error(ln, c1, 'expected a real number in '//cols(c1, c2)//' ('//what//'), '//found(ln, c1, msg))
    call check_spill(ln, c1, c2, what)
  end function get_real

  !> An integer from columns c1..c2.
  function get_int(ln, c1, c2, what) result(i)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: c1, c2
    character(len=*), intent(in) :: what
    integer :: i
    character(len=:), allocatable :: msg
    if (.not. parse_int(field(ln, c1, c2), i, msg)) &
      call line_error(ln, c1, 'expected an integer in '//cols(c1, c2)//' ('//what//'), '//found(ln, c1, msg))
    call check_spill(ln, c1, c2, what)
  end function get_int

  !> The parser's "found ..." message, made explicit for a line that ends
  !> before the field starts (writers trim trailing blanks).
  function found(ln, c1, msg) result(s)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: c1
    character(len=*), intent(in) :: msg
    character(len=:), allocatable :: s
    s = msg
    if (len(ln%text) < c1) s = 'found nothing (the line ends at column '//itoa(len(ln%text))//')'
  end function found

  !> The word in columns c1..c2 (leading/trailing blanks removed); blank is an
  !> error unless allow_blank.
  function get_word(ln, c1, c2, what, allow_blank) result(w)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: c1, c2
    character(len=*), intent(in) :: what
    logical, intent(in), optional :: allow_blank
    character(len=:), allocatable :: w
    logical :: blank_ok
    blank_ok = .false.
    if (present(allow_blank)) blank_ok = allow_blank
    w = trim(adjustl(field(ln, c1, c2)))
    if (len(w) == 0 .and. .not. blank_ok) then
      if (len(ln%text) < c1) then
        call line_error(ln, c1, 'expected '//what//' in '//cols(c1, c2)//', but the line ends at column ' &
                        //itoa(len(ln%text)))
      else
        call line_error(ln, c1, 'expected '//what//' in '//cols(c1, c2)//', found blanks')
      end if
    end if
    if (len(w) > 0) call check_spill(ln, c1, c2, what)
  end function get_word

  !> A value read from columns c1..c2 must end there: a non-blank in column c2
  !> followed by a non-blank means the value runs on past its field (LMGC90
  !> reads fixed columns: '1.0000000E-010' one column too far reads 0.1). A sign
  !> in column c2+1 starts the next value: LMGC90 writes negative numbers of
  !> adjacent fixed-width fields without a blank between them (GPV.OUT).
  subroutine check_spill(ln, c1, c2, what)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: c1, c2
    character(len=*), intent(in) :: what
    integer :: a, b
    if (c2 >= len(ln%text)) return
    if (ln%text(c2:c2) == ' ' .or. ln%text(c2 + 1:c2 + 1) == ' ') return
    if (ln%text(c2 + 1:c2 + 1) == '-' .or. ln%text(c2 + 1:c2 + 1) == '+') return
    a = c2
    do while (a > 1)
      if (ln%text(a - 1:a - 1) == ' ') exit
      a = a - 1
    end do
    b = c2 + 1
    do while (b < len(ln%text))
      if (ln%text(b + 1:b + 1) == ' ') exit
      b = b + 1
    end do
    call line_error(ln, c2 + 1, trim(what)//" in "//cols(c1, c2)//" runs on past its last column: found '"// &
                    ln%text(a:b)//"' (values are read from fixed columns; align it to end at column "// &
                    itoa(c2)//')')
  end subroutine check_spill

  !> Nothing may follow the last field of a line (columns after last_col blank).
  subroutine check_line_end(ln, last_col, what)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: last_col
    character(len=*), intent(in) :: what
    integer :: a
    if (len_trim(ln%text) <= last_col) return
    a = last_col + verify(ln%text(last_col + 1:), ' ')
    call line_error(ln, a, "unexpected text after the last field of "//what//" (column "//itoa(last_col)// &
                    "): '"//trim(ln%text(a:))//"'")
  end subroutine check_line_end

  !> The '$steps' header of DOF and Vloc_Rloc files: the integer after
  !> '$steps' and the number after 'time='. Read by token, not by column,
  !> because the .INI files (step in columns 9-15) and LMGC90's .OUT files
  !> (wider step field) place them differently.
  subroutine get_steps(ln, step, time)
    type(text_line_t), intent(in) :: ln
    integer, intent(out) :: step
    real(wp), intent(out) :: time
    integer :: a, b, k
    character(len=:), allocatable :: msg
    a = 7
    do while (a <= len(ln%text))
      if (ln%text(a:a) /= ' ') exit
      a = a + 1
    end do
    b = a
    do while (b <= len(ln%text))
      if (ln%text(b:b) == ' ') exit
      b = b + 1
    end do
    if (.not. parse_int(field(ln, a, b - 1), step, msg)) &
      call line_error(ln, a, "expected the step number after '$steps', "//found(ln, a, msg))
    if (step < 0) call line_error(ln, a, 'the step number must be >= 0, found '//itoa(step))
    k = index(ln%text, 'time=')
    if (k == 0) call line_error(ln, b, "expected 'time=' and the time after the step number")
    if (.not. parse_real(field(ln, k + 5, len(ln%text)), time, msg)) &
      call line_error(ln, k + 5, "expected a real number after 'time=', "//found(ln, k + 5, msg))
  end subroutine get_steps

  !> Parse a Fortran real literal: [sign] digits [. digits] [exponent], the
  !> exponent being e, E, d or D with optional sign, or a bare sign (as the D
  !> edit descriptor writes 3-digit exponents: 0.1234567-100). Blanks around the
  !> number are allowed. NaN and Inf are refused. On failure MSG says what was
  !> found (e.g. "found 'abc'").
  function parse_real(text, x, msg) result(ok)
    character(len=*), intent(in) :: text
    real(wp), intent(out) :: x
    character(len=:), allocatable, intent(out) :: msg
    logical :: ok
    character(len=:), allocatable :: s, low
    integer :: i, n, ndig, ios
    logical :: exp_seen, halt

    ok = .false.
    x = 0.0_wp
    s = trim(adjustl(text))
    n = len(s)
    if (n == 0) then
      msg = 'found nothing'
      if (len(text) > 0) msg = 'found blanks'
      return
    end if
    msg = "found '"//s//"'"
    low = lower(s)
    if (index(low, 'nan') > 0) then
      msg = msg//' (NaN is not a valid value)'
      return
    end if
    if (index(low, 'inf') > 0) then
      msg = msg//' (infinite values are not allowed)'
      return
    end if
    ! Syntax check.
    i = 1
    if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
    ndig = 0
    do while (i <= n)
      if (.not. is_digit(s(i:i))) exit
      ndig = ndig + 1
      i = i + 1
    end do
    if (i <= n) then
      if (s(i:i) == '.') then
        i = i + 1
        do while (i <= n)
          if (.not. is_digit(s(i:i))) exit
          ndig = ndig + 1
          i = i + 1
        end do
      end if
    end if
    if (ndig == 0) return
    exp_seen = .false.
    if (i <= n) then
      if (index('eEdD', s(i:i)) > 0) then
        i = i + 1
        exp_seen = .true.
        if (i <= n) then
          if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
        end if
      else if (s(i:i) == '+' .or. s(i:i) == '-') then
        i = i + 1
        exp_seen = .true.
      end if
      if (exp_seen) then
        ndig = 0
        do while (i <= n)
          if (.not. is_digit(s(i:i))) exit
          ndig = ndig + 1
          i = i + 1
        end do
        if (ndig == 0) return
      end if
    end if
    if (i <= n) return
    ! Conversion (a bare-sign exponent needs an explicit letter for list input).
    if (exp_seen) call insert_exponent_letter(s)
    ! A too large value gives Inf, not a floating-point trap (debug builds trap overflow).
    call ieee_get_halting_mode(ieee_overflow, halt)
    call ieee_set_halting_mode(ieee_overflow, .false.)
    read (s, *, iostat=ios) x
    call ieee_set_flag(ieee_overflow, .false.)
    call ieee_set_halting_mode(ieee_overflow, halt)
    if (ios /= 0) then
      msg = msg//' (out of range)'
      return
    end if
    if (.not. ieee_is_finite(x)) then
      x = 0.0_wp
      msg = msg//' (out of range)'
      return
    end if
    ok = .true.
    msg = ''
  end function parse_real

  !> Parse an integer: [sign] digits, blanks around allowed.
  function parse_int(text, i, msg) result(ok)
    character(len=*), intent(in) :: text
    integer, intent(out) :: i
    character(len=:), allocatable, intent(out) :: msg
    logical :: ok
    character(len=:), allocatable :: s
    integer :: k, k0, ios
    ok = .false.
    i = 0
    s = trim(adjustl(text))
    if (len(s) == 0) then
      msg = 'found nothing'
      if (len(text) > 0) msg = 'found blanks'
      return
    end if
    msg = "found '"//s//"'"
    k0 = 1
    if (s(1:1) == '+' .or. s(1:1) == '-') k0 = 2
    if (k0 > len(s)) return
    do k = k0, len(s)
      if (.not. is_digit(s(k:k))) return
    end do
    read (s, *, iostat=ios) i
    if (ios /= 0) then
      msg = msg//' (out of range)'
      return
    end if
    ok = .true.
    msg = ''
  end function parse_int

  !> '1.0-100' -> '1.0E-100' (the sign after the mantissa starts the exponent).
  subroutine insert_exponent_letter(s)
    character(len=:), allocatable, intent(inout) :: s
    integer :: k
    do k = 2, len(s)
      if (index('eEdD', s(k:k)) > 0) return
      if ((s(k:k) == '+' .or. s(k:k) == '-')) then
        s = s(1:k - 1)//'E'//s(k:)
        return
      end if
    end do
  end subroutine insert_exponent_letter

  pure logical function is_digit(c)
    character(len=1), intent(in) :: c
    is_digit = c >= '0' .and. c <= '9'
  end function is_digit




  !> Levenshtein distance (for "did you mean" suggestions).
  pure integer function edit_distance(a, b) result(d)
    character(len=*), intent(in) :: a, b
    integer :: prev(0:len(b)), cur(0:len(b)), i, j
    prev = [(j, j=0, len(b))]
    do i = 1, len(a)
      cur(0) = i
      do j = 1, len(b)
        cur(j) = min(prev(j) + 1, cur(j - 1) + 1, prev(j - 1) + merge(0, 1, a(i:i) == b(j:j)))
      end do
      prev = cur
    end do
    d = prev(len(b))
  end function edit_distance
end module fracas_datbox_text
