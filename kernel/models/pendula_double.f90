!> The double pendulum in canonical coordinates: two arms hang from a fixed
!> pivot, the second from the end of the first, theta1 and theta2 their
!> angles from the downward vertical.  Each arm is a massless rod with a
!> point mass at its end, or a uniform rod (the compound double pendulum).
!>
!> With d = theta1 - theta2 the kinetic energy is
!>   T = (a w1^2 + c w2^2) / 2 + b cos(d) w1 w2,
!> a = (m1 + m2) l1^2, b = m2 l1 l2, c = m2 l2^2 (point masses) or
!> a = (m1/3 + m2) l1^2, b = m2 l1 l2 / 2, c = m2 l2^2 / 3 (rods), and the
!> potential energy, zero at the bottom,
!>   V = g A (1 - cos theta1) + g B (1 - cos theta2),
!> A = (s m1 + m2) l1, B = s m2 l2, s = 1 (point masses) or 1/2 (rods).
!> The state is y = (theta1, theta2, p1, p2), p = M(d) w the canonical
!> momenta, M = [[a, b cos d], [b cos d, c]], so that a symplectic method
!> (Gauss-Legendre) keeps H = T + V bounded.  det M = D0 + b^2 sin^2 d with
!> D0 = ac - b^2 in closed form (m1 m2 l1^2 l2^2, or m2 l1^2 l2^2 (m1/9 +
!> m2/12) for rods), a sum of positive terms: no cancellation.
!>
!> Hamilton's equations (Goldstein, "Classical Mechanics", section 8.1),
!> with a viscous torque -k_i w_i on each angle:
!>   theta_i' = w_i,  w = M^-1 p,
!>   p1' = -b sin(d) w1 w2 - g A sin theta1 - k1 w1,
!>   p2' = +b sin(d) w1 w2 - g B sin theta2 - k2 w2.
module pendula_double
  use pendula_kinds, only: dp, two_pi
  implicit none
  private
  public :: double_pendulum, make_double, double_rhs, double_jacobian, double_energy, double_velocities
  public :: double_time_rates, double_default_dt

  !> the double pendulum's time scales (double_time_rates), and the Gauss-Legendre steps per period
  !> of the fastest (its default step)
  integer, parameter, public :: n_double_scales = 3, dts_modes = 1, dts_damping = 2, dts_rotation = 3
  character(len=12), parameter, public :: double_scale_names(n_double_scales) = [character(len=12) :: &
    'modes', 'damping', 'rotation']
  real(dp), parameter :: double_steps_per_period = 100.0_dp

  !> the entries of the parameter vector of make_double
  integer, parameter, public :: dpp_m1 = 1, dpp_m2 = 2, dpp_l1 = 3, dpp_l2 = 4, dpp_g = 5, dpp_rods = 6, &
    dpp_k1 = 7, dpp_k2 = 8, dpp_size = 8

  !> The coefficients of the equations of motion (see the module's text).
  type :: double_pendulum
    real(dp) :: a = 1.0_dp, b = 1.0_dp, c = 1.0_dp, d0 = 1.0_dp, ga = 1.0_dp, gb = 1.0_dp
    real(dp) :: k1 = 0.0_dp, k2 = 0.0_dp
  end type double_pendulum

contains

  !> The double pendulum of p = (m1, m2, l1, l2, g, rods, k1, k2): rods /= 0
  !> for uniform rods, k1 and k2 the viscous torque coefficients.
  pure function make_double(p) result(dpd)
    real(dp), intent(in) :: p(dpp_size)
    type(double_pendulum) :: dpd
    real(dp) :: m1, m2, l1, l2, g
    m1 = p(dpp_m1); m2 = p(dpp_m2); l1 = p(dpp_l1); l2 = p(dpp_l2); g = p(dpp_g)
    if (p(dpp_rods) /= 0.0_dp) then
      dpd%a = (m1 / 3.0_dp + m2) * l1 * l1
      dpd%b = 0.5_dp * m2 * l1 * l2
      dpd%c = m2 * l2 * l2 / 3.0_dp
      dpd%d0 = m2 * (l1 * l2)**2 * (m1 / 9.0_dp + m2 / 12.0_dp)
      dpd%ga = g * (0.5_dp * m1 + m2) * l1
      dpd%gb = g * 0.5_dp * m2 * l2
    else
      dpd%a = (m1 + m2) * l1 * l1
      dpd%b = m2 * l1 * l2
      dpd%c = m2 * l2 * l2
      dpd%d0 = m1 * m2 * (l1 * l2)**2
      dpd%ga = g * (m1 + m2) * l1
      dpd%gb = g * m2 * l2
    end if
    dpd%k1 = p(dpp_k1); dpd%k2 = p(dpp_k2)
  end function make_double

  !> The angular velocities w = M^-1 p of the state y = (theta1, theta2, p1, p2).
  pure subroutine double_velocities(dpd, y, w)
    type(double_pendulum), intent(in) :: dpd
    real(dp), intent(in) :: y(4)
    real(dp), intent(out) :: w(2)
    real(dp) :: cd, sd, det
    call velocities(dpd, y, cd, sd, det, w)
  end subroutine double_velocities

  !> w = M^-1 p, with cos d, sin d and det M on the way (each formed once).
  pure subroutine velocities(dpd, y, cd, sd, det, w)
    type(double_pendulum), intent(in) :: dpd
    real(dp), intent(in) :: y(4)
    real(dp), intent(out) :: cd, sd, det, w(2)
    cd = cos(y(1) - y(2)); sd = sin(y(1) - y(2))
    det = dpd%d0 + (dpd%b * sd)**2
    w(1) = (dpd%c * y(3) - dpd%b * cd * y(4)) / det
    w(2) = (dpd%a * y(4) - dpd%b * cd * y(3)) / det
  end subroutine velocities

  !> The right-hand side y' of Hamilton's equations.
  pure subroutine double_rhs(dpd, y, f)
    type(double_pendulum), intent(in) :: dpd
    real(dp), intent(in) :: y(4)
    real(dp), intent(out) :: f(4)
    real(dp) :: w(2), s, cd, sd, det
    call velocities(dpd, y, cd, sd, det, w)
    s = dpd%b * sd * w(1) * w(2)
    f(1:2) = w
    f(3) = -s - dpd%ga * sin(y(1)) - dpd%k1 * w(1)
    f(4) = s - dpd%gb * sin(y(2)) - dpd%k2 * w(2)
  end subroutine double_rhs

  !> The Jacobian jac(i, j) = df_i / dy_j of double_rhs.
  pure subroutine double_jacobian(dpd, y, jac)
    type(double_pendulum), intent(in) :: dpd
    real(dp), intent(in) :: y(4)
    real(dp), intent(out) :: jac(4, 4)
    real(dp) :: cd, sd, det, w(2), wd(2), wp(2, 2), sdd, sp(2)
    call velocities(dpd, y, cd, sd, det, w)
    ! dw/dd at fixed p, and dw/dp = M^-1
    wd(1) = (dpd%b * sd * y(4) - w(1) * 2.0_dp * dpd%b**2 * sd * cd) / det
    wd(2) = (dpd%b * sd * y(3) - w(2) * 2.0_dp * dpd%b**2 * sd * cd) / det
    wp(1, 1) = dpd%c / det; wp(1, 2) = -dpd%b * cd / det
    wp(2, 1) = -dpd%b * cd / det; wp(2, 2) = dpd%a / det
    ! s = b sin(d) w1 w2 and its derivatives in d and p
    sdd = dpd%b * (cd * w(1) * w(2) + sd * (wd(1) * w(2) + w(1) * wd(2)))
    sp = dpd%b * sd * (wp(1, :) * w(2) + w(1) * wp(2, :))
    ! rows 1, 2: w; columns 1, 2: d/dtheta1 = d/dd, d/dtheta2 = -d/dd
    jac(1, 1) = wd(1); jac(1, 2) = -wd(1); jac(1, 3:4) = wp(1, :)
    jac(2, 1) = wd(2); jac(2, 2) = -wd(2); jac(2, 3:4) = wp(2, :)
    jac(3, 1) = -sdd - dpd%ga * cos(y(1)) - dpd%k1 * wd(1)
    jac(3, 2) = sdd + dpd%k1 * wd(1)
    jac(3, 3:4) = -sp - dpd%k1 * wp(1, :)
    jac(4, 1) = sdd - dpd%k2 * wd(2)
    jac(4, 2) = -sdd - dpd%gb * cos(y(2)) + dpd%k2 * wd(2)
    jac(4, 3:4) = sp - dpd%k2 * wp(2, :)
  end subroutine double_jacobian

  !> The energy H = (p . w) / 2 + V, zero at rest at the bottom (1 - cos x
  !> as 2 sin^2(x/2): no cancellation near the bottom).
  pure function double_energy(dpd, y) result(en)
    type(double_pendulum), intent(in) :: dpd
    real(dp), intent(in) :: y(4)
    real(dp) :: en, w(2)
    call double_velocities(dpd, y, w)
    en = 0.5_dp * (y(3) * w(1) + y(4) * w(2)) &
         + 2.0_dp * (dpd%ga * sin(0.5_dp * y(1))**2 + dpd%gb * sin(0.5_dp * y(2))**2)
  end function double_energy

  !> The double pendulum's time scales as rates (1 / time): 'modes' the fast
  !> normal mode's angular frequency at the bottom, the larger root of
  !> D0 w^4 - (gA c + gB a) w^2 + gA gB = 0; 'damping' max(k1, k2) / lmin, lmin
  !> = the smallest eigenvalue of M(0), which bounds M(d)'s from below; and
  !> 'rotation' sqrt(2 H / lmin) at the state y, the largest angular speed the
  !> energy H allows (V >= 0 and T >= lmin |w|^2 / 2): the whirl of a high
  !> energy, which the modes no longer describe.
  pure function double_time_rates(dpd, y) result(r)
    type(double_pendulum), intent(in) :: dpd
    real(dp), intent(in) :: y(4)
    real(dp) :: r(n_double_scales), s, lmin
    s = dpd%ga * dpd%c + dpd%gb * dpd%a
    r(dts_modes) = sqrt((s + sqrt(max(s * s - 4.0_dp * dpd%d0 * dpd%ga * dpd%gb, 0.0_dp))) / (2.0_dp * dpd%d0))
    ! lmin = D0 / lmax: the product of M(0)'s eigenvalues is D0, so no cancellation
    lmin = dpd%d0 / (0.5_dp * (dpd%a + dpd%c) + sqrt(0.25_dp * (dpd%a - dpd%c)**2 + dpd%b**2))
    r(dts_damping) = max(abs(dpd%k1), abs(dpd%k2)) / lmin
    r(dts_rotation) = sqrt(2.0_dp * max(double_energy(dpd, y), 0.0_dp) / lmin)
  end function double_time_rates

  !> The default Gauss-Legendre step: 2 pi over the fastest rate over
  !> double_steps_per_period (1/100 of the fast mode's period at low energy).
  pure real(dp) function double_default_dt(r)
    real(dp), intent(in) :: r(n_double_scales)
    double_default_dt = two_pi / max(r(dts_modes), r(dts_damping), r(dts_rotation)) / double_steps_per_period
  end function double_default_dt

end module pendula_double
