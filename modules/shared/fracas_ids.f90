!> Integer ids and their LMGC90 names for contact statuses, interaction types and
!> contactor kinds.
!> Output files store the integer; the name tables are written next to them.
module fracas_ids
  implicit none
  private
  public :: n_status, status_names, st_noctc, st_stick, st_slifw, st_slibw, st_noact, &
            st_cnctc, st_cstck, st_cslfw, st_cslbw, status_id, &
            n_inter, inter_names, i_dkdkx, i_dkjcx, i_dkkdx, i_dkplx, i_plplx, i_pljcx, inter_id, &
            i_clalp, i_cljcx, i_dkalp, i_plalp, bm_rigid, bm_mesh, &
            n_tactor_kinds, tactor_kind_names, tk_disk, tk_xksid, tk_jonc, tk_polyg, tk_clxxx, tk_alpxx, &
            tactor_kind_id

  ! Statuses: 'C' variants are cohesive contacts (the glue is not yet broken).
  integer, parameter :: st_noctc = 1, st_stick = 2, st_slifw = 3, st_slibw = 4, st_noact = 5, &
                        st_cnctc = 6, st_cstck = 7, st_cslfw = 8, st_cslbw = 9
  integer, parameter :: n_status = 9
  character(len=5), parameter :: status_names(n_status) = &
    [character(len=5) :: 'noctc', 'stick', 'slifw', 'slibw', 'noact', 'Cnctc', 'Cstck', 'Cslfw', 'Cslbw']

  integer, parameter :: i_dkdkx = 1, i_dkjcx = 2, i_dkkdx = 3, i_dkplx = 4, i_plplx = 5, i_pljcx = 6, &
                        i_clalp = 7, i_cljcx = 8, i_dkalp = 9, i_plalp = 10
  integer, parameter :: n_inter = 10
  character(len=5), parameter :: inter_names(n_inter) = &
    [character(len=5) :: 'DKDKx', 'DKJCx', 'DKKDx', 'DKPLx', 'PLPLx', 'PLJCx', 'CLALp', 'CLJCx', 'DKALp', 'PLALp']

  !> Contactor kinds (a DISKb is a DISKx with an offset).
  integer, parameter :: tk_disk = 1, tk_xksid = 2, tk_jonc = 3, tk_polyg = 4, tk_clxxx = 5, tk_alpxx = 6
  integer, parameter :: n_tactor_kinds = 6
  character(len=5), parameter :: tactor_kind_names(n_tactor_kinds) = &
    [character(len=5) :: 'DISKx', 'xKSID', 'JONCx', 'POLYG', 'CLxxx', 'ALpxx']

  !> Body models: rigid 2D bodies (RBDY2) and meshed bodies (MAILx).
  integer, parameter :: bm_rigid = 1, bm_mesh = 2

contains

  !> Id of a status name, 0 if unknown. LMGC90's 'nknow' and 'vnish' read as noctc.
  pure integer function status_id(name) result(id)
    character(len=*), intent(in) :: name
    id = index_of(status_names, name)
    if (name == 'nknow' .or. name == 'vnish') id = st_noctc
  end function status_id

  !> Id of an interaction type name, 0 if unknown.
  pure integer function inter_id(name) result(id)
    character(len=*), intent(in) :: name
    id = index_of(inter_names, name)
  end function inter_id

  !> Id of a contactor kind name ('DISKb' is a DISKx), 0 if unknown.
  pure integer function tactor_kind_id(name) result(id)
    character(len=*), intent(in) :: name
    id = index_of(tactor_kind_names, name)
    if (name == 'DISKb') id = tk_disk
  end function tactor_kind_id

  !> Position of name in a name table (the last match), 0 if absent.
  pure integer function index_of(table, name) result(id)
    character(len=5), intent(in) :: table(:)
    character(len=*), intent(in) :: name
    integer :: i
    id = 0
    do i = 1, size(table)
      if (name == table(i)) id = i
    end do
  end function index_of
end module fracas_ids
