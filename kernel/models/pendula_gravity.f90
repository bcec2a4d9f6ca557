!> Non-uniform gravity (Prusa & Tuma, task 4): the pendulum of length l in a
!> conservative field that is not uniform, still one-dimensional:
!>   theta'' = -V'(theta),   E = theta'^2 / 2 + V(theta),   V(0) = 0,
!> in units of m l^2, with eps = g / l and g the field strength at the lowest
!> point of the circle.  Both fields depend on theta through w = sin^2(theta/2)
!> only (V = f(w)) and reduce to the uniform field f = 2 eps w in a limit:
!>
!>  kind 1, 'inverse-square': a point mass at distance D = d l below the pivot
!>    (d > 1).  With rho^2 = (d-1)^2 + 4 d w (the bob's distance to it, in l),
!>    f = eps (d-1)^2 (1/(d-1) - 1/rho) = eps 4 d (d-1) w / (rho (rho + d - 1)),
!>    theta'' = -eps d (d-1)^2 sin(theta) / rho^3.   Uniform as d -> infinity.
!>  kind 2, 'linear': g falls off linearly with height h = l (1 - cos theta)
!>    above the lowest point, g(h) = g (1 - kappa h / l), kappa < 1/2 (so the
!>    field still points down at the top):  f = 2 eps (w - kappa w^2),
!>    theta'' = -eps (1 - 2 kappa w) sin(theta).   Uniform at kappa = 0.
!>  kind 0: uniform, f = 2 eps w.
!> The inverse-square formulas are written with a = d - 1, g = d / a and
!> r = rho / a = sqrt(1 + 4 g w / a), so that nothing overflows for any d up to
!> huge (at d = 1e300, g = r = 1 to the bit: the uniform field exactly):
!>    f = eps 4 g w / (r (r + 1)),  Q = eps 4 g / (r r_m (r + r_m)),  V' = eps g sin / r^3.
!>
!> One classifier for every field: the regime is the sign of the distance from
!> the separatrix,  f(1) - E = Q(w0, 1) cos^2(theta0/2) - v0^2/2,  formed in
!> double-double, and mc = (f(1) - E) / Q(m, 1) (libration) or (E - f(1)) / E
!> (rotation) from it.  For the uniform field Q = 2 eps and this is exactly the
!> exact pendulum's rule (orbit_setup of pendula_exact), which answers the
!> uniform field whole (orbit_period, orbit_theta_max): gravity_orbit and the
!> exact orbit give the same bits there.  For the other fields the same routine
!> reduces theta0 and gives cos^2(theta0/2) in double-double (a start at rest
!> with eps = 1: its mc is cos^2(theta0/2)), and Q(w0, 1) is formed in
!> double-double (gravity_q1_dd), so the distance keeps its digits next to the
!> separatrix and the top.
!>
!> Plain-argument procedures only (no scene type).
module pendula_gravity
  use pendula_kinds, only: dp, nan_dp, inf_dp, pi
  use pendula_elliptic, only: ellip_k, jacobi_sncndn
  use pendula_dd, only: two_sum, two_prod, dd_add, dd_mul, dd_div, dd_div_d, dd_sqrt
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_period, orbit_theta_max, &
    regime_libration, regime_separatrix
  implicit none
  private
  public :: gravity_check, gravity_f, gravity_q, gravity_potential, gravity_accel, gravity_energy, &
    gravity_orbit, gravity_h

  integer, parameter, public :: gk_uniform = 0, gk_inverse_square = 1, gk_linear = 2
  integer, parameter, public :: gr_libration = 0, gr_separatrix = 1, gr_rotation = 2
  integer, parameter, public :: gs_ok = 0, gs_bad_param = 1, gs_bad_state = 2, gs_no_convergence = 3, &
    gs_theta0_too_large = 4, gs_too_fast = 5, gs_out_of_range = 6

contains

  !> status of the field's parameters: gs_ok or gs_bad_param.
  pure function gravity_check(kind, par, eps) result(status)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps
    integer :: status
    status = gs_bad_param
    if (.not. (eps > 0.0_dp .and. eps < huge(eps))) return
    select case (kind)
    case (gk_uniform)
    case (gk_inverse_square)
      if (.not. (par > 1.0_dp .and. par < huge(par))) return
    case (gk_linear)
      if (.not. (par < 0.5_dp .and. par > -huge(par))) return
    case default
      return
    end select
    status = gs_ok
  end function gravity_check

  !> V as a function of w = sin^2(theta/2).
  elemental function gravity_f(kind, par, eps, w) result(f)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, w
    real(dp) :: f, r, g
    select case (kind)
    case (gk_inverse_square)
      g = par / (par - 1.0_dp)
      r = sqrt(1.0_dp + 4.0_dp * g * w / (par - 1.0_dp))
      f = eps * 4.0_dp * g * w / (r * (r + 1.0_dp))
    case (gk_linear)
      f = 2.0_dp * eps * (w - par * w * w)
    case default
      f = 2.0_dp * eps * w
    end select
  end function gravity_f

  !> The divided difference (f(wm) - f(w)) / (wm - w), formed without cancellation.
  elemental function gravity_q(kind, par, eps, w, wm) result(q)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, w, wm
    real(dp) :: q, r, rm, g
    select case (kind)
    case (gk_inverse_square)
      g = par / (par - 1.0_dp)
      r = sqrt(1.0_dp + 4.0_dp * g * w / (par - 1.0_dp))
      rm = sqrt(1.0_dp + 4.0_dp * g * wm / (par - 1.0_dp))
      q = eps * 4.0_dp * g / (r * rm * (r + rm))
    case (gk_linear)
      q = 2.0_dp * eps * (1.0_dp - par * (w + wm))
    case default
      q = 2.0_dp * eps
    end select
  end function gravity_q

  elemental function gravity_potential(kind, par, eps, theta) result(v)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, theta
    real(dp) :: v
    v = gravity_f(kind, par, eps, sin(0.5_dp * theta)**2)
  end function gravity_potential

  !> theta'' = -V'(theta)
  elemental function gravity_accel(kind, par, eps, theta) result(a)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, theta
    real(dp) :: a, r, w, g
    select case (kind)
    case (gk_inverse_square)
      w = sin(0.5_dp * theta)**2
      g = par / (par - 1.0_dp)
      r = sqrt(1.0_dp + 4.0_dp * g * w / (par - 1.0_dp))
      a = -eps * g * sin(theta) / r**3
    case (gk_linear)
      w = sin(0.5_dp * theta)**2
      a = -eps * (1.0_dp - 2.0_dp * par * w) * sin(theta)
    case default
      a = -eps * sin(theta)
    end select
  end function gravity_accel

  elemental function gravity_energy(kind, par, eps, theta, v) result(e)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, theta, v
    real(dp) :: e
    e = 0.5_dp * v * v + gravity_potential(kind, par, eps, theta)
  end function gravity_energy

  !> The integrand h(u) of t = int h du at the nodes u (see the module header):
  !> regime gr_libration: m = w_m, h = sqrt(2/Q(m sn^2 u, m));
  !> gr_rotation: m = m_r, h = sqrt(2/(E H(sn^2 u))).
  elemental function gravity_h(kind, par, eps, regime, m, mc, e, u) result(h)
    integer, intent(in) :: kind, regime
    real(dp), intent(in) :: par, eps, m, mc, e, u
    real(dp) :: h, sn, cn, dn, am, w, f1, de, hh, q1
    call jacobi_sncndn(u, m, mc, sn, cn, dn, am)
    if (regime == gr_libration) then
      if (kind == gk_linear) then
        ! Q = 2 eps (1 - kappa (w + w_m)) = 2 eps ((1 - 2 kappa) + kappa (dn^2 + mc)): no cancellation
        ! next to the top when kappa is next to 1/2
        h = sqrt(2.0_dp / (2.0_dp * eps * ((1.0_dp - 2.0_dp * par) + par * (dn * dn + mc))))
      else
        h = sqrt(2.0_dp / gravity_q(kind, par, eps, m * sn * sn, m))
      end if
    else
      w = sn * sn
      f1 = gravity_f(kind, par, eps, 1.0_dp)
      de = mc * e                    ! E - f(1) = mc E, without the cancellation of e - f1
      if (kind == gk_linear) then    ! Q(w, 1) = 2 eps ((1 - 2 kappa) + kappa cn^2)
        q1 = 2.0_dp * eps * ((1.0_dp - 2.0_dp * par) + par * cn * cn)
      else
        q1 = gravity_q(kind, par, eps, w, 1.0_dp)
      end if
      hh = (de + q1 * cn * cn) / (de + f1 * cn * cn)
      h = sqrt(2.0_dp / (e * hh))
    end if
  end function gravity_h

  !> The orbit through (theta0, v0): energy, regime, the elliptic parameter m (and its
  !> complement mc, formed without cancellation near the separatrix) of the
  !> substitution, K(m), the amplitude theta_max (libration; pi on the separatrix,
  !> inf for rotation) and the period T (libration) or the time of one turn
  !> (rotation); inf on the separatrix.  The trapezoid rule on [0, K] is doubled
  !> from 4 panels until two successive sums agree to 2 ulps (at most 2^20 panels:
  !> otherwise gs_no_convergence and T = NaN).  Most orbits need 16 to 512 panels;
  !> the inverse-square field with the mass close under the circle, d - 1 = delta,
  !> puts a branch point of h at distance ~delta/2 from the real u axis and needs
  !> ~K/delta panels: delta = 1e-4 takes 2^18, delta below ~2e-5 is refused.
  pure subroutine gravity_orbit(kind, par, eps, theta0, v0, e, regime, m, mc, kk, theta_max, period, status)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, theta0, v0
    real(dp), intent(out) :: e, m, mc, kk, theta_max, period
    integer, intent(out) :: regime, status
    real(dp) :: w0, f1, c, omc, s_old, s_new, sfac, g, qh, ql, dh, dl, ph, pl, ah, al, eu, xh, xl
    integer :: n, st, ie, je
    type(pendulum_orbit) :: o
    !> below this sin(theta0/2) and the amplitude are tiny: their squares underflow
    real(dp), parameter :: tiny_s = 2.0_dp**(-450)
    e = nan_dp; m = nan_dp; mc = nan_dp; kk = nan_dp; theta_max = nan_dp; period = nan_dp; regime = -1
    status = gravity_check(kind, par, eps)
    if (status /= gs_ok) return
    if (.not. (abs(theta0) < huge(theta0) .and. abs(v0) < huge(v0))) then
      status = gs_bad_state; return
    end if
    ! the inverse-square field with the mass beyond 2^60 l differs from the uniform one by less
    ! than 3 / d relative (O(w / d)): below a rounding, and its double-double forms would overflow
    ! near huge (Dekker's splitting): the uniform field answers it
    if (kind == gk_uniform .or. (kind == gk_inverse_square .and. par >= 2.0_dp**60)) then
      ! the exact pendulum answers the uniform field whole
      call orbit_setup(theta0, v0, eps, o, st)
      status = status_of(st)
      if (status /= gs_ok) return
      e = 0.5_dp * v0 * v0 + gravity_f(gk_uniform, par, eps, sin(0.5_dp * theta0)**2)
      if (abs(theta0) < tiny_s) e = 0.5_dp * v0 * v0 + (0.5_dp * eps * theta0) * theta0
      regime = o%regime
      m = o%m; mc = o%mch
      theta_max = orbit_theta_max(o)
      period = orbit_period(o)
      kk = o%plan%kh
      if (regime == regime_separatrix) kk = inf_dp
      return
    end if
    ! theta0 reduced and c^2 = cos^2(theta0/2) in double-double: the exact pendulum's set-up at
    ! rest with eps = 1 (its mc is then c^2)
    call orbit_setup(theta0, 0.0_dp, 1.0_dp, o, st)
    status = status_of(st)
    if (status == gs_ok .and. .not. (eps <= 1.0e300_dp)) status = gs_bad_param
    if (status == gs_ok .and. .not. (abs(v0) < 1.0e150_dp)) status = gs_too_fast
    if (status /= gs_ok) return
    ! everything in units of eps (V is proportional to eps; time scales as 1/sqrt(eps)), so that
    ! no product under- or overflows for any eps: eu = E / eps, the distance d = (f(1) - E) / eps
    w0 = sin(0.5_dp * theta0)**2
    ! v0^2 / (2 eps) in double-double, both scaled to [0.5, 1) by exact powers of two first
    ! (Dekker's splitting overflows beyond ~1e300), the quotient scaled back
    call two_prod(v0, v0, ph, pl)
    ie = exponent(ph); je = exponent(2.0_dp * eps)
    call dd_div_d(scale(ph, -ie), scale(pl, -ie), scale(2.0_dp * eps, -je), ah, al)
    ah = scale(ah, ie - je); al = scale(al, ie - je)
    eu = ah + gravity_f(kind, par, 1.0_dp, w0)
    e = eps * eu
    ! where sin^2(theta0/2) underflows (|theta0| < 2^-450), V = f'(0) eps theta0^2 / 4 to 2^-900,
    ! the products taken from eps down (E came out 0 for theta0 = 1e-160, eps = 1e100)
    if (abs(theta0) < tiny_s) e = 0.5_dp * v0 * v0 + ((0.25_dp * fp0() * eps) * theta0) * theta0
    f1 = gravity_f(kind, par, 1.0_dp, 1.0_dp)
    ! the distance from the separatrix (f(1) - E) / eps = Q(w0, 1) c^2 / eps - v0^2 / (2 eps)
    call gravity_q1_dd(kind, par, 1.0_dp, o%mch, o%mcl, qh, ql)
    call dd_mul(qh, ql, o%mch, o%mcl, xh, xl)
    call dd_add(xh, xl, -ah, -al, dh, dl)          ! (outputs never alias inputs)
    if (dh > 0.0_dp) then
      regime = gr_libration
      if (v0 == 0.0_dp) then
        m = w0                       ! exactly, when starting at rest
      else
        select case (kind)           ! invert f(m) = E without cancellation (or overflow)
        case (gk_inverse_square)
          ! m = E (2 - c) / (4 g (1 - c)^2), c = E / (eps a); with a = d - 1 and f(w0) = a - a / r0
          ! (units of eps) 1 - c = 1 / r0 - v0^2 / (2 eps a): for c > 1/2 its two terms are formed
          ! apart in double-double, so that nothing cancels as d -> 1, where c -> 1 (a - E, formed
          ! as it stands, cost theta_max 50 eps at d = 1.004); below, 1 - c itself (one rounding)
          c = eu / (par - 1.0_dp)
          g = par / (par - 1.0_dp)
          omc = 1.0_dp - c
          if (c > 0.5_dp) omc = one_minus_c_dd()
          m = eu * (2.0_dp - c) / (4.0_dp * g * omc**2)
        case default
          if (abs(par) <= 1.0_dp) then
            m = eu / (1.0_dp + sqrt(1.0_dp - 2.0_dp * par * eu))
          else                       ! sqrt(1 - 2 kappa eu) = sqrt|kappa| sqrt(1/|kappa| - 2 sgn(kappa) eu)
            m = eu / (1.0_dp + sqrt(abs(par)) * sqrt(1.0_dp / abs(par) - 2.0_dp * sign(1.0_dp, par) * eu))
          end if
        end select
      end if
      ! 1 - m = (f(1) - E) / Q(m, 1)
      if (v0 == 0.0_dp) then
        mc = o%mch + o%mcl           ! cos^2(theta0/2), rounded once
      else if (kind == gk_linear .and. par > 0.0_dp) then
        ! Q(m, 1) = 2 ((1 - 2 kappa) + kappa mc): mc solves 2 kappa mc^2 + 2 (1 - 2 kappa) mc = d,
        ! taken in its stable form (1 - kappa (m + 1) would cancel next to the top, kappa near 1/2)
        mc = (dh + dl) / ((1.0_dp - 2.0_dp * par) + sqrt((1.0_dp - 2.0_dp * par)**2 + 2.0_dp * par * (dh + dl)))
      else
        mc = (dh + dl) / gravity_q(kind, par, 1.0_dp, m, 1.0_dp)
      end if
      if (mc < 0.5_dp) m = 1.0_dp - mc         ! next to the top, m from its complement
      theta_max = 2.0_dp * atan2(sqrt(m), sqrt(mc))
      ! an amplitude below 2^-450: the field is harmonic to 2^-900, theta_max^2 = th0^2 + 2 v0^2 / (eps
      ! f'(0)), by hypot (m = theta_max^2 / 4 underflowed, and theta_max came out 0)
      if (m < tiny_s**2) theta_max = hypot((theta0 - o%offset) - o%offl, v0 * (sqrt(2.0_dp / fp0()) / sqrt(eps)))
      if (v0 == 0.0_dp) theta_max = abs((theta0 - o%offset) - o%offl)
      sfac = 4.0_dp
    else if (dh == 0.0_dp) then
      regime = gr_separatrix
      m = 1.0_dp
      mc = 0.0_dp
      kk = inf_dp
      theta_max = pi
      period = kk
      return
    else
      regime = gr_rotation
      mc = -(dh + dl) / eu           ! (E - f(1)) / E
      m = f1 / eu
      if (mc < 0.5_dp) m = 1.0_dp - mc
      theta_max = inf_dp
      sfac = 2.0_dp
    end if
    ! (at the bottom mc = Q(w0, 1) / Q(m, 1) rounds to either side of 1: it is 1 there)
    if (mc > 1.0_dp .and. mc <= 1.0_dp + 8.0_dp * epsilon(1.0_dp)) mc = 1.0_dp
    ! what double precision cannot hold for this field (a parameter so extreme that a quantity of
    ! the orbit under- or overflows): refused, never a wrong number
    if (.not. (m >= 0.0_dp .and. m <= 1.0_dp .and. mc > 0.0_dp .and. mc <= 1.0_dp .and. &
               abs(eu) < huge(eu) .and. abs(e) < huge(e) .and. qh > 0.0_dp .and. qh < huge(qh))) then
      status = gs_out_of_range
      e = nan_dp; m = nan_dp; mc = nan_dp; theta_max = nan_dp; regime = -1
      return
    end if
    if (m == 0.0_dp) then            ! at rest at the bottom: the small-oscillation limit
      kk = 0.5_dp * pi
      period = sfac * kk * gravity_h(kind, par, 1.0_dp, regime, m, mc, eu, 0.0_dp) / sqrt(eps)
      return
    end if
    kk = ellip_k(m, mc)
    n = 4
    s_old = trap(n)
    do
      n = 2 * n
      s_new = 0.5_dp * s_old + mid(n)
      if (abs(s_new - s_old) <= 2.0_dp * epsilon(1.0_dp) * abs(s_new)) exit
      if (n >= 1048576) then
        status = gs_no_convergence; period = nan_dp; return
      end if
      s_old = s_new
    end do
    period = sfac * s_new / sqrt(eps)
    if (.not. (period > 0.0_dp .and. period < huge(period))) then
      status = gs_out_of_range; period = nan_dp
    end if
  contains
    !> 1 - E / (eps a) = 1 / r0 - (v0^2 / (2 eps)) / a (inverse-square, a = d - 1) in double-double,
    !> rounded once: r0 = sqrt(1 + 4 g w0 / a), w0 = 1 - cos^2(theta0/2) from the set-up's mc
    pure real(dp) function one_minus_c_dd() result(x)
      real(dp) :: a1, a2, g1, g2, w1, w2, t1, t2, u1, u2, r1, r2, y1, y2
      call two_sum(par, -1.0_dp, a1, a2)                  ! a = d - 1
      call dd_div(par, 0.0_dp, a1, a2, g1, g2)            ! g = d / a
      call two_sum(1.0_dp, -o%mch, w1, w2)                ! w0 = 1 - c^2
      w2 = w2 - o%mcl
      call dd_mul(4.0_dp * g1, 4.0_dp * g2, w1, w2, t1, t2)
      call dd_div(t1, t2, a1, a2, u1, u2)                 ! 4 g w0 / a
      call dd_add(1.0_dp, 0.0_dp, u1, u2, t1, t2)
      call dd_sqrt(t1, t2, r1, r2)                        ! r0
      call dd_div(1.0_dp, 0.0_dp, r1, r2, t1, t2)         ! 1 / r0
      call dd_div(ah, al, a1, a2, u1, u2)                 ! (v0^2 / (2 eps)) / a
      call dd_add(t1, t2, -u1, -u2, y1, y2)
      x = y1 + y2
    end function one_minus_c_dd
    !> f'(0) in units of eps: 2 d / (d - 1) (inverse-square), 2 (linear, uniform)
    pure real(dp) function fp0()
      fp0 = 2.0_dp
      if (kind == gk_inverse_square) fp0 = 2.0_dp * par / (par - 1.0_dp)
    end function fp0
    !> trapezoid sum on [0, K] with n panels
    pure function trap(np) result(s)
      integer, intent(in) :: np
      real(dp) :: s, hu
      integer :: j
      hu = kk / np
      s = 0.5_dp * (gravity_h(kind, par, 1.0_dp, regime, m, mc, eu, 0.0_dp) + &
                    gravity_h(kind, par, 1.0_dp, regime, m, mc, eu, kk))
      do j = 1, np - 1
        s = s + gravity_h(kind, par, 1.0_dp, regime, m, mc, eu, j * hu)
      end do
      s = s * hu
    end function trap
    !> the new midpoints' contribution when n/2 panels are halved to n (compensated sum,
    !> so that rounding does not stall the 2-ulp convergence test at 10^5 panels)
    pure function mid(np) result(s)
      integer, intent(in) :: np
      real(dp) :: s, hu, c, y, tt
      integer :: j
      hu = kk / np
      s = 0.0_dp
      c = 0.0_dp
      do j = 1, np - 1, 2
        y = gravity_h(kind, par, 1.0_dp, regime, m, mc, eu, j * hu) - c
        tt = s + y
        c = (tt - s) - y
        s = tt
      end do
      s = s * hu
    end function mid
  end subroutine gravity_orbit

  !> gravity_orbit's status from the exact pendulum's set-up status.
  pure integer function status_of(st)
    integer, intent(in) :: st
    select case (st)
    case (0)
      status_of = gs_ok
    case (1)
      status_of = gs_bad_param
    case (4)
      status_of = gs_theta0_too_large
    case (5)
      status_of = gs_too_fast
    case default
      status_of = gs_bad_state
    end select
  end function status_of

  !> Q(w0, 1) = (f(1) - f(w0)) / (1 - w0) in double-double, from c^2 = 1 - w0 = cos^2(theta0/2)
  !> given in double-double (ch + cl).  Linear: 2 eps ((1 - 2 kappa) + kappa c^2).
  !> Inverse-square (a = d - 1, g = d / a, r1 = (d + 1) / a, r0 = sqrt(1 + 4 g w0 / a)):
  !> 4 eps g / (r0 r1 (r0 + r1)).  Uniform: 2 eps.
  pure subroutine gravity_q1_dd(kind, par, eps, ch, cl, qh, ql)
    integer, intent(in) :: kind
    real(dp), intent(in) :: par, eps, ch, cl
    real(dp), intent(out) :: qh, ql
    real(dp) :: ah, al, bh, bl, gh, gl, wh, wl, rh, rl, sh, sl, th, tl, uh, ul
    select case (kind)
    case (gk_linear)
      call two_sum(1.0_dp, -2.0_dp * par, ah, al)
      call dd_mul(par, 0.0_dp, ch, cl, bh, bl)
      call dd_add(ah, al, bh, bl, sh, sl)
      call dd_mul(sh, sl, 2.0_dp * eps, 0.0_dp, qh, ql)
    case (gk_inverse_square)
      call two_sum(par, -1.0_dp, ah, al)                  ! a = d - 1
      call dd_div(par, 0.0_dp, ah, al, gh, gl)            ! g = d / a
      call two_sum(1.0_dp, -ch, wh, wl)                   ! w0 = 1 - c^2
      wl = wl - cl
      ! (outputs never alias inputs: th, tl / uh, ul take turns)
      call dd_mul(4.0_dp * gh, 4.0_dp * gl, wh, wl, th, tl)
      call dd_div(th, tl, ah, al, uh, ul)                 ! 4 g w0 / a
      call dd_add(1.0_dp, 0.0_dp, uh, ul, th, tl)
      call dd_sqrt(th, tl, rh, rl)                        ! r0
      call two_sum(par, 1.0_dp, bh, bl)
      call dd_div(bh, bl, ah, al, sh, sl)                 ! r1 = (d + 1) / a
      call dd_add(rh, rl, sh, sl, th, tl)                 ! r0 + r1
      call dd_mul(th, tl, rh, rl, uh, ul)
      call dd_mul(uh, ul, sh, sl, th, tl)                 ! r0 r1 (r0 + r1)
      call dd_div(4.0_dp * gh, 4.0_dp * gl, th, tl, uh, ul)
      call dd_mul(uh, ul, eps, 0.0_dp, qh, ql)
    case default
      qh = 2.0_dp * eps; ql = 0.0_dp
    end select
  end subroutine gravity_q1_dd

end module pendula_gravity
