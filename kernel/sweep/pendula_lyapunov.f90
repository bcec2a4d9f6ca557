!> Lyapunov exponents of the damped, torqued, driven rigid pendulum
!>   theta'' = -eps sin(theta) - beta theta' + tau + A cos(Omega t + phi)
!> (the model of pendula_integrators%make_model / accel, whose accel is used
!> here, so that the sign conventions are the same by construction).
!>
!> Method (Benettin et al. 1980): the orbit (theta, v) is integrated together
!> with two tangent vectors w1, w2 of the variational equations
!>   dw/dt = J w,   J = [[0, 1], [-eps cos(theta), -beta]]
!> by an adaptive embedded Runge-Kutta of order 8(5,3) (DOP853, the tables of
!> pendula_rk_tables.inc) on the 6-D state (theta, v, w1, w2).  Every
!> renormalisation interval h_r the pair is re-orthonormalised (Gram-Schmidt):
!> log |w1| accumulates the largest exponent, log |w2 - (w2.w1) w1| the
!> second.  Their sum is (1/T) log det of the tangent map = -beta exactly
!> (Liouville: trace J = -beta), a check on the whole computation.
!>
!> Time base: T_b = 2 pi / |Omega| for a driven model (A /= 0, Omega /= 0), else
!> the small-oscillation period 2 pi / sqrt(eps).  h_r = T_b / m with m the
!> smallest integer such that (beta + 2 sqrt(eps)) h_r <= 4: within one
!> interval the tangent norms change by at most about e^4, so neither vector
!> falls to the absolute tolerance, and the angle between them stays resolved.
!> Each interval restarts the model's clock at 0 with the drive phase
!> phi + 2 pi j / m (exact: Omega h_r = 2 pi / m), and theta is reduced mod
!> 2 pi (the force is 2 pi periodic), so that long runs lose no phase.
!> The transient is ceil(t_tr / T_b) base periods (whole drive periods, as the
!> poincare measure), the averaging window ceil(t_avg / T_b) base periods.
!>
!> Convergence estimate: the window is cut into nblock = 8 blocks of equal
!> numbers of intervals; err = the standard error of the mean of the 8 block
!> exponents, std(block lambda_1) / sqrt(8).
!>
!> Thread safety: no module variables; pure helpers; status codes only.
module pendula_lyapunov
  use pendula_kinds, only: dp, i8, two_pi, nan_dp
  use pendula_integrators, only: pendulum_model, make_model, add_effects, dop853_step_6, dop853_error_norm, system_rhs, max_steps, &
    st_ok, st_step_underflow, st_nonfinite, st_too_many_steps, start_step_euler, start_step_refined
  implicit none
  private
  public :: lyapunov_point, lyapunov_intervals, ly_nblock, point_model

  !> blocks of the averaging window for the convergence estimate
  integer, parameter :: ly_nblock = 8
  !> status of a point stopped by its cancel flag
  integer, parameter, public :: ly_cancelled = 9

