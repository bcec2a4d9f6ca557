!> The double pendulum (pendula_double) on the n-dimensional driver
!> (pendula_nd_run): its path by DOP853 or Gauss-Legendre, the flip-time map
!> over initial angles (on OpenMP threads), and the Lyapunov spectrum from
!> the variational equations with QR re-orthonormalisation (Benettin,
!> Galgani, Giorgilli and Strelcyn, Meccanica 15 (1980) 9).
module pendula_double_run
  use pendula_kinds, only: dp, i8, pi, two_pi, nan_dp, inf_dp
  use pendula_integrators, only: run_stats, st_ok, st_bad_method, st_bad_step, st_nonfinite
  use pendula_ode, only: ode_system, ode_dop853
  use pendula_nd_run, only: nd_run, nd_runs_start, dm_dop853 => nd_dop853, dm_gauss4 => nd_gauss4, &
    dm_gauss6 => nd_gauss6
  use pendula_double, only: double_pendulum, double_rhs, double_jacobian, double_velocities
  implicit none
  private
  public :: double_simulate, double_flip_map, double_lyapunov, double_section

  !> the methods of double_simulate and double_lyapunov: those of nd_run
  public :: dm_dop853, dm_gauss4, dm_gauss6

  !> the double pendulum as an ode_system, y = (theta1, theta2, p1, p2)
  type, extends(ode_system) :: double_ode
    type(double_pendulum) :: dpd
  contains
    procedure :: rhs => double_ode_rhs
  end type double_ode

  !> the state and its 4 x 4 tangent matrix (column-major), n = 20
  type, extends(ode_system) :: double_tangent_ode
    type(double_pendulum) :: dpd
  contains
    procedure :: rhs => double_tangent_rhs
  end type double_tangent_ode

  !> the output points per chunk of the flip search
  integer, parameter :: flip_chunk = 512

