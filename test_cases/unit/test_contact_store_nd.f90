!> The contact store's shapes in dimension 2 and 3 (fracas_contacts: contacts_reserve;
!> the size names of fracas_contacts and fracas_contact_laws). References: in 2D the
!> shapes the store always had (normal (2), lever (4), w (4), wi (6), coh (29),
!> internals (5), mnode/mwt (4)); in 3D what the definitions give: frame 3 x 3, w 9 (by
!> rows), wi 9 (inverse_block_3d), lever 2 x 9 ((P - c) x t1, x t2, x n, 3 components
!> each), mnode/mwt 2 x 4 (a face), internals 6 (L, ut1, ut2, un, beta, TPSini). The
!> layout of coh must tile 1 .. coh_size(nd) with its named parts, no gap, no overlap.
program test_contact_store_nd
  use fracas_contacts, only: contacts_t, contacts_reserve, rigid_lever_size, mesh_side_nodes, wi_size
  use fracas_contact_laws, only: coh_size, coh_wprime, coh_av, coh_k, coh_law, coh_h, coh_factor, coh_released, &
                                 coh_prev, coh_jh, coh_bracket, coh_u0, coh_uend, coh_j0, n_internals, int_jump, &
                                 int_beta, int_tps
  use fracas_testing, only: check_true, test_finish
  implicit none
  integer :: nd

  ! (nd, lever, w, wi, coh, internals, mnode/mwt) as the header says
  call check_store(2, [4, 4, 6, 29, 5, 4])
  call check_store(3, [18, 9, 9, 44, 6, 8])
  call check_true('2D internals: L, ut, un, beta, TPSini', int_jump == 2 .and. int_beta(2) == 4 .and. int_tps(2) == 5)
  call check_true('3D internals: L, ut1, ut2, un, beta, TPSini', int_beta(3) == 5 .and. int_tps(3) == 6)
  call check_true('sizes by nd', all(rigid_lever_size == [2, 9]) .and. all(mesh_side_nodes == [2, 4]) .and. &
                  all(wi_size == [6, 9]) .and. all(n_internals == [5, 6]))

  do nd = 2, 3
    call check_true('coh layout tiles 1..coh_size in '//achar(48 + nd)//'D', tiles(nd))
    call check_true('coh A and W'' are the first nd^2 blocks, a then K after them', &
                    coh_wprime(nd) == 1 + nd**2 .and. coh_av(nd) == 1 + 2 * nd**2 .and. coh_k(nd) == coh_av(nd) + nd)
  end do
  call test_finish()

contains

  !> A store of dimension nd with cohesion and meshes: every per-contact array's first
  !> extent(s); ref = (lever, w, wi, coh, internals, mnode/mwt).
  subroutine check_store(nd, ref)
    integer, intent(in) :: nd, ref(6)
    type(contacts_t) :: c
    character(len=2) :: d
    d = achar(48 + nd)//'D'
    c%nd = nd
    c%with_cohesion = .true.; c%with_mesh = .true.
    call contacts_reserve(c, 10)
    call check_true(d//': frame (nd, nd, cap)', all(shape(c%frame) == [nd, nd, size(c%inter)]))
    call check_true(d//': point, r, u, u_begin, shift (nd, cap)', all([size(c%point, 1), size(c%r, 1), &
                    size(c%u, 1), size(c%u_begin, 1), size(c%shift, 1)] == nd))
    call check_true(d//': lever, w, wi, coh, internals, mnode, mwt', all([size(c%lever, 1), size(c%w, 1), &
                    size(c%wi, 1), size(c%coh, 1), size(c%internals, 1), size(c%mnode, 1)] == ref) .and. &
                    size(c%mwt, 1) == ref(6))
  end subroutine check_store

  !> Every entry of 1..coh_size(nd) belongs to exactly one named part.
  logical function tiles(nd)
    integer, intent(in) :: nd
    integer :: used(coh_size(3)), part(2, 14), i
    part = reshape([1, nd**2, coh_wprime(nd), nd**2, coh_av(nd), nd, coh_k(nd), nd, coh_law(nd), 1, &
                    coh_h(nd), 1, coh_factor(nd), 1, coh_released(nd), 1, coh_prev(nd), 2, coh_jh(nd), 1, &
                    coh_bracket(nd), 4, coh_u0(nd), nd, coh_uend(nd), nd, coh_j0(nd), nd], [2, 14])
    used = 0
    do i = 1, size(part, 2)     ! (first, length) of each part
      used(part(1, i):part(1, i) + part(2, i) - 1) = used(part(1, i):part(1, i) + part(2, i) - 1) + 1
    end do
    tiles = all(used(1:coh_size(nd)) == 1) .and. all(used(coh_size(nd) + 1:) == 0)
  end function tiles
end program test_contact_store_nd
