!> Elliptic integrals, the nome and the Jacobi elliptic functions.
!>
!> Every routine takes the parameter m together with its complement
!> mc = 1 - m.  The complement is the primary variable: near the separatrix
!> of the pendulum m = 1 - 1e-300 is representable only through mc, and no
!> routine forms 1 - m by subtraction.  Callers pass both, consistent to
!> rounding (the binding layer derives whichever one the user omitted).
!>
!> Methods (all derived here; see DLMF chapters 19 and 22):
!>  * K(m): the arithmetic-geometric mean carried in double-double, closed by
!>    the expansion AGM(A+c, A-c) = A (1 - t^2/4 - 5 t^4/64 - 11 t^6/256 - ...),
!>    t = c/A, its leading term in double-double, so that K is known to ~1e-30
!>    relative for one parameter (~2^-75 on the per-element path, which is
!>    what 1e4 periods need).  The low part is what lets the Jacobi functions
!>    reduce u = 1000 periods without losing digits.
!>  * E(m), F(phi|m), E(phi|m): Carlson's symmetric integrals R_F and R_D by
!>    duplication, in forms whose terms are all positive for 0 <= m <= 1
!>    (no cancellation as m -> 1).
!>  * sn, cn, dn, am: reduction of u by 2K in double-double, a quarter-period
!>    shift to [0, K/2], an eight-term Maclaurin series of tn^2 at
!>    u / 2^n <= 1/8 and n duplications carried as a fraction P/Q (see
!>    jacobi_block); every factor is positive on [0, K/2], and all outputs
!>    come from P and Q.  For mc < 2^-60 the expansion about m = 1 instead
!>    (jacobi_hyp); m < 0 and m > 1 through the imaginary and reciprocal
!>    modulus transformations.
!>  * the nome q(m): the Jacobi series in eps = (1 - mc^(1/4)) / (2 (1 + mc^(1/4)))
!>    for m <= 1/2, and ln q ln q' = pi^2 with the complementary series above.
module pendula_elliptic
  use pendula_kinds, only: dp, i8, pi, pi_lo, half_pi, nan_dp, inf_dp
  use pendula_dd, only: two_sum, fast_two_sum, two_prod, dd_sqrt, dd_sincos, dd_mul, dd_add, dd_div
  use pendula_jacobi_theta, only: theta_plan, theta_prepare, theta_jacobi_neg, theta_mc_max
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none
  private
  public :: ellip_k, ellip_k_array, ellip_k_dd, ellip_e, ellip_f, ellip_f_sc, ellip_einc, ellip_nome
  public :: carlson_rf, carlson_rd
  public :: jacobi_plan, jacobi_prepare, jacobi_prepare_dd, jacobi_eval, jacobi_eval_array, jacobi_sncndn, &
            jacobi_eval_varm
  public :: jacobi_max_periods

  !> Arguments beyond this many half periods cannot be reduced accurately
  !> even with K in double-double; they give NaN.
  real(dp), parameter :: jacobi_max_periods = 2.0_dp**48

  !> Below this complementary parameter sn, cn, dn come from their first-order
  !> expansion about m = 1 (DLMF 22.10.6-8) instead of the duplications; see
  !> jacobi_hyp for why, and why the first order is enough.
  real(dp), parameter :: mc_hyp = 2.0_dp**(-60)

  !> the third part of pi (pi = pi + pi_lo + pi_lo2 to 160 bits)
  real(dp), parameter :: pi_lo2 = -2.9947698097183397e-33_dp

  interface
    !> K = kh + kl in double-double and sqrt(mc) for n parameters 2^-60 <= mc <= 1
    !> (complement mc + mcl), kernel/elliptic/pendula_agm.c: the AGM with fused
    !> multiply-adds where the CPU has them (Fortran cannot ask for one fma
    !> without contracting everything)
    pure subroutine c_agm_k(n, mc, mcl, kh, kl, smc) bind(C, name='pendula_agm_k')
      import :: c_double, c_int
      integer(c_int), value :: n
      real(c_double), intent(in) :: mc(*), mcl(*)
      real(c_double), intent(out) :: kh(*), kl(*), smc(*)
    end subroutine c_agm_k
    !> C99's expm1 (Fortran has none): e^x - 1 without cancellation for small x
    pure function c_expm1(x) bind(C, name='expm1') result(y)
      import :: c_double
      real(c_double), value :: x
      real(c_double) :: y
    end function c_expm1
  end interface

  ! kfit_p, kfit_q: K(m) = P(mc) - log(mc) Q(mc) on 0 < mc <= 1
  include 'pendula_ellipk_fit.inc'

  !> Everything about one parameter m that the Jacobi functions need.
  !> regime: -1 invalid, 0 for 0 <= m < 1, 1 for m = 1, 2 for m < 0
  !> (imaginary-modulus transformation), 3 for m > 1 (reciprocal modulus).
  type :: jacobi_plan
    integer :: regime = -1
    real(dp) :: mc = 1.0_dp                   !< complement of the core parameter (0 <= m < 1)
    real(dp) :: kh = 0.0_dp, kl = 0.0_dp      !< K of the core, double-double
    real(dp) :: sh = 1.0_dp, sl = 0.0_dp      !< argument scale (1, sqrt(1-m) or sqrt(m))
    real(dp) :: mo = 1.0_dp, mol = 0.0_dp     !< m < 0: the complement 1 - m itself, double-double
    real(dp) :: ct(8) = 0.0_dp                 !< Maclaurin series of tn^2 in u^2
    integer :: ndbl = 0                        !< duplications that cover [0, K/2]
    !> m < 0 with the core's complement 1/(1 - m) <= theta_mc_max (m <= -1023):
    !> the core by the theta series (see jacobi_eval_array)
    logical :: theta = .false.
    type(theta_plan) :: tp
  end type jacobi_plan

