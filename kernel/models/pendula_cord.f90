!> The pendulum on a flexible cord (Garfinkel 1957): compiled path of the
!> conservative case (no damping, torque or drive), the same physics as
!> python/pendula/models/cord.py.  Units: lengths in l, pivot at the origin,
!> y up, the bob at (sin theta, -cos theta) on the circle, gravity eps = g/l.
!>
!> circle: the exact elliptic solution (pendula_exact); departure where the
!>   tension v**2 + eps cos(theta) vanishes, cos theta1 = -xi, reached after a
!>   time given by the incomplete integral F (closed form, no root search).
!> flight: the parabola; re-entry at the root of the remaining factor of
!>   |p(tau)|**2 - 1 (tau = -4 u.g/|g|**2 for a tangential departure; after a
!>   springy jerk, the smallest positive root of a cubic, isolated between the
!>   roots of its derivative and bisected).
!> jerk: the radial velocity removed (reversed times e, the restitution).
!> One loop (cord_loop) runs circle and flight in turn for every circle
!> phase: the closed form here (cord_circle_exact) and the integrated one
!> with effects (pendula_cord_hybrid).
module pendula_cord
  use pendula_kinds, only: dp, nan_dp
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval
  use pendula_elliptic, only: ellip_f
  implicit none
  private
  public :: flip_map, cord_run, cord_run_all
  public :: cord_check, cord_depart, cord_flight_time, cord_land, cord_flight_state, cord_fly, cord_log_room
  public :: cord_flight_verdict, cord_loop, cord_blank, cord_circle_end
  !> what cord_flight_verdict says of a flight
  integer, parameter, public :: verdict_fly = 0, verdict_absorbed = 1, verdict_too_short = 2
  !> status codes of cord_run
  integer, parameter, public :: cord_ok = 0, cord_bad_eps = 1, cord_bad_state = 2, cord_bad_times = 3, &
    cord_bad_restitution = 4
  !> status of a run stopped by its cancel flag (set by another thread: Ctrl-C)
  integer, parameter, public :: cord_cancelled = 9
  !> stop reasons
  integer, parameter, public :: cord_stop_t_end = 0, cord_stop_max_flips = 1, cord_stop_min_flight = 2
  real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp

  !> A circle phase of the cord loop (cord_loop): from (tc, thc, vc) on the
  !> taut cord (cth = cos(thc)), the outputs theta, v, x, y, r (= 1) at the times t(i:j-1) it
  !> covers (j = cord_circle_end), and whether the bob leaves the circle (leaving), where (t1, th1,
  !> v1) and how (p, u, xib as cord_depart).  graze_restarts: the phase cannot
  !> see a departure at its own start (see cord_loop).
  type, abstract, public :: cord_circle
    logical :: graze_restarts = .false.
  contains
    procedure(circle_phase), deferred :: phase
  end type cord_circle

  abstract interface
    subroutine circle_phase(self, eps, tc, thc, vc, cth, vr, t, i, theta, v, x, y, r, j, leaving, &
                            t1, th1, v1, p, u, xib, status, cancel)
      import :: cord_circle, dp
      class(cord_circle), intent(inout) :: self
      real(dp), intent(in) :: eps, tc, thc, vc, cth, vr, t(:)
      integer, intent(in) :: i
      real(dp), intent(inout) :: theta(:), v(:), x(:), y(:), r(:)
      integer, intent(out) :: j, status
      logical, intent(out) :: leaving
      real(dp), intent(out) :: t1, th1, v1, p(2), u(2), xib
      integer, intent(inout), volatile, optional :: cancel
    end subroutine circle_phase
  end interface

  !> The closed-form circle phase: the exact elliptic motion (pendula_exact)
  !> and Garfinkel's departure point and time.
  type, extends(cord_circle), public :: cord_circle_exact
  contains
    procedure :: phase => exact_circle_phase
    procedure :: fill => exact_circle_fill
  end type cord_circle_exact