contains

  !> The base period, the intervals per base period m, the transient and
  !> window lengths in intervals (see the module text).
  pure subroutine lyapunov_intervals(p, t_tr, t_avg, tb, m, ntr, navg, ok)
    real(dp), intent(in) :: p(12), t_tr, t_avg
    real(dp), intent(out) :: tb
    integer, intent(out) :: m, ntr, navg
    logical, intent(out) :: ok
    real(dp) :: g, rm, rtr, ravg
    m = 0; ntr = 0; navg = 0
    if (p(4) /= 0.0_dp .and. p(5) /= 0.0_dp) then
      tb = two_pi / abs(p(5))
    else
      tb = two_pi / sqrt(p(1))
    end if
    ! a vibrating pivot (p(9), p(10)): its period, when the drive's is the same or there is none
    if (p(9) /= 0.0_dp) then
      if (p(4) /= 0.0_dp .and. p(5) /= 0.0_dp .and. p(5) /= p(10)) then
        ok = .false.; return
      end if
      tb = two_pi / p(10)
    end if
    g = abs(p(2)) + 2.0_dp * sqrt(p(1))
    if (p(9) /= 0.0_dp) g = g + 2.0_dp * sqrt(abs(p(9))) * p(10)
    ! dry friction sticks: the tangent flow has no derivative there (no exponents in this sense)
    if (p(11) /= 0.0_dp) then
      ok = .false.; return
    end if
    ! counted in reals first: a window too long to count is refused, not wrapped around
    rm = max(1.0_dp, real(ceiling(min(g * tb / 4.0_dp, 1.0e9_dp)), dp))
    rtr = max(0.0_dp, t_tr / tb - 1.0e-12_dp)
    ravg = max(1.0_dp, t_avg / tb - 1.0e-12_dp)
    ok = tb > 0.0_dp .and. tb <= huge(1.0_dp) .and. rm * (rtr + ravg + 2.0_dp) <= 1.0e9_dp
    if (.not. ok) return
    m = nint(rm)
    ntr = m * ceiling(rtr)
    navg = max(m * ceiling(ravg), ly_nblock)
  end subroutine lyapunov_intervals

  !> Largest (lam1) and second (lam2) Lyapunov exponents of the orbit from
  !> (theta0, v0) = (p(7), p(8)) with p = eps, beta, tau, amp, omega, phase,
  !> theta0, v0; err: the convergence estimate of lam1 (module text).
  !> t_tr, t_avg: transient and averaging time (rounded up to whole base
  !> periods).  status 0, or 100 + the integrator status (5 step underflow,
  !> 6 non-finite, 7 too many steps), or 2 for bad parameters (eps <= 0, a
  !> window too long to count in intervals).
  !> cancel (optional): read once per renormalisation interval; non-zero
  !> stops the point with status ly_cancelled.
  subroutine lyapunov_point(p, rtol, atol, t_tr, t_avg, lam1, lam2, err, status, cancel, uf)
    real(dp), intent(in) :: p(12), rtol, atol, t_tr, t_avg
    real(dp), intent(out) :: lam1, lam2, err
    integer, intent(out) :: status
    integer, intent(inout), volatile, optional :: cancel
    !> a user's force (uf%forced), its clock from the point's t = 0
    type(pendulum_model), intent(in), optional :: uf
    real(dp) :: tb, hr, y(6), h, s1, s2, n1, n2, d, blk(ly_nblock), bsum, phase, tblk, pphase
    integer :: m, ntr, navg, j, jb, jstart, jend, s
    integer(i8) :: nsteps
    logical :: ok
    lam1 = nan_dp; lam2 = nan_dp; err = nan_dp
    if (.not. (p(1) > 0.0_dp) .or. .not. (p(2) >= 0.0_dp) .or. .not. (t_tr >= 0.0_dp) &
        .or. .not. (t_avg > 0.0_dp) .or. .not. (rtol > 0.0_dp) .or. .not. (atol >= 0.0_dp)) then
      status = 2; return
    end if
    call lyapunov_intervals(p, t_tr, t_avg, tb, m, ntr, navg, ok)
    if (.not. ok) then
      status = 2; return
    end if
    hr = tb / real(m, dp)
    y = [p(7), p(8), 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp]
    h = 0.0_dp
    nsteps = 0
    s1 = 0.0_dp; s2 = 0.0_dp
    blk = 0.0_dp
    jb = 1; bsum = 0.0_dp
    jstart = 0
    status = st_ok
    do j = 0, ntr + navg - 1
      if (present(cancel)) then
        if (cancel /= 0) then
          status = ly_cancelled; return
        end if
      end if
      ! the drive phase at the start of interval j: phi + Omega j h_r = phi +- 2 pi j / m (mod 2 pi);
      ! a drive of frequency 0 is a constant force A cos(phi)
      phase = p(6)
      if (p(4) /= 0.0_dp .and. p(5) /= 0.0_dp) &
        phase = p(6) + sign(1.0_dp, p(5)) * two_pi * real(mod(j, m), dp) / real(m, dp)
      ! the pivot's phase likewise (its period is the base period)
      pphase = 0.0_dp
      if (p(9) /= 0.0_dp) pphase = two_pi * real(mod(j, m), dp) / real(m, dp)
      if (present(uf)) then
        call interval(p, phase, pphase, hr, rtol, atol, y, h, nsteps, s, uf, real(j, dp) * hr)
      else
        call interval(p, phase, pphase, hr, rtol, atol, y, h, nsteps, s)
      end if
      if (s /= st_ok) then
        status = 100 + s; return
      end if
      y(1) = y(1) - two_pi * anint(y(1) / two_pi)
      ! Gram-Schmidt
      n1 = hypot(y(3), y(4))
      y(3:4) = y(3:4) / n1
      d = y(5) * y(3) + y(6) * y(4)
      y(5:6) = y(5:6) - d * y(3:4)
      n2 = hypot(y(5), y(6))
      y(5:6) = y(5:6) / n2
      if (.not. (n1 > 0.0_dp .and. n2 > 0.0_dp .and. n1 <= huge(1.0_dp) .and. n2 <= huge(1.0_dp))) then
        status = 100 + st_nonfinite; return
      end if
      if (j >= ntr) then
        s1 = s1 + log(n1); s2 = s2 + log(n2)
        bsum = bsum + log(n1)
        ! block jb covers intervals [ntr + (jb-1) navg / nb, ntr + jb navg / nb)
        jend = ntr + int((int(jb, i8) * navg) / ly_nblock) - 1
        if (j == jend) then
          tblk = real(jend - (ntr + jstart) + 1, dp) * hr
          blk(jb) = bsum / tblk
          jstart = jend - ntr + 1
          bsum = 0.0_dp
          jb = jb + 1
        end if
      end if
    end do
    lam1 = s1 / (real(navg, dp) * hr)
    lam2 = s2 / (real(navg, dp) * hr)
    err = sqrt(sum((blk - sum(blk) / ly_nblock)**2) / real(ly_nblock - 1, dp)) / sqrt(real(ly_nblock, dp))
  end subroutine lyapunov_point

  !> Advance the 6-D state over [0, hr] with the model's clock at 0 and
  !> drive phase `phase`.  h: the step to try (0: choose one); on return the
  !> step the controller proposes next (not the one cut to reach hr).
  pure subroutine interval(p, phase, pphase, hr, rtol, atol, y, h, nsteps, status, uf, ut0)
    real(dp), intent(in) :: p(12), phase, pphase, hr, rtol, atol
    real(dp), intent(inout) :: y(6), h
    integer(i8), intent(inout) :: nsteps
    integer, intent(out) :: status
    type(pendulum_model), intent(in), optional :: uf
    real(dp), intent(in), optional :: ut0
    type(pendulum_model) :: md
    real(dp) :: t, f0(6), ynew(6), fnew(6), k(0:12, 6), err, fac, fac11, hnew, hprop
    logical :: last, reject
    real(dp), parameter :: safe = 0.9_dp, facc1 = 1.0_dp / 0.333_dp, facc2 = 1.0_dp / 6.0_dp, &
      expo1 = 1.0_dp / 8.0_dp
    md = point_model(p, phase, pphase, uf, ut0)
    t = 0.0_dp
    f0 = rhs(md, p, t, y)
    if (.not. (h > 0.0_dp)) h = initial_step(md, p, y, f0, hr, rtol, atol)
    h = min(h, hr)
    hprop = h
    reject = .false.
    status = st_ok
    do
      if (h <= 16.0_dp * epsilon(1.0_dp) * abs(t) .or. h <= 0.0_dp) then
        status = st_step_underflow; return
      end if
      if (nsteps >= max_steps) then
        status = st_too_many_steps; return
      end if
      last = .false.
      if (t + h >= hr) then
        hprop = h
        h = hr - t
        last = .true.
      end if
      call step853(md, p, t, y, f0, h, rtol, atol, k, ynew, fnew, err)
      nsteps = nsteps + 1
      if (.not. (err == err) .or. .not. all(abs(ynew) <= huge(1.0_dp))) then
        status = st_nonfinite; return
      end if
      fac11 = err**expo1
      fac = max(facc2, min(facc1, fac11 / safe))
      hnew = h / fac
      if (err <= 1.0_dp) then
        t = t + h
        y = ynew
        f0 = fnew
        if (reject) hnew = min(hnew, h)
        if (last) then
          ! a step cut to reach the interval's end says little about the next one
          h = max(hnew, hprop)
          if (reject) h = min(h, hprop)
          return
        end if
        reject = .false.
        h = hnew
      else
        hnew = h / min(facc1, fac11 / safe)
        reject = .true.
        h = hnew
      end if
    end do
  end subroutine interval

  !> The model of a sweep point p (eps, beta, tau, amp, omega, phase, theta0, v0, pivot amplitude and
  !> frequency, friction, drag) on a stretch whose clock starts where the drive's phase is phase and the pivot's pphase,
  !> with the user's force uf (if forced) on its clock from ut0.  The one map from a sweep point to its
  !> force law (the sweeps' windows and the Lyapunov intervals).
  pure function point_model(p, phase, pphase, uf, ut0) result(md)
    real(dp), intent(in) :: p(12), phase, pphase
    type(pendulum_model), intent(in), optional :: uf
    real(dp), intent(in), optional :: ut0
    type(pendulum_model) :: md
    md = make_model(p(1), p(2), p(3), p(4), p(5), phase)
    if (p(9) /= 0.0_dp .or. p(11) /= 0.0_dp .or. p(12) /= 0.0_dp) then
      md = add_effects(md, p(11), p(12), p(9), p(10))
      md%pphase = pphase
    end if
    if (present(uf)) then
      if (uf%forced) then
        md%forced = .true.; md%uforce => uf%uforce; md%uparams = uf%uparams; md%ut0 = ut0
      end if
    end if
  end function point_model

  !> The 6-D right-hand side (orbit and two tangent vectors): the integrators' system_rhs.
  pure function rhs(md, p, t, y) result(f)
    type(pendulum_model), intent(in) :: md
    real(dp), intent(in) :: p(12), t, y(6)
    real(dp) :: f(6)
    f = system_rhs(md, t, y)
  end function rhs

  !> One DOP853 step from (t, y) with f0 = f(t, y) (the integrators' n-dimensional
  !> stepper on the 6-D system): ynew, fnew = f(t + h, ynew) and Hairer's error norm.
  pure subroutine step853(md, p, t, y, f0, h, rtol, atol, k, ynew, fnew, errn)
    type(pendulum_model), intent(in) :: md
    real(dp), intent(in) :: p(12), t, y(6), f0(6), h, rtol, atol
    real(dp), intent(out) :: k(0:12, 6), ynew(6), fnew(6), errn
    real(dp) :: sk(6), e3(6), e5(6)
    call dop853_step_6(md, t, y, f0, h, k, ynew, fnew, e3, e5)
    ! (never 0: atol = 0 at the equilibrium theta = v = 0 must not divide 0 by 0)
    sk = max(atol + rtol * max(abs(y), abs(ynew)), tiny(1.0_dp))
    errn = dop853_error_norm(h, e3, e5, sk)
  end subroutine step853

  !> Hairer's starting step (order 8), at most hr.
  pure function initial_step(md, p, y, f0, hr, rtol, atol) result(h0)
    type(pendulum_model), intent(in) :: md
    real(dp), intent(in) :: p(12), y(6), f0(6), hr, rtol, atol
    real(dp) :: h0, sk(6), dnf, der2, f1(6)
    sk = max(atol + rtol * abs(y), tiny(1.0_dp))
    dnf = sum((f0 / sk)**2) / 6.0_dp
    h0 = start_step_euler(sum((y / sk)**2) / 6.0_dp, dnf, hr)
    f1 = rhs(md, p, h0, y + h0 * f0)
    der2 = sqrt(sum(((f1 - f0) / sk)**2) / 6.0_dp) / h0
    h0 = start_step_refined(h0, der2, dnf, 1.0_dp / 8.0_dp, hr)
  end function initial_step

end module pendula_lyapunov
