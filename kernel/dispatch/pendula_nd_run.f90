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
  public :: nd_run, nd_runs_start, nd_output_times, nd_method_code, nd_check_run, nd_output_counts

  !> the methods of nd_run (the codes the Python layer passes)
  integer, parameter, public :: nd_dop853 = 1, nd_gauss4 = 2, nd_gauss6 = 3
  !> the most output samples of a scene file's run
  integer, parameter, public :: nd_max_samples = 10000000

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

  !> nd_run's code of a method name ('dop853', 'gauss6', 'gauss4'), 0 for none.
  pure integer function nd_method_code(name)
    character(len=*), intent(in) :: name
    select case (trim(name))
    case ('dop853'); nd_method_code = nd_dop853
    case ('gauss6'); nd_method_code = nd_gauss6
    case ('gauss4'); nd_method_code = nd_gauss4
    case default; nd_method_code = 0
    end select
  end function nd_method_code

  !> The checks of a scene file's run fields (the systems' scene modules share them): msg blank, or the
  !> first field out of its domain, named.  Gauss-Legendre's step dt must divide the output spacing.
  pure subroutine nd_check_run(method, t_end, n_samples, dt, rtol, atol, msg)
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: t_end, dt, rtol, atol
    integer, intent(in) :: n_samples
    character(len=*), intent(out) :: msg
    real(dp) :: k
    msg = ''
    if (.not. (t_end > 0.0_dp .and. t_end <= huge(1.0_dp))) then
      msg = 'field ''t_end'' must be positive and finite'
    else if (n_samples < 1 .or. n_samples > nd_max_samples) then
      msg = 'field ''n_samples'' must lie in [1, 1e7]'
    else if (nd_method_code(method) == 0) then
      msg = 'field ''method'' must be ''dop853'', ''gauss6'' or ''gauss4'', got ''' // trim(method) // ''''
    else if (.not. (rtol > 0.0_dp .and. atol >= 0.0_dp .and. rtol < 1.0_dp .and. atol <= huge(1.0_dp))) then
      msg = 'fields ''rtol'', ''atol'' must satisfy 0 < rtol < 1 and atol >= 0'
    else if (nd_method_code(method) /= nd_dop853) then
      k = (t_end / real(max(n_samples - 1, 1), dp)) / dt
      if (.not. (dt > 0.0_dp .and. dt <= huge(1.0_dp))) then
        msg = 'field ''dt'' must be positive and finite'
      else if (.not. (k * real(n_samples, dp) <= 2.0e9_dp)) then
        msg = 'field ''dt'': the run needs more than 2e9 steps; give a larger dt or a shorter t_end'
      else if (abs(k - anint(k)) > 1.0e-9_dp * max(1.0_dp, k) .or. anint(k) < 1.0_dp) then
        msg = 'field ''dt'' must divide the output spacing t_end / (n_samples - 1) (Gauss-Legendre steps ' // &
              'land on the outputs)'
      end if
    end if
  end subroutine nd_check_run

  !> Gauss-Legendre's steps between the outputs of nd_output_times (counts(1) = 0: the start), or all 0
  !> for DOP853 (which outputs at the times themselves).
  pure subroutine nd_output_counts(method, t_end, dt, counts)
    character(len=*), intent(in) :: method
    real(dp), intent(in) :: t_end, dt
    integer(i8), intent(out) :: counts(:)
    counts = 0_i8
    if (nd_method_code(method) == nd_dop853 .or. size(counts) == 0) return
    counts = int(anint((t_end / real(max(size(counts) - 1, 1), dp)) / dt), i8)
    counts(1) = 0_i8
  end subroutine nd_output_counts

end module pendula_nd_run
