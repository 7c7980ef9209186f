!> DATBOX/POSTPRO.DAT reader: LMGC90's post-processing deck, a list of
!> commands, each a name line (as LMGC90 spells it, e.g. 'BODY TRACKING'),
!> then 'STEP n', then the command's parameter lines, up to 'END':
!>
!>   SOLVER INFORMATIONS
!>   STEP 1
!>   BODY TRACKING
!>   STEP 10
!>         2          <- number of bodies (I7)
!>         1          <- their RBDY2 numbers (I7), one per line
!>         5
!>   END
!>
!> LMGC90 reads 30 columns of each line: a ':' beyond column 30 (its example
!> decks end every line so) and what follows it are dropped.
!> A line followed by a 'STEP' line is a command: a name that is not one of
!> LMGC90's 2D commands is an error (with the closest name). Which commands
!> Fracas carries out is decided by fracas_postpro; here every command is
!> kept with its parameter lines, and those of BODY TRACKING and TORQUE
!> EVOLUTION are read and checked against the bodies of the deck.
module fracas_read_postpro
  use fracas_errors, only: input_error
  use fracas_deck, only: postpro_input_t, body_input_t
  use fracas_datbox_text, only: text_file_t, load_text, parse_int, upper, itoa, edit_distance
  implicit none
  private
  public :: read_postpro, postpro_command_names

  !> The commands of LMGC90's 2D post-processor (mod_postpro_2D), as spelled
  !> in POSTPRO.DAT.
  integer, parameter :: n_names = 40
  character(len=30), parameter :: postpro_command_names(n_names) = [character(len=30) :: &
    'AVERAGE VELOCITY EVOLUTION', 'SPECIES KINETIC ENERGY', 'SNAPSHOT SAMPLE', 'MP SNAPSHOT SAMPLE', &
    'NORMAL CONTACT DISTRIBUTION', 'CONTACT FORCE DISTRIBUTION', 'COORDINATION NUMBER', 'BODY TRACKING', &
    'MP VALUE TRACKING', 'TORQUE EVOLUTION', 'DENSE SAMPLE COMPACITY', 'DOUBLET INTERACTIONS', &
    '3D EXTRUSION', 'QUASI SLIDING CONTACT', 'NEW MECAx SETS', 'Fint EVOLUTION', 'Dep EVOLUTION', &
    'NEW DIST SETS', 'MAILx DIST', 'NEW RIGID SETS', 'NEW BOUNDED SETS', 'DISSIPATED ENERGY', &
    'SOLVER INFORMATIONS', 'DRY CONTACT NATURE', 'WET CONTACT NATURE', 'KINETIC ENERGY', &
    'VIOLATION EVOLUTION', 'PLPLx ANALYSIS', 'THERMAL EVOLUTION', 'NETWORK EVOLUTION', &
    'CREATE TEXT DATA', 'ELECTRO EVOLUTION', 'CLOUD ANALYSIS', 'DISPLAY TENSORS', 'COMPACITY EVOLUTION', &
    'HEAT BOUND PROFILE', 'CLxxx ANALYSIS', 'SURFACE ENERGIE SECTOR', 'CZM ENERGY EVOLUTION', &
    'ENERGY SNAPSHOT SAMPLE']

