!> The one n-dimensional driver of the systems built by their own class
!> (the network, the double pendulum, the Foucault pendulum): a system's
!> equations as an ode_system (pendula_ode, state vector of any size: 2N
!> phases and rates, 4 canonical coordinates, 6 Cartesian ones), run from
!> y0 at t0 by the method chosen, the path sampled at the outputs asked
!> for: DOP853 with error control (rtol, atol) at the times tout, or
!> Gauss-Legendre of order 4 or 6 with the fixed step dt, output k after
!> counts(k) more steps (tout ignored).  Each system's run module builds its
!> ode_system and calls nd_run; none keeps its own choice of integrator.
module pendula_nd_run
  use pendula_kinds, only: dp, i8, nan_dp
  use pendula_integrators, only: run_stats, st_bad_method, st_bad_step, st_cancelled
  use pendula_threads, only: thread_count
  use pendula_ode, only: ode_system, ode_dop853, ode_gauss, ode_gauss4, ode_gauss6
  implicit none
  private
  public :: nd_run, nd_runs_start, nd_output_times

  !> the methods of nd_run (the codes the Python layer passes)
  integer, parameter, public :: nd_dop853 = 1, nd_gauss4 = 2, nd_gauss6 = 3

contains

  !> The path of sys from y0 at t0 by `method` (nd_dop853, nd_gauss4,
  !> nd_gauss6): yout(:, k) at tout(k) (DOP853) or after counts(k) more steps
  !> of size dt (Gauss-Legendre).  status as pendula_ode's; st_bad_method
  !> (yout NaN) for another method.
  subroutine nd_run(sys, method, t0, y0, tout, counts, rtol, atol, dt, yout, stats, status, cancel)
    class(ode_system), intent(in) :: sys
    integer, intent(in) :: method
    real(dp), intent(in) :: t0, y0(:), tout(:), rtol, atol, dt
    integer(i8), intent(in) :: counts(:)
    real(dp), intent(out) :: yout(:, :)
    type(run_stats), intent(out) :: stats
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    select case (method)
    case (nd_dop853)
      call ode_dop853(sys, t0, y0, tout, rtol, atol, yout, stats, status, cancel)
    case (nd_gauss4)
      call ode_gauss(sys, ode_gauss4, t0, y0, dt, counts, yout, stats, status, cancel)
    case (nd_gauss6)
      call ode_gauss(sys, ode_gauss6, t0, y0, dt, counts, yout, stats, status, cancel)
    case default
      yout = nan_dp
      stats = run_stats()
      status = st_bad_method
    end select
  end subroutine nd_run

  !> The start of a set of runs on OpenMP threads (paths, pixels, orbits):
  !> each run's status st_cancelled until it reports (st_bad_step for all,
  !> and ok false, when the output spacing hg is not positive), nt the
  !> thread count for nthreads (0: OpenMP's default).
  subroutine nd_runs_start(hg, nthreads, status, nt, ok)
    real(dp), intent(in) :: hg
    integer, intent(in) :: nthreads
    integer, intent(out) :: status(:), nt
    logical, intent(out) :: ok
    ok = hg > 0.0_dp
    status = merge(st_cancelled, st_bad_step, ok)
    nt = thread_count(nthreads)
  end subroutine nd_runs_start

  !> The n output times from 0 to t_end as numpy.linspace spaces them (the step times the index, the
  !> end exact), so that a scene file's run and the Python class's on linspace(0, t_end, n) agree.
  pure subroutine nd_output_times(t_end, t)
    real(dp), intent(in) :: t_end
    real(dp), intent(out) :: t(:)
    integer :: j, n
    n = size(t)
    do j = 1, n
      t(j) = real(j - 1, dp) * (t_end / real(max(n - 1, 1), dp))
    end do
    if (n > 1) t(n) = t_end
  end subroutine nd_output_times

end module pendula_nd_run
