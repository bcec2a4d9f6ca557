!> The exact motion of the conservative pendulum theta'' + eps sin(theta) = 0.
!>
!> With k^2 = E / (2 eps) = sin^2(theta0/2) + (v0 / (2 sqrt(eps)))^2:
!>  * libration (k < 1):  sin(theta/2) = k sn(u | k^2), theta = 2 atan2(k sn, dn),
!>    v = 2 k sqrt(eps) cn, u = u0 + sqrt(eps) t;
!>  * separatrix (k = 1): theta = 2 gd(u), v = 2 sqrt(eps) sech(u);
!>  * rotation (k > 1):   theta = 2 am(u | 1/k^2), v = 2 k sqrt(eps) dn,
!>    u = u0 + k sqrt(eps) t, the angle unwrapped and growing.
!> The distance from the separatrix, mc = 1 - k^2 (or 1 - 1/k^2), is formed
!> as (4 eps c^2 - v0^2) / (4 eps), c = cos(theta0/2), with v0^2 exact (a
!> two-product) and c^2 in double-double, never as 1 - k^2 and never through
!> sqrt(eps): for theta0 = 0 the numerator is exact, so v0 = 2 -+ 1e-15 keeps
!> every digit of its period over 1e4 periods (through w = v0/(2 sqrt(eps)) in
!> double-double, the 1e-32 of the square root alone cost 250 eps there).
!> Within 2^-10 of the separatrix c^2 is taken in triple-double (distance_td):
!> its 2^-106 in double-double was 2^-106 / |1 - k^2| of mc, and of K and so
!> of the phase after every half period (5 eps of v after 1571 turns 3.6e-15
!> above it).  Below 2^-450, sin(theta0/2) and v0 / (2 sqrt(eps)) are carried
!> scaled by 2^600 (k^2 underflowed), and eps is scaled into [1/4, 2) by an
!> even power of two for sqrt(eps) (subnormal eps).
!> The phase u = u0 + rate t is carried in double-double too, so t of 1000
!> periods loses nothing to the product.
module pendula_exact
  use pendula_kinds, only: dp, pi, pi_lo, half_pi, two_pi, nan_dp, inf_dp
  use pendula_dd, only: two_sum, fast_two_sum, two_prod, dd_sqrt, dd_add, dd_mul, dd_sincos, dd_div_d, dd_div
  use pendula_elliptic, only: jacobi_plan, jacobi_prepare_dd, jacobi_eval_array, ellip_f_sc, ellip_nome
  use pendula_carlson_dd, only: ellip_f_dd
  use pendula_jacobi_theta, only: theta_plan, theta_prepare, theta_jacobi, theta_mc_max
  implicit none
  private
  public :: pendulum_orbit, orbit_setup, orbit_eval, orbit_period, orbit_theta_max, half_angle

  integer, parameter, public :: regime_libration = 0, regime_separatrix = 1, &
                                regime_rotation = 2
  integer, parameter, public :: orbit_ok = 0, orbit_bad_eps = 1, orbit_bad_theta0 = 2, &
                                orbit_bad_v0 = 3, orbit_theta0_too_large = 4, orbit_too_fast = 5
  !> the third part of pi (pi = pi + pi_lo + pi_lo2 to 160 bits)
  real(dp), parameter :: pi_lo2 = -2.9947698097183397e-33_dp

  type :: pendulum_orbit
    integer :: regime = regime_libration
    real(dp) :: eps = 1.0_dp, sqh = 1.0_dp, sql = 0.0_dp  !< eps and sqrt(eps) (double-double)
    real(dp) :: k = 0.0_dp                  !< modulus sqrt(E / (2 eps))
    !> k = ks 2^-kshift: below ~2^-450 (k^2 would underflow) k is carried scaled
    !> by 2^600 (kshift = 600), and the libration is then theta = 2 k sn / dn
    !> (atan2 is linear there) rounded once at the end; else ks = k, kshift = 0
    real(dp) :: ks = 0.0_dp
    integer :: kshift = 0
    real(dp) :: m = 0.0_dp, mch = 1.0_dp, mcl = 0.0_dp  !< parameter of sn/am and its complement
    real(dp) :: rateh = 1.0_dp, ratel = 0.0_dp  !< du/dt (double-double)
    real(dp) :: vsh = 0.0_dp, vsl = 0.0_dp  !< velocity scale 2 k sqrt(eps) (double-double)
    real(dp) :: u0 = 0.0_dp, u0l = 0.0_dp   !< phase at t = 0 (double-double)
    real(dp) :: offset = 0.0_dp, offl = 0.0_dp  !< 2 pi n (double-double): the well or the turns
    real(dp) :: dir = 1.0_dp                !< direction of a rotation or separatrix flight
    type(jacobi_plan) :: plan
    !> next to the separatrix (mc <= theta_mc_max): sn, cn, dn, am by the theta
    !> series, which keep cn and dn to their relative accuracy where they are
    !> small (the duplication core: 4-8 eps relative there, carried into v)
    logical :: near1 = .false.
    type(theta_plan) :: tp
  end type pendulum_orbit

