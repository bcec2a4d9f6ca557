!> Carlson's R_F and the incomplete integral F in double-double.
!>
!> Used once per orbit, at set-up, for the starting phase u0 = F(phi0) of the
!> exact motion: formed in double, its rounding (eps times a phase of order
!> K) is carried into v for the whole run, and next to the zeros of v that
!> was up to 18 eps of a small |v| (0.6 eps of the velocity scale 2 k
!> sqrt(eps)).  In double-double that error is gone (below 1e-30).
!>
!> The duplication (DLMF 19.26.18) runs until the three arguments agree to
!> Delta = max |A - x| / A < 1e-9; the series of DLMF 19.36.1 to degree 7
!> then truncates at Delta^8 ~ 1e-72, and its terms, of size Delta^2 and
!> below, are formed in double (E2 / 10 carries 2e-34 of rounding).  Each
!> step divides Delta by about 4 once the arguments are of one size; from
!> x, y << z the arguments first draw together in O(log log(z / x)) steps.
module pendula_carlson_dd
  use pendula_kinds, only: dp, nan_dp
  use pendula_dd, only: fast_two_sum, dd_sqrt, dd_add, dd_mul, dd_div_d, dd_div
  implicit none
  private
  public :: carlson_rf_dd, ellip_f_dd

contains

  !> (rh + rl) = R_F(x, y, z) for x, y, z >= 0 in double-double, at most one
  !> of them zero.  Inputs outside that domain give NaN.
  elemental subroutine carlson_rf_dd(xh, xl, yh, yl, zh, zl, rh, rl)
    real(dp), intent(in) :: xh, xl, yh, yl, zh, zl
    real(dp), intent(out) :: rh, rl
    real(dp) :: x(2), y(2), z(2), a(2), sx(2), sy(2), sz(2), t(2), lam(2), q(2)
    real(dp) :: delta, xx, yy, zz, e2, e3, s
    integer :: it
    if (.not. (xh >= 0.0_dp .and. yh >= 0.0_dp .and. zh >= 0.0_dp) .or. &
        min(xh + yh, xh + zh, yh + zh) == 0.0_dp .or. max(xh, yh, zh) > 1.0e300_dp) then
      rh = nan_dp; rl = 0.0_dp
      return
    end if
    x = [xh, xl]; y = [yh, yl]; z = [zh, zl]
    do it = 1, 200
      call mean3(x, y, z, a)
      delta = max(abs(a(1) - x(1)), abs(a(1) - y(1)), abs(a(1) - z(1))) / a(1)
      if (delta < 1.0e-9_dp) exit
      call dd_sqrt(x(1), x(2), sx(1), sx(2))
      call dd_sqrt(y(1), y(2), sy(1), sy(2))
      call dd_sqrt(z(1), z(2), sz(1), sz(2))
      call dd_add(sy(1), sy(2), sz(1), sz(2), t(1), t(2))
      call dd_mul(sx(1), sx(2), t(1), t(2), lam(1), lam(2))
      call dd_mul(sy(1), sy(2), sz(1), sz(2), t(1), t(2))
      q = lam
      call dd_add(q(1), q(2), t(1), t(2), lam(1), lam(2))
      call dd_add(x(1), x(2), lam(1), lam(2), q(1), q(2)); x = 0.25_dp * q
      call dd_add(y(1), y(2), lam(1), lam(2), q(1), q(2)); y = 0.25_dp * q
      call dd_add(z(1), z(2), lam(1), lam(2), q(1), q(2)); z = 0.25_dp * q
    end do
    ! X = 1 - x / A etc., each of size Delta: their double values suffice
    xx = rel_gap(a, x)
    yy = rel_gap(a, y)
    zz = -(xx + yy)
    e2 = xx * yy - zz * zz
    e3 = xx * yy * zz
    s = -e2 / 10.0_dp + e3 / 14.0_dp + e2 * e2 / 24.0_dp - 3.0_dp * e2 * e3 / 44.0_dp &
        - 5.0_dp * e2**3 / 208.0_dp + 3.0_dp * e3 * e3 / 104.0_dp + e2 * e2 * e3 / 16.0_dp
    ! R_F = (1 + s) / sqrt(A)
    call dd_sqrt(a(1), a(2), t(1), t(2))
    call fast_two_sum(1.0_dp, s, q(1), q(2))
    call dd_div(q(1), q(2), t(1), t(2), rh, rl)
  end subroutine carlson_rf_dd

  !> (fh + fl) = F(phi | m) for |phi| <= pi/2 given s = sin(phi) and
  !> c = cos(phi) >= 0 in double-double, and the complementary parameter
  !> mc = 1 - m > 0 in double-double:  F = s R_F(c^2, c^2 + mc s^2, 1), where
  !> 1 - m s^2 is formed as the sum of two positive terms (no cancellation).
  elemental subroutine ellip_f_dd(sh, sl, ch, cl, mch, mcl, fh, fl)
    real(dp), intent(in) :: sh, sl, ch, cl, mch, mcl
    real(dp), intent(out) :: fh, fl
    real(dp) :: c2h, c2l, s2h, s2l, ph, pl, yh, yl, rh, rl
    if (sh == 0.0_dp) then
      fh = 0.0_dp; fl = 0.0_dp
      return
    end if
    call dd_mul(ch, cl, ch, cl, c2h, c2l)
    call dd_mul(sh, sl, sh, sl, s2h, s2l)
    call dd_mul(s2h, s2l, mch, mcl, ph, pl)
    call dd_add(ph, pl, c2h, c2l, yh, yl)
    call carlson_rf_dd(c2h, c2l, yh, yl, 1.0_dp, 0.0_dp, rh, rl)
    call dd_mul(sh, sl, rh, rl, fh, fl)
  end subroutine ellip_f_dd

  !> (ah + al) = (x + y + z) / 3
  pure subroutine mean3(x, y, z, a)
    real(dp), intent(in) :: x(2), y(2), z(2)
    real(dp), intent(out) :: a(2)
    real(dp) :: t(2), u(2)
    call dd_add(x(1), x(2), y(1), y(2), t(1), t(2))
    call dd_add(t(1), t(2), z(1), z(2), u(1), u(2))
    call dd_div_d(u(1), u(2), 3.0_dp, a(1), a(2))
  end subroutine mean3

  !> (A - x) / A rounded to double
  pure function rel_gap(a, x) result(g)
    real(dp), intent(in) :: a(2), x(2)
    real(dp) :: g, d(2)
    call dd_add(a(1), a(2), -x(1), -x(2), d(1), d(2))
    g = (d(1) + d(2)) / a(1)
  end function rel_gap

end module pendula_carlson_dd
