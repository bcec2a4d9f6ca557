!> Error-free transformations and a few double-double operations.
!>
!> The kernel is compiled without FMA contraction (-ffp-contract=off), so
!> Dekker's splitting product is exact and Knuth's two-sum is exact.
module pendula_dd
  use pendula_kinds, only: dp
  implicit none
  private
  public :: two_sum, fast_two_sum, two_prod, dd_mul_d, dd_sqrt

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

  !> (rh + rl) = (xh + xl) * y to double-double accuracy.
  elemental subroutine dd_mul_d(xh, xl, y, rh, rl)
    real(dp), intent(in) :: xh, xl, y
    real(dp), intent(out) :: rh, rl
    real(dp) :: p, e
    call two_prod(xh, y, p, e)
    e = e + xl * y
    call fast_two_sum(p, e, rh, rl)
  end subroutine dd_mul_d

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

end module pendula_dd
