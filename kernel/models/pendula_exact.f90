!> The exact motion of the conservative pendulum theta'' + eps sin(theta) = 0.
!>
!> With k^2 = E / (2 eps) = sin^2(theta0/2) + (v0 / (2 sqrt(eps)))^2:
!>  * libration (k < 1):  sin(theta/2) = k sn(u | k^2), theta = 2 atan2(k sn, dn),
!>    v = 2 k sqrt(eps) cn, u = u0 + sqrt(eps) t;
!>  * separatrix (k = 1): theta = 2 gd(u), v = 2 sqrt(eps) sech(u);
!>  * rotation (k > 1):   theta = 2 am(u | 1/k^2), v = 2 k sqrt(eps) dn,
!>    u = u0 + k sqrt(eps) t, the angle unwrapped and growing.
!> The distance from the separatrix, mc = 1 - k^2 (or 1 - 1/k^2), is formed
!> as (c - w)(c + w), c = cos(theta0/2), w = |v0| / (2 sqrt(eps)), in
!> double-double, never as 1 - k^2: for theta0 = 0 it is exact, so v0 = 2 -
!> 1e-12 and v0 = 2 + 1e-12 (eps = 1) keep every digit of their period.
!> The phase u = u0 + rate t is carried in double-double too, so t of 1000
!> periods loses nothing to the product.
module pendula_exact
  use pendula_kinds, only: dp, pi, pi_lo, half_pi, two_pi, nan_dp, inf_dp
  use pendula_dd, only: two_sum, fast_two_sum, two_prod, dd_sqrt, dd_add, dd_mul, dd_sincos
  use pendula_elliptic, only: jacobi_plan, jacobi_prepare_dd, jacobi_eval_array, ellip_f, ellip_f_sc
  implicit none
  private
  public :: pendulum_orbit, orbit_setup, orbit_eval, orbit_period, orbit_theta_max

  integer, parameter, public :: regime_libration = 0, regime_separatrix = 1, &
                                regime_rotation = 2
  integer, parameter, public :: orbit_ok = 0, orbit_bad_eps = 1, orbit_bad_theta0 = 2, &
                                orbit_bad_v0 = 3

  type :: pendulum_orbit
    integer :: regime = regime_libration
    real(dp) :: eps = 1.0_dp, sqh = 1.0_dp, sql = 0.0_dp  !< eps and sqrt(eps) (double-double)
    real(dp) :: k = 0.0_dp                  !< modulus sqrt(E / (2 eps))
    real(dp) :: m = 0.0_dp, mch = 1.0_dp, mcl = 0.0_dp  !< parameter of sn/am and its complement
    real(dp) :: rateh = 1.0_dp, ratel = 0.0_dp  !< du/dt (double-double)
    real(dp) :: u0 = 0.0_dp                 !< phase at t = 0
    real(dp) :: offset = 0.0_dp             !< 2 pi n: the well of a libration
    real(dp) :: dir = 1.0_dp                !< direction of a rotation or separatrix flight
    type(jacobi_plan) :: plan
  end type pendulum_orbit

