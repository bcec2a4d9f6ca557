!> Error-free transformations and a few double-double operations.
!>
!> The kernel is compiled without FMA contraction (-ffp-contract=off), so
!> Dekker's splitting product is exact and Knuth's two-sum is exact.
module pendula_dd
  use pendula_kinds, only: dp
  implicit none
  private
  public :: two_sum, fast_two_sum, two_prod, dd_sqrt, dd_add, dd_mul, dd_sincos, dd_div_d, dd_div

  real(dp), parameter :: splitter = 134217729.0_dp   ! 2**27 + 1

contains

  !> s + e = a + b exactly (Knuth).
  elemental subroutine two_sum(a, b, s, e)
    real(dp), intent(in) :: a, b
    real(dp), intent(out) :: s, e
    real(dp) :: bb
    s = a + b
    bb = s - a
    e = (a - (s - bb)) + (b - bb)
  end subroutine two_sum

  !> s + e = a + b exactly, assuming |a| >= |b| (Dekker).
  elemental subroutine fast_two_sum(a, b, s, e)
    real(dp), intent(in) :: a, b
    real(dp), intent(out) :: s, e
    s = a + b
    e = b - (s - a)
  end subroutine fast_two_sum

  !> p + e = a * b exactly (Dekker's product with Veltkamp splitting).
  elemental subroutine two_prod(a, b, p, e)
    real(dp), intent(in) :: a, b
    real(dp), intent(out) :: p, e
    real(dp) :: t, ah, al, bh, bl
    p = a * b
    t = splitter * a
    ah = t - (t - a)
    al = a - ah
    t = splitter * b
    bh = t - (t - b)
    bl = b - bh
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl
  end subroutine two_prod

  !> (rh + rl) = sqrt(xh + xl) to double-double accuracy, xh >= 0.
  elemental subroutine dd_sqrt(xh, xl, rh, rl)
    real(dp), intent(in) :: xh, xl
    real(dp), intent(out) :: rh, rl
    real(dp) :: r, p, e, corr
    if (xh <= 0.0_dp) then
      rh = sqrt(xh)
      rl = 0.0_dp
      return
    end if
    r = sqrt(xh)
    call two_prod(r, r, p, e)
    corr = (((xh - p) - e) + xl) / (2.0_dp * r)
    call fast_two_sum(r, corr, rh, rl)
  end subroutine dd_sqrt

  !> (rh + rl) = (ah + al) + (bh + bl) to double-double accuracy.
  elemental subroutine dd_add(ah, al, bh, bl, rh, rl)
    real(dp), intent(in) :: ah, al, bh, bl
    real(dp), intent(out) :: rh, rl
    real(dp) :: s, e, t, f, s2, t2
    call two_sum(ah, bh, s, e)
    call two_sum(al, bl, t, f)
    call fast_two_sum(s, e + t, s2, t2)
    call fast_two_sum(s2, t2 + f, rh, rl)
  end subroutine dd_add

  !> (rh + rl) = (ah + al) * (bh + bl) to double-double accuracy.
  elemental subroutine dd_mul(ah, al, bh, bl, rh, rl)
    real(dp), intent(in) :: ah, al, bh, bl
    real(dp), intent(out) :: rh, rl
    real(dp) :: p, e
    call two_prod(ah, bh, p, e)
    call fast_two_sum(p, e + (ah * bl + al * bh), rh, rl)
  end subroutine dd_mul

  !> sin and cos of x = xh + xl (|x| <= 2) in double-double, by the Taylor
  !> series to x^45 (the last term is below 1e-40 there).
  elemental subroutine dd_sincos(xh, xl, sh, sl, ch, cl)
    real(dp), intent(in) :: xh, xl
    real(dp), intent(out) :: sh, sl, ch, cl
    real(dp) :: x2h, x2l, th, tl, uh, ul
    integer :: k
    call dd_mul(xh, xl, xh, xl, x2h, x2l)
    ! Horner from the top: sin x = x (1 - x^2/(2 3) (1 - x^2/(4 5) (...)))
    sh = 1.0_dp; sl = 0.0_dp
    ch = 1.0_dp; cl = 0.0_dp
    do k = 22, 1, -1
      call dd_mul(x2h, x2l, sh, sl, th, tl)
      call dd_div_d(th, tl, real((2 * k) * (2 * k + 1), dp), uh, ul)
      call dd_add(1.0_dp, 0.0_dp, -uh, -ul, sh, sl)
      call dd_mul(x2h, x2l, ch, cl, th, tl)
      call dd_div_d(th, tl, real((2 * k - 1) * (2 * k), dp), uh, ul)
      call dd_add(1.0_dp, 0.0_dp, -uh, -ul, ch, cl)
    end do
    call dd_mul(xh, xl, sh, sl, th, tl)
    sh = th; sl = tl
  end subroutine dd_sincos

  !> (rh + rl) = (ah + al) / b to double-double accuracy.
  elemental subroutine dd_div_d(ah, al, b, rh, rl)
    real(dp), intent(in) :: ah, al, b
    real(dp), intent(out) :: rh, rl
    real(dp) :: q, p, e
    q = ah / b
    call two_prod(q, b, p, e)
    call fast_two_sum(q, (((ah - p) - e) + al) / b, rh, rl)
  end subroutine dd_div_d

  !> (qh + ql) = (ah + al) / (bh + bl) to double-double accuracy, b /= 0.
  elemental subroutine dd_div(ah, al, bh, bl, qh, ql)
    real(dp), intent(in) :: ah, al, bh, bl
    real(dp), intent(out) :: qh, ql
    real(dp) :: q1, p, e, r
    q1 = ah / bh
    call two_prod(q1, bh, p, e)
    r = (((ah - p) - e) + al) - q1 * bl
    call fast_two_sum(q1, r / bh, qh, ql)
  end subroutine dd_div

end module pendula_dd