contains

  !> Read PATH into cmds. bodies: the deck's bodies (for the body numbers).
  subroutine read_postpro(path, bodies, cmds)
    character(len=*), intent(in) :: path
    type(body_input_t), intent(in) :: bodies(:)
    type(postpro_input_t), allocatable, intent(out) :: cmds(:)
    type(text_file_t) :: tf
    type(postpro_input_t), allocatable :: tmp(:)
    character(len=:), allocatable :: text, next
    integer :: i, n, k, line, col, ios
    logical :: ended

    call load_text(path, tf, keep_comments=.true.)
    allocate (cmds(0))
    n = 0
    ended = .false.
    i = 0
    do while (i < tf%n)
      i = i + 1
      text = trim(adjustl(content(tf%lines(i)%text)))
      line = tf%lines(i)%src%line
      col = verify(tf%lines(i)%text, ' ')
      if (text(1:1) == '#' .or. text(1:1) == '!') cycle
      if (upper(text) == 'END') then
        ended = .true.
        exit
      end if
      next = ''
      if (i < tf%n) next = upper(trim(adjustl(content(tf%lines(i + 1)%text))))
      if (starts_with_step(next)) then
        ! A command line: a known name, then STEP n.
        k = name_index(text)
        if (k == 0) call input_error(path, line, col, "unknown POSTPRO command '"//text//"'"//suggestion(text))
        allocate (tmp(n + 1))
        tmp(1:n) = cmds
        call move_alloc(tmp, cmds)
        n = n + 1
        cmds(n)%name = postpro_command_names(k)
        cmds(n)%src%file = path
        cmds(n)%src%line = line
        allocate (cmds(n)%params(0), cmds(n)%param_lines(0), cmds(n)%bodies(0))
        i = i + 1
        read (next(5:), *, iostat=ios) cmds(n)%every
        if (ios /= 0 .or. len_trim(next) <= 4) call input_error(path, tf%lines(i)%src%line, 1, &
          "expected 'STEP n' (n >= 1: every n steps) after '"//trim(cmds(n)%name)//"', found '"//next//"'")
        if (cmds(n)%every < 1) call input_error(path, tf%lines(i)%src%line, 1, &
          'STEP must be >= 1, found '//itoa(cmds(n)%every))
      else if (starts_with_step(upper(text))) then
        call input_error(path, line, col, "'STEP' without a command before it")
      else
        if (n == 0) call input_error(path, line, col, "expected a POSTPRO command (e.g. 'SOLVER INFORMATIONS'), found '" &
                                     //text//"'")
        cmds(n)%params = [character(len=80) :: cmds(n)%params, text]
        cmds(n)%param_lines = [cmds(n)%param_lines, line]
      end if
    end do
    if (.not. ended) call input_error(path, 0, 0, "no 'END' line: POSTPRO.DAT ends with END")
    do k = 1, n
      select case (trim(cmds(k)%name))
      case ('BODY TRACKING', 'TORQUE EVOLUTION')
        call read_body_list(cmds(k))
      end select
    end do

  contains

    !> A count, then that many RBDY2 body numbers, one per line.
    subroutine read_body_list(c)
      type(postpro_input_t), intent(inout) :: c
      character(len=:), allocatable :: msg
      integer :: m, j, ib, nrigid
      if (size(c%params) == 0) call input_error(path, c%src%line, 1, trim(c%name)// &
        ': expected the number of bodies, then one body number per line')
      if (.not. parse_int(c%params(1), m, msg) .or. m < 1) call input_error(path, c%param_lines(1), 1, &
        trim(c%name)//': expected the number of bodies (an integer >= 1), found '''//trim(c%params(1))//'''')
      if (size(c%params) /= m + 1) call input_error(path, c%param_lines(1), 1, trim(c%name)//': '// &
        itoa(m)//' bodies announced, '//itoa(size(c%params) - 1)//' body numbers follow')
      nrigid = count(bodies%model == 'RBDY2')
      deallocate (c%bodies)
      allocate (c%bodies(m))
      do j = 1, m
        if (.not. parse_int(c%params(j + 1), ib, msg)) call input_error(path, c%param_lines(j + 1), 1, &
          trim(c%name)//': expected a body number, found '''//trim(c%params(j + 1))//'''')
        if (ib < 1 .or. ib > nrigid) call input_error(path, c%param_lines(j + 1), 1, trim(c%name)// &
          ': body '//itoa(ib)//' does not exist (RBDY2 bodies are numbered 1 to '//itoa(nrigid)//')')
        c%bodies(j) = ib
      end do
    end subroutine read_body_list
  end subroutine read_postpro

  !> A line as LMGC90 reads it (30 columns): its example decks pad every line
  !> with blanks to column 30 and end it with ':' (a ruler), which is dropped.
  pure function content(s) result(c)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: c
    integer :: k
    k = index(s, ':')
    if (k > 30) then
      c = s(1:k - 1)
    else
      c = s
    end if
  end function content

  logical function starts_with_step(s)
    character(len=*), intent(in) :: s
    starts_with_step = .false.
    if (len(s) >= 4) starts_with_step = s(1:4) == 'STEP' .and. verify(s(5:), ' 0123456789+-') == 0
    if (len(s) == 4) starts_with_step = s == 'STEP'
  end function starts_with_step

  !> Index of NAME among the command names (letter case ignored), 0 if none.
  integer function name_index(name) result(k)
    character(len=*), intent(in) :: name
    integer :: j
    k = 0
    do j = 1, n_names
      if (upper(trim(postpro_command_names(j))) == upper(trim(name))) k = j
    end do
  end function name_index

  function suggestion(name) result(s)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: s
    integer :: j, d, best, jbest
    best = huge(1)
    jbest = 1
    do j = 1, n_names
      d = edit_distance(upper(trim(name)), upper(trim(postpro_command_names(j))))
      if (d < best) then
        best = d
        jbest = j
      end if
    end do
    if (best <= max(3, len_trim(name)/4)) then
      s = "; did you mean '"//trim(postpro_command_names(jbest))//"'?"
    else
      s = ' (not one of LMGC90''s 2D post-processing commands)'
    end if
  end function suggestion
end module fracas_read_postpro
