!> The flexible cord with damping, torque or drive: the hybrid loop.
!>
!> circle: the scene's adaptive integrator (dopri5, dop853) with the model's
!>   effects, stopped by the terminal event of the tension v**2 + eps cos(theta)
!>   falling through zero (event kind 4, located on the dense output);
!> flight: the parabola in closed form (pendula_cord: cord_flight_time,
!>   cord_flight_state): damping, torque and drive act at the pivot (the
!>   damping is pivot friction), and a slack cord transmits none of them;
!> jerk: the radial velocity removed, reversed times the restitution (cord_land).
!> The conservative cord has its own closed-form loop (pendula_cord%cord_run);
!> this one lives above the integrators, which the models layer may not use.
!> No module state: one run's locals only.
module pendula_cord_hybrid
  use pendula_kinds, only: dp, nan_dp, two_pi
  use pendula_cord, only: cord_check, cord_depart, cord_flight_time, cord_fly, cord_log_room, &
    cord_flight_verdict, verdict_absorbed, verdict_too_short, &
    cord_ok, cord_cancelled, cord_stop_t_end, cord_stop_max_flips, cord_stop_min_flight
  use pendula_integrators, only: pendulum_model, make_model, event_spec, run_stats, integrate, &
    m_dopri5, m_dop853, st_ok, st_stopped
  implicit none
  private
  public :: cord_hybrid_run, cord_hybrid_all

  !> status: cord_ok .. cord_bad_restitution as pendula_cord; 5: the method is
  !> not adaptive (the tension event needs dense output); 100 + s: the
  !> integrator failed with its status s (pendula_integrators st_*).
  integer, parameter, public :: cord_bad_method = 5, cord_integrator_failed = 100

