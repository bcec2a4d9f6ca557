!> Dry (Coulomb) friction on the rigid pendulum in uniform gravity: the exact
!> energy balance between turning points.
!>
!> theta'' = -eps sin(theta) + tau - mu sgn(theta') while the bob moves.  On a
!> stretch of constant sign s of theta' from theta_a (speed v_a), written in the
!> distance travelled x = s (theta - theta_a) >= 0, the work done is
!>   K(x) = v_a^2/2 + x g(x),  g(x) = s G_a = -s eps sin(theta_a + s x/2) sinc(x/2) + s tau - mu,
!> the kinetic energy v^2/2 there (G_a the divided difference of the energy
!> balance, exact and well conditioned: no spurious root at x = 0).  The next
!> turning point x_b is the first root of K (of g when v_a = 0), found by GSL's
!> Brent method in x, so that a turning point 1e-11 away keeps its relative
!> accuracy.  At a turning point the bob sticks for good when
!> |eps sin theta_b - tau| <= mu (static = kinetic coefficient), and otherwise
!> starts back with s = sgn(tau - eps sin theta_b).
!>
!> Where the search looks: with c = s tau - mu < 0 (friction, or the torque,
!> against the motion) K(x) lies within 2 eps of v_a^2/2 + c x, so the root
!> lies in [(v_a^2/2 - 2 eps)/|c|, (v_a^2/2 + 2 eps)/|c|]; with c >= 0,
!> K(x + 2 pi) = K(x) + 2 pi c >= K(x), so a stretch without a root in its
!> first turn never ends (the torque keeps the bob turning).
!>
!> The time of a stretch, the integral of dx / sqrt(2 K), is split at x_b/2,
!> and each half is given to GSL's quadrature (QAWS without weights) with its
!> singularity taken out (the square-root singularity of 1/v at a turning
!> point, and its near singularity behind a slow start, are what an adaptive
!> rule could not resolve: QAWS with the turning points' weights failed on 43
!> of 54 slow starts and was 3e5 eps off from moving ones):
!>   end:   x = x_b - y^2, K = y^2 (-D_b), dx/sqrt(2K) = 2 dy / sqrt(-2 D_b),
!>          D_b the divided difference of K between x and x_b;
!>   start from rest: x = y^2, dx/sqrt(2K) = 2 dy / sqrt(2 g);
!>   start moving, accelerated (g0 = g(0) > 0): 1/sqrt(2K) has a near singularity at
!>          x = -x0, x0 = v_a^2/(2 g0), behind the start (1.8e-11 behind it at v_a = 2.7e-6),
!>          so the first half is integrated in pieces graded at x0 4^k, each at least a
!>          third of its length away from it (a substitution v_a^2 + 2 g0 x = (y + a)^2
!>          leaves complex branch points of the exact K at a distance |v_a| from y = 0);
!>   start moving, decelerated: K >= about v_a^2/4 on the first half, smooth as it is.
!> No module state.
module pendula_friction
  use, intrinsic :: iso_c_binding, only: c_double, c_int, c_ptr, c_funptr, c_funloc, c_loc, c_f_pointer
  use pendula_kinds, only: dp, nan_dp, pi
  implicit none
  private
  public :: friction_turning, gsl_root, gsl_qaws

  !> status of friction_turning
  integer, parameter, public :: fr_ok = 0, fr_bad_input = 1, fr_runs_away = 2, fr_too_many = 3, &
    fr_gsl_failed = 4, fr_too_far = 5

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

  !> One stretch of constant sign s from theta_a (speed v_a) to the turning point at the
  !> distance xb; g0 = g(0), the start's acceleration along s.
  type :: stretch_t
    real(dp) :: eps = 1.0_dp, tau = 0.0_dp, mu = 0.0_dp, s = 1.0_dp
    real(dp) :: tha = 0.0_dp, va = 0.0_dp, xb = 0.0_dp, g0 = 0.0_dp
    real(dp) :: sa = 0.0_dp, ca = 1.0_dp   !< sin and cos of theta_a
  end type stretch_t

  !> the longest step of the search for the next turning point (shorter where K could reach
  !> zero within it: see one_stretch)
  real(dp), parameter :: search_step = pi / 64.0_dp
  !> the longest stretch computed (radians): beyond it the bob does stop, but the time of
  !> so long a stretch (thousands of swings over the top) is not computed
  real(dp), parameter :: search_limit = 2.0e4_dp
  !> the relative accuracy asked of each half stretch's quadrature: the least GSL takes
  !> (50 DBL_EPSILON); on the smooth integrands the result is closer (the rule's error
  !> falls exponentially with the points, and the estimate is pessimistic)
  real(dp), parameter :: quad_rel = 1.2e-14_dp

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
      real(dp) :: lo, hi, ghi, root, res, err, half, c, a2, xfirst, xlast, xa, xe, piece, kx, kp, disc
      integer :: k, s1, s2, s3, s4
      logical :: found
      st%sa = sin(st%tha); st%ca = cos(st%tha)
      ! where the root can be (see the module's notes)
      c = st%s * st%tau - st%mu
      a2 = 0.5_dp * st%va**2
      if (c < 0.0_dp) then
        xfirst = max(0.0_dp, (a2 - 2.0_dp * st%eps) / (-c))
        xlast = (a2 + 2.0_dp * st%eps) / (-c)
        if (xfirst > search_limit) then
          status = fr_too_far; return
        end if
        xlast = min(xlast, search_limit)
      else
        xfirst = 0.0_dp
        xlast = 2.0_dp * pi + search_step
      end if
      ! bracket: g (or K when v_a /= 0) turns from > 0 to <= 0, in steps that cannot pass
      ! over a root (a dip of K between two samples, a grazing pass next to the start or the
      ! top, was missed with fixed steps and a later root taken): |K''| = |eps cos theta|
      ! <= eps, so from x with K > 0 and slope K' there is no root before the positive root
      ! of K + K' h - eps h^2/2, and surely one before the first root of K + K' h + eps h^2/2
      lo = max(0.0_dp, search_step * (floor(xfirst / search_step) - 1))
      kx = a2 + lo * g_of(st, lo)
      ghi = 1.0_dp
      found = .false.
      do k = 1, 8 * ceiling(xlast / search_step) + 10000
        if (lo > xlast) exit
        kp = -st%s * st%eps * sin(st%tha + st%s * lo) + c
        disc = kp * kp - 2.0_dp * st%eps * kx
        if (kp < 0.0_dp .and. disc >= 0.0_dp) then
          hi = lo + 2.0_dp * kx / (sqrt(disc) - kp)
          ghi = h_of(st, hi)
          if (ghi <= 0.0_dp) then
            found = .true.; exit
          end if
        end if
        if (kp < 0.0_dp) then
          hi = lo + min(search_step, 2.0_dp * kx / (sqrt(kp * kp + 2.0_dp * st%eps * kx) - kp))
        else
          hi = lo + min(search_step, (kp + sqrt(kp * kp + 2.0_dp * st%eps * kx)) / st%eps)
        end if
        if (.not. (hi > lo)) exit              ! a grazing touch below the resolution of x
        ghi = h_of(st, hi)
        if (ghi <= 0.0_dp) then
          found = .true.; exit
        end if
        lo = hi
        kx = a2 + lo * g_of(st, lo)
      end do
      if (.not. found) then
        if (lo <= xlast) then
          status = fr_gsl_failed            ! a grazing touch, or too many steps
        else if (c < 0.0_dp) then
          status = fr_too_far
        else
          status = fr_runs_away
        end if
        return
      end if
      s1 = gsl_root(c_funloc(h_c), c_loc(st), lo, hi, 0.0_dp, 200, root)
      if (s1 /= 0) then
        status = fr_gsl_failed; return
      end if
      st%xb = root
      st%g0 = g_of(st, 0.0_dp)
      half = 0.5_dp * root
      ! the first half (substitutions: see the module's notes)
      if (st%va == 0.0_dp) then
        s2 = gsl_qaws(c_funloc(start_rest), c_loc(st), 0.0_dp, sqrt(half), 0.0_dp, 0.0_dp, quad_rel, res, err)
      else if (st%g0 > 0.0_dp) then
        ! graded at x0 4^k, x0 = v_a^2 / (2 g0): each piece at least a third of its length
        ! from the near singularity at -x0
        res = 0.0_dp; s2 = 0
        xa = 0.0_dp; xe = 0.5_dp * st%va**2 / st%g0
        do while (s2 == 0)
          xe = min(xe, half)
          s4 = gsl_qaws(c_funloc(speed_inverse), c_loc(st), xa, xe, 0.0_dp, 0.0_dp, quad_rel, piece, err)
          s2 = accept(s4, piece, err)
          res = res + piece
          if (xe >= half) exit
          xa = xe; xe = 4.0_dp * xe
        end do
      else
        s2 = gsl_qaws(c_funloc(speed_inverse), c_loc(st), 0.0_dp, half, 0.0_dp, 0.0_dp, quad_rel, res, err)
        s2 = accept(s2, res, err)
      end if
      t = t + res
      s3 = gsl_qaws(c_funloc(end_half), c_loc(st), 0.0_dp, sqrt(root - half), 0.0_dp, 0.0_dp, quad_rel, res, err)
      s3 = accept(s3, res, err)
      t = t + res
      if (s2 /= 0 .or. s3 /= 0) then
        status = fr_gsl_failed; return
      end if
      th = st%tha + st%s * root
    end subroutine one_stretch
  end subroutine friction_turning

  !> GSL's status, except that a round-off report (the integrand smooth, the asked
  !> accuracy at what the sum can show) is accepted when the error estimate is below 1e-13.
  pure function accept(st, res, err) result(s)
    integer, intent(in) :: st
    real(dp), intent(in) :: res, err
    integer :: s
    integer, parameter :: gsl_eround = 18
    s = st
    if (st == gsl_eround .and. err <= 1.0e-13_dp * abs(res)) s = 0
  end function accept

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

  !> The divided difference of K between the distances x and z along the stretch:
  !> (K(x) - K(z)) / (x - z) = -s eps sin(theta_a + s (x + z)/2) sinc((x - z)/2) + s tau - mu
  !> (exact for x = z too); half = (x - z)/2 passed as formed by the caller.
  pure function divided(st, mid, half) result(g)
    type(stretch_t), intent(in) :: st
    real(dp), intent(in) :: mid, half   !< (x + z)/2 and (x - z)/2
    real(dp) :: g
    ! sin(theta_a + s mid) by the addition theorem: theta_a + s mid rounded would put an
    ! absolute error of ulp(theta_a)/2 into the sine, which g, of order mu - eps sin theta_a
    ! (small where friction just holds), magnified to 174 eps in a turning point 9e-11 away
    g = -st%s * st%eps * (st%sa * cos(mid) + st%s * st%ca * sin(mid)) * sinc(half) + st%s * st%tau - st%mu
  end function divided

  !> g(x) = K(x)/x - v_a^2/(2x), the divided difference of K between x and 0.
  pure function g_of(st, x) result(g)
    type(stretch_t), intent(in) :: st
    real(dp), intent(in) :: x
    real(dp) :: g
    g = divided(st, 0.5_dp * x, 0.5_dp * x)
  end function g_of

  !> The bracketing function of the next turning point at the distance x: g when the
  !> stretch starts at rest (K = x g), K itself otherwise.
  pure function h_of(st, x) result(h)
    type(stretch_t), intent(in) :: st
    real(dp), intent(in) :: x
    real(dp) :: h
    if (st%va == 0.0_dp) then
      h = g_of(st, x)
    else
      h = 0.5_dp * st%va**2 + x * g_of(st, x)
    end if
  end function h_of

  function h_c(x, ctx) bind(C) result(h)
    real(c_double), value, intent(in) :: x
    type(c_ptr), value, intent(in) :: ctx
    real(c_double) :: h
    type(stretch_t), pointer :: st
    call c_f_pointer(ctx, st)
    h = h_of(st, x)
  end function h_c

  !> From rest, x = y^2: 2 / sqrt(2 g(y^2)).
  function start_rest(y, ctx) bind(C) result(f)
    real(c_double), value, intent(in) :: y
    type(c_ptr), value, intent(in) :: ctx
    real(c_double) :: f
    type(stretch_t), pointer :: st
    call c_f_pointer(ctx, st)
    f = 2.0_dp / sqrt(2.0_dp * g_of(st, y * y))
  end function start_rest

  !> With a starting speed: 1 / sqrt(2K(x)) as it is.
  function speed_inverse(x, ctx) bind(C) result(f)
    real(c_double), value, intent(in) :: x
    type(c_ptr), value, intent(in) :: ctx
    real(c_double) :: f
    type(stretch_t), pointer :: st
    call c_f_pointer(ctx, st)
    f = 1.0_dp / sqrt(st%va**2 + 2.0_dp * x * g_of(st, x))
  end function speed_inverse

  !> Towards the turning point, x = x_b - y^2: 2 / sqrt(-2 D_b(x)).
  function end_half(y, ctx) bind(C) result(f)
    real(c_double), value, intent(in) :: y
    type(c_ptr), value, intent(in) :: ctx
    real(c_double) :: f, y2
    type(stretch_t), pointer :: st
    call c_f_pointer(ctx, st)
    y2 = y * y
    f = 2.0_dp / sqrt(-2.0_dp * divided(st, st%xb - 0.5_dp * y2, -0.5_dp * y2))
  end function end_half

end module pendula_friction
