!> The overdamped (RSJ) Josephson junction under an rf drive, phi' = i + a cos(Omega t) - sin(phi)
!> (time in units of 1 / omega_c, omega_c = 2 pi I_c R / Phi_0): the mean phase velocity <phi'>
!> (the dc voltage in units of I_c R) at many biases, on OpenMP threads.  The map and its rotation
!> number are computed in pendula_rsj_map.c (GSL rk8pd and Brent); this module runs the biases.
!> No module variables (OpenMP-safe).
module pendula_rsj
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_long
  use pendula_kinds, only: dp, nan_dp
  use pendula_threads, only: thread_count
  implicit none
  private
  public :: rsj_mean_velocity, rsj_gap_ranges

  interface
    function rsj_rotation_c(i, a, omega, rtol, atol, periods, rho, err, step, nfev) &
        bind(C, name="pendula_rsj_rotation") result(status)
      import :: c_int, c_double, c_long
      real(c_double), value, intent(in) :: i, a, omega, rtol, atol
      integer(c_long), value, intent(in) :: periods
      real(c_double), intent(out) :: rho, err, step, nfev
      integer(c_int) :: status
    end function rsj_rotation_c

    function rsj_gap_range_c(i, a, omega, rtol, atol, gmin, gmax, nfev) &
        bind(C, name="pendula_rsj_gap_range") result(status)
      import :: c_int, c_double
      real(c_double), value, intent(in) :: i, a, omega, rtol, atol
      real(c_double), intent(out) :: gmin, gmax, nfev
      integer(c_int) :: status
    end function rsj_gap_range_c
  end interface

contains

  !> <phi'> = rho Omega at the biases bias(1:n): mean velocity, its error bound, the step n where
  !> locked (else NaN), status 0 decided, 6 locked, 1 failed; cancel read between biases (then 5).
  subroutine rsj_mean_velocity(n, bias, a, omega, rtol, atol, periods, vm, err, step, status, nthreads, cancel)
    integer, intent(in) :: n, nthreads
    real(dp), intent(in) :: bias(n), a, omega, rtol, atol
    integer(c_long), intent(in) :: periods
    real(dp), intent(out) :: vm(n), err(n), step(n)
    integer, intent(out) :: status(n)
    integer, intent(inout), volatile :: cancel
    integer :: k, nt
    real(dp) :: rho, e, s, nfev
    nt = thread_count(nthreads)
    !$omp parallel do schedule(dynamic, 1) default(none) num_threads(nt) &
    !$omp   shared(n, bias, a, omega, rtol, atol, periods, vm, err, step, status, cancel) private(k, rho, e, s, nfev)
    do k = 1, n
      if (cancel /= 0) then
        vm(k) = nan_dp; err(k) = nan_dp; step(k) = nan_dp; status(k) = 5
        cycle
      end if
      status(k) = int(rsj_rotation_c(bias(k), a, omega, rtol, atol, periods, rho, e, s, nfev))
      vm(k) = rho * omega
      err(k) = e * omega
      step(k) = s
    end do
    !$omp end parallel do
  end subroutine rsj_mean_velocity

  !> The extrema of g(x) = F(x) - x of the stroboscopic map at each bias (the step n spans the
  !> biases where gmin <= 2 pi n <= gmax); status 0, or 1 failed.
  subroutine rsj_gap_ranges(n, bias, a, omega, rtol, atol, gmin, gmax, status, nthreads)
    integer, intent(in) :: n, nthreads
    real(dp), intent(in) :: bias(n), a, omega, rtol, atol
    real(dp), intent(out) :: gmin(n), gmax(n)
    integer, intent(out) :: status(n)
    integer :: k, nt
    real(dp) :: nfev
    nt = thread_count(nthreads)
    !$omp parallel do schedule(dynamic, 1) default(none) num_threads(nt) &
    !$omp   shared(n, bias, a, omega, rtol, atol, gmin, gmax, status) private(k, nfev)
    do k = 1, n
      status(k) = int(rsj_gap_range_c(bias(k), a, omega, rtol, atol, gmin(k), gmax(k), nfev))
    end do
    !$omp end parallel do
  end subroutine rsj_gap_ranges
end module pendula_rsj
