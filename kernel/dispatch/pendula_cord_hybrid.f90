!> The flexible cord with damping, torque or drive: the integrated circle
!> phase of the cord loop (pendula_cord%cord_loop, which also runs the
!> conservative cord with its closed-form circle phase).
!>
!> circle: the scene's adaptive integrator (dopri5, dop853) with the model's
!>   effects, stopped by the terminal event of the tension v**2 + eps cos(theta)
!>   falling through zero (event kind 4, located on the dense output);
!> flight: the parabola in closed form (pendula_cord: cord_flight_time,
!>   cord_flight_state): damping, torque and drive act at the pivot (the
!>   damping is pivot friction), and a slack cord transmits none of them;
!> jerk: the radial velocity removed, reversed times the restitution (cord_land).
!> This circle phase lives above the integrators, which the models layer may
!> not use; the loop it plugs into lives in the models layer.
!> No module state: one run's locals only.
module pendula_cord_hybrid
  use pendula_kinds, only: dp, nan_dp
  use pendula_cord, only: cord_circle, cord_loop, cord_blank, cord_check, cord_depart, cord_circle_end, &
    cord_log_room, cord_ok, cord_stop_max_flips
  use pendula_integrators, only: pendulum_model, make_model, event_spec, run_stats, integrate, &
    m_dopri5, m_dop853, st_ok, st_stopped
  implicit none
  private
  public :: cord_hybrid_run, cord_hybrid_all

  !> status: cord_ok .. cord_bad_restitution as pendula_cord; 5: the method is
  !> not adaptive (the tension event needs dense output); 100 + s: the
  !> integrator failed with its status s (pendula_integrators st_*).
  integer, parameter, public :: cord_bad_method = 5, cord_integrator_failed = 100

  !> The integrated circle phase: the scene's adaptive method with the
  !> model's effects (params = eps, beta, tau, amp, omega, phase, as
  !> make_model), stopped by the terminal event of the tension falling
  !> through zero.  work: steps and right-hand-side evaluations so far.
  type, extends(cord_circle) :: cord_circle_integrated
    real(dp) :: params(6) = 0.0_dp, rtol = 0.0_dp, atol = 0.0_dp, work(2) = 0.0_dp
    integer :: method = 0
  contains
    procedure :: phase => integrated_circle_phase
  end type cord_circle_integrated