contains

  !> Garfinkel's flip map: x - (64/3) (x (1 - x**2))**3 on [0, 1], x elsewhere.
  elemental function flip_map(x) result(f)
    real(dp), intent(in) :: x
    real(dp) :: f, w
    if (x >= 0.0_dp .and. x <= 1.0_dp) then
      w = x * (1.0_dp - x) * (1.0_dp + x)
      f = x - (64.0_dp / 3.0_dp) * w * w * w
    else
      f = x
    end if
  end function flip_map

  !> Time from the angle phi (|phi| < theta1, moving forward) to theta1 = arccos(-xi), 0 < xi < 1.
  pure function time_to_departure(phi, xi, eps) result(dt)
    real(dp), intent(in) :: phi, xi, eps
    real(dp) :: dt, c2, s, psi0, psi1, m, mc
    c2 = (3.0_dp * xi + 2.0_dp) / 4.0_dp
    if (c2 <= 1.0_dp) then
      s = max(-1.0_dp, min(1.0_dp, sin(0.5_dp * phi) / sqrt(c2)))
      psi0 = asin(s)
      psi1 = atan2(sqrt(0.5_dp * (1.0_dp + xi)), 0.5_dp * sqrt(xi))
      mc = (2.0_dp - 3.0_dp * xi) / 4.0_dp
      dt = (ellip_f(psi1, c2, mc) - ellip_f(psi0, c2, mc)) / sqrt(eps)
    else
      m = 1.0_dp / c2
      mc = (3.0_dp * xi - 2.0_dp) / (3.0_dp * xi + 2.0_dp)
      dt = (ellip_f(0.5_dp * acos(-xi), m, mc) - ellip_f(0.5_dp * phi, m, mc)) / (sqrt(eps) * sqrt(c2))
    end if
    dt = max(dt, 0.0_dp)
  end function time_to_departure

  !> Smallest positive root of c1 + c2 t + c3 t**2 + c4 t**3 with c1 < 0 < c4: the real roots
  !> of the derivative split (0, inf) into monotone pieces; the first piece whose ends differ
  !> in sign holds the root, found by bisection to the last bit.
  pure function first_root(c1, c2, c3, c4) result(t)
    real(dp), intent(in) :: c1, c2, c3, c4
    real(dp) :: t, a, b, disc, q, r1, r2, pts(4), lo, hi, mid
    integer :: np_, k, it
    np_ = 1
    pts(1) = 0.0_dp
    a = 3.0_dp * c4
    b = 2.0_dp * c3
    disc = b * b - 4.0_dp * a * c2
    if (disc > 0.0_dp) then
      q = -0.5_dp * (b + sign(sqrt(disc), b))
      r1 = q / a
      r2 = c2 / q
      if (q == 0.0_dp) r2 = -r1
      if (min(r1, r2) > 0.0_dp) then
        np_ = np_ + 1; pts(np_) = min(r1, r2)
      end if
      if (max(r1, r2) > 0.0_dp) then
        np_ = np_ + 1; pts(np_) = max(r1, r2)
      end if
    end if
    ! a point beyond every root: Cauchy's bound
    np_ = np_ + 1
    pts(np_) = 1.0_dp + max(abs(c1), abs(c2), abs(c3)) / c4
    t = nan_dp
    do k = 1, np_ - 1
      lo = pts(k); hi = pts(k + 1)
      if (poly(hi) < 0.0_dp) cycle
      if (poly(lo) >= 0.0_dp .and. lo > 0.0_dp) then
        t = lo; return
      end if
      do it = 1, 2000
        mid = 0.5_dp * (lo + hi)
        if (mid <= lo .or. mid >= hi) exit
        if (poly(mid) < 0.0_dp) then
          lo = mid
        else
          hi = mid
        end if
      end do
      t = 0.5_dp * (lo + hi)
      return
    end do
  contains
    pure function poly(x) result(p)
      real(dp), intent(in) :: x
      real(dp) :: p
      p = c1 + x * (c2 + x * (c3 + x * c4))
    end function poly
  end function first_root

  !> The arguments of a cord run: eps > 0, a finite state, 0 <= restitution < 1,
  !> finite times >= 0 in increasing order (cord_ok or the cord_bad_* naming the first fault).
  pure integer function cord_check(eps, theta0, v0, restitution, t) result(status)
    real(dp), intent(in) :: eps, theta0, v0, restitution, t(:)
    integer :: i
    status = cord_ok
    if (.not. (eps > 0.0_dp .and. eps <= huge(eps))) then
      status = cord_bad_eps
    else if (.not. (abs(theta0) <= huge(eps) .and. abs(v0) <= huge(eps))) then
      status = cord_bad_state
    else if (.not. (restitution >= 0.0_dp .and. restitution < 1.0_dp)) then
      status = cord_bad_restitution
    else
      do i = 1, size(t)
        if (.not. (t(i) >= 0.0_dp .and. t(i) <= huge(eps))) then
          status = cord_bad_times; return
        end if
        if (i > 1) then
          if (t(i) < t(i - 1)) then
            status = cord_bad_times; return
          end if
        end if
      end do
    end if
  end function cord_check

  !> The bob leaves the circle at the angle th1 with the tangential velocity v1
  !> (= l theta') and the radial velocity vr (< 0: inward, after a springy
  !> jerk): its position p, velocity u and energy xi = (|u|^2 - 2 eps cos th1) / (3 eps).
  pure subroutine cord_depart(eps, th1, v1, vr, p, u, xi)
    real(dp), intent(in) :: eps, th1, v1, vr
    real(dp), intent(out) :: p(2), u(2), xi
    p = [sin(th1), -cos(th1)]
    u = [v1 * cos(th1) + vr * p(1), v1 * sin(th1) + vr * p(2)]
    xi = (v1 * v1 + vr * vr - 2.0_dp * eps * cos(th1)) / (3.0_dp * eps)
  end subroutine cord_depart

  !> Duration of the flight from p with velocity u under gravity eps: the
  !> root of |p(tau)|**2 - 1 = tau (c1 + c2 tau + c3 tau**2 + c4 tau**3).
  !> general = .false.: a tangential departure at zero tension (c1 = c2 = 0),
  !> tau = -c3 / c4 (Garfinkel, eq. 13.1), NaN when c3 >= 0 (the tension is
  !> zero but rising: no flight).  general = .true. (an inward radial velocity
  !> or a negative tension): the smallest positive root of the cubic, or of
  !> the quadratic when the departure is tangential (c1 >= 0).
  pure function cord_flight_time(eps, p, u, general) result(tau)
    real(dp), intent(in) :: eps, p(2), u(2)
    logical, intent(in) :: general
    real(dp) :: tau, c1, c2, c3, c4, d
    c3 = -eps * u(2)
    c4 = 0.25_dp * eps * eps
    if (.not. general) then
      tau = nan_dp
      if (c3 < 0.0_dp) tau = -c3 / c4
      return
    end if
    c1 = 2.0_dp * (p(1) * u(1) + p(2) * u(2))
    c2 = u(1) * u(1) + u(2) * u(2) - eps * p(2)
    if (c1 < 0.0_dp) then
      tau = first_root(c1, c2, c3, c4)
    else
      d = c3 * c3 - 4.0_dp * c4 * c2
      tau = nan_dp
      if (d >= 0.0_dp) tau = (-c3 + sqrt(d)) / (2.0_dp * c4)
    end if
  end function cord_flight_time

  !> Re-entry after the flight of duration tau from (p, u), which left the
  !> circle at th1: the angle th2 (continuous with th1), the tangential
  !> velocity v2 kept, the radial one removed and reversed times the
  !> restitution e (vr2 <= 0, inward).
  pure subroutine cord_land(eps, restitution, p, u, tau, th1, th2, v2, vr2)
    real(dp), intent(in) :: eps, restitution, p(2), u(2), tau, th1
    real(dp), intent(out) :: th2, v2, vr2
    real(dp) :: pe(2), w(2), rr, ct, st
    pe = p + u * tau + 0.5_dp * [0.0_dp, -eps] * tau * tau
    w = u + [0.0_dp, -eps] * tau
    th2 = atan2(pe(1), -pe(2))
    th2 = th2 + two_pi * anint((th1 - th2) / two_pi)
    rr = hypot(pe(1), pe(2))
    ct = -pe(2) / rr; st = pe(1) / rr
    v2 = w(1) * ct + w(2) * st
    vr2 = -restitution * (w(1) * st - w(2) * ct)
  end subroutine cord_land

  !> Whether a flight of duration tau is flown (verdict_fly), absorbed (a
  !> springy bounce, vr < 0, shorter than max(min_flight, 1e-9) / sqrt(eps):
  !> the cord stays taut) or ends the run (shorter than min_flight / sqrt(eps)).
  pure integer function cord_flight_verdict(eps, min_flight, general, vr, tau) result(verdict)
    real(dp), intent(in) :: eps, min_flight, vr, tau
    logical, intent(in) :: general
    verdict = verdict_fly
    if (general .and. vr < 0.0_dp .and. tau < max(min_flight, 1.0e-9_dp) / sqrt(eps)) then
      verdict = verdict_absorbed
    else if (tau < min_flight / sqrt(eps)) then
      verdict = verdict_too_short
    end if
  end function cord_flight_verdict

  !> One flight of the cord loop (every circle phase): from (p, u),
  !> left at (t1, th1, v1) with energy xib, for tau; the output times from
  !> t(i) on that fall inside it are filled (i advanced past them); row: the
  !> flip log's entry; th2, v2, vr2: the state after the jerk (cord_land).
  pure subroutine cord_fly(eps, restitution, p, u, tau, t1, th1, v1, xib, t, i, theta, v, x, y, r, &
                           row, th2, v2, vr2)
    real(dp), intent(in) :: eps, restitution, p(2), u(2), tau, t1, th1, v1, xib, t(:)
    integer, intent(inout) :: i
    real(dp), intent(inout) :: theta(:), v(:), x(:), y(:), r(:)
    real(dp), intent(out) :: row(8), th2, v2, vr2
    call cord_land(eps, restitution, p, u, tau, th1, th2, v2, vr2)
    do while (i <= size(t))
      if (t(i) > t1 + tau) exit
      call cord_flight_state(eps, p(1), p(2), u(1), u(2), th1, t(i) - t1, x(i), y(i), r(i), theta(i), v(i))
      i = i + 1
    end do
    row = [t1, th1, t1 + tau, th2, xib, (v2 * v2 + vr2 * vr2 - 2.0_dp * eps * cos(th2)) / (3.0_dp * eps), &
           v1, v2]
  end subroutine cord_fly

  !> The bob in flight, tt after leaving the circle at th1 from (p, u):
  !> position x, y, distance r from the pivot, angle theta (continuous with
  !> th1) and angular velocity theta'.
  elemental subroutine cord_flight_state(eps, p1, p2, u1, u2, th1, tt, x, y, r, theta, v)
    real(dp), intent(in) :: eps, p1, p2, u1, u2, th1, tt
    real(dp), intent(out) :: x, y, r, theta, v
    x = p1 + u1 * tt
    y = p2 + u2 * tt - 0.5_dp * eps * tt * tt
    r = hypot(x, y)
    theta = atan2(x, -y)
    theta = theta + two_pi * anint((th1 - theta) / two_pi)
    v = nan_dp
    if (r > 0.0_dp) v = (x * (u2 - eps * tt) - y * u1) / (r * r)
  end subroutine cord_flight_state

  !> The first output index j >= i past the circle phase: past the departure
  !> time t1 when the bob leaves the circle, else past every output time (n + 1).
  pure integer function cord_circle_end(t, i, leaving, t1) result(j)
    real(dp), intent(in) :: t(:), t1
    integer, intent(in) :: i
    logical, intent(in) :: leaving
    j = i
    if (.not. leaving) then
      j = size(t) + 1
      return
    end if
    do while (j <= size(t))
      if (t(j) > t1) exit
      j = j + 1
    end do
  end function cord_circle_end

  !> The closed-form circle phase from (tc, thc, vc): the exact elliptic
  !> motion, left where the energy xi = (v**2 - 2 eps cos theta) / (3 eps)
  !> lies in (0, 1), at cos theta1 = -xi after the time of time_to_departure.
  subroutine exact_circle_phase(self, eps, tc, thc, vc, cth, vr, t, i, theta, v, x, y, r, j, leaving, &
                                t1, th1, v1, p, u, xib, status, cancel)
    class(cord_circle_exact), intent(inout) :: self
    real(dp), intent(in) :: eps, tc, thc, vc, cth, vr, t(:)
    integer, intent(in) :: i
    real(dp), intent(inout) :: theta(:), v(:), x(:), y(:), r(:)
    integer, intent(out) :: j, status
    logical, intent(out) :: leaving
    real(dp), intent(out) :: t1, th1, v1, p(2), u(2), xib
    integer, intent(inout), volatile, optional :: cancel
    real(dp) :: xi, s, phi, phi0, kk, sq
    status = cord_ok
    leaving = .false.
    xi = (vc * vc - 2.0_dp * eps * cth) / (3.0_dp * eps)
    if (xi > 0.0_dp .and. xi < 1.0_dp) then
      s = sign(1.0_dp, vc)
      phi = s * thc
      kk = anint(phi / two_pi)
      phi0 = phi - two_pi * kk
      t1 = tc + time_to_departure(phi0, xi, eps)
      th1 = s * (two_pi * kk + acos(-xi))
      v1 = s * sqrt(eps * xi)
      sq = sqrt((1.0_dp - xi) * (1.0_dp + xi))
      p = [s * sq, xi]
      u = [-v1 * xi, v1 * s * sq]
      xib = xi
      leaving = .true.
    else
      t1 = nan_dp; th1 = nan_dp; v1 = nan_dp; p = nan_dp; u = nan_dp; xib = nan_dp
    end if
    j = cord_circle_end(t, i, leaving, t1)
    if (j > i) call self%fill(eps, tc, thc, vc, t(i:j - 1), theta(i:j - 1), v(i:j - 1), &
                                      x(i:j - 1), y(i:j - 1), r(i:j - 1))
  end subroutine exact_circle_phase

  !> The exact motion from (tc, thc, vc) at the times t: theta, v, x, y, r (= 1).
  !> (Its own procedure, called through the type so that it stays out of
  !> line: the orbit's large default initialisation and stack frame are paid
  !> only where a circle phase has output times, not once per flip.)
  pure subroutine exact_circle_fill(self, eps, tc, thc, vc, t, theta, v, x, y, r)
    class(cord_circle_exact), intent(in) :: self
    real(dp), intent(in) :: eps, tc, thc, vc, t(:)
    real(dp), intent(inout) :: theta(:), v(:), x(:), y(:), r(:)
    type(pendulum_orbit) :: o
    integer :: ost
    call orbit_setup(thc, vc, eps, o, ost)
    call orbit_eval(o, t - tc, theta, v)
    x = sin(theta); y = -cos(theta); r = 1.0_dp
  end subroutine exact_circle_fill

  !> The outputs blank (NaN), no flips, stop reason t_end: a cord run's start.
  pure subroutine cord_blank(theta, v, x, y, r, flips, nflips, stop_reason)
    real(dp), intent(out) :: theta(:), v(:), x(:), y(:), r(:), flips(:, :)
    integer, intent(out) :: nflips, stop_reason
    theta = nan_dp; v = nan_dp; x = nan_dp; y = nan_dp; r = nan_dp
    flips = nan_dp
    nflips = 0; stop_reason = cord_stop_t_end
  end subroutine cord_blank

  !> The cord loop, one for every circle phase: circle (circ%phase) and
  !> flight (cord_fly) in turn from (theta0, v0) at t = 0, the outputs at the
  !> sorted times t (>= 0) filled as they are passed.  flips(:, k) = t_leave,
  !> theta_leave, t_return, theta_return, xi_before, xi_after, v_leave,
  !> v_return; at most min(max_flips, size(flips, 2)) flips.  Output times
  !> after a stop (max_flips, min_flight) are NaN; stop_reason says which.
  !> status: cord_ok, a cord_bad_* of cord_check, or the circle phase's own.
  !> cancel (optional): read once per circle-flight cycle (a run of many short
  !> cycles may never reach an integrator's own polling); non-zero stops the
  !> run with status cord_cancelled (outputs not reached stay NaN).
  !> A flight that cannot start (zero tension, but rising) hands the bob back
  !> to the circle: with circ%graze_restarts (a circle phase that cannot see
  !> a departure at its own start, an integrator's event) at most 1000 times
  !> in a row (then stop_reason min_flight); otherwise the closed-form circle
  !> finds it again, and a start that was already slack ends the run.
  subroutine cord_loop(circ, eps, theta0, v0, restitution, max_flips, min_flight, t, theta, v, x, y, r, &
                       flips, nflips, stop_reason, status, cancel)
    class(cord_circle), intent(inout) :: circ
    real(dp), intent(in) :: eps, theta0, v0, restitution, min_flight, t(:)
    integer, intent(in) :: max_flips
    real(dp), intent(out) :: theta(:), v(:), x(:), y(:), r(:), flips(:, :)
    integer, intent(out) :: nflips, stop_reason, status
    integer, intent(inout), volatile, optional :: cancel
    real(dp) :: tc, thc, vc, cth, vr, t1, th1, v1, xib, tau, tension
    real(dp) :: p(2), u(2), th2, v2, vr2
    integer :: n, i, j, cap, nstay
    logical :: leaving, general, stay

    n = size(t)
    call cord_blank(theta, v, x, y, r, flips, nflips, stop_reason)
    status = cord_check(eps, theta0, v0, restitution, t)
    if (status /= cord_ok) return
    cap = min(max_flips, size(flips, 2))
    tc = 0.0_dp; thc = theta0; vc = v0; vr = 0.0_dp
    i = 1
    stay = .false.
    nstay = 0
    do
      if (present(cancel)) then
        if (cancel /= 0) then
          status = cord_cancelled; return
        end if
      end if
      ! ---- the circle from (tc, thc, vc), unless the bob is in flight or slack
      cth = cos(thc)
      tension = vc * vc + eps * cth
      general = .false.
      if ((vr < 0.0_dp .or. tension <= 0.0_dp) .and. .not. stay) then
        leaving = .true.; general = vr < 0.0_dp .or. tension < 0.0_dp
        t1 = tc; th1 = thc; v1 = vc
        call cord_depart(eps, th1, v1, vr, p, u, xib)
      else
        stay = .false.
        call circ%phase(eps, tc, thc, vc, cth, vr, t, i, theta, v, x, y, r, j, leaving, t1, th1, v1, p, u, xib, &
                        status, cancel)
        if (status /= cord_ok) return
        i = j
      end if
      if (.not. leaving) exit
      if (n > 0) then
        if (t1 > t(n)) exit
      end if
      if (nflips >= cap) then
        stop_reason = cord_stop_max_flips; exit
      end if
      ! ---- the flight
      tau = cord_flight_time(eps, p, u, general)
      if (tau /= tau) then  ! no flight: zero tension but rising
        tc = t1; thc = th1; vc = v1; vr = 0.0_dp
        if (circ%graze_restarts) then
          stay = .true.
          nstay = nstay + 1
          if (nstay > 1000) then  ! a grazing sequence that never gets off the circle
            stop_reason = cord_stop_min_flight; exit
          end if
        else
          if (tension <= 0.0_dp) exit
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
      if (n > 0) then
        if (tc > t(n)) exit
      end if
    end do
  end subroutine cord_loop

  !> Simulate a conservative flexible-cord pendulum at the sorted times t (>= 0):
  !> cord_loop with the closed-form circle phase (arguments and outputs as there).
  subroutine cord_run(eps, theta0, v0, restitution, max_flips, min_flight, t, theta, v, x, y, r, &
                      flips, nflips, stop_reason, status, cancel)
    real(dp), intent(in) :: eps, theta0, v0, restitution, min_flight, t(:)
    integer, intent(in) :: max_flips
    real(dp), intent(out) :: theta(:), v(:), x(:), y(:), r(:), flips(:, :)
    integer, intent(out) :: nflips, stop_reason, status
    integer, intent(inout), volatile, optional :: cancel
    type(cord_circle_exact) :: circ
    call cord_loop(circ, eps, theta0, v0, restitution, max_flips, min_flight, t, theta, v, x, y, r, &
                   flips, nflips, stop_reason, status, cancel)
  end subroutine cord_run

  !> The flip log's room for a (re)run of a cord loop: the first capacity
  !> (cap = 0 on entry), then 0 when the run just made is complete, or 8
  !> times more room when it stopped only because the log was full.
  pure integer function cord_log_room(cap, max_flips, status, stop_reason, nflips) result(next)
    integer, intent(in) :: cap, max_flips, status, stop_reason, nflips
    if (cap == 0) then
      next = max(1, min(max(max_flips, 0), 65536))
    else if (status /= cord_ok .or. stop_reason /= cord_stop_max_flips .or. nflips < cap &
             .or. cap >= max_flips) then
      next = 0
    else
      next = int(min(int(max_flips, kind(1_8)), 8_8 * cap))
    end if
  end function cord_log_room

  !> cord_run with a flip log that grows as needed (up to max_flips entries).
  subroutine cord_run_all(eps, theta0, v0, restitution, max_flips, min_flight, t, theta, v, x, y, r, &
                          flips, nflips, stop_reason, status, cancel)
    real(dp), intent(in) :: eps, theta0, v0, restitution, min_flight, t(:)
    integer, intent(in) :: max_flips
    real(dp), intent(out) :: theta(:), v(:), x(:), y(:), r(:)
    real(dp), allocatable, intent(out) :: flips(:, :)
    integer, intent(out) :: nflips, stop_reason, status
    integer, intent(inout), volatile, optional :: cancel
    integer :: cap
    cap = cord_log_room(0, max_flips, cord_ok, cord_stop_max_flips, 0)
    do
      if (allocated(flips)) deallocate(flips)
      allocate(flips(8, cap))
      call cord_run(eps, theta0, v0, restitution, max_flips, min_flight, t, theta, v, x, y, r, &
                    flips, nflips, stop_reason, status, cancel)
      cap = cord_log_room(cap, max_flips, status, stop_reason, nflips)
      if (cap == 0) exit
    end do
  end subroutine cord_run_all

end module pendula_cord
