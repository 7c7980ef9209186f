!> Small 3D geometry shared by the 3D rigid body model, its contactors and the
!> 3D detection: cross product, the exact rotation of a rotation vector
!> (Rodrigues), an orthonormal tangent pair completing a normal, and the
!> eigen-decomposition of a symmetric 3x3 (principal inertia frame).
module fracas_frame_3d
  use fracas_kinds, only: wp
  implicit none
  private
  public :: cross3, rotation_of_vector, tangents_of_normal, symmetric_eigen_3x3

contains

  pure function cross3(a, b) result(c)
    real(wp), intent(in) :: a(3), b(3)
    real(wp) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross3

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
    real(wp) :: m(3, 3), theta, t, c, s, off, scale, tmp(3), tl
    integer :: sweep, p, q, i, j, k
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
    ! ascending order (insertion sort of 3), vectors along
    do i = 2, 3
      j = i
      do while (j > 1)
        if (lam(j - 1) <= lam(j)) exit
        tl = lam(j); lam(j) = lam(j - 1); lam(j - 1) = tl
        tmp = v(:, j); v(:, j) = v(:, j - 1); v(:, j - 1) = tmp
        j = j - 1
      end do
    end do
    if (dot_product(cross3(v(:, 1), v(:, 2)), v(:, 3)) < 0.0_wp) v(:, 3) = -v(:, 3)
  end subroutine symmetric_eigen_3x3
end module fracas_frame_3d
