!> Characteristic values of Mathieu's equation y'' + (a - 2 q cos 2z) y = 0.
!>
!> Every value is an eigenvalue of a symmetric tridiagonal (Hill) matrix:
!> the Floquet solution sum_k c_k exp(i (nu + 2k) z) gives the bi-infinite
!> matrix with diagonal (nu + 2k)^2 and couplings q (DLMF 28.12), and the
!> solutions of period pi or 2 pi of integer order give the four classic
!> one-sided matrices of DLMF 28.4 (a_2m, a_2m+1, b_2m+1, b_2m+2).
!>
!> The wanted eigenvalue is picked by its index with Sturm-sequence
!> bisection, so a value never jumps to a neighbouring order: within one
!> matrix the eigenvalues are simple for every q, and the index says which.
!> The matrix is the window of rows whose order s lies where the eigenvector
!> lives (s^2 within a few |q| of the value, plus the decaying tail).  The
!> eigenvector's components at the window's edges (from a twisted
!> factorisation, accurate even when they are 1e-100) give the residual of
!> the truncated eigenvector in the infinite operator: |q| times the edge
!> components, an a-posteriori bound on the truncation error that the
!> window is widened until it meets.  The value from the bisection is the
!> exact eigenvalue of a matrix whose couplings differ from q by a few ulp
!> (Kahan's backward error of the Sturm count), so the absolute error is a
!> few eps times |q| plus the truncation bound.
!>
!> Negative q: a_2m(-q) = a_2m(q), b_2m+2(-q) = b_2m+2(q), a_2m+1(-q) =
!> b_2m+1(q) (DLMF 28.2.26), and the non-integer lambda_nu depends on |q|
!> only; the matrices below are written for q of either sign.
module pendula_mathieu
  use pendula_kinds, only: dp, nan_dp, eps_dp
  use pendula_dd, only: two_sum, two_prod, dd_add, dd_div, dd_mul
  use, intrinsic :: iso_c_binding, only: c_int, c_double
  implicit none
  private
  public :: mathieu_char, mathieu_level, mathieu_levels, mathieu_level_dd, mathieu_nu, mathieu_level_vector
  public :: mathieu_function
  public :: mathieu_max_q, mathieu_max_order
  public :: mathieu_ok, mathieu_bad_input, mathieu_no_convergence

  !> the largest |q| and order served (the window grows as sqrt(|q|))
  real(dp), parameter :: mathieu_max_q = 1.0e10_dp
  real(dp), parameter :: mathieu_max_order = 1.0e8_dp
  integer, parameter :: mathieu_ok = 0, mathieu_bad_input = 1, mathieu_no_convergence = 2
  !> the most rows of a window (|q| = 1e10 needs about 2e5)
  integer, parameter :: max_rows = 4000000
  real(dp), parameter :: sqrt2 = 1.4142135623730950488_dp
  !> windows up to this many rows factorise in stack arrays
  integer, parameter :: small_rows = 512

  interface
    !> The polish's rows (kernel/mathieu/pendula_mathieu_polish.c): z'r,
    !> z'z and r'r of the double-double residual r = (T - x) z on rows
    !> i1..i2 of the window (rows r0 .. r0 + n - 1 of family fam).
    pure subroutine c_polish_rows(fam, nu, q, aq, e0, e0l, r0, n, i1, i2, x, z, num, den, rr) &
        bind(C, name='pendula_mathieu_polish_rows')
      import :: c_int, c_double
      integer(c_int), value, intent(in) :: fam, r0, n, i1, i2
      real(c_double), value, intent(in) :: nu, q, aq, e0, e0l, x
      real(c_double), intent(in) :: z(*)
      real(c_double), intent(out) :: num, den, rr
    end subroutine c_polish_rows
  end interface

contains

  ! ------------------------------------------------------------------
  ! Families of matrices.  fam 0: bi-infinite, row k has order s = nu + 2k.
  ! fam 1..4: the one-sided matrices of a_2m, a_2m+1, b_2m+1, b_2m+2, row
  ! i >= 0 of order s = base + 2i with base 0, 1, 1, 2.
  ! ------------------------------------------------------------------

  pure integer function fam_base(fam)
    integer, intent(in) :: fam
    select case (fam)
    case (1); fam_base = 0
    case (2, 3); fam_base = 1
    case default; fam_base = 2
    end select
  end function fam_base

  !> First and last row index of the window of orders [slo, shi] (cut = no
  !> lower cut: the window reaches the natural start, row 0 of a one-sided
  !> family or s = -shi of the bi-infinite one).
  pure subroutine window_rows(fam, nu, slo, shi, cut, r0, r1)
    integer, intent(in) :: fam
    real(dp), intent(in) :: nu, slo, shi
    logical, intent(in) :: cut
    integer, intent(out) :: r0, r1
    real(dp) :: b
    if (fam == 0) then
      r1 = floor((shi - nu) / 2.0_dp)
      if (cut) then
        r0 = ceiling((slo - nu) / 2.0_dp)
      else
        r0 = ceiling((-shi - nu) / 2.0_dp)
      end if
    else
      b = real(fam_base(fam), dp)
      r1 = max(0, floor((shi - b) / 2.0_dp))
      r0 = 0
      if (cut) r0 = max(0, ceiling((slo - b) / 2.0_dp))
    end if
    r0 = min(r0, r1)
  end subroutine window_rows

  !> Diagonal d and squared couplings e2 (e2(i) couples rows i and i+1) of
  !> the rows r0..r1 of a family.
  pure subroutine build(fam, nu, q, r0, r1, d, e2)
    integer, intent(in) :: fam, r0, r1
    real(dp), intent(in) :: nu, q
    real(dp), intent(out) :: d(:), e2(:)
    integer :: r, i
    real(dp) :: s
    do r = r0, r1
      i = r - r0 + 1
      if (fam == 0) then
        s = nu + 2.0_dp * real(r, dp)
      else
        s = real(fam_base(fam) + 2 * r, dp)
      end if
      d(i) = s * s
      e2(i) = q * q
    end do
    if (r0 == 0) then
      if (fam == 1) e2(1) = 2.0_dp * q * q
      if (fam == 2) d(1) = 1.0_dp + q
      if (fam == 3) d(1) = 1.0_dp - q
    end if
  end subroutine build

  !> Number of eigenvalues below x (Sturm sequence of the LDL^T pivots).
  pure integer function sturm_count(d, e2, n, x, pivmin) result(c)
    integer, intent(in) :: n
    real(dp), intent(in) :: d(n), e2(n), x, pivmin
    real(dp) :: t
    integer :: i
    c = 0
    t = d(1) - x
    if (abs(t) < pivmin) t = -pivmin
    if (t < 0.0_dp) c = 1
    do i = 2, n
      t = (d(i) - x) - e2(i - 1) / t
      if (abs(t) < pivmin) t = -pivmin
      if (t < 0.0_dp) c = c + 1
    end do
  end function sturm_count

  !> The Sturm counts at two points xa and xb in one loop (the same counts
  !> as two calls of sturm_count; the two division chains overlap).
  pure subroutine sturm_count_pair(d, e2, n, xa, xb, pivmin, ca, cb)
    integer, intent(in) :: n
    real(dp), intent(in) :: d(n), e2(n), xa, xb, pivmin
    integer, intent(out) :: ca, cb
    real(dp) :: ta, tb
    integer :: i
    ca = 0
    cb = 0
    ta = d(1) - xa
    tb = d(1) - xb
    if (abs(ta) < pivmin) ta = -pivmin
    if (abs(tb) < pivmin) tb = -pivmin
    if (ta < 0.0_dp) ca = 1
    if (tb < 0.0_dp) cb = 1
    do i = 2, n
      ta = (d(i) - xa) - e2(i - 1) / ta
      tb = (d(i) - xb) - e2(i - 1) / tb
      if (abs(ta) < pivmin) ta = -pivmin
      if (abs(tb) < pivmin) tb = -pivmin
      if (ta < 0.0_dp) ca = ca + 1
      if (tb < 0.0_dp) cb = cb + 1
    end do
  end subroutine sturm_count_pair

  !> The j-th (0-based) eigenvalue: Rayleigh-quotient steps from the
  !> twisted factorisation (cubic convergence), each checked by a Sturm
  !> count that keeps a bracket [lo, hi] with count(lo) <= j < count(hi);
  !> a step that leaves the bracket is replaced by bisection, and the
  !> iteration stops only when the bracket holds the j-th eigenvalue alone
  !> and the step is below an ulp.  Returns the eigenvector's normalised
  !> components at the two ends too.
  !> With loose present, the Rayleigh-quotient steps may also stop once a
  !> step is below 1e-12 of the scale: loose is then true, x is the shift
  !> of the twist that gave z (not certified: the caller certifies the
  !> Rayleigh quotient of z by Temple's bound, or calls again without loose).
  pure subroutine eigenvalue(d, e2, n, j, x0, lo0, hi0, pivmin, x, first, last, z, loose)
    integer, intent(in) :: n, j
    real(dp), intent(in) :: d(n), e2(n), x0, lo0, hi0, pivmin
    real(dp), intent(out) :: x, first, last, z(n)
    logical, intent(out), optional :: loose
    real(dp) :: lo, hi, w, step, xn, del, emax
    integer :: it, cl, ch, c
    logical :: rq
    ! first, Rayleigh-quotient steps straight from the estimate x0: when
    ! they converge to the j-th eigenvalue (two counts certify it), done
    ! the rounding level of a step: eps times the value and the couplings
    ! (where |x| is below |q|, a step never gets below eps |x|; the polish
    ! that follows takes the value to its own rounding)
    emax = sqrt(maxval(e2))
    if (present(loose)) loose = .false.
    x = x0
    do it = 1, 8
      call twist(d, e2, n, x, pivmin, step, first, last, z)
      if (.not. abs(step) <= huge(1.0_dp)) exit
      xn = x + step
      if (abs(step) <= 0.5_dp * eps_dp * (abs(x) + emax)) then
        del = 4.0_dp * eps_dp * (abs(xn) + emax) + tiny(1.0_dp)
        call sturm_count_pair(d, e2, n, xn - del, xn + del, pivmin, cl, ch)
        if (cl <= j .and. ch > j) then
          x = xn
          return
        end if
        exit
      end if
      if (present(loose)) then
        if (abs(step) <= 1.0e-12_dp * (abs(x) + emax)) then
          loose = .true.
          return
        end if
      end if
      x = xn
    end do
    lo = lo0
    hi = hi0
    w = max(hi - lo, 1.0_dp)
    do it = 1, 60   ! widen until the bracket holds it (the bounds are Weyl's)
      cl = sturm_count(d, e2, n, lo, pivmin)
      if (cl <= j) exit
      lo = lo - w
      w = 2.0_dp * w
    end do
    w = max(hi - lo, 1.0_dp)
    do it = 1, 60
      ch = sturm_count(d, e2, n, hi, pivmin)
      if (ch > j) exit
      hi = hi + w
      w = 2.0_dp * w
    end do
    ! bisection until the bracket holds the j-th eigenvalue alone: the
    ! Rayleigh-quotient steps then stay with it or leave the bracket
    do it = 1, 200
      if (cl == j .and. ch == j + 1) exit
      xn = lo + 0.5_dp * (hi - lo)
      if (xn <= lo .or. xn >= hi) exit
      c = sturm_count(d, e2, n, xn, pivmin)
      if (c > j) then
        hi = xn
        ch = c
      else
        lo = xn
        cl = c
      end if
    end do
    x = lo + 0.5_dp * (hi - lo)
    rq = .true.
    do it = 1, 300
      call twist(d, e2, n, x, pivmin, step, first, last, z)
      xn = x + step
      if (rq .and. abs(step) <= 0.5_dp * eps_dp * (abs(x) + emax)) then
        ! converged: certify that the j-th eigenvalue is within a few ulp
        del = 4.0_dp * eps_dp * (abs(xn) + emax) + tiny(1.0_dp)
        call sturm_count_pair(d, e2, n, xn - del, xn + del, pivmin, cl, ch)
        if (cl <= j .and. ch > j) then
          x = xn
          return
        end if
        rq = .false.     ! converged to a neighbour: bisection from here
      end if
      if (it > 12) rq = .false.
      if (.not. rq .or. .not. (xn > lo .and. xn < hi)) xn = lo + 0.5_dp * (hi - lo)
      if (xn <= lo .or. xn >= hi) exit       ! lo and hi adjacent floats
      c = sturm_count(d, e2, n, xn, pivmin)
      if (c > j) then
        hi = xn
      else
        lo = xn
      end if
      x = xn
      if (hi - lo <= 2.0_dp * eps_dp * max(abs(lo), abs(hi))) exit
    end do
    x = lo + 0.5_dp * (hi - lo)
    call twist(d, e2, n, x, pivmin, step, first, last, z)
  end subroutine eigenvalue

  !> The twisted factorisation of T - x at the row r of the smallest
  !> twist pivot gamma_r: the Rayleigh-quotient step gamma_r / ||z||^2 of its
  !> vector z (z_r = 1, (T - x) z = gamma_r e_r), and z's normalised
  !> components at the two ends (each a product of ratios away from the
  !> twist, so tiny ones keep their relative accuracy).
  pure subroutine twist(d, e2, n, x, pivmin, step, first, last, z)
    integer, intent(in) :: n
    real(dp), intent(in) :: d(n), e2(n), x, pivmin
    real(dp), intent(out) :: step, first, last, z(n)
    real(dp), allocatable :: dp_(:), dm(:)
    real(dp) :: bp(small_rows), bm(small_rows)
    if (n == 1) then
      step = d(1) - x
      first = 1.0_dp
      last = 1.0_dp
      z(1) = 1.0_dp
      return
    end if
    ! the pivots of the usual small window live on the stack (no allocation)
    if (n <= small_rows) then
      call twist_pivots(d, e2, n, x, pivmin, step, first, last, z, bp, bm)
    else
      allocate(dp_(n), dm(n))
      call twist_pivots(d, e2, n, x, pivmin, step, first, last, z, dp_, dm)
    end if
  end subroutine twist

  !> twist with the caller's work arrays dp_ and dm (at least n long).
  pure subroutine twist_pivots(d, e2, n, x, pivmin, step, first, last, z, dp_, dm)
    integer, intent(in) :: n
    real(dp), intent(in) :: d(n), e2(n), x, pivmin
    real(dp), intent(out) :: step, first, last, z(n)
    real(dp), intent(inout) :: dp_(:), dm(:)
    integer :: i, k
    dp_(1) = d(1) - x
    if (abs(dp_(1)) < pivmin) dp_(1) = -pivmin
    dm(n) = d(n) - x
    if (abs(dm(n)) < pivmin) dm(n) = -pivmin
    ! the two factorisations in one loop: their division chains are
    ! independent, so the processor overlaps them
    do i = 2, n
      k = n + 1 - i
      dp_(i) = (d(i) - x) - e2(i - 1) / dp_(i - 1)
      if (abs(dp_(i)) < pivmin) dp_(i) = -pivmin
      dm(k) = (d(k) - x) - e2(k) / dm(k + 1)
      if (abs(dm(k)) < pivmin) dm(k) = -pivmin
    end do
    call twist_vector(d, e2, n, x, dp_, dm, step, first, last, z)
  end subroutine twist_pivots

  !> Two twists at the shifts xa and xb (as two calls of twist): the four
  !> factorisations in one loop, their division chains overlapped.
  pure subroutine twist_pair(d, e2, n, xa, xb, pivmin, stepa, firsta, lasta, za, stepb, firstb, lastb, zb)
    integer, intent(in) :: n
    real(dp), intent(in) :: d(n), e2(n), xa, xb, pivmin
    real(dp), intent(out) :: stepa, firsta, lasta, za(n), stepb, firstb, lastb, zb(n)
    real(dp) :: pa(small_rows), ma(small_rows), pb(small_rows), mb(small_rows)
    integer :: i, k
    if (n == 1 .or. n > small_rows) then
      call twist(d, e2, n, xa, pivmin, stepa, firsta, lasta, za)
      call twist(d, e2, n, xb, pivmin, stepb, firstb, lastb, zb)
      return
    end if
    pa(1) = d(1) - xa
    pb(1) = d(1) - xb
    ma(n) = d(n) - xa
    mb(n) = d(n) - xb
    if (abs(pa(1)) < pivmin) pa(1) = -pivmin
    if (abs(pb(1)) < pivmin) pb(1) = -pivmin
    if (abs(ma(n)) < pivmin) ma(n) = -pivmin
    if (abs(mb(n)) < pivmin) mb(n) = -pivmin
    do i = 2, n
      k = n + 1 - i
      pa(i) = (d(i) - xa) - e2(i - 1) / pa(i - 1)
      pb(i) = (d(i) - xb) - e2(i - 1) / pb(i - 1)
      ma(k) = (d(k) - xa) - e2(k) / ma(k + 1)
      mb(k) = (d(k) - xb) - e2(k) / mb(k + 1)
      if (abs(pa(i)) < pivmin) pa(i) = -pivmin
      if (abs(pb(i)) < pivmin) pb(i) = -pivmin
      if (abs(ma(k)) < pivmin) ma(k) = -pivmin
      if (abs(mb(k)) < pivmin) mb(k) = -pivmin
    end do
    call twist_vector(d, e2, n, xa, pa, ma, stepa, firsta, lasta, za)
    call twist_vector(d, e2, n, xb, pb, mb, stepb, firstb, lastb, zb)
  end subroutine twist_pair

  !> The rest of twist from the pivots dp_ (top down) and dm (bottom up) of
  !> T - x: the twist row, the Rayleigh-quotient step, the vector.
  pure subroutine twist_vector(d, e2, n, x, dp_, dm, step, first, last, z)
    integer, intent(in) :: n
    real(dp), intent(in) :: d(n), e2(n), x, dp_(:), dm(:)
    real(dp), intent(out) :: step, first, last, z(n)
    real(dp) :: g, gbest, gr, nrm2, big, rbig, e2c, ec
    integer :: i, r
    r = 1
    gbest = huge(1.0_dp)
    gr = 0.0_dp
    do i = 1, n
      g = dp_(i) + dm(i) - (d(i) - x)
      if (abs(g) < gbest) then
        gbest = abs(g)
        gr = g
        r = i
      end if
    end do
    ! the couplings sqrt(e2): all equal but the first of a_2m's matrix, so
    ! the square root is taken only where the squared coupling changes
    z(r) = 1.0_dp
    big = 1.0_dp
    nrm2 = 1.0_dp
    e2c = -1.0_dp
    ec = 0.0_dp
    do i = r - 1, 1, -1
      if (e2(i) /= e2c) then
        e2c = e2(i)
        ec = sqrt(e2c)
      end if
      z(i) = -(ec / dp_(i)) * z(i + 1)
      big = max(big, abs(z(i)))
      nrm2 = nrm2 + z(i) * z(i)
    end do
    do i = r + 1, n
      if (e2(i - 1) /= e2c) then
        e2c = e2(i - 1)
        ec = sqrt(e2c)
      end if
      z(i) = -(ec / dm(i)) * z(i - 1)
      big = max(big, abs(z(i)))
      nrm2 = nrm2 + z(i) * z(i)
    end do
    ! z is left unnormalised (z_r = 1; every caller scales it); only where
    ! its square could overflow is it scaled by its largest component
    if (big > 1.0e150_dp) then
      rbig = 1.0_dp / big
      nrm2 = 0.0_dp
      do i = 1, n
        z(i) = z(i) * rbig
        nrm2 = nrm2 + z(i) * z(i)
      end do
      step = (gr * rbig) / (nrm2 * big)
    else
      step = gr / nrm2
    end if
    nrm2 = sqrt(nrm2)
    first = abs(z(1)) / nrm2
    last = abs(z(n)) / nrm2
  end subroutine twist_vector

  ! ------------------------------------------------------------------
  ! The solver: the eigenvalue of index mode, in the window, widened until
  ! the truncation bound meets the tolerance.
  ! ------------------------------------------------------------------

  !> Index of the wanted eigenvalue within the window rows r0..r1.
  !> fam 0, order nu (not an integer): the number of rows of order
  !> |nu + 2k| < nu, i.e. -nu < k < 0.  fam 0, global index m (window from
  !> -shi): m itself.  fam 1..4: m - r0.
  pure integer function window_index(fam, nu, m, by_order, r0) result(j)
    integer, intent(in) :: fam, m, r0
    real(dp), intent(in) :: nu
    logical, intent(in) :: by_order
    if (fam == 0 .and. by_order) then
      j = max(0, -max(r0, 1 - ceiling(nu)))
    else if (fam == 0) then
      j = m
    else
      j = m - r0
    end if
  end function window_index

  !> Eigenvalue of family fam: by_order (fam 0) the one continuing nu^2,
  !> else the m-th; centre^2 is the q = 0 value, the value lies within
  !> spread |q| of it (Weyl).  tol_rel: the truncation bound to meet,
  !> relative to max(1, |value|).  Also returns the window when asked (d,
  !> e2 present: left allocated) so a refinement can reuse it.  A window of
  !> up to small_rows rows lives in stack arrays (no allocation per value).
  pure subroutine solve(fam, nu, q, m, by_order, centre, spread, tol_rel, x, bound, status, d, e2, j, r0, level)
    integer, intent(in) :: fam, m
    real(dp), intent(in) :: nu, q, centre, spread, tol_rel
    logical, intent(in) :: by_order
    real(dp), intent(out) :: x, bound
    integer, intent(out) :: status, j, r0
    real(dp), allocatable, intent(out), optional :: d(:), e2(:)
    real(dp) :: aq, lam_lo, lam_hi, p, rr, ehi, elo, slo, shi
    integer, intent(in) :: level
    real(dp), allocatable :: dh(:), eh(:), zh(:)
    real(dp) :: ds(small_rows), es(small_rows), zs(small_rows)
    real(dp) :: guess
    integer :: r1, n, attempt
    logical :: cut, done
    aq = abs(q)
    call window_plan(fam, q, centre, spread, tol_rel, level, guess, lam_lo, lam_hi, p, rr, ehi, elo)
    ! the starting estimate: q = 0's value, or for large |q| the harmonic
    ! ladder of the level's band, -2|q| + 2 s sqrt|q| - (s^2 + 1)/8 - ...
    ! with s = 2 level + 1 (DLMF 28.8.1)
    status = mathieu_no_convergence
    x = nan_dp
    bound = nan_dp
    j = 0
    r0 = 0
    do attempt = 1, 12
      shi = p + ehi
      slo = rr - elo
      cut = (slo > 2.0_dp) .and. by_order .or. (slo > 2.0_dp .and. fam /= 0)
      call window_rows(fam, nu, slo, shi, cut, r0, r1)
      n = r1 - r0 + 1
      if (n > max_rows) return
      if (n <= small_rows) then
        call try_window(fam, nu, q, m, by_order, tol_rel, guess, lam_lo, lam_hi, r0, n, &
                        ds, es, zs, x, bound, j, status, done)
        if (done .and. present(d)) then
          allocate(d(n), e2(n))
          d = ds(1:n)
          e2 = es(1:n)
        end if
      else
        if (allocated(dh)) deallocate(dh, eh, zh)
        allocate(dh(n), eh(n), zh(n))
        call try_window(fam, nu, q, m, by_order, tol_rel, guess, lam_lo, lam_hi, r0, n, &
                        dh, eh, zh, x, bound, j, status, done)
        if (done .and. present(d)) then
          call move_alloc(dh, d)
          call move_alloc(eh, e2)
        end if
      end if
      if (done) return
      ehi = 2.0_dp * ehi + 4.0_dp
      elo = 2.0_dp * elo + 4.0_dp
    end do
  end subroutine solve

  !> The first window of solve: the starting estimate guess of the level
  !> (the q = 0 value centre^2, a power series for small |q|, the harmonic
  !> ladder for large |q|), the Weyl interval [lam_lo, lam_hi] of spread
  !> |q| about centre^2, the turning points p (upper) and rr (lower), and the
  !> tails ehi, elo beyond them (in orders s) for the tolerance tol_rel.
  pure subroutine window_plan(fam, q, centre, spread, tol_rel, level, guess, lam_lo, lam_hi, p, rr, ehi, elo)
    integer, intent(in) :: fam, level
    real(dp), intent(in) :: q, centre, spread, tol_rel
    real(dp), intent(out) :: guess, lam_lo, lam_hi, p, rr, ehi, elo
    real(dp) :: aq, sl, h
    h = 0.0_dp
    aq = abs(q)
    lam_hi = centre * centre + spread * aq
    lam_lo = centre * centre - spread * aq
    guess = centre * centre
    sl = real(2 * level + 1, dp)
    if (aq > 0.25_dp * sl * sl) then
      h = sqrt(aq)
      guess = -2.0_dp * aq + 2.0_dp * sl * h - (sl * sl + 1.0_dp) / 8.0_dp &
              - (sl ** 3 + 3.0_dp * sl) / (128.0_dp * h)
    else if (fam == 1 .and. centre == 0.0_dp) then
      ! small |q|: the power series of DLMF 28.6.1, 28.6.4-5 and 28.6.14
      ! (the bracket and the Sturm counts decide, the guess only saves steps)
      guess = -0.5_dp * q * q + (7.0_dp / 128.0_dp) * q ** 4
    else if ((fam == 2 .or. fam == 3) .and. centre == 1.0_dp) then
      guess = 1.0_dp + merge(q, -q, fam == 2) - 0.125_dp * q * q
    else if (abs(centre * centre - 1.0_dp) >= 0.5_dp) then
      h = q * q / (2.0_dp * (centre * centre - 1.0_dp))
      guess = centre * centre + sign(min(abs(h), aq), h)
    end if
    ! the upper turning point: of the Weyl bound, or for large |q| of the
    ! ladder's estimate plus a generous margin (the bound checks it)
    p = sqrt(max(lam_hi + 2.0_dp * aq, 0.0_dp))
    if (aq > sl * sl) p = sqrt(max(guess + 4.0_dp * sl * h + 2.0_dp * aq, 0.0_dp))
    rr = sqrt(max(lam_lo - 2.0_dp * aq, 0.0_dp))
    ! the tails: beyond the turning points the Fourier coefficients fall by
    ! at most |q| / (s^2 - lambda) a row (two orders); rows are added until
    ! that product is below the tolerance over |q|
    call tail(aq, p, lam_hi, 1.0_dp, tol_rel, ehi)
    call tail(aq, rr, lam_lo, -1.0_dp, tol_rel, elo)
  end subroutine window_plan

  !> One window of solve: rows r0 .. r0 + n - 1 built into d, e2 (the
  !> caller's work arrays, z too), the eigenvalue of index j found and
  !> polished, and its truncation bound.  done: the bound met the tolerance
  !> (status ok) or q = 0; otherwise the caller widens the window.
  pure subroutine try_window(fam, nu, q, m, by_order, tol_rel, guess, lam_lo, lam_hi, r0, n, &
                             d, e2, z, x, bound, j, status, done)
    integer, intent(in) :: fam, m, r0, n
    real(dp), intent(in) :: nu, q, tol_rel, guess, lam_lo, lam_hi
    logical, intent(in) :: by_order
    real(dp), intent(inout) :: d(n), e2(n), z(n)
    real(dp), intent(out) :: x, bound
    integer, intent(out) :: j
    integer, intent(inout) :: status
    logical, intent(out) :: done
    real(dp) :: aq, pivmin, f1, fn, c1, cn, lo, hi, rho, res2, g, delta, temple
    integer :: cl, ch
    logical :: loose, good
    done = .false.
    aq = abs(q)
    call build(fam, nu, q, r0, r0 + n - 1, d, e2)
    j = window_index(fam, nu, m, by_order, r0)
    if (j < 0 .or. j >= n) then
      x = nan_dp
      bound = nan_dp
      return
    end if
    pivmin = tiny(1.0_dp) * max(1.0_dp, maxval(e2))
    lo = lam_lo - 1.0e-3_dp * abs(lam_lo) - 1.0_dp
    hi = lam_hi + 1.0e-3_dp * abs(lam_hi) + 1.0_dp
    if (aq == 0.0_dp) then   ! the diagonal itself: snap to its entry
      call eigenvalue(d, e2, n, j, guess, lo, hi, pivmin, x, f1, fn, z)
      x = d(minloc(abs(d - x), 1))
      bound = 0.0_dp
      status = mathieu_ok
      done = .true.
      return
    end if
    ! the couplings that the window cuts: below row r0 (none at row 0 of
    ! a one-sided family) and above row r1
    c1 = sqrt2 * aq
    if (fam /= 0 .and. r0 == 0) c1 = 0.0_dp
    cn = aq
    call eigenvalue(d, e2, n, j, guess, lo, hi, pivmin, x, f1, fn, z, loose)
    temple = 0.0_dp
    if (loose) then
      ! the Rayleigh quotient of z certified by Temple's bound: one count
      ! each side, g away, proves the j-th eigenvalue alone within g - slack
      ! of rho (slack: the counts' backward error, couplings a few ulp off,
      ! and the diagonal's rounding), and then it is within eps_r^2 / delta
      call polish_res(fam, nu, q, r0, n, x, z, rho, res2)
      g = 1.0e-4_dp * (abs(rho) + aq)
      call sturm_count_pair(d, e2, n, rho - g, rho + g, pivmin, cl, ch)
      delta = g - (8.0_dp * eps_dp * (abs(rho) + g + 2.0_dp * aq) + eps_dp * maxval(abs(d)) + tiny(1.0_dp))
      bound = sqrt((c1 * f1) ** 2 + (cn * fn) ** 2)
      if (n == 1) bound = (c1 + cn)
      good = cl == j .and. ch == j + 1 .and. delta > 0.0_dp
      if (good) good = res2 < delta * delta
      if (good) then
        temple = res2 / delta
        good = bound + temple <= tol_rel * max(1.0_dp, abs(rho))
      end if
      if (good) then
        x = rho
      else
        temple = 0.0_dp
        call eigenvalue(d, e2, n, j, guess, lo, hi, pivmin, x, f1, fn, z)
        x = polish(fam, nu, q, r0, n, x, z)
      end if
    else
      x = polish(fam, nu, q, r0, n, x, z)
    end if
    bound = sqrt((c1 * f1) ** 2 + (cn * fn) ** 2) + temple
    if (n == 1) bound = (c1 + cn)   ! a single row says nothing
    if (bound <= tol_rel * max(1.0_dp, abs(x))) then
      status = mathieu_ok
      done = .true.
    end if
  end subroutine try_window

  !> The Rayleigh quotient of the eigenvector z about x, with the residual
  !> (T - x) z in double-double and the matrix's entries exact ((nu + 2k)^2
  !> by two-sum and Dekker's product, 1 +- q, the coupling sqrt(2) q): x
  !> plus z'(T - x)z / z'z.  The error of z is second order, so the value
  !> is the eigenvalue of the exact matrix to about an ulp, free of the
  !> few-ulp-of-|q| error of the Sturm count where |q| exceeds the value.
  pure real(dp) function polish(fam, nu, q, r0, n, x, z) result(xp)
    integer, intent(in) :: fam, r0, n
    real(dp), intent(in) :: nu, q, x, z(n)
    real(dp) :: resid2
    call polish_res(fam, nu, q, r0, n, x, z, xp, resid2)
  end function polish

  !> polish, and resid2: an upper bound on ||(T - xp) z||^2 / ||z||^2 (the
  !> squared residual of the Rayleigh quotient xp, for Temple's bound): the
  !> sum of the squared residual components of the rows kept, and for the
  !> rows left out (z_i below tau of the largest; z satisfies their rows to
  !> a few ulp of the row's scale) 8 eps times that scale times tau, squared.
  pure subroutine polish_res(fam, nu, q, r0, n, x, z, xp, resid2)
    integer, intent(in) :: fam, r0, n
    real(dp), intent(in) :: nu, q, x, z(n)
    real(dp), intent(out) :: xp, resid2
    real(dp) :: num, den, aq, e0, e0l, rr, smax
    real(dp), parameter :: sqrt2_lo = -9.6667966258595e-17_dp
    integer :: i1, i2
    real(dp) :: thr
    aq = abs(q)
    ! rows whose component is below tau = 1e-10 of the largest are left out:
    ! z is the eigenvector to rounding, so each one's term z_i ((T - x) z)_i
    ! is below tau^2 eps times the matrix's scale there (s^2 + 2|q|), and
    ! their sum is below 1e-20 of the quotient's rounding
    thr = 1.0e-10_dp * maxval(abs(z))
    i1 = 1
    do while (i1 < n .and. abs(z(i1)) <= thr)
      i1 = i1 + 1
    end do
    i2 = n
    do while (i2 > i1 .and. abs(z(i2)) <= thr)
      i2 = i2 - 1
    end do
    ! and one row more each side: the rows left out then have all three
    ! components below tau (their residual is rounding of tau's size)
    i1 = max(1, i1 - 1)
    i2 = min(n, i2 + 1)
    ! the coupling of rows 0 and 1 of a_2m's matrix, sqrt(2)|q| in double-double
    call prod_dd(sqrt2, aq, e0, e0l)
    e0l = e0l + sqrt2_lo * aq
    ! the rows' residuals, summed (kernel/mathieu/pendula_mathieu_polish.c:
    ! fused multiply-adds for the exact products where the CPU has them)
    call c_polish_rows(int(fam, c_int), nu, q, aq, e0, e0l, int(r0, c_int), int(n, c_int), &
                       int(i1, c_int), int(i2, c_int), x, z, num, den, rr)
    xp = x + num / den
    ! the rows left out: their scale |s^2 - x| + 2|q| is largest at the ends
    smax = 0.0_dp
    if (i1 > 1 .or. i2 < n) then
      smax = max(abs(real(r0, dp)), abs(real(r0 + n - 1, dp)))
      smax = (abs(nu) + real(fam_base(fam), dp) + 2.0_dp * smax) ** 2 + abs(x) + 3.0_dp * aq
      smax = 8.0_dp * eps_dp * smax * thr
    end if
    resid2 = (rr + real(n, dp) * smax * smax) / den * (1.0_dp + real(2 * n + 8, dp) * eps_dp)
  end subroutine polish_res

  !> p + e = a * b exactly (Dekker's product with Veltkamp's splitting).
  pure subroutine prod_dd(a, b, p, e)
    real(dp), intent(in) :: a, b
    real(dp), intent(out) :: p, e
    real(dp), parameter :: splitter = 134217729.0_dp   ! 2**27 + 1
    real(dp) :: t, ah, al, bh, bl
    p = a * b
    t = splitter * a
    ah = t - (t - a)
    al = a - ah
    t = splitter * b
    bh = t - (t - b)
    bl = b - bh
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl
  end subroutine prod_dd


  !> How far (in orders s) past the turning point s0 the window must reach
  !> for the tail's decay to fall below tol_rel / |q| (dir +1: upwards from
  !> s0 with s^2 above lam; -1: downwards with s^2 below lam).
  pure subroutine tail(aq, s0, lam, dir, tol_rel, ext)
    real(dp), intent(in) :: aq, s0, lam, dir, tol_rel
    real(dp), intent(out) :: ext
    real(dp) :: prod, s, gap, goal
    integer :: k
    ext = 4.0_dp
    if (aq == 0.0_dp) return
    goal = 1.0e-2_dp * tol_rel / max(aq, 1.0_dp)
    prod = 1.0_dp
    s = s0
    do k = 1, max_rows
      s = s + 2.0_dp * dir
      if (dir < 0.0_dp .and. s <= 0.0_dp) exit
      gap = dir * (s * s - lam)
      if (gap > 0.0_dp) prod = prod * min(1.0_dp, aq / gap)
      if (prod <= goal) exit
    end do
    ext = abs(s - s0) + 4.0_dp
  end subroutine tail

  !> Characteristic value a_nu(q) (kind 1) or b_nu(q) (kind 2) of real order
  !> nu >= 0; for non-integer nu both are lambda_nu(q) (DLMF 28.12).  bound:
  !> the a-posteriori bound on the truncation error.  b_0 does not exist
  !> (NaN, bad input); so do negative or non-finite orders and |q| beyond
  !> mathieu_max_q.
  elemental subroutine mathieu_char(kind, nu, q, val, bound, status)
    integer, intent(in) :: kind
    real(dp), intent(in) :: nu, q
    real(dp), intent(out) :: val, bound
    integer, intent(out) :: status
    integer :: n, fam, m, j, r0, lev
    val = nan_dp
    bound = nan_dp
    status = mathieu_bad_input
    if (.not. (nu >= 0.0_dp .and. nu <= mathieu_max_order)) return
    if (.not. (abs(q) <= mathieu_max_q)) return
    if (nu /= aint(nu)) then
      call solve(0, nu, q, 0, .true., nu, 2.0_dp, 0.25_dp * eps_dp, val, bound, status, j=j, r0=r0, &
                 level=int(nu))
      return
    end if
    n = int(nu)
    if (kind == 2 .and. n == 0) return
    if (kind == 1) then
      if (mod(n, 2) == 0) then
        fam = 1
        m = n / 2
      else
        fam = 2
        m = (n - 1) / 2
      end if
    else
      if (mod(n, 2) == 1) then
        fam = 3
        m = (n - 1) / 2
      else
        fam = 4
        m = n / 2 - 1
      end if
    end if
    ! the band at large |q|: a_n and b_n+1 share the level n (q > 0); for
    ! q < 0 the odd orders swap (a_2m+1(-q) = b_2m+1(q))
    lev = n
    if (kind == 2) lev = n - 1
    if (q < 0.0_dp .and. mod(n, 2) == 1) lev = n - 1 + 2 * (kind - 1)
    call solve(fam, 0.0_dp, q, m, .false., nu, 3.0_dp, 0.25_dp * eps_dp, val, bound, status, j=j, r0=r0, &
               level=lev)
  end subroutine mathieu_char

  !> q = 0 value of the m-th level of the bi-infinite matrix of offset nu
  !> (0 <= nu < 2): the m-th smallest |nu + 2k|.
  pure real(dp) function level_order(nu, m) result(s)
    real(dp), intent(in) :: nu
    integer, intent(in) :: m
    integer :: c, k
    ! orders nu, 2 - nu, 2 + nu, 4 - nu, ... interleave as the sorted
    ! |nu + 2k|: for nu <= 1 the k = 0, -1, 1, -2, ... order, else -1, 0, ...
    c = m / 2
    if (nu <= 1.0_dp) then
      if (mod(m, 2) == 0) then
        k = c
        s = nu + 2.0_dp * real(k, dp)
      else
        s = 2.0_dp * real(c + 1, dp) - nu
      end if
    else
      if (mod(m, 2) == 0) then
        s = 2.0_dp * real(c + 1, dp) - nu
      else
        s = nu + 2.0_dp * real(c, dp)
      end if
    end if
  end function level_order

  !> The m-th (0-based) eigenvalue of the bi-infinite matrix of offset nu
  !> (reduced to [0, 2): the matrix only shifts its rows), q of either sign:
  !> the levels of the quantum pendulum H = 4 E_C (n - n_g)^2 - E_J cos phi
  !> are E_C times these with nu = 2 n_g, q = -E_J / (2 E_C).
  elemental subroutine mathieu_level(nu, q, m, val, bound, status)
    real(dp), intent(in) :: nu, q
    integer, intent(in) :: m
    real(dp), intent(out) :: val, bound
    integer, intent(out) :: status
    real(dp) :: nr
    integer :: j, r0
    val = nan_dp
    bound = nan_dp
    status = mathieu_bad_input
    if (.not. (abs(nu) <= mathieu_max_order) .or. m < 0 .or. m > 100000000) return
    if (.not. (abs(q) <= mathieu_max_q)) return
    nr = modulo(nu, 2.0_dp)
    if (nr >= 2.0_dp) nr = 0.0_dp
    call solve(0, nr, q, m, .false., level_order(nr, m), 2.0_dp, 0.25_dp * eps_dp, val, bound, &
               status, j=j, r0=r0, level=m)
  end subroutine mathieu_level

  !> The lowest nlev levels m = 0 .. nlev - 1 of the bi-infinite matrix of
  !> offset nu (as mathieu_level, each to the same tolerance and with its own
  !> bound) from one window: the window of the top level holds every lower
  !> one, whose eigenvectors are more confined.  The starting values are all
  !> the window's eigenvalues by implicit QL (Bowdler, Martin, Reinsch and
  !> Wilkinson), close enough that one or two Rayleigh-quotient steps converge
  !> and two Sturm counts certify the index; each value is then polished as
  !> in mathieu_level.  A level whose bound is not met in this window (or a
  !> failed QL) is solved on its own by mathieu_level.
  pure subroutine mathieu_levels(nu, q, nlev, val, bound, status)
    real(dp), intent(in) :: nu, q
    integer, intent(in) :: nlev
    real(dp), intent(out) :: val(nlev), bound(nlev)
    integer, intent(out) :: status(nlev)
    real(dp), allocatable :: d(:), e2(:), ev(:), ee(:), z(:)
    real(dp) :: nr, x, b, pivmin, f1, fn, w, aq, t
    integer :: j, r0, n, k, i, st, i1, i2, nb
    logical :: ok
    val = nan_dp
    bound = nan_dp
    status = mathieu_bad_input
    if (nlev < 1) return
    if (.not. (abs(nu) <= mathieu_max_order) .or. nlev > 100000000) return
    if (.not. (abs(q) <= mathieu_max_q)) return
    nr = modulo(nu, 2.0_dp)
    if (nr >= 2.0_dp) nr = 0.0_dp
    aq = abs(q)
    if (nlev == 1 .or. aq == 0.0_dp) then
      do k = 0, nlev - 1
        call mathieu_level(nu, q, k, val(k + 1), bound(k + 1), status(k + 1))
      end do
      return
    end if
    ! first every level, the top one too, certified together in solve's
    ! first window of the top level; then, where that fails, the top level
    ! solved on its own and the rest certified in its window
    call levels_one_window(nr, q, nlev, val, bound, status, ok)
    if (ok) return
    val = nan_dp
    bound = nan_dp
    status = mathieu_bad_input
    call solve(0, nr, q, nlev - 1, .false., level_order(nr, nlev - 1), 2.0_dp, 0.25_dp * eps_dp, x, b, &
               st, d, e2, j, r0, nlev - 1)
    n = 0
    if (st == mathieu_ok) n = size(d)
    ok = st == mathieu_ok .and. n >= nlev
    if (ok) then
      val(nlev) = x
      bound(nlev) = b
      status(nlev) = mathieu_ok
      ! the starting values come from the rows inside the top level's
      ! turning points (s^2 <= its value + 2|q|) and 3 beyond on each side:
      ! the lower eigenvectors have decayed there, so the block's
      ! eigenvalues are close to theirs (the steps below make them exact)
      t = x + 2.0_dp * aq
      i1 = 1
      do while (i1 < n .and. d(i1) > t)
        i1 = i1 + 1
      end do
      i2 = n
      do while (i2 > i1 .and. d(i2) > t)
        i2 = i2 - 1
      end do
      i1 = max(1, i1 - 3)
      i2 = min(n, i2 + 3)
      if (i2 - i1 + 1 < nlev) then
        i1 = 1
        i2 = n
      end if
      nb = i2 - i1 + 1
      allocate(ev(nb), ee(nb), z(n))
      ev = d(i1:i2)
      ee(1:nb - 1) = sqrt(e2(i1:i2 - 1))
      ee(nb) = 0.0_dp
      call ql_values(nb, ev, ee, ok)
    end if
    if (.not. ok) then
      do k = 0, nlev - 1
        call mathieu_level(nu, q, k, val(k + 1), bound(k + 1), status(k + 1))
      end do
      return
    end if
    ! the lowest nlev - 1 of the QL values, in order (insertion sort of a
    ! prefix: the window is short)
    do i = 2, nb
      t = ev(i)
      k = i - 1
      do while (k >= 1)
        if (ev(k) <= t) exit
        ev(k + 1) = ev(k)
        k = k - 1
      end do
      ev(k + 1) = t
    end do
    pivmin = tiny(1.0_dp) * max(1.0_dp, maxval(e2))
    call levels_certified(nr, q, r0, n, d, e2, nlev, nlev - 1, 0.0_dp, ev, pivmin, val, bound, status, z)
    do k = 0, nlev - 2
      if (status(k + 1) == mathieu_ok) cycle
      w = 1.0e-8_dp * max(1.0_dp, abs(ev(k + 1)), aq)
      call eigenvalue(d, e2, n, k, ev(k + 1), ev(k + 1) - w, ev(k + 1) + w, pivmin, x, f1, fn, z)
      x = polish(0, nr, q, r0, n, x, z)
      ! the couplings the window cuts, below and above (as in solve)
      b = sqrt((sqrt2 * aq * f1) ** 2 + (aq * fn) ** 2)
      if (b <= 0.25_dp * eps_dp * max(1.0_dp, abs(x))) then
        val(k + 1) = x
        bound(k + 1) = b
        status(k + 1) = mathieu_ok
      else
        call mathieu_level(nu, q, k, val(k + 1), bound(k + 1), status(k + 1))
      end if
    end do
  end subroutine mathieu_levels

  !> All nlev levels of offset nr (reduced to [0, 2)) in the first window
  !> that solve would take for the top one (window_plan), with no level
  !> solved on its own: starting values by QL on the window's central rows,
  !> then levels_certified for all of them (the top level's gap above from
  !> the next QL value).  ok only when every level is certified, its
  !> truncation bound included; otherwise the caller takes its own path.
  pure subroutine levels_one_window(nr, q, nlev, val, bound, status, ok)
    real(dp), intent(in) :: nr, q
    integer, intent(in) :: nlev
    real(dp), intent(inout) :: val(nlev), bound(nlev)
    integer, intent(inout) :: status(nlev)
    logical, intent(out) :: ok
    real(dp) :: d(small_rows), e2(small_rows), z(small_rows), ev(small_rows), ee(small_rows)
    real(dp) :: guess, lam_lo, lam_hi, p, rr, ehi, elo, t, aq, pivmin
    integer :: r0, r1, n, i1, i2, nb, i, k
    ok = .false.
    aq = abs(q)
    call window_plan(0, q, level_order(nr, nlev - 1), 2.0_dp, 0.25_dp * eps_dp, nlev - 1, guess, &
                     lam_lo, lam_hi, p, rr, ehi, elo)
    call window_rows(0, nr, rr - elo, p + ehi, .false., r0, r1)
    n = r1 - r0 + 1
    if (n > small_rows .or. n < nlev + 1) return
    call build(0, nr, q, r0, r1, d, e2)
    ! the central rows (as in mathieu_levels, about the top level's estimate)
    t = guess + 2.0_dp * aq
    i1 = 1
    do while (i1 < n .and. d(i1) > t)
      i1 = i1 + 1
    end do
    i2 = n
    do while (i2 > i1 .and. d(i2) > t)
      i2 = i2 - 1
    end do
    i1 = max(1, i1 - 3)
    i2 = min(n, i2 + 3)
    nb = i2 - i1 + 1
    if (nb < nlev + 1) return
    ev(1:nb) = d(i1:i2)
    ee(1:nb - 1) = sqrt(e2(i1:i2 - 1))
    ee(nb) = 0.0_dp
    call ql_values(nb, ev(1:nb), ee(1:nb), ok)
    if (.not. ok) return
    do i = 2, nb     ! in order
      t = ev(i)
      k = i - 1
      do while (k >= 1)
        if (ev(k) <= t) exit
        ev(k + 1) = ev(k)
        k = k - 1
      end do
      ev(k + 1) = t
    end do
    pivmin = tiny(1.0_dp) * max(1.0_dp, maxval(e2(1:n)))
    call levels_certified(nr, q, r0, n, d(1:n), e2(1:n), nlev, nlev, ev(nlev + 1), ev(1:nb), pivmin, &
                          val, bound, status, z(1:n))
    ok = all(status == mathieu_ok)
  end subroutine levels_one_window

  !> The levels 0 .. ncomp - 1 of the window (d, e2; rows r0 .. r0 + n - 1 of
  !> offset nu, couplings |q|) certified together: ncomp = nlev - 1 with
  !> level nlev - 1 (val) certified already, or ncomp = nlev with above a
  !> value between the top level and the next eigenvalue.  Each level: a twist at its starting
  !> value ev (and, where needed, one more at the result), its Rayleigh
  !> quotient rho polished in double-double with the residual norm eps_r.
  !> One Sturm count at each midpoint between consecutive rho (and one
  !> below the lowest) proves that the interval (alpha, beta) around each
  !> rho holds no other eigenvalue (up to the counts' backward error, a
  !> few ulp of the couplings, and the rounding of the diagonal); then the
  !> eigenvalue is within eps_r^2 / delta of rho, delta the distance from
  !> rho to the interval's ends (Kato and Temple; Parlett, The Symmetric
  !> Eigenvalue Problem, section 10.5).  A level whose bound plus its
  !> truncation bound meets eps/4 of max(1, |rho|) gets status ok with that
  !> sum as its bound; the others keep status bad_input for the caller's
  !> own path (so do all of them when a count disagrees).
  pure subroutine levels_certified(nr, q, r0, n, d, e2, nlev, ncomp, above, ev, pivmin, val, bound, status, z)
    integer, intent(in) :: r0, n, nlev, ncomp
    real(dp), intent(in) :: nr, q, d(n), e2(n), above, ev(:), pivmin
    real(dp), intent(inout) :: val(nlev), bound(nlev), z(n)
    integer, intent(inout) :: status(nlev)
    ! work arrays on the heap: nlev and n can be large (a spectrum of many
    ! levels), beyond what a thread's stack holds
    real(dp), allocatable :: rho(:), res2(:), tb(:), mid(:), zb(:)
    real(dp) :: step, f1, fn, aq, emax, slack, delta, temple, tol, xs, dmax
    real(dp) :: xa, xb, stepb, f1b, fnb
    integer :: k, it, ca, cb, kmax
    logical :: good, moved, movedb
    if (nlev < 2) return
    allocate(rho(nlev), res2(nlev), tb(nlev), mid(0:nlev), zb(n))
    aq = abs(q)
    emax = sqrt(maxval(e2))
    dmax = maxval(abs(d))
    if (ncomp < nlev) then
      rho(nlev) = val(nlev)
      res2(nlev) = 0.0_dp
    end if
    ! two levels at a time (their factorisations overlap): a Rayleigh-
    ! quotient step from the starting value where it is not already within
    ! 1e-13 of the scale (cubic: the next vector is good), then the polish
    do k = 1, ncomp, 2
      if (k + 1 <= ncomp) then
        xa = ev(k)
        xb = ev(k + 1)
        call twist_pair(d, e2, n, xa, xb, pivmin, step, f1, fn, z, stepb, f1b, fnb, zb)
        moved = abs(step) > 1.0e-13_dp * (abs(xa) + emax)
        movedb = abs(stepb) > 1.0e-13_dp * (abs(xb) + emax)
        if (moved) xa = xa + step
        if (movedb) xb = xb + stepb
        if (moved .and. movedb) then
          call twist_pair(d, e2, n, xa, xb, pivmin, step, f1, fn, z, stepb, f1b, fnb, zb)
        else if (moved) then
          call twist(d, e2, n, xa, pivmin, step, f1, fn, z)
        else if (movedb) then
          call twist(d, e2, n, xb, pivmin, stepb, f1b, fnb, zb)
        end if
        call polish_res(0, nr, q, r0, n, xa, z, rho(k), res2(k))
        tb(k) = sqrt((sqrt2 * aq * f1) ** 2 + (aq * fn) ** 2)
        call polish_res(0, nr, q, r0, n, xb, zb, rho(k + 1), res2(k + 1))
        tb(k + 1) = sqrt((sqrt2 * aq * f1b) ** 2 + (aq * fnb) ** 2)
      else
        xs = ev(k)
        call twist(d, e2, n, xs, pivmin, step, f1, fn, z)
        if (abs(step) > 1.0e-13_dp * (abs(xs) + emax)) then
          xs = xs + step
          call twist(d, e2, n, xs, pivmin, step, f1, fn, z)
        end if
        call polish_res(0, nr, q, r0, n, xs, z, rho(k), res2(k))
        tb(k) = sqrt((sqrt2 * aq * f1) ** 2 + (aq * fn) ** 2)
      end if
    end do
    do k = 1, nlev - 1
      if (.not. (rho(k) < rho(k + 1))) return
    end do
    ! the midpoints, below the lowest its mirror image, and (when the top
    ! level is computed here too) one between it and the value above
    do k = 1, nlev - 1
      mid(k) = rho(k) + 0.5_dp * (rho(k + 1) - rho(k))
    end do
    mid(0) = rho(1) - (mid(1) - rho(1))
    kmax = nlev - 1
    if (ncomp == nlev) then
      if (.not. (above > rho(nlev))) return
      mid(nlev) = rho(nlev) + 0.5_dp * (above - rho(nlev))
      kmax = nlev
    end if
    do k = 0, kmax, 2
      if (k + 1 <= kmax) then
        call sturm_count_pair(d, e2, n, mid(k), mid(k + 1), pivmin, ca, cb)
        if (ca /= k .or. cb /= k + 1) return
      else
        if (sturm_count(d, e2, n, mid(k), pivmin) /= k) return
      end if
    end do
    do k = 1, ncomp
      good = .false.
      do it = 1, 2
        tol = 0.25_dp * eps_dp * max(1.0_dp, abs(rho(k)))
        ! the counts' backward error: couplings a few ulp off (Kahan), and
        ! the diagonal rounded to an ulp of its largest entry
        slack = 8.0_dp * eps_dp * (max(abs(mid(k - 1)), abs(mid(k))) + emax) + eps_dp * dmax + tiny(1.0_dp)
        delta = min(rho(k) - mid(k - 1), mid(k) - rho(k)) - slack
        if (delta > 0.0_dp .and. res2(k) < delta * delta) then
          temple = res2(k) / delta
          if (temple + tb(k) <= tol) then
            good = .true.
            exit
          end if
        end if
        if (it == 2) exit
        ! one more twist, at rho: its vector is closer to the eigenvector
        xs = rho(k)
        call twist(d, e2, n, xs, pivmin, step, f1, fn, z)
        call polish_res(0, nr, q, r0, n, xs, z, rho(k), res2(k))
        tb(k) = sqrt((sqrt2 * aq * f1) ** 2 + (aq * fn) ** 2)
      end do
      if (good) then
        val(k) = rho(k)
        bound(k) = tb(k) + temple
        status(k) = mathieu_ok
      end if
    end do
  end subroutine levels_certified

  !> All eigenvalues of the symmetric tridiagonal matrix of diagonal d and
  !> off-diagonal e (e(i) couples rows i and i + 1; e(n) unused) by the
  !> implicit QL algorithm with Wilkinson's shift (Bowdler, Martin, Reinsch
  !> and Wilkinson 1968; the tqli of Press et al., section 11.3): d is
  !> overwritten by the eigenvalues (unordered), e is destroyed.  ok is
  !> false when an eigenvalue takes more than 60 sweeps.
  pure subroutine ql_values(n, d, e, ok)
    integer, intent(in) :: n
    real(dp), intent(inout) :: d(n), e(n)
    logical, intent(out) :: ok
    integer :: l, m, i, iter
    real(dp) :: g, r, s, c, p, f, b, dd
    logical :: split
    ok = .true.
    e(n) = 0.0_dp
    do l = 1, n
      iter = 0
      do
        m = n
        do i = l, n - 1
          dd = abs(d(i)) + abs(d(i + 1))
          if (abs(e(i)) <= eps_dp * dd) then
            m = i
            exit
          end if
        end do
        if (m == l) exit
        iter = iter + 1
        if (iter > 60) then
          ok = .false.
          return
        end if
        g = (d(l + 1) - d(l)) / (2.0_dp * e(l))
        r = sqrt(g * g + 1.0_dp)
        if (abs(g) > 1.0e150_dp) r = abs(g)
        g = d(m) - d(l) + e(l) / (g + sign(r, g))
        s = 1.0_dp
        c = 1.0_dp
        p = 0.0_dp
        split = .false.
        do i = m - 1, l, -1
          f = s * e(i)
          b = c * e(i)
          r = sqrt(f * f + g * g)     ! no overflow: the window's entries are below 1e40
          e(i + 1) = r
          if (r == 0.0_dp) then
            d(i + 1) = d(i + 1) - p
            e(m) = 0.0_dp
            split = .true.
            exit
          end if
          s = f / r
          c = g / r
          g = d(i + 1) - p
          r = (d(i) - g) * s + 2.0_dp * c * b
          p = s * r
          d(i + 1) = g + p
          g = c * r - b
        end do
        if (split) cycle
        d(l) = d(l) - p
        e(l) = g
        e(m) = 0.0_dp
      end do
    end do
  end subroutine ql_values

  !> The m-th level of the bi-infinite matrix of offset nu (as
  !> mathieu_level) and its eigenvector c_k, k = kmin .. kmin + nk - 1, of
  !> the matrix with couplings q (its sign kept: for q < 0 the components
  !> alternate relative to q > 0), unit norm, the largest component
  !> positive.  Rows of the window outside the requested range are dropped;
  !> lost is the norm they carried (the caller widens the range when it is
  !> not negligible).  The row index k is that of nu reduced to [0, 2).
  pure subroutine mathieu_level_vector(nu, q, m, kmin, nk, val, c, lost, status)
    real(dp), intent(in) :: nu, q
    integer, intent(in) :: m, kmin, nk
    real(dp), intent(out) :: val, c(nk), lost
    integer, intent(out) :: status
    real(dp), allocatable :: d(:), e2(:), z(:)
    real(dp) :: nr, bound, step, f1, fn, pivmin, nrm, big
    integer :: j, r0, n, i, k, ib
    c = 0.0_dp
    lost = nan_dp
    val = nan_dp
    status = mathieu_bad_input
    if (.not. (abs(nu) <= mathieu_max_order) .or. m < 0 .or. m > 100000000) return
    if (.not. (abs(q) <= mathieu_max_q)) return
    nr = modulo(nu, 2.0_dp)
    if (nr >= 2.0_dp) nr = 0.0_dp
    call solve(0, nr, q, m, .false., level_order(nr, m), 2.0_dp, 0.25_dp * eps_dp, val, bound, &
               status, d, e2, j, r0, m)
    if (status /= mathieu_ok) return
    n = size(d)
    allocate(z(n))
    pivmin = tiny(1.0_dp) * max(1.0_dp, maxval(e2))
    if (abs(q) > 0.0_dp) then
      call twist(d, e2, n, val, pivmin, step, f1, fn, z)
    else
      z = 0.0_dp
      z(minloc(abs(d - val), 1)) = 1.0_dp
    end if
    do i = 1, n     ! the couplings were |q|: back to q's sign
      if (q < 0.0_dp .and. mod(r0 + i - 1, 2) /= 0) z(i) = -z(i)
    end do
    nrm = sqrt(sum(z * z))
    ib = maxloc(abs(z), 1)
    big = sign(1.0_dp, z(ib)) / nrm
    lost = 0.0_dp
    do i = 1, n
      k = r0 + i - 1
      if (k >= kmin .and. k < kmin + nk) then
        c(k - kmin + 1) = z(i) * big
      else
        lost = lost + (z(i) * big) ** 2
      end if
    end do
    lost = sqrt(lost)
  end subroutine mathieu_level_vector

  !> The periodic Mathieu function ce_n (kind 1) or se_n (kind 2) of integer
  !> order n and its derivative at the points z, from the Fourier series of
  !> DLMF 28.4 with the normalisation 28.4.9-12 (the integral of the square
  !> over a period 2 pi is pi) and the signs of q = 0 carried by continuity,
  !> which for real q is ce_n(0, q) > 0 and se_n'(0, q) > 0 (neither can
  !> vanish: an even solution with y(0) = 0, or an odd one with y'(0) = 0,
  !> is zero).  The coefficients are the eigenvector of the one-sided Hill
  !> matrix; the values have an absolute error of a few eps (relative where
  !> the function is not small: near z = 0 and pi/2 for large q the values
  !> are exponentially small and only absolutely accurate).
  pure subroutine mathieu_function(kind, n, q, nz, z, val, dval, status)
    integer, intent(in) :: kind, n, nz
    real(dp), intent(in) :: q, z(nz)
    real(dp), intent(out) :: val(nz), dval(nz)
    integer, intent(out) :: status
    real(dp), allocatable :: d(:), e2(:), y(:)
    real(dp) :: x, bound, step, f1, fn, pivmin, s, sgn, w
    integer :: fam, m, j, r0, nr, i, k, base, lev
    val = nan_dp
    dval = nan_dp
    status = mathieu_bad_input
    if (n < 0 .or. (kind == 2 .and. n == 0) .or. n > 100000000) return
    if (.not. (abs(q) <= mathieu_max_q)) return
    if (kind == 1) then
      fam = 1 + mod(n, 2)
      m = n / 2
    else
      fam = 3 + (1 - mod(n, 2))
      m = (n - 1) / 2
    end if
    lev = n
    if (kind == 2) lev = n - 1
    if (q < 0.0_dp .and. mod(n, 2) == 1) lev = n - 1 + 2 * (kind - 1)
    call solve(fam, 0.0_dp, q, m, .false., real(n, dp), 3.0_dp, 0.25_dp * eps_dp, x, bound, status, &
               d, e2, j, r0, lev)
    if (status /= mathieu_ok) return
    nr = size(d)
    allocate(y(nr))
    pivmin = tiny(1.0_dp) * max(1.0_dp, maxval(e2))
    if (q /= 0.0_dp) then
      call twist(d, e2, nr, x, pivmin, step, f1, fn, y)
    else
      y = 0.0_dp
      y(j + 1) = 1.0_dp
    end if
    base = fam_base(fam)
    ! the couplings were |q|: back to q's sign; A_0 = y_0 / sqrt(2)
    do i = 1, nr
      k = r0 + i - 1
      if (q < 0.0_dp .and. mod(k, 2) /= 0) y(i) = -y(i)
    end do
    y = y / sqrt(sum(y * y))
    if (fam == 1 .and. r0 == 0) y(1) = y(1) / sqrt2
    ! the sign: ce_n(0) > 0, se_n'(0) > 0
    s = 0.0_dp
    do i = 1, nr
      w = 1.0_dp
      if (kind == 2) w = real(base + 2 * (r0 + i - 1), dp)
      s = s + w * y(i)
    end do
    sgn = sign(1.0_dp, s)
    do k = 1, nz
      val(k) = 0.0_dp
      dval(k) = 0.0_dp
      do i = 1, nr
        w = real(base + 2 * (r0 + i - 1), dp)
        if (kind == 1) then
          val(k) = val(k) + y(i) * cos(w * z(k))
          dval(k) = dval(k) - w * y(i) * sin(w * z(k))
        else
          val(k) = val(k) + y(i) * sin(w * z(k))
          dval(k) = dval(k) + w * y(i) * cos(w * z(k))
        end if
      end do
      val(k) = sgn * val(k)
      dval(k) = sgn * dval(k)
    end do
  end subroutine mathieu_function

  !> Sturm count in double-double: the window's diagonal (nu + 2k)^2 is
  !> formed exactly (nu + 2k by two-sum, the square by Dekker's product).
  pure integer function sturm_count_dd(nu, q, r0, n, xh, xl) result(c)
    real(dp), intent(in) :: nu, q, xh, xl
    integer, intent(in) :: r0, n
    real(dp) :: sh, sl, dh, dl, ph, pl, th, tl, uh, ul, e2h, e2l, pivmin
    integer :: i
    call two_prod(q, q, e2h, e2l)
    pivmin = tiny(1.0_dp) * max(1.0_dp, e2h) * 1.0e20_dp
    c = 0
    do i = 1, n
      call two_sum(nu, 2.0_dp * real(r0 + i - 1, dp), sh, sl)
      call dd_mul(sh, sl, sh, sl, dh, dl)
      call dd_add(dh, dl, -xh, -xl, ph, pl)
      if (i == 1) then
        th = ph
        tl = pl
      else
        call dd_div(e2h, e2l, th, tl, uh, ul)
        call dd_add(ph, pl, -uh, -ul, th, tl)
      end if
      if (abs(th) < pivmin) then
        th = -pivmin
        tl = 0.0_dp
      end if
      if (th < 0.0_dp) c = c + 1
    end do
  end function sturm_count_dd

  !> mathieu_level to double-double precision (vh + vl, about 1e-31
  !> relative to |q|): the difference of two levels keeps its relative
  !> accuracy down to 1e-15 of the levels (the charge dispersion).  bound:
  !> the bound on the error of vh + vl (truncation, bracket, rounding).
  elemental subroutine mathieu_level_dd(nu, q, m, vh, vl, bound, status)
    real(dp), intent(in) :: nu, q
    integer, intent(in) :: m
    real(dp), intent(out) :: vh, vl, bound
    integer, intent(out) :: status
    real(dp), allocatable :: d(:), e2(:)
    real(dp) :: nr, x, w, loh, lol, hih, hil, mh, ml, th, tl
    integer :: j, n, r0, it
    vh = nan_dp
    vl = nan_dp
    bound = nan_dp
    status = mathieu_bad_input
    if (.not. (abs(nu) <= mathieu_max_order) .or. m < 0 .or. m > 100000000) return
    if (.not. (abs(q) <= 1.0e6_dp)) return
    nr = modulo(nu, 2.0_dp)
    if (nr >= 2.0_dp) nr = 0.0_dp
    call solve(0, nr, q, m, .false., level_order(nr, m), 2.0_dp, 1.0e-33_dp, x, bound, &
               status, d, e2, j, r0, m)
    if (status /= mathieu_ok) return
    n = size(d)
    ! bracket: the double value is exact for couplings a few ulp off
    w = 64.0_dp * eps_dp * (abs(q) + abs(x)) + tiny(1.0_dp)
    loh = x - w
    lol = 0.0_dp
    hih = x + w
    hil = 0.0_dp
    do it = 1, 40
      if (sturm_count_dd(nr, q, r0, n, loh, lol) <= j) exit
      loh = loh - w
      w = 2.0_dp * w
    end do
    w = 64.0_dp * eps_dp * (abs(q) + abs(x)) + tiny(1.0_dp)
    do it = 1, 40
      if (sturm_count_dd(nr, q, r0, n, hih, hil) > j) exit
      hih = hih + w
      w = 2.0_dp * w
    end do
    do it = 1, 200
      call dd_add(hih, hil, -loh, -lol, th, tl)
      if (abs(th) <= 4.0e-32_dp * max(1.0_dp, abs(hih))) exit
      call dd_add(loh, lol, 0.5_dp * th, 0.5_dp * tl, mh, ml)
      if ((mh == loh .and. ml == lol) .or. (mh == hih .and. ml == hil)) exit
      if (sturm_count_dd(nr, q, r0, n, mh, ml) > j) then
        hih = mh
        hil = ml
      else
        loh = mh
        lol = ml
      end if
    end do
    call dd_add(hih, hil, -loh, -lol, th, tl)
    call dd_add(loh, lol, 0.5_dp * th, 0.5_dp * tl, vh, vl)
    ! the error: the truncation, the bracket's width, and the Sturm count's
    ! backward error (couplings a few units of 1e-32 off)
    bound = bound + abs(th) + 8.0e-32_dp * (abs(q) + abs(vh))
    status = mathieu_ok
  end subroutine mathieu_level_dd

  !> The characteristic exponent nu(a, q) >= 0: the order whose
  !> characteristic value is a (DLMF 28.2(iii)), real where the solutions
  !> are bounded (a in a band [a_n, b_n+1] of |q|).  NaN with status
  !> mathieu_ok where they are not (an instability tongue, or a < a_0).
  elemental subroutine mathieu_nu(a, q, nu, status)
    real(dp), intent(in) :: a, q
    real(dp), intent(out) :: nu
    integer, intent(out) :: status
    real(dp), allocatable :: d(:), e2(:)
    real(dp) :: aq, p, rr, e, shi, slo, lo, hi, mid, pivmin, nbnd
    integer :: fam, r0, r1, n, na, nb, band, it, j
    logical :: cut
    nu = nan_dp
    status = mathieu_bad_input
    if (.not. (abs(q) <= mathieu_max_q)) return
    if (.not. (abs(a) <= mathieu_max_order ** 2)) return
    status = mathieu_ok
    aq = abs(q)
    if (aq == 0.0_dp) then
      if (a >= 0.0_dp) nu = sqrt(a)
      return
    end if
    p = sqrt(max(a + 4.0_dp * aq, 0.0_dp))
    rr = sqrt(max(a - 4.0_dp * aq, 0.0_dp))
    e = 16.0_dp + 10.0_dp * log10(max(aq, 1.0_dp))
    shi = p + e
    ! which band edges lie below a: the counts of the four families, each
    ! over the rows near a (the rows below the window, far below a, are
    ! counted whole: their eigenvalues lie below a)
    slo = rr - e
    na = 0
    nb = 0
    do fam = 1, 4
      call window_rows(fam, 0.0_dp, slo, shi, slo > 2.0_dp, r0, r1)
      n = r1 - r0 + 1
      if (n > max_rows) then
        status = mathieu_no_convergence
        return
      end if
      if (allocated(d)) deallocate(d, e2)
      allocate(d(n), e2(n))
      call build(fam, 0.0_dp, aq, r0, r1, d, e2)
      pivmin = tiny(1.0_dp) * max(1.0_dp, maxval(e2))
      if (fam <= 2) then
        na = na + r0 + sturm_count(d, e2, n, a, pivmin)
      else
        nb = nb + r0 + sturm_count(d, e2, n, a, pivmin)
      end if
    end do
    if (na /= nb + 1) return     ! unstable: a <= a_0 or b_n <= a <= a_n
    band = na - 1                ! a_band < a <= b_band+1: nu in (band, band+1]
    nbnd = real(band, dp)
    ! bisection in nu: lambda_nu(q) increases with nu in the band, and
    ! lambda_nu < a exactly when the window has more than j levels below a
    lo = nbnd
    hi = nbnd + 1.0_dp
    cut = slo > 2.0_dp
    do it = 1, 200
      mid = lo + 0.5_dp * (hi - lo)
      if (mid <= lo .or. mid >= hi) exit
      call window_rows(0, mid, slo, shi, cut, r0, r1)
      n = r1 - r0 + 1
      if (allocated(d)) deallocate(d, e2)
      allocate(d(n), e2(n))
      call build(0, mid, aq, r0, r1, d, e2)
      pivmin = tiny(1.0_dp) * max(1.0_dp, maxval(e2))
      j = window_index(0, mid, 0, .true., r0)
      if (sturm_count(d, e2, n, a, pivmin) > j) then
        lo = mid
      else
        hi = mid
      end if
    end do
    nu = lo + 0.5_dp * (hi - lo)
  end subroutine mathieu_nu

end module pendula_mathieu
