!> cn and dn near m = 1 with relative accuracy where they are small, from
!> Jacobi's imaginary transformation and theta series in the complementary
!> nome q' = q(mc) (DLMF 22.6.iv, 22.2.4-6, 20.2):
!>
!>   cn(u|m) = 1 / cn(iu|mc) = A0 D / (D0 A),   dn(u|m) = A0 C / (C0 A),
!>
!>   A = sum q^(n(n+1)) cosh((2n+1) v),  C = theta3(iv) = 1 + 2 sum q^(n^2) cosh(2nv),
!>   D = theta4(iv) = 1 + 2 sum (-1)^n q^(n^2) cosh(2nv),  A0, C0, D0 their values at v = 0,
!>   v = pi u / (2 K(mc)) = u AGM(1, sqrt(m)).
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
!> Range: mc <= 2^-10 and |u| <= K/2 (after the reduction by 2K).  There
!> q <= 6.2e-5 and x = q exp(2v) <= sqrt(q) < 0.008, so the series need
!> terms to x^3 q^9 only (the next is below 1e-40) and nothing cancels.
module pendula_jacobi_theta
  use pendula_kinds, only: dp
  use pendula_dd, only: fast_two_sum, dd_sqrt, dd_add, dd_mul
  use pendula_elliptic, only: ellip_nome
  implicit none
  private
  public :: theta_plan, theta_prepare, theta_cn_dn, theta_mc_max

  !> the largest mc the series are used for
  real(dp), parameter :: theta_mc_max = 2.0_dp**(-10)

  type :: theta_plan
    real(dp) :: ch = 1.0_dp, cl = 0.0_dp   !< pi / (2 K(mc)) = AGM(1, sqrt(m)), double-double
    real(dp) :: q = 0.0_dp                 !< the complementary nome q(mc)
    real(dp) :: a0 = 1.0_dp, c0 = 1.0_dp, d0 = 1.0_dp
  end type theta_plan

contains

  !> The constants for the complement mc = mch + mcl of the parameter m
  !> (0 <= mc <= theta_mc_max).
  pure function theta_prepare(mch, mcl) result(p)
    real(dp), intent(in) :: mch, mcl
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
    p%q = ellip_nome(mch, mh)
    p%a0 = 1.0_dp + p%q**2 + p%q**6
    p%c0 = 1.0_dp + 2.0_dp * (p%q + p%q**4 + p%q**9)
    p%d0 = 1.0_dp - 2.0_dp * p%q + 2.0_dp * p%q**4 - 2.0_dp * p%q**9
  end function theta_prepare

  !> cn(u|m) and dn(u|m) for reduced arguments u = uh + ul, |u| <= K/2 (the
  !> caller keeps only those).  Loops without branches or calls except exp,
  !> so that they vectorize (exp from the vector libm).
  pure subroutine theta_cn_dn(p, uh, ul, cn, dn)
    type(theta_plan), intent(in) :: p
    real(dp), intent(in) :: uh(:), ul(:)
    real(dp), intent(out) :: cn(:), dn(:)
    real(dp), parameter :: splitter = 134217729.0_dp
    real(dp) :: vh(size(uh)), vl(size(uh)), em(size(uh))
    real(dp) :: x, y, q, a, c, d, au, t, ah, al, bh, bl, pr, e, s
    integer :: i
    q = p%q
    t = splitter * p%ch; bh = t - (t - p%ch); bl = p%ch - bh
    do i = 1, size(uh)
      ! v = |u| pi / (2 K(mc)) in double-double (Dekker's product written out)
      au = abs(uh(i))
      pr = au * p%ch
      t = splitter * au; ah = t - (t - au); al = au - ah
      e = ((ah * bh - pr) + ah * bl + al * bh) + al * bl
      e = e + au * p%cl + sign(1.0_dp, uh(i)) * ul(i) * p%ch
      s = pr + e
      vl(i) = e - (s - pr)
      vh(i) = min(s, 350.0_dp)      ! (only |u| <= K/2 is kept: v < 200 there)
    end do
    em = exp(-vh)
    do i = 1, size(uh)
      ! exp(-v) to first order in the low part (|vl| < 1e-16 |v|)
      em(i) = em(i) - em(i) * vl(i)
      x = q / (em(i) * em(i))                         ! q e^(2v) <= sqrt(q)
      y = q * em(i) * em(i)                           ! q e^(-2v) <= q
      ! A = (e^v / 2) a with a = 1 + q x + q^4 x^2 + q^9 x^3 + e^(-2v) (1 + q y)
      a = (1.0_dp + q * x * (1.0_dp + q**3 * x * (1.0_dp + q**5 * x))) + em(i) * em(i) * (1.0_dp + q * y)
      c = 1.0_dp + (x + y) + q * q * (x * x + y * y) + q**6 * (x**3 + y**3)
      d = 1.0_dp - (x + y) + q * q * (x * x + y * y) - q**6 * (x**3 + y**3)
      ! cn = A0 D / (D0 A), dn = A0 C / (C0 A), with 1 / A = 2 e^-v / a
      a = (2.0_dp * p%a0) * em(i) / a
      cn(i) = a * (d / p%d0)
      dn(i) = a * (c / p%c0)
    end do
  end subroutine theta_cn_dn

end module pendula_jacobi_theta
