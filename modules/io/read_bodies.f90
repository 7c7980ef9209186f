!> BODIES.DAT reader: rigid bodies (RBDY2) and meshed bodies (MAILx). Bodies
!> are numbered by order of appearance within their model, as LMGC90 numbers
!> them ('RBDY2 1' and 'MAILx 1' can both exist); the number written in the
!> file is not used. Supported records:
!> - RBDY2: $blmty PLAIN (material, avrd, gyrd), $nodty NO3xx (x, y, angle),
!>   $tacty DISKx / xKSID / JONCx / POLYG / DISKb;
!> - MAILx: $blmty T3xxx / Q4xxx / T6xxx / Q8xxx element lines, each with its
!>   'model ... behav' line, $nodty NO2xx (x, y), $tacty CLxxx (one candidate
!>   point per line, '+' lines included) and ALpxx (a polyline: the line and
!>   its '+' lines);
!> end of body $$$$$$.
module fracas_read_bodies
  use fracas_kinds, only: wp
  use fracas_deck, only: body_input_t, tactor_input_t, material_input_t, element_input_t
  use fracas_errors, only: input_error
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, is_blank, check_line_end, &
                                keyword_of, is_data, get_real, get_int, get_word, itoa, rtoa
  implicit none
  private
  public :: read_bodies, material_list, check_material_defined, body_lookup_t, body_lookup, find_body, no_such_body, element_node_count, &
            element_kinds

  character(len=*), parameter :: supported_tactors = 'DISKx, xKSID, JONCx, POLYG, DISKb'
  character(len=*), parameter :: supported_mesh_tactors = 'CLxxx, ALpxx'
  !> Element geometries of MAILx bodies and their node counts.
  character(len=5), parameter :: element_kinds(4) = ['T3xxx', 'Q4xxx', 'T6xxx', 'Q8xxx']
  integer, parameter :: element_nodes(4) = [3, 4, 6, 8]
  !> Bulk laws a meshed body's elements may use.
  character(len=*), parameter :: mesh_material_laws = 'ELAS, ELAS_PLAS'
  !> Where each body is in the list of BODIES.DAT, by model and number.
  type :: body_lookup_t
    integer, allocatable :: rigid(:), mesh(:)
  end type body_lookup_t

  !> Columns of an element line: node k in columns node_col(k) .. node_col(k) + 6 (I7).
  integer, parameter :: node_col0 = 21, node_width = 7
  !> Names of the node fields in error messages (constants, not formatted per element).
  character(len=6), parameter :: node_label(8) = ['node 1', 'node 2', 'node 3', 'node 4', 'node 5', 'node 6', &
                                                  'node 7', 'node 8']

