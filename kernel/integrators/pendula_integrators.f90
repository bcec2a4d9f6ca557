!> Integrators for theta'' = -eps sin(theta) [- beta theta'] [+ tau] [+ A cos(Omega t + phase)].
!>
!> The right-hand side holds exactly the effects a scene names (flags set from
!> nonzero coefficients); an absent effect is a branch not taken.
!>
!> Fixed step (dt): rk4; Stormer-Verlet and Yoshida's compositions of it
!> (orders 4, 6, 8), built on the symmetric splitting
!>   damping flow h/2 | kick h/2 | drift h | kick h/2 | damping flow h/2
!> (the damping flow v -> v exp(-beta h/2) is exact, so the base method is
!> symmetric and the compositions reach their order with damping too);
!> Gauss-Legendre collocation with 2 and 3 stages (orders 4, 6), solved by
!> fixed-point iteration until the increments stop decreasing.  All fixed-step
!> methods add their increments with compensated (Kahan) summation.  Output
!> at times between grid points: one extra step of the same method from the
!> last grid point, branched off (the main trajectory keeps its step).
!>
!> Adaptive (rtol, atol): DOPRI5 (5(4), Shampine's 4th-order dense output)
!> and DOP853 (8(5,3), 7th-order dense output with three extra stages), both
!> with Gustafsson's PI step-size control in Hairer's form (pi_controller).  Output at requested times comes
!> from the dense output; steps are never shortened to hit them (unless asked:
!> integrate's land, then each output is a step's own end).  Events are
!> located on the dense output: each accepted step is sampled at 4 interior
!> points, so that two sign changes in one step are not missed, then refined
!> by the Illinois method.
!>
!> Runge-Kutta-Nystrom (rtol, atol): Dormand & Prince's RKN6(4)6FD pair for
!> theta'' = f(t, theta) (no damping: the pair's stages never form theta'),
!> five force evaluations per step (the sixth stage is the next step's first),
!> the step controlled by the embedded 4th-order pair.  No dense output: the
!> steps are shortened to land on the output times, so no events.
!>
!> Verner's 9(8) pair (rtol, atol): 16 stages, any model; the step controlled
!> by the embedded 8th-order weights; outputs inside a step from Verner's
!> order-8 interpolant (5 more stages, the first the next step's), or, on
!> request (land), steps shortened to end on the output times; no events.
!> Verner's 'most efficient' 8(7) pair likewise: 13 stages, the step
!> controlled by the embedded 7th-order weights, Verner's order-8 interpolant
!> (8 more stages, the first the next step's).
module pendula_integrators
  use, intrinsic :: iso_c_binding, only: c_double, c_ptr, c_null_ptr
  use pendula_kinds, only: dp, i8, nan_dp, pi
  use pendula_gravity, only: gravity_accel
  use pendula_equilibria, only: field_slope
  use pendula_time_scales, only: n_scales, time_rates, fastest_rate
  implicit none
  private
  public :: pendulum_model, make_model, add_effects, model_rates, kahan_add, step_guard, cancel_polled, user_force_fn, &
    gauss_iteration_done, &
    free_accel, pi_controller, pi_step_factor, &
    event_spec, run_stats, integrate, accel, accel_jacobian, &
    dop853_error_norm, dop853_step_2, dop853_step_6, system_rhs, verner_one_step_dense, &
    start_step_euler, start_step_refined

  include 'pendula_rk_tables.inc'
  !> DOP853's A transposed, so that each stage's weights are contiguous
  real(dp), parameter :: d8_at(0:15, 0:15) = transpose(d8_a)
  !> The nodes of all 21 stages of Verner's pairs with their interpolants
  real(dp), parameter :: v9_cc(0:20) = [v9_c, v9i_c], v8_cc(0:20) = [v8_c, v8i_c]

  integer, parameter, public :: m_rk4 = 1, m_verlet = 2, m_yoshida4 = 3, m_yoshida6 = 4, &
    m_yoshida8 = 5, m_gauss4 = 6, m_gauss6 = 7, m_dopri5 = 8, m_dop853 = 9, m_dprkn6 = 11, m_vern9 = 12, &
    m_vern8 = 14
  integer, parameter, public :: st_ok = 0, st_bad_step = 1, st_bad_tol = 2, st_bad_method = 3, &
    st_step_underflow = 5, st_nonfinite = 6, st_no_dense = 9, st_stopped = 10, &
    st_too_many_steps = 7, st_cancelled = 8, st_velocity_force = 12
  !> The work limit of one call: steps of the integrator (fixed or adaptive).
  !> A span that needs more (t = 1e15, dt = 1e-18, a drive at 1e300 rad/s) is
  !> an error that says so, never a hang or a wrapped-around step count.
  integer(i8), parameter, public :: max_steps = 100000000_i8
  !> Fixed-step methods know their count in advance and their steps are cheap:
  !> their limit is higher, so that 10^6 periods at dt = T/1000 (10^9 steps,
  !> the long-run round-off study) still run.
  integer(i8), parameter, public :: max_fixed_steps = 2000000000_i8
  !> How often the cancel flag is read (steps).
  integer(i8), parameter :: poll_every = 4096_i8
  !> The PI terms (beta) of the step-size controller (pi_controller).  DOPRI5:
  !> 0.04, the default of Hairer's DOPRI5.  Hairer's DOP853 ships with beta = 0
  !> (pure I control) and rejected 22 % of its steps on the five problems of
  !> the work-precision study (rtol 1e-3 ... 1e-12); beta = 0.06 rejects 9 %
  !> and needs 4 % fewer evaluations for the same errors (0.04: 16 %, 0.08:
  !> 4 % but 7 % more evaluations).  Verner's 9(8) with its interpolant: 0.05
  !> (15 % -> 4 %, 2 % fewer evaluations; 0.04: 8 %, 0.06: 2 % but 4 % more).
  !> Verner's 8(7) with its interpolant: 0.05 (17 % -> 7 %, 3 % fewer
  !> evaluations; 0.04: 10 %, 0.06: 4 % but 1 % more, 0.08: 0.2 % but 14 % more).
  real(dp), parameter :: dop853_beta = 0.06_dp, vern9_beta = 0.05_dp, vern8_beta = 0.05_dp

  type :: pendulum_model
    real(dp) :: eps = 1.0_dp, beta = 0.0_dp, tau = 0.0_dp
    real(dp) :: amp = 0.0_dp, omega = 0.0_dp, phase = 0.0_dp
    logical :: damped = .false., torqued = .false., driven = .false.
    !> non-uniform gravity: field kind and parameter of pendula_gravity; 0 = uniform
    integer :: gkind = 0
    real(dp) :: gpar = 0.0_dp
    !> friction mu, drag gamma, vibrating pivot (pamp cos(pomega t + pphase)); vsign: the sign of v on
    !> a stretch between the v = 0 events of friction and drag (0: the sign of v itself, no events);
    !> the user's force uforce(t + ut0, th, v, uparams) (ut0: the time origin of a restarted stretch)
    real(dp) :: mu = 0.0_dp, gamma = 0.0_dp, pamp = 0.0_dp, pomega = 0.0_dp, pphase = 0.0_dp, vsign = 0.0_dp
    real(dp) :: ut0 = 0.0_dp
    logical :: rubbed = .false., dragged = .false., vibrated = .false., forced = .false.
    procedure(user_force_fn), pointer, nopass :: uforce => null()
    type(c_ptr) :: uparams = c_null_ptr
  end type pendulum_model

  !> A user's force: double f(double t, double theta, double v, const double *params), called on
  !> every right-hand side from every thread (declared pure: it must not keep state of its own).
  abstract interface
    pure function user_force_fn(t, th, v, params) bind(C) result(a)
      import :: c_double, c_ptr
      real(c_double), value, intent(in) :: t, th, v
      type(c_ptr), value, intent(in) :: params
      real(c_double) :: a
    end function user_force_fn
  end interface

  !> kind 0: none; 1: g = v (turning points); 2: g = theta - level;
  !> 3: g = sin((theta - level)/2) (theta passing level + 2 pi k, for rotations);
  !> 4: g = v**2 + eps cos(theta), the cord tension / (m l) (flexible cord: it slackens at g = 0).
  !> direction +1: only g rising through 0, -1: only falling, 0: both.
  type :: event_spec
    integer :: kind = 0
    real(dp) :: level = 0.0_dp
    integer :: direction = 0
    logical :: terminal = .false.
  end type event_spec

  type :: run_stats
    integer(i8) :: nsteps = 0, naccept = 0, nreject = 0, nfev = 0
  end type run_stats

contains

  !> Hairer's error norm of a DOP853 step of size h in n components: the 5th-
  !> and 3rd-order estimates e5, e3 combined, each scaled by sk (the tolerance
  !> per component).  The adaptive integrator here and the Lyapunov stepper
  !> of the sweeps (6-D) both use it.
  pure function dop853_error_norm(h, e3, e5, sk) result(errn)
    real(dp), intent(in) :: h, e3(:), e5(:), sk(:)
    real(dp) :: errn, err5, err3, deno
    err5 = sum((e5 / sk)**2)
    err3 = sum((e3 / sk)**2)
    deno = err5 + 0.01_dp * err3
    if (deno <= 0.0_dp) deno = 1.0_dp
    errn = abs(h) * err5 * sqrt(1.0_dp / (real(size(sk), dp) * deno))
  end function dop853_error_norm

  !> The right-hand side of the systems the DOP853 stepper integrates, by the
  !> size of the state: n = 2, (theta, v) of the model; n = 6, (theta, v) with
  !> two tangent vectors w1 = y(3:4), w2 = y(5:6) of the variational equations
  !> dw/dt = J w, J = [[0, 1], [da/dtheta, da/dv]] (accel_jacobian; the
  !> Lyapunov exponents of pendula_lyapunov).
  pure function system_rhs(m, t, y) result(f)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: t, y(:)
    real(dp) :: f(size(y))
    call system_rhs_n(m, size(y), t, y, f)
  end function system_rhs

  pure subroutine system_rhs_n(m, n, t, y, f)
    type(pendulum_model), intent(in) :: m
    integer, intent(in) :: n
    real(dp), intent(in) :: t, y(n)
    real(dp), intent(out) :: f(n)
    real(dp) :: dadth, dadv
    f(1) = y(2)
    f(2) = accel(m, t, y(1), y(2))
    if (n == 6) then
      call accel_jacobian(m, t, y(1), y(2), dadth, dadv)
      f(3) = y(4)
      f(4) = dadth * y(3) + dadv * y(4)
      f(5) = y(6)
      f(6) = dadth * y(5) + dadv * y(6)
    end if
  end subroutine system_rhs_n

  !> One DOP853 step of the n-dimensional system of system_rhs from (t, y) with
  !> f0 = f(t, y): the stages k(0:12, 1:n), the solution ynew, fnew = f(t + h, ynew)
  !> (the next step's first stage) and the 3rd- and 5th-order error estimates
  !> e3, e5 (to be weighed by dop853_error_norm).  The one stepper of the
  !> integrators (n = 2) and of the Lyapunov tangent system (n = 6): its text is
  !> pendula_dop853_step.inc, compiled for each n so that the compiler sees n
  !> (a run-time n costs the 2-D integrator 17 % of its time).
  pure subroutine dop853_step_2(m, t, y, f0, h, k, ynew, fnew, e3, e5)
    integer, parameter :: n = 2, ldk = 16
    include 'pendula_dop853_step.inc'
  end subroutine dop853_step_2

  pure subroutine dop853_step_6(m, t, y, f0, h, k, ynew, fnew, e3, e5)
    integer, parameter :: n = 6, ldk = 13
    include 'pendula_dop853_step.inc'
  end subroutine dop853_step_6

  pure function make_model(eps, beta, tau, amp, omega, phase) result(m)
    real(dp), intent(in) :: eps, beta, tau, amp, omega, phase
    type(pendulum_model) :: m
    m%eps = eps; m%beta = beta; m%tau = tau; m%amp = amp; m%omega = omega; m%phase = phase
    m%damped = beta /= 0.0_dp
    m%torqued = tau /= 0.0_dp
    m%driven = amp /= 0.0_dp
  end function make_model

  !> The model m with dry friction mu, quadratic drag gamma and a vibrating pivot (amplitude pamp,
  !> frequency pomega) added; each effect is in the force law only when its coefficient is nonzero.
  pure function add_effects(m, mu, gamma, pamp, pomega) result(me)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: mu, gamma, pamp, pomega
    type(pendulum_model) :: me
    me = m
    me%mu = mu; me%gamma = gamma; me%pamp = pamp; me%pomega = pomega
    me%rubbed = mu /= 0.0_dp
    me%dragged = gamma /= 0.0_dp
    me%vibrated = pamp /= 0.0_dp
  end function add_effects

  !> The model's time-scale rates (pendula_time_scales) from the state's speed v0.
  pure function model_rates(m, v0) result(r)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: v0
    real(dp) :: r(n_scales)
    r = time_rates(m%eps, m%beta, m%tau, m%amp, m%omega, m%pamp, m%pomega, m%gkind, m%gpar, m%mu, m%gamma, v0)
  end function model_rates

  !> theta'' without the friction term (the force friction must hold at rest).
  pure function free_accel(m, t, th, v) result(a)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: t, th, v
    real(dp) :: a
    type(pendulum_model) :: mf
    mf = m
    mf%rubbed = .false.
    a = accel(mf, t, th, v)
  end function free_accel

  !> theta'' for the effects the model names.
  pure function accel(m, t, th, v) result(a)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: t, th, v
    real(dp) :: a
    if (m%gkind == 0) then
      a = -m%eps * sin(th)
    else
      a = gravity_accel(m%gkind, m%gpar, m%eps, th)
    end if
    if (m%damped) a = a - m%beta * v
    if (m%torqued) a = a + m%tau
    if (m%driven) a = a + m%amp * cos(m%omega * t + m%phase)
    if (m%rubbed .or. m%dragged .or. m%vibrated .or. m%forced) a = a + effects_accel(m, t, th, v)
  end function accel

  !> The terms of friction, drag, the vibrating pivot and the user's force.  On a stretch of
  !> known sign s = vsign, friction is -mu s and drag -gamma s v^2 (smooth through v = 0, so that
  !> the event is located on a smooth path); without it, -mu sgn(v) and -gamma v |v|.
  pure function effects_accel(m, t, th, v) result(a)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: t, th, v
    real(dp) :: a
    a = 0.0_dp
    if (m%vibrated) a = a + m%pamp * m%pomega**2 * cos(m%pomega * t + m%pphase) * sin(th)
    if (m%rubbed) then
      if (m%vsign /= 0.0_dp) then
        a = a - m%mu * m%vsign
      else if (v /= 0.0_dp) then
        a = a - sign(m%mu, v)
      end if
    end if
    if (m%dragged) then
      if (m%vsign /= 0.0_dp) then
        a = a - m%gamma * m%vsign * v * v
      else
        a = a - m%gamma * v * abs(v)
      end if
    end if
    if (m%forced) a = a + m%uforce(t + m%ut0, th, v, m%uparams)
  end function effects_accel

  !> The Jacobian of theta'' = accel(m, t, th, v) in the state: d theta''/d theta
  !> (the field's exact slope) and d theta''/d v, for the effects the model
  !> names (t and v enter through effects that depend on them).  The one
  !> linearisation of the model: the variational equations of the Lyapunov
  !> exponents and of the monodromy (periodic orbits, their continuation) all
  !> take it from here.
  pure subroutine accel_jacobian(m, t, th, v, dadth, dadv)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: t, th, v
    real(dp), intent(out) :: dadth, dadv
    real(dp) :: hth, hv, tt
    dadth = field_slope(m%gkind, m%gpar, m%eps, th)
    dadv = 0.0_dp
    if (m%damped) dadv = -m%beta
    if (m%vibrated) dadth = dadth + m%pamp * m%pomega**2 * cos(m%pomega * t + m%pphase) * cos(th)
    if (m%dragged) dadv = dadv - 2.0_dp * m%gamma * merge(m%vsign * v, abs(v), m%vsign /= 0.0_dp)
    if (m%forced) then
      ! the user's force has no derivative of its own: central differences, steps of
      ! eps^(1/3) relative (errors near eps^(2/3) of the force's scale)
      tt = t + m%ut0
      hth = 6.0e-6_dp * max(1.0_dp, abs(th)); hv = 6.0e-6_dp * max(1.0_dp, abs(v))
      dadth = dadth + (m%uforce(tt, th + hth, v, m%uparams) - m%uforce(tt, th - hth, v, m%uparams)) / (2 * hth)
      dadv = dadv + (m%uforce(tt, th, v + hv, m%uparams) - m%uforce(tt, th, v - hv, m%uparams)) / (2 * hv)
    end if
  end subroutine accel_jacobian

  !> The position- and time-dependent force alone (the kick of the splitting).
  pure function force(m, t, th) result(a)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: t, th
    real(dp) :: a
    if (m%gkind == 0) then
      a = -m%eps * sin(th)
    else
      a = gravity_accel(m%gkind, m%gpar, m%eps, th)
    end if
    if (m%torqued) a = a + m%tau
    if (m%driven) a = a + m%amp * cos(m%omega * t + m%phase)
    if (m%vibrated) a = a + m%pamp * m%pomega**2 * cos(m%pomega * t + m%pphase) * sin(th)
  end function force

  !> The step-size controller of the adaptive pairs (Gustafsson's PI control in
  !> Hairer's form, Hairer, Norsett & Wanner, Solving ODE I, section II.4, and
  !> the codes DOPRI5/DOP853): after a step with error norm err (<= 1: accepted)
  !>   h_new = h / max(facc2, min(facc1, err**expo * errold**(-beta) / safe)),
  !> errold the norm of the last accepted step (at least 1e-4); after a
  !> rejection the proportional part alone (errold not used, and the step may
  !> not grow on the next acceptance).  expo = 1/q - k_beta beta, q the order
  !> of the error estimate; beta > 0 is the PI term that damps the oscillation
  !> of h between acceptance and rejection.
  pure subroutine pi_controller(method, beta_set, expo, beta, facc1, facc2, safe)
    integer, intent(in) :: method
    !> the PI term to use instead of the method's default, if >= 0
    real(dp), intent(in) :: beta_set
    real(dp), intent(out) :: expo, beta, facc1, facc2, safe
    select case (method)
    case (m_dop853)
      beta = dop853_beta
      if (beta_set >= 0.0_dp) beta = beta_set
      expo = 1.0_dp / 8.0_dp - 0.2_dp * beta
      facc1 = 1.0_dp / 0.333_dp; facc2 = 1.0_dp / 6.0_dp; safe = 0.9_dp
    case (m_vern9)
      beta = vern9_beta
      if (beta_set >= 0.0_dp) beta = beta_set
      expo = 1.0_dp / 9.0_dp - 0.2_dp * beta
      facc1 = 1.0_dp / 0.333_dp; facc2 = 1.0_dp / 6.0_dp; safe = 0.9_dp
    case (m_vern8)
      beta = vern8_beta
      if (beta_set >= 0.0_dp) beta = beta_set
      expo = 1.0_dp / 8.0_dp - 0.2_dp * beta
      facc1 = 1.0_dp / 0.333_dp; facc2 = 1.0_dp / 6.0_dp; safe = 0.9_dp
    case default
      beta = 0.04_dp
      if (beta_set >= 0.0_dp) beta = beta_set
      expo = 0.2_dp - 0.75_dp * beta
      facc1 = 5.0_dp; facc2 = 0.1_dp; safe = 0.9_dp
    end select
  end subroutine pi_controller

  !> The step-size factor of that control after a step with error norm err (facold: the last accepted
  !> step's, see pi_controller): fac11 = err^expo and fac = fac11 / facold^beta / safe kept in
  !> [facc2, facc1].  The next step is h / fac after an acceptance, h / min(facc1, fac11 / safe) after a
  !> rejection.
  pure subroutine pi_step_factor(err, expo, beta, facold, safe, facc1, facc2, fac11, fac)
    real(dp), intent(in) :: err, expo, beta, facold, safe, facc1, facc2
    real(dp), intent(out) :: fac11, fac
    fac11 = err**expo
    fac = fac11 / facold**beta
    fac = max(facc2, min(facc1, fac / safe))
  end subroutine pi_step_factor

  !> The adaptive drivers' guard before each step, one rule for all of them: st_step_underflow when the
  !> step no longer moves t (Hairer's test, relative to t, so that a span of 1e-15 from t = 0 is not an
  !> underflow), st_too_many_steps at the work limit, st_cancelled when another thread set the cancel flag
  !> (read every poll_every steps); st_ok to go on.
  pure integer function step_guard(h, t, nsteps, cancel) result(st)
    real(dp), intent(in) :: h, t
    integer(i8), intent(in) :: nsteps
    integer, intent(in) :: cancel
    st = st_ok
    if (abs(h) <= 16.0_dp * epsilon(1.0_dp) * abs(t) .or. h == 0.0_dp) then
      st = st_step_underflow
    else if (nsteps >= max_steps) then
      st = st_too_many_steps
    else if (mod(nsteps, poll_every) == 0) then
      if (cancel /= 0) st = st_cancelled
    end if
  end function step_guard

  !> The fixed-step drivers' poll of the cancel flag: whether another thread has set it, read at the
  !> steps istep that are multiples of poll_every (0 included).
  pure logical function cancel_polled(istep, cancel)
    integer(i8), intent(in) :: istep
    integer, intent(in) :: cancel
    cancel_polled = .false.
    if (mod(istep, poll_every) == 0) cancel_polled = cancel /= 0
  end function cancel_polled

  !> Hairer's starting step, its first part (Hairer, Norsett & Wanner, Solving ODEs I, section II.4):
  !> 0.01 sqrt(dny / dnf) from the squared scaled norms of the state (dny) and of its slope (dnf),
  !> 1e-6 when either is negligible; at most hmax.
  pure function start_step_euler(dny, dnf, hmax) result(h0)
    real(dp), intent(in) :: dny, dnf, hmax
    real(dp) :: h0
    if (dnf <= 1.0e-10_dp .or. dny <= 1.0e-10_dp) then
      h0 = 1.0e-6_dp
    else
      h0 = sqrt(dny / dnf) * 0.01_dp
    end if
    h0 = min(h0, hmax)
  end function start_step_euler

  !> Hairer's starting step, its second part: der2 is the scaled change of the slope over the
  !> explicit Euler step h0, divided by h0; expo = 1/(order + 1) of the method's error estimate.
  !> At most 100 h0 and hmax.
  pure function start_step_refined(h0, der2, dnf, expo, hmax) result(h)
    real(dp), intent(in) :: h0, der2, dnf, expo, hmax
    real(dp) :: h, der12, h1
    der12 = max(abs(der2), sqrt(dnf))
    if (der12 <= 1.0e-15_dp) then
      h1 = max(1.0e-6_dp, abs(h0) * 1.0e-3_dp)
    else
      h1 = (0.01_dp / der12)**expo
    end if
    h = min(100.0_dp * abs(h0), h1, hmax)
  end function start_step_refined

  !> Hairer's one-evaluation first guess of the explicit pairs: 0.01 sqrt(dny / dnf), at least 1e-6,
  !> at most hmax (the span).
  pure function start_step_guess(dny, dnf, hmax) result(h)
    real(dp), intent(in) :: dny, dnf, hmax
    real(dp) :: h
    h = 0.01_dp * sqrt(dny / max(1.0e-10_dp, dnf))
    if (.not. (h > 1.0e-6_dp)) h = 1.0e-6_dp
    h = min(h, hmax)
  end function start_step_guess

  !> The outputs that fall on t itself (ts(kout), ts(kout + 1), ... equal to t) take the state (th, v);
  !> kout moves past them.
  pure subroutine outputs_at(t, th, v, ts, kout, ths, vs)
    real(dp), intent(in) :: t, th, v, ts(:)
    integer, intent(inout) :: kout
    real(dp), intent(inout) :: ths(:), vs(:)
    do while (kout <= size(ts))
      if (ts(kout) /= t) exit
      ths(kout) = th; vs(kout) = v
      kout = kout + 1
    end do
  end subroutine outputs_at

  !> y + e += d with compensation (Kahan): e carries what y could not hold.
  elemental subroutine kahan_add(y, e, d)
    real(dp), intent(inout) :: y, e
    real(dp), intent(in) :: d
    real(dp) :: dd, s
    dd = d + e
    s = y + dd
    e = dd - (s - y)
    y = s
  end subroutine kahan_add

  ! ====================================================================
  ! Driver
  ! ====================================================================

  !> Integrate from (theta0, v0) at t = 0 to the output times tout, which must be
  !> sorted ascending (negative times are reached by integrating backwards).
  !> Events (adaptive methods only) are recorded in the forward direction.
  subroutine integrate(m, method, theta0, v0, tout, rtol, atol, dt, theta, v, stats, status, &
                       ev, nev, tev, thev, vev, cancel, pi_beta, land)
    type(pendulum_model), intent(in) :: m
    !> the PI term of the step-size controller instead of the method's default
    !> (pi_controller; 0: pure I control, Hairer's DOP853 as published); ignored if negative
    real(dp), intent(in), optional :: pi_beta
    !> the adaptive pairs with an interpolant (DOPRI5, DOP853, Verner's 9(8) and 8(7)):
    !> shorten the steps to end on every output time (no interpolation: the
    !> outputs are the steps' own values)
    logical, intent(in), optional :: land
    !> set to non-zero by another thread to stop the run (status st_cancelled)
    integer, intent(inout), volatile, optional :: cancel
    integer, intent(in) :: method
    real(dp), intent(in) :: theta0, v0, tout(:), rtol, atol, dt
    real(dp), intent(out) :: theta(:), v(:)
    type(run_stats), intent(out) :: stats
    integer, intent(out) :: status
    type(event_spec), intent(in) :: ev
    integer, intent(out) :: nev
    real(dp), intent(out) :: tev(:), thev(:), vev(:)
    integer :: n, ineg, k
    logical :: adaptive, land_out
    real(dp) :: beta_set, th_start
    integer, volatile, target :: no_cancel
    no_cancel = 0
    beta_set = -1.0_dp
    if (present(pi_beta)) beta_set = pi_beta
    land_out = .false.
    if (present(land)) land_out = land

    n = size(tout)
    theta = nan_dp; v = nan_dp
    nev = 0
    status = st_ok
    adaptive = method == m_dopri5 .or. method == m_dop853 .or. method == m_dprkn6 .or. method == m_vern9 &
               .or. method == m_vern8
    if ((method < m_rk4 .or. method > m_dop853) .and. method /= m_dprkn6 .and. method /= m_vern9 &
        .and. method /= m_vern8) then
      status = st_bad_method; return
    end if
    if ((method == m_vern9 .or. method == m_vern8) .and. ev%kind /= 0) then
      status = st_no_dense; return
    end if
    if (method == m_dprkn6) then
      if (m%damped .or. m%rubbed .or. m%dragged .or. m%forced) then
        status = st_velocity_force; return
      end if
      if (ev%kind /= 0) then
        status = st_no_dense; return
      end if
    end if
    if (adaptive) then
      if (.not. (rtol > 0.0_dp .and. atol >= 0.0_dp)) then
        status = st_bad_tol; return
      end if
    else
      if (.not. (dt > 0.0_dp)) then
        status = st_bad_step; return
      end if
      if (ev%kind /= 0) then
        status = st_no_dense; return
      end if
    end if
    ! a run that certainly needs more than max_steps fails at once, not after
    ! them: every method takes at least 4 steps per period of the fastest of
    ! the model's time scales (pendula_time_scales: the oscillation in its
    ! field, the drive, the pivot and its force, the damping, a rotation at
    ! |v0|; t = 1e15, a drive at 1e300 rad/s)
    if (n > 0 .and. adaptive) then
      if (.not. (max(abs(tout(1)), abs(tout(n))) * fastest_rate(model_rates(m, v0)) &
                 * (4.0_dp / 6.283185307179586_dp) < real(max_steps, dp))) then
        status = st_too_many_steps; return
      end if
    end if
    ! The integration starts from theta0 reduced mod 2 pi (the force law is
    ! 2 pi-periodic in theta for every model of pendulum_model): stepping the
    ! absolute angle would round every increment to ulp(theta0) (2.4e-4 at
    ! 2^40) and scale the angle's tolerance by rtol |theta0|.  The outputs are
    ! theta0 + (theta_reduced - r0): the motion relative to the start, exact
    ! to the rounding of the absolute angle.  |theta0| <= pi: nothing changes.
    th_start = theta0
    if (abs(theta0) > pi .and. abs(theta0) <= huge(theta0)) th_start = atan2(sin(theta0), cos(theta0))
    ! the first index with tout >= 0
    ineg = 0
    do k = 1, n
      if (tout(k) < 0.0_dp) ineg = k
    end do
    ! forward: tout(ineg+1:n); backward: tout(ineg:1:-1)
    if (ineg < n) then
      call one_direction(tout(ineg + 1:n), theta(ineg + 1:n), v(ineg + 1:n), 1.0_dp, .true.)
    end if
    if (ineg > 0 .and. status == st_ok) then
      call one_direction(tout(ineg:1:-1), theta(ineg:1:-1), v(ineg:1:-1), -1.0_dp, .false.)
    end if
    if (th_start /= theta0) then
      theta = theta0 + (theta - th_start)
      thev(1:nev) = theta0 + (thev(1:nev) - th_start)
    end if

  contains

    subroutine one_direction(ts, ths, vs, dir, with_events)
      real(dp), intent(in) :: ts(:), dir
      real(dp), intent(inout) :: ths(:), vs(:)
      logical, intent(in) :: with_events
      type(event_spec) :: e
      e = ev
      if (.not. with_events) e%kind = 0
      ! a level of the angle moves with the reduced start
      if (e%kind == 2 .or. e%kind == 3) e%level = (e%level - theta0) + th_start
      if (status /= st_ok) return
      select case (method)
      case (m_vern9, m_vern8)
        if (present(cancel)) then
          call run_verner(m, method, th_start, v0, ts, dir, rtol, atol, ths, vs, stats, status, cancel, beta_set, &
                          land_out)
        else
          call run_verner(m, method, th_start, v0, ts, dir, rtol, atol, ths, vs, stats, status, no_cancel, &
                          beta_set, land_out)
        end if
      case (m_dprkn6)
        if (present(cancel)) then
          call run_nystrom(m, th_start, v0, ts, dir, rtol, atol, ths, vs, stats, status, cancel)
        else
          call run_nystrom(m, th_start, v0, ts, dir, rtol, atol, ths, vs, stats, status, no_cancel)
        end if
      case (m_dopri5, m_dop853)
        if (present(cancel)) then
          call run_adaptive(m, method, th_start, v0, ts, dir, rtol, atol, ths, vs, stats, status, &
                            e, nev, tev, thev, vev, cancel, beta_set, land_out)
        else
          call run_adaptive(m, method, th_start, v0, ts, dir, rtol, atol, ths, vs, stats, status, &
                            e, nev, tev, thev, vev, no_cancel, beta_set, land_out)
        end if
      case default
        if (present(cancel)) then
          call run_fixed(m, method, th_start, v0, ts, dir * dt, ths, vs, stats, status, cancel)
        else
          call run_fixed(m, method, th_start, v0, ts, dir * dt, ths, vs, stats, status, no_cancel)
        end if
      end select
    end subroutine one_direction

  end subroutine integrate

  ! ====================================================================
  ! Fixed-step methods
  ! ====================================================================

  subroutine run_fixed(m, method, theta0, v0, ts, h, ths, vs, stats, status, cancel)
    type(pendulum_model), intent(in) :: m
    integer, intent(inout), volatile :: cancel
    integer, intent(in) :: method
    real(dp), intent(in) :: theta0, v0, ts(:), h
    real(dp), intent(inout) :: ths(:), vs(:)
    type(run_stats), intent(inout) :: stats
    integer, intent(inout) :: status
    real(dp) :: t, th, v, the, ve, bt, bthe, bve
    integer(i8) :: istep, nsteps
    integer :: k, kout
    real(dp) :: tend

    if (size(ts) == 0) return
    tend = ts(size(ts))
    ! the step count is checked before it is formed: no integer overflow
    if (.not. (abs(tend) / abs(h) < real(max_fixed_steps, dp))) then
      status = st_too_many_steps; return
    end if
    nsteps = int(abs(tend) / abs(h), i8) + 1
    th = theta0; v = v0; the = 0.0_dp; ve = 0.0_dp
    kout = 1
    do istep = 0, nsteps
      t = real(istep, dp) * h
      ! outputs in [t, t + h): one branched-off step of the needed length
      do while (kout <= size(ts))
        if (abs(ts(kout)) >= abs(t) + abs(h)) exit
        bt = t; bthe = the; bve = ve
        ths(kout) = th; vs(kout) = v
        if (ts(kout) /= t) then
          call fixed_step(m, method, bt, ts(kout) - t, ths(kout), bthe, vs(kout), bve, stats)
        end if
        kout = kout + 1
      end do
      if (kout > size(ts)) exit
      if (cancel_polled(istep, cancel)) then
        status = st_cancelled; return
      end if
      call fixed_step(m, method, t, h, th, the, v, ve, stats)
      stats%nsteps = stats%nsteps + 1
      stats%naccept = stats%naccept + 1
      if (.not. (abs(th) <= huge(th) .and. abs(v) <= huge(v))) then
        status = st_nonfinite
        return
      end if
    end do
    do k = kout, size(ts)
      ths(k) = th; vs(k) = v
    end do
  end subroutine run_fixed

  !> One step of a fixed-step method from (t, th, v) with compensation terms.
  subroutine fixed_step(m, method, t, h, th, the, v, ve, stats)
    type(pendulum_model), intent(in) :: m
    integer, intent(in) :: method
    real(dp), intent(in) :: t, h
    real(dp), intent(inout) :: th, the, v, ve
    type(run_stats), intent(inout) :: stats
    real(dp) :: k1t, k1v, k2t, k2v, k3t, k3v, k4t, k4v, tt
    select case (method)
    case (m_rk4)
      k1t = v;                     k1v = accel(m, t, th, v)
      k2t = v + 0.5_dp * h * k1v;  k2v = accel(m, t + 0.5_dp * h, th + 0.5_dp * h * k1t, k2t)
      k3t = v + 0.5_dp * h * k2v;  k3v = accel(m, t + 0.5_dp * h, th + 0.5_dp * h * k2t, k3t)
      k4t = v + h * k3v;           k4v = accel(m, t + h, th + h * k3t, k4t)
      call kahan_add(th, the, h * (k1t + 2.0_dp * (k2t + k3t) + k4t) / 6.0_dp)
      call kahan_add(v, ve, h * (k1v + 2.0_dp * (k2v + k3v) + k4v) / 6.0_dp)
      stats%nfev = stats%nfev + 4
    case (m_verlet)
      tt = t
      call verlet(m, tt, h, th, the, v, ve, stats)
    case (m_yoshida4)
      call compose(yo4_w)
    case (m_yoshida6)
      call compose(yo6_w)
    case (m_yoshida8)
      call compose(yo8_w)
    case (m_gauss4)
      call gauss_step(m, 2, g2_mu, g2_b, g2_c, t, h, th, the, v, ve, stats)
    case (m_gauss6)
      call gauss_step(m, 3, g3_mu, g3_b, g3_c, t, h, th, the, v, ve, stats)
    end select
  contains
    !> Symmetric composition w_k ... w_1 w_0 w_1 ... w_k of the Verlet step.
    subroutine compose(w)
      real(dp), intent(in) :: w(0:)
      integer :: kk
      tt = t
      do kk = ubound(w, 1), 1, -1
        call verlet(m, tt, w(kk) * h, th, the, v, ve, stats)
      end do
      call verlet(m, tt, w(0) * h, th, the, v, ve, stats)
      do kk = 1, ubound(w, 1)
        call verlet(m, tt, w(kk) * h, th, the, v, ve, stats)
      end do
    end subroutine compose
  end subroutine fixed_step

  !> The symmetric base step: damping h/2, kick h/2, drift h, kick h/2, damping h/2.
  subroutine verlet(m, t, h, th, the, v, ve, stats)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(inout) :: t
    real(dp), intent(in) :: h
    real(dp), intent(inout) :: th, the, v, ve
    type(run_stats), intent(inout) :: stats
    real(dp) :: damp
    if (m%damped) then
      damp = exp(-0.5_dp * m%beta * h)
      call kahan_add(v, ve, (damp - 1.0_dp) * (v + ve))
    end if
    call kahan_add(v, ve, 0.5_dp * h * force(m, t, th))
    call kahan_add(th, the, h * v)
    t = t + h
    call kahan_add(v, ve, 0.5_dp * h * force(m, t, th))
    if (m%damped) call kahan_add(v, ve, (damp - 1.0_dp) * (v + ve))
    stats%nfev = stats%nfev + 2
  end subroutine verlet

  !> One Gauss-Legendre step in the mu form of Antonana, Makazaga & Murua
  !> (2017): L_i = h b_i f(y + sum_j mu_ij L_j), y1 = y + sum_i L_i, with
  !> mu_ij = a_ij / b_j stored so that mu_ij + mu_ji = 1 holds exactly (the
  !> symplecticity condition b_i a_ij + b_j a_ji = b_i b_j, which the a_ij rounded
  !> one by one miss by 1.7e-17: enough for a linear energy drift over long runs,
  !> see data/brouwer/).  No extra f evaluation for the update.  Fixed-point
  !> iteration on L from L = 0, stopped by gauss_iteration_done (the increments
  !> vanish, or stop decreasing at the round-off level).
  !> The stop of the Gauss-Legendre stages' fixed-point iteration (after iteration it, whose largest
  !> increment is d, the one before dold): the increments vanish, or they stop decreasing once they are
  !> within 1e-13 of the scale of the stages and the state (the round-off-limited rule of Hairer,
  !> McLachlan & Razakarivony 2008).  Far above round-off an oscillating system's increments need not
  !> fall monotonically in the max norm, so a rise there is not taken for convergence (it stopped the
  !> sixth-order method at fourth-order accuracy on a stiffly coupled chain).  The round-off floor of the
  !> increments is below eps (|stages| + h L |state|) with h L < 1 where the iteration converges, so the
  !> band leaves a margin of about 450 eps.
  pure logical function gauss_iteration_done(it, d, dold, scale)
    integer, intent(in) :: it
    real(dp), intent(in) :: d, dold, scale
    gauss_iteration_done = d == 0.0_dp .or. (it > 2 .and. d >= dold .and. d <= 1.0e-13_dp * scale)
  end function gauss_iteration_done

  subroutine gauss_step(m, s, mu, b, c, t, h, th, the, v, ve, stats)
    type(pendulum_model), intent(in) :: m
    integer, intent(in) :: s
    real(dp), intent(in) :: mu(0:s-1, 0:s-1), b(0:s-1), c(0:s-1), t, h
    real(dp), intent(inout) :: th, the, v, ve
    type(run_stats), intent(inout) :: stats
    real(dp) :: el(s, 2), eln(s, 2), hb(s), d, dold, zt, zv
    integer :: it, i, j
    do i = 1, s
      hb(i) = h * b(i - 1)
    end do
    el = 0.0_dp
    dold = huge(1.0_dp)
    do it = 1, 60
      do i = 1, s
        zt = 0.0_dp; zv = 0.0_dp
        do j = 1, s
          zt = zt + mu(i - 1, j - 1) * el(j, 1)
          zv = zv + mu(i - 1, j - 1) * el(j, 2)
        end do
        eln(i, 1) = hb(i) * (v + zv)
        eln(i, 2) = hb(i) * accel(m, t + c(i - 1) * h, th + zt, v + zv)
      end do
      stats%nfev = stats%nfev + s
      d = maxval(abs(eln - el))
      el = eln
      if (gauss_iteration_done(it, d, dold, maxval(abs(eln)) + abs(th) + abs(v))) exit
      dold = d
    end do
    zt = 0.0_dp; zv = 0.0_dp
    do i = 1, s
      zt = zt + el(i, 1)
      zv = zv + el(i, 2)
    end do
    call kahan_add(th, the, zt)
    call kahan_add(v, ve, zv)
  end subroutine gauss_step

  ! ====================================================================
  ! Runge-Kutta-Nystrom pair for theta'' = f(t, theta)
  ! ====================================================================

  !> Dormand & Prince's RKN6(4)6FD: Q_i = th + c_i h v + h^2 sum_j a_ij F_j,
  !> F_i = force(t + c_i h, Q_i); th1 = th + h v + h^2 sum b_i F_i, v1 = v +
  !> h sum bp_i F_i; the error is that of the embedded 4th-order weights (the
  !> stored differences eb, ebp), in Hairer's RMS norm over (theta, v).  Step
  !> control as DOPRI5 (error exponent 1/5, factors in [0.1, 5]); steps are
  !> shortened to end on each output time.
  subroutine run_nystrom(m, theta0, v0, ts, dir, rtol, atol, ths, vs, stats, status, cancel)
    type(pendulum_model), intent(in) :: m
    integer, intent(inout), volatile :: cancel
    real(dp), intent(in) :: theta0, v0, ts(:), dir, rtol, atol
    real(dp), intent(inout) :: ths(:), vs(:)
    type(run_stats), intent(inout) :: stats
    integer, intent(inout) :: status
    real(dp) :: t, th, v, f(0:5), qs, th1, v1, eth, ev, err, h, hnew, hs, fac, fac11, sk1, sk2, target
    real(dp) :: safe, expo, beta, facc1, facc2
    integer :: kout, i
    logical :: reject, hit

    if (size(ts) == 0) return
    call pi_controller(m_dopri5, 0.0_dp, expo, beta, facc1, facc2, safe)   ! DOPRI5's, without the PI term
    t = 0.0_dp; th = theta0; v = v0
    kout = 1
    call outputs_at(t, th, v, ts, kout, ths, vs)
    if (kout > size(ts)) return
    f(0) = force(m, t, th)
    stats%nfev = stats%nfev + 1
    ! starting step: the velocity and force scales against the tolerance (Hairer's first guess)
    sk1 = atol + rtol * abs(th); sk2 = atol + rtol * abs(v)
    h = dir * start_step_guess((th / sk1)**2 + (v / sk2)**2, (v / sk1)**2 + (f(0) / sk2)**2, abs(ts(size(ts))))
    reject = .false.
    do
      status = step_guard(h, t, stats%nsteps, cancel)
      if (status /= st_ok) return
      target = ts(kout)
      hit = dir * (t + h - target) >= 0.0_dp
      hs = h
      if (hit) hs = target - t
      do i = 1, 5
        qs = th + n6_c(i) * hs * v + hs * hs * dot_product(n6_a(i, 0:i-1), f(0:i-1))
        f(i) = force(m, t + n6_c(i) * hs, qs)
      end do
      th1 = th + hs * v + hs * hs * dot_product(n6_b(0:4), f(0:4))
      ! the sixth stage (c = 1, row of b): the force at the new position
      f(5) = force(m, t + hs, th1)
      v1 = v + hs * dot_product(n6_bp, f)
      stats%nfev = stats%nfev + 5
      stats%nsteps = stats%nsteps + 1
      eth = hs * hs * dot_product(n6_eb, f)
      ev = hs * dot_product(n6_ebp, f)
      sk1 = atol + rtol * max(abs(th), abs(th1)); sk2 = atol + rtol * max(abs(v), abs(v1))
      err = sqrt(0.5_dp * ((eth / sk1)**2 + (ev / sk2)**2))
      if (.not. (err == err) .or. .not. (abs(th1) <= huge(1.0_dp) .and. abs(v1) <= huge(1.0_dp))) then
        status = st_nonfinite; return
      end if
      call pi_step_factor(err, expo, beta, 1.0_dp, safe, facc1, facc2, fac11, fac)
      hnew = hs / fac
      if (err <= 1.0_dp) then
        stats%naccept = stats%naccept + 1
        t = t + hs
        if (hit) t = target
        th = th1; v = v1
        f(0) = f(5)
        call outputs_at(t, th, v, ts, kout, ths, vs)
        if (kout > size(ts)) exit
        ! a step shortened to land on an output does not shrink the next one
        if (hit) hnew = sign(max(abs(hnew), abs(h)), h)
        if (abs(hnew) > abs(h) .and. reject) hnew = h
        reject = .false.
        h = hnew
      else
        stats%nreject = stats%nreject + 1
        h = hs / min(facc1, fac11 / safe)
        reject = .true.
      end if
    end do
  end subroutine run_nystrom

  ! ====================================================================
  ! Verner's 9(8) and 8(7) pairs
  ! ====================================================================

  ! vern9_step, vern9_dense_stages, vern8_step, vern8_dense_stages (generated)
  include 'pendula_verner_steps.inc'

  !> The state at t + x h on the step [t, t + h] from y (0 <= x <= 1): y + h sum_i
  !> b_i(x) k_i with Verner's weight polynomials b_i(x) = sum_j p_ij x^j, j = 1..8.
  !> The weights reach 1.3e4 (9(8)) and 1.4e6 (8(7)) while sum_i b_i(x) = x and
  !> sum_i b_i(x) c_i = x^2/2 (the conditions of order 1 and 2): the sum is formed
  !> as x k_0 + x^2/2 d + sum_i b_i(x) (k_i - k_0 - c_i d), d = k_inew - k_0 (f at
  !> the step's end minus f at its start, h f' + O(h^2)), whose terms are O(h^2),
  !> so that the cancellation costs 1e6 eps h^2 |f''| instead of 1e6 eps h |f'|
  !> (1e-11 at h = 0.2 for the 8(7) pair's weights).  c(0:20): the stages' nodes.
  pure function verner_dense(y, h, k, x, p, c, inew) result(yo)
    real(dp), intent(in) :: y(2), h, k(0:20, 2), x, p(0:20, 0:7), c(0:20)
    integer, intent(in) :: inew
    real(dp) :: yo(2), w(1:20), d
    integer :: i, j
    do i = 1, 20
      w(i) = p(i, 7)
      do j = 6, 0, -1
        w(i) = w(i) * x + p(i, j)
      end do
      w(i) = w(i) * x
    end do
    do i = 1, 2
      d = k(inew, i) - k(0, i)
      yo(i) = y(i) + h * (x * k(0, i) + 0.5_dp * x * x * d + dot_product(w, k(1:20, i) - k(0, i) - c(1:20) * d))
    end do
  end function verner_dense

  !> One step of Verner's pair (method m_vern9 or m_vern8) of size h from
  !> (theta0, v0) at t = 0 and its interpolant at the fractions x of the step
  !> (the interpolants' order is measured with it:
  !> tests/test_integrators_vern9_dense.py, tests/test_integrators_vern8.py).
  pure subroutine verner_one_step_dense(m, method, theta0, v0, h, x, theta, v)
    type(pendulum_model), intent(in) :: m
    integer, intent(in) :: method
    real(dp), intent(in) :: theta0, v0, h, x(:)
    real(dp), intent(out) :: theta(:), v(:)
    real(dp) :: y(2), ynew(2), e(2), k(0:20, 2), yy(2)
    integer :: i, inew
    y = [theta0, v0]
    k = 0.0_dp
    k(0, 1) = y(2); k(0, 2) = accel(m, 0.0_dp, y(1), y(2))
    if (method == m_vern8) then
      inew = 13
      call vern8_step(m, 0.0_dp, y, h, k, ynew, e)
    else
      inew = 16
      call vern9_step(m, 0.0_dp, y, h, k, ynew, e)
    end if
    k(inew, 1) = ynew(2); k(inew, 2) = accel(m, h, ynew(1), ynew(2))
    if (method == m_vern8) then
      call vern8_dense_stages(m, 0.0_dp, y, h, k)
    else
      call vern9_dense_stages(m, 0.0_dp, y, h, k)
    end if
    do i = 1, size(x)
      if (method == m_vern8) then
        yy = verner_dense(y, h, k, x(i), v8i_p, v8_cc, inew)
      else
        yy = verner_dense(y, h, k, x(i), v9i_p, v9_cc, inew)
      end if
      theta(i) = yy(1); v(i) = yy(2)
    end do
  end subroutine verner_one_step_dense

  !> Verner's 9(8) pair (method m_vern9) on (theta, v): 16 evaluations per step
  !> (the 16th is f at the new point, the next step's first stage), Hairer's RMS
  !> error norm of the difference to the embedded 8th-order solution, the step
  !> controlled by pi_controller (exponent 1/9, PI term vern9_beta, factors in
  !> [1/6, 3]); Verner's 8(7) pair (m_vern8) likewise with 13 evaluations per
  !> step (exponent 1/8, PI term vern8_beta).  Outputs inside a step come from
  !> Verner's order-8 interpolant (4 more evaluations on the steps that hold an
  !> output for the 9(8) pair, 7 for the 8(7)), so the steps are never
  !> shortened for them; land: the steps are shortened to end on each output
  !> time instead (the outputs are then the steps' own values).
  subroutine run_verner(m, method, theta0, v0, ts, dir, rtol, atol, ths, vs, stats, status, cancel, beta_set, land)
    type(pendulum_model), intent(in) :: m
    integer, intent(in) :: method
    integer, intent(inout), volatile :: cancel
    real(dp), intent(in) :: theta0, v0, ts(:), dir, rtol, atol, beta_set
    logical, intent(in) :: land
    real(dp), intent(inout) :: ths(:), vs(:)
    type(run_stats), intent(inout) :: stats
    integer, intent(inout) :: status
    real(dp) :: t, y(2), ynew(2), e(2), sk(2), k(0:20, 2), err, h, hnew, hs, fac, fac11, target, yy(2)
    real(dp) :: safe, expo, facc1, facc2, beta, facold
    integer :: kout, inew
    logical :: reject, hit

    if (size(ts) == 0) return
    call pi_controller(method, beta_set, expo, beta, facc1, facc2, safe)
    ! the index of f at the new point (the next step's first stage, the interpolant's first own stage)
    inew = 16
    if (method == m_vern8) inew = 13
    facold = 1.0e-4_dp
    t = 0.0_dp; y = [theta0, v0]
    kout = 1
    call outputs_at(t, y(1), y(2), ts, kout, ths, vs)
    if (kout > size(ts)) return
    k = 0.0_dp
    k(0, 1) = y(2); k(0, 2) = accel(m, t, y(1), y(2))
    stats%nfev = stats%nfev + 1
    ! starting step: Hairer's first guess from the state and slope scales (order 9)
    sk = atol + rtol * abs(y)
    h = dir * start_step_guess(sum((y / sk)**2), sum((k(0, :) / sk)**2), abs(ts(size(ts))))
    reject = .false.
    do
      status = step_guard(h, t, stats%nsteps, cancel)
      if (status /= st_ok) return
      if (land) then
        target = ts(kout)
      else
        target = ts(size(ts))
      end if
      hit = dir * (t + h - target) >= 0.0_dp
      hs = h
      if (hit) hs = target - t
      if (method == m_vern8) then
        call vern8_step(m, t, y, hs, k, ynew, e)
      else
        call vern9_step(m, t, y, hs, k, ynew, e)
      end if
      stats%nfev = stats%nfev + (inew - 1)
      stats%nsteps = stats%nsteps + 1
      sk = atol + rtol * max(abs(y), abs(ynew))
      err = sqrt(0.5_dp * sum((e / sk)**2))
      if (.not. (err == err) .or. .not. all(abs(ynew) <= huge(1.0_dp))) then
        status = st_nonfinite; return
      end if
      call pi_step_factor(err, expo, beta, facold, safe, facc1, facc2, fac11, fac)
      hnew = hs / fac
      if (err <= 1.0_dp) then
        facold = max(err, 1.0e-4_dp)
        stats%naccept = stats%naccept + 1
        ! f at the new point: the next step's first stage and the interpolant's stage inew
        k(inew, 1) = ynew(2); k(inew, 2) = accel(m, t + hs, ynew(1), ynew(2))
        stats%nfev = stats%nfev + 1
        ! outputs strictly inside the step, from the interpolant
        if (kout <= size(ts)) then
          if (dir * (ts(kout) - (t + hs)) < 0.0_dp) then
            if (method == m_vern8) then
              call vern8_dense_stages(m, t, y, hs, k)
            else
              call vern9_dense_stages(m, t, y, hs, k)
            end if
            stats%nfev = stats%nfev + (20 - inew)
            do while (kout <= size(ts))
              if (dir * (ts(kout) - (t + hs)) >= 0.0_dp) exit
              if (method == m_vern8) then
                yy = verner_dense(y, hs, k, (ts(kout) - t) / hs, v8i_p, v8_cc, inew)
              else
                yy = verner_dense(y, hs, k, (ts(kout) - t) / hs, v9i_p, v9_cc, inew)
              end if
              ths(kout) = yy(1); vs(kout) = yy(2)
              kout = kout + 1
            end do
          end if
        end if
        t = t + hs
        if (hit) t = target
        y = ynew
        k(0, :) = k(inew, :)
        call outputs_at(t, y(1), y(2), ts, kout, ths, vs)
        if (kout > size(ts)) exit
        ! a step shortened to land on an output does not shrink the next one
        if (hit) hnew = sign(max(abs(hnew), abs(h)), h)
        if (abs(hnew) > abs(h) .and. reject) hnew = h
        reject = .false.
        h = hnew
      else
        stats%nreject = stats%nreject + 1
        h = hs / min(facc1, fac11 / safe)
        reject = .true.
      end if
    end do
  end subroutine run_verner

  ! ====================================================================
  ! Adaptive methods with dense output
  ! ====================================================================

  subroutine run_adaptive(m, method, theta0, v0, ts, dir, rtol, atol, ths, vs, stats, status, &
                          ev, nev, tev, thev, vev, cancel, beta_set, land)
    type(pendulum_model), intent(in) :: m
    integer, intent(inout), volatile :: cancel
    integer, intent(in) :: method
    real(dp), intent(in) :: theta0, v0, ts(:), dir, rtol, atol, beta_set
    !> end the steps on the output times (their values then the steps' own, not interpolated)
    logical, intent(in) :: land
    real(dp), intent(inout) :: ths(:), vs(:)
    type(run_stats), intent(inout) :: stats
    integer, intent(inout) :: status
    type(event_spec), intent(in) :: ev
    integer, intent(inout) :: nev
    real(dp), intent(inout) :: tev(:), thev(:), vev(:)
    real(dp) :: t, y(2), f0(2), ynew(2), fnew(2), h, err, hnew, fac, fac11, facold, tend, x, target, hfree
    real(dp) :: k(0:15, 2), cont(2, 0:6), expo1, beta, facc1, facc2, safe, gprev, yy(2)
    integer :: kout, order
    logical :: last, reject, stop_now, need_dense

    if (size(ts) == 0) return
    tend = ts(size(ts))
    if (method == m_dop853) then
      order = 8
      call pi_controller(m_dop853, beta_set, expo1, beta, facc1, facc2, safe)
    else
      order = 5
      call pi_controller(m_dopri5, beta_set, expo1, beta, facc1, facc2, safe)
    end if
    facold = 1.0e-4_dp
    t = 0.0_dp
    y = [theta0, v0]
    f0 = rhs(t, y)
    stats%nfev = stats%nfev + 1
    kout = 1
    call outputs_at(t, y(1), y(2), ts, kout, ths, vs)
    if (kout > size(ts)) return
    gprev = gfun(y)
    h = dir * initial_step()
    reject = .false.
    last = .false.
    do
      status = step_guard(h, t, stats%nsteps, cancel)
      if (status /= st_ok) return
      ! the step ends on the last output time (land: on the next one) rather than pass it
      target = tend
      if (land) target = ts(kout)
      hfree = h
      if (dir * (t + h - target) >= 0.0_dp) then
        h = target - t
        last = .true.
      end if
      if (method == m_dop853) then
        call step853(err)
      else
        call step5(err)
      end if
      stats%nsteps = stats%nsteps + 1
      if (.not. (err == err) .or. .not. all(abs(ynew) <= huge(1.0_dp))) then
        status = st_nonfinite; return
      end if
      call pi_step_factor(err, expo1, beta, facold, safe, facc1, facc2, fac11, fac)
      hnew = h / fac
      if (err <= 1.0_dp) then
        facold = max(err, 1.0e-4_dp)
        stats%naccept = stats%naccept + 1
        ! the dense output (3 more stages for DOP853) only when an output time
        ! falls strictly inside the step, or events are being located
        need_dense = ev%kind /= 0
        if (kout <= size(ts)) need_dense = need_dense .or. dir * (ts(kout) - (t + h)) < 0.0_dp
        if (need_dense) call dense_coefficients()
        ! events inside [t, t + h]
        stop_now = .false.
        if (ev%kind /= 0) call locate_events(stop_now)
        ! outputs inside (t, t + h]
        do while (kout <= size(ts))
          if (dir * (ts(kout) - (t + h)) > 0.0_dp .and. .not. (last .and. ts(kout) == target)) exit
          ! (nested: Fortran's .and. need not short-circuit, and tev(0) does not exist)
          if (stop_now) then
            if (dir * (ts(kout) - tev(nev)) > 0.0_dp) exit
          end if
          x = (ts(kout) - t) / h
          yy = dense(x)
          ths(kout) = yy(1); vs(kout) = yy(2)
          kout = kout + 1
        end do
        if (stop_now) then
          status = st_stopped
          return
        end if
        t = t + h
        if (last) t = target
        y = ynew
        f0 = fnew
        if (kout > size(ts) .or. (last .and. .not. land)) exit
        ! a step shortened to land on an output does not shrink the next one
        if (last .and. land) hnew = sign(max(abs(hnew), abs(hfree)), h)
        last = .false.
        if (abs(hnew) > abs(h) .and. reject) hnew = h
        reject = .false.
        h = hnew
      else
        stats%nreject = stats%nreject + 1
        hnew = h / min(facc1, fac11 / safe)
        reject = .true.
        last = .false.
        h = hnew
      end if
    end do

  contains

    function rhs(tt, yv) result(f)
      real(dp), intent(in) :: tt, yv(2)
      real(dp) :: f(2)
      f(1) = yv(2)
      f(2) = accel(m, tt, yv(1), yv(2))
    end function rhs

    function scale_of(a, b) result(sk)
      real(dp), intent(in) :: a(2), b(2)
      real(dp) :: sk(2)
      sk = atol + rtol * max(abs(a), abs(b))
    end function scale_of

    !> Hairer's starting step: balance an explicit Euler step against f's change.
    function initial_step() result(h0)
      real(dp) :: h0, sk(2), dnf, der2, y1(2), f1(2)
      sk = atol + rtol * abs(y)
      dnf = sum((f0 / sk)**2)
      h0 = start_step_euler(sum((y / sk)**2), dnf, abs(tend))
      y1 = y + dir * h0 * f0
      f1 = rhs(dir * h0, y1)
      stats%nfev = stats%nfev + 1
      der2 = sqrt(sum(((f1 - f0) / sk)**2)) / h0
      h0 = start_step_refined(h0, der2, dnf, 1.0_dp / order, abs(tend))
    end function initial_step

    subroutine step5(errn)
      real(dp), intent(out) :: errn
      real(dp) :: yst(2), e(2), sk(2)
      integer :: s, jj
      k(0, :) = f0
      do s = 1, 5
        yst = y
        do jj = 0, s - 1
          yst = yst + h * d5_a(s, jj) * k(jj, :)
        end do
        k(s, :) = rhs(t + d5_c(s) * h, yst)
      end do
      ynew = y
      do jj = 0, 5
        ynew = ynew + h * d5_b(jj) * k(jj, :)
      end do
      fnew = rhs(t + h, ynew)
      k(6, :) = fnew
      stats%nfev = stats%nfev + 6
      e = 0.0_dp
      do jj = 0, 6
        e = e + h * d5_e(jj) * k(jj, :)
      end do
      sk = scale_of(y, ynew)
      errn = sqrt(sum((e / sk)**2) / 2.0_dp)
    end subroutine step5

    subroutine step853(errn)
      real(dp), intent(out) :: errn
      real(dp) :: e3(2), e5(2)
      call dop853_step_2(m, t, y, f0, h, k, ynew, fnew, e3, e5)
      stats%nfev = stats%nfev + 12
      errn = dop853_error_norm(h, e3, e5, scale_of(y, ynew))
    end subroutine step853

    !> Coefficients of the dense output on the accepted step [t, t + h].
    subroutine dense_coefficients()
      real(dp) :: yst(2), dy(2)
      integer :: s, jj
      if (method == m_dop853) then
        do s = 13, 15
          yst = y
          do jj = 0, s - 1
            yst = yst + h * d8_a(s, jj) * k(jj, :)
          end do
          k(s, :) = rhs(t + d8_c(s) * h, yst)
        end do
        stats%nfev = stats%nfev + 3
        dy = ynew - y
        cont(:, 0) = dy
        cont(:, 1) = h * k(0, :) - dy
        cont(:, 2) = 2.0_dp * dy - h * (k(0, :) + k(12, :))
        do s = 0, 3
          yst = 0.0_dp
          do jj = 0, 15
            yst = yst + d8_d(s, jj) * k(jj, :)
          end do
          cont(:, 3 + s) = h * yst
        end do
      else
        do s = 0, 3
          yst = 0.0_dp
          do jj = 0, 6
            yst = yst + d5_p(jj, s) * k(jj, :)
          end do
          cont(:, s) = h * yst
        end do
      end if
    end subroutine dense_coefficients

    !> The state at t + x h, 0 <= x <= 1.
    function dense(xx) result(yo)
      real(dp), intent(in) :: xx
      real(dp) :: yo(2)
      integer :: s
      if (xx == 1.0_dp) then
        yo = ynew
        return
      end if
      if (method == m_dop853) then
        yo = 0.0_dp
        do s = 6, 0, -1
          yo = yo + cont(:, s)
          if (mod(6 - s, 2) == 0) then
            yo = yo * xx
          else
            yo = yo * (1.0_dp - xx)
          end if
        end do
        yo = yo + y
      else
        yo = xx * (cont(:, 0) + xx * (cont(:, 1) + xx * (cont(:, 2) + xx * cont(:, 3))))
        yo = yo + y
      end if
    end function dense

    function gfun(yv) result(g)
      real(dp), intent(in) :: yv(2)
      real(dp) :: g
      select case (ev%kind)
      case (1)
        g = yv(2)
      case (2)
        g = yv(1) - ev%level
      case (3)
        g = sin(0.5_dp * (yv(1) - ev%level))
      case (4)
        g = yv(2)**2 + m%eps * cos(yv(1))
      case default
        g = 0.0_dp
      end select
    end function gfun

    !> Sample g at x = 1/4, 1/2, 3/4, 1 of the step.  In each quarter, a sign
    !> change of g is a root; without one, a sign change of g' means g has an
    !> extremum inside, which is located and checked, so that two roots close
    !> together (theta grazing a level near a turning point) are both found.
    !> A zero at the start of the step (g exactly 0 there) is not a new root:
    !> the sign carried is the last nonzero one.
    subroutine locate_events(stop_now)
      logical, intent(out) :: stop_now
      real(dp) :: xa, xb, ga, gb, da, db, xm, gm
      integer :: q
      stop_now = .false.
      xa = 0.0_dp
      ga = gprev
      da = dgfun(0.0_dp)
      do q = 1, 4
        xb = 0.25_dp * q
        gb = gfun(dense(xb))
        db = dgfun(xb)
        if (ga /= 0.0_dp .and. gb /= 0.0_dp .and. sign(1.0_dp, ga) == sign(1.0_dp, gb) .and. &
            da /= 0.0_dp .and. db /= 0.0_dp .and. sign(1.0_dp, da) /= sign(1.0_dp, db)) then
          xm = root_of(2, xa, da, xb, db)
          gm = gfun(dense(xm))
          if (gm == 0.0_dp .or. sign(1.0_dp, gm) /= sign(1.0_dp, ga)) then
            call record(xa, ga, xm, gm, stop_now)
            if (stop_now) return
            if (gm /= 0.0_dp) then
              call record(xm, gm, xb, gb, stop_now)
              if (stop_now) return
            end if
          end if
        else
          call record(xa, ga, xb, gb, stop_now)
          if (stop_now) return
        end if
        if (gb /= 0.0_dp) ga = gb
        xa = xb
        da = db
      end do
      gprev = ga
    end subroutine locate_events

    !> If g changes sign (or reaches 0) from ga on [xa, xb], refine and store the event.
    subroutine record(xa, ga, xb, gb, stop_now)
      real(dp), intent(in) :: xa, ga, xb, gb
      logical, intent(inout) :: stop_now
      real(dp) :: xr
      if (ga == 0.0_dp) return
      if (gb /= 0.0_dp .and. sign(1.0_dp, ga) == sign(1.0_dp, gb)) return
      if (ev%direction > 0 .and. ga > 0.0_dp) return
      if (ev%direction < 0 .and. ga < 0.0_dp) return
      xr = xb
      if (gb /= 0.0_dp) xr = root_of(1, xa, ga, xb, gb)
      if (nev < size(tev)) then
        nev = nev + 1
        tev(nev) = t + xr * h
        yy = dense(xr)
        thev(nev) = yy(1); vev(nev) = yy(2)
      end if
      if (ev%terminal) stop_now = .true.
    end subroutine record

    !> Root of g (which = 1) or of g' (which = 2) on [xa, xb] with a sign change:
    !> the Illinois method (regula falsi halving the stale end's value).
    function root_of(which, xa, fa, xb, fb) result(xr)
      integer, intent(in) :: which
      real(dp), intent(in) :: xa, fa, xb, fb
      real(dp) :: xr, lo, hi, flo, fhi, fr, side
      integer :: it
      lo = xa; hi = xb; flo = fa; fhi = fb
      side = 0.0_dp
      xr = hi
      do it = 1, 200
        xr = (lo * fhi - hi * flo) / (fhi - flo)
        if (which == 1) then
          fr = gfun(dense(xr))
        else
          fr = dgfun(xr)
        end if
        if (fr == 0.0_dp .or. abs(hi - lo) * abs(h) <= 4.0_dp * epsilon(1.0_dp) * max(abs(t), abs(h))) exit
        if (sign(1.0_dp, fr) == sign(1.0_dp, fhi)) then
          hi = xr; fhi = fr
          if (side < 0.0_dp) flo = 0.5_dp * flo
          side = -1.0_dp
        else
          lo = xr; flo = fr
          if (side > 0.0_dp) fhi = 0.5_dp * fhi
          side = 1.0_dp
        end if
      end do
    end function root_of

    !> dg/dt along the dense output.
    function dgfun(xx) result(dg)
      real(dp), intent(in) :: xx
      real(dp) :: dg, yv(2)
      yv = dense(xx)
      select case (ev%kind)
      case (1)
        dg = accel(m, t + xx * h, yv(1), yv(2))
      case (2)
        dg = yv(2)
      case (3)
        dg = 0.5_dp * cos(0.5_dp * (yv(1) - ev%level)) * yv(2)
      case (4)
        dg = yv(2) * (2.0_dp * accel(m, t + xx * h, yv(1), yv(2)) - m%eps * sin(yv(1)))
      case default
        dg = 0.0_dp
      end select
    end function dgfun

  end subroutine run_adaptive

end module pendula_integrators
