!> OUTBOX text writers in LMGC90's layout: DOF.OUT.n, Vloc_Rloc.OUT.n and
!> GPV.OUT.n (values in D14.7, e.g. 0.1234567D+01). A file is written to PATH.part and
!> renamed to PATH once complete, so an interrupted run never leaves a
!> complete-looking file.
module fracas_write_outbox
  use fracas_kinds, only: wp
  use fracas_errors, only: fatal
  use fracas_files, only: atomic_rename, close_written
  use fracas_deck, only: dof_record_t, contact_record_t, gpv_record_t
  use fracas_deck_3d, only: dof3_record_t
  use fracas_read_vloc_rloc, only: vloc_layout_t, vloc_layout, internals_per_line
  use fracas_vloc_rloc_3d, only: contact3_record_t, write_vloc3_record
  implicit none
  private
  public :: write_dof_file, write_vloc_rloc_file, write_gpv_file, write_dof_file_3d, write_vloc_rloc_file_3d

  character(len=*), parameter :: rule = '!-----------------------------------------------------------------------'
  !> Names of the 2D cohesive internals (L, ut, un, beta, TPSini) in the comment
  !> line before the internal values, padded as LMGC90 pads it.
  character(len=*), parameter :: czm_names = 'taille_ele     saut_de_ut     saut_de_un     beta           TPSini'
  integer, parameter :: comment_len = 284
  character(len=*), parameter :: fmt_steps = '(a6,i9,14x,a5,d14.7)'
  character(len=*), parameter :: fmt_3 = '(29x,3(a5,d14.7,:,2x))'
  !> Values of the stress and strain lines of a Gauss point in GPV files
  !> (xx, yy, xy, zz); further values (internal variables) go on a third line.
  integer, parameter :: gpv_line_values = 4