contains

  !> Everything the exact solution needs for one initial state.
  pure subroutine orbit_setup(theta0, v0, eps, o, status)
    real(dp), intent(in) :: theta0, v0, eps
    type(pendulum_orbit), intent(out) :: o
    integer, intent(out) :: status
    real(dp) :: n, p, e, th, tl, c0, s0, wh, wl, r, awh, awl, dh, dl, sh, sl, qh, ql
    real(dp) :: k2h, k2l, a, b, kh, kl, s0l, c0l

    status = orbit_ok
    if (.not. (eps > 0.0_dp .and. eps <= huge(1.0_dp))) then
      status = orbit_bad_eps; return
    else if (.not. (abs(theta0) <= huge(1.0_dp))) then
      status = orbit_bad_theta0; return
    else if (.not. (abs(v0) <= huge(1.0_dp))) then
      status = orbit_bad_v0; return
    end if
    o%eps = eps
    call dd_sqrt(eps, 0.0_dp, o%sqh, o%sql)
    ! theta0 = 2 pi n + (th + tl), |th| <= pi, with pi in double-double
    n = anint(theta0 / two_pi)
    call two_prod(2.0_dp * n, pi, p, e)
    call two_sum(theta0 - p, -e - 2.0_dp * n * pi_lo, th, tl)
    ! the quotient may round across +-pi: keep the reduced angle inside [-pi, pi] exactly
    if (th > pi .or. (th == pi .and. tl > pi_lo)) then
      n = n + 1.0_dp
    else if (th < -pi .or. (th == -pi .and. tl < -pi_lo)) then
      n = n - 1.0_dp
    end if
    call two_prod(2.0_dp * n, pi, p, e)
    call two_sum(theta0 - p, -e - 2.0_dp * n * pi_lo, th, tl)
    ! sin and cos of theta0/2 in double-double (cos >= 0 on the reduced angle)
    call dd_sincos(0.5_dp * th, 0.5_dp * tl, s0, s0l, c0, c0l)
    ! w = v0 / (2 sqrt(eps)) in double-double
    wh = v0 / (2.0_dp * o%sqh)
    call two_prod(2.0_dp * o%sqh, wh, p, e)
    r = ((v0 - p) - e) - 2.0_dp * o%sql * wh
    wl = r / (2.0_dp * o%sqh)
    awh = abs(wh); awl = sign(1.0_dp, wh) * wl
    ! d = c0 - |w| and s = c0 + |w|: the distance from the separatrix is d s
    call dd_add(c0, c0l, -awh, -awl, dh, dl)
    call dd_add(c0, c0l, awh, awl, sh, sl)
    ! k^2 = s0^2 + w^2 in double-double
    call dd_mul(s0, s0l, s0, s0l, a, e)
    call dd_mul(wh, wl, wh, wl, b, r)
    call dd_add(a, e, b, r, k2h, k2l)

    if (dh > 0.0_dp) then
      ! libration: mc = (c0 - |w|)(c0 + |w|), m = k^2
      o%regime = regime_libration
      call dd_mul(dh, dl, sh, sl, o%mch, o%mcl)
      o%m = k2h
      o%k = sqrt(k2h)
      o%offset = two_pi * n
      o%rateh = o%sqh; o%ratel = o%sql
      ! sn(u0) = s0/k, cn(u0) = w/k: F from sine and cosine, never from an angle
      if (o%k > 0.0_dp) then
        o%u0 = ellip_f_sc(s0 / o%k, wh / o%k, o%m, o%mch)
      else
        o%u0 = 0.0_dp
      end if
      o%plan = jacobi_prepare_dd(o%m, o%mch, o%mcl)
    else if (dh == 0.0_dp .and. dl == 0.0_dp) then
      ! the separatrix.  cos(theta0/2) > 0 for every double theta0 (pi is not a
      ! double), so |w| = cos(theta0/2) > 0 here: the inverted equilibrium at
      ! rest cannot be given, and the flight always has a direction.
      o%regime = regime_separatrix
      o%k = 1.0_dp; o%m = 1.0_dp; o%mch = 0.0_dp; o%mcl = 0.0_dp
      o%offset = two_pi * n
      o%rateh = o%sqh; o%ratel = o%sql
      o%dir = sign(1.0_dp, wh)
      o%u0 = atanh(o%dir * s0)
      o%plan = jacobi_prepare_dd(1.0_dp, 0.0_dp, 0.0_dp)
    else
      ! rotation: parameter 1/k^2, complement (|w| - c0)(|w| + c0) / k^2
      o%regime = regime_rotation
      o%dir = sign(1.0_dp, wh)
      call dd_mul(-dh, -dl, sh, sl, qh, ql)
      ! divide by k^2 (double-double quotient)
      a = qh / k2h
      call two_prod(a, k2h, p, e)
      b = (((qh - p) - e) + ql - a * k2l) / k2h
      call fast_two_sum(a, b, o%mch, o%mcl)
      o%m = 1.0_dp / k2h
      call dd_sqrt(k2h, k2l, kh, kl)
      o%k = kh
      ! rate = k sqrt(eps) (double-double)
      call two_prod(kh, o%sqh, p, e)
      e = e + kh * o%sql + kl * o%sqh
      call fast_two_sum(p, e, o%rateh, o%ratel)
      o%u0 = ellip_f(0.5_dp * o%dir * theta0, o%m, o%mch)
      o%plan = jacobi_prepare_dd(o%m, o%mch, o%mcl)
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
    real(dp) :: p, e, s, f, x, rh, rl, u0, ah, al, bh, bl, c2
    real(dp), parameter :: splitter = 134217729.0_dp
    integer :: i, i0, nb

    rh = o%rateh; rl = o%ratel; u0 = o%u0
    f = splitter * rh; bh = f - (f - rh); bl = rh - bh
    do i0 = 1, size(t), blk
      nb = min(blk, size(t) - i0 + 1)
      ! u = u0 + rate t in double-double (Dekker's product written out)
      do i = 1, nb
        x = t(i0 + i - 1)
        p = x * rh
        f = splitter * x; ah = f - (f - x); al = x - ah
        e = ((ah * bh - p) + ah * bl + al * bh) + al * bl + x * rl
        s = u0 + p
        f = s - u0
        f = (u0 - (s - f)) + (p - f)
        uh(i) = s + (f + e)
        ul(i) = (f + e) - (uh(i) - s)
      end do
      call jacobi_eval_array(o%plan, uh(1:nb), sn(1:nb), cn(1:nb), dn(1:nb), am(1:nb), ul(1:nb))
      select case (o%regime)
      case (regime_libration)
        ! theta/2 = atan2(k sn, dn) with dn >= sqrt(mc) > 0: an atan that vectorizes
        c2 = 2.0_dp * o%k * o%sqh
        do i = 1, nb
          x = o%k * sn(i) / dn(i)
          theta(i0 + i - 1) = o%offset + 2.0_dp * sign(atan_pos(abs(x)), x)
          v(i0 + i - 1) = c2 * cn(i)
        end do
      case (regime_separatrix)
        theta(i0:i0+nb-1) = o%offset + o%dir * 2.0_dp * am(1:nb)
        v(i0:i0+nb-1) = o%dir * (2.0_dp * o%sqh) * cn(1:nb)
        ! t = +-Inf: the limits pi and -pi of the separatrix flight
        do i = 1, nb
          if (abs(t(i0 + i - 1)) > huge(1.0_dp)) then
            theta(i0 + i - 1) = o%offset + o%dir * sign(pi, t(i0 + i - 1))
            v(i0 + i - 1) = 0.0_dp
          end if
        end do
      case default
        theta(i0:i0+nb-1) = o%dir * 2.0_dp * am(1:nb)
        v(i0:i0+nb-1) = o%dir * (2.0_dp * o%k * o%sqh) * dn(1:nb)
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
      tm = 2.0_dp * atan2(o%k, sqrt(o%mch))
    case (regime_separatrix)
      tm = pi
    case default
      tm = inf_dp
    end select
  end function orbit_theta_max

  include 'pendula_atan.inc'

end module pendula_exact
