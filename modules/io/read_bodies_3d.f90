!> LMGC90's 3D DATBOX, rigid part: RBDY3 bodies of BODIES.DAT and their
!> DOF.INI records (DRV_DOF.DAT's RBDY3 blocks are read by fracas_read_drv_dof).
!> Not used by the scene yet (the scene is 2D; doc/rigid_3d.md). Records, as
!> LMGC90 writes them (values in columns 35-48, 56-69, 77-90):
!> - ' RBDY3  number'; $blmty: ' PLAIN  1  behav  NICKx  avrd= ...', then
!>   optionally the line 'I1  = ... I2  = ... I3  = ...' ('I1' in columns
!>   30-31; LMGC90 takes the moments as zero otherwise);
!> - $nodty: ' NO6xx  1  coo1= coo2= coo3=' and its line coo4= coo5= coo6=;
!> - $tacty: ' SPHER  1  color  COLOR  byrd= r' (SPHEb: and a line coo1..3,
!>   its offset from the node); ' PLANx  1  color  COLOR
!>   axe1= axe2= axe3=', optionally followed by 'localframe' (columns 30-39)
!>   and the lines alpha, beta, gamma (the plane's axes) and coo1..3 (offset);
!> - ' CYLND  1  color  COLOR  High= h  byrd= r' (h: half length of the axis
!>   segment, along the contactor's third axis), with the same optional
!>   'localframe' block;
!> - ' POLYR  1  color  COLOR  nb_vertex= nv  nb_faces= nf', nv vertex lines
!>   (coo1..3, relative to the node) and nf lines of three vertex numbers;
!> - $$$$$$ ends the body.
!> DOF.INI: '$steps', then per body ' RBDY3  number' (9-15), $nodty, the
!> NO6xx X lines (2), the V lines (2) and the alpha, beta, gamma lines.
module fracas_read_bodies_3d
  use fracas_kinds, only: wp
  use fracas_deck, only: material_input_t
  use fracas_deck_3d, only: tactor3_input_t, body3_input_t, dof3_record_t
  use fracas_read_bodies, only: check_material_defined
  use fracas_frame_3d, only: polyhedron_volume_inertia, cross3, identity3
  use fracas_datbox_text, only: text_file_t, text_line_t, load_text, line_error, field, check_line_end, &
                                keyword_of, is_data, get_real, get_word, get_int, itoa, rtoa, get_steps
  implicit none
  private
  public :: read_bodies_3d, read_dof_3d

  integer, parameter :: value_col(3) = [35, 56, 77]

contains

  !> Read PATH into BODIES (RBDY3 only). With MATERIALS, every PLAIN's
  !> nickname must be one of them.
  subroutine read_bodies_3d(path, bodies, materials)
    character(len=*), intent(in) :: path
    type(body3_input_t), allocatable, intent(out) :: bodies(:)
    type(material_input_t), intent(in), optional :: materials(:)
    type(text_file_t) :: tf
    integer :: i, nb, ib
    call load_text(path, tf)
    nb = count([(keyword_of(tf%lines(i)) == 'bdyty', i=1, tf%n)])
    allocate (bodies(nb))
    ib = 0
    i = 1
    do while (i <= tf%n)
      if (keyword_of(tf%lines(i)) /= 'bdyty') &
        call line_error(tf%lines(i), 1, "expected '$bdyty' (start of a body), found '"//trim(field(tf%lines(i), 1, 40))//"'")
      if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$bdyty' must be followed by ' RBDY3  number'")
      if (get_word(tf%lines(i + 1), 2, 6, 'body model') /= 'RBDY3') &
        call line_error(tf%lines(i + 1), 2, "unknown body model '"//trim(field(tf%lines(i + 1), 2, 6))// &
                        "' in a 3D deck (supported: RBDY3)")
      ib = ib + 1
      call read_body3(tf, i, bodies(ib), ib, materials)
    end do
  end subroutine read_bodies_3d

  !> One RBDY3 from its '$bdyty' line to '$$$$$$'; i ends after it.
  subroutine read_body3(tf, i, b, number, materials)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(body3_input_t), intent(inout) :: b
    integer, intent(in) :: number
    type(material_input_t), intent(in), optional :: materials(:)
    type(tactor3_input_t) :: tacs(64)
    integer :: ibdy, ntac
    logical :: have_bulk, have_node
    ibdy = i
    b%number = number
    b%src = tf%lines(i + 1)%src
    have_bulk = .false.
    have_node = .false.
    ntac = 0
    i = i + 2
    do
      if (i > tf%n) call line_error(tf%lines(ibdy), 1, 'body '//itoa(number)//" is not closed by '$$$$$$'")
      select case (keyword_of(tf%lines(i)))
      case ('$$$$$')
        i = i + 1
        exit
      case ('blmty')
        i = i + 1
        if (.not. is_data(tf, i)) call line_error(tf%lines(i - 1), 1, "'$blmty' must be followed by a PLAIN line")
        if (have_bulk) call line_error(tf%lines(i), 2, 'a rigid body has exactly one PLAIN line')
        have_bulk = .true.
        call read_plain(tf, i, b, materials)
      case ('nodty')
        i = i + 1
        if (.not. (is_data(tf, i) .and. is_data(tf, i + 1))) &
          call line_error(tf%lines(i - 1), 1, "'$nodty' must be followed by the NO6xx line (coo1..3) and its line coo4..6")
        if (get_word(tf%lines(i), 2, 6, 'node type') /= 'NO6xx') &
          call line_error(tf%lines(i), 2, "unknown node type '"//trim(field(tf%lines(i), 2, 6))// &
                          "' for RBDY3 (supported: NO6xx)")
        if (have_node) call line_error(tf%lines(i), 2, 'a rigid body has exactly one NO6xx node')
        have_node = .true.
        b%coor(1:3) = values3(tf%lines(i), 'coo')
        b%coor(4:6) = values3(tf%lines(i + 1), 'coo')
        i = i + 2
      case ('tacty')
        i = i + 1
        do while (is_data(tf, i))
          ntac = ntac + 1
          if (ntac > size(tacs)) call line_error(tf%lines(i), 2, 'more than '//itoa(size(tacs))//' contactors in one body')
          call read_tactor3(tf, i, tacs(ntac))
        end do
      case default
        call line_error(tf%lines(i), 1, "expected $blmty, $nodty, $tacty or $$$$$$ in an RBDY3, found '"// &
                        trim(field(tf%lines(i), 1, 40))//"'")
      end select
    end do
    if (.not. have_bulk) call line_error(tf%lines(ibdy), 1, 'body '//itoa(number)//" has no '$blmty' PLAIN line")
    if (.not. have_node) call line_error(tf%lines(ibdy), 1, 'body '//itoa(number)//" has no '$nodty' NO6xx node")
    if (ntac == 0) call line_error(tf%lines(ibdy), 1, 'body '//itoa(number)//' has no contactor (its mass comes from them)')
    b%tactors = tacs(1:ntac)
  end subroutine read_body3

  !> The PLAIN line at i and its optional 'I1  =' line; i ends after them.
  subroutine read_plain(tf, i, b, materials)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(body3_input_t), intent(inout) :: b
    type(material_input_t), intent(in), optional :: materials(:)
    associate (ln => tf%lines(i))
      if (get_word(ln, 2, 6, 'bulk element type') /= 'PLAIN') &
        call line_error(ln, 2, "unknown bulk element '"//trim(field(ln, 2, 6))//"' for RBDY3 (supported: PLAIN)")
      b%behav = get_word(ln, 23, 27, 'material nickname')
      b%avrd = get_real(ln, 35, 48, "average radius 'avrd='")
      if (b%avrd < 0.0_wp) call line_error(ln, 35, 'avrd must be >= 0 (0: computed from the contactors), found '//rtoa(b%avrd))
      call check_line_end(ln, 48, 'the PLAIN line')
      if (present(materials)) call check_material_defined(ln, b%behav, materials)
    end associate
    i = i + 1
    if (.not. is_data(tf, i)) return
    if (field(tf%lines(i), 30, 31) /= 'I1') return
    b%inertia = values3(tf%lines(i), 'I')
    if (any(b%inertia < 0.0_wp)) call line_error(tf%lines(i), 35, 'principal inertia must be >= 0 (0: computed)')
    i = i + 1
  end subroutine read_plain

  !> One contactor at line i with its continuation lines; i ends after them.
  subroutine read_tactor3(tf, i, t)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(tactor3_input_t), intent(out) :: t
    integer :: k
    associate (ln => tf%lines(i))
      t%src = ln%src
      t%kind = get_word(ln, 2, 6, 'contactor type')
      t%color = get_word(ln, 23, 27, 'colour')
      select case (t%kind)
      case ('SPHER', 'SPHEb')
        t%radius = get_real(ln, 35, 48, "radius 'byrd='")
        if (t%radius <= 0.0_wp) call line_error(ln, 35, t%kind//' radius must be > 0, found '//rtoa(t%radius))
        call check_line_end(ln, 48, 'the '//t%kind//' line')
        if (t%kind == 'SPHEb') then
          i = i + 1
          if (.not. is_data(tf, i)) call line_error(ln, 1, 'SPHEb needs an offset line (coo1=, coo2=, coo3=) after it')
          t%shift = values3(tf%lines(i), 'coo')
        end if
      case ('PLANx')
        t%axes = values3(ln, 'axe')
        do k = 1, 3
          if (t%axes(k) <= 0.0_wp) call line_error(ln, value_col(k), 'PLANx half axes must be > 0, found '//rtoa(t%axes(k)))
        end do
        call read_localframe(tf, i, t)
      case ('CYLND')
        ! 'High=' (half length of the axis segment) at 35-48, 'byrd=' at 56-69, as LMGC90
        t%axes(1) = get_real(ln, 35, 48, "half length 'High='")
        t%radius = get_real(ln, 56, 69, "radius 'byrd='")
        if (t%axes(1) <= 0.0_wp) call line_error(ln, 35, 'CYLND High must be > 0, found '//rtoa(t%axes(1)))
        if (t%radius <= 0.0_wp) call line_error(ln, 56, 'CYLND radius must be > 0, found '//rtoa(t%radius))
        call check_line_end(ln, 69, 'the CYLND line')
        call read_localframe(tf, i, t)
      case ('POLYR')
        call read_polyr(tf, i, t)
      case ('DNLYC', 'PT3Dx', 'POLYF')
        call line_error(ln, 2, "contactor '"//t%kind//"' is not read yet (3D: SPHER, SPHEb, PLANx, POLYR, CYLND)")
      case default
        call line_error(ln, 2, "unknown contactor type '"//trim(t%kind)//"' for RBDY3 (supported: SPHER, SPHEb, " &
                        //"PLANx, POLYR, CYLND)")
      end select
    end associate
    i = i + 1
  end subroutine read_tactor3

  !> The optional 'localframe' block after line i of a PLANx or CYLND (columns
  !> 30-39), then the lines alpha, beta, gamma (axes, global) and coo1..3
  !> (offset); i ends at its last line.
  subroutine read_localframe(tf, i, t)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(tactor3_input_t), intent(inout) :: t
    real(wp) :: g
    integer :: k
    if (.not. is_data(tf, i + 1)) return
    if (field(tf%lines(i + 1), 30, 39) /= 'localframe') return
    if (.not. all([(is_data(tf, i + 1 + k), k=1, 4)])) &
      call line_error(tf%lines(i + 1), 30, "'localframe' must be followed by the alpha, beta, gamma and coo lines")
    do k = 1, 3
      t%frame(:, k) = values3(tf%lines(i + 1 + k), 'axis')
    end do
    t%shift = values3(tf%lines(i + 5), 'coo')
    ! an orthonormal right-handed frame, to the 7 digits the file keeps
    g = maxval(abs(matmul(transpose(t%frame), t%frame) - identity3()))
    if (g > 1.0e-6_wp) call line_error(tf%lines(i + 2), 35, 'the '//t%kind//' localframe is not orthonormal ' &
                                        //'(|F^T F - I| = '//rtoa(g)//')')
    i = i + 5
  end subroutine read_localframe

  !> A POLYR line ('nb_vertex=' count in columns 40-47, 'nb_faces=' in 60-67),
  !> its vertex lines (coo1..3) and face lines (three vertex numbers in columns
  !> 35-47, 56-68, 77-89); i ends at the last face line. The surface must
  !> enclose a positive volume (outward triangles) and be convex (every vertex
  !> on the inner side of every triangle's plane, to 1e-9 of the extent; a
  !> non-convex shape is several POLYR, as in LMGC90).
  subroutine read_polyr(tf, i, t)
    type(text_file_t), intent(in) :: tf
    integer, intent(inout) :: i
    type(tactor3_input_t), intent(inout) :: t
    integer :: nv, nf, k, j
    integer, parameter :: face_col(3) = [35, 56, 77]
    associate (ln => tf%lines(i))
      nv = get_int(ln, 40, 47, "number of vertices 'nb_vertex='")
      nf = get_int(ln, 60, 67, "number of faces 'nb_faces='")
      if (nv < 4) call line_error(ln, 40, 'a POLYR needs at least 4 vertices, found '//itoa(nv))
      if (nf < 4) call line_error(ln, 60, 'a POLYR needs at least 4 triangles, found '//itoa(nf))
      call check_line_end(ln, 67, 'the POLYR line')
      if (.not. all([(is_data(tf, i + k), k=1, nv + nf)])) &
        call line_error(ln, 2, 'POLYR declares '//itoa(nv)//' vertices and '//itoa(nf)//' faces: '//itoa(nv + nf)// &
                        ' lines must follow')
    end associate
    allocate (t%vert(3, nv), t%faces(3, nf))
    do k = 1, nv
      t%vert(:, k) = values3(tf%lines(i + k), 'vertex coo')
    end do
    do k = 1, nf
      associate (lf => tf%lines(i + nv + k))
        do j = 1, 3
          t%faces(j, k) = get_int(lf, face_col(j), face_col(j) + 12, 'face vertex number')
          if (t%faces(j, k) < 1 .or. t%faces(j, k) > nv) &
            call line_error(lf, face_col(j), 'face vertex '//itoa(t%faces(j, k))//' does not exist (the POLYR has ' &
                            //itoa(nv)//' vertices)')
        end do
        call check_line_end(lf, 89, 'a POLYR face line')
      end associate
    end do
    call check_polyr_shape(tf%lines(i), t%vert, t%faces)
    i = i + nv + nf
  end subroutine read_polyr

  subroutine check_polyr_shape(ln, vert, faces)
    type(text_line_t), intent(in) :: ln
    real(wp), intent(in) :: vert(:, :)
    integer, intent(in) :: faces(:, :)
    real(wp) :: vol, g(3), tens(3, 3), nrm(3), extent, d
    integer :: k, j
    call polyhedron_volume_inertia(vert, faces, vol, g, tens)
    if (.not. vol > 0.0_wp) call line_error(ln, 2, 'POLYR encloses no positive volume (volume '//rtoa(vol)// &
                                            '): its triangles must be closed and counter-clockwise seen from outside')
    extent = maxval(maxval(vert, dim=2) - minval(vert, dim=2))
    do k = 1, size(faces, 2)
      nrm = cross3(vert(:, faces(2, k)) - vert(:, faces(1, k)), vert(:, faces(3, k)) - vert(:, faces(1, k)))
      if (norm2(nrm) <= epsilon(1.0_wp) * extent**2) call line_error(ln, 2, 'POLYR face '//itoa(k)//' is degenerate')
      nrm = nrm / norm2(nrm)
      do j = 1, size(vert, 2)
        d = dot_product(vert(:, j) - vert(:, faces(1, k)), nrm)
        if (d > 1.0e-9_wp * extent) call line_error(ln, 2, 'POLYR is not convex: vertex '//itoa(j)// &
                                                    ' is outside the plane of face '//itoa(k)//' by '//rtoa(d)// &
                                                    ' (a non-convex shape is several POLYR)')
      end do
    end do
  end subroutine check_polyr_shape

  !> The three values of a line in columns 35-48, 56-69, 77-90, nothing after.
  function values3(ln, what) result(v)
    type(text_line_t), intent(in) :: ln
    character(len=*), intent(in) :: what
    real(wp) :: v(3)
    integer :: k
    do k = 1, 3
      v(k) = get_real(ln, value_col(k), value_col(k) + 13, what//' '//itoa(k))
    end do
    call check_line_end(ln, 90, 'a line of three values')
  end function values3

  !> DOF.INI of a 3D deck: step, time and one record per RBDY3 (numbers in
  !> 1..NBODIES, each once).
  subroutine read_dof_3d(path, nbodies, step, time, records)
    character(len=*), intent(in) :: path
    integer, intent(in) :: nbodies
    integer, intent(out) :: step
    real(wp), intent(out) :: time
    type(dof3_record_t), allocatable, intent(out) :: records(:)
    type(text_file_t) :: tf
    integer :: i, n, k
    integer, allocatable :: seen(:)
    call load_text(path, tf)
    step = 0
    time = 0.0_wp
    allocate (records(count([(keyword_of(tf%lines(i)) == 'bdyty', i=1, tf%n)])), seen(nbodies))
    seen = 0
    n = 0
    i = 1
    do while (i <= tf%n)
      select case (keyword_of(tf%lines(i)))
      case ('steps')
        call get_steps(tf%lines(i), step, time)
        i = i + 1
      case ('bdyty')
        if (.not. is_data(tf, i + 1)) call line_error(tf%lines(i), 1, "'$bdyty' must be followed by ' RBDY3  number'")
        n = n + 1
        associate (ln => tf%lines(i + 1), r => records(n))
          if (get_word(ln, 2, 6, 'body model') /= 'RBDY3') &
            call line_error(ln, 2, "unknown body model '"//trim(field(ln, 2, 6))//"' in a 3D DOF.INI (supported: RBDY3)")
          r%body = get_int(ln, 9, 15, 'body number')
          r%src = ln%src
          if (r%body < 1 .or. r%body > nbodies) &
            call line_error(ln, 9, 'RBDY3 body '//itoa(r%body)//' does not exist (BODIES.DAT has '//itoa(nbodies)//')')
          if (seen(r%body) > 0) call line_error(ln, 9, 'RBDY3 body '//itoa(r%body)//' is already given at line ' &
                                                //itoa(seen(r%body)))
          seen(r%body) = ln%src%line
        end associate
        i = i + 2
        if (keyword_of(tf%lines(min(i, tf%n))) /= 'nodty' .or. i > tf%n) &
          call line_error(tf%lines(i - 1), 1, "expected '$nodty' after the body line")
        if (.not. all([(is_data(tf, i + k), k=1, 7)])) &
          call line_error(tf%lines(i), 1, "'$nodty' must be followed by the NO6xx lines X(1..6), V(1..6) " &
                          //'and the alpha, beta, gamma lines')
        if (get_word(tf%lines(i + 1), 2, 6, 'node type') /= 'NO6xx') &
          call line_error(tf%lines(i + 1), 2, "unknown node type '"//trim(field(tf%lines(i + 1), 2, 6))// &
                          "' for RBDY3 (supported: NO6xx)")
        associate (r => records(n))
          r%x(1:3) = values3(tf%lines(i + 1), 'X')
          r%x(4:6) = values3(tf%lines(i + 2), 'X')
          r%v(1:3) = values3(tf%lines(i + 3), 'V')
          r%v(4:6) = values3(tf%lines(i + 4), 'V')
          do k = 1, 3
            r%frame(:, k) = values3(tf%lines(i + 4 + k), 'axis')
          end do
        end associate
        i = i + 8
      case ('$$$$$')
        i = i + 1
      case default
        call line_error(tf%lines(i), 1, "expected $steps, $bdyty or $$$$$$, found '"//trim(field(tf%lines(i), 1, 40))//"'")
      end select
    end do
  end subroutine read_dof_3d
end module fracas_read_bodies_3d
