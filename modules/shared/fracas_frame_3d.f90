!> Small 3D geometry shared by the 3D rigid body model, its contactors and the
!> 3D detection: cross product, the exact rotation of a rotation vector
!> (Rodrigues), an orthonormal tangent pair completing a normal, and the
!> eigen-decomposition of a symmetric 3x3 (principal inertia frame), volume and
!> inertia of a closed triangulated surface (POLYR).
module fracas_frame_3d
  use fracas_kinds, only: wp
  implicit none
  private
  public :: sort_columns, cross3, identity3, rotation_of_vector, tangents_of_normal, symmetric_eigen_3x3, polyhedron_volume_inertia, &
            local3_to_fclib

contains

  pure function cross3(a, b) result(c)
    real(wp), intent(in) :: a(3), b(3)
    real(wp) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross3

  !> Sort key ascending (insertion sort: short lists), the columns of v along.
  pure subroutine sort_columns(key, v)
    real(wp), intent(inout) :: key(:), v(:, :)
    real(wp) :: tk, tmp(size(v, 1))
    integer :: i, j
    do i = 2, size(key)
      j = i
      do while (j > 1)
        if (key(j - 1) <= key(j)) exit
        tk = key(j); key(j) = key(j - 1); key(j - 1) = tk
        tmp = v(:, j); v(:, j) = v(:, j - 1); v(:, j - 1) = tmp
        j = j - 1
      end do
    end do
  end subroutine sort_columns

  pure function identity3() result(m)
    real(wp) :: m(3, 3)
    m = 0.0_wp
    m(1, 1) = 1.0_wp; m(2, 2) = 1.0_wp; m(3, 3) = 1.0_wp
  end function identity3

  !> A 3D local block and vector from the contact store's order (t1, t2, n),
  !> the block by rows (fracas_contacts), to FCLib's (n, t1, t2), the block
  !> column-major (the order of fracas_local_solver's coulomb_3d); back with
  !> v(perm) = vf, perm = [3, 1, 2].
  pure subroutine local3_to_fclib(w, q, wf, qf)
    real(wp), intent(in) :: w(9), q(3)
    real(wp), intent(out) :: wf(9), qf(3)
    integer, parameter :: perm(3) = [3, 1, 2]   ! FCLib index -> store index
    integer :: i, j
    do j = 1, 3
      do i = 1, 3
        wf(i + 3 * (j - 1)) = w(3 * (perm(i) - 1) + perm(j))
      end do
    end do
    qf = q(perm)
  end subroutine local3_to_fclib

  !> The rotation matrix exp([phi]x) of the rotation vector phi (angle |phi|
  !> about phi / |phi|), Rodrigues' formula; Taylor terms below |phi| = 1e-4
  !> (the neglected terms are below 1e-17 there).
  pure function rotation_of_vector(phi) result(r)
    real(wp), intent(in) :: phi(3)
    real(wp) :: r(3, 3), k(3, 3), a2, a, s, c
    integer :: i
    a2 = sum(phi**2)
    a = sqrt(a2)
    k = reshape([0.0_wp, phi(3), -phi(2), -phi(3), 0.0_wp, phi(1), phi(2), -phi(1), 0.0_wp], [3, 3])
    if (a < 1.0e-4_wp) then
      s = 1.0_wp - a2 / 6.0_wp
      c = 0.5_wp - a2 / 24.0_wp
    else
      s = sin(a) / a
      c = (1.0_wp - cos(a)) / a2
    end if
    r = s * k + c * matmul(k, k)
    do i = 1, 3
      r(i, i) = r(i, i) + 1.0_wp
    end do
  end function rotation_of_vector

  !> Unit tangents t1, t2 with (t1, t2, n) a right-handed orthonormal frame
  !> (t1 x t2 = n), n a unit vector: t1 is normal to n and to the global axis
  !> least aligned with n (the first such axis on ties), t2 = n x t1.
  pure subroutine tangents_of_normal(n, t1, t2)
    real(wp), intent(in) :: n(3)
    real(wp), intent(out) :: t1(3), t2(3)
    real(wp) :: e(3)
    integer :: k
    k = minloc(abs(n), dim=1)
    e = 0.0_wp
    e(k) = 1.0_wp
    t1 = cross3(e, n)
    t1 = t1 / sqrt(sum(t1**2))
    t2 = cross3(n, t1)
  end subroutine tangents_of_normal

  !> Eigenvalues lam (ascending) and orthonormal eigenvectors (columns of v,
  !> right-handed) of the symmetric matrix a, by cyclic Jacobi rotations until
  !> the off-diagonal part is below 1e-15 of the norm (a few sweeps in 3x3).
  pure subroutine symmetric_eigen_3x3(a, lam, v)
    real(wp), intent(in) :: a(3, 3)
    real(wp), intent(out) :: lam(3), v(3, 3)
    real(wp) :: m(3, 3), theta, t, c, s, off, scale, tmp(3)
    integer :: sweep, p, q, i, k
    m = a
    v = 0.0_wp
    do i = 1, 3
      v(i, i) = 1.0_wp
    end do
    scale = sqrt(sum(a**2))
    do sweep = 1, 50
      off = sqrt(m(1, 2)**2 + m(1, 3)**2 + m(2, 3)**2)
      if (off <= 1.0e-15_wp * scale) exit
      do p = 1, 2
        do q = p + 1, 3
          if (m(p, q) == 0.0_wp) cycle
          theta = (m(q, q) - m(p, p)) / (2.0_wp * m(p, q))
          t = sign(1.0_wp, theta) / (abs(theta) + sqrt(theta**2 + 1.0_wp))
          c = 1.0_wp / sqrt(t**2 + 1.0_wp)
          s = t * c
          do k = 1, 3   ! m <- J^T m J with the rotation J in the (p, q) plane
            tmp(1) = m(k, p); tmp(2) = m(k, q)
            m(k, p) = c * tmp(1) - s * tmp(2)
            m(k, q) = s * tmp(1) + c * tmp(2)
          end do
          do k = 1, 3
            tmp(1) = m(p, k); tmp(2) = m(q, k)
            m(p, k) = c * tmp(1) - s * tmp(2)
            m(q, k) = s * tmp(1) + c * tmp(2)
          end do
          do k = 1, 3
            tmp(1) = v(k, p); tmp(2) = v(k, q)
            v(k, p) = c * tmp(1) - s * tmp(2)
            v(k, q) = s * tmp(1) + c * tmp(2)
          end do
        end do
      end do
    end do
    lam = [m(1, 1), m(2, 2), m(3, 3)]
    call sort_columns(lam, v)
    if (dot_product(cross3(v(:, 1), v(:, 2)), v(:, 3)) < 0.0_wp) v(:, 3) = -v(:, 3)
  end subroutine symmetric_eigen_3x3

  !> Volume, centroid g and inertia tensor about g (per unit density) of the
  !> solid bounded by a closed triangulated surface (outward triangles: each
  !> seen counter-clockwise from outside), summed over the tetrahedra (o, a, b,
  !> c) from a reference point o inside the hull (the vertex mean): V = det/6,
  !> int x x^T = V/20 (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
  pure subroutine polyhedron_volume_inertia(vert, faces, vol, g, tens)
    real(wp), intent(in) :: vert(:, :)
    integer, intent(in) :: faces(:, :)
    real(wp), intent(out) :: vol, g(3), tens(3, 3)
    real(wp) :: o(3), a(3), b(3), c(3), sm(3), v, cov(3, 3)
    integer :: k, i
    o = sum(vert, dim=2) / size(vert, 2)
    vol = 0.0_wp; sm = 0.0_wp; cov = 0.0_wp
    do k = 1, size(faces, 2)
      a = vert(:, faces(1, k)) - o
      b = vert(:, faces(2, k)) - o
      c = vert(:, faces(3, k)) - o
      v = dot_product(a, cross3(b, c)) / 6.0_wp
      vol = vol + v
      sm = sm + v * (a + b + c) / 4.0_wp
      cov = cov + v / 20.0_wp * (outer(a, a) + outer(b, b) + outer(c, c) + outer(a + b + c, a + b + c))
    end do
    g = sm / vol
    cov = cov - vol * outer(g, g)      ! second moments about the centroid
    g = g + o
    tens = -cov
    do i = 1, 3
      tens(i, i) = tens(i, i) + (cov(1, 1) + cov(2, 2) + cov(3, 3))
    end do
  contains
    pure function outer(x, y) result(m)
      real(wp), intent(in) :: x(3), y(3)
      real(wp) :: m(3, 3)
      m = spread(x, 2, 3) * spread(y, 1, 3)
    end function outer
  end subroutine polyhedron_volume_inertia
end module fracas_frame_3d
