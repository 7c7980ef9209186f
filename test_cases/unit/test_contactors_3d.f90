!> 3D contactors and pairs: mass properties (fracas_contactors_3d) against the
!> textbook formulas, the principal frame of a two-sphere body, the symmetric
!> 3x3 eigen-decomposition, POLYR volume and inertia, and the SPSPx, SPPLx,
!> PRPLx, SPPRx and PRPRx gap, point and frame against hand computations. References in each check's name or comment; tolerances
!> are round-off (1e-12 relative) except where stated.
!> Planted bugs watched red: the parallel-axis term with + vi d d^T (4 checks:
!> the moment about the line of centres 1.78e-2 for 1.07e-3, the axis across);
!> SPPLx's lower face with the upper normal (normal and handedness off by 2);
!> SPSPx's point on the candidate's surface (0.05 off); the polyhedron's second
!> moments not moved to the centroid (pyramid Ixx 2.24 for 2.15: the tetrahedron and
!> the box are blind to it, their vertex mean being their centroid); PRPLx
!> keeping the first 4 vertices met (upside-down cube); SPPRx's triangle edge
!> regions projected to a vertex (edge gap 0.507 for 0.3), its inside point
!> moved the wrong way (0.2 off); PRPRx's clipping sides outward (12 checks:
!> no face point kept); PRPRx taking the first edge pair along the best axis,
!> not the supporting one (edge-edge point 0.85 off).
program test_contactors_3d
  use fracas_kinds, only: wp
  use fracas_testing, only: check_close, check_true, test_finish
  use fracas_contactors_3d, only: tactor3_t, tk3_spher, tk3_planx, body3_mass_properties, tactor3_place, &
                                  polyr_from_surface, box_surface, polyr_vertices
  use fracas_frame_3d, only: polyhedron_volume_inertia
  use fracas_prplx, only: prplx_contacts
  use fracas_spprx, only: spprx_geometry
  use fracas_prprx, only: prprx_contacts
  use fracas_frame_3d, only: symmetric_eigen_3x3, cross3, rotation_of_vector, identity3
  use fracas_spspx, only: spspx_geometry
  use fracas_spplx, only: spplx_geometry
  implicit none
  real(wp), parameter :: pi = acos(-1.0_wp)

  call sphere_and_box()
  call two_spheres()
  call eigen()
  call spsp()
  call sppl()
  call polyr()
  call prpl()
  call sppr()
  call prpr()
  call test_finish()