contains

  !> Read PATH into BODIES. If MATERIALS is given, every body's material
  !> nickname must be one of them (error at the PLAIN line, or at an element's
  !> 'model ... behav' line, otherwise), and a meshed body's materials must be
  !> ELAS or ELAS_PLAS.
  subroutine read_bodies(path, bodies, materials)
    character(len=*), intent(in) :: path
    type(body_input_t), allocatable, intent(out) :: bodies(:)
    type(material_input_t), intent(in), optional :: materials(:)
    type(text_file_t) :: tf
    integer :: i, nb, ib, n_rigid, n_mesh
    character(len=:), allocatable :: model

    call load_text(path, tf)
    nb = 0
    do i = 1, tf%n
      if (keyword_of(tf%lines(i)) == 'bdyty') nb = nb + 1
    end do
    allocate (bodies(nb))
    ib = 0
    n_rigid = 0
    n_mesh = 0
    i = 1
    do while (i <= tf%n)
      if (keyword_of(tf%lines(i)) /= 'bdyty') &
        call line_error(tf%lines(i), 1, "expected '$bdyty' (start of a body), found '"// &
                        trim(field(tf%lines(i), 1, 40))//"'")
      if (.not. is_data(tf, i + 1)) &
        call line_error(tf%lines(i), 1, "'$bdyty' must be followed by a body line (' RBDY2  number' or ' MAILx  number')")
      ib = ib + 1
      model = get_word(tf%lines(i + 1), 2, 6, 'body model')
      select case (model)
      case ('RBDY2')
        n_rigid = n_rigid + 1
        call read_body(tf, i, bodies(ib), n_rigid, materials)
      case ('MAILx')
        n_mesh = n_mesh + 1
        call read_mesh_body(tf, i, bodies(ib), n_mesh, materials)
      case ('RBDY3')
        ! 3D rigid bodies are read by fracas_read_bodies_3d, but the scene is 2D (doc/rigid_3d.md)
        call line_error(tf%lines(i + 1), 2, 'RBDY3 is a 3D rigid body: 3D decks are not run yet (the scene is 2D; ' &
                        //'supported: RBDY2, MAILx)')
      case default
        call line_error(tf%lines(i + 1), 2, "unknown body model '"//model//"' (supported: RBDY2, MAILx)")
      end select
    end do
  end subroutine read_bodies

  !> One rigid body from its '$bdyty' line (tf%lines(i)) to '$$$$$$'; i ends after it.
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
    i = i + 1
    b%model = 'RBDY2'
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

    elem = get_word(ln, 2, 6, 'bulk element type')
    if (elem /= 'PLAIN') call line_error(ln, 2, "unknown bulk element '"//elem//"' for RBDY2 (supported: PLAIN)")
    if (have_bulk) call line_error(ln, 2, 'a rigid body has exactly one PLAIN line')
    have_bulk = .true.
    b%behav = get_word(ln, 23, 27, 'material nickname')
    b%avrd = get_real(ln, 35, 48, "average radius 'avrd='")
    ! LMGC90's example decks may end the line after avrd: gyrd 0 (computed).
    b%gyrd = 0.0_wp
    if (len_trim(ln%text) >= 56) b%gyrd = get_real(ln, 56, 69, "gyration radius 'gyrd='")
    if (b%avrd < 0.0_wp) call line_error(ln, 35, 'avrd must be >= 0 (0: computed from the contactors), found '//rtoa(b%avrd))
    if (b%gyrd < 0.0_wp) call line_error(ln, 56, 'gyrd must be >= 0 (0: computed from the contactors), found '//rtoa(b%gyrd))
    call check_line_end(ln, 69, 'the PLAIN line')
    if (present(materials)) call check_material_defined(ln, b%behav, materials)
  end subroutine read_bulk_line

  !> A PLAIN line's material nickname (columns 23-27) must be one of MATERIALS.
  subroutine check_material_defined(ln, behav, materials)
    type(text_line_t), intent(in) :: ln
    character(len=*), intent(in) :: behav
    type(material_input_t), intent(in) :: materials(:)
    if (any(materials%nickname == behav)) return
    call line_error(ln, 23, "material '"//trim(behav)//"' is not defined in BULK_BEHAV.DAT (defined: "// &
                    material_list(materials)//')')
  end subroutine check_material_defined

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
        ! Older decks add 'byrd=' (columns 51-55, value 56-69), the radius of a
        ! bounding disk that LMGC90 computes anyway: read, not used.
        if (field(ln, 51, 55) == 'byrd=') then
          if (get_real(ln, 56, 69, "bounding radius 'byrd='") < 0.0_wp) &
            call line_error(ln, 56, 'byrd must be >= 0')
          call check_line_end(ln, 69, 'the POLYG line')
        else
          call check_line_end(ln, 46, 'the POLYG line')
        end if
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
  !> One meshed body from its '$bdyty' line (tf%lines(i)) to '$$$$$$'; i ends
  !> after it. Elements come first ($blmty), then nodes ($nodty), then
  !> contactors ($tacty), as LMGC90 writes them.
  subroutine read_mesh_body(tf, i, b, number, materials)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(body_input_t), intent(inout) :: b
    integer, intent(in) :: number
    type(material_input_t), intent(in), optional :: materials(:)
    type(tactor_input_t), allocatable :: tacs(:)
    type(element_input_t), allocatable :: elems(:)
    real(wp), allocatable :: coor(:, :)
    integer :: ibdy, ntac, nel, nnod, k, j
    character(len=5) :: kw
    character(len=:), allocatable :: name

    ibdy = i
    i = i + 1
    b%model = 'MAILx'
    b%number = number
    b%src = tf%lines(i)%src
    name = 'MAILx body '//itoa(number)
    ntac = 0
    nel = 0
    nnod = 0
    allocate (tacs(4), elems(16), coor(2, 16))
    i = i + 1
    do
      if (i > tf%n) call line_error(tf%lines(ibdy), 1, name//" is not closed by '$$$$$$' before the end of the file")
      kw = keyword_of(tf%lines(i))
      select case (kw)
      case ('$$$$$')
        i = i + 1
        exit
      case ('blmty')
        i = i + 1
        do while (is_data(tf, i))
          nel = nel + 1
          if (nel > size(elems)) call grow_elements(elems)
          call read_element(tf, i, elems(nel), materials)
        end do
      case ('nodty')
        i = i + 1
        do while (is_data(tf, i))
          nnod = nnod + 1
          if (nnod > size(coor, 2)) call grow_coor(coor)
          call read_mesh_node(tf%lines(i), nnod, coor(:, nnod))
          i = i + 1
        end do
      case ('tacty')
        if (nnod == 0) call line_error(tf%lines(i), 1, "the '$tacty' contactors of a MAILx body come after its " &
                                       //"'$nodty' nodes (they name nodes of the body)")
        i = i + 1
        j = i
        do while (is_data(tf, i))
          call read_mesh_tactor(tf%lines(i), i == j, tacs, ntac, nnod, name)
          i = i + 1
        end do
      case ('bdyty')
        call line_error(tf%lines(ibdy), 1, name//" is not closed by '$$$$$$' (next '$bdyty' at line " &
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
    if (nel == 0) call line_error(tf%lines(ibdy), 1, name//" has no elements (a '$blmty' block of T3xxx, Q4xxx, " &
                                  //'T6xxx or Q8xxx lines)')
    if (nnod == 0) call line_error(tf%lines(ibdy), 1, name//" has no nodes (a '$nodty' block of NO2xx lines)")
    ! Element nodes, now that the nodes are known.
    do k = 1, nel
      do j = 1, size(elems(k)%nodes)
        if (elems(k)%nodes(j) < 1 .or. elems(k)%nodes(j) > nnod) &
          call input_error(elems(k)%src%file, elems(k)%src%line, node_col0 + node_width*(j - 1), &
                              'node '//itoa(elems(k)%nodes(j))//' does not exist ('//name//' has ' &
                              //itoa(nnod)//' nodes)')
      end do
    end do
    b%elements = elems(1:nel)
    b%node_coor = coor(:, 1:nnod)
    b%tactors = tacs(1:ntac)
  end subroutine read_mesh_body

  !> An element line and its 'model ... behav' line, from line i; i ends after them.
  subroutine read_element(tf, i, e, materials)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(element_input_t), intent(out) :: e
    type(material_input_t), intent(in), optional :: materials(:)
    integer :: nn, nf, k, j, c
    character(len=:), allocatable :: kind

    associate (ln => tf%lines(i))
      e%src = ln%src
      kind = get_word(ln, 2, 6, 'element type (T3xxx, Q4xxx, T6xxx or Q8xxx)')
      nn = element_node_count(kind)
      if (nn == 0) call line_error(ln, 2, "unknown element type '"//kind//"' for MAILx (supported: " &
                                   //kind_list()//')')
      e%kind = kind
      ! Node numbers: one I7 field each from column 21; count the fields written.
      nf = 0
      c = node_col0
      do while (c <= len(ln%text))
        if (.not. is_blank(ln, c, c + node_width - 1)) nf = nf + 1
        c = c + node_width
      end do
      if (nf /= nn) call line_error(ln, node_col0, 'a '//kind//' element has '//itoa(nn)//' nodes: expected ' &
                                    //itoa(nn)//' node numbers in '//node_cols(nn)//', found '//itoa(nf))
      allocate (e%nodes(nn))
      do k = 1, nn
        c = node_col0 + node_width*(k - 1)
        e%nodes(k) = get_int(ln, c, c + node_width - 1, node_label(k)//' of the '//kind)
        do j = 1, k - 1
          if (e%nodes(j) == e%nodes(k)) call line_error(ln, c, 'node '//itoa(e%nodes(k))// &
                                                        ' appears twice in this '//kind)
        end do
      end do
    end associate
    i = i + 1
    ok_model: block
      logical :: ok
      ok = is_data(tf, i)
      if (ok) ok = is_blank(tf%lines(i), 1, 6)
      if (.not. ok) call line_error(tf%lines(i - 1), 2, 'a '//kind//" element line must be followed by its " &
                                    //"'model ... behav' line (model nickname in columns 23-27, material in 37-41)")
    end block ok_model
    associate (ln => tf%lines(i))
      e%model_src = ln%src
      e%model = get_word(ln, 23, 27, 'model nickname (MODELS.DAT)')
      e%behav = get_word(ln, 37, 41, 'material nickname (BULK_BEHAV.DAT)')
      if (present(materials)) call check_mesh_material(ln, e%behav, materials)
    end associate
    i = i + 1
    if (is_data(tf, i)) then
      if (is_blank(tf%lines(i), 1, 6)) &
        call line_error(tf%lines(i), 16, "a second 'model ... behav' line for one element: Fracas runs one " &
                        //'MECAx model per element (no multi-physics elements)')
    end if
  end subroutine read_element

  !> The material of an element exists and is a law for meshes.
  subroutine check_mesh_material(ln, behav, materials)
    type(text_line_t), intent(in) :: ln
    character(len=*), intent(in) :: behav
    type(material_input_t), intent(in) :: materials(:)
    integer :: k
    do k = 1, size(materials)
      if (materials(k)%nickname /= behav) cycle
      select case (materials(k)%law)
      case ('ELAS', 'ELAS_PLAS')
        return
      case default
        call line_error(ln, 37, "material '"//trim(behav)//"' has the law "//trim(materials(k)%law)// &
                        ' (BULK_BEHAV.DAT line '//itoa(materials(k)%src%line)// &
                        '): the elements of a meshed body need '//mesh_material_laws)
      end select
    end do
    call line_error(ln, 37, "material '"//trim(behav)//"' is not defined in BULK_BEHAV.DAT (defined: " &
                    //material_list(materials)//')')
  end subroutine check_mesh_material

  !> One NO2xx line: node number n (nodes are numbered 1, 2, ... in order), x, y.
  subroutine read_mesh_node(ln, n, x)
    type(text_line_t), intent(in) :: ln
    integer, intent(in) :: n
    real(wp), intent(out) :: x(2)
    character(len=:), allocatable :: node
    integer :: num
    node = get_word(ln, 2, 6, 'node type')
    if (node /= 'NO2xx') call line_error(ln, 2, "unknown node type '"//node//"' for MAILx (supported: NO2xx)")
    num = get_int(ln, 7, 13, 'node number')
    if (num /= n) call line_error(ln, 7, 'nodes are numbered 1, 2, 3, ... in order: expected node '//itoa(n)// &
                                  ', found '//itoa(num))
    x(1) = get_real(ln, 35, 48, "x 'coo1='")
    x(2) = get_real(ln, 56, 69, "y 'coo2='")
  end subroutine read_mesh_node

  !> One CLxxx or ALpxx line of a MAILx body (FIRST: first line of its $tacty
  !> block). A CLxxx line, '+' or not, is a contactor of its own (as LMGC90
  !> numbers them); a '+ALpxx' line adds a segment to the polyline before it,
  !> starting where that one ends.
  subroutine read_mesh_tactor(ln, first, tacs, ntac, nnod, name)
    type(text_line_t), intent(in) :: ln
    logical, intent(in) :: first
    type(tactor_input_t), allocatable, intent(inout) :: tacs(:)
    integer, intent(inout) :: ntac
    integer, intent(in) :: nnod
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: kind, color
    logical :: plus
    integer :: noda, nodb, last
    real(wp) :: apab

    plus = ln%text(1:1) == '+'
    if (.not. plus .and. ln%text(1:1) /= ' ') &
      call line_error(ln, 1, "column 1 of a contactor line is blank, or '+' for a continuation line, found '" &
                      //ln%text(1:1)//"'")
    kind = get_word(ln, 2, 6, 'contactor type')
    if (kind /= 'CLxxx' .and. kind /= 'ALpxx') &
      call line_error(ln, 2, "unknown contactor type '"//kind//"' for MAILx (supported: "//supported_mesh_tactors//')')
    if (plus) then
      if (first .or. ntac == 0) call line_error(ln, 1, "'+"//kind//"' continues the "//kind// &
                                               ' line before it, but it starts a $tacty block')
      if (tacs(ntac)%kind /= kind) call line_error(ln, 1, "'+"//kind//"' continues a "//kind//' line, but the ' &
                                                   //'line before it is a '//tacs(ntac)%kind)
    end if
    ! A '+ALpxx' line may leave the colour blank (LMGC90 does not read it there).
    if (plus .and. kind == 'ALpxx' .and. is_blank(ln, 16, 27)) then
      color = tacs(ntac)%color
    else
      color = get_word(ln, 23, 27, 'colour')
    end if
    noda = get_int(ln, 35, 39, "first node 'noda='")
    nodb = get_int(ln, 47, 51, "second node 'nodb='")
    if (noda < 1 .or. noda > nnod) call line_error(ln, 35, 'node '//itoa(noda)//' does not exist ('//name// &
                                                   ' has '//itoa(nnod)//' nodes)')
    if (nodb < 1 .or. nodb > nnod) call line_error(ln, 47, 'node '//itoa(nodb)//' does not exist ('//name// &
                                                   ' has '//itoa(nnod)//' nodes)')
    if (noda == nodb) call line_error(ln, 47, 'the two nodes of a '//kind//' edge must differ, found '// &
                                      itoa(noda)//' twice')
    if (kind == 'ALpxx' .and. plus) then
      associate (t => tacs(ntac))
        last = t%nodes(size(t%nodes))
        if (noda /= last) call line_error(ln, 35, "'+ALpxx' segment starts at node "//itoa(noda)// &
                                          ' but the segment before it ends at node '//itoa(last)// &
                                          ': the segments of a polyline follow each other')
        if (color /= t%color) call line_error(ln, 23, "'+ALpxx' colour '"//color//"' differs from the polyline's '" &
                                              //trim(t%color)//"' (line "//itoa(t%src%line)//')')
        t%nodes = [t%nodes, nodb]
      end associate
      return
    end if
    ntac = ntac + 1
    if (ntac > size(tacs)) call grow(tacs)
    associate (t => tacs(ntac))
      t%kind = kind
      t%color = color
      t%src = ln%src
      t%nodes = [noda, nodb]
      if (kind == 'CLxxx') then
        apab = get_real(ln, 59, 72, "position on the edge 'apab='")
        if (apab < 0.0_wp .or. apab > 1.0_wp) call line_error(ln, 59, "'apab=' (position of the point on the edge " &
                                                              //'noda-nodb) must be in [0, 1], found '//rtoa(apab))
        t%apab = apab
      end if
    end associate
  end subroutine read_mesh_tactor

  !> Number of nodes of an element geometry, 0 if unknown.
  pure integer function element_node_count(kind) result(n)
    character(len=*), intent(in) :: kind
    integer :: k
    n = 0
    do k = 1, size(element_kinds)
      if (kind == element_kinds(k)) n = element_nodes(k)
    end do
  end function element_node_count

  function kind_list() result(s)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, size(element_kinds)
      if (k > 1) s = s//', '
      s = s//element_kinds(k)
    end do
  end function kind_list

  !> "columns 21-41" for n node fields.
  function node_cols(n) result(s)
    integer, intent(in) :: n
    character(len=:), allocatable :: s
    s = 'columns '//itoa(node_col0)//'-'//itoa(node_col0 + node_width*n - 1)
  end function node_cols

  !> Index in BODIES of each body by its number within its model.
  function body_lookup(bodies) result(lk)
    type(body_input_t), intent(in) :: bodies(:)
    type(body_lookup_t) :: lk
    integer :: k, nr, nm
    allocate (lk%rigid(count(bodies%model == 'RBDY2')), lk%mesh(count(bodies%model == 'MAILx')))
    nr = 0
    nm = 0
    do k = 1, size(bodies)
      if (bodies(k)%model == 'RBDY2') then
        nr = nr + 1
        lk%rigid(nr) = k
      else if (bodies(k)%model == 'MAILx') then
        nm = nm + 1
        lk%mesh(nm) = k
      end if
    end do
  end function body_lookup

  !> Index in BODIES of body NUMBER of MODEL, 0 if there is none.
  pure integer function find_body(lk, model, number) result(ib)
    type(body_lookup_t), intent(in) :: lk
    character(len=*), intent(in) :: model
    integer, intent(in) :: number
    ib = 0
    if (model == 'RBDY2') then
      if (number >= 1 .and. number <= size(lk%rigid)) ib = lk%rigid(number)
    else if (model == 'MAILx') then
      if (number >= 1 .and. number <= size(lk%mesh)) ib = lk%mesh(number)
    end if
  end function find_body

  !> "body 3 does not exist (BODIES.DAT has 2 bodies)"; in a deck with meshed
  !> bodies the model is named: "MAILx body 3 does not exist (BODIES.DAT has 2 MAILx bodies)".
  function no_such_body(bodies, model, number) result(s)
    type(body_input_t), intent(in) :: bodies(:)
    character(len=*), intent(in) :: model
    integer, intent(in) :: number
    character(len=:), allocatable :: s
    if (all(bodies%model == 'RBDY2') .and. model == 'RBDY2') then
      s = 'body '//itoa(number)//' does not exist (BODIES.DAT has '//itoa(size(bodies))//' bodies)'
    else
      s = trim(model)//' body '//itoa(number)//' does not exist (BODIES.DAT has '// &
          itoa(count(bodies%model == model))//' '//trim(model)//' bodies)'
    end if
  end function no_such_body

  subroutine grow_elements(elems)
    type(element_input_t), allocatable, intent(inout) :: elems(:)
    type(element_input_t), allocatable :: tmp(:)
    allocate (tmp(2*size(elems)))
    tmp(1:size(elems)) = elems
    call move_alloc(tmp, elems)
  end subroutine grow_elements

  subroutine grow_coor(coor)
    real(wp), allocatable, intent(inout) :: coor(:, :)
    real(wp), allocatable :: tmp(:, :)
    allocate (tmp(2, 2*size(coor, 2)))
    tmp(:, 1:size(coor, 2)) = coor
    call move_alloc(tmp, coor)
  end subroutine grow_coor

  subroutine grow(tacs)
    type(tactor_input_t), allocatable, intent(inout) :: tacs(:)
    type(tactor_input_t), allocatable :: tmp(:)
    allocate (tmp(2*size(tacs)))
    tmp(1:size(tacs)) = tacs
    call move_alloc(tmp, tacs)
  end subroutine grow
end module fracas_read_bodies