contains

  !> The circle from (tc, thc, vc) integrated over the remaining output
  !> times t(i:) (or to the departure); status cord_integrator_failed + s
  !> when the integrator fails with its status s.
  subroutine integrated_circle_phase(self, eps, tc, thc, vc, cth, vr, t, i, theta, v, x, y, r, j, leaving, &
                                     t1, th1, v1, p, u, xib, status, cancel)
    class(cord_circle_integrated), intent(inout) :: self
    real(dp), intent(in) :: eps, tc, thc, vc, cth, vr, t(:)
    integer, intent(in) :: i
    real(dp), intent(inout) :: theta(:), v(:), x(:), y(:), r(:)
    integer, intent(out) :: j, status
    logical, intent(out) :: leaving
    real(dp), intent(out) :: t1, th1, v1, p(2), u(2), xib
    integer, intent(inout), volatile, optional :: cancel
    type(pendulum_model) :: m
    type(event_spec) :: ev
    type(run_stats) :: st
    real(dp) :: tev(1), thev(1), vev(1)
    real(dp), allocatable :: ts(:), ths(:), vs(:)
    integer :: n, k, ist, nev
    integer, volatile :: no_cancel

    n = size(t)
    status = cord_ok
    leaving = .false.
    t1 = nan_dp; th1 = nan_dp; v1 = nan_dp; p = nan_dp; u = nan_dp; xib = nan_dp
    j = i
    no_cancel = 0
    ev%kind = 4; ev%level = 0.0_dp; ev%direction = -1; ev%terminal = .true.
    ! the drive's phase at tc: the model's clock restarts at the segment
    m = make_model(eps, self%params(2), self%params(3), self%params(4), self%params(5), &
                   self%params(6) + self%params(5) * tc)
    if (i <= n) then
      allocate(ts(n - i + 1), ths(n - i + 1), vs(n - i + 1))
      ts = t(i:n) - tc
    else
      allocate(ts(1), ths(1), vs(1))
      ts = 0.0_dp
    end if
    if (present(cancel)) then
      call integrate(m, self%method, thc, vc, ts, self%rtol, self%atol, 0.0_dp, ths, vs, st, ist, ev, nev, &
                     tev, thev, vev, cancel)
    else
      call integrate(m, self%method, thc, vc, ts, self%rtol, self%atol, 0.0_dp, ths, vs, st, ist, ev, nev, &
                     tev, thev, vev, no_cancel)
    end if
    self%work = self%work + [real(st%nsteps, dp), real(st%nfev, dp)]
    if (ist /= st_ok .and. ist /= st_stopped) then
      status = cord_integrator_failed + ist; return
    end if
    if (ist == st_stopped .and. nev > 0) then
      leaving = .true.
      t1 = tc + tev(1); th1 = thev(1); v1 = vev(1)
      call cord_depart(eps, th1, v1, vr, p, u, xib)
    end if
    ! outputs up to the departure belong to the circle
    j = cord_circle_end(t, i, leaving, t1)
    if (j > i) then
      k = j - i
      theta(i:j - 1) = ths(1:k); v(i:j - 1) = vs(1:k)
      x(i:j - 1) = sin(ths(1:k)); y(i:j - 1) = -cos(ths(1:k)); r(i:j - 1) = 1.0_dp
    end if
  end subroutine integrated_circle_phase

  !> A flexible-cord run with effects at the sorted times t >= 0: cord_loop
  !> with the integrated circle phase.  params = eps, beta, tau, amp, omega,
  !> phase (as make_model).  flips(:, k) = t_leave, theta_leave, t_return,
  !> theta_return, xi_before, xi_after, v_leave, v_return for at most
  !> min(max_flips, size(flips, 2)) flips.  Outputs after a stop (max_flips,
  !> min_flight) are NaN; stop_reason says which.  work = steps and
  !> right-hand-side evaluations of the circle phases.
  subroutine cord_hybrid_run(params, method, rtol, atol, theta0, v0, restitution, max_flips, min_flight, &
                             t, theta, v, x, y, r, flips, nflips, stop_reason, work, status, cancel)
    real(dp), intent(in) :: params(6), rtol, atol, theta0, v0, restitution, min_flight, t(:)
    integer, intent(in) :: method, max_flips
    real(dp), intent(out) :: theta(:), v(:), x(:), y(:), r(:), flips(:, :), work(2)
    integer, intent(out) :: nflips, stop_reason, status
    integer, intent(inout), volatile, optional :: cancel
    type(cord_circle_integrated) :: circ

    work = 0.0_dp
    call cord_blank(theta, v, x, y, r, flips, nflips, stop_reason)
    status = cord_check(params(1), theta0, v0, restitution, t)
    if (status /= cord_ok) return
    if (method /= m_dopri5 .and. method /= m_dop853) then
      status = cord_bad_method; return
    end if
    if (size(t) == 0) return
    circ%graze_restarts = .true.
    circ%params = params; circ%method = method; circ%rtol = rtol; circ%atol = atol
    call cord_loop(circ, params(1), theta0, v0, restitution, max_flips, min_flight, t, theta, v, x, y, r, &
                   flips, nflips, stop_reason, status, cancel)
    work = circ%work
  end subroutine cord_hybrid_run

  !> cord_hybrid_run with a flip log that grows as needed (up to max_flips entries).
  subroutine cord_hybrid_all(params, method, rtol, atol, theta0, v0, restitution, max_flips, min_flight, &
                             t, theta, v, x, y, r, flips, nflips, stop_reason, work, status, cancel)
    real(dp), intent(in) :: params(6), rtol, atol, theta0, v0, restitution, min_flight, t(:)
    integer, intent(in) :: method, max_flips
    real(dp), intent(out) :: theta(:), v(:), x(:), y(:), r(:), work(2)
    real(dp), allocatable, intent(out) :: flips(:, :)
    integer, intent(out) :: nflips, stop_reason, status
    integer, intent(inout), volatile, optional :: cancel
    integer :: cap
    cap = cord_log_room(0, max_flips, cord_ok, cord_stop_max_flips, 0)
    do
      if (allocated(flips)) deallocate(flips)
      allocate(flips(8, cap))
      call cord_hybrid_run(params, method, rtol, atol, theta0, v0, restitution, max_flips, min_flight, &
                           t, theta, v, x, y, r, flips, nflips, stop_reason, work, status, cancel)
      cap = cord_log_room(cap, max_flips, status, stop_reason, nflips)
      if (cap == 0) exit
    end do
  end subroutine cord_hybrid_all

end module pendula_cord_hybrid