contains

  !> A flexible-cord run with effects at the sorted times t >= 0.
  !> params = eps, beta, tau, amp, omega, phase (as make_model).  flips(:, k) =
  !> t_leave, theta_leave, t_return, theta_return, xi_before, xi_after, v_leave,
  !> v_return for at most min(max_flips, size(flips, 2)) flips.  Outputs after a
  !> stop (max_flips, min_flight) are NaN; stop_reason says which.  work =
  !> steps and right-hand-side evaluations of the circle phases.
  subroutine cord_hybrid_run(params, method, rtol, atol, theta0, v0, restitution, max_flips, min_flight, &
                             t, theta, v, x, y, r, flips, nflips, stop_reason, work, status, cancel)
    real(dp), intent(in) :: params(6), rtol, atol, theta0, v0, restitution, min_flight, t(:)
    integer, intent(in) :: method, max_flips
    real(dp), intent(out) :: theta(:), v(:), x(:), y(:), r(:), flips(:, :), work(2)
    integer, intent(out) :: nflips, stop_reason, status
    integer, intent(inout), volatile, optional :: cancel
    type(pendulum_model) :: m
    type(event_spec) :: ev
    type(run_stats) :: st
    real(dp) :: eps, tc, thc, vc, vr, tension, t1, th1, v1, xib, tau, th2, v2, vr2, p(2), u(2)
    real(dp) :: tev(1), thev(1), vev(1)
    real(dp), allocatable :: ts(:), ths(:), vs(:)
    integer :: n, i, j, k, cap, ist, nev, nstay
    logical :: leaving, general, stay
    integer, volatile :: no_cancel

    n = size(t)
    theta = nan_dp; v = nan_dp; x = nan_dp; y = nan_dp; r = nan_dp
    flips = nan_dp; work = 0.0_dp
    nflips = 0; stop_reason = cord_stop_t_end; status = cord_ok
    no_cancel = 0
    eps = params(1)
    status = cord_check(eps, theta0, v0, restitution, t)
    if (status /= cord_ok) return
    if (method /= m_dopri5 .and. method /= m_dop853) then
      status = cord_bad_method; return
    end if
    if (n == 0) return
    cap = min(max_flips, size(flips, 2))
    ev%kind = 4; ev%level = 0.0_dp; ev%direction = -1; ev%terminal = .true.
    tc = 0.0_dp; thc = theta0; vc = v0; vr = 0.0_dp
    i = 1
    stay = .false.
    nstay = 0
    do
      ! the flag is read once per circle-flight cycle too: a run of many short
      ! cycles never reaches the integrator's own polling interval
      if (present(cancel)) then
        if (cancel /= 0) then
          status = cord_cancelled; return
        end if
      end if
      ! ---- the circle from (tc, thc, vc), unless the bob is in flight or slack
      tension = vc * vc + eps * cos(thc)
      leaving = .false.
      if ((vr < 0.0_dp .or. tension <= 0.0_dp) .and. .not. stay) then
        leaving = .true.
        general = vr < 0.0_dp .or. tension < 0.0_dp
        t1 = tc; th1 = thc; v1 = vc
      else
        stay = .false.
        ! the drive's phase at tc: the model's clock restarts at the segment
        m = make_model(eps, params(2), params(3), params(4), params(5), params(6) + params(5) * tc)
        if (i <= n) then
          allocate(ts(n - i + 1), ths(n - i + 1), vs(n - i + 1))
          ts = t(i:n) - tc
        else
          allocate(ts(1), ths(1), vs(1))
          ts = 0.0_dp
        end if
        if (present(cancel)) then
          call integrate(m, method, thc, vc, ts, rtol, atol, 0.0_dp, ths, vs, st, ist, ev, nev, tev, thev, vev, &
                         cancel)
        else
          call integrate(m, method, thc, vc, ts, rtol, atol, 0.0_dp, ths, vs, st, ist, ev, nev, tev, thev, vev, &
                         no_cancel)
        end if
        work = work + [real(st%nsteps, dp), real(st%nfev, dp)]
        if (ist /= st_ok .and. ist /= st_stopped) then
          status = cord_integrator_failed + ist; return
        end if
        j = n + 1
        if (ist == st_stopped .and. nev > 0) then
          leaving = .true.; general = .false.
          t1 = tc + tev(1); th1 = thev(1); v1 = vev(1)
          ! outputs up to the departure belong to the circle
          j = i
          do while (j <= n)
            if (t(j) > t1) exit
            j = j + 1
          end do
        end if
        if (j > i) then
          k = j - i
          theta(i:j - 1) = ths(1:k); v(i:j - 1) = vs(1:k)
          x(i:j - 1) = sin(ths(1:k)); y(i:j - 1) = -cos(ths(1:k)); r(i:j - 1) = 1.0_dp
          i = j
        end if
        deallocate(ts, ths, vs)
      end if
      if (.not. leaving) exit
      if (t1 > t(n)) exit
      if (nflips >= cap) then
        stop_reason = cord_stop_max_flips; exit
      end if
      ! ---- the flight
      call cord_depart(eps, th1, v1, vr, p, u, xib)
      tau = cord_flight_time(eps, p, u, general)
      if (tau /= tau) then
        ! the tension is zero but rising: the bob stays on the circle (the
        ! integrator does not report an event at its starting point)
        tc = t1; thc = th1; vc = v1; vr = 0.0_dp
        stay = .true.
        ! a grazing sequence that never gets off the circle: stop, saying so
        nstay = nstay + 1
        if (nstay > 1000) then
          stop_reason = cord_stop_min_flight; exit
        end if
        cycle
      end if
      select case (cord_flight_verdict(eps, min_flight, general, vr, tau))
      case (verdict_absorbed)
        vr = 0.0_dp; tc = t1; thc = th1; vc = v1
        cycle
      case (verdict_too_short)
        stop_reason = cord_stop_min_flight; exit
      end select
      nflips = nflips + 1
      nstay = 0
      call cord_fly(eps, restitution, p, u, tau, t1, th1, v1, xib, t, i, theta, v, x, y, r, &
                    flips(:, nflips), th2, v2, vr2)
      tc = t1 + tau; thc = th2; vc = v2; vr = vr2
      if (tc > t(n)) exit
    end do
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
