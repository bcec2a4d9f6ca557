!> Thermal noise: the Langevin equation of the pendulum at temperature T,
!>
!>   theta'' = F(theta, t) - beta theta' + sqrt(2 beta T) xi(t),
!>
!> F the position- and time-dependent force (field, torque, drive), xi unit
!> white noise, T in units of the energy scale eps (the Josephson energy of a
!> junction): the fluctuation-dissipation theorem ties the noise to the
!> damping, so the equilibrium density is exp(-(v^2/2 + U(theta)) / T).
!>
!> Integrator: BAOAB (Leimkuhler and Matthews, "Rational construction of
!> stochastic numerical methods for molecular sampling", Appl. Math. Res.
!> Express 2013, and their book "Molecular Dynamics", Springer 2015, section
!> 7.4): half kick B, half drift A, the exact Ornstein-Uhlenbeck step O
!> (v -> c v + sqrt(T (1 - c^2)) z, c = exp(-beta h)), half drift, half
!> kick.  Weak order 2 for averages (both of the configuration and of v^2),
!> stable at any damping (the friction is solved exactly).  Fixed step h.
!>
!> Noise: counter-based (kernel/base/pendula_rng.c): the normal number used
!> by step j of a path is a pure function of the path's key and j, and the
!> key of a path is a function of (seed, index) alone.  A path is therefore
!> the same bit for bit whichever thread runs it, whatever ran before it,
!> and however a sweep is chunked or resumed.
!>
!> No module variables: every path works on its own locals (OpenMP-safe).
module pendula_langevin
  use, intrinsic :: iso_c_binding, only: c_int64_t, c_int32_t, c_double
  use pendula_rng_iface, only: pendula_rng_key, pendula_rng_normals
  use, intrinsic :: iso_fortran_env, only: int64
  use pendula_kinds, only: dp, two_pi, pi, nan_dp
  use pendula_threads, only: thread_count
  use pendula_integrators, only: pendulum_model, accel, make_model
  use pendula_time_scales, only: n_scales, langevin_step_rate
  implicit none
  private
  public :: langevin_stream, langevin_open, langevin_steps, langevin_default_dt, langevin_path, &
            langevin_switching, langevin_moments, langevin_escape_times, langevin_max_steps

  integer, parameter, public :: lv_ok = 0, lv_bad_step = 1, lv_backward = 2, lv_too_many_steps = 3, &
    lv_cancelled = 4, lv_nonfinite = 5, lv_bad_argument = 6
  !> the most steps one path may take (as the fixed-step integrators' limit)
  integer(int64), parameter :: langevin_max_steps = 2000000000_int64
  !> normal numbers drawn per call of the generator
  integer, parameter :: nbuf = 512
  !> steps between two readings of the cancel flag
  integer(int64), parameter :: poll = 65536_int64

  !> One path's noise: its key, and a buffer of the next normal numbers
  !> (buf(pos) has index next - nbuf + pos - 1).
  type :: langevin_stream
    integer(c_int64_t) :: key = 0_c_int64_t, next = 0_c_int64_t
    real(dp) :: buf(nbuf) = 0.0_dp
    integer :: pos = nbuf + 1
  end type langevin_stream


contains

  !> The stream of path `index` of a run seeded with `seed` (both >= 0).
  function langevin_open(seed, index) result(s)
    integer(int64), intent(in) :: seed, index
    type(langevin_stream) :: s
    s%key = pendula_rng_key(int(seed, c_int64_t), int(index, c_int64_t))
    s%next = 0_c_int64_t
    s%pos = nbuf + 1
  end function langevin_open

  !> The next normal number of a stream.
  function next_normal(s) result(z)
    type(langevin_stream), intent(inout) :: s
    real(dp) :: z
    if (s%pos > nbuf) then
      call pendula_rng_normals(s%key, s%next, int(nbuf, c_int32_t), s%buf)
      s%next = s%next + nbuf
      s%pos = 1
    end if
    z = s%buf(s%pos)
    s%pos = s%pos + 1
  end function next_normal

  !> The step a noisy scene takes when it names none: 2 pi / 100 of the
  !> fastest of the time scales that bound BAOAB's step (pendula_time_scales:
  !> langevin_step_rate of the scene's rates: the small oscillation in its
  !> field, the drive, the pivot and the damping).  BAOAB's error in <v^2> is
  !> about (h omega)^2 / 4, 0.1 % at this step; beta h <= 0.063 keeps the
  !> stationary velocity under a torque within 0.04 % of tau / beta.
  pure function langevin_default_dt(rates) result(h)
    real(dp), intent(in) :: rates(n_scales)
    real(dp) :: h
    h = two_pi / max(langevin_step_rate(rates), tiny(1.0_dp))
    h = h / 100.0_dp
  end function langevin_default_dt

  !> n BAOAB steps of size h from time t0 (the drive's time), state (th, v).
  !> The model's damping m%beta is the friction; temp the temperature.
  !> status lv_cancelled when cancel is set (read every `poll` steps),
  !> lv_nonfinite when the state leaves the doubles.  sums (optional): v^2
  !> and cos(theta) after each step are added to sums(1), sums(2).
  subroutine langevin_steps(m, temp, s, t0, h, n, th, v, status, cancel, sums)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: temp, t0, h
    type(langevin_stream), intent(inout) :: s
    integer(int64), intent(in) :: n
    real(dp), intent(inout) :: th, v
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    real(dp), intent(inout), optional :: sums(2)
    real(dp) :: c1, c2, hh, t
    integer(int64) :: j
    status = lv_ok
    c1 = exp(-m%beta * h)
    ! sqrt(T (1 - c1^2)), 1 - c1^2 without cancellation at small beta h
    c2 = sqrt(temp * (-expm1_dp(-2.0_dp * m%beta * h)))
    hh = 0.5_dp * h
    do j = 0, n - 1
      if (mod(j + 1, poll) == 0) then
        if (cancel /= 0) then
          status = lv_cancelled; return
        end if
      end if
      t = t0 + real(j, dp) * h
      v = v + hh * force_at(t, th)
      th = th + hh * v
      v = c1 * v + c2 * next_normal(s)
      th = th + hh * v
      v = v + hh * force_at(t + h, th)
      if (present(sums)) then
        sums(1) = sums(1) + v * v; sums(2) = sums(2) + cos(th)
      end if
    end do
    if (.not. (abs(th) <= huge(1.0_dp) .and. abs(v) <= huge(1.0_dp))) status = lv_nonfinite
  contains
    pure real(dp) function force_at(tt, x)
      real(dp), intent(in) :: tt, x
      ! accel at v = 0: the field, torque and drive without the friction
      force_at = accel(m, tt, x, 0.0_dp)
    end function force_at
  end subroutine langevin_steps

  !> exp(x) - 1 without cancellation for small |x| (x <= 0 here).
  elemental real(dp) function expm1_dp(x)
    real(dp), intent(in) :: x
    if (abs(x) < 1.0e-5_dp) then
      expm1_dp = x * (1.0_dp + x * (0.5_dp + x / 6.0_dp))
    else
      expm1_dp = exp(x) - 1.0_dp
    end if
  end function expm1_dp

  !> A noisy path sampled at the times t (ascending, >= 0) from (th0, v0) at
  !> time 0.  Between two samples t_k, t_k+1 it takes n = ceil((t_k+1 - t_k) / dt)
  !> equal steps h = (t_k+1 - t_k) / n <= dt (the step is dt where the samples
  !> are dt apart).  status lv_*.
  subroutine langevin_path(m, temp, seed, dt, th0, v0, t, theta, v, nsteps, status, cancel)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: temp, dt, th0, v0, t(:)
    integer(int64), intent(in) :: seed
    real(dp), intent(out) :: theta(:), v(:)
    integer(int64), intent(out) :: nsteps
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    type(langevin_stream) :: s
    real(dp) :: th, vv, tp, x
    integer(int64) :: n
    integer :: k
    theta = nan_dp; v = nan_dp; nsteps = 0
    if (.not. (dt > 0.0_dp)) then
      status = lv_bad_step; return
    end if
    if (size(t) == 0) then
      status = lv_ok; return
    end if
    if (.not. all(abs(t) <= huge(1.0_dp))) then
      status = lv_bad_argument; return
    end if
    if (t(1) < 0.0_dp) then
      status = lv_backward; return
    end if
    if (size(t) > 1) then
      if (any(t(2:) < t(:size(t) - 1))) then
        status = lv_bad_argument; return
      end if
    end if
    if (.not. (t(size(t)) / dt + real(size(t), dp) <= real(langevin_max_steps, dp))) then
      status = lv_too_many_steps; return
    end if
    s = langevin_open(seed, 0_int64)
    th = th0; vv = v0; tp = 0.0_dp
    do k = 1, size(t)
      x = t(k) - tp
      n = ceiling(x / dt - 1.0e-12_dp, int64)
      if (x > 0.0_dp) n = max(1_int64, n)
      if (n > 0) then
        call langevin_steps(m, temp, s, tp, x / real(n, dp), n, th, vv, status, cancel)
        if (status /= lv_ok) return
        nsteps = nsteps + n
      end if
      theta(k) = th; v(k) = vv; tp = t(k)
    end do
    status = lv_ok
  end subroutine langevin_path

  !> Equilibrium averages for the checks: from (theta, v) = (0, 0), a burn-in
  !> of nburn steps of h, then nbatch batches of nper steps each; the batch
  !> means of v^2 and cos(theta) after every step.  Path `index` of `seed`.
  subroutine langevin_moments(m, temp, seed, index, h, nburn, nbatch, nper, v2, cth, status, cancel)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: temp, h
    integer(int64), intent(in) :: seed, index, nburn, nper
    integer, intent(in) :: nbatch
    real(dp), intent(out) :: v2(nbatch), cth(nbatch)
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    type(langevin_stream) :: s
    real(dp) :: th, v, acc(2)
    integer(int64) :: step
    integer :: k
    v2 = nan_dp; cth = nan_dp
    s = langevin_open(seed, index)
    th = 0.0_dp; v = 0.0_dp
    call langevin_steps(m, temp, s, 0.0_dp, h, nburn, th, v, status, cancel)
    if (status /= lv_ok) return
    step = nburn
    do k = 1, nbatch
      acc = 0.0_dp
      call langevin_steps(m, temp, s, real(step, dp) * h, h, nper, th, v, status, cancel, acc)
      if (status /= lv_ok) return
      step = step + nper
      v2(k) = acc(1) / real(nper, dp); cth(k) = acc(2) / real(nper, dp)
    end do
  end subroutine langevin_moments

  !> First-passage times out of a tilted well: n paths (path i has stream
  !> (seed, i - 1)), each from the well's bottom asin(tau / eps) with v drawn
  !> from the Maxwell distribution at temp, run until theta >= theta_exit
  !> (times(i)) or t_max (times(i) = NaN).  OpenMP over the paths.
  subroutine langevin_escape_times(m, temp, seed, h, theta_exit, t_max, n, times, status, nthreads, cancel)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: temp, h, theta_exit, t_max
    integer(int64), intent(in) :: seed
    integer, intent(in) :: n, nthreads
    real(dp), intent(out) :: times(n)
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    integer :: i, nt, st
    integer(int64) :: j, jmax
    real(dp) :: th, v
    type(langevin_stream) :: s
    status = lv_ok
    nt = thread_count(nthreads)
    jmax = int(min(t_max / h, real(langevin_max_steps, dp)), int64)
    !$omp parallel do schedule(dynamic, 1) default(none) num_threads(nt) &
    !$omp   shared(m, temp, seed, h, theta_exit, n, times, cancel, jmax, status) private(i, th, v, s, j, st)
    do i = 1, n
      times(i) = nan_dp
      if (cancel /= 0) cycle
      s = langevin_open(seed, int(i - 1, int64))
      th = asin(m%tau / m%eps); v = sqrt(temp) * next_normal(s)
      j = 0
      do while (j < jmax)
        ! one step at a time (the exit is read after each); the stream s is this thread's
        ! private copy, so it is passed, never reached by host association
        call langevin_steps(m, temp, s, real(j, dp) * h, h, 1_int64, th, v, st, cancel)
        j = j + 1
        if (st /= lv_ok) exit
        if (th >= theta_exit) then
          times(i) = real(j, dp) * h; exit
        end if
        if (mod(j, poll) == 0 .and. cancel /= 0) exit   ! the cancel flag, once per `poll` steps
      end do
    end do
    !$omp end parallel do
    if (cancel /= 0) status = lv_cancelled
  end subroutine langevin_escape_times

  !> Switching currents of a current-biased junction (eps = 1, reduced
  !> units): n paths (path i: stream (seed, i - 1)), each starting in
  !> thermal equilibrium of the untilted well (theta, v drawn from the
  !> Gaussian of the harmonic well at temp: exact to O(temp^2)), the bias
  !> ramped as i(t) = rate t.  A path has switched when theta passes the
  !> second barrier (3 pi - asin(i), two wells on: a retrapped phase slip
  !> does not count); its switching bias is i at the last upward crossing
  !> of the first barrier's top (pi - asin(i), at each step's bias) before that.  isw(i) = NaN
  !> when a path has not switched by i = i_max.  OpenMP over the paths.
  subroutine langevin_switching(beta, temp, rate, seed, h, i_max, n, isw, status, nthreads, cancel)
    real(dp), intent(in) :: beta, temp, rate, h, i_max
    integer(int64), intent(in) :: seed
    integer, intent(in) :: n, nthreads
    real(dp), intent(out) :: isw(n)
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    integer :: i, nt, st
    integer(int64) :: j, jmax
    real(dp) :: th, v, t, bias, top, cross
    logical :: below
    type(langevin_stream) :: s
    type(pendulum_model) :: m
    status = lv_ok
    if (.not. (rate > 0.0_dp .and. h > 0.0_dp .and. temp >= 0.0_dp .and. beta > 0.0_dp)) then
      status = lv_bad_argument; isw = nan_dp; return
    end if
    nt = thread_count(nthreads)
    jmax = int(min(i_max / rate / h, real(langevin_max_steps, dp)), int64)
    !$omp parallel do schedule(dynamic, 1) default(none) num_threads(nt) &
    !$omp   shared(beta, temp, rate, seed, h, n, isw, cancel, jmax) &
    !$omp   private(i, th, v, s, j, st, t, bias, top, cross, m, below)
    do i = 1, n
      isw(i) = nan_dp
      if (cancel /= 0) cycle
      s = langevin_open(seed, int(i - 1, int64))
      th = sqrt(temp) * next_normal(s); v = sqrt(temp) * next_normal(s)
      cross = nan_dp; below = .true.
      j = 0
      do while (j < jmax)
        t = real(j, dp) * h
        ! the bias of this step: the ramp at its midpoint (a constant torque per step)
        bias = rate * (t + 0.5_dp * h)
        m = make_model(1.0_dp, beta, bias, 0.0_dp, 0.0_dp, 0.0_dp)
        call langevin_steps(m, temp, s, t, h, 1_int64, th, v, st, cancel)
        j = j + 1
        if (st /= lv_ok) exit
        ! below the top at this step's bias (the top moves down with the ramp: a crossing may be its move)
        top = pi - asin(min(bias, 1.0_dp))
        if (below .and. th >= top) cross = bias
        below = th < top
        if (th >= 3.0_dp * pi - asin(min(bias, 1.0_dp))) then
          isw(i) = cross; exit
        end if
        if (mod(j, poll) == 0 .and. cancel /= 0) exit
      end do
    end do
    !$omp end parallel do
    if (cancel /= 0) status = lv_cancelled
  end subroutine langevin_switching

end module pendula_langevin