contains

  !> Everything the exact solution needs for one initial state.
  pure subroutine orbit_setup(theta0, v0, eps, o, status)
    real(dp), intent(in) :: theta0, v0, eps
    type(pendulum_orbit), intent(out) :: o
    integer, intent(out) :: status
    real(dp) :: n, p, e, th, tl, c0, s0, wh, wl, r, awh, awl, dh, dl, sh, sl, qh, ql
    real(dp) :: k2h, k2l, a, b, kh, kl, s0l, c0l, nh, nl, es, vs
    integer :: ie, bsh
    !> below this, sin(theta0/2) and v0 / (2 sqrt(eps)) are carried scaled by 2^600
    real(dp), parameter :: tiny_k = 2.0_dp**(-450)

    status = orbit_ok
    ! (eps above 1e300 leaves no room for the double-double splits of sqrt(eps))
    if (.not. (eps > 0.0_dp .and. eps <= 1.0e300_dp)) then
      status = orbit_bad_eps; return
    else if (.not. (abs(theta0) <= huge(1.0_dp))) then
      status = orbit_bad_theta0; return
    else if (.not. (abs(v0) <= huge(1.0_dp))) then
      status = orbit_bad_v0; return
    end if
    o%eps = eps
    ! eps scaled by an even power of two into [1/4, 2), v0 with it: w = v0 / (2 sqrt(eps)) and
    ! the distance (4 eps c0^2 - v0^2) / (4 eps) are unchanged to the bit, and sqrt(eps) and
    ! that distance keep every digit for eps down to the smallest subnormal (the low part of
    ! sqrt(eps) and the product 4 eps c0^2 underflowed there)
    ie = exponent(eps) / 2
    es = scale(eps, -2 * ie)
    vs = scale(v0, -ie)
    call dd_sqrt(es, 0.0_dp, a, b)
    o%sqh = scale(a, ie); o%sql = scale(b, ie)
    ! theta0 = 2 pi n + (th + tl), |th| <= pi.  Beyond 2^52 the quotient n is
    ! no longer an exact double and the angle cannot be reduced: status 4
    if (abs(theta0) > 2.0_dp**52) then
      status = orbit_theta0_too_large; return
    end if
    call reduce_angle(theta0, n, th, tl)
    ! where both sin(theta0/2) and w = v0 / (2 sqrt(eps)) are below 2^-450, k^2 = s0^2 + w^2
    ! would underflow (k came out 0 for v0 = 1e-208): both are carried scaled by 2^600
    ! (exact), and so are k and the velocity scale until they are rounded once
    bsh = 0
    if (max(abs(th), abs(vs) / (2.0_dp * a)) < tiny_k) bsh = 600
    ! sin and cos of theta0/2 in double-double (cos >= 0 on the reduced angle)
    if (abs(th) < tiny_k) then
      ! (n = 0, tl = 0) sin(th/2) = th/2 and cos = 1 within 2^-900 relative: th/2 exact, scaled
      ! (the half of a subnormal th would round)
      s0 = 0.5_dp * scale(th, bsh); s0l = 0.0_dp; c0 = 1.0_dp; c0l = 0.0_dp
    else
      call half_sincos(th, tl, s0, s0l, c0, c0l)
    end if
    ! w = v0 / (2 sqrt(eps)) in double-double (from the scaled v0 and eps, times 2^bsh)
    wh = scale(vs, bsh) / (2.0_dp * a)
    call two_prod(2.0_dp * a, wh, p, e)
    r = ((scale(vs, bsh) - p) - e) - 2.0_dp * b * wh
    wl = r / (2.0_dp * a)
    awh = abs(wh); awl = sign(1.0_dp, wh) * wl
    ! k^2 = w^2 + ... must stay a double (with room for the double-double splits)
    if (awh > 1.0e154_dp) then
      status = orbit_too_fast; return
    end if
    ! the distance from the separatrix: N = 4 eps c0^2 - v0^2 (d = N / (4 eps));
    ! where 4 eps or v0^2 would overflow, as 4 eps (c0 - |w|)(c0 + |w|)
    if (abs(vs) < 1.0e150_dp .and. bsh == 0) then
      call dd_mul(c0, c0l, c0, c0l, qh, ql)
      call dd_mul(qh, ql, 4.0_dp * es, 0.0_dp, a, e)
      call two_prod(vs, vs, b, r)
      call dd_add(a, e, -b, -r, qh, ql)
      call dd_div_d(qh, ql, 4.0_dp * es, nh, nl)
    else
      call dd_add(c0, c0l, -awh, -awl, dh, dl)
      call dd_add(c0, c0l, awh, awl, sh, sl)
      call dd_mul(dh, dl, sh, sl, nh, nl)
    end if
    ! next to the separatrix the distance is the difference of two numbers of order one, and the
    ! 2^-106 of c0^2 in double-double is an error of 2^-106 / |N| in mc, of K(mc) and so of the phase
    ! after each half period (5 eps of v 3.6e-15 above the separatrix after 1571 turns): there
    ! 4 eps c0^2 - v0^2 again, c0^2 in triple-double (distance_td)
    if (abs(nh) < 2.0_dp**(-10) .and. abs(vs) < 1.0e150_dp .and. bsh == 0) &
      call distance_td(theta0, n, es, vs, nh, nl)
    ! now nh + nl = c0^2 - w^2 = 1 - k^2, signed (for bsh > 0: w scaled, 1 - k^2 = 1 to the bit)
    if (bsh > 0) then
      nh = 1.0_dp; nl = 0.0_dp
    end if
    ! k^2 = s0^2 + w^2 in double-double
    call dd_mul(s0, s0l, s0, s0l, a, e)
    call dd_mul(wh, wl, wh, wl, b, r)
    call dd_add(a, e, b, r, k2h, k2l)

    if (nh > 0.0_dp) then
      ! libration: mc = 1 - k^2, m = k^2
      o%regime = regime_libration
      o%mch = nh; o%mcl = nl
      o%m = scale(k2h, -2 * bsh)
      o%ks = sqrt(k2h); o%kshift = bsh
      o%k = scale(o%ks, -bsh)
      ! v = 2 k sqrt(eps) cn with the scale in double-double (its rounding
      ! would add 1.5 eps to v next to the turning points, where v is small)
      call dd_sqrt(k2h, k2l, kh, kl)
      call dd_mul(kh, kl, 2.0_dp * o%sqh, 2.0_dp * o%sql, o%vsh, o%vsl)
      o%vsh = scale(o%vsh, -bsh); o%vsl = scale(o%vsl, -bsh)
      call two_prod(2.0_dp * n, pi, o%offset, o%offl)
      o%offl = o%offl + 2.0_dp * n * pi_lo
      o%rateh = o%sqh; o%ratel = o%sql
      o%plan = jacobi_prepare_dd(o%m, o%mch, o%mcl)
      o%near1 = o%mch <= theta_mc_max
      if (o%near1) o%tp = theta_prepare(o%mch, o%mcl, o%plan%kh, o%plan%kl, &
                                     ellip_nome(o%mch, 1.0_dp - o%mch))
      ! sn(u0) = s0/k, cn(u0) = w/k, dn(u0) = cos(theta0/2): F from sine and
      ! cosine, never from an angle, next to the nearest multiple of K
      if (kh > 0.0_dp) then
        call dd_div(s0, s0l, kh, kl, a, e)
        call dd_div(wh, wl, kh, kl, b, r)
        call phase_dd([a, e], [b, r], [c0, c0l], o%plan%kh, o%plan%kl, o%m, [o%mch, o%mcl], &
                      o%u0, o%u0l)
      end if
    else if (nh == 0.0_dp .and. nl == 0.0_dp) then
      ! the separatrix.  cos(theta0/2) > 0 for every double theta0 (pi is not a
      ! double), so |w| = cos(theta0/2) > 0 here: the inverted equilibrium at
      ! rest cannot be given, and the flight always has a direction.
      o%regime = regime_separatrix
      o%k = 1.0_dp; o%ks = 1.0_dp; o%m = 1.0_dp; o%mch = 0.0_dp; o%mcl = 0.0_dp
      call two_prod(2.0_dp * n, pi, o%offset, o%offl)
      o%offl = o%offl + 2.0_dp * n * pi_lo
      o%rateh = o%sqh; o%ratel = o%sql
      o%dir = sign(1.0_dp, wh)
      o%u0 = atanh(o%dir * s0)
      o%plan = jacobi_prepare_dd(1.0_dp, 0.0_dp, 0.0_dp)
    else
      ! rotation: parameter 1/k^2, complement (k^2 - 1) / k^2
      o%regime = regime_rotation
      o%dir = sign(1.0_dp, wh)
      qh = -nh; ql = -nl
      ! divide by k^2 (double-double quotient; for k^2 beyond 1e280 the
      ! splitting of k^2 would overflow, and mc = 1 - 1/k^2 to all digits)
      if (k2h > 1.0e280_dp) then
        o%mch = 1.0_dp; o%mcl = -1.0_dp / k2h
      else
        a = qh / k2h
        call two_prod(a, k2h, p, e)
        b = (((qh - p) - e) + ql - a * k2l) / k2h
        call fast_two_sum(a, b, o%mch, o%mcl)
      end if
      o%m = 1.0_dp / k2h
      call dd_sqrt(k2h, k2l, kh, kl)
      o%k = kh; o%ks = kh
      call dd_mul(kh, kl, 2.0_dp * o%sqh, 2.0_dp * o%sql, o%vsh, o%vsl)
      ! rate = k sqrt(eps) (double-double)
      call two_prod(kh, o%sqh, p, e)
      e = e + kh * o%sql + kl * o%sqh
      call fast_two_sum(p, e, o%rateh, o%ratel)
      o%plan = jacobi_prepare_dd(o%m, o%mch, o%mcl)
      o%near1 = o%mch <= theta_mc_max
      if (o%near1) o%tp = theta_prepare(o%mch, o%mcl, o%plan%kh, o%plan%kl, &
                                     ellip_nome(o%mch, 1.0_dp - o%mch))
      ! theta = dir 2 am(u): sn = dir sin(th/2), cn = cos(th/2), dn = |w|/k on the
      ! reduced angle, and the n turns of theta0 as 2 n K more phase (in
      ! double-double): am then carries every turn itself, as j pi + a small
      ! angle, and theta(t) is not the difference of two large numbers.
      ! Beyond 2^46 turns (|theta0| > 4.4e14) that phase would leave too
      ! little of the 2^48 half periods the Jacobi functions reduce (NaN came
      ! out from |theta0| ~ 9e14 on): the turns go into the offset 2 pi n
      ! instead, as for a libration (theta then reaches the far side of 0
      ! only after ~1e14 turns, beyond that range anyway)
      call dd_div(awh, awl, kh, kl, a, e)
      call phase_dd(o%dir * [s0, s0l], [c0, c0l], [a, e], o%plan%kh, o%plan%kl, o%m, &
                    [o%mch, o%mcl], o%u0, o%u0l)
      if (abs(n) > 2.0_dp**46) then
        call two_prod(2.0_dp * n, pi, o%offset, o%offl)
        o%offl = o%offl + 2.0_dp * n * pi_lo
      else
        call two_prod(o%dir * 2.0_dp * n, o%plan%kh, p, e)
        e = e + o%dir * 2.0_dp * n * o%plan%kl
        call two_sum(p, o%u0, qh, r)
        call fast_two_sum(qh, (r + e) + o%u0l, o%u0, o%u0l)
      end if
    end if
  end subroutine orbit_setup

  !> theta(t) and v(t) at any times (before or after t = 0, in any order).
  !> Works in blocks that stay in cache; every inner loop vectorizes.
  pure subroutine orbit_eval(o, t, theta, v)
    type(pendulum_orbit), intent(in) :: o
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:)
    integer, parameter :: blk = 512
    real(dp) :: uh(blk), ul(blk), sn(blk), cn(blk), dn(blk), am(blk)
    real(dp) :: p, e, s, f, x, rh, rl, u0, u0l, ah, al, bh, bl
    real(dp), parameter :: splitter = 134217729.0_dp
    integer :: i, i0, nb

    rh = o%rateh; rl = o%ratel; u0 = o%u0; u0l = o%u0l
    f = splitter * rh; bh = f - (f - rh); bl = rh - bh
    do i0 = 1, size(t), blk
      nb = min(blk, size(t) - i0 + 1)
      ! u = u0 + rate t in double-double (Dekker's product written out)
      do i = 1, nb
        x = t(i0 + i - 1)
        p = x * rh
        f = splitter * x; ah = f - (f - x); al = x - ah
        e = ((ah * bh - p) + ah * bl + al * bh) + al * bl + x * rl + u0l
        s = u0 + p
        f = s - u0
        f = (u0 - (s - f)) + (p - f)
        uh(i) = s + (f + e)
        ul(i) = (f + e) - (uh(i) - s)
      end do
      if (o%near1) then
        ! next to the separatrix: the theta series, which keep cn and dn to their
        ! relative accuracy where they are small (pendula_jacobi_theta)
        call theta_jacobi(o%tp, uh(1:nb), ul(1:nb), sn(1:nb), cn(1:nb), dn(1:nb), am(1:nb))
      else
        ! a libration needs sn, cn, dn only (theta from atan2(k sn, dn)): no am
        call jacobi_eval_array(o%plan, uh(1:nb), sn(1:nb), cn(1:nb), dn(1:nb), am(1:nb), ul(1:nb), &
                               want_am=o%regime /= regime_libration)
      end if
      select case (o%regime)
      case (regime_libration)
        ! theta/2 = atan2(k sn, dn) with dn >= sqrt(mc) > 0: an atan2 that vectorizes
        ! (one division and one square root)
        if (o%kshift == 0) then
          do i = 1, nb
            x = atan2_pos(o%k * abs(sn(i)), dn(i))
            theta(i0 + i - 1) = o%offset + (o%offl + 2.0_dp * sign(x, sn(i)))
            v(i0 + i - 1) = o%vsh * cn(i) + o%vsl * cn(i)
          end do
        else
          ! k below 2^-450: atan2(k sn, dn) = k sn / dn within 2^-900, from the scaled k
          ! and rounded once (offset = 0: the well of a tiny theta0 is the first)
          do i = 1, nb
            theta(i0 + i - 1) = scale(2.0_dp * o%ks * sn(i) / dn(i), -o%kshift)
            v(i0 + i - 1) = o%vsh * cn(i) + o%vsl * cn(i)
          end do
        end if
      case (regime_separatrix)
        theta(i0:i0+nb-1) = o%offset + (o%offl + o%dir * 2.0_dp * am(1:nb))
        v(i0:i0+nb-1) = o%dir * (2.0_dp * o%sqh) * cn(1:nb)
        ! t = +-Inf: the limits pi and -pi of the separatrix flight
        do i = 1, nb
          if (abs(t(i0 + i - 1)) > huge(1.0_dp)) then
            theta(i0 + i - 1) = o%offset + (o%offl + o%dir * sign(pi, t(i0 + i - 1)))
            v(i0 + i - 1) = 0.0_dp
          end if
        end do
      case default
        theta(i0:i0+nb-1) = o%offset + (o%offl + o%dir * 2.0_dp * am(1:nb))
        v(i0:i0+nb-1) = o%dir * (o%vsh * dn(1:nb) + o%vsl * dn(1:nb))
      end select
    end do
  end subroutine orbit_eval

  !> Period: 4K/sqrt(eps) for a libration, one full turn 2K(1/k^2)/(k sqrt(eps))
  !> for a rotation, +Inf on the separatrix.
  pure function orbit_period(o) result(tp)
    type(pendulum_orbit), intent(in) :: o
    real(dp) :: tp
    select case (o%regime)
    case (regime_libration)
      tp = 4.0_dp * (o%plan%kh + o%plan%kl) / o%sqh
    case (regime_rotation)
      tp = 2.0_dp * (o%plan%kh + o%plan%kl) / o%rateh
    case default
      tp = inf_dp
    end select
  end function orbit_period

  !> Largest |theta - 2 pi n| reached: 2 atan2(k, sqrt(mc)) in libration, pi on
  !> the separatrix, +Inf for a rotation (no turning point).
  pure function orbit_theta_max(o) result(tm)
    type(pendulum_orbit), intent(in) :: o
    real(dp) :: tm
    select case (o%regime)
    case (regime_libration)
      if (o%kshift == 0) then
        tm = 2.0_dp * atan2(o%k, sqrt(o%mch))
      else
        tm = scale(2.0_dp * o%ks / sqrt(o%mch), -o%kshift)   ! (k below 2^-450: atan is linear)
      end if
    case (regime_separatrix)
      tm = pi
    case default
      tm = inf_dp
    end select
  end function orbit_theta_max

  !> theta0 = 2 pi n + (th + tl) with the remainder in [-pi, pi] exactly
  !> (|theta0| <= 2^52, where n is an exact double).
  pure subroutine reduce_angle(theta0, n, th, tl)
    real(dp), intent(in) :: theta0
    real(dp), intent(out) :: n, th, tl
    n = anint(theta0 / two_pi)
    call reduce_2pi(theta0, n, th, tl)
    ! 2 n pi_lo can be many radians for a large theta0 (39 at 1e18): reduce what is left
    if (abs(th) > pi) then
      n = n + anint(th / two_pi)
      call reduce_2pi(theta0, n, th, tl)
    end if
    ! the quotient may round across +-pi: keep the reduced angle inside [-pi, pi] exactly
    if (th > pi .or. (th == pi .and. tl > pi_lo)) then
      n = n + 1.0_dp
    else if (th < -pi .or. (th == -pi .and. tl < -pi_lo)) then
      n = n - 1.0_dp
    end if
    call reduce_2pi(theta0, n, th, tl)
  end subroutine reduce_angle

  !> sin and cos of (th + tl)/2, |th| <= pi, in double-double, each to its
  !> relative accuracy (cos >= 0).
  pure subroutine half_sincos(th, tl, s0, s0l, c0, c0l)
    real(dp), intent(in) :: th, tl
    real(dp), intent(out) :: s0, s0l, c0, c0l
    real(dp) :: p, e, qh, ql
    if (abs(th) <= half_pi) then
      call dd_sincos(0.5_dp * th, 0.5_dp * tl, s0, s0l, c0, c0l)
    else
      ! next to the top cos(theta0/2) = sin((pi - |th|)/2) is tiny: form the
      ! distance pi - |th| with pi in three parts (pi_hi - |th| is exact), so
      ! that cos(theta0/2) keeps its relative accuracy (through pi in two
      ! parts, 1e-33 / 1.5e-15 of it was lost: 450 eps after 7700 periods)
      call two_sum(pi - abs(th), pi_lo, p, e)
      e = e + (pi_lo2 - sign(1.0_dp, th) * tl)
      call fast_two_sum(p, e, qh, ql)
      call dd_sincos(0.5_dp * qh, 0.5_dp * ql, c0, c0l, s0, s0l)
      s0 = sign(1.0_dp, th) * s0; s0l = sign(1.0_dp, th) * s0l
    end if
  end subroutine half_sincos

  !> An angle reduced exactly (pi in three parts, as theta0 is): theta =
  !> 2 pi turns + w, w in [-pi, pi]; s = sin(w/2), c = cos(w/2) >= 0, each
  !> rounded once from double-double (c to its relative accuracy next to
  !> w = +-pi).  NaN beyond |theta| = 2^52, where turns is no longer exact.
  elemental subroutine half_angle(theta, turns, s, c)
    real(dp), intent(in) :: theta
    real(dp), intent(out) :: turns, s, c
    real(dp) :: th, tl, s0, s0l, c0, c0l
    if (.not. (abs(theta) <= 2.0_dp**52)) then
      turns = nan_dp; s = nan_dp; c = nan_dp; return
    end if
    call reduce_angle(theta, turns, th, tl)
    call half_sincos(th, tl, s0, s0l, c0, c0l)
    s = s0 + s0l; c = c0 + c0l
  end subroutine half_angle

  !> The distance from the separatrix N = (4 es c0^2 - vs^2) / (4 es) (double-double) with
  !> c0^2 = cos^2(theta0/2) in triple-double: the angle reduced by 2 pi n (pi in three parts) to a
  !> triple-double r, then c0^2 = 1 - H(r)/2 for |r| <= pi/2, H(pi - |r|)/2 beyond (no
  !> cancellation either way), H(z) = 1 - cos z (td_one_minus_cos).  About 2^-150 relative.
  pure subroutine distance_td(theta0, n, es, vs, nh, nl)
    real(dp), intent(in) :: theta0, n, es, vs
    real(dp), intent(out) :: nh, nl
    real(dp) :: r(3), c2(3), x(3), p, e, q, f, g, sg
    ! r = theta0 - 2 n (pi + pi_lo + pi_lo2): every product exact but the last (below 2^-150 n)
    call two_prod(2.0_dp * n, pi, p, e)
    call two_prod(2.0_dp * n, pi_lo, q, f)
    g = 2.0_dp * n * pi_lo2
    r = td_add([theta0 - p, 0.0_dp, 0.0_dp], [-e, -q, -f - g])
    if (abs(r(1)) <= half_pi) then
      c2 = td_add([1.0_dp, 0.0_dp, 0.0_dp], -0.5_dp * td_one_minus_cos(r))
    else
      sg = sign(1.0_dp, r(1))
      x = td_add([pi, pi_lo, pi_lo2], -sg * r)
      c2 = 0.5_dp * td_one_minus_cos(x)
    end if
    call two_prod(vs, vs, p, e)
    x = td_add(td_mul(c2, [4.0_dp * es, 0.0_dp, 0.0_dp]), [-p, -e, 0.0_dp])
    call fast_two_sum(x(1), x(2) + x(3), p, e)
    call dd_div_d(p, e, 4.0_dp * es, nh, nl)
  end subroutine distance_td

  !> 1 - cos z for |z| <= pi/2 in triple-double: Maclaurin at z / 2^8 (nine terms, below 2^-160),
  !> then eight doublings 1 - cos 2a = 2 H (2 - H), every factor positive.
  pure function td_one_minus_cos(z) result(h)
    real(dp), intent(in) :: z(3)
    real(dp) :: h(3), a(3), a2(3), pp(3)
    integer :: k
    a = scale(z, -8)
    a2 = td_mul(a, a)
    ! 1 - cos a = (a^2 / 2) (1 - a^2 / (3 4) (1 - a^2 / (5 6) (...)))
    pp = [1.0_dp, 0.0_dp, 0.0_dp]
    do k = 9, 1, -1
      pp = td_add([1.0_dp, 0.0_dp, 0.0_dp], -td_div_int(td_mul(a2, pp), (2 * k + 1) * (2 * k + 2)))
    end do
    h = td_mul(0.5_dp * a2, pp)
    do k = 1, 8
      h = 2.0_dp * td_mul(h, td_add([2.0_dp, 0.0_dp, 0.0_dp], -h))
    end do
  end function td_one_minus_cos

  !> a + b in triple-double (components decreasing, each below half an ulp of the one before or
  !> nearly so), to about 2^-150 relative.
  pure function td_add(a, b) result(r)
    real(dp), intent(in) :: a(3), b(3)
    real(dp) :: r(3), s0, e0, s1, e1, t, u
    call two_sum(a(1), b(1), s0, e0)
    call two_sum(a(2), b(2), s1, e1)
    call two_sum(s1, e0, t, u)
    r = td_renorm(s0, t, (a(3) + b(3)) + (e1 + u))
  end function td_add

  !> a b in triple-double (the products of order three and beyond in double).
  pure function td_mul(a, b) result(r)
    real(dp), intent(in) :: a(3), b(3)
    real(dp) :: r(3), p0, q0, p1, q1, p2, q2, s, e, t, f
    call two_prod(a(1), b(1), p0, q0)
    call two_prod(a(1), b(2), p1, q1)
    call two_prod(a(2), b(1), p2, q2)
    call two_sum(p1, p2, s, e)
    call two_sum(s, q0, t, f)
    r = td_renorm(p0, t, (a(1) * b(3) + a(2) * b(2) + a(3) * b(1)) + ((q1 + q2) + (e + f)))
  end function td_mul

  !> a / d for a small integer d in triple-double (each remainder exact by two-products).
  pure function td_div_int(a, d) result(r)
    real(dp), intent(in) :: a(3)
    integer, intent(in) :: d
    real(dp) :: r(3), dd, q1, q2, q3, p, e, s, t, u, v, lo
    dd = real(d, dp)
    q1 = a(1) / dd
    call two_prod(q1, dd, p, e)
    call two_sum(a(1) - p, -e, s, t)
    call two_sum(s, a(2), u, v)
    lo = (t + v) + a(3)
    q2 = u / dd
    call two_prod(q2, dd, p, e)
    q3 = (((u - p) - e) + lo) / dd
    r = td_renorm(q1, q2, q3)
  end function td_div_int

  !> (a, b, c) with |a| >= |b| >= |c| roughly, as a normalized triple-double.
  pure function td_renorm(a, b, c) result(r)
    real(dp), intent(in) :: a, b, c
    real(dp) :: r(3), s, t, u, v, w, x
    call two_sum(b, c, t, u)
    call two_sum(a, t, s, v)
    call two_sum(v, u, w, x)
    call fast_two_sum(s, w, r(1), t)        ! (no output aliases an input)
    call fast_two_sum(t, x, r(2), r(3))
  end function td_renorm

  !> th + tl = theta0 - 2 pi n with pi in three parts (2n and each part's
  !> products exact through two-products), summed in double-double: the
  !> error e of the first product is as large as an ulp of theta0 (0.06 at
  !> |theta0| = 7e14), and added to the low part in double it lost 1e-17 of
  !> the angle, which k^2 and so the rate carried: v was 170 eps off after
  !> 2000 periods.
  pure subroutine reduce_2pi(theta0, n, th, tl)
    real(dp), intent(in) :: theta0, n
    real(dp), intent(out) :: th, tl
    real(dp) :: p, e, q, f, s, r, a, b
    call two_prod(2.0_dp * n, pi, p, e)
    call two_prod(2.0_dp * n, pi_lo, q, f)
    s = theta0 - p                     ! exact (Sterbenz) when n is the nearest quotient
    call two_sum(s, -q, a, r)
    call two_sum(a, -e, th, b)
    tl = (r + b) - f - 2.0_dp * n * pi_lo2
    call fast_two_sum(th, tl, s, r)
    th = s
    tl = r
  end subroutine reduce_2pi

  !> The phase u0 (double-double) with sn(u0) = sn0, cn(u0) = cn0,
  !> dn(u0) = dn0 > 0 for the parameter m (K = kh + kl, mc = mch + mcl its
  !> complement); sn0, cn0, dn0 are given in double-double (the pairs).
  !>
  !> F is computed only for the part of u0 beyond the nearest multiple of K
  !> (a start at rest near the top has u0 = K, a libration run backward u0
  !> near 2K), and in double-double (pendula_carlson_dd): formed in double,
  !> its rounding of eps times a phase of order K stayed in v for the whole
  !> run, up to 18 eps of a small |v| next to its zeros.
  !>   u0 = j K + F(remainder): j = 0 and 2 use sn(2K - u) = sn(u),
  !>   cn(2K - u) = -cn(u); j = 1 uses sn(K - u) = cd(u), cn(K - u) = k' sd(u).
  !> The branch is chosen from the double values (the choice only has to
  !> keep the remainder small, not be exact).
  pure subroutine phase_dd(sn0, cn0, dn0, kh, kl, m, mc, uh, ul)
    real(dp), intent(in) :: sn0(2), cn0(2), dn0(2), kh, kl, m, mc(2)
    real(dp), intent(out) :: uh, ul
    real(dp) :: sg, as(2), f0, f1, jk, ph, pl, fh, fl, ah(2), bh(2), r(2), t(2)
    sg = sign(1.0_dp, sn0(1))
    as = sg * sn0
    ! from 0 (cn >= 0) or from 2K (cn < 0)
    if (cn0(1) >= 0.0_dp) then
      f0 = ellip_f_sc(as(1), cn0(1), m, mc(1)); jk = 0.0_dp
    else
      f0 = -ellip_f_sc(as(1), -cn0(1), m, mc(1)); jk = 2.0_dp
    end if
    ! from K: u0 = K - u1, sn(u1) = cn0/dn0, cn(u1) = sqrt(mc) |sn0| / dn0
    f1 = ellip_f_sc(cn0(1) / dn0(1), sqrt(mc(1)) * as(1) / dn0(1), m, mc(1))
    if (abs(f1) < abs(f0)) then
      jk = 1.0_dp
      call dd_div(cn0(1), cn0(2), dn0(1), dn0(2), ah(1), ah(2))
      call dd_sqrt(mc(1), mc(2), r(1), r(2))
      call dd_mul(r(1), r(2), as(1), as(2), t(1), t(2))
      call dd_div(t(1), t(2), dn0(1), dn0(2), bh(1), bh(2))
      ! cn(u1) >= 0 always; sn(u1) may have either sign
      call ellip_f_dd(abs(ah(1)), sign(1.0_dp, ah(1)) * ah(2), bh(1), bh(2), mc(1), mc(2), fh, fl)
      fh = -sign(1.0_dp, ah(1)) * fh; fl = -sign(1.0_dp, ah(1)) * fl
    else if (jk == 0.0_dp) then
      call ellip_f_dd(as(1), as(2), cn0(1), cn0(2), mc(1), mc(2), fh, fl)
    else
      call ellip_f_dd(as(1), as(2), -cn0(1), -cn0(2), mc(1), mc(2), fh, fl)
      fh = -fh; fl = -fl
    end if
    ! u0 = sg (jk K + f), the multiple of K in double-double
    call two_prod(jk, kh, ph, pl)
    pl = pl + jk * kl
    call dd_add(ph, pl, fh, fl, uh, ul)
    uh = sg * uh; ul = sg * ul
  end subroutine phase_dd

  include 'pendula_atan.inc'

end module pendula_exact
