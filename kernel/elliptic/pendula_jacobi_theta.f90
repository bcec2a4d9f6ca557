!> sn, cn, dn, am near m = 1, each with its relative accuracy, from Jacobi's
!> imaginary transformation and theta series in the complementary nome
!> q' = q(mc) (DLMF 22.6.iv, 22.2.4-6, 20.2): for 0 <= w <= K/2
!>
!>   sn(w|m) = sc(w|m) cn(w|m) = C0 B / (D0 A),   cn(w|m) = 1 / cn(iw|mc) = A0 D / (D0 A),
!>   dn(w|m) = A0 C / (C0 A),                    am(w|m) = atan2(C0 B, A0 D),
!>
!>   A = sum q^(n(n+1)) cosh((2n+1) v),  B = sum (-1)^n q^(n(n+1)) sinh((2n+1) v),
!>   C = theta3(iv) = 1 + 2 sum q^(n^2) cosh(2nv),
!>   D = theta4(iv) = 1 + 2 sum (-1)^n q^(n^2) cosh(2nv),  A0, C0, D0 their values at v = 0,
!>   v = pi w / (2 K(mc)) = w AGM(1, sqrt(m)),
!>
!> and beyond K/2 through w = K - |r|: sn = cd(w), cn = k' sd(w), dn = k' nd(w).
!>
!> Why: the duplication core computes tn^2 by doubling from a small argument,
!> and the doubling map amplifies a relative error by about 2 per step once
!> tn^2 > 1; near m = 1 with cn ~ sech(u) small on |u| <= K/2 that left cn
!> and dn with 4 to 8 eps of relative error (harmless for sn, cn, dn as
!> functions, whose errors are absolute, but the exact motion's v = 2 k
!> sqrt(eps) cn carries cn's relative error times a scale up to ~60).  Here
!> the only amplified quantity is v, formed in double-double, and exp(-v)
!> to one rounding: cn and dn come out within ~2 eps relative.
!>
!> Range: mc <= 2^-10 (0 < mc).  There q <= 6.2e-5 and, on w <= K/2,
!> q cosh(2v) <= sqrt(q) < 0.008, so the series need three terms (the next
!> is below 1e-40) and nothing cancels: every multiple angle is written
!> through S = sinh v and c = cosh v (sinh 3v = S (3 + 4 S^2), ...), so B
!> keeps its relative accuracy as v -> 0 (S by its Taylor series there).
module pendula_jacobi_theta
  use pendula_kinds, only: dp, pi, pi_lo, half_pi, nan_dp
  use pendula_dd, only: fast_two_sum, dd_sqrt, dd_add, dd_mul
  implicit none
  private
  public :: theta_plan, theta_prepare, theta_jacobi, theta_jacobi_neg, theta_mc_max

  !> the largest mc the series are used for
  real(dp), parameter :: theta_mc_max = 2.0_dp**(-10)
  !> arguments per block of theta_jacobi
  integer, parameter :: theta_blk = 256

  type :: theta_plan
    real(dp) :: ch = 1.0_dp, cl = 0.0_dp   !< pi / (2 K(mc)) = AGM(1, sqrt(m)), double-double
    real(dp) :: q = 0.0_dp                 !< the complementary nome q(mc)
    real(dp) :: a0 = 1.0_dp, c0 = 1.0_dp, d0 = 1.0_dp
    real(dp) :: kh = 0.0_dp, kl = 0.0_dp    !< K(m), double-double
    real(dp) :: kp = 0.0_dp                 !< k' = sqrt(mc)
  end type theta_plan

contains

  !> The constants for the complement mc = mch + mcl of the parameter m
  !> (0 <= mc <= theta_mc_max).
  pure function theta_prepare(mch, mcl, kh, kl, q) result(p)
    real(dp), intent(in) :: mch, mcl
    real(dp), intent(in) :: kh, kl   !< K(m) in double-double
    !> the complementary nome q(mc), ellip_nome(mch, 1 - mch) of pendula_elliptic
    !> (passed in: that module uses this one for m < 0)
    real(dp), intent(in) :: q
    type(theta_plan) :: p
    real(dp) :: mh, ml, ah, al, bh, bl, sh, sl, th, tl
    integer :: it
    ! m = 1 - mc in double-double (exact: mc is small)
    call fast_two_sum(1.0_dp, -mch, mh, ml)
    ml = ml - mcl
    ! AGM(1, sqrt(m)) in double-double: quadratic convergence from 1 - mc/2
    ah = 1.0_dp; al = 0.0_dp
    call dd_sqrt(mh, ml, bh, bl)
    do it = 1, 8
      call dd_add(ah, al, bh, bl, sh, sl)
      call dd_mul(ah, al, bh, bl, th, tl)
      call dd_sqrt(th, tl, bh, bl)
      ah = 0.5_dp * sh; al = 0.5_dp * sl
      if (abs(ah - bh) <= 1.0e-33_dp * ah) exit
    end do
    p%ch = ah; p%cl = al
    p%q = q
    p%a0 = 1.0_dp + p%q**2 + p%q**6
    p%c0 = 1.0_dp + 2.0_dp * (p%q + p%q**4 + p%q**9)
    p%d0 = 1.0_dp - 2.0_dp * p%q + 2.0_dp * p%q**4 - 2.0_dp * p%q**9
    p%kh = kh; p%kl = kl
    call dd_sqrt(mch, mcl, sh, sl)
    p%kp = sh + sl
  end function theta_prepare

  !> sn, cn, dn, am of u + ul (double-double) at the plan's parameter, any u:
  !> reduced by 2K in double-double, then the theta series on w <= K/2.
  !> Loops without branches (merges) and no calls but exp and sqrt, so that
  !> they vectorize.  NaN for a NaN or infinite u and beyond 2^48 half periods.
  pure subroutine theta_jacobi(p, uh, ul, sn, cn, dn, am)
    type(theta_plan), intent(in) :: p
    real(dp), intent(in) :: uh(:), ul(:)
    real(dp), intent(out) :: sn(:), cn(:), dn(:), am(:)
    integer :: i0, i1
    ! blocks of a fixed size, so that the work arrays live on the stack (an
    ! automatic array of size(uh) would be a heap allocation per call)
    do i0 = 1, size(uh), theta_blk
      i1 = min(size(uh), i0 + theta_blk - 1)
      call theta_block(p, uh(i0:i1), ul(i0:i1), sn(i0:i1), cn(i0:i1), dn(i0:i1), am(i0:i1), .false., 0.0_dp, 0.0_dp)
    end do
  end subroutine theta_jacobi

  !> sn, cn, dn, am(x / sqrt(mo) | m) for the negative parameter m = 1 - mo
  !> whose imaginary-modulus core (DLMF 22.17.4-6: sn(u|m) = sd(x|mu)/sqrt(mo),
  !> cn = cd(x|mu), dn = nd(x|mu), x = sqrt(mo) u, mu = -m/mo) is the plan's
  !> parameter mu, with complement 1/mo <= theta_mc_max.  Written in the
  !> series (k' = sqrt(1/mo), so k' sqrt(mo) = 1 exactly in real arithmetic):
  !>   w = |r| <= K/2:  sn = k' C0^2 B/(D0 A0 C),  cn = C0 D/(D0 C),
  !>                    dn = C0 A/(A0 C),          am(|r|) = atan2(k' C0 B, A0 D);
  !>   w = K - |r|:     sn = A0 D/(D0 A),  cn = C0 B/(D0 A),
  !>                    dn = sqrt(mo) A0 C/(C0 A), am(|r|) = atan2(A0 D, C0 B).
  !> Every factor is positive and none cancels, so dn (up to sqrt(mo)) keeps
  !> its relative accuracy: through the duplication core (its tn^2 near
  !> m = 1 to 4-8 eps relative) dn was 5.5 eps off at m = -1.3e8, 23 eps at
  !> -1e41, and NaN (an overflow of mo T) at m = -3e221.
  pure subroutine theta_jacobi_neg(p, smo, smol, xh, xl, sn, cn, dn, am)
    type(theta_plan), intent(in) :: p
    real(dp), intent(in) :: smo, smol      !< sqrt(mo) in double-double
    real(dp), intent(in) :: xh(:), xl(:)   !< x = sqrt(mo) u in double-double
    real(dp), intent(out) :: sn(:), cn(:), dn(:), am(:)
    integer :: i0, i1
    do i0 = 1, size(xh), theta_blk
      i1 = min(size(xh), i0 + theta_blk - 1)
      call theta_block(p, xh(i0:i1), xl(i0:i1), sn(i0:i1), cn(i0:i1), dn(i0:i1), am(i0:i1), .true., smo, smol)
    end do
  end subroutine theta_jacobi_neg

  !> theta_jacobi (neg = .false.) or theta_jacobi_neg (neg = .true., smo + smol
  !> = sqrt(mo)) on at most theta_blk arguments.
  pure subroutine theta_block(p, uh, ul, sn, cn, dn, am, neg, smo, smol)
    type(theta_plan), intent(in) :: p
    real(dp), intent(in) :: uh(:), ul(:)
    real(dp), intent(out) :: sn(:), cn(:), dn(:), am(:)
    logical, intent(in) :: neg
    real(dp), intent(in) :: smo, smol
    real(dp), parameter :: splitter = 134217729.0_dp
    !> (x + magic) - magic rounds |x| < 2^51 to an integer, and vectorizes
    real(dp), parameter :: magic = 6755399441055744.0_dp
    real(dp) :: vh(theta_blk), vl(theta_blk), ex(theta_blk), sg(theta_blk), jj(theta_blk), shf(theta_blk)
    real(dp) :: sa(theta_blk), sb(theta_blk), sc(theta_blk), sd(theta_blk)
    real(dp) :: j, g, pr, t, ah, al, bh, bl, kbh, kbl, e, s, rh, rl, wh, wl, f, ss
    real(dp) :: q, sv, cv, v2, c2, a, b, c, d, inv, num_s, num_c, num_d, ya, yb, h
    integer :: i
    q = p%q
    t = splitter * p%kh; kbh = t - (t - p%kh); kbl = p%kh - kbh
    t = splitter * p%ch; bh = t - (t - p%ch); bl = p%ch - bh
    do i = 1, size(uh)
      ! r = u - 2 j K in double-double (Dekker's product written out)
      j = (min(abs(uh(i)) / (2.0_dp * p%kh), 2.0_dp**50) + magic) - magic
      j = sign(j, uh(i))
      g = 2.0_dp * j
      pr = g * p%kh
      t = splitter * g; ah = t - (t - g); al = g - ah
      e = ((ah * kbh - pr) + ah * kbl + al * kbh) + al * kbl
      s = uh(i) - pr
      e = (ul(i) - e) - g * p%kl
      rh = s + e
      rl = e - (rh - s)
      ! w = |r| or, beyond K/2, K - |r| (exact by Sterbenz, the low parts added)
      f = merge(1.0_dp, 0.0_dp, abs(rh) > 0.5_dp * p%kh)
      sg(i) = sign(1.0_dp, rh)
      wh = merge(p%kh - abs(rh), abs(rh), f > 0.0_dp)
      wl = merge(p%kl - sg(i) * rl, sg(i) * rl, f > 0.0_dp)
      s = wh + wl
      wl = wl - (s - wh)
      wh = s
      ! (a remainder just past K, w < 0 by rounding: w -> 0, where cn = 0 to
      ! within |w| ~ 1e-16 K)
      wl = merge(0.0_dp, wl, wh < 0.0_dp)
      wh = max(wh, 0.0_dp)
      ! v = w AGM(1, k) in double-double
      pr = wh * p%ch
      t = splitter * wh; ah = t - (t - wh); al = wh - ah
      e = ((ah * bh - pr) + ah * bl + al * bh) + al * bl + wh * p%cl + wl * p%ch
      vh(i) = pr + e
      vl(i) = e - (vh(i) - pr)
      vh(i) = min(vh(i), 350.0_dp)
      shf(i) = f
      ! NaN input or beyond 2^48 half periods: a marker carried in jj
      jj(i) = merge(j, huge(1.0_dp), uh(i) == uh(i) .and. abs(uh(i)) <= huge(1.0_dp) &
                    .and. abs(j) <= 2.0_dp**48)
    end do
    ex(1:size(uh)) = exp(vh(1:size(uh)))
    do i = 1, size(uh)
      ! S = sinh v, c = cosh v: from e^v above v = 1/4, the Taylor series
      ! below (where e^v - e^-v would cancel); then the low part of v
      v2 = vh(i) * vh(i)
      sv = vh(i) * (1.0_dp + v2 * (1.0_dp / 6.0_dp + v2 * (1.0_dp / 120.0_dp + v2 * (1.0_dp / 5040.0_dp &
           + v2 * (1.0_dp / 362880.0_dp + v2 * (1.0_dp / 39916800.0_dp + v2 / 6227020800.0_dp))))))
      e = 1.0_dp / ex(i)
      sv = merge(0.5_dp * (ex(i) - e), sv, vh(i) > 0.25_dp)
      cv = merge(0.5_dp * (ex(i) + e), sqrt(1.0_dp + sv * sv), vh(i) > 0.25_dp)
      ss = sv
      sv = sv + cv * vl(i)
      cv = cv + ss * vl(i)
      ! the series through S and c (cosh 2v = 1 + 2 S^2, cosh 3v = c (4 c^2 - 3),
      ! sinh 3v = S (3 + 4 S^2), ...), each correction a product of small factors
      c2 = 1.0_dp + 2.0_dp * sv * sv
      ya = q * cv * cv                   ! q cosh^2 v <= sqrt(q) / 4 on w <= K/2
      yb = q * c2                        ! q cosh 2v
      sa(i) = cv * (1.0_dp + (4.0_dp * q * ya - 3.0_dp * q * q) &
              + (16.0_dp * (q * ya)**2 * q**2 - 20.0_dp * q**5 * ya + 5.0_dp * q**6))
      sb(i) = sv * (1.0_dp - q * q * (3.0_dp + 4.0_dp * sv * sv) &
              + q**6 * (5.0_dp + 20.0_dp * sv * sv + 16.0_dp * sv**4))
      sc(i) = 1.0_dp + 2.0_dp * yb + (4.0_dp * (q * yb)**2 - 2.0_dp * q**4) &
              + (8.0_dp * (q * q * yb)**3 * q**3 - 6.0_dp * q**8 * yb)
      sd(i) = 1.0_dp - 2.0_dp * yb + (4.0_dp * (q * yb)**2 - 2.0_dp * q**4) &
              - (8.0_dp * (q * q * yb)**3 * q**3 - 6.0_dp * q**8 * yb)
    end do
    if (neg) then
      do i = 1, size(uh)
        a = sa(i); b = sb(i); c = sc(i); d = sd(i)
        ! m < 0 (theta_jacobi_neg): w <= K/2: sn = k' C0^2 B/(D0 A0 C),
        ! cn = C0 D/(D0 C), dn = C0 A/(A0 C); shifted: sn = A0 D/(D0 A),
        ! cn = C0 B/(D0 A), dn = sqrt(mo) A0 C/(C0 A)
        f = shf(i)
        inv = 1.0_dp / merge(a, c, f > 0.0_dp)
        num_s = merge((p%a0 / p%d0) * d, p%kp * ((p%c0 * p%c0) / (p%d0 * p%a0)) * b, f > 0.0_dp)
        num_c = merge((p%c0 / p%d0) * b, (p%c0 / p%d0) * d, f > 0.0_dp)
        num_d = merge(((p%a0 / p%c0) * c) / a, (p%c0 / p%a0) * a / c, f > 0.0_dp)
        num_d = merge(smo * num_d + smol * num_d, num_d, f > 0.0_dp)
        ya = merge(p%a0 * d, p%kp * p%c0 * b, f > 0.0_dp)
        yb = merge(p%c0 * b, p%a0 * d, f > 0.0_dp)
        h = atan2_pos(ya, yb)
        s = num_s * inv
        c = num_c * inv
        d = num_d
        call back_to_u(jj(i), sg(i), s, c, d, h, sn(i), cn(i), dn(i), am(i))
      end do
      return
    end if
    do i = 1, size(uh)
      a = sa(i); b = sb(i); c = sc(i); d = sd(i)
      ! w <= K/2:  sn = C0 B/(D0 A), cn = A0 D/(D0 A), dn = A0 C/(C0 A);
      ! shifted (w = K - |r|): sn = cd(w) = C0 D/(D0 C), cn = k' sd(w) =
      ! k' C0^2 B/(D0 A0 C), dn = k' nd(w) = k' C0 A/(A0 C)
      f = shf(i)
      inv = 1.0_dp / merge(c, a, f > 0.0_dp)
      num_s = merge((p%c0 / p%d0) * d, (p%c0 / p%d0) * b, f > 0.0_dp)
      num_c = merge(p%kp * ((p%c0 * p%c0) / (p%d0 * p%a0)) * b, (p%a0 / p%d0) * d, f > 0.0_dp)
      num_d = merge(p%kp * (p%c0 / p%a0) * a, (p%a0 / p%c0) * c, f > 0.0_dp)
      ! am(|r|) = atan2(sn, cn): atan2(C0 B, A0 D) on w <= K/2, and
      ! atan2(cd(w), k' sd(w)) = atan2(A0 D, k' C0 B) beyond
      ya = merge(p%a0 * d, p%c0 * b, f > 0.0_dp)
      yb = merge(p%kp * p%c0 * b, p%a0 * d, f > 0.0_dp)
      h = atan2_pos(ya, yb)
      s = num_s * inv
      c = num_c * inv
      d = num_d * inv
      call back_to_u(jj(i), sg(i), s, c, d, h, sn(i), cn(i), dn(i), am(i))
    end do
  end subroutine theta_block

  !> From the reduced argument |r| back to u = 2 j K + sg |r|: sn and cn change sign with j, dn does
  !> not, am = j pi + sg am(|r|) (h = am(|r|)); NaN beyond 2^48 half periods.
  elemental subroutine back_to_u(j, sg, s, c, d, h, sn, cn, dn, am)
    real(dp), intent(in) :: j, sg, s, c, d, h
    real(dp), intent(out) :: sn, cn, dn, am
    !> (x + magic) - magic rounds |x| < 2^51 to an integer
    real(dp), parameter :: magic = 6755399441055744.0_dp
    real(dp) :: odd
    odd = merge(1.0_dp, 0.0_dp, ((0.5_dp * abs(j) + magic) - magic) /= 0.5_dp * abs(j))
    sn = sg * s * (1.0_dp - 2.0_dp * odd)
    cn = c * (1.0_dp - 2.0_dp * odd)
    dn = d
    am = (j * pi + sg * h) + j * pi_lo
    if (.not. (abs(j) <= 2.0_dp**48)) then
      sn = nan_dp; cn = nan_dp; dn = nan_dp; am = nan_dp
    end if
  end subroutine back_to_u

  include 'pendula_atan.inc'

end module pendula_jacobi_theta
