!> A network of pendula (pendula_network) on the n-dimensional driver
!> (pendula_nd_run): the network as a mechanical system, y = (phi, phi'),
!> its acceleration the force over each element's C, its friction beta / C.
!> Simulation by DOP853 or Gauss-Legendre (nd_run), Langevin paths by BAOAB
!> (a set of paths on OpenMP threads, path k on the noise streams of point k).
module pendula_network_run
  use pendula_kinds, only: dp, i8, nan_dp
  use pendula_threads, only: thread_count
  use pendula_integrators, only: run_stats, st_cancelled
  use pendula_ode, only: mechanical_system, ode_baoab
  use pendula_nd_run, only: nd_run, nd_dop853, nd_gauss4, nd_gauss6
  use pendula_network, only: network, network_force
  implicit none
  private
  public :: network_ode, make_network_ode, network_simulate, network_simulate_batch, network_langevin

  !> the methods of network_simulate: those of nd_run
  public :: nd_dop853, nd_gauss4, nd_gauss6

  type, extends(mechanical_system) :: network_ode
    type(network) :: net
    real(dp), allocatable :: inv_c(:)
  contains
    procedure :: accel => network_accel
  end type network_ode

contains

  pure function make_network_ode(net) result(sys)
    type(network), intent(in) :: net
    type(network_ode) :: sys
    sys%net = net
    sys%n = 2 * net%nel
    sys%inv_c = 1.0_dp / net%c
    sys%gamma = net%beta * sys%inv_c
  end function make_network_ode

  pure subroutine network_accel(self, t, q, a)
    class(network_ode), intent(in) :: self
    real(dp), intent(in) :: t, q(:)
    real(dp), intent(out) :: a(:)
    call network_force(self%net, t, q, a)
    a = a * self%inv_c
  end subroutine network_accel

  !> The network from y0 = (phi, phi') at t = 0 to the times tout by
  !> DOP853 (rtol, atol) or Gauss-Legendre (fixed step dt; the outputs after
  !> counts(k) more steps, tout ignored).  status as pendula_ode's.
  subroutine network_simulate(net, method, y0, tout, counts, rtol, atol, dt, yout, stats, status, cancel)
    type(network), intent(in) :: net
    integer, intent(in) :: method
    real(dp), intent(in) :: y0(:), tout(:), rtol, atol, dt
    integer(i8), intent(in) :: counts(:)
    real(dp), intent(out) :: yout(:, :)
    type(run_stats), intent(out) :: stats
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    call nd_run(make_network_ode(net), method, 0.0_dp, y0, tout, counts, rtol, atol, dt, yout, stats, status, &
                cancel)
  end subroutine network_simulate

  !> A batch of deterministic runs of one network (network_simulate's methods): run k from y0(:, k) to the
  !> same output times, yout(:, :, k), stats(:, k) = (steps, accepted, rejected, rhs evaluations) and
  !> status(k) its results (NaN and st_cancelled for a run the cancel flag skipped).  The runs share nothing but the network, so each one's result is the same
  !> whatever the thread count nthreads (0: OpenMP's default).
  subroutine network_simulate_batch(net, method, y0, tout, counts, rtol, atol, dt, nthreads, yout, stats, &
                                    status, cancel)
    type(network), intent(in) :: net
    integer, intent(in) :: method, nthreads
    real(dp), intent(in) :: y0(:, :), tout(:), rtol, atol, dt
    integer(i8), intent(in) :: counts(:)
    real(dp), intent(out) :: yout(:, :, :)
    integer(i8), intent(out) :: stats(:, :)
    integer, intent(out) :: status(:)
    integer, intent(inout), volatile :: cancel
    type(network_ode) :: sys
    type(run_stats) :: st
    integer :: k, nt
    sys = make_network_ode(net)
    status = st_cancelled
    stats = 0_i8
    yout = nan_dp     ! a run skipped on cancellation reports NaN, not stale memory
    nt = thread_count(nthreads)
    !$omp parallel do schedule(dynamic, 1) default(none) num_threads(nt) private(st) &
    !$omp   shared(sys, method, y0, tout, counts, rtol, atol, dt, yout, stats, status, cancel)
    do k = 1, size(y0, 2)
      if (cancel == 0) then
        call nd_run(sys, method, 0.0_dp, y0(:, k), tout, counts, rtol, atol, dt, yout(:, :, k), st, &
                    status(k), cancel)
        stats(:, k) = [st%nsteps, st%naccept, st%nreject, st%nfev]
      end if
    end do
    !$omp end parallel do
  end subroutine network_simulate_batch

  !> npath Langevin paths of the network at the temperatures temp(nel)
  !> (energy units of the couplings and eps): path k starts from y0(:, k),
  !> draws its noise from the streams of point first + k - 1 of seed, and
  !> records the state after counts(j) more BAOAB steps of size h into
  !> yout(:, j, k); status(k) its status.  The paths run on nthreads OpenMP
  !> threads (0: OpenMP's default); each path's result is the same whatever
  !> the thread count.
  subroutine network_langevin(net, temp, seed, first, h, y0, counts, nthreads, yout, status, cancel)
    type(network), intent(in) :: net
    real(dp), intent(in) :: temp(:), h, y0(:, :)
    integer(i8), intent(in) :: seed, first, counts(:)
    integer, intent(in) :: nthreads
    real(dp), intent(out) :: yout(:, :, :)
    integer, intent(out) :: status(:)
    integer, intent(inout), volatile :: cancel
    type(network_ode) :: sys
    real(dp), allocatable :: s2(:)
    integer :: k, nt
    sys = make_network_ode(net)
    s2 = temp * sys%inv_c
    status = st_cancelled
    yout = nan_dp     ! a path skipped on cancellation reports NaN, not stale memory
    nt = thread_count(nthreads)
    !$omp parallel do schedule(dynamic, 1) default(none) num_threads(nt) &
    !$omp   shared(sys, s2, seed, first, h, y0, counts, yout, status, cancel)
    do k = 1, size(y0, 2)
      if (cancel == 0) then
        call ode_baoab(sys, s2, seed, first + int(k - 1, i8), 0.0_dp, y0(:, k), h, counts, yout(:, :, k), &
                       status(k), cancel)
      end if
    end do
    !$omp end parallel do
  end subroutine network_langevin

end module pendula_network_run
