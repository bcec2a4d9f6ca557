!> Entry points the C glue calls: the pendulum's right-hand side and its
!> Jacobian, so that GSL's integrators integrate exactly the same model as
!> pendula's own.  The model travels through C as an opaque address (c_loc of
!> a pendulum_model the Fortran caller owns): every effect the model carries
!> reaches GSL's flows without the C side knowing it.
module pendula_capi
  use, intrinsic :: iso_c_binding, only: c_double, c_ptr, c_f_pointer
  use pendula_kinds, only: dp
  use pendula_integrators, only: pendulum_model, accel, accel_jacobian
  implicit none
  private
  public :: pendula_accel_c, pendula_accel_jac_c

contains

  !> theta'' of the model at address mp.
  function pendula_accel_c(mp, t, th, v) bind(C, name="pendula_accel_c") result(a)
    type(c_ptr), value, intent(in) :: mp
    real(c_double), value, intent(in) :: t, th, v
    real(c_double) :: a
    type(pendulum_model), pointer :: m
    call c_f_pointer(mp, m)
    a = accel(m, t, th, v)
  end function pendula_accel_c

  !> d theta'' / d theta and d theta'' / d theta' of the model at address mp.
  subroutine pendula_accel_jac_c(mp, t, th, v, dadth, dadv) bind(C, name="pendula_accel_jac_c")
    type(c_ptr), value, intent(in) :: mp
    real(c_double), value, intent(in) :: t, th, v
    real(c_double), intent(out) :: dadth, dadv
    type(pendulum_model), pointer :: m
    call c_f_pointer(mp, m)
    call accel_jacobian(m, t, th, v, dadth, dadv)
  end subroutine pendula_accel_jac_c

end module pendula_capi
