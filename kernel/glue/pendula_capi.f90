!> Entry points the C glue calls: the pendulum's right-hand side, so that GSL's
!> integrators integrate exactly the same model as pendula's own.
module pendula_capi
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  use pendula_kinds, only: dp
  use pendula_integrators, only: pendulum_model, make_model, accel
  use pendula_equilibria, only: field_slope
  implicit none
  private
  public :: pendula_accel_c, pendula_accel_jac_c

contains

  !> theta'' for params = [eps, beta, tau, amp, omega, phase].
  function pendula_accel_c(params, t, th, v) bind(C, name="pendula_accel_c") result(a)
    real(c_double), intent(in) :: params(6)
    real(c_double), value, intent(in) :: t, th, v
    real(c_double) :: a
    type(pendulum_model) :: m
    m = make_model(params(1), params(2), params(3), params(4), params(5), params(6))
    a = accel(m, t, th, v)
  end function pendula_accel_c

  !> The Jacobian of theta'' for params = [eps, beta, tau, amp, omega, phase]:
  !> d theta'' / d theta (the field's exact slope) and d theta'' / d theta' = -beta.
  subroutine pendula_accel_jac_c(params, th, dadth, dadv) bind(C, name="pendula_accel_jac_c")
    real(c_double), intent(in) :: params(6)
    real(c_double), value, intent(in) :: th
    real(c_double), intent(out) :: dadth, dadv
    type(pendulum_model) :: m
    m = make_model(params(1), params(2), params(3), params(4), params(5), params(6))
    dadth = field_slope(m%gkind, m%gpar, m%eps, th)
    dadv = -m%beta
  end subroutine pendula_accel_jac_c

end module pendula_capi
