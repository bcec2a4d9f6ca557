!> Sweeps: one measure evaluated at a block of grid points, in parallel.
!>
!> Each grid point is a full model (eps, beta, tau, A, Omega, phase) and an
!> initial state (theta0, v0).  A point computes only what its measure needs
!> and stops as soon as the answer is decided.  The orbit is advanced with the
!> existing DOP853 integrator (pendula_integrators%integrate) over short
!> windows, the stop test being applied at samples of each window; a window
!> restarts the integrator from the state where the last one ended (for a
!> driven model the phase is advanced by Omega * t, so the orbit is the same
!> as one long run up to the restart of the step-size control).
!>
!> Thread safety: no module variables; every point works on its own locals.
!> The block loop is an OpenMP parallel do (thread count from OMP_NUM_THREADS).
!> Results never depend on the thread count: each point is computed by one
!> thread, from its own inputs only, in the same order of operations.
!>
!> Measures (codes), outputs per point:
!>   1 final_well:    out(1) = n (well at asin(tau/eps) + 2 pi n), out(2) = time decided
!>   2 mean_velocity: out(1) = <v> after the transient, out(2) = its error bar, out(3) (when
!>                    nout >= 3) = the Shapiro step p / q of a phase-locked driven orbit (NaN
!>                    otherwise); a driven point averages over whole drive periods and a
!>                    locked one reports <v> = p Omega / q exactly (status 6)
!>   3 locked:        out(1) = 1 locked / 0 running, out(2) = time decided
!>   4 poincare:      out(2k-1), out(2k) = theta mod 2 pi in [-pi, pi), v at t = (n_tr + k) T,
!>                    n_tr = ceil(t_tr / T) with each point's own drive period T
!>   5 lyapunov:      out(1) = largest Lyapunov exponent, out(2) = its convergence estimate
!>                    (standard error over 8 blocks), out(3) (when nout >= 3) = the second
!>                    exponent; t_tr = transient, t_max = averaging time, both rounded up to
!>                    whole base periods (pendula_lyapunov)
!> Point status: 0 decided; 1 not settled / not decided by t_max; 2 the
!> measure does not apply to this point (e.g. final_well without damping,
!> no well when |tau| >= eps, poincare without a drive, |theta0| > 2^52);
!> 3 bad measure code; 5 stopped by the cancel flag; 6 phase-locked to the drive (mean_velocity:
!> decided, exact);
!> 100 + s: the integrator failed with status s.
!>
!> The rules every caller applies before a sweep (pendula.sweep, pendula.iv_curve,
!> pendula-run) live in the capability table (pendula_system: which measure
!> honours which field on which model; a scene naming another model is
!> refused, the model named) and here: the limits sweep_max_threads, sweep_max_time and
!> sweep_max_angle (sweep_limits gives them to the Python layer).
module pendula_sweep
  use pendula_kinds, only: dp, pi, two_pi, nan_dp
  use pendula_threads, only: thread_count, max_threads
  use pendula_time_scales, only: n_scales, time_rates
  use pendula_scene, only: scene_t
  use pendula_integrators, only: pendulum_model, event_spec, run_stats, integrate, &
    m_dop853, st_ok, st_cancelled
  use pendula_lyapunov, only: lyapunov_point, ly_cancelled, point_model
  use pendula_stick_slip, only: stick_slip_run, switched
  use pendula_outfile, only: outfile_t, out_line, out_reals
  use pendula_simulate, only: attach_force
  use pendula_system, only: capability_check, cap_ok, cap_not_implemented
  use, intrinsic :: iso_c_binding, only: c_funptr
  use pendula_langevin, only: langevin_stream, langevin_open, langevin_steps, langevin_default_dt, lv_ok, &
    lv_cancelled
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private
  public :: sweep_points, sweep_points_noisy, iv_branch, np_params, sweep_scene_csv, sweep_limits
  public :: advance, forcing_omega, point_rates   ! one window of a point's orbit; the period of its forcing (the attractor finder)
  public :: ms_final_well, ms_mean_velocity, ms_locked, ms_poincare, ms_lyapunov

  !> eps, beta, tau, amp, omega, phase, theta0, v0, then the vibrating pivot's amplitude and frequency,
  !> dry friction mu and quadratic drag gamma
  integer, parameter :: np_params = 12
  integer, parameter :: ms_final_well = 1, ms_mean_velocity = 2, ms_locked = 3, ms_poincare = 4, &
    ms_lyapunov = 5
  integer, parameter :: ps_decided = 0, ps_unsettled = 1, ps_not_applicable = 2, ps_bad_measure = 3, &
    ps_uncertain = 4, ps_cancelled = 5, ps_locked = 6
  !> OpenMP threads of one sweep call: 0 (OpenMP's default) or 1 .. sweep_max_threads;
  !> the kernel clamps anything else into that range (the callers refuse it first)
  integer, parameter, public :: sweep_max_threads = max_threads
  !> the longest t_max and transient a sweep point may be asked for (time units:
  !> about 1.6e7 small-oscillation periods at eps = 1, hours of work per point)
  real(dp), parameter, public :: sweep_max_time = 1.0e8_dp
  !> the largest |theta0| (2^52: beyond it theta0 has no fractional digits and the
  !> well index no meaning)
  real(dp), parameter, public :: sweep_max_angle = 4503599627370496.0_dp
  !> samples per window at which the stop test is applied
  integer, parameter :: nsub = 8

contains

  !> Evaluate measure at npts points.  params(:, i) = eps, beta, tau, amp,
  !> omega, phase, theta0, v0.  t_tr: transient (mean_velocity: time; poincare:
  !> drive periods); t_max: limit (final_well, locked) or averaging time
  !> (mean_velocity).  nout outputs per point (2, or 2 * samples for poincare).
  !> cancel: set non-zero by another thread (Ctrl-C in Python) to stop the
  !> block: every point not finished gets status 5 (ps_cancelled).  It is read
  !> before each point and once per integration window inside a point.
  !> force, fparams (optional): a user's force (pendula_integrators%user_force_fn) added to every
  !> point's force law, called from every thread; final_well and locked do not apply with it.
  subroutine sweep_points(measure, npts, params, rtol, atol, t_tr, t_max, nout, out, pstat, nthreads, cancel, &
                          force, fparams)
    integer, intent(in) :: measure, npts, nout, nthreads
    real(dp), intent(in) :: params(np_params, npts), rtol, atol, t_tr, t_max
    real(dp), intent(out) :: out(nout, npts)
    integer, intent(out) :: pstat(npts)
    integer, intent(inout), volatile :: cancel
    type(c_funptr), intent(in), optional :: force
    real(dp), intent(in), target, contiguous, optional :: fparams(:)
    type(pendulum_model) :: uf
    integer :: i, nt
    if (present(force)) call attach_force(uf, force, fparams)
    nt = thread_count(nthreads)
    !$omp parallel do schedule(dynamic, 16) default(none) num_threads(nt) &
    !$omp   shared(measure, npts, params, rtol, atol, t_tr, t_max, nout, out, pstat, cancel, uf)
    do i = 1, npts
      if (cancel /= 0) then
        out(:, i) = nan_dp; pstat(i) = ps_cancelled
      else
        call one_point(measure, params(:, i), rtol, atol, t_tr, t_max, out(:, i), pstat(i), cancel, uf)
      end if
    end do
    !$omp end parallel do
  end subroutine sweep_points

  !> The limits of sweep_points' arguments, for the Python layer's checks
  !> (one statement of each rule): [max threads, max t_max and transient, max |theta0|].
  pure subroutine sweep_limits(lim)
    real(dp), intent(out) :: lim(3)
    lim = [real(sweep_max_threads, dp), sweep_max_time, sweep_max_angle]
  end subroutine sweep_limits

  subroutine one_point(measure, p, rtol, atol, t_tr, t_max, o, st, cancel, uf)
    integer, intent(in) :: measure
    real(dp), intent(in) :: p(np_params), rtol, atol, t_tr, t_max
    real(dp), intent(out) :: o(:)
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    !> the user's force (uf%forced), if any
    type(pendulum_model), intent(in) :: uf
    real(dp) :: th, v, tdec, vm, err, lam2
    integer :: n
    integer(int64) :: nw
    logical :: settled
    o = nan_dp
    if (.not. (abs(p(7)) <= sweep_max_angle) .or. .not. (t_max <= sweep_max_time) &
        .or. .not. (t_tr <= sweep_max_time)) then
      st = ps_not_applicable; return
    end if
    select case (measure)
    case (ms_final_well)
      if (.not. dissipative(p) .or. p(4) /= 0.0_dp .or. p(9) /= 0.0_dp .or. uf%forced .or. &
          abs(p(3)) >= p(1)) then
        st = ps_not_applicable; return
      end if
      call settle(p, rtol, atol, t_max, p(7), p(8), th, v, settled, nw, tdec, st, cancel)
      if (st /= ps_decided) return
      if (settled) then
        o(1) = real(nw, dp); o(2) = tdec
      else
        st = ps_unsettled; o(2) = t_max
      end if
    case (ms_locked)
      if (.not. dissipative(p) .or. p(4) /= 0.0_dp .or. p(9) /= 0.0_dp .or. uf%forced) then
        st = ps_not_applicable; return
      end if
      if (abs(p(3)) >= p(1)) then
        ! no equilibrium: every orbit runs
        o(1) = 0.0_dp; o(2) = 0.0_dp; st = ps_decided; return
      end if
      call settle(p, rtol, atol, t_max, p(7), p(8), th, v, settled, nw, tdec, st, cancel)
      if (st /= ps_decided) return
      if (settled) then
        o(1) = 1.0_dp; o(2) = tdec
      else if (running(p, rtol, atol, th, v, st, cancel)) then
        o(1) = 0.0_dp; o(2) = t_max
      else if (st == ps_decided) then
        st = ps_unsettled
      end if
    case (ms_mean_velocity)
      call mean_velocity(p, rtol, atol, t_tr, t_max, p(7), p(8), vm, err, lam2, th, v, st, cancel, uf)
      o(1) = vm; o(2) = err
      if (size(o) >= 3) o(3) = lam2
    case (ms_poincare)
      ! the transient is a time: each point skips whole periods of its own drive
      n = 0
      if (forcing_omega(p) > 0.0_dp) then
        vm = real(ceiling(min(t_tr * forcing_omega(p) / two_pi, 1.0e9_dp) - 1.0e-12_dp), dp)
        if (vm > 1.0e8_dp) then
          st = ps_unsettled; return   ! beyond any work a sweep point may take
        end if
        n = int(vm)
      end if
      call poincare(p, rtol, atol, n, size(o) / 2, o, st, cancel, uf)
    case (ms_lyapunov)
      if (size(o) < 2) then
        st = ps_bad_measure; return
      end if
      call lyapunov_point(p, rtol, atol, t_tr, t_max, vm, lam2, err, st, cancel, uf)
      if (st == 2) st = ps_not_applicable
      if (st == ly_cancelled) st = ps_cancelled
      if (st /= ps_decided) return
      o(1) = vm; o(2) = err
      if (size(o) >= 3) o(3) = lam2
    case default
      st = ps_bad_measure
    end select
  end subroutine one_point

  !> Advance (th, v) from time t0 by dt (model time origin shifted by t0).
  !> cancel: read by the integrator every few thousand steps (a window of a
  !> fast orbit may take up to its work limit of 10^8 steps): status ps_cancelled.
  subroutine advance(p, t0, rtol, atol, ts, th, v, ths, vs, st, cancel, uf)
    real(dp), intent(in) :: p(np_params), t0, rtol, atol, ts(:)
    real(dp), intent(inout) :: th, v
    real(dp), intent(out) :: ths(:), vs(:)
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    !> the user's force (optional): its clock runs from the point's t = 0
    type(pendulum_model), intent(in), optional :: uf
    type(pendulum_model) :: m
    type(event_spec) :: ev
    type(run_stats) :: stats
    integer :: nev, s
    real(dp) :: tev(1), thev(1), vev(1), work(4)
    integer(int64) :: nsw
    m = point_model(p, p(6) + p(5) * t0, p(10) * t0, uf, t0)
    if (switched(m)) then
      ! friction, drag: the stretches between the v = 0 events (as simulate)
      call stick_slip_run(m, m_dop853, th, v, ts, rtol, atol, ths, vs, work, nsw, s, cancel)
    else
      call integrate(m, m_dop853, th, v, ts, rtol, atol, 0.0_dp, ths, vs, stats, s, ev, nev, tev, thev, vev, &
                     cancel)
    end if
    if (s == st_cancelled) then
      st = ps_cancelled; return
    end if
    if (s /= st_ok) then
      st = 100 + s; return
    end if
    st = ps_decided
    th = ths(size(ts)); v = vs(size(ts))
  end subroutine advance

  !> The well an undriven damped orbit is trapped in, once its energy
  !> E = v^2/2 - eps cos(theta) - tau theta (non-increasing: dE/dt = -beta v^2)
  !> is below the lower of the two barriers around its current well.
  pure subroutine trapped(p, th, v, yes, n)
    real(dp), intent(in) :: p(np_params), th, v
    logical, intent(out) :: yes
    integer(int64), intent(out) :: n
    real(dp) :: ths, tl, tr, e, ul, ur
    ths = asin(p(3) / p(1))
    ! well n spans (-pi - ths + 2 pi n, pi - ths + 2 pi n) between two maxima of U
    ! 64 bits: |theta| <= 2^52 (sweep_max_angle) gives |n| < 2^50
    n = floor((th + pi + ths) / two_pi, int64)
    tl = -pi - ths + two_pi * n
    tr = tl + two_pi
    e = 0.5_dp * v * v + pot(th)
    ul = pot(tl); ur = pot(tr)
    yes = e < min(ul, ur)
  contains
    pure function pot(x) result(u)
      real(dp), intent(in) :: x
      real(dp) :: u
      u = -p(1) * cos(x) - p(3) * x
    end function pot
  end subroutine trapped

  !> Integrate until trapped (decided) or t_max.
  subroutine settle(p, rtol, atol, t_max, th0, v0, th, v, settled, n, tdec, st, cancel)
    real(dp), intent(in) :: p(np_params), rtol, atol, t_max, th0, v0
    real(dp), intent(out) :: th, v, tdec
    logical, intent(out) :: settled
    integer(int64), intent(out) :: n
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    real(dp) :: t, tw, ts(nsub), ths(nsub), vs(nsub)
    integer :: k
    th = th0; v = v0; t = 0.0_dp; st = ps_decided; tdec = 0.0_dp
    call trapped(p, th, v, settled, n)
    if (settled) return
    tw = two_pi / sqrt(p(1))
    do while (t < t_max)
      if (cancel /= 0) then
        st = ps_cancelled; return
      end if
      ts = [(tw * k / real(nsub, dp), k = 1, nsub)]
      call advance(p, t, rtol, atol, ts, th, v, ths, vs, st, cancel)
      if (st /= ps_decided) return
      do k = 1, nsub
        call trapped(p, ths(k), vs(k), settled, n)
        if (settled) then
          tdec = t + ts(k); th = ths(k); v = vs(k); return
        end if
      end do
      t = t + tw
    end do
  end subroutine settle

  !> An open orbit: over one more window, v keeps its sign and theta advances
  !> by more than 2 pi.
  function running(p, rtol, atol, th, v, st, cancel) result(yes)
    real(dp), intent(in) :: p(np_params), rtol, atol
    real(dp), intent(inout) :: th, v
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    logical :: yes
    real(dp) :: tw, ts(4 * nsub), ths(4 * nsub), vs(4 * nsub), th1
    integer :: k
    tw = 4.0_dp * two_pi / sqrt(p(1))
    ts = [(tw * k / real(4 * nsub, dp), k = 1, 4 * nsub)]
    th1 = th
    call advance(p, 0.0_dp, rtol, atol, ts, th, v, ths, vs, st, cancel)
    yes = .false.
    if (st /= ps_decided) return
    yes = (all(vs > 0.0_dp) .or. all(vs < 0.0_dp)) .and. abs(ths(size(ts)) - th1) > two_pi
  end function running

  !> <v> over t_avg after a transient t_tr, from (th0, v0).  A driven orbit
  !> (A /= 0, Omega > 0): mean_velocity_driven (whole drive periods, phase
  !> locking detected).  Otherwise the window is t_avg after t_tr and the error
  !> bar err = max(|<v> - <v>_second half|, the windowing bound w) with
  !> w = min(2 pi (v_max - v_min) / (|<v>| t_avg), (theta_max - theta_min) / t_avg):
  !> for a running periodic orbit theta - <v> t has period 2 pi / |<v>| and
  !> oscillates by at most (v_max - v_min) pi / |<v>| (half of it, doubled for
  !> extrema between the 8 samples per window); a bounded one cannot move the
  !> mean by more than its range.  An undriven damped orbit trapped in a well
  !> has <v> = 0 exactly: decided as soon as it is trapped.
  !> step: the Shapiro step p / q of a phase-locked driven orbit, NaN otherwise;
  !> st = ps_locked then (<v> = p Omega / q exactly, err = 0).
  subroutine mean_velocity(p, rtol, atol, t_tr, t_avg, th0, v0, vm, err, step, th, v, st, cancel, uf)
    real(dp), intent(in) :: p(np_params), rtol, atol, t_tr, t_avg, th0, v0
    real(dp), intent(out) :: vm, err, step, th, v
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    type(pendulum_model), intent(in), optional :: uf
    real(dp) :: t, tw, ts(nsub), ths(nsub), vs(nsub), tha, thh, seg_end(3), h, vlo, vhi, tlo, thi
    integer(int64) :: n
    integer :: seg, k
    logical :: can_trap, tr
    step = nan_dp
    ! whole drive periods where the drive sets the period (a pivot, if any, at the same frequency)
    if (p(4) /= 0.0_dp .and. p(5) > 0.0_dp .and. forcing_omega(p) == p(5)) then
      call mean_velocity_driven(p, rtol, atol, t_tr, t_avg, th0, v0, vm, err, step, th, v, st, cancel, uf)
      return
    end if
    th = th0; v = v0; t = 0.0_dp; st = ps_decided
    vm = nan_dp; err = nan_dp
    can_trap = dissipative(p) .and. p(4) == 0.0_dp .and. p(9) == 0.0_dp .and. abs(p(3)) < p(1)
    if (present(uf)) can_trap = can_trap .and. .not. uf%forced
    tw = two_pi / sqrt(p(1))
    seg_end = [t_tr, t_tr + 0.5_dp * t_avg, t_tr + t_avg]
    ! a window below the resolution of the transient (t_tr + t_avg / 2 == t_tr) would give
    ! <v> = 0 or NaN as if decided: the measure does not apply
    if (.not. (seg_end(1) < seg_end(2) .and. seg_end(2) < seg_end(3))) then
      st = ps_not_applicable; return
    end if
    tha = th; thh = th
    vlo = huge(1.0_dp); vhi = -huge(1.0_dp); tlo = huge(1.0_dp); thi = -huge(1.0_dp)
    do seg = 1, 3
      do while (t < seg_end(seg))
        if (cancel /= 0) then
          st = ps_cancelled; return
        end if
        if (can_trap) then
          call trapped(p, th, v, tr, n)
          if (tr) then
            vm = 0.0_dp; err = 0.0_dp; return
          end if
        end if
        h = min(tw, seg_end(seg) - t)
        ts = [(h * k / real(nsub, dp), k = 1, nsub)]
        ts(nsub) = h
        call advance(p, t, rtol, atol, ts, th, v, ths, vs, st, cancel, uf)
        if (st /= ps_decided) return
        if (seg > 1) then
          vlo = min(vlo, minval(vs)); vhi = max(vhi, maxval(vs))
          tlo = min(tlo, minval(ths)); thi = max(thi, maxval(ths))
        end if
        ! the segment ends exactly at seg_end, whatever the rounding of the sum
        if (h == seg_end(seg) - t) then
          t = seg_end(seg)
        else
          t = t + h
        end if
      end do
      if (seg == 1) tha = th
      if (seg == 2) thh = th
    end do
    vm = (th - tha) / t_avg
    h = (thi - tlo) / t_avg
    if (vm /= 0.0_dp) h = min(h, two_pi * (vhi - vlo) / (abs(vm) * t_avg))
    err = max(abs(vm - (th - thh) / (0.5_dp * t_avg)), h)
  end subroutine mean_velocity

  !> Does the point lose energy whenever it moves (damping, friction or drag)?  Then an undriven
  !> orbit whose energy is below the barriers of its well stays in it (trapped).
  pure logical function dissipative(p)
    real(dp), intent(in) :: p(np_params)
    dissipative = p(2) > 0.0_dp .or. p(11) > 0.0_dp .or. p(12) > 0.0_dp
  end function dissipative

  !> The angular frequency of the periodic forcing (the stroboscopic map's): the drive's, or
  !> the vibrating pivot's when there is no drive; 0 when the two differ (no common period here).
  !> A sweep point's time-scale rates (pendula_time_scales; sweeps run the rigid pendulum in the uniform field).
  pure function point_rates(p) result(r)
    real(dp), intent(in) :: p(np_params)
    real(dp) :: r(n_scales)
    r = time_rates(p(1), p(2), p(3), p(4), p(5), p(9), p(10), 0, 0.0_dp, p(11), p(12), p(8))
  end function point_rates

  pure real(dp) function forcing_omega(p)
    real(dp), intent(in) :: p(np_params)
    forcing_omega = p(5)
    if (p(9) /= 0.0_dp) then
      if (p(4) == 0.0_dp .or. p(5) == p(10)) then
        forcing_omega = p(10)
      else
        forcing_omega = 0.0_dp
      end if
    end if
  end function forcing_omega
  !> <v> of a driven orbit over whole drive periods T = 2 pi / Omega: the
  !> stroboscopic map (one period from drive phase p(6), theta reduced to
  !> [-pi, pi] and its turns counted) is iterated ceil(t_tr / T) periods of
  !> transient, then an even number of periods covering t_avg (at least 2).
  !> Phase locking: when the map returns to a state q periods back (q <= 8)
  !> with theta advanced by 2 pi p, the orbit is on a periodic orbit of the
  !> map and <v> = p Omega / q exactly (the rotation number of a periodic
  !> orbit); detected when the distance d = max(|d theta|, |d v|) between the
  !> two states is at the rounding level (1e-12 (1 + |v|)), or below 1e-7 and
  !> shrinking geometrically (the ratio r of successive distances below 1
  !> twice running, with d r / (1 - r) <= 1e-7: the rest of the convergence).
  !> A slow passage near a lost locking (a saddle-node ghost of width mu)
  !> shrinks with a ratio near 1: d r / (1 - r) >= sqrt(mu) there, so only a
  !> ghost with mu <= 1e-14 (one phase slip per more than 1e7 periods) could
  !> pass for locking.
  !> Otherwise err = max(|<v> - <v>_second half|, the spread of theta_k - <v> t_k
  !> over the stroboscopic samples of the window / the window): a quasi-periodic
  !> orbit's discrepancy is bounded, and the window's mean is within that
  !> spread / window of its rotation number.
  !> Locked means found: a window that ends unlocked but whose mean is within
  !> its error bar of a step p Omega / q (q <= 8) with err <= Omega / (2 qmax^2)
  !> (the window cannot tell the orbit from a locked one: a slow convergence,
  !> next to a period doubling or a saddle-node, not finished), or whose last
  !> return to the state q periods back is closer than 1e-3 (1 + |v|) (a
  !> chaotic transient that has settled onto a periodic orbit), is followed by
  !> a window twice as long from where it ended, the locking detection going
  !> on, until the map locks, the error bar falls below the distance to the
  !> nearest step (decided off the steps), or the windows reach 63 times the
  !> first (ext_windows; then the last window's mean and error bar, status
  !> decided); a mean within its error bar of a whole step n Omega with an
  !> error bar up to Omega / 8 (a slow passage next to a step's edge), or an
  !> error bar above Omega / 8 (a chaotic transient, or chaos: the error bar
  !> falls below its target or the windows end), runs on the same way up to
  !> 7 first windows.  vm and err are the last window's.  A window of 500 periods or
  !> more whose stroboscopic phase theta_k - (p / q) Omega t_k stayed within a
  !> band narrower than pi (a phase slip moves it by 2 pi) is locked to p / q
  !> too (status 6, <v> = p Omega / q, err = 0): a bounded phase, a locked
  !> orbit of period above 8 or phase-locked chaos; a saddle-node ghost
  !> slipping less often than once per window could pass (within about
  !> (pi / 500)^2 of the edge in the map's parameter).
  subroutine mean_velocity_driven(p, rtol, atol, t_tr, t_avg, th0, v0, vm, err, step, th, v, st, cancel, uf)
    real(dp), intent(in) :: p(np_params), rtol, atol, t_tr, t_avg, th0, v0
    real(dp), intent(out) :: vm, err, step, th, v
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    !> a user's force (optional): its clock is the point's time, period k starting at (k - 1) T
    type(pendulum_model), intent(in), optional :: uf
    integer, parameter :: qmax = 8, nkeep = 8192
    real(dp), parameter :: lock_tol = 1.0e-7_dp, max_periods = 1.0e9_dp
    !> the longest the windows may run, in first windows (1 + 2 + ... + 32)
    integer(int64), parameter :: ext_windows = 63
    !> a window this long (periods) without a phase slip off a step's line is locked to it
    integer(int64), parameter :: bound_periods = 500
    !> a return to within this of the state q periods back at the window's end: the map is closing in
    real(dp), parameter :: closing_tol = 1.0e-3_dp
    real(dp) :: tp, ts(1), ths(1), vs(1), sth(0:qmax), sv(0:qmax), dprev(qmax), rprev(qmax), d, dth, r, x, &
                tha, thh, rs(0:nkeep), lo, hi, y
    integer(int64) :: sw(0:qmax), w, wa, wh, k, n_tr, n_avg, stride, turns, n0, n_end, n_lim, n_short
    integer :: q, j, nr
    vm = nan_dp; err = nan_dp; step = nan_dp
    th = th0; v = v0; st = ps_decided
    tp = two_pi / p(5)
    x = real(ceiling(min(t_tr / tp, max_periods) - 1.0e-12_dp), dp)
    r = 2.0_dp * real(ceiling(min(t_avg / tp, max_periods) * 0.5_dp - 1.0e-12_dp), dp)
    if (.not. (x + max(r, 2.0_dp) <= max_periods)) then
      st = ps_unsettled; return   ! beyond any work a sweep point may take
    end if
    n_tr = max(0_int64, int(x, int64)); n_avg = max(2_int64, int(r, int64))
    stride = max(1_int64, (n_avg + nkeep - 1) / nkeep)
    w = nint(th / two_pi, int64); th = th - two_pi * real(w, dp)
    sth = 0.0_dp; sv = 0.0_dp; sw = 0; dprev = huge(1.0_dp); rprev = huge(1.0_dp)
    sth(0) = th; sv(0) = v; sw(0) = w
    wa = w; tha = th; wh = w; thh = th; nr = 0
    if (n_tr == 0) then
      rs(0) = 0.0_dp
    end if
    ts(1) = tp
    n0 = n_tr; n_end = n_tr + n_avg; n_lim = min(n_tr + ext_windows * n_avg, int(max_periods, int64))
    n_short = min(n_tr + 7_int64 * n_avg, n_lim)
    k = 0
    do
      k = k + 1
      if (cancel /= 0) then
        st = ps_cancelled; return
      end if
      ! the same map every period: time origin at the drive phase p(6)
      if (present(uf)) then
        call advance(p, real(k - 1, dp) * tp, rtol, atol, ts, th, v, ths, vs, st, cancel, uf)
      else
        call advance(p, 0.0_dp, rtol, atol, ts, th, v, ths, vs, st, cancel)
      end if
      if (st /= ps_decided) return
      turns = nint(th / two_pi, int64)
      w = w + turns; th = th - two_pi * real(turns, dp)
      ! locking: the state q periods back (the smallest q that repeats)
      do q = 1, int(min(int(qmax, int64), k))
        j = int(mod(k - q, int(qmax + 1, int64)))
        dth = th - sth(j)
        turns = nint(dth / two_pi, int64)
        dth = dth - two_pi * real(turns, dp)
        d = max(abs(dth), abs(v - sv(j)))
        r = d / dprev(q)
        if (d <= 1.0e-12_dp * (1.0_dp + abs(v)) .or. &
            (d <= lock_tol .and. r < 1.0_dp .and. rprev(q) < 1.0_dp .and. &
             d * r <= lock_tol * (1.0_dp - r))) then
          turns = w - sw(j) + turns
          vm = real(turns, dp) * p(5) / real(q, dp)
          step = real(turns, dp) / real(q, dp)
          err = 0.0_dp; st = ps_locked
          return
        end if
        dprev(q) = d; rprev(q) = r
      end do
      j = int(mod(k, int(qmax + 1, int64)))
      sth(j) = th; sv(j) = v; sw(j) = w
      if (k == n0) then
        wa = w; tha = th; rs(0) = 0.0_dp
      end if
      if (k == n0 + n_avg / 2) then
        wh = w; thh = th
      end if
      if (k > n0 .and. mod(k - n0, stride) == 0) then
        nr = int((k - n0) / stride)
        rs(nr) = two_pi * real(w - wa, dp) + (th - tha)
      end if
      if (k < n_end) cycle
      ! the window's mean and error bar
      vm = (two_pi * real(w - wa, dp) + (th - tha)) / (real(n_avg, dp) * tp)
      err = abs(vm - (two_pi * real(w - wh, dp) + (th - thh)) / (real(n_avg / 2, dp) * tp))
      lo = 0.0_dp; hi = 0.0_dp
      do j = 1, nr
        x = rs(j) - vm * real(j, dp) * real(stride, dp) * tp
        lo = min(lo, x); hi = max(hi, x)
      end do
      err = max(err, (hi - lo) / (real(n_avg, dp) * tp))
      ! a window of bound_periods or more in which the phase kept within pi of the step's line: no slip
      if (n_avg >= bound_periods .and. bounded_on_step(vm, err, p(5), y)) then
        vm = y * p(5); step = y; err = 0.0_dp; st = ps_locked
        return
      end if
      ! not locked yet: a longer window from here while the mean may be on a step
      ! (or while the map is closing in on a periodic orbit: a chaotic transient that has settled);
      ! a mean near an integer step with a coarser error bar (Omega / 8), or an error bar above Omega / 8
      ! (a chaotic transient after the bias moved, or chaos), runs on up to 7 first windows
      if (.not. (((near_step(vm, err, p(5)) .or. minval(dprev) <= closing_tol * (1.0_dp + abs(v))) .and. &
                  n_end + 2_int64 * n_avg <= n_lim) .or. &
                 ((near_whole_step(vm, err, p(5)) .or. .not. err <= 0.125_dp * p(5)) .and. &
                  n_end + 2_int64 * n_avg <= n_short))) exit
      n0 = k; n_avg = 2_int64 * n_avg; n_end = k + n_avg
      stride = max(1_int64, (n_avg + nkeep - 1) / nkeep)
      wa = w; tha = th; rs(0) = 0.0_dp; nr = 0
    end do
  contains
    !> Did the window's stroboscopic phase stay within a band narrower than pi about the line of the
    !> step p / q that its mean is within its error bar of (q <= qmax, the smallest)?  y = p / q then.
    logical function bounded_on_step(vm, err, omega, y)
      real(dp), intent(in) :: vm, err, omega
      real(dp), intent(out) :: y
      real(dp) :: z, lo, hi, x
      integer :: q, j
      bounded_on_step = .false.; y = nan_dp
      if (.not. near_step(vm, err, omega)) return
      do q = 1, qmax
        z = vm * real(q, dp) / omega
        if (abs(z - anint(z)) * omega / real(q, dp) <= err) exit
      end do
      y = anint(z) / real(q, dp)
      lo = 0.0_dp; hi = 0.0_dp
      do j = 1, nr
        x = rs(j) - y * omega * real(j, dp) * real(stride, dp) * tp
        lo = min(lo, x); hi = max(hi, x)
      end do
      bounded_on_step = hi - lo < pi
    end function bounded_on_step
    !> Is the window's mean within its error bar of a whole step n Omega, with an error bar below Omega / 8?
    pure logical function near_whole_step(vm, err, omega)
      real(dp), intent(in) :: vm, err, omega
      near_whole_step = err <= 0.125_dp * omega .and. abs(vm - anint(vm / omega) * omega) <= err
    end function near_whole_step
    !> Is the window's mean within its error bar of a step p Omega / q (q <= qmax), with an error bar
    !> that resolves the steps of q <= qmax (err <= Omega / (2 qmax^2))?
    pure logical function near_step(vm, err, omega)
      real(dp), intent(in) :: vm, err, omega
      real(dp) :: y
      integer :: q
      near_step = .false.
      if (.not. (err <= omega / (2.0_dp * qmax * qmax))) return
      do q = 1, qmax
        y = vm * real(q, dp) / omega
        if (abs(y - anint(y)) * omega / real(q, dp) <= err) then
          near_step = .true.; return
        end if
      end do
    end function near_step
  end subroutine mean_velocity_driven

  !> <v> of an orbit with thermal noise at temperature temp (stream s): BAOAB
  !> steps of h <= dt (dt <= 0: langevin_default_dt).  A driven orbit: h
  !> divides the drive period, transient and window are whole periods (at
  !> least ceil(t_tr / T) and ceil(t_avg / T)).  Otherwise ceil(t_tr / h) and
  !> ceil(t_avg / h) steps of h = dt.  err: the standard error of <v> from
  !> the spread of up to 16 batch means of the window (batches of whole
  !> periods when driven).
  subroutine mean_velocity_noisy(p, temp, s, dt, t_tr, t_avg, th0, v0, vm, err, th, v, st, cancel)
    real(dp), intent(in) :: p(np_params), temp, dt, t_tr, t_avg, th0, v0
    type(langevin_stream), intent(inout) :: s
    real(dp), intent(out) :: vm, err, th, v
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    integer, parameter :: nbatch_max = 16
    type(pendulum_model) :: m
    real(dp) :: h, tp, thb, bv(nbatch_max), tha
    integer(int64) :: per, ntr, navg, k, nb, b, kb_end, nchunk
    logical :: driven
    vm = nan_dp; err = nan_dp; th = th0; v = v0; st = ps_decided
    m = point_model(p, p(6), 0.0_dp)
    driven = p(4) /= 0.0_dp .and. p(5) > 0.0_dp
    h = dt
    if (.not. (h > 0.0_dp)) h = langevin_default_dt(point_rates(p))
    if (driven) then
      tp = two_pi / p(5)
      per = max(1_int64, ceiling(tp / h - 1.0e-12_dp, int64))
      h = tp / real(per, dp)
    else
      per = 4096
    end if
    ! chunks of per steps: the transient's and the window's
    if (.not. ((t_tr + t_avg) / h <= 2.0e9_dp)) then
      st = ps_unsettled; return   ! beyond the work a point may take
    end if
    ntr = ceiling(t_tr / (h * real(per, dp)) - 1.0e-12_dp, int64)
    navg = max(1_int64, ceiling(t_avg / (h * real(per, dp)) - 1.0e-12_dp, int64))
    if (.not. driven) navg = max(1_int64, ceiling(t_avg / h - 1.0e-12_dp, int64))
    do k = 1, ntr
      call chunk(per)
      if (st /= ps_decided) return
    end do
    tha = th
    if (driven) then
      nb = min(int(nbatch_max, int64), navg)
      do b = 1, nb
        thb = th
        do k = (b - 1) * navg / nb + 1, b * navg / nb
          call chunk(per)
          if (st /= ps_decided) return
        end do
        bv(b) = (th - thb) / (real(b * navg / nb - (b - 1) * navg / nb, dp) * real(per, dp) * h)
      end do
      vm = (th - tha) / (real(navg, dp) * real(per, dp) * h)
    else
      ! navg steps in nb batches, each in chunks of at most per steps
      nb = min(int(nbatch_max, int64), navg)
      do b = 1, nb
        thb = th
        kb_end = b * navg / nb - (b - 1) * navg / nb
        do while (kb_end > 0)
          nchunk = min(per, kb_end)
          call chunk(nchunk)
          if (st /= ps_decided) return
          kb_end = kb_end - nchunk
        end do
        bv(b) = (th - thb) / (real(b * navg / nb - (b - 1) * navg / nb, dp) * h)
      end do
      vm = (th - tha) / (real(navg, dp) * h)
    end if
    err = 0.0_dp
    if (nb > 1) err = sqrt(sum((bv(1:nb) - sum(bv(1:nb)) / real(nb, dp)) ** 2) / real(nb - 1, dp) / real(nb, dp))
  contains
    subroutine chunk(n)
      integer(int64), intent(in) :: n
      integer :: ls
      if (cancel /= 0) then
        st = ps_cancelled; return
      end if
      ! a driven chunk is one period from the drive's phase p(6): time origin 0
      call langevin_steps(m, temp, s, 0.0_dp, h, n, th, v, ls, cancel)
      if (ls == lv_cancelled) then
        st = ps_cancelled
      else if (ls /= lv_ok) then
        st = 106   ! the integrator's non-finite state
      end if
    end subroutine chunk
  end subroutine mean_velocity_noisy

  !> sweep_points for the measure mean_velocity with thermal noise (temp > 0,
  !> the damping of every point > 0): point i runs the stream (seed,
  !> first + i - 1), its global index in the grid, so the result of a point
  !> does not depend on the block or the thread that computes it.  dt: the
  !> Langevin step (<= 0: langevin_default_dt).  out(:, i) = <v>, its
  !> standard error, NaN (no Shapiro step under noise).
  subroutine sweep_points_noisy(npts, params, temp, seed, first, dt, t_tr, t_max, out, pstat, nthreads, cancel)
    integer, intent(in) :: npts, nthreads
    real(dp), intent(in) :: params(np_params, npts), temp, dt, t_tr, t_max
    integer(int64), intent(in) :: seed, first
    real(dp), intent(out) :: out(3, npts)
    integer, intent(out) :: pstat(npts)
    integer, intent(inout), volatile :: cancel
    integer :: i, nt
    type(langevin_stream) :: s
    real(dp) :: th, v
    nt = thread_count(nthreads)
    !$omp parallel do schedule(dynamic, 4) default(none) num_threads(nt) &
    !$omp   shared(npts, params, temp, seed, first, dt, t_tr, t_max, out, pstat, cancel) private(i, s, th, v)
    do i = 1, npts
      out(:, i) = nan_dp
      if (cancel /= 0) then
        pstat(i) = ps_cancelled
      else if (.not. (params(2, i) > 0.0_dp) .or. .not. (t_max <= sweep_max_time) .or. &
               .not. (t_tr <= sweep_max_time) .or. .not. (abs(params(7, i)) <= sweep_max_angle)) then
        pstat(i) = ps_not_applicable
      else
        s = langevin_open(seed, first + i - 1)
        call mean_velocity_noisy(params(:, i), temp, s, dt, t_tr, t_max, params(7, i), params(8, i), out(1, i), &
                                 out(2, i), th, v, pstat(i), cancel)
      end if
    end do
    !$omp end parallel do
  end subroutine sweep_points_noisy

  !> Stroboscopic samples once per drive period after n_tr periods.
  subroutine poincare(p, rtol, atol, n_tr, ns, o, st, cancel, uf)
    real(dp), intent(in) :: p(np_params), rtol, atol
    integer, intent(in) :: n_tr, ns
    real(dp), intent(out) :: o(:)
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    type(pendulum_model), intent(in), optional :: uf
    real(dp) :: tp, t, th, v, ts(1), ths(1), vs(1)
    integer :: k
    o = nan_dp
    if (.not. (forcing_omega(p) > 0.0_dp)) then
      st = ps_not_applicable; return
    end if
    tp = two_pi / forcing_omega(p)
    th = p(7); v = p(8); t = 0.0_dp; st = ps_decided
    ts(1) = tp
    do k = 1, n_tr + ns
      if (cancel /= 0) then
        o = nan_dp; st = ps_cancelled; return
      end if
      ! time origin at k tp exactly: the drive phase is p(6) + Omega * (k-1) tp
      call advance(p, tp * (k - 1), rtol, atol, ts, th, v, ths, vs, st, cancel, uf)
      if (st /= ps_decided) return
      th = th - two_pi * anint(th / two_pi)   ! keep theta small; the force is 2 pi periodic
      if (k > n_tr) then
        o(2 * (k - n_tr) - 1) = th
        if (th >= pi) o(2 * (k - n_tr) - 1) = th - two_pi
        o(2 * (k - n_tr)) = v
      end if
    end do
  end subroutine poincare

  !> One adiabatic I-V branch: for each torque in turn, the mean velocity
  !> after t_tr over t_avg, starting from the end state of the previous torque
  !> (the first from theta0, v0 in params).  params(3) (tau) is overridden.
  !> th, v: the end state (theta reduced to [-pi, pi]), to start another branch.
  !> temp > 0: thermal noise (mean_velocity_noisy), torque k on the stream
  !> (seed, first + k - 1), Langevin step dt (<= 0: the default).
  subroutine iv_branch(params, ntau, taus, rtol, atol, t_tr, t_avg, temp, seed, first, dt, vm, err, step, pstat, &
                       th, v, cancel)
    integer, intent(in) :: ntau
    real(dp), intent(in) :: params(np_params), taus(ntau), rtol, atol, t_tr, t_avg, temp, dt
    integer(int64), intent(in) :: seed, first
    real(dp), intent(out) :: vm(ntau), err(ntau), step(ntau), th, v
    integer, intent(out) :: pstat(ntau)
    integer, intent(inout), volatile :: cancel
    real(dp) :: p(np_params)
    integer :: k
    type(langevin_stream) :: s
    p = params
    th = p(7); v = p(8)
    vm = nan_dp; err = nan_dp; step = nan_dp; pstat = ps_unsettled
    do k = 1, ntau
      ! a locked undriven state follows its equilibrium (the limit of a slow
      ! ramp: a sudden torque step would kick it over a shallow barrier); a
      ! driven one carries its state on, at a whole drive period
      if (k > 1 .and. abs(taus(k)) <= p(1) .and. .not. (p(4) /= 0.0_dp .and. p(5) > 0.0_dp)) then
        if (vm(k - 1) == 0.0_dp .and. abs(p(3)) <= p(1)) then
          th = asin(taus(k) / p(1)) + two_pi * anint((th - asin(p(3) / p(1))) / two_pi); v = 0.0_dp
        end if
      end if
      p(3) = taus(k)
      p(7) = th - two_pi * anint(th / two_pi); p(8) = v
      if (temp > 0.0_dp) then
        s = langevin_open(seed, first + k - 1)
        call mean_velocity_noisy(p, temp, s, dt, t_tr, t_avg, p(7), p(8), vm(k), err(k), th, v, pstat(k), cancel)
      else
        call mean_velocity(p, rtol, atol, t_tr, t_avg, p(7), p(8), vm(k), err(k), step(k), th, v, pstat(k), cancel)
      end if
      if (pstat(k) /= ps_decided .and. pstat(k) /= ps_locked) exit
    end do
    th = th - two_pi * anint(th / two_pi)
  end subroutine iv_branch

  !> A sweep scene (grid + measure) as CSV through the checked writer f
  !> (pendula_outfile: every write error seen): one row per grid point
  !> (poincare: per sample) with the axis values, the outputs and the status,
  !> in the order of pendula.sweep (first axis slowest).  Blocks of whole rows
  !> of the first axis are computed (OpenMP) and written as they finish, so
  !> memory stays bounded.  final_well and locked: the boundary recheck of
  !> pendula.sweep (boundary_recheck), with the row after each block computed
  !> ahead so that neighbours across block edges are seen; the answers are
  !> those of pendula.sweep whatever its chunks.
  !> status: 0 ok, 2 bad scene for a sweep (a field the measure does not honour: the capability
  !> table), 3 the scene's model is not one a sweep runs, 5 write error (f%err holds errno).
  subroutine sweep_scene_csv(sc, f, status, msg)
    type(scene_t), intent(in) :: sc
    type(outfile_t), intent(inout) :: f
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    integer, parameter :: block = 4096
    real(dp), allocatable :: ax(:, :), params(:, :), o(:, :), ans(:), prev(:)
    integer, allocatable :: pst(:)
    integer :: n(3), k, j, nout, measure, idx(3), inner, rb, r0, r1, rl, nrow, c0, i, s
    real(dp) :: base(np_params), t_tr, a, b, step
    logical :: recheck, have_next
    character(len=256) :: head
    integer, volatile :: no_cancel
    status = 0; msg = ''
    no_cancel = 0
    if (.not. (sc%sweep_t_max <= sweep_max_time) .or. .not. (sc%sweep_transient <= sweep_max_time)) then
      status = 2
      write(msg, '(a, es8.1, a)') 'fields ''sweep_t_max'' and ''sweep_transient'' must be at most ', &
        sweep_max_time, ' (the work of one sweep point is bounded)'
      return
    end if
    select case (trim(sc%measure))
    case ('final_well'); measure = ms_final_well
    case ('mean_velocity'); measure = ms_mean_velocity
    case ('locked'); measure = ms_locked
    case ('poincare'); measure = ms_poincare
    case ('lyapunov'); measure = ms_lyapunov
    case default
      status = 2; msg = 'field ''measure'' must name a measure for a sweep'; return
    end select
    ! the capability table: the fields this measure honours on the scene's model, the grid's axes counted on
    head = ''
    do k = 1, sc%n_grid
      head = trim(head) // ' ' // trim(sc%grid(k))
    end do
    call capability_check(sc, 'sweep:' // trim(sc%measure), head, .false., status, msg)
    if (status == cap_not_implemented) then
      status = 3; return
    else if (status /= cap_ok) then
      status = 2; return
    end if
    n = 1
    n(1:sc%n_grid) = sc%grid_n(1:sc%n_grid)
    allocate(ax(maxval(n), 3))
    ax = 0.0_dp
    do k = 1, sc%n_grid
      if (sc%grid_values(1, k) == sc%grid_values(1, k)) then
        ax(1:n(k), k) = sc%grid_values(1:n(k), k)
      else
        ! as numpy.linspace: start + j * ((stop - start) / (count - 1)), the last one stop
        a = sc%grid_range(1, k); b = sc%grid_range(2, k)
        step = 0.0_dp
        if (n(k) > 1) step = (b - a) / real(n(k) - 1, dp)
        do j = 1, n(k)
          ax(j, k) = real(j - 1, dp) * step + a
        end do
        if (n(k) > 1) ax(n(k), k) = b
      end if
    end do
    base = [sc%eps, sc%damping, sc%torque, sc%drive_amplitude, sc%drive_frequency, sc%drive_phase, &
            sc%theta0, sc%v0, sc%pivot_amplitude, sc%pivot_frequency, sc%friction, sc%drag]
    do k = 0, sc%n_grid
      if (k > 0) then
        if (trim(sc%grid(k)) /= 'theta0') cycle
        a = maxval(abs(ax(1:n(k), k)))
      else
        a = abs(sc%theta0)
      end if
      if (.not. (a <= sweep_max_angle)) then
        status = 2; msg = 'field ''theta0'': |theta0| must be at most 2^52 in a sweep'; return
      end if
    end do
    nout = 2
    t_tr = sc%sweep_transient
    if (measure == ms_poincare) then
      if (.not. (sc%drive_frequency > 0.0_dp) .and. .not. any(sc%grid(1:sc%n_grid) == 'drive_frequency') .and. &
          sc%pivot_amplitude == 0.0_dp) then
        status = 2; msg = 'measure ''poincare'' needs a drive (drive_frequency > 0)'; return
      end if
      nout = 2 * sc%sweep_samples
    end if
    if (measure == ms_lyapunov .or. measure == ms_mean_velocity) nout = 3
    recheck = measure == ms_final_well .or. measure == ms_locked
    head = ''
    do k = 1, sc%n_grid
      head = trim(head) // trim(sc%grid(k)) // ','
    end do
    select case (measure)
    case (ms_final_well); head = trim(head) // 'well,t_decided,status'
    case (ms_locked); head = trim(head) // 'locked,t_decided,status'
    case (ms_mean_velocity); head = trim(head) // 'mean_velocity,mean_velocity_err,step,status'
    case (ms_poincare); head = trim(head) // 'sample,theta,v,status'
    case (ms_lyapunov); head = trim(head) // 'lyapunov,lyapunov_err,lyapunov2,status'
    end select
    call out_line(f, '# pendula-run sweep: measure = ' // trim(sc%measure) // &
      '; status 0 decided, 1 not settled by sweep_t_max, 2 measure does not apply, ' // &
      '4 uncertain (a basin-boundary answer that changes at 1000 times tighter tolerances), ' // &
      '6 locked (phase-locked to the drive: mean_velocity = step * drive_frequency exactly)')
    call out_line(f, trim(head))
    inner = n(2) * n(3)
    rb = max(1, block / inner)
    ! rows r0 .. r1 of the first axis per block, plus one row ahead (rechecks)
    allocate(params(np_params, (rb + 1) * inner), o(nout, (rb + 1) * inner), pst((rb + 1) * inner))
    allocate(ans((rb + 2) * inner), prev(inner))
    have_next = .false.
    r0 = 1
    do while (r0 <= n(1))
      r1 = min(n(1), r0 + rb - 1)
      rl = r1
      if (recheck) rl = min(n(1), r1 + 1)
      nrow = rl - r0 + 1
      do i = 1, nrow * inner
        call unflatten((r0 - 1) * inner + i - 1, idx)
        params(:, i) = base
        do k = 1, sc%n_grid
          params(slot(sc%grid(k)), i) = ax(idx(k), k)
        end do
      end do
      ! the first row was computed ahead by the previous block: moved, not recomputed
      c0 = 1
      if (have_next) c0 = inner + 1
      if (c0 <= nrow * inner .and. sc%noise > 0.0_dp) then
        ! thermal noise: grid point k (flat, from 0) on the stream (seed, k), as pendula.sweep
        call sweep_points_noisy(nrow * inner - c0 + 1, params(:, c0:nrow * inner), sc%noise, sc%seed, &
                                int((r0 - 1) * inner + c0 - 1, int64), sc%dt, t_tr, sc%sweep_t_max, &
                                o(:, c0:nrow * inner), pst(c0:nrow * inner), 0, no_cancel)
      else if (c0 <= nrow * inner) then
        call sweep_points(measure, nrow * inner - c0 + 1, params(:, c0:nrow * inner), sc%rtol, sc%atol, &
                          t_tr, sc%sweep_t_max, nout, o(:, c0:nrow * inner), pst(c0:nrow * inner), 0, no_cancel)
      end if
      if (recheck) then
        ! answers of the previous row, this block's rows and the row ahead (first pass)
        if (r0 > 1) ans(1:inner) = prev
        do i = 1, nrow * inner
          ans(inner + i) = answer(o(1, i), pst(i))
        end do
        call boundary_recheck(measure, n, r0, r1, rl, inner, params, sc%rtol, sc%atol, t_tr, sc%sweep_t_max, &
                              nout, ans, o, pst)
        prev = ans((r1 - r0 + 1) * inner + 1:(r1 - r0 + 2) * inner)
      end if
      do i = 1, (r1 - r0 + 1) * inner
        call unflatten((r0 - 1) * inner + i - 1, idx)
        if (measure == ms_poincare) then
          do s = 1, nout / 2
            call out_line(f, axes_text(idx) // ',' // int_text(s - 1) // ',' // &
              out_reals(o(2 * s - 1:2 * s, i)) // ',' // int_text(pst(i)))
          end do
        else
          call out_line(f, axes_text(idx) // ',' // out_reals(o(:, i)) // ',' // int_text(pst(i)))
        end if
      end do
      if (f%err /= 0) then
        ! a full disk: stop computing what cannot be written
        status = 5; write(msg, '(a, i0, a)') 'write error (errno ', f%err, ')'; return
      end if
      have_next = rl > r1
      if (have_next) then
        o(:, 1:inner) = o(:, (r1 - r0 + 1) * inner + 1:(r1 - r0 + 2) * inner)
        pst(1:inner) = pst((r1 - r0 + 1) * inner + 1:(r1 - r0 + 2) * inner)
      end if
      r0 = r1 + 1
    end do

  contains

    !> flat index (0-based, first axis slowest) -> 1-based axis indices
    subroutine unflatten(fl, id)
      integer, intent(in) :: fl
      integer, intent(out) :: id(3)
      id(3) = mod(fl, n(3)) + 1
      id(2) = mod(fl / n(3), n(2)) + 1
      id(1) = fl / (n(3) * n(2)) + 1
    end subroutine unflatten

    function axes_text(id) result(t)
      integer, intent(in) :: id(3)
      character(len=:), allocatable :: t
      integer :: kk
      t = out_reals([(ax(id(kk), kk), kk = 1, sc%n_grid)])
    end function axes_text

    function int_text(x) result(t)
      integer, intent(in) :: x
      character(len=:), allocatable :: t
      character(len=16) :: b
      write(b, '(i0)') x
      t = trim(b)
    end function int_text

    pure integer function slot(name)
      character(len=*), intent(in) :: name
      select case (trim(name))
      case ('eps'); slot = 1
      case ('damping'); slot = 2
      case ('torque'); slot = 3
      case ('drive_amplitude'); slot = 4
      case ('drive_frequency'); slot = 5
      case ('drive_phase'); slot = 6
      case ('theta0'); slot = 7
      case ('pivot_amplitude'); slot = 9
      case ('pivot_frequency'); slot = 10
      case ('friction'); slot = 11
      case ('drag'); slot = 12
      case default; slot = 8
      end select
    end function slot

  end subroutine sweep_scene_csv


  !> The answer of a point for the boundary test: out(1) when decided, else a
  !> value no answer takes (so decided/undecided neighbours also differ).
  elemental real(dp) function answer(o1, st)
    real(dp), intent(in) :: o1
    integer, intent(in) :: st
    answer = -1.0e300_dp
    if (st == ps_decided) answer = o1
  end function answer

  !> The uncertainty recheck of final_well / locked (as pendula.sweep's): a
  !> point of rows r0 .. r1 whose answer differs from a grid neighbour's (along
  !> any axis; the previous row from ans(1:inner) when r0 > 1, the row ahead
  !> when rl > r1) is computed again at 1000 times tighter tolerances; where
  !> its answer changes it is not known: out(1) = NaN, status 4.
  !> ans((r - r0 + 1) * inner + j): first-pass answer of point j of row r
  !> (row r0 - 1 at offset 0); o, pst: outputs of rows r0 .. rl from index 1.
  subroutine boundary_recheck(measure, n, r0, r1, rl, inner, params, rtol, atol, t_tr, t_max, nout, ans, o, pst)
    integer, intent(in) :: measure, n(3), r0, r1, rl, inner, nout
    real(dp), intent(in) :: params(:, :), rtol, atol, t_tr, t_max, ans(:)
    real(dp), intent(inout) :: o(:, :)
    integer, intent(inout) :: pst(:)
    logical, allocatable :: edge(:)
    integer, allocatable :: id(:)
    real(dp), allocatable :: p2(:, :), o2(:, :)
    integer, allocatable :: s2(:)
    integer :: r, j, i2, i3, c, m, q
    integer, volatile :: no_cancel
    real(dp) :: a
    allocate(edge((r1 - r0 + 1) * inner))
    edge = .false.
    do r = r0, r1
      do j = 1, inner
        c = (r - r0 + 1) * inner + j          ! this point in ans
        a = ans(c)
        q = (r - r0) * inner + j              ! and in o, pst
        i3 = mod(j - 1, n(3)) + 1
        i2 = (j - 1) / n(3) + 1
        if (r > 1) edge(q) = edge(q) .or. ans(c - inner) /= a
        if (r < rl) edge(q) = edge(q) .or. ans(c + inner) /= a
        if (i2 > 1) edge(q) = edge(q) .or. ans(c - n(3)) /= a
        if (i2 < n(2)) edge(q) = edge(q) .or. ans(c + n(3)) /= a
        if (i3 > 1) edge(q) = edge(q) .or. ans(c - 1) /= a
        if (i3 < n(3)) edge(q) = edge(q) .or. ans(c + 1) /= a
      end do
    end do
    m = count(edge)
    if (m == 0) return
    allocate(id(m), p2(size(params, 1), m), o2(nout, m), s2(m))
    id = pack([(q, q = 1, size(edge))], edge)
    p2 = params(:, id)
    no_cancel = 0
    call sweep_points(measure, m, p2, rtol * 1.0e-3_dp, atol * 1.0e-3_dp, t_tr, t_max, nout, o2, s2, 0, no_cancel)
    do q = 1, m
      if (answer(o2(1, q), s2(q)) /= answer(o(1, id(q)), pst(id(q)))) then
        o(1, id(q)) = nan_dp
        pst(id(q)) = ps_uncertain
      end if
    end do
  end subroutine boundary_recheck

end module pendula_sweep
