!> Dry (Coulomb) friction on the rigid pendulum in uniform gravity: the exact
!> energy balance between turning points.
!>
!> theta'' = -eps sin(theta) + tau - mu sgn(theta') while the bob moves.  On a
!> stretch of constant sign s of theta' the work done from theta_a to theta is
!>   K(theta) = v_a^2/2 + eps (cos theta - cos theta_a) + (tau - mu s)(theta - theta_a),
!> the kinetic energy v^2/2 there, so a turning point theta_b (v = 0) is a root
!> of K: with v_a = 0 and tau = 0, eps (cos theta_b - cos theta_a) = mu |theta_b -
!> theta_a|.  At a turning point the bob sticks for good when |eps sin theta_b -
!> tau| <= mu (static = kinetic coefficient), and otherwise starts back with
!> s = sgn(tau - eps sin theta_b).  The time of a stretch is the integral of
!> dtheta / sqrt(2 K).  Both by GSL: the roots by Brent's method on the
!> divided difference G_b(theta) = K(theta) / (theta - theta_b) (exact, well
!> conditioned: K(theta) = (theta - theta_b) G_b(theta) with
!>   G_b(theta) = -eps sin((theta + theta_b)/2) sinc((theta - theta_b)/2) + tau - mu s),
!> the times by QAWS with the inverse square-root weights of the turning points.
!> No module state.
module pendula_friction
  use, intrinsic :: iso_c_binding, only: c_double, c_int, c_ptr, c_funptr, c_funloc, c_loc, c_f_pointer
  use pendula_kinds, only: dp, nan_dp, pi
  implicit none
  private
  public :: friction_turning, gsl_root, gsl_qaws

  !> status of friction_turning
  integer, parameter, public :: fr_ok = 0, fr_bad_input = 1, fr_runs_away = 2, fr_too_many = 3, &
    fr_gsl_failed = 4

  interface
    !> GSL's Brent root finder on f(x, ctx) over [lo, hi] (kernel/glue/pendula_gsl_solve.c)
    function gsl_root(f, ctx, lo, hi, xtol, maxit, root) bind(C, name="pendula_gsl_root") result(st)
      import :: c_funptr, c_ptr, c_double, c_int
      type(c_funptr), value, intent(in) :: f
      type(c_ptr), value, intent(in) :: ctx
      real(c_double), value, intent(in) :: lo, hi, xtol
      integer(c_int), value, intent(in) :: maxit
      real(c_double), intent(out) :: root
      integer(c_int) :: st
    end function gsl_root
    !> GSL's QAWS: the integral of f(x, ctx) (x - a)^alpha (b - x)^beta over [a, b]
    function gsl_qaws(f, ctx, a, b, alpha, beta, epsrel, res, abserr) bind(C, name="pendula_gsl_qaws") result(st)
      import :: c_funptr, c_ptr, c_double, c_int
      type(c_funptr), value, intent(in) :: f
      type(c_ptr), value, intent(in) :: ctx
      real(c_double), value, intent(in) :: a, b, alpha, beta, epsrel
      real(c_double), intent(out) :: res, abserr
      integer(c_int) :: st
    end function gsl_qaws
  end interface

  !> One stretch of constant sign s from theta_a (speed v_a) to the turning point theta_b.
  type :: stretch_t
    real(dp) :: eps = 1.0_dp, tau = 0.0_dp, mu = 0.0_dp, s = 1.0_dp
    real(dp) :: tha = 0.0_dp, va = 0.0_dp, thb = 0.0_dp
  end type stretch_t

  !> angular step of the search for the next turning point (a root of K between two samples
  !> is bracketed; two roots closer than this, a grazing pass near the top, would be missed)
  real(dp), parameter :: search_step = pi / 64.0_dp
  !> the farthest the search goes before calling the motion a runaway (radians)
  real(dp), parameter :: search_limit = 2.0e4_dp

contains

  !> The turning points of the rigid pendulum with dry friction mu > 0 (and a constant torque
  !> tau), from (theta0, v0) at t = 0: times(1:n), angles(1:n) where v = 0 (theta0 itself first
  !> when v0 = 0), stuck: whether the bob sticks at the last one (for good: no drive).
  !> status fr_ok; fr_bad_input; fr_runs_away (a stretch passes search_limit radians: the torque
  !> keeps the bob turning); fr_too_many (more than size(times) turning points before it sticks,
  !> the first size(times) returned); fr_gsl_failed.
  subroutine friction_turning(eps, tau, mu, theta0, v0, times, angles, n, stuck, status)
    real(dp), intent(in) :: eps, tau, mu, theta0, v0
    real(dp), intent(out) :: times(:), angles(:)
    integer, intent(out) :: n, status
    logical, intent(out) :: stuck
    type(stretch_t), target :: st
    real(dp) :: t, th, f
    times = nan_dp; angles = nan_dp
    n = 0; stuck = .false.; status = fr_ok
    if (.not. (eps > 0 .and. mu > 0 .and. abs(tau) <= huge(1.0_dp) .and. abs(theta0) <= huge(1.0_dp) .and. &
               abs(v0) <= huge(1.0_dp) .and. mu <= huge(1.0_dp) .and. eps <= huge(1.0_dp))) then
      status = fr_bad_input; return
    end if
    t = 0.0_dp; th = theta0
    st%eps = eps; st%tau = tau; st%mu = mu
    if (v0 /= 0.0_dp) then
      st%s = sign(1.0_dp, v0); st%tha = theta0; st%va = v0
      call one_stretch()
      if (status /= fr_ok) return
    end if
    do
      if (n >= size(times)) then
        status = fr_too_many; return
      end if
      n = n + 1
      times(n) = t; angles(n) = th
      f = tau - eps * sin(th)
      if (abs(f) <= mu) then
        stuck = .true.; return
      end if
      st%s = sign(1.0_dp, f); st%tha = th; st%va = 0.0_dp
      call one_stretch()
      if (status /= fr_ok) return
    end do

  contains

    !> From st%tha (speed st%va) to the next turning point: th, and t advanced by the stretch's time.
    subroutine one_stretch()
      real(dp) :: lo, hi, glo, ghi, root, res, err, half
      integer :: k, s1, s2, s3
      ! bracket: s G_a (or K when v_a /= 0) turns from > 0 to <= 0 along s
      lo = st%tha; glo = 1.0_dp
      do k = 1, ceiling(search_limit / search_step)
        hi = st%tha + st%s * search_step * k
        ghi = k_over(st, hi)
        if (ghi <= 0.0_dp) exit
        lo = hi; glo = ghi
      end do
      if (ghi > 0.0_dp) then
        status = fr_runs_away; return
      end if
      s1 = gsl_root(c_funloc(k_over_c), c_loc(st), min(lo, hi), max(lo, hi), 0.0_dp, 200, root)
      if (s1 /= 0) then
        status = fr_gsl_failed; return
      end if
      st%thb = root
      ! the time: QAWS with (x)^(-1/2) at a turning start, (L - x)^(-1/2) at the end; the
      ! integrand split at the middle so that each half divides K by the factor vanishing there
      half = 0.5_dp * abs(root - st%tha)
      s2 = gsl_qaws(c_funloc(speed_factor_a), c_loc(st), 0.0_dp, half, merge(-0.5_dp, 0.0_dp, st%va == 0.0_dp), &
                    0.0_dp, 1.0e-13_dp, res, err)
      t = t + res
      s3 = gsl_qaws(c_funloc(speed_factor_b), c_loc(st), half, 2.0_dp * half, 0.0_dp, -0.5_dp, 1.0e-13_dp, &
                    res, err)
      t = t + res
      if (s2 /= 0 .or. s3 /= 0) then
        status = fr_gsl_failed; return
      end if
      th = root
    end subroutine one_stretch
  end subroutine friction_turning

  !> sinc(x) = sin(x)/x
  pure elemental function sinc(x) result(y)
    real(dp), intent(in) :: x
    real(dp) :: y
    if (abs(x) < 1.0e-4_dp) then
      y = 1.0_dp - x * x / 6.0_dp
    else
      y = sin(x) / x
    end if
  end function sinc

  !> (K(theta) - K(theta_c)) / (theta - theta_c): -eps sin((theta + theta_c)/2) sinc((theta - theta_c)/2)
  !> + tau - mu s (the divided difference of K, exact for theta = theta_c too).
  pure function divided(st, th, thc) result(g)
    type(stretch_t), intent(in) :: st
    real(dp), intent(in) :: th, thc
    real(dp) :: g
    g = -st%eps * sin(0.5_dp * (th + thc)) * sinc(0.5_dp * (th - thc)) + st%tau - st%mu * st%s
  end function divided

  !> The bracketing function of the next turning point at theta: s G_a(theta) when the stretch
  !> starts at rest (K = (theta - theta_a) G_a), K(theta) itself otherwise.
  pure function k_over(st, th) result(g)
    type(stretch_t), intent(in) :: st
    real(dp), intent(in) :: th
    real(dp) :: g
    if (st%va == 0.0_dp) then
      g = st%s * divided(st, th, st%tha)
    else
      g = 0.5_dp * st%va**2 + (th - st%tha) * divided(st, th, st%tha)
    end if
  end function k_over

  function k_over_c(th, ctx) bind(C) result(g)
    real(c_double), value, intent(in) :: th
    type(c_ptr), value, intent(in) :: ctx
    real(c_double) :: g
    type(stretch_t), pointer :: st
    call c_f_pointer(ctx, st)
    g = k_over(st, th)
  end function k_over_c

  !> The smooth factor of 1/v on the first half, x = |theta - theta_a|: 1/sqrt(2 k_over), which is
  !> sqrt(x / (2K)) from rest (K = (theta - theta_a) G_a) and 1/sqrt(2K) with a starting speed.
  function speed_factor_a(x, ctx) bind(C) result(f)
    real(c_double), value, intent(in) :: x
    type(c_ptr), value, intent(in) :: ctx
    real(c_double) :: f
    type(stretch_t), pointer :: st
    call c_f_pointer(ctx, st)
    f = 1.0_dp / sqrt(2.0_dp * k_over(st, st%tha + st%s * x))
  end function speed_factor_a

  !> The smooth factor of 1/v on the second half: sqrt((L - x) / (2K)), K = (theta - theta_b) G_b.
  function speed_factor_b(x, ctx) bind(C) result(f)
    real(c_double), value, intent(in) :: x
    type(c_ptr), value, intent(in) :: ctx
    real(c_double) :: f
    type(stretch_t), pointer :: st
    call c_f_pointer(ctx, st)
    f = 1.0_dp / sqrt(-2.0_dp * st%s * divided(st, st%tha + st%s * x, st%thb))
  end function speed_factor_b

end module pendula_friction
