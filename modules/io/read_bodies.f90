!> BODIES.DAT reader (RBDY2 rigid bodies). Bodies are numbered by order of
!> appearance; the number written in the file is not used. Supported records:
!> $bdyty RBDY2, $blmty PLAIN (material, avrd, gyrd), $nodty NO3xx (x, y,
!> angle), $tacty DISKx / xKSID / JONCx / POLYG / DISKb, end of body $$$$$$.
module fracas_read_bodies
  use fracas_kinds, only: wp
  use fracas_deck, only: body_input_t, tactor_input_t, material_input_t
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, check_line_end, &
                                keyword_of, is_data, get_real, get_int, get_word, itoa, rtoa
  implicit none
  private
  public :: read_bodies, material_list

  character(len=*), parameter :: supported_tactors = 'DISKx, xKSID, JONCx, POLYG, DISKb'

contains

  !> Read PATH into BODIES. If MATERIALS is given, every body's material
  !> nickname must be one of them (error at the PLAIN line otherwise).
  subroutine read_bodies(path, bodies, materials)
    character(len=*), intent(in) :: path
    type(body_input_t), allocatable, intent(out) :: bodies(:)
    type(material_input_t), intent(in), optional :: materials(:)
    type(text_file_t) :: tf
    integer :: i, nb, ib

    call load_text(path, tf)
    nb = 0
    do i = 1, tf%n
      if (keyword_of(tf%lines(i)) == 'bdyty') nb = nb + 1
    end do
    allocate (bodies(nb))
    ib = 0
    i = 1
    do while (i <= tf%n)
      if (keyword_of(tf%lines(i)) /= 'bdyty') &
        call line_error(tf%lines(i), 1, "expected '$bdyty' (start of a body), found '"// &
                        trim(field(tf%lines(i), 1, 40))//"'")
      ib = ib + 1
      call read_body(tf, i, bodies(ib), ib, materials)
    end do
  end subroutine read_bodies

  !> One body from its '$bdyty' line (tf%lines(i)) to '$$$$$$'; i ends after it.
  subroutine read_body(tf, i, b, number, materials)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(body_input_t), intent(inout) :: b
    integer, intent(in) :: number
    type(material_input_t), intent(in), optional :: materials(:)
    type(tactor_input_t), allocatable :: tacs(:)
    integer :: ibdy, ntac
    logical :: have_bulk, have_node
    character(len=5) :: kw

    ibdy = i
    if (i + 1 > tf%n) call line_error(tf%lines(i), 1, "'$bdyty' must be followed by a body line (' RBDY2  number')")
    i = i + 1
    b%model = get_word(tf%lines(i), 2, 6, 'body model')
    if (b%model /= 'RBDY2') call line_error(tf%lines(i), 2, "unknown body model '"//trim(b%model)// &
                                            "' (supported: RBDY2)")
    b%number = number
    b%src = tf%lines(i)%src
    have_bulk = .false.
    have_node = .false.
    ntac = 0
    allocate (tacs(4))
    i = i + 1
    do
      if (i > tf%n) call line_error(tf%lines(ibdy), 1, 'body '//itoa(number)// &
                                    " is not closed by '$$$$$$' before the end of the file")
      kw = keyword_of(tf%lines(i))
      select case (kw)
      case ('$$$$$')
        i = i + 1
        exit
      case ('blmty')
        i = i + 1
        do while (is_data(tf, i))
          call read_bulk_line(tf%lines(i), b, have_bulk, materials)
          i = i + 1
        end do
      case ('nodty')
        i = i + 1
        do while (is_data(tf, i))
          call read_node_line(tf%lines(i), b, have_node)
          i = i + 1
        end do
      case ('tacty')
        i = i + 1
        do while (is_data(tf, i))
          ntac = ntac + 1
          if (ntac > size(tacs)) call grow(tacs)
          call read_tactor(tf, i, tacs(ntac))
        end do
      case ('bdyty')
        call line_error(tf%lines(ibdy), 1, 'body '//itoa(number)//" is not closed by '$$$$$$' (next '$bdyty' at line " &
                        //itoa(tf%lines(i)%src%line)//')')
      case default
        if (tf%lines(i)%text(1:1) == '$') then
          call line_error(tf%lines(i), 1, "unexpected keyword '"//trim(field(tf%lines(i), 1, 6))// &
                          "' in a body (expected $blmty, $nodty, $tacty or $$$$$$)")
        else
          call line_error(tf%lines(i), 1, "expected a keyword ($blmty, $nodty, $tacty or $$$$$$), found '" &
                          //trim(field(tf%lines(i), 1, 40))//"'")
        end if
      end select
    end do
    if (.not. have_bulk) call line_error(tf%lines(ibdy), 1, 'body '//itoa(number)// &
                                         " has no '$blmty' PLAIN line (material, avrd, gyrd)")
    if (.not. have_node) call line_error(tf%lines(ibdy), 1, 'body '//itoa(number)// &
                                         " has no '$nodty' NO3xx line (reference position)")
    b%tactors = tacs(1:ntac)
  end subroutine read_body

  !> Line i exists and is a data line (not a '$' keyword line).
  subroutine read_bulk_line(ln, b, have_bulk, materials)
    type(text_line_t), intent(in) :: ln
    type(body_input_t), intent(inout) :: b
    logical, intent(inout) :: have_bulk
    type(material_input_t), intent(in), optional :: materials(:)
    character(len=:), allocatable :: elem
    integer :: k
    logical :: found

    elem = get_word(ln, 2, 6, 'bulk element type')
    if (elem /= 'PLAIN') call line_error(ln, 2, "unknown bulk element '"//elem//"' for RBDY2 (supported: PLAIN)")
    if (have_bulk) call line_error(ln, 2, 'a rigid body has exactly one PLAIN line')
    have_bulk = .true.
    b%behav = get_word(ln, 23, 27, 'material nickname')
    b%avrd = get_real(ln, 35, 48, "average radius 'avrd='")
    b%gyrd = get_real(ln, 56, 69, "gyration radius 'gyrd='")
    if (b%avrd < 0.0_wp) call line_error(ln, 35, 'avrd must be >= 0 (0: computed from the contactors), found '//rtoa(b%avrd))
    if (b%gyrd < 0.0_wp) call line_error(ln, 56, 'gyrd must be >= 0 (0: computed from the contactors), found '//rtoa(b%gyrd))
    call check_line_end(ln, 69, 'the PLAIN line')
    if (present(materials)) then
      found = .false.
      do k = 1, size(materials)
        if (materials(k)%nickname == b%behav) found = .true.
      end do
      if (.not. found) call line_error(ln, 23, "material '"//trim(b%behav)// &
                                       "' is not defined in BULK_BEHAV.DAT (defined: "//material_list(materials)//')')
    end if
  end subroutine read_bulk_line

  !> "STONE, TDURx" (or "none").
  function material_list(materials) result(s)
    type(material_input_t), intent(in) :: materials(:)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, size(materials)
      if (k > 1) s = s//', '
      s = s//trim(materials(k)%nickname)
    end do
    if (len(s) == 0) s = 'none'
  end function material_list

  subroutine read_node_line(ln, b, have_node)
    type(text_line_t), intent(in) :: ln
    type(body_input_t), intent(inout) :: b
    logical, intent(inout) :: have_node
    character(len=:), allocatable :: node
    node = get_word(ln, 2, 6, 'node type')
    if (node /= 'NO3xx') call line_error(ln, 2, "unknown node type '"//node//"' for RBDY2 (supported: NO3xx)")
    if (have_node) call line_error(ln, 2, 'a rigid body has exactly one NO3xx node')
    have_node = .true.
    b%coor(1) = get_real(ln, 35, 48, "reference x 'coo1='")
    b%coor(2) = get_real(ln, 56, 69, "reference y 'coo2='")
    b%coor(3) = get_real(ln, 77, 90, "reference angle 'coo3='")
    call check_line_end(ln, 90, 'the NO3xx line')
  end subroutine read_node_line

  !> One contactor starting at line i (with its continuation lines); i ends
  !> at the next line.
  subroutine read_tactor(tf, i, t)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(tactor_input_t), intent(out) :: t
    integer :: nv, k, i0
    real(wp) :: area

    i0 = i
    associate (ln => tf%lines(i0))
      t%src = ln%src
      t%kind = get_word(ln, 2, 6, 'contactor type')
      t%color = get_word(ln, 23, 27, 'colour')
      select case (t%kind)
      case ('DISKx', 'xKSID', 'DISKb')
        t%radius = get_real(ln, 35, 48, "radius 'byrd='")
        if (t%radius <= 0.0_wp) call line_error(ln, 35, t%kind//' radius must be > 0, found '//rtoa(t%radius))
        call check_line_end(ln, 48, 'the '//t%kind//' line')
        if (t%kind == 'DISKb') then
          i = i + 1
          if (.not. is_data(tf, i)) call line_error(ln, 1, 'DISKb needs an offset line (coo1=, coo2=) after it')
          t%shift(1) = get_real(tf%lines(i), 35, 48, "offset x 'coo1='")
          t%shift(2) = get_real(tf%lines(i), 56, 69, "offset y 'coo2='")
          call check_line_end(tf%lines(i), 69, 'the DISKb offset line')
        end if
      case ('JONCx')
        t%ax1 = get_real(ln, 35, 48, "half length 'ax1='")
        t%ax2 = get_real(ln, 56, 69, "half thickness 'ax2='")
        if (t%ax1 <= 0.0_wp) call line_error(ln, 35, 'JONCx half length ax1 must be > 0, found '//rtoa(t%ax1))
        if (t%ax2 <= 0.0_wp) call line_error(ln, 56, 'JONCx half thickness ax2 must be > 0, found '//rtoa(t%ax2))
        call check_line_end(ln, 69, 'the JONCx line')
      case ('POLYG')
        nv = get_int(ln, 40, 46, "number of vertices 'nb_vertex='")
        if (nv < 3) call line_error(ln, 40, 'a POLYG needs at least 3 vertices, found nb_vertex = '//itoa(nv))
        call check_line_end(ln, 46, 'the POLYG line')
        allocate (t%vertices(2, nv))
        do k = 1, nv
          if (.not. is_data(tf, i + k)) call line_error(ln, 40, 'POLYG declares '//itoa(nv)// &
                                                        ' vertices but only '//itoa(k - 1)//' vertex lines follow')
          t%vertices(1, k) = get_real(tf%lines(i + k), 35, 48, "vertex x 'coo1='")
          t%vertices(2, k) = get_real(tf%lines(i + k), 56, 69, "vertex y 'coo2='")
          call check_line_end(tf%lines(i + k), 69, 'a POLYG vertex line')
        end do
        i = i + nv
        area = 0.0_wp
        do k = 1, nv
          area = area + t%vertices(1, k)*t%vertices(2, mod(k, nv) + 1) - t%vertices(1, mod(k, nv) + 1)*t%vertices(2, k)
        end do
        area = 0.5_wp*area
        if (area < 0.0_wp) call line_error(ln, 2, 'POLYG vertices are in clockwise order (signed area ' &
                                           //rtoa(area)//'); list them counter-clockwise')
        if (area == 0.0_wp) call line_error(ln, 2, 'POLYG has zero area (all vertices on a line)')
        call check_polygon_shape(tf, i0, t%vertices)
      case default
        call line_error(ln, 2, "unknown contactor type '"//trim(t%kind)//"' for RBDY2 (supported: " &
                        //supported_tactors//')')
      end select
    end associate
    i = i + 1
  end subroutine read_tactor

  !> A POLYG must be convex (one contactor per convex part), its edges not
  !> degenerate: each edge longer than what double precision resolves at the
  !> polygon's extent (1e-3 extent / eps, as for body positions), so that edge
  !> normals exist. Errors at the vertex line (line i0 + k for vertex k).
  subroutine check_polygon_shape(tf, i0, v)
    type(text_file_t), intent(in) :: tf
    integer, intent(in) :: i0
    real(wp), intent(in) :: v(:, :)
    integer :: k, nv, kn, kp
    real(wp) :: extent, edge, turn
    nv = size(v, 2)
    extent = maxval(abs(v))
    do k = 1, nv
      kn = mod(k, nv) + 1
      edge = norm2(v(:, kn) - v(:, k))
      if (.not. (edge > 1.0e3_wp * epsilon(1.0_wp) * extent)) call line_error(tf%lines(i0 + kn), 35, &
        'POLYG vertex '//itoa(kn)//' is '//rtoa(edge)//' from vertex '//itoa(k)//' in a polygon of extent '// &
        rtoa(extent)//': a degenerate edge (what double precision resolves at that extent is '// &
        rtoa(1.0e3_wp * epsilon(1.0_wp) * extent)//')')
    end do
    do k = 1, nv
      kp = mod(k + nv - 2, nv) + 1
      kn = mod(k, nv) + 1
      turn = (v(1, k) - v(1, kp)) * (v(2, kn) - v(2, k)) - (v(2, k) - v(2, kp)) * (v(1, kn) - v(1, k))
      if (turn < 0.0_wp) call line_error(tf%lines(i0 + k), 35, 'POLYG is not convex at vertex '//itoa(k)// &
        ' (a clockwise turn): split a non-convex shape into convex POLYG contactors of one body')
    end do
  end subroutine check_polygon_shape

  subroutine grow(tacs)
    type(tactor_input_t), allocatable, intent(inout) :: tacs(:)
    type(tactor_input_t), allocatable :: tmp(:)
    allocate (tmp(2*size(tacs)))
    tmp(1:size(tacs)) = tacs
    call move_alloc(tmp, tacs)
  end subroutine grow
end module fracas_read_bodies