contains

  !> DOF.OUT.n: header, the rigid bodies (body number, X(1..3), V(1..3)), then
  !> the meshed bodies (per node X(1..2), V(1..2)), each model in the order of
  !> RECORDS. As LMGC90, the rigid part always ends with a rule line, the
  !> meshed part only when there are meshed bodies, and a last rule closes the file.
  subroutine write_dof_file(path, step, time, records)
    character(len=*), intent(in) :: path
    integer, intent(in) :: step
    real(wp), intent(in) :: time
    type(dof_record_t), intent(in) :: records(:)
    integer :: u, k, j

    u = open_titled(path, '! DOF', 5, step, time)
    do k = 1, size(records)
      associate (r => records(k))
        if (r%model /= 'RBDY2') cycle
        write (u, '(a)') '$bdyty'
        write (u, '(1x,a5,i9)') r%model, r%body
        write (u, '(a)') '$nodty'
        write (u, '(1x,a5,2x,i5,16x,3(a5,d14.7,:,2x))') 'NO3xx', 1, 'X(1)=', r%x(1), 'X(2)=', r%x(2), 'X(3)=', r%x(3)
        write (u, fmt_3) 'V(1)=', r%v(1), 'V(2)=', r%v(2), 'V(3)=', r%v(3)
        write (u, '(a)') '$$$$$$'
        write (u, '(a)') '      '
      end associate
    end do
    write (u, '(a)') rule
    if (any(records%model == 'MAILx')) then
      do k = 1, size(records)
        associate (r => records(k))
          if (r%model /= 'MAILx') cycle
          write (u, '(a)') '$bdyty'
          write (u, '(1x,a5,i7)') r%model, r%body
          write (u, '(a)') '$model'
          write (u, '(a)') ' MECAx'
          write (u, '(a)') '$nodty'
          do j = 1, size(r%nodes)
            write (u, '(1x,a5,2x,i5,16x,2(a5,d14.7,:,2x))') 'NO2xx', r%nodes(j), 'X(1)=', r%node_x(1, j), &
              'X(2)=', r%node_x(2, j)
            write (u, fmt_3) 'V(1)=', r%node_v(1, j), 'V(2)=', r%node_v(2, j)
          end do
          write (u, '(a)') '$$$$$$'
          write (u, '(a)') '      '
        end associate
      end do
      write (u, '(a)') rule
    end if
    write (u, '(a)') rule
    call close_part(u, path)
  end subroutine write_dof_file

  !> DOF.OUT.n of a 3D deck (RBDY3, as LMGC90's RBDY3 writes it): per body
  !> the NO6xx lines X(1..3), X(4..6) (0: LMGC90 keeps the rotation as the
  !> frame), V(1..3), V(4..6) (omega in the principal frame), then the frame's
  !> axes on the lines a(1..3), b(1..3), g(1..3); a rule after the bodies and a
  !> last one, as the 2D file.
  subroutine write_dof_file_3d(path, step, time, records)
    character(len=*), intent(in) :: path
    integer, intent(in) :: step
    real(wp), intent(in) :: time
    type(dof3_record_t), intent(in) :: records(:)
    integer :: u, k, i, j
    character(len=5), parameter :: axis_label(3, 3) = reshape(['a(1)=', 'a(2)=', 'a(3)=', 'b(1)=', 'b(2)=', 'b(3)=', &
                                                               'g(1)=', 'g(2)=', 'g(3)='], [3, 3])
    u = open_titled(path, '! DOF', 5, step, time)
    do k = 1, size(records)
      associate (r => records(k))
        write (u, '(a)') '$bdyty'
        write (u, '(1x,a5,i9)') 'RBDY3', r%body
        write (u, '(a)') '$nodty'
        write (u, '(1x,a5,2x,i5,16x,3(a5,d14.7,:,2x))') 'NO6xx', 1, 'X(1)=', r%x(1), 'X(2)=', r%x(2), 'X(3)=', r%x(3)
        write (u, fmt_3) 'X(4)=', r%x(4), 'X(5)=', r%x(5), 'X(6)=', r%x(6)
        write (u, fmt_3) 'V(1)=', r%v(1), 'V(2)=', r%v(2), 'V(3)=', r%v(3)
        write (u, fmt_3) 'V(4)=', r%v(4), 'V(5)=', r%v(5), 'V(6)=', r%v(6)
        do j = 1, 3
          write (u, fmt_3) (axis_label(i, j), r%frame(i, j), i=1, 3)
        end do
        write (u, '(a)') '$$$$$$'
        write (u, '(a)') '      '
      end associate
    end do
    write (u, '(a)') rule
    write (u, '(a)') rule
    call close_part(u, path)
  end subroutine write_dof_file_3d

  !> Open PATH.part and write LMGC90's header: a blank line, TITLE, PAD blanks
  !> (LMGC90 pads DOF's with 5, Vloc_Rloc's with 6), '$steps', a blank, a rule.
  integer function open_titled(path, title, pad, step, time) result(u)
    character(len=*), intent(in) :: path, title
    integer, intent(in) :: pad, step
    real(wp), intent(in) :: time
    u = open_part(path)
    write (u, '(a)') '     '
    write (u, '(a)') title
    write (u, '(a)') repeat(' ', pad)
    write (u, fmt_steps) '$steps', step, 'time=', time
    write (u, '(a)') ' '
    write (u, '(a)') rule
  end function open_titled

  !> GPV.OUT.n: header, then per meshed body ('$bdyty', body number) its
  !> elements ('$blmty', geometry and rank, '$model' MECAx) with, per Gauss
  !> point, the stress line, the strain line and, if there are more values,
  !> one line of internal values. Records of one body follow each other.
  subroutine write_gpv_file(path, step, time, records)
    character(len=*), intent(in) :: path
    integer, intent(in) :: step
    real(wp), intent(in) :: time
    type(gpv_record_t), intent(in) :: records(:)
    integer :: u, k, g, nv, body

    u = open_part(path)
    write (u, '(a)') '     '
    write (u, '(a)') '! Gauss Point Values'
    write (u, '(a)') '      '
    write (u, fmt_steps) '$steps', step, 'time=', time
    write (u, '(a)') ' '
    write (u, '(a)') rule
    body = 0
    do k = 1, size(records)
      associate (r => records(k))
        if (r%body /= body) then
          if (body /= 0) write (u, '(a)') '$$$$$$'
          write (u, '(a)') '$bdyty'
          write (u, '(1x,a5,i7)') 'MAILx', r%body
          body = r%body
        end if
        write (u, '(a)') '$blmty'
        write (u, '(1x,a5,i7)') r%kind, r%element
        write (u, '(a)') '$model'
        write (u, '(a)') ' MECAx'
        nv = size(r%values, 1)
        do g = 1, size(r%values, 2)
          write (u, '(*(d14.7))') r%values(1:min(nv, gpv_line_values), g)
          if (nv > gpv_line_values) write (u, '(*(d14.7))') r%values(gpv_line_values + 1:min(nv, 2*gpv_line_values), g)
          if (nv > 2*gpv_line_values) write (u, '(*(d14.7))') r%values(2*gpv_line_values + 1:nv, g)
        end do
      end associate
    end do
    if (body /= 0) write (u, '(a)') '$$$$$$'
    write (u, '(a)') rule
    call close_part(u, path)
  end subroutine write_gpv_file

  !> Vloc_Rloc.OUT.n: header then one $icdan block per record, with the id
  !> line layout of its interaction type, n/coo lines if has_geometry and the
  !> internal values (after a '#' comment line) if any.
  subroutine write_vloc_rloc_file(path, step, time, records)
    character(len=*), intent(in) :: path
    integer, intent(in) :: step
    real(wp), intent(in) :: time
    type(contact_record_t), intent(in) :: records(:)
    integer :: u, k
    type(vloc_layout_t) :: lay

    u = open_titled(path, '! Vloc_Rloc', 6, step, time)
    do k = 1, size(records)
      associate (r => records(k))
        lay = vloc_layout(r%inter)
        write (u, '(a6,2x,a5,i9)') '$icdan', r%inter, r%number
        write (u, '(a)') lay%header(1:lay%header_len)
        write (u, '(a)') id_line(r, lay)
        write (u, fmt_3) 'rlt/H', r%rlt, 'rln/H', r%rln, lay%rls_label, 0.0_wp
        write (u, fmt_3) 'vlt =', r%vlt, 'vln =', r%vln, 'vls =', 0.0_wp
        write (u, fmt_3) 'gapTT', r%gap
        if (r%has_geometry) then
          write (u, fmt_3) 'n(1)=', r%normal(1), 'n(2)=', r%normal(2), 'n(3)=', 0.0_wp
          write (u, fmt_3) 'coo1=', r%coor(1), 'coo2=', r%coor(2), 'coo3=', 0.0_wp
        end if
        if (allocated(r%internals)) call write_internals(u, r%internals, r%internal_name)
        write (u, '(a)') ' '
      end associate
    end do
    call close_part(u, path)
  end subroutine write_vloc_rloc_file

  !> Vloc_Rloc.OUT.n of 3D interactions (fracas_vloc_rloc_3d's layouts): the
  !> header of the 2D file, then per record its lines and internal values.
  subroutine write_vloc_rloc_file_3d(path, step, time, records)
    character(len=*), intent(in) :: path
    integer, intent(in) :: step
    real(wp), intent(in) :: time
    type(contact3_record_t), intent(in) :: records(:)
    integer :: u, k
    u = open_titled(path, '! Vloc_Rloc', 6, step, time)
    do k = 1, size(records)
      call write_vloc3_record(u, records(k))
      if (allocated(records(k)%internals)) call write_internals(u, records(k)%internals, '')
      write (u, '(a)') ' '
    end do
    call close_part(u, path)
  end subroutine write_vloc_rloc_file_3d

  !> A record's internal values, if any: a '#' line naming them (NAME when
  !> there is one value and a name), then internals_per_line values per line.
  subroutine write_internals(u, internals, name)
    integer, intent(in) :: u
    real(wp), intent(in) :: internals(:)
    character(len=*), intent(in) :: name
    integer :: n, j
    n = size(internals)
    if (n == 0) return
    if (len_trim(name) > 0 .and. n == 1) then
      write (u, '(a)') '#'//name
    else
      write (u, '(a)') '#'//internal_comment(n)
    end if
    do j = 1, n, internals_per_line
      write (u, '(*(1x,d14.7))') internals(j:min(n, j + internals_per_line - 1))
    end do
  end subroutine write_internals

  !> The id line of a record, fields placed at the columns of its layout.
  function id_line(r, lay) result(s)
    type(contact_record_t), intent(in) :: r
    type(vloc_layout_t), intent(in) :: lay
    character(len=lay%width) :: s
    s = ''
    call put(r%cdbdy, lay%cdbdy)
    call put_int(r%icdbdy, lay%icdbdy, 5)
    call put(r%cdtac, lay%cdtac)
    call put_int(r%icdtac, lay%icdtac, 5)
    if (lay%cdver > 0) then
      call put('CDVER', lay%cdver_label)
      call put_int(r%cdver, lay%cdver, 5)
    end if
    call put(r%behav, lay%behav)
    call put(r%anbdy, lay%anbdy)
    call put_int(r%ianbdy, lay%ianbdy, 5)
    call put(r%antac, lay%antac)
    call put_int(r%iantac, lay%iantac, 5)
    if (lay%anseg > 0) then
      if (lay%anseg_label > 0) call put('ANSEG', lay%anseg_label)
      call put_int(r%anseg, lay%anseg, 5)
    end if
    call put(r%status, lay%status)
    call put_int(r%iadj, lay%iadj, lay%w_iadj)

  contains

    subroutine put(word, col)
      character(len=*), intent(in) :: word
      integer, intent(in) :: col
      s(col:col + 4) = word
    end subroutine put

    subroutine put_int(i, col, w)
      integer, intent(in) :: i, col, w
      character(len=16) :: f
      write (f, '(a,i0,a)') '(i', w, ')'
      write (s(col:col + w - 1), f) i
    end subroutine put_int
  end function id_line

  !> Names of n internal values in 15-character columns, padded to comment_len:
  !> the cohesive internals for 5, the contact length alone for 1 (LMGC90's
  !> one internal of a contact on a mesh with a law without internals).
  function internal_comment(n) result(s)
    integer, intent(in) :: n
    character(len=comment_len) :: s
    integer :: k
    if (n == 5) then
      s = czm_names
    else if (n == 1) then
      s = czm_names(1:10)
    else
      s = ''
      do k = 1, min(n, 18)   ! 18 names of 15 characters fit in comment_len
        write (s(15*(k - 1) + 1:15*k), '(a,i0,a)') 'internal(', k, ')'
      end do
    end if
  end function internal_comment

  integer function open_part(path) result(u)
    character(len=*), intent(in) :: path
    integer :: ios
    character(len=256) :: iomsg
    open (newunit=u, file=path//'.part', status='replace', action='write', form='formatted', &
          iostat=ios, iomsg=iomsg)
    if (ios /= 0) call fatal('cannot write '//path//'.part: '//trim(iomsg))
  end function open_part

  !> Close the unit and move PATH.part to PATH.
  subroutine close_part(u, path)
    integer, intent(in) :: u
    character(len=*), intent(in) :: path
    call close_written(u, path//'.part')
    call atomic_rename(path//'.part', path)
  end subroutine close_part
end module fracas_write_outbox
