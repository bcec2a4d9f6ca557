!> Equilibria of the autonomous models and their linear stability.
!>
!> Every model here reduces near a rest point to one coordinate x with
!>   x'' = a(x) - beta x',
!> so an equilibrium is a root of a(x) = 0 and its linearisation
!>   lambda^2 + beta lambda + c = 0,   c = -a'(x*),
!> has eigenvalues lambda = (-beta +- sqrt(beta^2 - 4 c)) / 2 (Suzuki & Suzuki,
!> section 7.1: the points 2 n pi are stable spirals, the odd multiples of pi
!> saddles, lambda^2 + beta lambda -+ eps = 0 for the untorqued rigid pendulum).
!> c < 0 is a saddle; c > 0 a centre (beta = 0), a spiral (beta^2 < 4 c) or a
!> node, stable for beta > 0; c = 0 the saddle-node where two equilibria merge.
!>
!> The models:
!>  - rigid pendulum, uniform field, torque tau: a = tau - eps sin(theta), so
!>    theta* = asin(tau/eps) (c = eps cos theta* > 0) and pi - asin(tau/eps)
!>    (c < 0), each + 2 pi n; none when |tau| > eps.  cos theta* is formed as
!>    sqrt((1 - r)(1 + r)), r = tau/eps, with 1 -+ r = (eps -+ tau)/eps, and
!>    theta* = atan2(r, cos theta*): well conditioned up to |tau| = eps.
!>  - cycloidal guide (Huygens; pendula_cycloid): along the path s'' = tau -
!>    w2 s - beta s', one equilibrium s* = tau / w2, theta* = asin(s*/(4 r)),
!>    c = w2, when it lies strictly between the cusps.
!>  - non-uniform gravity (pendula_gravity): a = tau - eps G(w) sin(theta),
!>    G > 0; without torque theta* = 0 (c = V''(0)) and pi (c = -|V''(pi)|),
!>    with a torque the roots of a(theta) are bracketed on a grid of
!>    n_scan points per turn and refined by safeguarded Newton on the exact
!>    slope a'(theta) (a root where a only touches 0 between two grid points,
!>    the saddle-node itself, is not found: it is a single value of tau).
!>
!> Plain-argument procedures only; no module state.
module pendula_equilibria
  use pendula_kinds, only: dp, pi, pi_lo, two_pi, nan_dp
  use pendula_gravity, only: gravity_accel, gravity_check, gk_uniform, gk_inverse_square, gk_linear, gs_ok
  implicit none
  private
  public :: linear_stability, rigid_equilibria, cycloid_equilibrium, field_equilibria, field_slope, &
    model_equilibria

  !> kinds of equilibrium (the linearisation's phase portrait)
  integer, parameter, public :: ek_stable_node = 1, ek_stable_spiral = 2, ek_centre = 3, ek_saddle = 4, &
    ek_unstable_node = 5, ek_unstable_spiral = 6, ek_saddle_node = 7
  !> status codes
  integer, parameter, public :: eq_ok = 0, eq_bad_param = 1, eq_too_many = 2
  !> grid points per turn for bracketing the torqued non-uniform field's roots
  integer, parameter :: n_scan = 4096
  !> the models that have equilibria (the autonomous ones)
  integer, parameter, public :: em_rigid = 1, em_cord = 2, em_cycloid = 3

contains

  !> Eigenvalues (re, im) of lambda^2 + beta lambda + c = 0, largest real
  !> part first, and the kind of the rest point.  The real pair is formed
  !> without cancellation (q = -(beta + sign(beta) sqrt(disc)) / 2, c / q).
  elemental subroutine linear_stability(beta, c, re1, im1, re2, im2, kind)
    real(dp), intent(in) :: beta, c
    real(dp), intent(out) :: re1, im1, re2, im2
    integer, intent(out) :: kind
    real(dp) :: disc, s, q, l1, l2, sc
    ! scaled by sc = max(|beta|, 2 sqrt|c|): beta^2 - 4 c neither overflows (beta = 1e200) nor
    ! loses c next to a huge beta (the small root c / q keeps it)
    sc = max(abs(beta), 2.0_dp * sqrt(abs(c)))
    if (sc > 0.0_dp) then
      disc = (beta / sc)**2 - 4.0_dp * ((c / sc) / sc)
    else
      disc = 0.0_dp
    end if
    if (disc >= 0.0_dp) then
      s = sc * sqrt(disc)
      q = -0.5_dp * (beta + sign(s, beta))
      l1 = q
      if (q /= 0.0_dp) then
        l2 = c / q
      else
        l2 = 0.0_dp
      end if
      re1 = max(l1, l2); re2 = min(l1, l2)
      im1 = 0.0_dp; im2 = 0.0_dp
    else
      re1 = -0.5_dp * beta; re2 = re1
      im1 = 0.5_dp * sc * sqrt(-disc); im2 = -im1
    end if
    if (c < 0.0_dp) then
      kind = ek_saddle
    else if (c == 0.0_dp) then
      kind = ek_saddle_node
    else if (beta == 0.0_dp) then
      kind = ek_centre
    else if (beta > 0.0_dp) then
      kind = merge(ek_stable_spiral, ek_stable_node, disc < 0.0_dp)
    else
      kind = merge(ek_unstable_spiral, ek_unstable_node, disc < 0.0_dp)
    end if
  end subroutine linear_stability

  !> The copies x + 2 pi n (n whole) with lo < x + 2 pi n <= hi, appended to
  !> theta(count+1:) with the slope c; eq_too_many when they do not fit.
  pure subroutine append_copies(x, c, lo, hi, theta, cs, count, status)
    real(dp), intent(in) :: x, c, lo, hi
    real(dp), intent(inout) :: theta(:), cs(:)
    integer, intent(inout) :: count, status
    real(dp) :: n1, n2, n, y
    integer :: i, ncopies
    ! whole numbers around (lo - x) / 2 pi and (hi - x) / 2 pi, one beyond each
    ! end (the test below decides), in floating point: no integer overflow
    n1 = aint((lo - x) / two_pi) - 2.0_dp
    n2 = aint((hi - x) / two_pi) + 2.0_dp
    ! beyond 2^50 turns n + 1 is no longer exact enough to count copies (and an
    ! angle of 2^52 has no fractional digits left): refused, never a long loop
    if (.not. (abs(n1) < 2.0_dp**50 .and. abs(n2) < 2.0_dp**50)) then
      status = eq_bad_param
      return
    end if
    if (n2 - n1 > real(size(theta), dp) + 4.0_dp) then
      status = eq_too_many
      return
    end if
    ncopies = int(n2 - n1)
    do i = 0, ncopies
      n = n1 + real(i, dp)
      ! 2 pi n in two parts: the copy is the nearest double to x + 2 pi n
      y = x + (n * two_pi + n * (2.0_dp * pi_lo))
      if (y > lo .and. y <= hi) then
        if (count >= size(theta)) then
          status = eq_too_many
          return
        end if
        count = count + 1
        theta(count) = y
        cs(count) = c
      end if
    end do
  end subroutine append_copies

  !> Equilibria of the rigid pendulum in the uniform field with torque tau,
  !> in lo < theta <= hi, sorted; c = -a'(theta*) for each.
  pure subroutine rigid_equilibria(eps, tau, lo, hi, theta, cs, count, status)
    real(dp), intent(in) :: eps, tau, lo, hi
    real(dp), intent(out) :: theta(:), cs(:)
    integer, intent(out) :: count, status
    real(dp) :: r, a, cosa
    count = 0
    status = eq_ok
    theta = nan_dp; cs = nan_dp
    if (.not. (eps > 0.0_dp .and. eps < huge(eps)) .or. .not. (abs(tau) < huge(tau)) .or. &
        .not. (lo < hi) .or. .not. (abs(lo) < huge(lo) .and. abs(hi) < huge(hi))) then
      status = eq_bad_param
      return
    end if
    r = tau / eps
    if (abs(r) > 1.0_dp) return
    ! cos(theta*) = sqrt((1 - r)(1 + r)) with 1 -+ r = (eps -+ tau) / eps: exact
    ! differences (Sterbenz) where they cancel, so that theta* = atan2(r, cos)
    ! stays accurate next to |tau| = eps, where asin(r) would magnify r's rounding
    cosa = sqrt(((eps - tau) / eps) * ((eps + tau) / eps))
    a = atan2(r, cosa)
    cosa = eps * cosa
    call append_copies(a, cosa, lo, hi, theta, cs, count, status)
    if (cosa > 0.0_dp) then
      ! pi - a in two parts (pi_lo keeps the saddle at the nearest double)
      call append_copies((pi - a) + pi_lo, -cosa, lo, hi, theta, cs, count, status)
    end if
    if (status == eq_ok) call sort_pairs(theta(1:count), cs(1:count))
  end subroutine rigid_equilibria

  !> The cycloidal guide's one equilibrium theta* = asin(tau / (w2 4 r)), c = w2
  !> (count 0 when it would lie at or beyond a cusp).
  pure subroutine cycloid_equilibrium(eps, r, tau, theta, c, count, status)
    real(dp), intent(in) :: eps, r, tau
    real(dp), intent(out) :: theta, c
    integer, intent(out) :: count, status
    real(dp) :: w2, x
    count = 0; theta = nan_dp; c = nan_dp
    status = eq_bad_param
    if (.not. (eps > 0.0_dp .and. eps < huge(eps) .and. r > 0.0_dp .and. r < huge(r) &
               .and. abs(tau) < huge(tau))) return
    status = eq_ok
    w2 = eps / (4.0_dp * r)
    ! s* / (4 r) = tau / (w2 4 r) = tau / eps: the guide's radius cancels
    x = tau / eps
    if (.not. (abs(x) < 1.0_dp)) return
    theta = asin(x)
    c = w2
    count = 1
  end subroutine cycloid_equilibrium

  !> a'(theta) of the field's acceleration a = -V'(theta) (exact derivative):
  !>   uniform       -eps cos(theta)
  !>   inverse-square -eps d (d-1)^2 (cos(theta) / rho^3 - 3 d sin(theta)^2 / rho^5)
  !>   linear        -eps ((1 - 2 kappa w) cos(theta) - kappa sin(theta)^2)
  elemental function field_slope(kind, par, eps, theta) result(s)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, theta
    real(dp) :: s, w, rho, sn, q
    sn = sin(theta)
    w = sin(0.5_dp * theta)**2
    select case (kind)
    case (gk_inverse_square)
      ! in the ratios q = (d - 1) / rho <= 1 and d / rho, so that a far field (d = 1e200) does not
      ! overflow: d (d-1)^2 / rho^3 = (d / rho) q^2, 3 d^2 (d-1)^2 / rho^5 = 3 (d / rho)^2 q^2 / rho
      rho = hypot(par - 1.0_dp, 2.0_dp * sqrt(par * w))
      q = (par - 1.0_dp) / rho
      s = -eps * (par / rho) * q * q * (cos(theta) - 3.0_dp * (par / rho) * sn * sn / rho)
    case (gk_linear)
      s = -eps * ((1.0_dp - 2.0_dp * par * w) * cos(theta) - par * sn * sn)
    case default
      s = -eps * cos(theta)
    end select
  end function field_slope

  !> Equilibria in the field kind (pendula_gravity) with torque tau, in
  !> lo < theta <= hi, sorted, with c = -a'(theta*).
  pure subroutine field_equilibria(kind, par, eps, tau, lo, hi, theta, cs, count, status)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, tau, lo, hi
    real(dp), intent(out) :: theta(:), cs(:)
    integer, intent(out) :: count, status
    real(dp) :: x0, x1, f0, f1, root
    integer :: i
    if (kind == gk_uniform) then
      call rigid_equilibria(eps, tau, lo, hi, theta, cs, count, status)
      return
    end if
    count = 0
    theta = nan_dp; cs = nan_dp
    status = eq_bad_param
    if (gravity_check(kind, par, eps) /= gs_ok .or. .not. (abs(tau) < huge(tau)) .or. .not. (lo < hi) &
        .or. .not. (abs(lo) < huge(lo) .and. abs(hi) < huge(hi))) return
    status = eq_ok
    if (tau == 0.0_dp) then
      ! a = -eps G(w) sin(theta), G > 0: the bottom and the top, exactly
      call append_copies(0.0_dp, -field_slope(kind, par, eps, 0.0_dp), lo, hi, theta, cs, count, status)
      call append_copies(pi + pi_lo, -field_slope(kind, par, eps, pi), lo, hi, theta, cs, count, status)
    else
      ! roots of tau + a(theta) on (-pi, pi]: bracket on the grid, then refine
      x0 = -pi
      f0 = tau + gravity_accel(kind, par, eps, x0)
      do i = 1, n_scan
        x1 = -pi + two_pi * real(i, dp) / real(n_scan, dp)
        f1 = tau + gravity_accel(kind, par, eps, x1)
        if (f1 == 0.0_dp) then
          root = x1
        else if ((f0 < 0.0_dp .and. f1 > 0.0_dp) .or. (f0 > 0.0_dp .and. f1 < 0.0_dp)) then
          root = refine_root(kind, par, eps, tau, x0, x1, f0)
        else
          x0 = x1; f0 = f1
          cycle
        end if
        call append_copies(root, -field_slope(kind, par, eps, root), lo, hi, theta, cs, count, status)
        if (status /= eq_ok) return
        x0 = x1; f0 = f1
      end do
    end if
    if (status == eq_ok) call sort_pairs(theta(1:count), cs(1:count))
  end subroutine field_equilibria

  !> Equilibria of a model (em_rigid: the rigid pendulum in field kind/par;
  !> em_cord: the same with the cord taut, so only where its tension at rest,
  !> eps G cos(theta*) per unit mass and length, is positive; em_cycloid: the
  !> guide of radius ratio r), in lo < theta <= hi, sorted, with c = -a'(theta*).
  pure subroutine model_equilibria(model, kind, par, eps, r, tau, lo, hi, theta, cs, count, status)
    integer, intent(in) :: model, kind
    real(dp), intent(in) :: par, eps, r, tau, lo, hi
    real(dp), intent(out) :: theta(:), cs(:)
    integer, intent(out) :: count, status
    integer :: i, j
    select case (model)
    case (em_rigid)
      call field_equilibria(kind, par, eps, tau, lo, hi, theta, cs, count, status)
    case (em_cord)
      call field_equilibria(kind, par, eps, tau, lo, hi, theta, cs, count, status)
      j = 0
      do i = 1, count
        if (cos(theta(i)) > 0.0_dp) then
          j = j + 1
          theta(j) = theta(i); cs(j) = cs(i)
        end if
      end do
      theta(j + 1:) = nan_dp; cs(j + 1:) = nan_dp
      count = j
    case (em_cycloid)
      theta = nan_dp; cs = nan_dp
      call cycloid_equilibrium(eps, r, tau, theta(1), cs(1), count, status)
    case default
      theta = nan_dp; cs = nan_dp
      count = 0
      status = eq_bad_param
    end select
  end subroutine model_equilibria

  !> The root of tau + a(theta) in the bracket [x0, x1] (f0 its value at x0):
  !> Newton on the exact slope, falling back to bisection whenever a step
  !> leaves the bracket; stops when the bracket or the step reaches 1 ulp.
  pure function refine_root(kind, par, eps, tau, x0, x1, f0) result(x)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, tau, x0, x1, f0
    real(dp) :: x, a, b, fa, f, d, xn
    integer :: it
    a = x0; b = x1; fa = f0
    x = 0.5_dp * (a + b)
    do it = 1, 200
      f = tau + gravity_accel(kind, par, eps, x)
      if (f == 0.0_dp) return
      if ((f < 0.0_dp) .eqv. (fa < 0.0_dp)) then
        a = x; fa = f
      else
        b = x
      end if
      d = field_slope(kind, par, eps, x)
      xn = x - f / d
      if (.not. (xn > min(a, b) .and. xn < max(a, b))) xn = 0.5_dp * (a + b)
      if (abs(xn - x) <= 2.0_dp * spacing(x) .or. abs(b - a) <= 2.0_dp * spacing(x)) then
        x = xn
        return
      end if
      x = xn
    end do
  end function refine_root

  !> Insertion sort of theta with its c (a handful of entries).
  pure subroutine sort_pairs(theta, cs)
    real(dp), intent(inout) :: theta(:), cs(:)
    integer :: i, j
    real(dp) :: t, c
    do i = 2, size(theta)
      t = theta(i); c = cs(i)
      j = i - 1
      do while (j >= 1)
        if (theta(j) <= t) exit
        theta(j + 1) = theta(j); cs(j + 1) = cs(j)
        j = j - 1
      end do
      theta(j + 1) = t; cs(j + 1) = c
    end do
  end subroutine sort_pairs

end module pendula_equilibria