contains

  ! ------------------------------------------------------------------
  ! Complete integral of the first kind
  ! ------------------------------------------------------------------

  !> K(m) = pi / (2 AGM(1, sqrt(mc))) in double-double: K = kh + kl.
  !> Valid for every mc >= 0 (m <= 1); mc = 0 gives +Inf, mc < 0 NaN.
  elemental subroutine ellip_k_dd(mc, kh, kl)
    real(dp), intent(in) :: mc
    real(dp), intent(out) :: kh, kl
    call ellip_k_dd2(mc, 0.0_dp, kh, kl)
  end subroutine ellip_k_dd

  !> K for a complementary parameter given itself in double-double (mc + mcl):
  !> the transformed parameters of m < 0 and m > 1 are not representable.
  elemental subroutine ellip_k_dd2(mc, mcl, kh, kl)
    real(dp), intent(in) :: mc, mcl
    real(dp), intent(out) :: kh, kl
    real(dp) :: b, bl

    if (.not. (mc >= 0.0_dp)) then
      kh = nan_dp; kl = 0.0_dp; return
    else if (mc == 0.0_dp) then
      kh = inf_dp; kl = 0.0_dp; return
    else if (mc > huge(1.0_dp)) then
      kh = 0.0_dp; kl = 0.0_dp; return
    end if
    ! sqrt(mc) in double-double; below 1e-200 through mc 2^600, so that the
    ! error term of r^2 (2^-106 mc) does not fall into the subnormals (for
    ! mc = 1e-300 K was good to 2^-80 only: 1e11 eps in cn next to its zeros)
    if (mc < 1.0e-200_dp) then
      call dd_sqrt(scale(mc, 600), scale(mcl, 600), b, bl)
      b = scale(b, -300); bl = scale(bl, -300)
    else
      call dd_sqrt(mc, mcl, b, bl)
    end if
    call ellip_k_sqrt(b, bl, kh, kl)
  end subroutine ellip_k_dd2

  !> K = pi / (2 AGM(1, k')) in double-double from k' = sqrt(mc) = b + bl in
  !> double-double (0 < k' <= 1).  Given k' itself, a complement below 1e-292
  !> keeps its digits: for m < 0 the core's k' = 1/sqrt(1 - m) is normal
  !> while its square's low part would be subnormal (there it carried 1e-25
  !> of relative error, an error of 1e-25 in K that the reduction of u by
  !> 1e13 periods made 1e-12: a thousand eps in dn at m = -3e298).
  elemental subroutine ellip_k_sqrt(b0, bl0, kh, kl)
    real(dp), intent(in) :: b0, bl0
    real(dp), intent(out) :: kh, kl
    real(dp) :: a, al, b, bl, s, e, an, anl, p, pe, ah2, al2, c, t, corr, mh, ml, q, r
    integer :: it
    b = b0; bl = bl0
    a = 1.0_dp; al = 0.0_dp
    do it = 1, 64
      if (abs(a - b) <= 2.0_dp**(-14) * (a + b)) exit
      call two_sum(a, b, s, e)
      e = e + (al + bl)
      call fast_two_sum(s, e, an, anl)
      call two_prod(a, b, p, pe)
      call fast_two_sum(p, pe + (a * bl + al * b), s, e)
      call dd_sqrt(s, e, b, bl)
      a = 0.5_dp * an; al = 0.5_dp * anl
    end do
    ! A = (a + b)/2 and c = (a - b)/2; a - b is exact (Sterbenz).
    call two_sum(a, b, s, e)
    e = e + (al + bl)
    call fast_two_sum(s, e, ah2, al2)
    ah2 = 0.5_dp * ah2; al2 = 0.5_dp * al2
    ! M = A - c^2/(4A) - A t^4 (5/64 + 11 t^2/256 + 469 t^4/16384), t = c/A <= 2^-14.
    ! The leading term (2^-30 of A) in double-double from c = ch + cl in
    ! double-double (a - b exact); the rest is below 2^-59 of A, so double
    ! (a few roundings, 2^-51 of it) suffices, and the first term left out
    ! (1379/65536 t^10) is below 2^-145.  (Closed at t <= 2^-10, the rest was
    ! 2^-43 of A and its roundings 4e-29 of K: 1.6e3 eps in dn after 1e13
    ! quarter periods at m = -4e258.)
    ! (With c and the whole correction in double, K was good to ~2^-75 only:
    ! 1e9 eps in cn 1e-12 from its zero at u = 21 K, mc = 1e-226.)
    call fast_two_sum(0.5_dp * (a - b), 0.5_dp * (al - bl), c, corr)
    call two_prod(c, c, p, pe)
    pe = pe + 2.0_dp * c * corr
    call dd_div(p, pe, 4.0_dp * ah2, 4.0_dp * al2, q, r)
    t = c / ah2
    t = t * t
    corr = ah2 * t * t * (5.0_dp / 64.0_dp + t * (11.0_dp / 256.0_dp + t * (469.0_dp / 16384.0_dp)))
    call two_sum(ah2, -q, s, e)
    call fast_two_sum(s, e + (al2 - r - corr), mh, ml)
    ! K = pi / (2 M) in double-double
    q = pi / (2.0_dp * mh)
    call two_prod(2.0_dp * mh, q, p, pe)
    r = ((pi - p) - pe) + (pi_lo - 2.0_dp * ml * q)
    call fast_two_sum(q, r / (2.0_dp * mh), kh, kl)
  end subroutine ellip_k_sqrt

  !> Complete elliptic integral of the first kind K(m), m = 1 - mc.
  !> 0 <= m < 1: K = P(mc) - log(mc) Q(mc), a fit of degree 11 (generated by
  !> data/gen_ellipk_fit.py, 0.15 eps); m < 0: the AGM in double-double.
  elemental function ellip_k(m, mc) result(k)
    real(dp), intent(in) :: m, mc
    real(dp) :: k, kl, p, q
    integer :: i
    if (m /= m .or. mc /= mc) then
      k = nan_dp
    else if (mc == 0.0_dp) then
      k = inf_dp
    else if (mc > 0.0_dp .and. mc <= 1.0_dp) then
      p = kfit_p(11); q = kfit_q(11)
      do i = 10, 0, -1
        p = p * mc + kfit_p(i)
        q = q * mc + kfit_q(i)
      end do
      k = p - log(mc) * q
    else
      call ellip_k_dd(mc, k, kl)
      k = k + kl
    end if
  end function ellip_k

  !> K for whole arrays: the fit's two polynomials in a loop that vectorizes,
  !> log in a loop of its own, the rare cases (m < 0, NaN, m >= 1) after.
  pure subroutine ellip_k_array(m, k, mc)
    real(dp), intent(in) :: m(:)
    real(dp), intent(out) :: k(:)
    real(dp), intent(in), optional :: mc(:)   !< the complement; 1 - m when absent
    integer, parameter :: blk = 256
    real(dp) :: lg(blk), cb(blk), x, p, q
    integer :: i0, nb, i, d
    do i0 = 1, size(m), blk
      nb = min(blk, size(m) - i0 + 1)
      if (present(mc)) then
        cb(1:nb) = mc(i0:i0+nb-1)
      else
        cb(1:nb) = 1.0_dp - m(i0:i0+nb-1)
      end if
      do i = 1, nb
        x = cb(i)
        lg(i) = log(merge(x, 1.0_dp, x > 0.0_dp .and. x <= 1.0_dp))
      end do
      do i = 1, nb
        x = min(max(cb(i), 0.0_dp), 1.0_dp)
        p = kfit_p(11); q = kfit_q(11)
        do d = 10, 0, -1
          p = p * x + kfit_p(d)
          q = q * x + kfit_q(d)
        end do
        k(i0 + i - 1) = p - lg(i) * q
      end do
      do i = 1, nb
        if (.not. (cb(i) > 0.0_dp .and. cb(i) <= 1.0_dp) .or. m(i0 + i - 1) /= m(i0 + i - 1)) &
          k(i0 + i - 1) = ellip_k(m(i0 + i - 1), cb(i))
      end do
    end do
  end subroutine ellip_k_array

  ! ------------------------------------------------------------------
  ! Carlson's symmetric integrals
  ! ------------------------------------------------------------------

  !> R_F(x, y, z); NaN unless x, y, z >= 0 with at most one of them zero.
  elemental function carlson_rf(x0, y0, z0) result(rf)
    real(dp), intent(in) :: x0, y0, z0
    real(dp) :: rf, x, y, z, a, a0, q, lam, sx, sy, sz, xx, yy, zz, e2, e3, f
    integer :: it
    if (.not. (x0 >= 0.0_dp .and. y0 >= 0.0_dp .and. z0 >= 0.0_dp)) then
      rf = nan_dp; return
    end if
    if (min(x0 + y0, x0 + z0, y0 + z0) == 0.0_dp) then
      rf = inf_dp; return
    end if
    if (max(x0, y0, z0) > huge(1.0_dp)) then
      rf = 0.0_dp; return
    end if
    x = x0; y = y0; z = z0
    a0 = (x + y + z) / 3.0_dp
    a = a0
    ! Carlson's bound: stop when 4^-n Q < |A|, Q = (3 r)^(-1/6) max|A0 - x|, r = 2^-56
    q = 540.0_dp * max(abs(a0 - x), abs(a0 - y), abs(a0 - z))
    f = 1.0_dp
    do it = 1, 200
      if (q * f < abs(a)) exit
      sx = sqrt(x); sy = sqrt(y); sz = sqrt(z)
      lam = sx * (sy + sz) + sy * sz
      x = 0.25_dp * (x + lam); y = 0.25_dp * (y + lam); z = 0.25_dp * (z + lam)
      a = 0.25_dp * (a + lam)
      f = 0.25_dp * f
    end do
    xx = (a0 - x0) * f / a
    yy = (a0 - y0) * f / a
    zz = -(xx + yy)
    e2 = xx * yy - zz * zz
    e3 = xx * yy * zz
    rf = (1.0_dp - e2 / 10.0_dp + e3 / 14.0_dp + e2 * e2 / 24.0_dp - 3.0_dp * e2 * e3 / 44.0_dp &
         - 5.0_dp * e2**3 / 208.0_dp + 3.0_dp * e3 * e3 / 104.0_dp + e2 * e2 * e3 / 16.0_dp) / sqrt(a)
  end function carlson_rf

  !> R_D(x, y, z); NaN unless x, y >= 0 (not both zero) and z > 0.
  elemental function carlson_rd(x0, y0, z0) result(rd)
    real(dp), intent(in) :: x0, y0, z0
    real(dp) :: rd, x, y, z, a, a0, q, lam, sx, sy, sz, xx, yy, zz, e2, e3, e4, e5, f, s, xy, zz2
    integer :: it
    if (.not. (x0 >= 0.0_dp .and. y0 >= 0.0_dp .and. z0 >= 0.0_dp)) then
      rd = nan_dp; return
    end if
    if (z0 == 0.0_dp .or. x0 + y0 == 0.0_dp) then
      rd = inf_dp; return
    end if
    if (max(x0, y0, z0) > huge(1.0_dp)) then
      rd = 0.0_dp; return
    end if
    x = x0; y = y0; z = z0
    a0 = (x + y + 3.0_dp * z) / 5.0_dp
    a = a0
    ! Carlson's bound: Q = (r/4)^(-1/6) max|A0 - x|, r = 2^-56
    q = 820.0_dp * max(abs(a0 - x), abs(a0 - y), abs(a0 - z))
    s = 0.0_dp
    f = 1.0_dp
    do it = 1, 200
      if (q * f < abs(a)) exit
      sx = sqrt(x); sy = sqrt(y); sz = sqrt(z)
      lam = sx * (sy + sz) + sy * sz
      s = s + f / (sz * (z + lam))
      x = 0.25_dp * (x + lam); y = 0.25_dp * (y + lam); z = 0.25_dp * (z + lam)
      a = 0.25_dp * (a + lam)
      f = 0.25_dp * f
    end do
    xx = (a0 - x0) * f / a
    yy = (a0 - y0) * f / a
    zz = -(xx + yy) / 3.0_dp
    xy = xx * yy
    zz2 = zz * zz
    e2 = xy - 6.0_dp * zz2
    e3 = (3.0_dp * xy - 8.0_dp * zz2) * zz
    e4 = 3.0_dp * (xy - zz2) * zz2
    e5 = xy * zz2 * zz
    rd = f * (1.0_dp - 3.0_dp * e2 / 14.0_dp + e3 / 6.0_dp + 9.0_dp * e2 * e2 / 88.0_dp &
         - 3.0_dp * e4 / 22.0_dp - 9.0_dp * e2 * e3 / 52.0_dp + 3.0_dp * e5 / 26.0_dp) / (a * sqrt(a)) &
         + 3.0_dp * s
  end function carlson_rd

  ! ------------------------------------------------------------------
  ! E(m), F(phi|m), E(phi|m)
  ! ------------------------------------------------------------------

  !> Complete elliptic integral of the second kind E(m) for m <= 1.
  !> E = (mc/3) (R_D(0, mc, 1) + R_D(0, 1, mc)) (DLMF 19.25.1), no cancellation.
  elemental function ellip_e(m, mc) result(e)
    real(dp), intent(in) :: m, mc
    real(dp) :: e
    if (m /= m .or. .not. (mc >= 0.0_dp)) then
      e = nan_dp
    else if (mc == 0.0_dp) then
      e = 1.0_dp
    else if (mc > huge(1.0_dp)) then
      e = inf_dp
    else if (mc < 1.0e-30_dp) then
      ! E(1 - mc) = 1 + (mc/4)(ln(16/mc) - 1) + O(mc^2 ln mc): the Carlson form
      ! overflows its intermediate 1/mc^(3/2) for subnormal mc
      e = 1.0_dp + 0.25_dp * mc * (log(16.0_dp) - log(mc) - 1.0_dp)
    else
      e = (mc / 3.0_dp) * (carlson_rd(0.0_dp, mc, 1.0_dp) + carlson_rd(0.0_dp, 1.0_dp, mc))
    end if
  end function ellip_e

  !> phi = j pi + r with |r| <= pi/2; s = sin r and c = cos r >= 0, each to
  !> full relative accuracy, next to r = +-pi/2 too (see reduce_pi_r).
  elemental subroutine reduce_pi(phi, j, s, c)
    real(dp), intent(in) :: phi
    real(dp), intent(out) :: j, s, c
    real(dp) :: rh, rl, dh, dl, sg, p, e
    logical :: near
    ! the first steps of reduce_pi_r written out: this is every F's and E's
    ! path, and as a call it cost 15% of ellipf
    j = anint(phi / pi)
    call two_prod(j, pi, p, e)
    call two_sum(phi - p, -e, rh, rl)       ! phi - p is exact near j pi (Sterbenz)
    rl = rl - j * pi_lo
    if (abs(abs(rh) - half_pi) < 2.0_dp**(-20) + abs(rl)) then
      call reduce_pi_r(phi, j, rh, rl, near, sg, dh, dl)
      if (near) then
        call near_sincos(sg, dh, dl, s, c)
        return
      end if
    else if (rh > half_pi) then
      j = j + 1.0_dp
      call two_sum(rh - pi, rl - pi_lo, rh, e)
      rl = e
    else if (rh < -half_pi) then
      j = j - 1.0_dp
      call two_sum(rh + pi, rl + pi_lo, rh, e)
      rl = e
    end if
    s = sin(rh) + cos(rh) * rl
    c = abs(cos(rh) - sin(rh) * rl)
  end subroutine reduce_pi

  !> r = sg (pi/2 - d), d = dh + dl >= 0 below 2^-20: s = sin r = sg cos d,
  !> c = cos r = sin d (apart from reduce_pi, so that the common path stays
  !> small enough to be inlined)
  elemental subroutine near_sincos(sg, dh, dl, s, c)
    real(dp), intent(in) :: sg, dh, dl
    real(dp), intent(out) :: s, c
    s = sg * (cos(dh) - sin(dh) * dl)
    c = sin(dh) + cos(dh) * dl
  end subroutine near_sincos

  !> As reduce_pi with sin r and cos r in double-double (s = sh + sl, c = ch + cl).
  elemental subroutine reduce_pi_dd(phi, j, sh, sl, ch, cl)
    real(dp), intent(in) :: phi
    real(dp), intent(out) :: j, sh, sl, ch, cl
    real(dp) :: rh, rl, dh, dl, sg
    logical :: near
    call reduce_pi_r(phi, j, rh, rl, near, sg, dh, dl)
    if (near) then
      call dd_sincos(dh, dl, ch, cl, sh, sl)
      sh = sg * sh; sl = sg * sl
    else
      call dd_sincos(rh, rl, sh, sl, ch, cl)
      cl = sign(1.0_dp, ch) * cl; ch = abs(ch)
    end if
  end subroutine reduce_pi_dd

  !> The reduction of the exact double phi by pi: phi = j pi + r, |r| <= pi/2,
  !> r = rh + rl with pi in double-double (phi - j pi_hi is exact by Sterbenz).
  !>
  !> Next to an odd multiple N pi/2 (| |r| - pi/2 | < 2^-20) the multiple j
  !> is chosen, and the distance d = pi/2 - |r| >= 0 formed, from
  !> delta = phi - N pi/2 with pi/2 in three parts (two-products for the
  !> first two, so every product of N is exact or below 2^-160 N), summed in
  !> double-double: d keeps its relative accuracy even when it is 1e-20 (the
  !> cosine there is d itself, and F's derivative 1/D ~ 1/d when mc < d^2).
  !> Through pi in two parts, unnormalized, the rounded rh alone chose j: a
  !> phi 1e-16 beyond (2j+1) pi/2 was taken as the other side, and F came out
  !> 2 (K - F(r)) off (2.4e14 eps at mc = 3e-199).  Then near = .true., sg =
  !> sign(r) and r = sg (pi/2 - d); elsewhere near = .false. and d = 0.
  elemental subroutine reduce_pi_r(phi, j, rh, rl, near, sg, dh, dl)
    real(dp), intent(in) :: phi
    real(dp), intent(out) :: j, rh, rl, sg, dh, dl
    logical, intent(out) :: near
    real(dp) :: p, e, a, b
    j = anint(phi / pi)
    call two_prod(j, pi, p, e)
    call two_sum(phi - p, -e, rh, rl)       ! phi - p is exact near j pi (Sterbenz)
    rl = rl - j * pi_lo
    call fast_two_sum(rh, rl, a, b)
    rh = a; rl = b
    dh = 0.0_dp; dl = 0.0_dp
    near = abs(abs(rh) - half_pi) < 2.0_dp**(-20)
    if (near) then
      call reduce_pi_near(phi, j, rh, sg, dh, dl)
      rl = 0.0_dp
      return
    end if
    if (rh > half_pi) then
      j = j + 1.0_dp
      call two_sum(rh - pi, rl - pi_lo, rh, e)
      rl = e
    else if (rh < -half_pi) then
      j = j - 1.0_dp
      call two_sum(rh + pi, rl + pi_lo, rh, e)
      rl = e
    end if
    sg = sign(1.0_dp, rh)
  end subroutine reduce_pi_r

  !> reduce_pi_r next to an odd multiple of pi/2: from the first guess j and
  !> remainder rh, the final j, sg = sign(r), d = dh + dl = pi/2 - |r| >= 0 and
  !> rh = r rounded.
  elemental subroutine reduce_pi_near(phi, j, rh, sg, dh, dl)
    real(dp), intent(in) :: phi
    real(dp), intent(inout) :: j, rh
    real(dp), intent(out) :: sg, dh, dl
    real(dp) :: p, e, q, f, a, a2, b, en
    sg = sign(1.0_dp, rh)
    ! delta = phi - en pi/2, en = 2 j + sg odd (exact below 2^53)
    en = 2.0_dp * j + sg
    call two_prod(en, half_pi, p, e)
    call two_prod(en, 0.5_dp * pi_lo, q, f)
    call two_sum(phi - p, -e, a, b)          ! phi - p exact (Sterbenz)
    call two_sum(a, -q, a2, e)               ! (never an output aliased to an input)
    b = (b + e) - f - en * (0.5_dp * pi_lo2)
    call fast_two_sum(a2, b, dh, dl)
    ! r = sg pi/2 + delta: inside when sg delta <= 0, else the next multiple of pi
    if (sg * dh > 0.0_dp) then
      j = j + sg
      sg = -sg
    end if
    if (dh < 0.0_dp) then
      dh = -dh; dl = -dl
    end if
    rh = sg * half_pi - sg * dh
  end subroutine reduce_pi_near

  !> Incomplete integral of the first kind F(phi|m) for any real phi.
  elemental function ellip_f(phi, m, mc) result(f)
    real(dp), intent(in) :: phi, m, mc
    real(dp) :: f, j, s, c
    if (phi /= phi .or. m /= m .or. mc /= mc .or. abs(phi) > huge(1.0_dp)) then
      f = nan_dp; return
    end if
    call reduce_pi(phi, j, s, c)
    if (mc < 0.0_dp .and. -mc * s * s > 0.5_dp * c * c) then
      f = f_beyond_one(phi, mc)
    else
      f = f_reduced(s, c, mc)
    end if
    if (j /= 0.0_dp) f = f + 2.0_dp * j * ellip_k(m, mc)
  end function ellip_f

  !> For m > 1 (mc < 0) next to the edge of the real domain |sin r| = 1/sqrt(m),
  !> where D^2 = 1 - m s^2 = c^2 + mc s^2 cancels: s = sin r, c = cos r and
  !> D^2 from the double-double sine and cosine of the exact reduced angle,
  !> so that D^2 keeps its relative accuracy and its sign says exactly
  !> whether m sin^2 phi > 1 (beyond the domain: inside = .false.).  In
  !> double the roundings of s and c were amplified by dF/dphi = 1/D,
  !> unbounded there (up to 4e6 eps in F), and E(phi|m) was given a real
  !> value 4.8e-17 beyond the edge.  Only here: the double-double sine and
  !> cosine cost about a microsecond.
  !>
  !> mc s^2 is formed as (mc 2^-2k)(s 2^k)^2, exact scalings by powers of two
  !> with k = 256 when |mc| > 2^900: Dekker's product splits each factor
  !> by multiplying it by 2^27 + 1, which overflows for |mc| > 1.3e300 (the
  !> split was Inf - Inf = NaN, and F and E NaN inside the domain), and
  !> s^2 <= 1/m there lies near the subnormal range, where its low part
  !> loses its digits.
  elemental subroutine edge_terms(phi, mc, s, c, c2, d2, inside)
    real(dp), intent(in) :: phi, mc
    real(dp), intent(out) :: s, c, c2, d2
    logical, intent(out) :: inside
    real(dp) :: j, sh, sl, ch, cl, ah, al, bh, bl, dh, dl, ss, ms
    call reduce_pi_dd(phi, j, sh, sl, ch, cl)
    call dd_mul(ch, cl, ch, cl, ah, al)
    ss = 1.0_dp; ms = 1.0_dp
    if (abs(mc) > 2.0_dp**900) then
      ss = 2.0_dp**256; ms = 2.0_dp**(-512)
    end if
    call dd_mul(ss * sh, ss * sl, ss * sh, ss * sl, bh, bl)
    call dd_mul(bh, bl, ms * mc, 0.0_dp, dh, dl)
    call dd_add(ah, al, dh, dl, bh, bl)
    inside = bh >= 0.0_dp
    s = sh + sl
    c = ch + cl
    c2 = ah + al
    d2 = bh + bl
  end subroutine edge_terms

  !> F(phi|m), m > 1, next to the edge of the real domain (see edge_terms).
  elemental function f_beyond_one(phi, mc) result(f)
    real(dp), intent(in) :: phi, mc
    real(dp) :: f, s, c, c2, d2
    logical :: inside
    call edge_terms(phi, mc, s, c, c2, d2, inside)
    if (.not. inside) then
      f = nan_dp            ! beyond the real range
    else
      f = s * carlson_rf(c2, d2, 1.0_dp)
    end if
  end function f_beyond_one

  !> F(phi|m) from s = sin(phi) and c = cos(phi) (any quadrant of phi in
  !> (-pi, pi]), without forming phi: next to a turning point of the
  !> pendulum phi is pi/2 - tiny, and dF/dphi ~ 1/sqrt(mc) would amplify the
  !> rounding of an atan2 by 1e16 when mc ~ 1e-32.
  elemental function ellip_f_sc(s, c, m, mc) result(f)
    real(dp), intent(in) :: s, c, m, mc
    real(dp) :: f
    if (c >= 0.0_dp) then
      f = f_reduced(s, c, mc)
    else
      f = sign(2.0_dp * ellip_k(m, mc) - f_reduced(abs(s), -c, mc), s)
    end if
  end function ellip_f_sc

  !> F on |r| <= pi/2 from s = sin r, c = cos r >= 0.
  elemental function f_reduced(s, c, mc) result(f)
    real(dp), intent(in) :: s, c, mc
    real(dp) :: f, d2
    if (mc == 0.0_dp) then
      ! inverse Gudermannian atanh(s) = asinh(s/c), without the rounding of
      ! s next to 1 (+-Inf at c = 0)
      f = asinh(s / c)
      return
    end if
    d2 = c * c + mc * s * s
    if (d2 < 0.0_dp) then
      f = nan_dp            ! m > 1 beyond the real range
    else
      f = s * carlson_rf(c * c, d2, 1.0_dp)
    end if
  end function f_reduced

  !> Incomplete integral of the second kind E(phi|m) for any real phi.
  elemental function ellip_einc(phi, m, mc) result(ev)
    real(dp), intent(in) :: phi, m, mc
    real(dp) :: ev, j, s, c, c2, d2
    logical :: inside
    if (phi /= phi .or. m /= m .or. mc /= mc .or. abs(phi) > huge(1.0_dp)) then
      ev = nan_dp; return
    end if
    call reduce_pi(phi, j, s, c)
    if (mc < 0.0_dp .and. -mc * s * s > 0.5_dp * c * c) then
      ! m > 1 next to the edge of the real domain: as F (edge_terms)
      call edge_terms(phi, mc, s, c, c2, d2, inside)
      if (.not. inside) then
        ev = nan_dp
      else
        ev = einc_reduced(s, c, c2, d2, m, mc)
      end if
    else if (mc == 0.0_dp) then
      ev = s
    else if (j /= 0.0_dp .and. j * s < 0.0_dp .and. c < abs(s) .and. mc >= 1.0e-150_dp) then
      ! 2 j E + E(r) with r of the other sign and |r| > pi/4 cancels (up to
      ! half, at |j| = 1 next to |r| = pi/2, where E's own error doubled):
      ! E(phi) = (2 j + sg) E - sg Delta, sg = sign(r), both terms of one sign,
      ! with Delta = E - E(|r|) = int_0^d sqrt(mc + m sin^2 t) dt, d = pi/2 - |r|,
      ! = sqrt(mc) E(d | -m/mc), sin d = c, cos d = |s| (mc >= 1e-150: m/mc
      ! stays finite)
      ev = (2.0_dp * j + sign(1.0_dp, s)) * ellip_e(m, mc) - sign(1.0_dp, s) * sqrt(mc) &
           * einc_reduced(c, abs(s), s * s, 1.0_dp + (m / mc) * (c * c), -m / mc, 1.0_dp / mc)
      return
    else
      ev = einc_reduced(s, c, c * c, c * c + mc * s * s, m, mc)
    end if
    if (j /= 0.0_dp) ev = ev + 2.0_dp * j * ellip_e(m, mc)
  end function ellip_einc

  !> E on |r| <= pi/2 from s = sin r, c = cos r >= 0, c2 = c^2 and
  !> D^2 = d2 = 1 - m s^2 = c^2 + mc s^2 (NaN for d2 < 0: m > 1 beyond the
  !> real range).
  elemental function einc_reduced(s, c, c2, d2, m, mc) result(ev)
    real(dp), intent(in) :: s, c, c2, d2, m, mc
    real(dp) :: ev, as, s3
    if (d2 < 0.0_dp) then
      ev = nan_dp; return
    end if
    as = abs(s)
    ! for |m| > 1 the s^3 terms are m s^2 / 3 times s, m s^2 of order one or
    ! less where they matter: formed in that order, since s^3 alone
    ! underflows (to 0 for s < 5e-109, m ~ 1e250, losing a tenth of E)
    s3 = as * as * as
    if (m >= 0.0_dp .and. mc > 0.0_dp) then
      ! E = mc F + (m mc / 3) s^3 R_D(c^2, 1, D^2) + m s c / D: positive terms
      ev = mc * as * carlson_rf(c2, d2, 1.0_dp) &
           + (m * mc / 3.0_dp) * s3 * carlson_rd(c2, 1.0_dp, d2) + m * as * c / sqrt(d2)
    else if (mc < 0.0_dp) then
      ! DLMF 19.25.11 scaled by s^2: E = ((m - 1)/3) s^3 R_D(D^2, 1, c^2) + s D / c,
      ! both terms positive for m > 1 (where c > 0 on the whole domain); the
      ! form of 19.25.9 below subtracts two large terms next to the edge
      ! |s| = 1/sqrt(m) (12 eps at phi = 1.566, m = 1.00001).  Chosen by the
      ! sign of mc, not by m: for 0 < -mc < 1.1e-16 m rounds to 1 and the
      ! form below subtracted two terms of ~ln(4/c) next to pi/2 (16 eps at
      ! phi = -1.5707963257, mc = -1.6e-180)
      ev = (((-mc * as) * as) / 3.0_dp) * as * carlson_rd(d2, 1.0_dp, c2) + as * sqrt(d2) / c
    else
      ev = as * carlson_rf(c2, d2, 1.0_dp) - (((m * as) * as) / 3.0_dp) * as * carlson_rd(c2, d2, 1.0_dp)
    end if
    ev = sign(ev, s)
  end function einc_reduced

  ! ------------------------------------------------------------------
  ! The nome
  ! ------------------------------------------------------------------

  !> The variable of Jacobi's nome series: e = m / den, den = 2 (1+r)^2 (1+r^2),
  !> r = mc^(1/4) (den without cancellation).
  elemental subroutine nome_e(m, mc, den, e)
    real(dp), intent(in) :: m, mc
    real(dp), intent(out) :: den, e
    real(dp) :: r
    r = sqrt(sqrt(mc))
    den = 2.0_dp * (1.0_dp + r)**2 * (1.0_dp + r * r)
    e = m / den
  end subroutine nome_e

  !> Jacobi's series q = e + 2 e^5 + 15 e^9 + ... in e = m / (2 (1+r)^2 (1+r^2)), r = mc^(1/4).
  elemental function nome_series(m, mc) result(q)
    real(dp), intent(in) :: m, mc
    real(dp) :: q, e, e4, den
    call nome_e(m, mc, den, e)
    e4 = (e * e) * (e * e)
    q = e * (1.0_dp + e4 * (2.0_dp + e4 * (15.0_dp + e4 * (150.0_dp + e4 * (1707.0_dp &
        + e4 * (20910.0_dp + e4 * 268616.0_dp))))))
  end function nome_series

  !> ln of nome_series(m, mc) for 0 < m <= 1/2, without forming the series' value.
  elemental function log_nome_series(m, mc) result(lq)
    real(dp), intent(in) :: m, mc
    real(dp) :: lq, e, e4, den
    call nome_e(m, mc, den, e)
    e4 = (e * e) * (e * e)
    lq = log(m) - log(den) &
         + log1p_small(e4 * (2.0_dp + e4 * (15.0_dp + e4 * (150.0_dp + e4 * (1707.0_dp &
         + e4 * (20910.0_dp + e4 * 268616.0_dp))))))
  end function log_nome_series

  !> log(1 + x) for 0 <= x < 0.1 (the tail of the nome series), accurate for tiny x.
  elemental function log1p_small(x) result(y)
    real(dp), intent(in) :: x
    real(dp) :: y, u
    u = 1.0_dp + x
    if (u == 1.0_dp) then
      y = x
    else
      y = log(u) * (x / (u - 1.0_dp))
    end if
  end function log1p_small

  !> The nome q(m) = exp(-pi K(mc)/K(m)) for 0 <= m <= 1.
  elemental function ellip_nome(m, mc) result(q)
    real(dp), intent(in) :: m, mc
    real(dp) :: q
    if (.not. (m >= 0.0_dp .and. mc >= 0.0_dp)) then
      q = nan_dp
    else if (mc == 0.0_dp) then
      q = 1.0_dp
    else if (m <= 0.5_dp) then
      q = nome_series(m, mc)
    else
      ! ln q = pi^2 / ln q', with ln q' from the logarithm of the series' leading
      ! factor, so that q' (~ mc/16) may underflow without q becoming 1
      q = exp(pi * pi / log_nome_series(mc, m))
    end if
  end function ellip_nome

  ! ------------------------------------------------------------------
  ! Jacobi elliptic functions
  ! ------------------------------------------------------------------

  !> The parameter as a pair of double-doubles m = mh + ml, mc = mch + mcl with
  !> m + mc = 1 exactly, from whichever of m and mc is the exact one.
  !>
  !> Callers pass both, one derived from the other by one rounded subtraction
  !> (the binding forms mc = 1 - m when m is given, m = 1 - mc when mc is).
  !> If fl(1 - m) reproduces mc, m may be the exact one and its complement is
  !> 1 - m = mc + e exactly (two-sum); otherwise mc is, and m = 1 - mc = s + e.
  !> (When both are consistent, e = 0 and either reading is the same.)  For
  !> m = 0.1 the rounded 1 - m is 2.8e-17 off, which 2500 reductions by 2K
  !> turned into 138 eps in sn: the low parts are what keep them.
  elemental subroutine param_dd(m, mc, mh, ml, mch, mcl)
    real(dp), intent(in) :: m, mc
    real(dp), intent(out) :: mh, ml, mch, mcl
    real(dp) :: s, e
    call two_sum(1.0_dp, -m, s, e)
    if (s == mc) then
      mh = m; ml = 0.0_dp; mch = mc; mcl = e
    else
      call two_sum(1.0_dp, -mc, s, e)
      mh = s; ml = e; mch = mc; mcl = 0.0_dp
    end if
  end subroutine param_dd

  !> Precompute what the Jacobi functions need for the parameter m (= 1 - mc).
  elemental function jacobi_prepare(m, mc) result(p)
    real(dp), intent(in) :: m, mc
    type(jacobi_plan) :: p
    real(dp) :: mh, ml, mch, mcl
    call param_dd(m, mc, mh, ml, mch, mcl)
    p = jacobi_prepare_dd(mh, mch, mcl, ml)
  end function jacobi_prepare

  !> As jacobi_prepare, with the complement known in double-double (mc + mcl,
  !> used for 0 <= m < 1): the pendulum's distance from its separatrix is a
  !> product of two exact doubles, and its period over 1000 cycles needs it all.
  elemental function jacobi_prepare_dd(m, mc, mcl, ml) result(p)
    real(dp), intent(in) :: m, mc, mcl
    real(dp), intent(in), optional :: ml   !< low part of m (m + ml = 1 - (mc + mcl))
    type(jacobi_plan) :: p
    real(dp) :: cm, cmc, cmcl, mlow, kp, kpl
    if (m /= m .or. mc /= mc .or. abs(m) > huge(1.0_dp) .or. abs(mc) > huge(1.0_dp)) then
      p%regime = -1; return
    end if
    if (mc == 0.0_dp) then
      p%regime = 1; return
    else if (m >= 0.0_dp .and. mc > 0.0_dp) then
      p%regime = 0
      cm = m; cmc = mc; cmcl = mcl
    else if (m < 0.0_dp) then
      ! sn(u|m) = sd(nu u|mu)/nu, cn = cd, dn = nd, mu = -m/mc, nu = sqrt(mc);
      ! the core's complement 1/mc and the scale sqrt(mc) from mc + mcl
      p%regime = 2
      cm = -m / mc
      if (mc > 2.0_dp**900) then    ! scaled as for m > 1 below: the division's split of mc overflowed
        call dd_div(scale(1.0_dp, -600), 0.0_dp, scale(mc, -600), scale(mcl, -600), cmc, cmcl)
      else
        call dd_div(1.0_dp, 0.0_dp, mc, mcl, cmc, cmcl)
      end if
      call dd_sqrt(mc, mcl, p%sh, p%sl)
      p%mo = mc; p%mol = mcl
      p%theta = cmc <= theta_mc_max
    else
      ! sn(u|m) = sn(k u|1/m)/k, cn = dn(k u|1/m), dn = cn(k u|1/m), k = sqrt(m);
      ! the core's complement -mc/m and the scale sqrt(m) from m + ml
      p%regime = 3
      mlow = 0.0_dp
      if (present(ml)) mlow = ml
      cm = 1.0_dp / m
      ! -mc / m with both scaled by 2^-600 (exactly) where m is huge: Dekker's split inside the
      ! division multiplies by 2^27 + 1, which overflowed above m = 1.3e300 (NaN inside the domain)
      if (m > 2.0_dp**900) then
        call dd_div(scale(-mc, -600), scale(-mcl, -600), scale(m, -600), scale(mlow, -600), cmc, cmcl)
      else
        call dd_div(-mc, -mcl, m, mlow, cmc, cmcl)
      end if
      call dd_sqrt(m, mlow, p%sh, p%sl)
    end if
    p%mc = cmc
    if (p%regime == 2) then
      ! the core's k' = 1/sqrt(mo) from sqrt(mo) itself (see ellip_k_sqrt)
      call dd_div(1.0_dp, 0.0_dp, p%sh, p%sl, kp, kpl)
      call ellip_k_sqrt(kp, kpl, p%kh, p%kl)
    else
      call ellip_k_dd2(cmc, cmcl, p%kh, p%kl)
    end if
    ! Maclaurin series of tn^2 = sn^2/cn^2 in t = u^2 (coefficients from
    ! data/gen_jacobi_series.py).  tn^2 is analytic for |u| < K >= pi/2 (its
    ! nearest poles are cn's zeros +-K), so the terms fall at least as
    ! (u / (pi/2))^2 = 0.0063 each at u <= 1/8: the ninth term is below 1.2e-17
    ! of the sum (0.05 ulp; six terms at 1/16 left 0.35 ulp at m = 0), and
    ! the eight terms take one duplication fewer.
    p%ct(1) = 1.0_dp
    p%ct(2) = (2.0_dp - cm) / 3.0_dp
    p%ct(3) = (17.0_dp + cm * (-17.0_dp + cm * 2.0_dp)) / 45.0_dp
    p%ct(4) = (62.0_dp + cm * (-93.0_dp + cm * (33.0_dp - cm))) / 315.0_dp
    p%ct(5) = (1382.0_dp + cm * (-2764.0_dp + cm * (1641.0_dp + cm * (-259.0_dp + cm * 2.0_dp)))) &
              / 14175.0_dp
    p%ct(6) = (21844.0_dp + cm * (-54610.0_dp + cm * (45736.0_dp + cm * (-13994.0_dp &
              + cm * (1028.0_dp - cm * 2.0_dp))))) / 467775.0_dp
    p%ct(7) = (929569.0_dp + cm * (-2788707.0_dp + cm * (3021099.0_dp + cm * (-1394353.0_dp &
              + cm * (240594.0_dp + cm * (-8202.0_dp + cm * 4.0_dp)))))) / 42567525.0_dp
    p%ct(8) = (6404582.0_dp + cm * (-22416037.0_dp + cm * (29821335.0_dp + cm * (-18513245.0_dp &
              + cm * (5220109.0_dp + cm * (-524937.0_dp + cm * (8195.0_dp - cm))))))) / 638512875.0_dp
    p%ndbl = max(0, exponent(0.5_dp * p%kh) + 3)
    if (p%theta) p%tp = theta_prepare(cmc, cmcl, p%kh, p%kl, ellip_nome(cmc, 1.0_dp - cmc))
  end function jacobi_prepare_dd

  !> Round to the nearest integer (ties to even) for |x| < 2^51, with plain
  !> arithmetic so that loops using it vectorize (anint calls libm).
  elemental function round_int(x) result(j)
    real(dp), intent(in) :: x
    real(dp) :: j
    real(dp), parameter :: magic = 6755399441055744.0_dp   ! 2^52 + 2^51
    j = (x + magic) - magic
  end function round_int

  include 'pendula_atan.inc'


  !> The Jacobi functions of an array of u (+ ul, double-double) at one
  !> prepared parameter: blocks of 256 through jacobi_block (the method is
  !> described there), then the way back from the core parameter to m for
  !> m < 0 (jacobi_neg_final) and m > 1.
  pure subroutine jacobi_eval_array(p, u, sn, cn, dn, am, ul, want_am)
    type(jacobi_plan), intent(in) :: p
    real(dp), intent(in) :: u(:)
    real(dp), intent(in), optional :: ul(:)   !< low parts: the argument is u + ul
    !> .false.: am is not needed (NaN out) for 0 <= m < 1, a fifth less work
    logical, intent(in), optional :: want_am
    real(dp), intent(out) :: sn(:), cn(:), dn(:), am(:)
    integer, parameter :: blk = 256
    real(dp) :: ulb(blk), kh(blk), kl(blk), sc(blk), scl(blk), mc(blk), smc(blk), ct(blk, 8)
    real(dp) :: j(blk), r(blk), pp(blk), qq(blk), shf(blk), wl(blk), d
    integer :: i0, nb, k
    logical :: want
    want = .true.
    if (present(want_am)) want = want_am

    if (p%regime /= 0 .and. p%regime /= 2 .and. p%regime /= 3) then
      call jacobi_special(p, u, sn, cn, dn, am)
      return
    end if
    ! the plan's constants as per-element arrays, only as long as the longest block
    nb = min(blk, size(u))
    kh(1:nb) = p%kh; kl(1:nb) = p%kl; sc(1:nb) = p%sh; scl(1:nb) = p%sl; mc(1:nb) = p%mc
    smc(1:nb) = sqrt(p%mc)
    do k = 1, 8
      ct(1:nb, k) = p%ct(k)
    end do
    do i0 = 1, size(u), blk
      nb = min(blk, size(u) - i0 + 1)
      if (present(ul)) then
        ulb(1:nb) = ul(i0:i0+nb-1)
      else
        ulb(1:nb) = 0.0_dp
      end if
      if (p%theta) then
        ! m <= -1023: the core (complement 1/(1 - m) <= 2^-10) by the theta
        ! series, at x = sqrt(1 - m) u in double-double
        call scale_dd(nb, u(i0:i0+nb-1), ulb, p%sh, p%sl, j, r)
        call theta_jacobi_neg(p%tp, p%sh, p%sl, j(1:nb), r(1:nb), &
                              sn(i0:i0+nb-1), cn(i0:i0+nb-1), dn(i0:i0+nb-1), am(i0:i0+nb-1))
        cycle
      end if
      call jacobi_block(nb, u(i0:i0+nb-1), ulb, kh, kl, sc, scl, p%sh == 1.0_dp .and. p%sl == 0.0_dp, &
                        mc, smc, ct, p%ndbl, &
                        p%mc < mc_hyp .and. p%regime /= 2, &
                        sn(i0:i0+nb-1), cn(i0:i0+nb-1), dn(i0:i0+nb-1), am(i0:i0+nb-1), j, r, pp, qq, shf, wl, &
                        merge(want, .true., p%regime == 0))
      ! back from the core parameter to m
      select case (p%regime)
      case (2)
        call jacobi_neg_final(nb, p, u(i0:i0+nb-1), j, r, pp, qq, shf, wl, &
                              sn(i0:i0+nb-1), cn(i0:i0+nb-1), dn(i0:i0+nb-1), am(i0:i0+nb-1))
      case (3)
        ! m > 1: sn = sn(k u|1/m)/k, cn = dn(k u|1/m) > 0, dn = cn(k u|1/m);
        ! am = asin(sn) in [-pi/2, pi/2] taken as atan2(sn, cn): next to
        ! sn = +-1/k (k -> 1) the asin amplified sn's rounding by 1/cn
        ! (3.9e7 eps at m = 1 + 1.9e-16), while cn = dn of the core keeps its
        ! relative accuracy there
        do k = i0, i0 + nb - 1
          d = cn(k)
          sn(k) = sn(k) / p%sh
          cn(k) = dn(k)
          dn(k) = d
          am(k) = atan2(sn(k), cn(k))
        end do
      end select
    end do
  end subroutine jacobi_eval_array

  !> x = (u + ul) (sh + sl) in double-double, x = xh + xl (Dekker's product
  !> written out, as in jacobi_block).
  pure subroutine scale_dd(nb, u, ul, sh, sl, xh, xl)
    integer, intent(in) :: nb
    real(dp), intent(in) :: u(:), ul(:), sh, sl
    real(dp), intent(out) :: xh(:), xl(:)
    real(dp), parameter :: splitter = 134217729.0_dp
    real(dp) :: t, bh, bl, hi, lo, x, p, e
    integer :: i
    t = splitter * sh; bh = t - (t - sh); bl = sh - bh
    do i = 1, nb
      x = u(i)
      p = x * sh
      t = splitter * x; hi = t - (t - x); lo = x - hi
      e = ((hi * bh - p) + hi * bl + lo * bh) + lo * bl + x * sl + ul(i) * sh
      xh(i) = p + e
      xl(i) = e - (xh(i) - p)
    end do
  end subroutine scale_dd

  !> m < 0 from the core (parameter mu = -m/mo, mo = 1 - m, argument x = sqrt(mo) u):
  !> sn(u|m) = sd(x|mu)/sqrt(mo), cn = cd(x|mu), dn = nd(x|mu) (DLMF 22.17.4-6).
  !> Written in the core's T = tn^2 = P/Q (and mu_c = 1 - mu = 1/mo, so
  !> mo mu_c = 1 exactly in real arithmetic), every division of the
  !> transformation folds into one:
  !>   unshifted (w = |r|):  sn^2 = P/(mo Q + P),  cn^2 = mo Q/(mo Q + P),
  !>                         dn^2 = mo (Q + P)/(mo Q + P);
  !>   shifted (w = K - |r|, T = tn^2(w)):  sn^2 = Q/(Q + P),  cn^2 = P/(Q + P),
  !>                         dn^2 = (mo Q + P)/(Q + P);
  !> am = atan2(sn, cn).  All terms are positive, so each output carries T's
  !> relative error halved plus ~1.5 roundings (dividing the core's sn by dn
  !> and by sqrt(mo), as before, added two roundings and dn's own error:
  !> 4.6 eps at m = -1343).
  pure subroutine jacobi_neg_final(nb, p, u, j, r, pp, qq, shf, wl, sn, cn, dn, am)
    integer, intent(in) :: nb
    type(jacobi_plan), intent(in) :: p
    real(dp), intent(in) :: u(:), j(:), r(:), pp(:), qq(:), shf(:), wl(:)
    real(dp), intent(out) :: sn(:), cn(:), dn(:), am(:)
    real(dp) :: t, q, s, e, h, moq, inv, a, b, c, ar, half, sg, du
    integer :: i
    do i = 1, nb
      t = pp(i); q = qq(i)
      ! mo Q + P to within half an ulp (mo carried double-double)
      h = p%mo * q
      moq = h + p%mol * q
      s = h + t; e = s - h; e = (h - (s - e)) + (t - e)
      s = s + (e + p%mol * q)
      if (shf(i) > 0.0_dp) then
        inv = 1.0_dp / (q + t)
        a = q * inv
        b = t * inv
        c = s * inv
      else
        inv = 1.0_dp / s
        a = t * inv
        b = moq * inv
        c = (p%mo * (q + t) + p%mol * (q + t)) * inv
      end if
      s = sqrt(a)
      b = sqrt(b)
      c = sqrt(c)
      ! the argument's low part, du = dx / sqrt(mo): sn' = cn dn, cn' = -sn dn,
      ! dn' = -m sn cn (in u)
      du = wl(i) / p%sh
      e = s; h = b
      s = s + h * c * du
      b = b - e * c * du
      c = c + (p%mo - 1.0_dp) * e * h * du
      ar = merge(half_pi - atan_pos(b / s), atan_pos(s / b), s > b)
      ! T underflows for |r| < 1e-100: there sn = r/sqrt(mo), am = r to all digits
      s = merge(abs(r(i)) / p%sh, s, abs(r(i)) < 1.0e-100_dp)
      ar = merge(abs(r(i)) / p%sh, ar, abs(r(i)) < 1.0e-100_dp)
      half = 0.5_dp * j(i)
      sg = 1.0_dp - 2.0_dp * merge(1.0_dp, 0.0_dp, round_int(half) /= half)
      sn(i) = sign(s, r(i)) * sg
      cn(i) = b * sg
      dn(i) = c
      am(i) = (j(i) * pi + sign(ar, r(i))) + j(i) * pi_lo
      if (u(i) /= u(i) .or. abs(u(i)) > huge(1.0_dp) .or. abs(j(i)) > jacobi_max_periods) then
        sn(i) = nan_dp; cn(i) = nan_dp; dn(i) = nan_dp; am(i) = nan_dp
      end if
    end do
  end subroutine jacobi_neg_final

  !> sn, cn, dn of the core at x = w (unshifted) or x = K - w (shifted), for
  !> mc < mc_hyp, by the expansion about m = 1 (DLMF 22.10.6-8):
  !>   sn = tanh w (1 + (mc/4)(1 - w/S)),   S = sinh w cosh w,
  !>   cn = sech w (1 - (mc/4)(S - w) tanh w),  dn = sech w (1 + (mc/4)(S + w) tanh w),
  !> and, shifted, sn(K - w) = cd(w), cn(K - w) = sqrt(mc) sd(w), dn(K - w) = sqrt(mc) nd(w).
  !> Why: near m = 1 the duplications carry a relative error of a few ulp
  !> per step that the exponential growth of tn^2 amplifies by ~w (the
  !> condition number of sech w): cn ~ sech(100) came out 130 eps off,
  !> relative, at mc = 1e-280.  Here only sinh, cosh (from expm1) enter: 2-3 ulp.
  !> Why first order suffices: on [0, K/2] mc e^(2w) <= mc e^K ~ 4 sqrt(mc), so
  !> the first-order terms are below sqrt(mc)/4 <= 2^-32 of the result and the
  !> second-order ones below mc/16 <= 2^-64 (mc < 2^-60).
  pure subroutine jacobi_hyp(nb, w, sh, mc, smc, s3, c3, d3)
    integer, intent(in) :: nb
    real(dp), intent(in) :: w(:), sh(:), mc(:), smc(:)
    real(dp), intent(out) :: s3(:), c3(:), d3(:)
    real(dp) :: em, e, sw, cw, tw, ss, al, a1, b1, q
    integer :: i
    do i = 1, nb
      em = c_expm1(w(i))
      e = 1.0_dp + em
      sw = 0.5_dp * (em + em / e)          ! sinh w, no cancellation for small w
      cw = 0.5_dp * (e + 1.0_dp / e)       ! cosh w
      tw = sw / cw
      ss = sw * cw
      al = 0.25_dp * mc(i) * (1.0_dp - w(i) / max(ss, tiny(1.0_dp)))
      a1 = 0.25_dp * mc(i) * (ss - w(i)) * tw
      b1 = 0.25_dp * mc(i) * (ss + w(i)) * tw
      q = 1.0_dp / (1.0_dp + b1)
      if (sh(i) > 0.0_dp) then
        s3(i) = (1.0_dp - a1) * q          ! cd(w)
        c3(i) = smc(i) * (sw * (1.0_dp + al) * q)   ! sqrt(mc) sd(w)
        d3(i) = smc(i) * (cw * q)          ! sqrt(mc) nd(w)
      else
        s3(i) = tw * (1.0_dp + al)
        c3(i) = (1.0_dp - a1) / cw
        d3(i) = (1.0_dp + b1) / cw
      end if
    end do
  end subroutine jacobi_hyp

  !> The Jacobi functions of one block of up to 256 arguments, each with its
  !> own core parameter (0 <= m < 1 given by mc, its K = kh + kl and series
  !> ct), its own argument scale (sc + scl) and a common duplication bound.
  !>
  !> 1. reduce: x = u * scale = 2 K j + r (|r| <= K, double-double throughout),
  !>    fold onto [0, K/2]: w = |r| or w = K - |r| (shifted), kept as wh + wl
  !>    (a remainder just past K moves to the next half period);
  !> 2. T = tn^2(w) = P/Q: Maclaurin series at w / 2^n <= 1/8 (P = T, Q = 1;
  !>    n <= ndbl per element), then n duplications
  !>    tn^2(2u) = 4 T (1 + mc T) (1 + T) / (1 - mc T^2)^2 carried as a
  !>    fraction without dividing: with Y = (Q^2 - mc P^2)^2 and
  !>    D = Q^3 (P + mc P) + mc P^2 (3 Q^2 - mc P^2), P' = 4 P (Y + D), Q' = Q Y.
  !>    Every term is positive on [0, K/2] (mc T^2 <= sqrt(mc)/4 at K/4), so
  !>    nothing cancels.  Range: Q_n = prod_k (1 - mc T_k^2)^(2 5^(n-1-k)); the
  !>    last factor is >= (3/4)^2 and mc T_k^2 shrinks at least 16-fold per step
  !>    back (T ~ u^2 below K/4), against the exponent's 5, so Q_n >= 0.4:
  !>    Q neither underflows nor overflows, and P = T Q <= tn^2(K/2) =
  !>    1/sqrt(mc) < 1e162, whose largest intermediate ~T_(n-1)^2 is as small;
  !>    for mc < mc_hyp the expansion about m = 1 instead (jacobi_hyp);
  !> 3. sn, cn, dn from P and Q with one division:
  !>      unshifted: sn^2 = P/(Q+P), cn^2 = Q/(Q+P), dn^2 = (Q + mc P)/(Q+P);
  !>      shifted (tn^2(K-w) = 1/(mc T)): sn^2 = Q/(Q+mc P),
  !>      cn = sqrt(mc) sqrt(P/(Q+mc P)), dn = sqrt(mc) sqrt((Q+P)/(Q+mc P)),
  !>    the low part wl put back to first order, am = atan2(sn, cn) (one more
  !>    division), so whatever rounding does they stay consistent with one
  !>    argument, and cd = cn/dn keeps full accuracy next to K.  (The divided
  !>    form took ndbl + 4 divisions per element; this one takes 2.)
  !> The loops have no data-dependent trip counts and no libm calls, so the
  !> compiler vectorizes them.  Also returned: j, r (rounded), the final P and
  !> Q, the shift flag and wl (for the m < 0 transformation).
  pure subroutine jacobi_block(nb, u, ulb, kh, kl, sc, scl, unit, mc, smc, ct, ndbl, hyp, sn, cn, dn, am, j, r, pp, qq, sh, wl, &
                          want_am)
    integer, intent(in) :: nb, ndbl
    !> am is computed only when wanted (the exact libration needs sn, cn, dn only:
    !> its atan2 is a fifth of the block's work); otherwise am = NaN
    logical, intent(in), optional :: want_am
    logical, intent(in) :: unit  !< the scale is exactly 1 (sc = 1, scl = 0)
    logical, intent(in) :: hyp   !< m -> 1 (mc < mc_hyp): sn, cn, dn by their expansion in mc
    real(dp), intent(in) :: u(:), ulb(:), kh(:), kl(:), sc(:), scl(:), mc(:), ct(:, :)
    real(dp), intent(in) :: smc(:)   !< sqrt(mc)
    real(dp), intent(out) :: sn(:), cn(:), dn(:), am(:), j(:), r(:), pp(:), qq(:), sh(:), wl(:)
    real(dp), parameter :: splitter = 134217729.0_dp
    real(dp) :: w(nb), a(nb), s3(nb), c3(nb), d3(nb), xha(nb), xla(nb), xa, xb, z, z2, z4, z8, pz
    integer :: ndup
    real(dp) :: x, xh, xl, hi, lo, bh, bl, pr, pe, t, g, xx, inv, s, c, d, ar, half, odd, ss, e1, q, q2, gp, y, f, t2, t4
    integer :: i, k

    ! 1. reduction (Dekker products written out so that the loop vectorizes)
    !    x = u * scale in double-double; the scale is 1 for 0 <= m < 1 (and
    !    every per-element parameter), and then x = u + ul as it stands
    if (unit) then
      xha(1:nb) = u(1:nb)
      xla(1:nb) = ulb(1:nb)
    else
      do i = 1, nb
        x = u(i)
        t = splitter * sc(i); bh = t - (t - sc(i)); bl = sc(i) - bh
        xh = x * sc(i)
        t = splitter * x; hi = t - (t - x); lo = x - hi
        xl = ((hi * bh - xh) + hi * bl + lo * bh) + lo * bl + x * scl(i)
        xha(i) = xh
        xla(i) = xl + ulb(i) * sc(i)
      end do
    end if
    do i = 1, nb
      xh = xha(i); xl = xla(i)
      j(i) = round_int(xh * (0.5_dp / kh(i)))
      g = 2.0_dp * j(i)
      pr = g * kh(i)
      t = splitter * g; hi = t - (t - g); lo = g - hi
      t = splitter * kh(i); xx = t - (t - kh(i)); ss = kh(i) - xx
      pe = ((hi * xx - pr) + hi * ss + lo * xx) + lo * ss
      ! r = x - 2 j K kept in double-double (rh + rl): next to a turning point
      ! the shifted argument K - |r| must not carry the rounding of r (eps K)
      hi = xh - pr                       ! exact (Sterbenz)
      lo = -pe
      t = hi + lo; ss = t - hi; e1 = (hi - (t - ss)) + (lo - ss)
      lo = xl - g * kl(i)
      r(i) = t + lo; ss = r(i) - t; e1 = e1 + ((t - (r(i) - ss)) + (lo - ss))
      ! w = |r| (unshifted) or K - |r| (shifted), as wh + wl: the low part
      ! is put back at the end, to first order (step 3)
      w(i) = abs(r(i))
      sh(i) = merge(1.0_dp, 0.0_dp, w(i) > 0.5_dp * kh(i))
      hi = kh(i) - w(i)                  ! exact (Sterbenz) when shifted
      lo = kl(i) - sign(1.0_dp, r(i)) * e1
      t = hi + lo; ss = t - hi; ss = (hi - (t - ss)) + (lo - ss)
      ! j = round(x / 2K) is taken from the rounded x / 2K, so next to an odd
      ! multiple of K the remainder may pass K by a little: w < 0.  That point
      ! is w' = -w into the next half period (j + 1 in the direction of r,
      ! r' = r -+ 2K); clamping w to 0 instead lost cn's sign and size
      ! entirely next to its zeros
      f = merge(1.0_dp, 0.0_dp, sh(i) > 0.0_dp .and. t < 0.0_dp)
      g = sign(1.0_dp, r(i))
      j(i) = j(i) + f * g
      r(i) = r(i) - f * (2.0_dp * g * kh(i))
      ss = ss - 2.0_dp * f * ss
      wl(i) = merge(-ss, g * e1, sh(i) > 0.0_dp)   ! d x = this
      w(i) = merge(abs(t), w(i), sh(i) > 0.0_dp)
    end do
    ndup = ndbl
    if (hyp) ndup = 0
    ! 2. T = tn^2(w) = P/Q; each element scaled to w 2^-n <= 1/8 with its own
    !    n <= ndbl (a small w takes fewer duplications, so fewer roundings)
    a(1:nb) = 1.0_dp
    do k = 1, ndup
      do i = 1, nb
        a(i) = merge(0.5_dp * a(i), a(i), w(i) * a(i) > 0.125_dp)
      end do
    end do
    do i = 1, nb
      a(i) = w(i) * a(i)                 ! exact: a power of 2 times w
      t = a(i) * a(i)
      ! Estrin's scheme (t <= 1/64: each term ~100 times below the one before,
      ! so the order of rounding hardly matters; Horner's chain of 8 was slow)
      t2 = t * t
      t4 = t2 * t2
      pp(i) = t * (((ct(i, 1) + t * ct(i, 2)) + t2 * (ct(i, 3) + t * ct(i, 4))) &
              + t4 * ((ct(i, 5) + t * ct(i, 6)) + t2 * (ct(i, 7) + t * ct(i, 8))))
      qq(i) = 1.0_dp
    end do
    do k = 1, ndup
      do i = 1, nb
        ! T' = 4 T (1 + D/Y) with Y = (Q^2 - mc P^2)^2 and
        ! D = Q(Q + mc P)(Q + P) Q^2 - Y = Q^3 (P + mc P) + mc P^2 (3 Q^2 - mc P^2) > 0:
        ! P' = 4 P (Y + D), Q' = Q Y.  The same rounded Y in P' and Q' cancels
        ! in T' except through D/Y, which is small while T is (~1.5 ulp a step
        ! against ~2.5 for the product form)
        t = pp(i); q = qq(i)
        g = mc(i) * t
        q2 = q * q
        gp = g * t
        y = (q2 - gp)**2
        d = q2 * q * (t + g) + gp * (3.0_dp * q2 - gp)
        ! active while the element's argument a is below its w: 0/1 factors
        ! (exact), as merges here kept the loop from vectorizing
        f = merge(1.0_dp, 0.0_dp, a(i) < w(i))
        pp(i) = f * (4.0_dp * t * (y + d)) + (1.0_dp - f) * t
        qq(i) = f * (q * y) + (1.0_dp - f) * q
        a(i) = a(i) + f * a(i)
      end do
    end do
    ! 3. sn, cn, dn, am of the core; sign of r; parity of j
    if (hyp) then
      call jacobi_hyp(nb, w, sh, mc, smc, s3, c3, d3)
    else
      do i = 1, nb
        t = pp(i); q = qq(i)
        g = mc(i) * t
        inv = 1.0_dp / (q + merge(g, t, sh(i) > 0.0_dp))
        s3(i) = sqrt(merge(q, t, sh(i) > 0.0_dp) * inv)
        ! shifted: cn = sqrt(mc) sqrt(P/(Q + mc P)), dn = sqrt(mc) sqrt((Q+P)/(Q + mc P)):
        ! mc P itself is subnormal next to cn's zeros when mc ~ 1e-300
        c3(i) = sqrt(merge(t, q, sh(i) > 0.0_dp) * inv) * merge(smc(i), 1.0_dp, sh(i) > 0.0_dp)
        d3(i) = sqrt(merge(q + t, q + g, sh(i) > 0.0_dp) * inv) * merge(smc(i), 1.0_dp, sh(i) > 0.0_dp)
      end do
    end if
    do i = 1, nb
      s = s3(i); c = c3(i); d = d3(i)
      ! the low part dx of the argument: sn' = cn dn, cn' = -sn dn, dn' = -m sn cn
      ! (s, c, d >= 0 here; m = 1 - mc of the core)
      e1 = wl(i)
      pe = s; pr = c
      s = s + pr * d * e1
      c = c - pe * d * e1
      d = d - (1.0_dp - mc(i)) * pe * pr * e1
      s3(i) = s; c3(i) = c
      ! T underflows for |r| < 1e-154: there sn = am = r to all digits
      s = merge(abs(r(i)), s, abs(r(i)) < 1.0e-100_dp)
      s = sign(s, r(i))
      half = 0.5_dp * j(i)
      odd = merge(1.0_dp, 0.0_dp, round_int(half) /= half)
      ! NaN for NaN or infinite u and beyond 2^48 half periods (merges, not an
      ! if, so that the loop stays vectorized)
      x = u(i)
      f = merge(1.0_dp, 0.0_dp, x /= x .or. abs(x) > huge(1.0_dp) .or. abs(j(i)) > jacobi_max_periods)
      sn(i) = merge(nan_dp, s * (1.0_dp - 2.0_dp * odd), f > 0.0_dp)
      cn(i) = merge(nan_dp, c * (1.0_dp - 2.0_dp * odd), f > 0.0_dp)
      dn(i) = merge(nan_dp, d, f > 0.0_dp)
    end do
    if (present(want_am)) then
      if (.not. want_am) then
        am(1:nb) = nan_dp
        return
      end if
    end if
    do i = 1, nb
      s = s3(i); c = c3(i)
      ! am = atan2(s, c) for s, c >= 0 with one division, written out here (as
      ! a function gcc inlined it only with a single call site, and the loop
      ! did not vectorize otherwise): the reductions of atan_pos (z -> 1/z
      ! above 1, z -> (z-1)/(z+1) above tan(pi/8), the half angle
      ! z -> z/(1 + sqrt(1 + z^2))) done on the pair (a, b) with z = a/b as
      ! 0/1 factors (exact: x + 0 y = x), and one a/(b + sqrt(a^2 + b^2)) at
      ! the end; s, c <= ~1, so nothing over- or underflows.  About 2 ulp.
      g = merge(1.0_dp, 0.0_dp, s > c)
      xa = merge(c, s, s > c)
      xb = merge(s, c, s > c)
      f = merge(1.0_dp, 0.0_dp, xa > 0.41421356237309503_dp * xb)
      z = xa - f * xb
      xb = xb + f * xa
      z = z / (xb + sqrt(xb * xb + z * z))
      z2 = z * z
      ! the series sum_k (-1)^k z2^k / (2k+3), k <= 11, by Estrin's scheme (a
      ! Horner chain of 12 dependent multiply-adds was the loop's critical
      ! path; |z| <= tan(pi/16): z2 <= 0.04, each term 25 times below the one
      ! before, and p enters times z2, so the order of rounding hardly matters)
      z4 = z2 * z2
      z8 = z4 * z4
      pz = ((1.0_dp/3.0_dp - z2 * (1.0_dp/5.0_dp)) + z4 * (1.0_dp/7.0_dp - z2 * (1.0_dp/9.0_dp))) &
           + z8 * (((1.0_dp/11.0_dp - z2 * (1.0_dp/13.0_dp)) + z4 * (1.0_dp/15.0_dp - z2 * (1.0_dp/17.0_dp))) &
           + z8 * ((1.0_dp/19.0_dp - z2 * (1.0_dp/21.0_dp)) + z4 * (1.0_dp/23.0_dp - z2 * (1.0_dp/25.0_dp))))
      ar = 2.0_dp * (z - z * z2 * pz)
      ar = merge(0.78539816339744831_dp + ar, ar, f > 0.0_dp)
      ar = merge(half_pi - ar, ar, g > 0.0_dp)
      ar = merge(abs(r(i)), ar, abs(r(i)) < 1.0e-100_dp)
      ar = sign(ar, r(i))
      x = u(i)
      f = merge(1.0_dp, 0.0_dp, x /= x .or. abs(x) > huge(1.0_dp) .or. abs(j(i)) > jacobi_max_periods)
      am(i) = merge(nan_dp, (j(i) * pi + ar) + j(i) * pi_lo, f > 0.0_dp)
    end do
  end subroutine jacobi_block

  !> sn, cn, dn, am for arrays of u and of m (one parameter per argument).
  !> The common case 0 <= m < 1 runs vectorized in blocks: K in double-double
  !> by an AGM iterated until every element of the block has converged, the
  !> series coefficients, and jacobi_block with the block's largest duplication
  !> count; m < 0, m >= 1 and NaN take the scalar path.
  pure subroutine jacobi_eval_varm(u, m, mc, sn, cn, dn, am)
    real(dp), intent(in) :: u(:), m(:), mc(:)
    real(dp), intent(out) :: sn(:), cn(:), dn(:), am(:)
    integer, parameter :: blk = 256
    real(dp) :: pm(blk), pmc(blk), pmcl(blk), kh(blk), kl(blk), one(blk), zero(blk), ct(blk, 8)
    real(dp) :: j(blk), s(blk), c(blk), pq(blk), sf(blk), wq(blk), smc(blk)
    logical :: ok(blk)
    real(dp) :: x, sm, e, t
    integer :: i0, nb, i, ndbl

    one = 1.0_dp; zero = 0.0_dp
    do i0 = 1, size(u), blk
      nb = min(blk, size(u) - i0 + 1)
      do i = 1, nb
        ! (mc below mc_hyp: the scalar path, which takes the expansion about m = 1)
        ok(i) = m(i0 + i - 1) >= 0.0_dp .and. mc(i0 + i - 1) >= mc_hyp .and. &
                m(i0 + i - 1) <= 1.0_dp .and. mc(i0 + i - 1) <= 1.0_dp
        pm(i) = merge(m(i0 + i - 1), 0.5_dp, ok(i))
        pmc(i) = merge(mc(i0 + i - 1), 0.5_dp, ok(i))
        ! the complement's low part when m is the exact one (see param_dd)
        sm = 1.0_dp - pm(i); t = sm - 1.0_dp; e = (1.0_dp - (sm - t)) + (-pm(i) - t)
        pmcl(i) = merge(e, 0.0_dp, sm == pmc(i))
      end do
      ! K = pi / (2 AGM(1, sqrt(mc))) in double-double, all elements together
      ! (in C for its fused multiply-adds; the algorithm and its error are
      ! described there)
      call c_agm_k(int(nb, c_int), pmc, pmcl, kh, kl, smc)
      ! series of tn^2 for each parameter, the divisions by constants as
      ! products (a coefficient then carries ~1 ulp instead of 0.5, which moves
      ! T at w 2^-n <= 1/8 by less than 2^-6 ulp)
      do i = 1, nb
        x = pm(i)
        ct(i, 1) = 1.0_dp
        ct(i, 2) = (2.0_dp - x) * (1.0_dp / 3.0_dp)
        ct(i, 3) = (17.0_dp + x * (-17.0_dp + x * 2.0_dp)) * (1.0_dp / 45.0_dp)
        ct(i, 4) = (62.0_dp + x * (-93.0_dp + x * (33.0_dp - x))) * (1.0_dp / 315.0_dp)
        ct(i, 5) = (1382.0_dp + x * (-2764.0_dp + x * (1641.0_dp + x * (-259.0_dp + x * 2.0_dp)))) &
                   * (1.0_dp / 14175.0_dp)
        ct(i, 6) = (21844.0_dp + x * (-54610.0_dp + x * (45736.0_dp + x * (-13994.0_dp &
                   + x * (1028.0_dp - x * 2.0_dp))))) * (1.0_dp / 467775.0_dp)
        ct(i, 7) = (929569.0_dp + x * (-2788707.0_dp + x * (3021099.0_dp + x * (-1394353.0_dp &
                   + x * (240594.0_dp + x * (-8202.0_dp + x * 4.0_dp)))))) * (1.0_dp / 42567525.0_dp)
        ct(i, 8) = (6404582.0_dp + x * (-22416037.0_dp + x * (29821335.0_dp + x * (-18513245.0_dp &
                   + x * (5220109.0_dp + x * (-524937.0_dp + x * (8195.0_dp - x))))))) * (1.0_dp / 638512875.0_dp)
      end do
      ndbl = max(0, exponent(0.5_dp * maxval(kh(1:nb))) + 3)
      call jacobi_block(nb, u(i0:i0+nb-1), zero, kh, kl, one, zero, .true., pmc, smc, ct, ndbl, .false., &
                        sn(i0:i0+nb-1), cn(i0:i0+nb-1), dn(i0:i0+nb-1), am(i0:i0+nb-1), j, s, c, pq, sf, wq)
      do i = 1, nb
        if (.not. ok(i)) call jacobi_sncndn(u(i0 + i - 1), m(i0 + i - 1), mc(i0 + i - 1), &
          sn(i0 + i - 1), cn(i0 + i - 1), dn(i0 + i - 1), am(i0 + i - 1))
      end do
    end do
  end subroutine jacobi_eval_varm

  !> sn, cn, dn and the continuous amplitude am at u, for a prepared parameter.
  elemental subroutine jacobi_eval(p, u, sn, cn, dn, am)
    type(jacobi_plan), intent(in) :: p
    real(dp), intent(in) :: u
    real(dp), intent(out) :: sn, cn, dn, am
    real(dp) :: o(4, 1)
    call jacobi_eval_array(p, [u], o(1, :), o(2, :), o(3, :), o(4, :))
    sn = o(1, 1); cn = o(2, 1); dn = o(3, 1); am = o(4, 1)
  end subroutine jacobi_eval

  !> m = 1 (tanh, sech, the Gudermannian) and the NaN cases.
  elemental subroutine jacobi_special(p, u, sn, cn, dn, am)
    type(jacobi_plan), intent(in) :: p
    real(dp), intent(in) :: u
    real(dp), intent(out) :: sn, cn, dn, am
    if (p%regime == 1 .and. u == u) then
      sn = tanh(u)
      cn = 1.0_dp / cosh(u)
      dn = cn
      am = atan(sinh(u))
    else
      sn = nan_dp; cn = nan_dp; dn = nan_dp; am = nan_dp
    end if
  end subroutine jacobi_special

  !> sn, cn, dn, am(u|m) in one call (prepares the parameter each time).
  elemental subroutine jacobi_sncndn(u, m, mc, sn, cn, dn, am)
    real(dp), intent(in) :: u, m, mc
    real(dp), intent(out) :: sn, cn, dn, am
    call jacobi_eval(jacobi_prepare(m, mc), u, sn, cn, dn, am)
  end subroutine jacobi_sncndn

end module pendula_elliptic