contains

  !> Sphere r = 0.5, density 2000: m = 4/3 pi r^3 rho, I = 2/5 m r^2; box of half
  !> lengths (1, 0.5, 0.25), density 1000: m = 8 abc rho, I1 = m (b^2 + c^2) / 3
  !> (half lengths; = m (B^2 + C^2) / 12 with the full ones).
  subroutine sphere_and_box()
    type(tactor3_t) :: t(1)
    real(wp) :: avrd, c(3), f(3, 3), m, ii(3), mref
    t(1)%kind = tk3_spher
    t(1)%radius = 0.5_wp
    avrd = 0.0_wp
    call body3_mass_properties(t, [1.0_wp, 2.0_wp, 3.0_wp], 2000.0_wp, avrd, c, f, m, ii)
    mref = 4.0_wp / 3.0_wp * pi * 0.125_wp * 2000.0_wp
    call check_close('sphere mass', m, mref, 1.0e-12_wp * mref)
    call check_close('sphere I1 = 2/5 m r^2', ii(1), 0.4_wp * mref * 0.25_wp, 1.0e-12_wp * mref)
    call check_close('sphere I3 = I1', ii(3), ii(1), 0.0_wp)
    call check_close('sphere avrd computed = r', avrd, 0.5_wp, 1.0e-14_wp)
    call check_close('sphere centre = node', norm2(c - [1.0_wp, 2.0_wp, 3.0_wp]), 0.0_wp, 0.0_wp)
    t(1)%kind = tk3_planx
    t(1)%axes = [1.0_wp, 0.5_wp, 0.25_wp]
    t(1)%frame = rotation_of_vector([0.3_wp, -0.2_wp, 0.5_wp])
    t(1)%shift = [0.0_wp, 0.0_wp, -0.25_wp]
    avrd = 0.0_wp
    call body3_mass_properties(t, [0.0_wp, 0.0_wp, 0.0_wp], 1000.0_wp, avrd, c, f, m, ii)
    mref = 8.0_wp * 0.125_wp * 1000.0_wp
    call check_close('box mass', m, mref, 1.0e-12_wp * mref)
    call check_close('box I1 = m (b^2 + c^2) / 3', ii(1), mref * (0.25_wp + 0.0625_wp) / 3.0_wp, 1.0e-12_wp * mref)
    call check_close('box I2 = m (a^2 + c^2) / 3', ii(2), mref * (1.0_wp + 0.0625_wp) / 3.0_wp, 1.0e-12_wp * mref)
    call check_close('box I3 = m (a^2 + b^2) / 3', ii(3), mref * (1.0_wp + 0.25_wp) / 3.0_wp, 1.0e-12_wp * mref)
    call check_close('box body frame = its PLANx frame', maxval(abs(f - rotation_of_vector([0.3_wp, -0.2_wp, 0.5_wp]))), &
                     0.0_wp, 0.0_wp)
    call check_close('box centre = node + shift', c(3), -0.25_wp, 0.0_wp)
  end subroutine sphere_and_box

  !> Two spheres r = 0.2 at +-d = 0.5 along the unit axis e (tilted), density 1:
  !> about e, I = 2 (2/5 v r^2); across, I = 2 (2/5 v r^2 + v d^2) (Huygens);
  !> the smallest moment's axis is e; centre midway; offsets -+ d along axis 1.
  subroutine two_spheres()
    type(tactor3_t) :: t(2)
    real(wp) :: avrd, c(3), f(3, 3), m, ii(3), e(3), v, i0, pos(3), tf(3, 3)
    e = [1.0_wp, 2.0_wp, 2.0_wp] / 3.0_wp
    t%kind = tk3_spher
    t%radius = 0.2_wp
    t(1)%shift = [1.0_wp, 1.0_wp, 1.0_wp] + 0.5_wp * e
    t(2)%shift = [1.0_wp, 1.0_wp, 1.0_wp] - 0.5_wp * e
    avrd = 0.0_wp
    call body3_mass_properties(t, [0.0_wp, 0.0_wp, 1.0_wp], 1.0_wp, avrd, c, f, m, ii)
    v = 4.0_wp / 3.0_wp * pi * 0.2_wp**3
    i0 = 0.4_wp * v * 0.04_wp
    call check_close('two spheres: mass', m, 2.0_wp * v, 1.0e-14_wp)
    call check_close('two spheres: I about the line of centres', ii(1), 2.0_wp * i0, 1.0e-12_wp * ii(3))
    call check_close('two spheres: I across (Huygens)', ii(2), 2.0_wp * (i0 + v * 0.25_wp), 1.0e-12_wp * ii(3))
    call check_close('two spheres: I3 = I2', ii(3), ii(2), 1.0e-12_wp * ii(3))
    call check_close('two spheres: axis 1 along the line of centres', abs(dot_product(f(:, 1), e)), 1.0_wp, 1.0e-12_wp)
    call check_close('two spheres: centre', norm2(c - [1.0_wp, 1.0_wp, 2.0_wp]), 0.0_wp, 1.0e-14_wp)
    call check_close('two spheres: offset of the first along axis 1', abs(t(1)%shift(1)), 0.5_wp, 1.0e-12_wp)
    call tactor3_place(t(1), c, f, pos, tf)
    call check_close('two spheres: first placed back where read', norm2(pos - ([1.0_wp, 1.0_wp, 2.0_wp] + 0.5_wp * e)), &
                     0.0_wp, 1.0e-14_wp)
    call check_close('two spheres: frame right-handed', dot_product(cross3(f(:, 1), f(:, 2)), f(:, 3)), 1.0_wp, 1.0e-14_wp)
  end subroutine two_spheres

  !> A symmetric matrix built from known eigenpairs: R diag(1, 4, 9) R^T.
  subroutine eigen()
    real(wp) :: r(3, 3), a(3, 3), lam(3), v(3, 3), d(3, 3)
    integer :: k
    r = rotation_of_vector([0.7_wp, -1.1_wp, 0.4_wp])
    a = matmul(r, matmul(reshape([9.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 4.0_wp], [3, 3]), &
                         transpose(r)))
    call symmetric_eigen_3x3(a, lam, v)
    call check_close('eigen: lambda 1', lam(1), 1.0_wp, 1.0e-13_wp)
    call check_close('eigen: lambda 2', lam(2), 4.0_wp, 1.0e-13_wp)
    call check_close('eigen: lambda 3', lam(3), 9.0_wp, 1.0e-13_wp)
    d = 0.0_wp
    do k = 1, 3
      d(k, k) = lam(k)
    end do
    call check_close('eigen: V diag V^T = A', maxval(abs(matmul(v, matmul(d, transpose(v))) - a)), 0.0_wp, 1.0e-13_wp)
    call check_close('eigen: axis of 9 = R e1', abs(dot_product(v(:, 3), r(:, 1))), 1.0_wp, 1.0e-13_wp)
  end subroutine eigen

  !> Spheres r = 1 at (0,0,0) (antagonist) and r = 0.5 at (3, 4, 0)/5 * 1.4:
  !> distance 1.4, gap -0.1, n = (0.6, 0.8, 0), point mid-gap at 0.95 n.
  subroutine spsp()
    real(wp) :: gap, p(3), f(3, 3)
    call spspx_geometry([0.84_wp, 1.12_wp, 0.0_wp], 0.5_wp, [0.0_wp, 0.0_wp, 0.0_wp], 1.0_wp, gap, p, f)
    call check_close('SPSPx gap', gap, -0.1_wp, 1.0e-14_wp)
    call check_close('SPSPx normal', norm2(f(:, 3) - [0.6_wp, 0.8_wp, 0.0_wp]), 0.0_wp, 1.0e-15_wp)
    call check_close('SPSPx point mid-gap', norm2(p - 0.95_wp * [0.6_wp, 0.8_wp, 0.0_wp]), 0.0_wp, 1.0e-15_wp)
    call check_frame('SPSPx', f)
  end subroutine spsp

  !> A PLANx (half axes 2, 1, 0.1) turned by 30 degrees about x, at (0, 0, 1);
  !> sphere r = 0.5 above the upper face at height 0.55 over the mid-plane
  !> (gap -0.05), then below the lower face at 0.7 (gap 0.1), then beyond the
  !> rim: 2.3 along alpha, 0.4 along gamma from the centre: nearest mid-plane
  !> point at 2 alpha, distance 0.5, gap 0.5 - 0.5 - 0.1 = -0.1.
  subroutine sppl()
    real(wp) :: pf(3, 3), p(3), c(3), gap, pt(3), f(3, 3)
    logical :: found
    pf = rotation_of_vector([pi / 6.0_wp, 0.0_wp, 0.0_wp])
    p = [0.0_wp, 0.0_wp, 1.0_wp]
    c = p + 0.3_wp * pf(:, 1) - 0.2_wp * pf(:, 2) + 0.55_wp * pf(:, 3)
    call spplx_geometry(c, 0.5_wp, p, pf, [2.0_wp, 1.0_wp, 0.1_wp], 0.01_wp, found, gap, pt, f)
    call check_true('SPPLx upper face found', found)
    call check_close('SPPLx upper face gap', gap, -0.05_wp, 1.0e-14_wp)
    call check_close('SPPLx upper normal = gamma', norm2(f(:, 3) - pf(:, 3)), 0.0_wp, 1.0e-15_wp)
    call check_close('SPPLx upper point mid-gap', norm2(pt - (c - 0.475_wp * pf(:, 3))), 0.0_wp, 1.0e-14_wp)
    call check_frame('SPPLx upper', f)
    c = p + 0.3_wp * pf(:, 1) - 0.2_wp * pf(:, 2) - 0.7_wp * pf(:, 3)
    call spplx_geometry(c, 0.5_wp, p, pf, [2.0_wp, 1.0_wp, 0.1_wp], 0.2_wp, found, gap, pt, f)
    call check_true('SPPLx lower face found (alert 0.2)', found)
    call check_close('SPPLx lower face gap', gap, 0.1_wp, 1.0e-14_wp)
    call check_close('SPPLx lower normal = -gamma', norm2(f(:, 3) + pf(:, 3)), 0.0_wp, 1.0e-15_wp)
    call check_frame('SPPLx lower', f)
    call spplx_geometry(c, 0.5_wp, p, pf, [2.0_wp, 1.0_wp, 0.1_wp], 0.05_wp, found, gap, pt, f)
    call check_true('SPPLx lower face not found (alert 0.05 < gap 0.1)', .not. found)
    c = p + 2.3_wp * pf(:, 1) + 0.4_wp * pf(:, 3)
    call spplx_geometry(c, 0.5_wp, p, pf, [2.0_wp, 1.0_wp, 0.1_wp], 0.01_wp, found, gap, pt, f)
    call check_true('SPPLx rim found', found)
    call check_close('SPPLx rim gap', gap, -0.1_wp, 1.0e-14_wp)
    call check_close('SPPLx rim normal', norm2(f(:, 3) - (0.6_wp * pf(:, 1) + 0.8_wp * pf(:, 3))), 0.0_wp, 1.0e-15_wp)
    call check_frame('SPPLx rim', f)
  end subroutine sppl

  !> POLYR: a box of half lengths (1, 0.5, 0.25) turned by R and moved by d,
  !> against the PLANx formulas (moments ascending: V/3 (b^2 + c^2), ...,
  !> principal axis 1 = R e1, centroid d); the corner tetrahedron (0, e1, e2,
  !> e3): V = 1/6, centroid 1/4 (1, 1, 1), about it Ixx = 1/80, Ixy = 1/480
  !> (int x^2 = 1/60, int xy = 1/120 over it, less the centroid's share); a
  !> square pyramid (base 2 x 2, height 3; its vertex mean is not its centroid):
  !> V = 4, centroid at h/4, Izz = V a^2/10 = 1.6, Ixx = V (a^2/20 + 3 h^2/80) = 2.15.
  subroutine polyr()
    real(wp) :: vert(3, 8), r(3, 3), d(3), vol, g(3), tens(3, 3), vt(3, 4), pv(3, 8)
    integer :: faces(3, 12), k
    type(tactor3_t) :: t
    call box_surface([1.0_wp, 0.5_wp, 0.25_wp], vert, faces)
    r = rotation_of_vector([0.3_wp, 0.8_wp, -0.4_wp])
    d = [2.0_wp, -1.0_wp, 0.5_wp]
    do k = 1, 8
      vert(:, k) = d + matmul(r, vert(:, k))
    end do
    t = polyr_from_surface(vert, faces)
    call check_close('POLYR box: volume', t%volume, 1.0_wp, 1.0e-14_wp)
    call check_close('POLYR box: I1 = V (b^2 + c^2) / 3', t%moments(1), 0.3125_wp / 3.0_wp, 1.0e-14_wp)
    call check_close('POLYR box: I2 = V (a^2 + c^2) / 3', t%moments(2), 1.0625_wp / 3.0_wp, 1.0e-14_wp)
    call check_close('POLYR box: I3 = V (a^2 + b^2) / 3', t%moments(3), 1.25_wp / 3.0_wp, 1.0e-14_wp)
    call check_close('POLYR box: axis 1 = R e1', abs(dot_product(t%frame(:, 1), r(:, 1))), 1.0_wp, 1.0e-13_wp)
    call check_close('POLYR box: offset = centroid', norm2(t%shift - d), 0.0_wp, 1.0e-14_wp)
    pv = polyr_vertices(t, [0.0_wp, 0.0_wp, 0.0_wp], identity3())
    call check_close('POLYR box: vertices placed back where read', maxval(abs(pv - vert)), 0.0_wp, 1.0e-14_wp)
    vt = reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 4])
    call polyhedron_volume_inertia(vt, reshape([1, 3, 2, 1, 2, 4, 1, 4, 3, 2, 3, 4], [3, 4]), vol, g, tens)
    call check_close('tetrahedron: volume 1/6', vol, 1.0_wp / 6.0_wp, 1.0e-15_wp)
    call check_close('tetrahedron: centroid', norm2(g - 0.25_wp), 0.0_wp, 1.0e-15_wp)
    call check_close('tetrahedron: Ixx = 1/80', tens(1, 1), 1.0_wp / 80.0_wp, 1.0e-15_wp)
    call check_close('tetrahedron: Ixy = 1/480', tens(1, 2), 1.0_wp / 480.0_wp, 1.0e-15_wp)
    pv(:, 1:5) = reshape([-1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, &
                          0.0_wp, 0.0_wp, 3.0_wp], [3, 5])
    call polyhedron_volume_inertia(pv(:, 1:5), reshape([1, 3, 2, 1, 4, 3, 1, 2, 5, 2, 3, 5, 3, 4, 5, 4, 1, 5], [3, 6]), &
                                   vol, g, tens)
    call check_close('pyramid: volume 4', vol, 4.0_wp, 1.0e-14_wp)
    call check_close('pyramid: centroid at h/4', norm2(g - [0.0_wp, 0.0_wp, 0.75_wp]), 0.0_wp, 1.0e-15_wp)
    call check_close('pyramid: Izz = 1.6', tens(3, 3), 1.6_wp, 1.0e-14_wp)
    call check_close('pyramid: Ixx = 2.15', tens(1, 1), 2.15_wp, 1.0e-14_wp)
  end subroutine polyr

  !> PRPLx: a unit cube (half 0.5) over a horizontal PLANx (half thickness 0.05,
  !> top face at z = 0): centre at z = 0.5 - 0.01: 4 bottom vertices at gap
  !> -0.01, normal +z; tilted by 0.1 rad about x with its lowest edge's
  !> vertices at z = -0.02: 2 points at gap -0.02 and 2 at -0.02 + sin(0.1),
  !> within the alert 0.15 (the top vertices stay out); and under the plate
  !> (centre at z = -0.6): the lower face, normal -z, the top vertices; the
  !> cube upside down (vertices 5-8 at the bottom) with an alert taking all 8:
  !> the 4 deepest are kept, 5-8.
  subroutine prpl()
    real(wp) :: vert(3, 8), pf(3, 3), gap(4), pt(3, 4), f(3, 3), c(3), r(3, 3), zmin
    integer :: faces(3, 12), npt, iv(4), k
    call box_surface([0.5_wp, 0.5_wp, 0.5_wp], vert, faces)
    pf = identity3()
    c = [0.1_wp, 0.2_wp, 0.49_wp]
    call prplx_contacts(spread(c, 2, 8) + vert, c, [0.0_wp, 0.0_wp, -0.05_wp], pf, [3.0_wp, 3.0_wp, 0.05_wp], &
                        0.05_wp, npt, iv, gap, pt, f)
    call check_true('PRPLx flat: 4 points, the bottom vertices', npt == 4 .and. all(iv <= 4))
    call check_close('PRPLx flat: gaps -0.01', maxval(abs(gap + 0.01_wp)), 0.0_wp, 1.0e-15_wp)
    call check_close('PRPLx flat: normal +z', norm2(f(:, 3) - [0.0_wp, 0.0_wp, 1.0_wp]), 0.0_wp, 0.0_wp)
    call check_close('PRPLx flat: point = vertex', norm2(pt(:, 1) - (c + vert(:, iv(1)))), 0.0_wp, 0.0_wp)
    r = rotation_of_vector([0.1_wp, 0.0_wp, 0.0_wp])
    do k = 1, 8
      vert(:, k) = matmul(r, vert(:, k))
    end do
    zmin = minval(vert(3, :))
    c = [0.0_wp, 0.0_wp, -0.02_wp - zmin]
    call prplx_contacts(spread(c, 2, 8) + vert, c, [0.0_wp, 0.0_wp, -0.05_wp], pf, [3.0_wp, 3.0_wp, 0.05_wp], &
                        0.15_wp, npt, iv, gap, pt, f)
    call check_true('PRPLx tilted: 4 points', npt == 4)
    call check_close('PRPLx tilted: deepest gap', minval(gap), -0.02_wp, 1.0e-15_wp)
    call check_close('PRPLx tilted: shallowest gap = -0.02 + sin 0.1', maxval(gap), -0.02_wp + sin(0.1_wp), 1.0e-15_wp)
    call check_true('PRPLx tilted: two at each depth', count(abs(gap + 0.02_wp) < 1.0e-12_wp) == 2)
    call box_surface([0.5_wp, 0.5_wp, 0.5_wp], vert, faces)
    c = [0.0_wp, 0.0_wp, -0.6_wp]
    call prplx_contacts(spread(c, 2, 8) + vert, c, [0.0_wp, 0.0_wp, 0.0_wp], pf, [3.0_wp, 3.0_wp, 0.05_wp], &
                        0.1_wp, npt, iv, gap, pt, f)
    call check_true('PRPLx under: the 4 top vertices', npt == 4 .and. all(iv >= 5))
    call check_close('PRPLx under: normal -z', norm2(f(:, 3) + [0.0_wp, 0.0_wp, 1.0_wp]), 0.0_wp, 0.0_wp)
    call check_close('PRPLx under: gap 0.6 - 0.5 - 0.05', maxval(abs(gap - 0.05_wp)), 0.0_wp, 1.0e-15_wp)
    call check_frame('PRPLx under', f)
    r = rotation_of_vector([pi, 0.0_wp, 0.0_wp])
    do k = 1, 8
      vert(:, k) = matmul(r, vert(:, k))
    end do
    c = [0.0_wp, 0.0_wp, 0.5_wp]
    call prplx_contacts(spread(c, 2, 8) + vert, c, [0.0_wp, 0.0_wp, -0.05_wp], pf, [3.0_wp, 3.0_wp, 0.05_wp], &
                        2.0_wp, npt, iv, gap, pt, f)
    call check_true('PRPLx upside down, alert 2: the 4 deepest (5-8) kept', npt == 4 .and. all(iv >= 5))
  end subroutine prpl

  !> SPPRx: a cube of half side 0.5 turned by R and moved by d, sphere r = 0.2
  !> (in the cube's axes): over the top face at 0.65 (gap -0.05, n = R e3, point
  !> on the face); off an edge at (0.8, 0, 0.9) (closest (0.5, 0, 0.5),
  !> distance 0.5, gap 0.3, n = R (0.6, 0, 0.8)); off a corner at 0.5 + 0.1
  !> (gap 0.1 sqrt 3 - 0.2); inside at (0, 0, 0.4) (nearest face the top:
  !> gap -0.1 - 0.2, point (0, 0, 0.5)); far (alert 0.1 < gap 0.3): not found.
  subroutine sppr()
    real(wp) :: vert(3, 8), r(3, 3), d(3), gap, pt(3), f(3, 3)
    integer :: faces(3, 12), k
    logical :: found
    call box_surface([0.5_wp, 0.5_wp, 0.5_wp], vert, faces)
    r = rotation_of_vector([0.2_wp, -0.5_wp, 0.3_wp])
    d = [1.0_wp, 2.0_wp, 3.0_wp]
    do k = 1, 8
      vert(:, k) = d + matmul(r, vert(:, k))
    end do
    call spprx_geometry(cube_point(d, r, [0.1_wp, -0.2_wp, 0.65_wp]), 0.2_wp, vert, faces, 0.01_wp, found, gap, pt, f)
    call check_true('SPPRx face: found', found)
    call check_close('SPPRx face: gap', gap, -0.05_wp, 1.0e-14_wp)
    call check_close('SPPRx face: normal R e3', norm2(f(:, 3) - r(:, 3)), 0.0_wp, 1.0e-14_wp)
    call check_close('SPPRx face: point on the face', norm2(pt - cube_point(d, r, [0.1_wp, -0.2_wp, 0.5_wp])), 0.0_wp, 1.0e-14_wp)
    call check_frame('SPPRx face', f)
    call spprx_geometry(cube_point(d, r, [0.8_wp, 0.0_wp, 0.9_wp]), 0.2_wp, vert, faces, 0.5_wp, found, gap, pt, f)
    call check_close('SPPRx edge: gap', gap, 0.3_wp, 1.0e-14_wp)
    call check_close('SPPRx edge: normal R (0.6, 0, 0.8)', norm2(f(:, 3) - matmul(r, [0.6_wp, 0.0_wp, 0.8_wp])), 0.0_wp, &
                     1.0e-14_wp)
    call check_close('SPPRx edge: point on the edge', norm2(pt - cube_point(d, r, [0.5_wp, 0.0_wp, 0.5_wp])), 0.0_wp, 1.0e-14_wp)
    call spprx_geometry(cube_point(d, r, [0.6_wp, 0.6_wp, 0.6_wp]), 0.2_wp, vert, faces, 0.5_wp, found, gap, pt, f)
    call check_close('SPPRx corner: gap 0.1 sqrt 3 - 0.2', gap, 0.1_wp * sqrt(3.0_wp) - 0.2_wp, 1.0e-14_wp)
    call check_close('SPPRx corner: point at the corner', norm2(pt - cube_point(d, r, [0.5_wp, 0.5_wp, 0.5_wp])), 0.0_wp, 1.0e-14_wp)
    call spprx_geometry(cube_point(d, r, [0.0_wp, 0.0_wp, 0.4_wp]), 0.2_wp, vert, faces, 0.01_wp, found, gap, pt, f)
    call check_close('SPPRx inside: gap -0.1 - r', gap, -0.3_wp, 1.0e-14_wp)
    call check_close('SPPRx inside: normal R e3', norm2(f(:, 3) - r(:, 3)), 0.0_wp, 1.0e-14_wp)
    call check_close('SPPRx inside: point on the top face', norm2(pt - cube_point(d, r, [0.0_wp, 0.0_wp, 0.5_wp])), 0.0_wp, 1.0e-14_wp)
    call spprx_geometry(cube_point(d, r, [0.8_wp, 0.0_wp, 0.9_wp]), 0.2_wp, vert, faces, 0.1_wp, found, gap, pt, f)
    call check_true('SPPRx edge beyond the alert: not found', .not. found)
  end subroutine sppr

  !> PRPRx with two cubes of half side 0.5, antagonist B at the origin:
  !> A above at (0.3, 0.2, 1.01): face contact on B's top face, 4 points at the
  !> corners of [-0.2, 0.5] x [-0.3, 0.5] at z = 0.51 (on A's face), gaps
  !> 0.01, n = +z; A also turned 45 deg about z: the octagon reduced to 4
  !> points, gaps 0.01, within both squares; B turned 45 deg about y and A
  !> 45 deg about x at height sqrt 2 + 0.02: edge on edge, one point at
  !> (0, 0, sqrt 2 / 2 + 0.01), gap 0.02, n = +z; A on its corner (its
  !> diagonal vertical) 0.01 above B's top face: one point, the corner; apart
  !> by 0.5 with the alert 0.1: none.
  subroutine prpr()
    real(wp) :: vb(3, 8), va(3, 8), base(3, 8), gap(4), pt(3, 4), f(3, 3), ra(3, 3), rb(3, 3), h
    integer :: faces(3, 12), npt
    call box_surface([0.5_wp, 0.5_wp, 0.5_wp], base, faces)
    vb = base
    va = base + spread([0.3_wp, 0.2_wp, 1.01_wp], 2, 8)
    call prprx_contacts(va, faces, vb, faces, 0.05_wp, npt, gap, pt, f)
    call check_true('PRPRx face: 4 points', npt == 4)
    call check_close('PRPRx face: gaps 0.01', maxval(abs(gap - 0.01_wp)), 0.0_wp, 1.0e-14_wp)
    call check_close('PRPRx face: normal +z', norm2(f(:, 3) - [0.0_wp, 0.0_wp, 1.0_wp]), 0.0_wp, 1.0e-15_wp)
    call check_close('PRPRx face: the corners, sum of x', sum(pt(1, :)), 0.6_wp, 1.0e-14_wp)
    call check_close('PRPRx face: the corners, sum of y', sum(pt(2, :)), 0.4_wp, 1.0e-14_wp)
    call check_close('PRPRx face: on the incident face z = 0.51', maxval(abs(pt(3, :) - 0.51_wp)), 0.0_wp, 1.0e-14_wp)
    call check_frame('PRPRx face', f)
    ra = rotation_of_vector([0.0_wp, 0.0_wp, pi / 4.0_wp])
    va = matmul(ra, base) + spread([0.0_wp, 0.0_wp, 1.01_wp], 2, 8)
    call prprx_contacts(va, faces, vb, faces, 0.05_wp, npt, gap, pt, f)
    call check_true('PRPRx octagon: 4 points kept', npt == 4)
    call check_close('PRPRx octagon: gaps 0.01', maxval(abs(gap - 0.01_wp)), 0.0_wp, 1.0e-14_wp)
    call check_true('PRPRx octagon: points within both squares', all(abs(pt(1:2, :)) <= 0.5_wp + 1.0e-14_wp) .and. &
                    all(abs(matmul(transpose(ra(1:2, 1:2)), pt(1:2, :))) <= 0.5_wp + 1.0e-14_wp))
    rb = rotation_of_vector([0.0_wp, pi / 4.0_wp, 0.0_wp])
    ra = rotation_of_vector([pi / 4.0_wp, 0.0_wp, 0.0_wp])
    vb = matmul(rb, base)
    va = matmul(ra, base) + spread([0.0_wp, 0.0_wp, sqrt(2.0_wp) + 0.02_wp], 2, 8)
    call prprx_contacts(va, faces, vb, faces, 0.05_wp, npt, gap, pt, f)
    call check_true('PRPRx edge-edge: 1 point', npt == 1)
    call check_close('PRPRx edge-edge: gap 0.02', gap(1), 0.02_wp, 1.0e-14_wp)
    call check_close('PRPRx edge-edge: normal +z', norm2(f(:, 3) - [0.0_wp, 0.0_wp, 1.0_wp]), 0.0_wp, 1.0e-14_wp)
    call check_close('PRPRx edge-edge: point between the edges', &
                     norm2(pt(:, 1) - [0.0_wp, 0.0_wp, sqrt(0.5_wp) + 0.01_wp]), 0.0_wp, 1.0e-14_wp)
    vb = base
    ra = rotation_of_vector(acos(1.0_wp / sqrt(3.0_wp)) * [1.0_wp, -1.0_wp, 0.0_wp] / sqrt(2.0_wp))
    h = 0.5_wp + sqrt(0.75_wp) + 0.01_wp
    va = matmul(ra, base) + spread([0.0_wp, 0.0_wp, h], 2, 8)
    call prprx_contacts(va, faces, vb, faces, 0.05_wp, npt, gap, pt, f)
    call check_true('PRPRx corner: 1 point', npt == 1)
    call check_close('PRPRx corner: gap 0.01', gap(1), 0.01_wp, 1.0e-14_wp)
    call check_close('PRPRx corner: the corner', norm2(pt(:, 1) - [0.0_wp, 0.0_wp, h - sqrt(0.75_wp)]), 0.0_wp, 1.0e-14_wp)
    va = base + spread([0.0_wp, 0.0_wp, 1.5_wp], 2, 8)
    call prprx_contacts(va, faces, vb, faces, 0.1_wp, npt, gap, pt, f)
    call check_true('PRPRx apart by 0.5, alert 0.1: none', npt == 0)
  end subroutine prpr

  !> A point given in the cube's axes (turned by r, moved by d), in global coordinates.
  pure function cube_point(d, r, x) result(y)
    real(wp), intent(in) :: d(3), r(3, 3), x(3)
    real(wp) :: y(3)
    y = d + matmul(r, x)
  end function cube_point

  !> Columns t1, t2, n orthonormal and right-handed.
  subroutine check_frame(name, f)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: f(3, 3)
    call check_close(name//' frame orthonormal', maxval(abs(matmul(transpose(f), f) - identity3())), 0.0_wp, 1.0e-15_wp)
    call check_close(name//' frame t1 x t2 = n', norm2(cross3(f(:, 1), f(:, 2)) - f(:, 3)), 0.0_wp, 1.0e-15_wp)
  end subroutine check_frame
end program test_contactors_3d
