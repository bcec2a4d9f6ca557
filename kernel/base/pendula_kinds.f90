!> Kinds and IEEE constants shared by every pendula kernel module.
module pendula_kinds
  use, intrinsic :: iso_fortran_env, only: real64, int64
  implicit none
  private
  public :: dp, i8, pi, pi_lo, half_pi, two_pi, nan_dp, inf_dp, eps_dp

  integer, parameter :: dp = real64
  integer, parameter :: i8 = int64

  !> pi as a double-double: pi = pi + pi_lo to about 1e-32.
  real(dp), parameter :: pi = 3.141592653589793116_dp
  real(dp), parameter :: pi_lo = 1.2246467991473532e-16_dp
  real(dp), parameter :: half_pi = 1.5707963267948966192_dp
  real(dp), parameter :: two_pi = 6.283185307179586232_dp
  real(dp), parameter :: eps_dp = epsilon(1.0_dp)
  !> quiet NaN (0x7FF8000000000000) and +Inf (0x7FF0000000000000)
  real(dp), parameter :: nan_dp = transfer(9221120237041090560_int64, 1.0_dp)
  real(dp), parameter :: inf_dp = transfer(9218868437227405312_int64, 1.0_dp)
end module pendula_kinds