contains

  pure subroutine double_ode_rhs(self, t, y, f)
    class(double_ode), intent(in) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: f(:)
    call double_rhs(self%dpd, y(1:4), f(1:4))
  end subroutine double_ode_rhs

  pure subroutine double_tangent_rhs(self, t, y, f)
    class(double_tangent_ode), intent(in) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: f(:)
    real(dp) :: jac(4, 4)
    call double_rhs(self%dpd, y(1:4), f(1:4))
    call double_jacobian(self%dpd, y(1:4), jac)
    f(5:20) = reshape(matmul(jac, reshape(y(5:20), [4, 4])), [16])
  end subroutine double_tangent_rhs

  !> The path from y0 = (theta1, theta2, p1, p2) at t = 0 to the times tout
  !> by DOP853 (rtol, atol), or Gauss-Legendre of order 4 or 6 (fixed step
  !> dt; output k after counts(k) more steps, tout ignored).
  subroutine double_simulate(dpd, method, y0, tout, counts, rtol, atol, dt, yout, stats, status, cancel)
    type(double_pendulum), intent(in) :: dpd
    integer, intent(in) :: method
    real(dp), intent(in) :: y0(4), tout(:), rtol, atol, dt
    integer(i8), intent(in) :: counts(:)
    real(dp), intent(out) :: yout(:, :)
    type(run_stats), intent(out) :: stats
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    call nd_run(double_ode(n=4, dpd=dpd), method, 0.0_dp, y0, tout, counts, rtol, atol, dt, yout, stats, status, &
                cancel)
  end subroutine double_simulate

  !> The first time either arm passes over the top (abs(theta_i) = pi) for
  !> the start y0 (angles in [-pi, pi]), by DOP853 at (rtol, atol), searched
  !> up to tmax: inf when neither flips by tmax.  The path is output on a
  !> grid of spacing hg (in chunks of flip_chunk points); the crossing is
  !> first the root of the cubic Hermite interpolant of theta_i (its rates
  !> w_i) on the grid interval where abs(theta_i) first exceeds pi, by
  !> bisection, then polished by Newton's method on the integrated path (the
  !> state integrated from the interval's start over the time found), so the
  !> grid need only be fine enough not to miss a crossing.
  subroutine flip_time(sys, y0, tmax, hg, rtol, atol, tf, status, cancel)
    type(double_ode), intent(in) :: sys
    real(dp), intent(in) :: y0(4), tmax, hg, rtol, atol
    real(dp), intent(out) :: tf
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    real(dp) :: y(4), tout(flip_chunk), yout(4, flip_chunk), t0, ya(4), wa(2), wb(2), tc, s1, lev
    real(dp) :: yc(4), wc(2), dt
    type(run_stats) :: st
    integer :: k, j, arm, nk, it, nchunk
    tf = inf_dp
    status = st_ok
    y = y0
    t0 = 0.0_dp
    ! the first chunk short and each one twice the last (up to flip_chunk grid points): a pixel that flips
    ! early stops soon after its flip instead of integrating a whole long chunk past it
    nchunk = 16
    do while (t0 < tmax)
      nk = int(min(real(nchunk, dp), real(ceiling((tmax - t0) / hg), dp)))
      nchunk = min(2 * nchunk, flip_chunk)
      nk = max(nk, 1)
      do k = 1, nk
        tout(k) = t0 + real(k, dp) * hg
      end do
      call ode_dop853(sys, 0.0_dp, y, tout(1:nk) - t0, rtol, atol, yout(:, 1:nk), st, status, cancel)
      if (status /= st_ok) then
        tf = nan_dp
        return
      end if
      ya = y
      do k = 1, nk
        if (abs(yout(1, k)) > pi .or. abs(yout(2, k)) > pi) then
          call double_velocities(sys%dpd, ya, wa)
          call double_velocities(sys%dpd, yout(:, k), wb)
          tc = huge(1.0_dp)
          arm = 1
          do j = 1, 2
            if (abs(yout(j, k)) > pi) then
              s1 = crossing(ya(j), wa(j), yout(j, k), wb(j), sign(pi, yout(j, k)))
              if (s1 < tc) then
                tc = s1
                arm = j
              end if
            end if
          end do
          ! polish on the integrated path: Newton on abs(theta_arm) - pi in the time after ya
          lev = sign(pi, yout(arm, k))
          do it = 1, 3
            call advance(ya, tc, yc)
            if (status /= st_ok) then
              tf = nan_dp
              return
            end if
            call double_velocities(sys%dpd, yc, wc)
            if (.not. (abs(wc(arm)) > 0.0_dp)) exit
            dt = (yc(arm) - lev) / wc(arm)
            tc = tc - dt
            if (abs(dt) <= 1.0e-15_dp * (1.0_dp + tc)) exit
          end do
          tf = tout(k) - hg + tc
          if (tf > tmax) tf = inf_dp
          return
        end if
        ya = yout(:, k)
      end do
      y = yout(:, nk)
      t0 = tout(nk)
    end do

  contains

    !> the s in [0, hg] where the cubic Hermite of (x0, v0) and (x1, v1) equals
    !> level (x0 on the level's near side, x1 past it)
    pure function crossing(x0, v0, x1, v1, level) result(s)
      real(dp), intent(in) :: x0, v0, x1, v1, level
      real(dp) :: s, lo, hi, mid, u, h00, h10, h01, h11, val, s0
      integer :: it
      lo = 0.0_dp; hi = 1.0_dp
      s0 = sign(1.0_dp, x1 - level)
      do it = 1, 60
        mid = 0.5_dp * (lo + hi)
        u = mid
        h00 = (1.0_dp + 2.0_dp * u) * (1.0_dp - u)**2
        h10 = u * (1.0_dp - u)**2
        h01 = u * u * (3.0_dp - 2.0_dp * u)
        h11 = u * u * (u - 1.0_dp)
        val = h00 * x0 + h10 * hg * v0 + h01 * x1 + h11 * hg * v1 - level
        if (val * s0 >= 0.0_dp) then
          hi = mid
        else
          lo = mid
        end if
      end do
      s = hi * hg
    end function crossing

    !> the state a time tau after y1 by DOP853 at the search's tolerances
    subroutine advance(y1, tau, y2)
      real(dp), intent(in) :: y1(4), tau
      real(dp), intent(out) :: y2(4)
      real(dp) :: yy(4, 1)
      type(run_stats) :: st1
      y2 = y1
      if (.not. (tau > 0.0_dp)) return
      call ode_dop853(sys, 0.0_dp, y1, [tau], rtol, atol, yy, st1, status, cancel)
      y2 = yy(:, 1)
    end subroutine advance

  end subroutine flip_time

  !> The flip-time map: pixel k released from rest at (th1(k), th2(k)); skip(k)
  !> /= 0 marks a pixel that cannot flip (tflip = inf without integrating).
  !> tflip(k) the flip time at (rtol, atol), tcheck(k) at the tolerance
  !> tightened tenfold (rtol / 10, atol / 10); status(k) the pixel's status.
  !> Pixels run on nthreads OpenMP threads (0: OpenMP's default); each
  !> pixel's result is the same whatever the thread count.
  subroutine double_flip_map(dpd, th1, th2, skip, tmax, hg, rtol, atol, nthreads, tflip, tcheck, status, cancel)
    type(double_pendulum), intent(in) :: dpd
    real(dp), intent(in) :: th1(:), th2(:), tmax, hg, rtol, atol
    integer, intent(in) :: skip(:), nthreads
    real(dp), intent(out) :: tflip(:), tcheck(:)
    integer, intent(out) :: status(:)
    integer, intent(inout), volatile :: cancel
    type(double_ode) :: sys
    real(dp) :: y0(4)
    integer :: k, nt, s2
    logical :: ok
    sys = double_ode(n=4, dpd=dpd)
    tflip = nan_dp
    tcheck = nan_dp
    call nd_runs_start(hg, nthreads, status, nt, ok)
    if (.not. ok) return
    !$omp parallel do schedule(dynamic, 1) default(none) num_threads(nt) private(y0, s2) &
    !$omp   shared(sys, th1, th2, skip, tmax, hg, rtol, atol, tflip, tcheck, status, cancel)
    do k = 1, size(th1)
      if (cancel == 0) then
        if (skip(k) /= 0) then
          tflip(k) = inf_dp
          tcheck(k) = inf_dp
          status(k) = st_ok
        else
          y0 = [th1(k), th2(k), 0.0_dp, 0.0_dp]
          call flip_time(sys, y0, tmax, hg, rtol, atol, tflip(k), status(k), cancel)
          if (status(k) == st_ok) then
            call flip_time(sys, y0, tmax, hg, 0.1_dp * rtol, 0.1_dp * atol, tcheck(k), s2, cancel)
            status(k) = s2
          end if
        end if
      end if
    end do
    !$omp end parallel do
  end subroutine double_flip_map

  !> The Lyapunov spectrum from y0: the variational equations beside the
  !> path, re-orthonormalised by QR (modified Gram-Schmidt) every `every`
  !> steps of Gauss-Legendre (method dm_gauss4 or dm_gauss6, step h) or
  !> every span h * every of DOP853 (rtol, atol), nren times.  lam(4) the
  !> exponents in the order of the Gram-Schmidt vectors (largest first),
  !> yend the final state.
  subroutine double_lyapunov(dpd, method, y0, h, every, nren, rtol, atol, lam, yend, status, cancel)
    type(double_pendulum), intent(in) :: dpd
    integer, intent(in) :: method
    real(dp), intent(in) :: y0(4), h, rtol, atol
    integer(i8), intent(in) :: every, nren
    real(dp), intent(out) :: lam(4), yend(4)
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    type(double_tangent_ode) :: sys
    type(run_stats) :: st
    real(dp) :: y(20), yo(20, 1), q(4, 4), sumlog(4), r, span, tt(1)
    integer(i8) :: cnt(1), it
    integer :: i, j
    sys = double_tangent_ode(n=20, dpd=dpd)
    lam = nan_dp
    yend = nan_dp
    status = st_ok
    if (.not. (h > 0.0_dp .and. every > 0_i8 .and. nren > 0_i8)) then
      status = st_bad_step
      return
    end if
    ! the frame (e1, e2, e4, e3) in y = (theta1, theta2, p1, p2): its last vector is -J times its first
    ! (J the symplectic unit) and its first three span the symplectic complement of the first.  A
    ! symplectic map keeps both properties, and Gram-Schmidt keeps them (the first k vectors span the
    ! map's image of the first k), so R(4, 4) = 1 / R(1, 1) at every step: lambda1 + lambda4 = 0 to
    ! rounding at any t for a symplectic method, not only in the limit.
    q = 0.0_dp
    q(1, 1) = 1.0_dp; q(2, 2) = 1.0_dp; q(4, 3) = 1.0_dp; q(3, 4) = 1.0_dp
    y(1:4) = y0
    y(5:20) = reshape(q, [16])
    sumlog = 0.0_dp
    span = h * real(every, dp)
    cnt(1) = every
    tt(1) = span
    do it = 1_i8, nren
      call nd_run(sys, method, 0.0_dp, y, tt, cnt, rtol, atol, h, yo, st, status, cancel)
      if (status /= st_ok) return
      y = yo(:, 1)
      q = reshape(y(5:20), [4, 4])
      ! modified Gram-Schmidt, each column orthogonalised twice (Giraud et al.: twice is enough)
      do j = 1, 4
        do i = 1, j - 1
          q(:, j) = q(:, j) - dot_product(q(:, i), q(:, j)) * q(:, i)
        end do
        do i = 1, j - 1
          q(:, j) = q(:, j) - dot_product(q(:, i), q(:, j)) * q(:, i)
        end do
        r = norm2(q(:, j))
        sumlog(j) = sumlog(j) + log(r)
        q(:, j) = q(:, j) / r
      end do
      y(5:20) = reshape(q, [16])
    end do
    lam = sumlog / (span * real(nren, dp))
    yend = y(1:4)
  end subroutine double_lyapunov

  !> The cubic Hermite interpolant at u in [0, 1] of (x0, v0) and (x1, v1)
  !> over an interval of length h.
  pure elemental function hermite(x0, v0, x1, v1, h, u) result(x)
    real(dp), intent(in) :: x0, v0, x1, v1, h, u
    real(dp) :: x
    x = (1.0_dp + 2.0_dp * u) * (1.0_dp - u)**2 * x0 + u * (1.0_dp - u)**2 * h * v0 &
        + u * u * (3.0_dp - 2.0_dp * u) * x1 + u * u * (u - 1.0_dp) * h * v1
  end function hermite

  !> The Poincare section theta1 = 0 (mod 2 pi) crossed upwards (theta1
  !> increasing) of norb orbits from y0s(:, k): the states at the first
  !> maxpts crossings before tmax into pts(:, 1:npts(k), k) (theta1 set to
  !> the multiple of 2 pi it crossed, theta2 as integrated).  The path is
  !> output every hg, by Gauss-Legendre of order 6 with step hg
  !> (method dm_gauss6: the energy stays bounded, the section's points stay
  !> on their energy shell) or by DOP853 at (rtol, atol) (dm_dop853); the
  !> crossing is the root of the cubic Hermite interpolant of theta1 on the
  !> grid interval, the other components interpolated there the same way.
  !> Orbits run on nthreads OpenMP threads.
  subroutine double_section(dpd, method, y0s, tmax, hg, rtol, atol, nthreads, pts, npts, status, cancel)
    type(double_pendulum), intent(in) :: dpd
    integer, intent(in) :: method, nthreads
    real(dp), intent(in) :: y0s(:, :), tmax, hg, rtol, atol
    real(dp), intent(out) :: pts(:, :, :)
    integer, intent(out) :: npts(:), status(:)
    integer, intent(inout), volatile :: cancel
    type(double_ode) :: sys
    integer :: k, nt
    logical :: ok
    sys = double_ode(n=4, dpd=dpd)
    pts = nan_dp
    npts = 0
    call nd_runs_start(hg, nthreads, status, nt, ok)
    if (.not. ok) return
    !$omp parallel do schedule(dynamic, 1) default(none) num_threads(nt) &
    !$omp   shared(sys, method, y0s, tmax, hg, rtol, atol, pts, npts, status, cancel)
    do k = 1, size(y0s, 2)
      if (cancel == 0) call section_one(sys, method, y0s(:, k), tmax, hg, rtol, atol, pts(:, :, k), npts(k), &
                                        status(k), cancel)
    end do
    !$omp end parallel do
  end subroutine double_section

  subroutine section_one(sys, method, y0, tmax, hg, rtol, atol, pts, npts, status, cancel)
    type(double_ode), intent(in) :: sys
    integer, intent(in) :: method
    real(dp), intent(in) :: y0(4), tmax, hg, rtol, atol
    real(dp), intent(inout) :: pts(:, :)
    integer, intent(out) :: npts, status
    integer, intent(inout), volatile :: cancel
    real(dp) :: y(4), tout(flip_chunk), yout(4, flip_chunk), t0, ya(4), fa(4), fb(4), lev, lo, hi, mid
    real(dp) :: tc, yc(4), fc(4)
    integer(i8) :: cnt(flip_chunk)
    type(run_stats) :: st
    integer :: k, nk, it
    npts = 0
    status = st_ok
    if (method /= dm_dop853 .and. method /= dm_gauss6) then
      status = st_bad_method
      return
    end if
    y = y0
    t0 = 0.0_dp
    cnt = 1_i8
    do while (t0 < tmax .and. npts < size(pts, 2))
      nk = int(min(real(flip_chunk, dp), real(ceiling((tmax - t0) / hg), dp)))
      nk = max(nk, 1)
      do k = 1, nk
        tout(k) = real(k, dp) * hg
      end do
      call nd_run(sys, method, 0.0_dp, y, tout(1:nk), cnt(1:nk), rtol, atol, hg, yout(:, 1:nk), st, status, cancel)
      if (status /= st_ok) return
      ya = y
      call double_rhs(sys%dpd, ya, fa)
      do k = 1, nk
        call double_rhs(sys%dpd, yout(:, k), fb)
        if (floor(yout(1, k) / two_pi) > floor(ya(1) / two_pi)) then
          ! an upward crossing of lev = 2 pi n, ya(1) < lev <= yout(1, k)
          lev = two_pi * real(floor(yout(1, k) / two_pi), dp)
          lo = 0.0_dp; hi = 1.0_dp
          do it = 1, 60
            mid = 0.5_dp * (lo + hi)
            if (hermite(ya(1), fa(1), yout(1, k), fb(1), hg, mid) >= lev) then
              hi = mid
            else
              lo = mid
            end if
          end do
          ! polish: integrate from ya over the interpolated time, then Newton on theta1 (its rate
          ! theta1' = w1) twice, so that the point is on the integrated path, not on the interpolant
          tc = hi * hg
          do it = 1, 3
            call advance(ya, tc, yc)
            if (status /= st_ok) return
            call double_rhs(sys%dpd, yc, fc)
            if (.not. (fc(1) > 0.0_dp)) exit
            tc = tc - (yc(1) - lev) / fc(1)
          end do
          npts = npts + 1
          pts(:, npts) = yc
          if (npts >= size(pts, 2)) return
        end if
        ya = yout(:, k)
        fa = fb
      end do
      if (.not. all(abs(yout(:, nk)) <= huge(1.0_dp))) then
        status = st_nonfinite
        return
      end if
      y = yout(:, nk)
      t0 = t0 + real(nk, dp) * hg
    end do

  contains

    !> the state a time tau after y0 by the run's method (one Gauss-Legendre step of size tau)
    subroutine advance(y0, tau, y1)
      real(dp), intent(in) :: y0(4), tau
      real(dp), intent(out) :: y1(4)
      real(dp) :: yy(4, 1), tt(1)
      integer(i8) :: one(1)
      type(run_stats) :: st1
      y1 = y0
      if (tau <= 0.0_dp) return
      tt(1) = tau
      one(1) = 1_i8
      call nd_run(sys, method, 0.0_dp, y0, tt, one, rtol, atol, tau, yy, st1, status, cancel)
      y1 = yy(:, 1)
    end subroutine advance

  end subroutine section_one

end module pendula_double_run
