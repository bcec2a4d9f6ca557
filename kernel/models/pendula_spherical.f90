!> The exact motion of the spherical pendulum (a point mass on a massless rod
!> of length l, free to move on the sphere), in the units g = l = 1 scaled by
!> eps = g / l as the planar pendulum is: theta is the polar angle from the
!> downward vertical, phi the azimuth, L = sin^2(theta) phi' the vertical
!> angular momentum per unit m l^2.
!>
!> With x = 1 - cos(theta) = 2 sin^2(theta/2) (the height above the lowest
!> point) and time scaled by sqrt(eps), energy and L give
!>   x'^2 = Q(x) = 2 (e - x) x (2 - x) - L^2 = 2 (x - xa)(xb - x)(xc - x),
!> e the energy above the bottom, 0 <= xa <= xb <= 2 the turning heights and
!> xc >= max(2, e) the third root.  (In z = cos(theta) these are the roots
!> z2 = 1 - xa >= z1 = 1 - xb of the cubic; its third root 1 - xc lies below
!> -1, beyond the lowest point of the sphere.)  Then (Landau and Lifshitz,
!> Mechanics, section 14, problem 1; Whittaker, Analytical Dynamics, section 56)
!>   x = xa + d sn^2(u | m),   2 - x = yb + d cn^2(u | m),
!>   d = xb - xa, yb = 2 - xb, m = d / (xc - xa), u = u0 + w sqrt(eps) t,
!>   w^2 = (xc - xa) / 2,
!> so that theta = 2 atan2(sqrt(x), sqrt(2 - x)) from two sums of positive
!> terms (every digit of a small theta near the bottom and of pi - theta near
!> the top).  The azimuth phi' = (L / 2)(1/x + 1/(2 - x)) integrates to two
!> elliptic integrals of the third kind, each taken from the turning point
!> where it is of the hyperbolic case (all terms positive):
!>   1/(2 - x) from u = 0:  Pi(n2; u) / ya, n2 = d / ya, 1 - n2 = yb / ya;
!>   1/x from u = K (the shift sn(w + K) = cd(w)):
!>     ((m/N) w + (1 - m/N) Pi(N; w)) / xb, N - m = d mc / xb, 1 - N = xa mc / xb,
!> with Pi(n; am r) = r + (n/3) s^3 R_J(c^2, dn^2, 1, 1 - n s^2) (DLMF 19.25.14)
!> and 1 - n s^2 = c^2 + (1 - n) s^2.  Per sample R_J is GSL's
!> gsl_sf_ellint_RJ; the complete integrals, whose sum is the azimuth advance
!> per polar period (multiplied by the number of periods), are formed once in
!> quadruple precision (rj_qp).
!>
!> The phase u is carried in double-double and reduced by whole polar
!> periods 2K exactly (K in double-double): u = 2 K j + r, |r| <= K; theta and
!> its rate depend on r alone, the azimuth is j times its advance per polar
!> period plus the part of r, so the cost per sample is constant and t = 1e12
!> loses nothing to the reduction.  The roots and everything formed from them
!> are computed once per orbit in quadruple precision (gfortran's real(16)),
!> from the state: Q(x0 + h) = w0^2 S + Q1 h + Q2 h^2 + 2 h^3, the roots
!> ha <= 0 <= hb bracketed and bisected; xa = L^2 / (2 xb xc) (Vieta), so
!> that a small xa (L small) keeps its relative accuracy, and 2 - xb likewise
!> from (2 - xb)(xc - 2) = L^2 / (2 (2 - xa)) where it is the smaller factor.
!> (2 - xb and xc - 2 both small, within about 1e-9 rad of the top at the
!> separatrix, keep fewer digits.)
!>
!> L = 0 is the planar pendulum: the motion stays in the plane phi = phi0 and
!> is answered by the planar exact path (pendula_exact), theta then signed and
!> unwrapped as the planar angle is.
module pendula_spherical
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  use pendula_kinds, only: dp, pi, pi_lo, nan_dp, inf_dp
  use pendula_dd, only: two_sum, fast_two_sum, two_prod, dd_add
  use pendula_elliptic, only: jacobi_plan, jacobi_prepare_dd, jacobi_eval_array
  use pendula_carlson_dd, only: ellip_f_dd
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval, orbit_period, &
                           regime_libration, regime_rotation
  implicit none
  private
  public :: spherical_orbit, spherical_setup, spherical_eval, spherical_facts, spherical_nfacts

  integer, parameter, public :: sph_ok = 0, sph_bad_eps = 1, sph_bad_theta0 = 2, sph_bad_theta_dot0 = 3, &
                                sph_bad_phi_dot0 = 4, sph_pole_spin = 5, sph_too_fast = 6, &
                                sph_tiny_lz = 7, sph_bad_phi0 = 8
  !> the number of facts spherical_facts returns
  integer, parameter :: spherical_nfacts = 12

  integer, parameter :: qp = selected_real_kind(30)

  interface
    !> GSL's Carlson R_J (gsl_sf_ellint.h): NaN outside its domain.  Pure as
    !> pendula calls it: GSL's error handler is off (pendula_gsl_init).
    pure function gsl_rj(x, y, z, p, mode) bind(C, name='gsl_sf_ellint_RJ') result(r)
      import :: c_double, c_int
      real(c_double), value :: x, y, z, p
      integer(c_int), value :: mode
      real(c_double) :: r
    end function gsl_rj
  end interface

  type :: spherical_orbit
    logical :: planar = .false.
    type(pendulum_orbit) :: po                 !< L = 0: the planar exact path
    real(dp) :: eps = 1.0_dp, phi0 = 0.0_dp
    real(dp) :: lz = 0.0_dp                    !< L = sin^2(theta) phi' (real time)
    real(dp) :: energy = 0.0_dp                !< (theta'^2 + sin^2 theta phi'^2)/2 + eps (1 - cos theta)
    real(dp) :: xa = 0.0_dp, xb = 0.0_dp, ya = 2.0_dp, yb = 2.0_dp, d = 0.0_dp
    real(dp) :: m = 0.0_dp, mc = 1.0_dp, smc = 1.0_dp
    real(dp) :: rateh = 1.0_dp, ratel = 0.0_dp !< du/dt = w sqrt(eps) (double-double)
    real(dp) :: u0h = 0.0_dp, u0l = 0.0_dp     !< phase at t = 0 (double-double)
    real(dp) :: kh = 0.0_dp, kl = 0.0_dp       !< K(m) (double-double)
    real(dp) :: cphi = 0.0_dp                  !< L / (2 w) in scaled units
    real(dp) :: n2 = 0.0_dp, one_n2 = 1.0_dp   !< the 1/(2 - x) part: n2 and 1 - n2
    real(dp) :: nm = 0.0_dp, one_n = 1.0_dp    !< the 1/x part: N - m and 1 - N
    real(dp) :: rj1 = 0.0_dp                   !< R_J(0, mc, 1, 1 - N)
    real(dp) :: delta = 0.0_dp                 !< azimuth advance per polar period
    real(dp) :: ch = 0.0_dp, cl = 0.0_dp       !< phi0 - A(u0) (double-double)
    type(jacobi_plan) :: plan
  end type spherical_orbit

contains

  !> Everything the exact path needs for the state (theta0, theta_dot0, phi_dot0)
  !> at t = 0 with azimuth phi0, for g / l = eps.
  pure subroutine spherical_setup(theta0, theta_dot0, phi_dot0, phi0, eps, o, status)
    real(dp), intent(in) :: theta0, theta_dot0, phi_dot0, phi0, eps
    type(spherical_orbit), intent(out) :: o
    integer, intent(out) :: status
    real(qp) :: sq, w, p, x0, y0, s, lq, kin, q0, q1, q2, ha, hb, xa, xb, xc, ya, yb, d, xcb, xca
    real(qp) :: om, m, mc, sn0, cn0, kq, rj1q, rjn2q, xc2
    real(dp) :: a(1), b(1), fh, fl, ah, al

    status = sph_ok
    if (.not. (eps > 0.0_dp .and. eps <= 1.0e300_dp)) then
      status = sph_bad_eps; return
    else if (.not. (theta0 >= 0.0_dp .and. theta0 <= pi)) then
      status = sph_bad_theta0; return
    else if (.not. (abs(theta_dot0) <= huge(1.0_dp))) then
      status = sph_bad_theta_dot0; return
    else if (.not. (abs(phi_dot0) <= huge(1.0_dp))) then
      status = sph_bad_phi_dot0; return
    else if (.not. (abs(phi0) <= huge(1.0_dp))) then
      status = sph_bad_phi0; return
    end if
    if (theta0 == 0.0_dp .and. phi_dot0 /= 0.0_dp) then
      ! at the pole the azimuth is undefined: an azimuthal rate there is no state
      status = sph_pole_spin; return
    end if
    o%eps = eps; o%phi0 = phi0
    sq = sqrt(real(eps, qp))
    w = real(theta_dot0, qp) / sq
    p = real(phi_dot0, qp) / sq
    if (abs(w) > 1.0e100_qp .or. abs(p) > 1.0e100_qp) then
      status = sph_too_fast; return
    end if
    x0 = 2.0_qp * sin(0.5_qp * real(theta0, qp))**2
    y0 = 2.0_qp * cos(0.5_qp * real(theta0, qp))**2
    s = x0 * y0                      ! sin^2(theta0)
    lq = s * p
    kin = 0.5_qp * (w * w + s * p * p)
    o%lz = real(lq * sq, dp)
    o%energy = real(eps * (kin + x0), dp)
    if (lq == 0.0_qp) then
      o%planar = .true.
      call orbit_setup(theta0, theta_dot0, eps, o%po, status)
      ! (the planar checks are those above: its statuses cannot occur here)
      if (status /= 0) status = sph_too_fast
      return
    end if
    if (abs(lq) < 1.0e-100_qp) then
      status = sph_tiny_lz; return
    end if
    ! Q(x0 + h) = q0 + q1 h + q2 h^2 + 2 h^3
    q0 = w * w * s
    q1 = 2.0_qp * (kin * (y0 - x0) - s)
    q2 = -2.0_qp * (kin + (y0 - x0))
    ha = bisect(-x0, 0.0_qp)
    hb = bisect(min(kin, y0), 0.0_qp)
    d = hb - ha
    xb = x0 + hb
    yb = y0 - hb
    xc = (kin - hb) + y0 - ha        ! the sum of the roots, every term >= 0
    xa = lq * lq / (2.0_qp * xb * xc)
    ya = 2.0_qp - xa
    ! 2 - xb and xc - 2 multiply to L^2 / (2 ya) (the roots in 2 - x): each is a
    ! difference, good to 1e-34 absolute, so the smaller one is taken from the
    ! larger (2 - xb of 1e-22, over the top with a tiny L, kept 12 digits only)
    xc2 = (kin - hb) - xa
    if (xc2 > yb) yb = lq * lq / (2.0_qp * ya * xc2)
    xcb = (kin - hb) + yb - xa       ! xc - xb
    xca = xcb + d
    m = d / xca
    mc = xcb / xca
    om = sqrt(0.5_qp * xca)
    o%xa = real(xa, dp); o%xb = real(xb, dp); o%ya = real(ya, dp); o%yb = real(yb, dp); o%d = real(d, dp)
    o%m = real(m, dp); o%mc = real(mc, dp); o%smc = sqrt(o%mc)
    call split(om * sq, o%rateh, o%ratel)
    o%cphi = real(lq / (2.0_qp * om), dp)
    o%n2 = real(d / ya, dp); o%one_n2 = real(yb / ya, dp)
    o%nm = real(d * mc / xb, dp); o%one_n = real(xa * mc / xb, dp)
    o%plan = jacobi_prepare_dd(o%m, o%mc, real(mc - real(mc, dp), dp))
    o%kh = o%plan%kh; o%kl = o%plan%kl
    ! the complete integrals of the azimuth, in quadruple precision (the advance per
    ! period is multiplied by the number of periods)
    kq = real(o%kh, qp) + real(o%kl, qp)
    rj1q = rj_qp(0.0_qp, mc, 1.0_qp, xa * mc / xb)
    rjn2q = rj_qp(0.0_qp, mc, 1.0_qp, yb / ya)
    o%rj1 = real(rj1q, dp)
    o%delta = real(2.0_qp * (lq / (2.0_qp * om)) * ((kq + (d / ya / 3.0_qp) * rjn2q) / ya &
                                                    + (kq + (d * mc / xb / 3.0_qp) * rj1q) / xb), dp)
    if (.not. (abs(o%delta) <= huge(1.0_dp) .and. abs(o%kh) <= huge(1.0_dp))) then
      status = sph_tiny_lz; return
    end if
    ! the phase at t = 0: sn(u0)^2 = (x0 - xa) / d, cn(u0)^2 = (xb - x0) / d, sn(u0) of the sign of theta'
    if (d > 0.0_qp) then
      sn0 = sqrt(max(-ha, 0.0_qp) / d)
      cn0 = sqrt(hb / d)
      call ellip_f_dd(real(sn0, dp), real(sn0 - real(sn0, dp), dp), real(cn0, dp), &
                      real(cn0 - real(cn0, dp), dp), o%mc, real(mc - real(mc, dp), dp), fh, fl)
      if (theta_dot0 < 0.0_dp) then
        fh = -fh; fl = -fl
      end if
      o%u0h = fh; o%u0l = fl
    end if
    ! phi(t) = phi0 + A(u) - A(u0): the constant phi0 - A(u0) in double-double
    a = 0.0_dp
    call azimuth(o, [o%u0h], [o%u0l], a, b)
    call dd_add(phi0, 0.0_dp, -a(1), -b(1), ah, al)
    o%ch = ah; o%cl = al
  contains
    !> the root of Q(x0 + h) between neg0 (Q <= 0 there) and pos0 (Q >= 0), by
    !> bisection to the last bit of quadruple precision
    pure function bisect(neg0, pos0) result(r)
      real(qp), intent(in) :: neg0, pos0
      real(qp) :: r, neg, pos, mid
      integer :: it
      neg = neg0; pos = pos0
      do it = 1, 400
        mid = 0.5_qp * (neg + pos)
        if (mid == neg .or. mid == pos) exit
        if (cubic(mid) > 0.0_qp) then
          pos = mid
        else
          neg = mid
        end if
      end do
      ! the end where Q is nearer zero
      if (abs(cubic(neg)) < abs(cubic(pos))) then
        r = neg
      else
        r = pos
      end if
    end function bisect
    pure function cubic(h) result(f)
      real(qp), intent(in) :: h
      real(qp) :: f
      f = q0 + h * (q1 + h * (q2 + 2.0_qp * h))
    end function cubic
  end subroutine spherical_setup

  !> a quadruple-precision number as a double-double
  pure subroutine split(q, h, l)
    real(qp), intent(in) :: q
    real(dp), intent(out) :: h, l
    h = real(q, dp)
    l = real(q - real(h, qp), dp)
  end subroutine split

  !> Carlson's R_J(x, y, z, p) for x, y, z >= 0 (at most one zero), p > 0, through
  !> GSL's gsl_sf_ellint_RJ; the arguments are scaled by a power of two (R_J is homogeneous of degree
  !> -3/2) when the smallest sum would fall below GSL's lower limit.  NaN where
  !> GSL reports a domain error.
  elemental function rj(x, y, z, p) result(r)
    real(dp), intent(in) :: x, y, z, p
    real(dp) :: r, lo
    integer :: k
    lo = min(x + y, x + z, y + z, p)
    k = 0
    if (lo < 1.0e-90_dp) k = 330 - exponent(max(x, y, z, p))
    r = gsl_rj(scale(x, k), scale(y, k), scale(z, k), scale(p, k), 0_c_int) * 2.0_dp**(1.5_dp * k)
  end function rj

  !> A(u) = j delta + A(r) of the phases u = uh + ul (double-double): the azimuth
  !> without phi0, as ah + al
  pure subroutine azimuth(o, uh, ul, ah, al)
    type(spherical_orbit), intent(in) :: o
    real(dp), intent(in) :: uh(:), ul(:)
    real(dp), intent(out) :: ah(:), al(:)
    real(dp) :: rh(size(uh)), rl(size(uh)), jj(size(uh)), sn(size(uh)), cn(size(uh)), dn(size(uh))
    real(dp) :: am(size(uh)), th(size(uh)), td(size(uh))
    call reduce(o, uh, ul, jj, rh, rl)
    call jacobi_eval_array(o%plan, rh, sn, cn, dn, am, rl, want_am=.false.)
    call reduced_values(o, jj, rh, sn, cn, dn, th, td, ah, al)
  end subroutine azimuth

  !> u = 2 K j + r, |r| <= K (r in double-double)
  pure subroutine reduce(o, uh, ul, jj, rh, rl)
    type(spherical_orbit), intent(in) :: o
    real(dp), intent(in) :: uh(:), ul(:)
    real(dp), intent(out) :: jj(:), rh(:), rl(:)
    real(dp) :: p, e, s, f
    integer :: i
    do i = 1, size(uh)
      jj(i) = anint(uh(i) / (2.0_dp * o%kh))
      call two_prod(-2.0_dp * jj(i), o%kh, p, e)
      e = e - 2.0_dp * jj(i) * o%kl
      call two_sum(uh(i), p, s, f)
      call fast_two_sum(s, f + (e + ul(i)), rh(i), rl(i))
    end do
  end subroutine reduce

  !> From the Jacobi functions at the reduced phases: the polar angle (th), its
  !> rate (td, real time) and the azimuth A = j delta + A(r) (ah + al, no phi0)
  pure subroutine reduced_values(o, jj, rh, sn, cn, dn, th, td, ah, al)
    type(spherical_orbit), intent(in) :: o
    real(dp), intent(in) :: jj(:), rh(:), sn(:), cn(:), dn(:)
    real(dp), intent(out) :: th(:), td(:), ah(:), al(:)
    real(dp) :: s, c, x, y, ar, t2, t1, s1, c1, d1, p, e, q, g
    integer :: i
    do i = 1, size(rh)
      s = sn(i); c = abs(cn(i))
      x = o%xa + o%d * (s * s)
      y = o%yb + o%d * (c * c)
      th(i) = 2.0_dp * atan2(sqrt(x), sqrt(y))
      td(i) = (2.0_dp * o%d * o%rateh) * (s * c * dn(i)) / sqrt(x * y)
      ! the 1/(2 - x) part from u = 0
      t2 = abs(rh(i))
      if (o%n2 > 0.0_dp) t2 = t2 + (o%n2 / 3.0_dp) * abs(s)**3 &
                                * rj(c * c, dn(i) * dn(i), 1.0_dp, c * c + o%one_n2 * (s * s))
      t2 = t2 / o%ya
      ! the 1/x part from u = K: at K - |r|, sn = cn/dn, cn = sqrt(mc) |sn| / dn, dn = sqrt(mc) / dn
      t1 = abs(rh(i))
      if (o%nm > 0.0_dp) then
        s1 = c / dn(i); c1 = o%smc * abs(s) / dn(i); d1 = o%smc / dn(i)
        t1 = t1 + (o%nm / 3.0_dp) * (o%rj1 - s1**3 * rj(c1 * c1, d1 * d1, 1.0_dp, c1 * c1 + o%one_n * (s1 * s1)))
      end if
      t1 = t1 / o%xb
      ar = sign(1.0_dp, rh(i)) * o%cphi * (t1 + t2)
      ! j delta + A(r) in double-double
      call two_prod(jj(i), o%delta, p, e)
      call two_sum(p, ar, q, g)
      call fast_two_sum(q, g + e, ah(i), al(i))
    end do
  end subroutine reduced_values

  !> theta, phi and their rates at the times t (any order, before or after 0).
  pure subroutine spherical_eval(o, t, theta, phi, theta_dot, phi_dot)
    type(spherical_orbit), intent(in) :: o
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), phi(:), theta_dot(:), phi_dot(:)
    integer, parameter :: blk = 256
    real(dp) :: uh(blk), ul(blk), jj(blk), rh(blk), rl(blk), sn(blk), cn(blk), dn(blk), am(blk)
    real(dp) :: ah(blk), al(blk), p, e, s, f, x, y
    integer :: i, i0, nb
    if (o%planar) then
      call orbit_eval(o%po, t, theta, theta_dot)
      ! (NaN where the planar path gives NaN: an infinite time, beyond 2^48 half periods)
      phi = merge(nan_dp, o%phi0, theta /= theta)
      phi_dot = merge(nan_dp, 0.0_dp, theta /= theta)
      return
    end if
    do i0 = 1, size(t), blk
      nb = min(blk, size(t) - i0 + 1)
      do i = 1, nb
        ! u = u0 + rate t in double-double
        call two_prod(t(i0 + i - 1), o%rateh, p, e)
        e = e + t(i0 + i - 1) * o%ratel + o%u0l
        call two_sum(o%u0h, p, s, f)
        call fast_two_sum(s, f + e, uh(i), ul(i))
      end do
      call reduce(o, uh(1:nb), ul(1:nb), jj(1:nb), rh(1:nb), rl(1:nb))
      call jacobi_eval_array(o%plan, rh(1:nb), sn(1:nb), cn(1:nb), dn(1:nb), am(1:nb), rl(1:nb), &
                             want_am=.false.)
      call reduced_values(o, jj(1:nb), rh(1:nb), sn(1:nb), cn(1:nb), dn(1:nb), theta(i0:i0+nb-1), &
                          theta_dot(i0:i0+nb-1), ah(1:nb), al(1:nb))
      do i = 1, nb
        call dd_add(o%ch, o%cl, ah(i), al(i), s, f)
        phi(i0 + i - 1) = s + f
        x = o%xa + o%d * sn(i)**2
        y = o%yb + o%d * cn(i)**2
        phi_dot(i0 + i - 1) = o%lz / (x * y)
        if (.not. (abs(t(i0 + i - 1)) <= huge(1.0_dp)) .or. .not. (abs(uh(i)) < 2.0_dp**48 * o%kh)) then
          theta(i0 + i - 1) = nan_dp; phi(i0 + i - 1) = nan_dp
          theta_dot(i0 + i - 1) = nan_dp; phi_dot(i0 + i - 1) = nan_dp
        end if
      end do
    end do
  end subroutine spherical_eval

  !> The orbit's facts: [polar period, azimuth advance per polar period, apsidal
  !> angle (the azimuth between a lowest and the next highest point), the apsidal
  !> precession rate (advance - pi sign(L)) / period, theta_min, theta_max,
  !> energy, L, m, mc, planar (1 or 0), the polar frequency 2 pi / period].
  !> L = 0: the limit L -> 0+ (the azimuth jumps by pi at the bottom and at the top).
  pure function spherical_facts(o) result(f)
    type(spherical_orbit), intent(in) :: o
    real(dp) :: f(spherical_nfacts)
    real(dp) :: per, adv, tmin, tmax
    if (o%planar) then
      select case (o%po%regime)
      case (regime_libration)
        per = 0.5_dp * orbit_period(o%po); adv = pi
        tmin = 0.0_dp; tmax = 2.0_dp * atan2(o%po%k, sqrt(o%po%mch))
        if (o%po%kshift /= 0) tmax = scale(2.0_dp * o%po%ks / sqrt(o%po%mch), -o%po%kshift)
      case (regime_rotation)
        per = orbit_period(o%po); adv = 2.0_dp * pi; tmin = 0.0_dp; tmax = pi
      case default
        per = inf_dp; adv = pi; tmin = 0.0_dp; tmax = pi
      end select
      f = [per, adv, 0.5_dp * adv, (adv - pi) / per, tmin, tmax, o%energy, 0.0_dp, o%po%m, o%po%mch, &
           1.0_dp, 2.0_dp * pi / per]
      return
    end if
    per = 2.0_dp * (o%kh + o%kl) / o%rateh
    tmin = 2.0_dp * atan2(sqrt(o%xa), sqrt(o%ya))
    tmax = 2.0_dp * atan2(sqrt(o%xb), sqrt(o%yb))
    f = [per, o%delta, 0.5_dp * o%delta, (o%delta - sign(pi, o%lz)) / per, tmin, tmax, o%energy, o%lz, &
         o%m, o%mc, 0.0_dp, 2.0_dp * pi / per]
  end function spherical_facts

  !> Carlson's R_J(x, y, z, p) in quadruple precision (x, y, z >= 0, at most one
  !> zero, p > 0), for the complete integrals of the azimuth: the advance per
  !> polar period multiplies the number of periods, so it is formed to about
  !> 1e-33 (GSL's double R_J is good to a few eps).  Carlson's duplication with
  !> the R_C terms in closed form (Carlson 1995, section 2; DLMF 19.36.2),
  !> run until the arguments agree to 1e-7 (the degree-5 series then
  !> truncates below 1e-35).
  pure function rj_qp(x0, y0, z0, p0) result(r)
    real(qp), intent(in) :: x0, y0, z0, p0
    real(qp) :: r, x, y, z, p, sx, sy, sz, sp, lam, a, a0, dl, dm, em, s, f, q, xx, yy, zz, pp
    real(qp) :: e2, e3, e4, e5, rc
    integer :: k
    x = x0; y = y0; z = z0; p = p0
    a0 = (x + y + z + 2.0_qp * p) / 5.0_qp
    a = a0
    dl = (p - x) * (p - y) * (p - z)
    s = 0.0_qp
    f = 1.0_qp                          ! 4^-k
    q = 1.0_qp                          ! 4^-3k
    do k = 1, 200
      if (max(abs(a - x), abs(a - y), abs(a - z), abs(a - p)) < 1.0e-7_qp * a) exit
      sx = sqrt(x); sy = sqrt(y); sz = sqrt(z); sp = sqrt(p)
      lam = sx * sy + sx * sz + sy * sz
      dm = (sp + sx) * (sp + sy) * (sp + sz)
      em = q * dl / (dm * dm)
      ! R_C(1, 1 + em)
      if (em > 0.0_qp) then
        rc = atan(sqrt(em)) / sqrt(em)
      else if (em < 0.0_qp) then
        rc = atanh(sqrt(-em)) / sqrt(-em)
      else
        rc = 1.0_qp
      end if
      s = s + f / dm * rc
      x = 0.25_qp * (x + lam); y = 0.25_qp * (y + lam); z = 0.25_qp * (z + lam); p = 0.25_qp * (p + lam)
      a = 0.25_qp * (a + lam)
      f = 0.25_qp * f; q = q / 64.0_qp
    end do
    xx = (a - x) / a; yy = (a - y) / a; zz = (a - z) / a
    pp = -(xx + yy + zz) / 2.0_qp
    e2 = xx * yy + xx * zz + yy * zz - 3.0_qp * pp * pp
    e3 = xx * yy * zz + 2.0_qp * e2 * pp + 4.0_qp * pp**3
    e4 = (2.0_qp * xx * yy * zz + e2 * pp + 3.0_qp * pp**3) * pp
    e5 = xx * yy * zz * pp * pp
    r = f / (a * sqrt(a)) * (1.0_qp - 3.0_qp * e2 / 14.0_qp + e3 / 6.0_qp + 9.0_qp * e2 * e2 / 88.0_qp &
                             - 3.0_qp * e4 / 22.0_qp - 9.0_qp * e2 * e3 / 52.0_qp + 3.0_qp * e5 / 26.0_qp) &
        + 6.0_qp * s
  end function rj_qp

end module pendula_spherical
