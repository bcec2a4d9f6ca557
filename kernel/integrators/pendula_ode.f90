!> The n-dimensional integrator core: any system y' = f(t, y) with a state
!> of n numbers, given as a type that extends ode_system and supplies its
!> right-hand side as a type-bound procedure (the context travels in the
!> type: a network's couplings, a double pendulum's lengths).
!>
!> Three integrators, each one routine for every system:
!>
!> * ode_dop853: Hairer's DOP853 (8(5,3), the tables of
!>   pendula_rk_tables.inc), Gustafsson's PI step control in Hairer's form
!>   with the PI term and limits of the one-phase integrator (beta = 0.06),
!>   Hairer's starting step and error norm, and output at the requested times
!>   from the 7th-order dense output (three extra stages, formed only on a
!>   step that holds an output time).  Steps are never shortened to hit an
!>   output.
!> * ode_gauss: Gauss-Legendre collocation with 2 or 3 stages (orders 4, 6):
!>   symplectic for a Hamiltonian system, so the energy error stays bounded
!>   over long spans.  The stages in the mu form (mu_ij + mu_ji = 1 exactly,
!>   pendula_rk_tables.inc), solved by fixed-point iteration until the
!>   increments stop decreasing, the increments added with compensated
!>   (Kahan) summation.  Fixed step h; outputs on the step grid.
!> * ode_baoab: BAOAB (Leimkuhler and Matthews, "Molecular Dynamics",
!>   Springer 2015, section 7.4) for a mechanical_system q'' = a(t, q) -
!>   gamma v + noise, with a temperature per element: the exact
!>   Ornstein-Uhlenbeck step v_i -> c_i v_i + sqrt(s2_i (1 - c_i^2)) z_i,
!>   c_i = exp(-gamma_i h), s2_i the element's equilibrium variance of v_i.
!>   One counter-based noise stream per element keyed by (seed, point,
!>   element) (kernel/base/pendula_rng.c): a path is the same bit for bit
!>   whichever thread runs it and whatever ran before.
!>
!> The conventions of the one-phase integrators (pendula_integrators): the
!> status codes st_*, the work limits max_steps (adaptive) and
!> max_fixed_steps (fixed step), the cancel flag read every poll_every steps.
!> No module variables: every call works on its own locals (OpenMP-safe).
module pendula_ode
  use, intrinsic :: iso_c_binding, only: c_int64_t, c_int32_t, c_double
  use pendula_rng_iface, only: pendula_rng_key, pendula_rng_normals
  use pendula_kinds, only: dp, i8, nan_dp
  use pendula_integrators, only: kahan_add, step_guard, cancel_polled, gauss_iteration_done, &
    run_stats, dop853_error_norm, max_steps, &
    max_fixed_steps, pi_controller, pi_step_factor, m_dop853, &
    st_ok, st_bad_step, st_bad_tol, st_bad_method, st_step_underflow, st_nonfinite, st_too_many_steps, &
    st_cancelled, start_step_euler, start_step_refined
  use pendula_rk_coefficients, only: d8_a, d8_b, d8_c, d8_d, d8_e3, d8_e5, g2_mu, g2_b, g2_c, g3_mu, g3_b, g3_c
  implicit none
  private
  public :: ode_system, mechanical_system, ode_dop853, ode_gauss, ode_baoab, ode_noise_key

  !> DOP853's A and dense-output D transposed: each stage's weights contiguous
  real(dp), parameter :: d8_at(0:15, 0:15) = transpose(d8_a), d8_dt(0:15, 0:3) = transpose(d8_d)

  !> status: output times not ascending, or before the start time
  integer, parameter, public :: ode_st_bad_times = 20
  !> status: a noisy element without friction (gamma_i = 0 with s2_i > 0)
  integer, parameter, public :: ode_st_undamped_noise = 21
  !> the methods of ode_gauss: stages 2 (order 4) or 3 (order 6)
  integer, parameter, public :: ode_gauss4 = 2, ode_gauss6 = 3

  !> A system y' = f(t, y) of n equations.
  type, abstract :: ode_system
    integer :: n = 0
  contains
    procedure(rhs_fn), deferred :: rhs
  end type ode_system

  !> A mechanical system of m = n/2 elements, y = (q(1:m), v(1:m)):
  !>   q' = v,  v' = a(t, q) - gamma v  (+ noise in ode_baoab),
  !> a its position- and time-dependent acceleration, gamma(m) >= 0 the
  !> friction rate of each element.
  type, abstract, extends(ode_system) :: mechanical_system
    real(dp), allocatable :: gamma(:)
  contains
    procedure(accel_fn), deferred :: accel
    procedure :: rhs => mechanical_rhs
  end type mechanical_system

  abstract interface
    pure subroutine rhs_fn(self, t, y, f)
      import :: ode_system, dp
      class(ode_system), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: f(:)
    end subroutine rhs_fn
    pure subroutine accel_fn(self, t, q, a)
      import :: mechanical_system, dp
      class(mechanical_system), intent(in) :: self
      real(dp), intent(in) :: t, q(:)
      real(dp), intent(out) :: a(:)
    end subroutine accel_fn
  end interface


contains

  pure subroutine mechanical_rhs(self, t, y, f)
    class(mechanical_system), intent(in) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: f(:)
    integer :: m
    m = self%n / 2
    f(1:m) = y(m + 1:2 * m)
    call self%accel(t, y(1:m), f(m + 1:2 * m))
    f(m + 1:2 * m) = f(m + 1:2 * m) - self%gamma * y(m + 1:2 * m)
  end subroutine mechanical_rhs

  !> The key of the noise stream of element `element` (0-based) of path
  !> `point` of a run seeded with `seed`: SplitMix64's key of the element's
  !> index under the key of (seed, point).
  function ode_noise_key(seed, point, element) result(key)
    integer(i8), intent(in) :: seed, point, element
    integer(c_int64_t) :: key
    key = pendula_rng_key(pendula_rng_key(int(seed, c_int64_t), int(point, c_int64_t)), &
                          int(element, c_int64_t))
  end function ode_noise_key

  !> out = base + sum_j (h c(j)) k(:, j) over the nonzero c(j), j = 0 .. nc - 1, in that order, over
  !> blocks of the state that stay in the first-level cache (one pass over memory instead of one per
  !> stage: a chain of 4096 spends its time here otherwise).  base may be absent (then 0).
  pure subroutine combine(n, h, c, nc, k, out, base)
    integer, intent(in) :: n, nc
    real(dp), intent(in) :: h, c(0:), k(:, 0:)
    real(dp), intent(out) :: out(n)
    real(dp), intent(in), optional :: base(n)
    integer, parameter :: blk = 256
    integer :: i0, i1, j
    do i0 = 1, n, blk
      i1 = min(n, i0 + blk - 1)
      if (present(base)) then
        out(i0:i1) = base(i0:i1)
      else
        out(i0:i1) = 0.0_dp
      end if
      do j = 0, nc - 1
        if (c(j) /= 0.0_dp) out(i0:i1) = out(i0:i1) + (h * c(j)) * k(i0:i1, j)
      end do
    end do
  end subroutine combine

  !> True when the output times are ascending and none is before t0.
  pure logical function times_ok(t0, tout)
    real(dp), intent(in) :: t0, tout(:)
    integer :: k
    times_ok = .true.
    do k = 1, size(tout)
      if (.not. (tout(k) >= t0)) times_ok = .false.
      if (k > 1) then
        if (.not. (tout(k) >= tout(k - 1))) times_ok = .false.
      end if
    end do
  end function times_ok

  !> The fixed-step drivers' check of their grid: st_bad_step unless 0 < h < inf, ode_st_bad_times
  !> for a negative count of steps, else st_ok.
  pure integer function fixed_grid_status(h, counts) result(st)
    real(dp), intent(in) :: h
    integer(i8), intent(in) :: counts(:)
    st = st_ok
    if (.not. (h > 0.0_dp .and. h <= huge(h))) then
      st = st_bad_step
    else if (any(counts < 0_i8)) then
      st = ode_st_bad_times
    end if
  end function fixed_grid_status

  ! ====================================================================
  ! DOP853 with dense output
  ! ====================================================================

  !> Integrate sys from y0 at t0 with DOP853 to the times tout (ascending,
  !> >= t0); yout(:, k) the state at tout(k) (NaN after a failure).  rtol > 0,
  !> atol >= 0: the tolerance of each component, atol + rtol |y|.
  !> status st_ok, st_bad_tol, ode_st_bad_times, st_step_underflow,
  !> st_nonfinite, st_too_many_steps or st_cancelled (cancel set non-zero by
  !> another thread, read every poll_every steps).
  subroutine ode_dop853(sys, t0, y0, tout, rtol, atol, yout, stats, status, cancel)
    class(ode_system), intent(in) :: sys
    real(dp), intent(in) :: t0, y0(:), tout(:), rtol, atol
    real(dp), intent(out) :: yout(:, :)
    type(run_stats), intent(out) :: stats
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    real(dp), allocatable :: k(:, :), y(:), ynew(:), f0(:), fnew(:), ys(:), e3(:), e5(:), sk(:), cont(:, :)
    real(dp) :: t, tnew, h, err, hnew, fac, fac11, facold, tend, expo1, beta, facc1, facc2, safe, x
    integer :: n, kout, s
    logical :: last, reject

    n = sys%n
    yout = nan_dp
    status = st_ok
    if (.not. (rtol > 0.0_dp .and. atol >= 0.0_dp)) then
      status = st_bad_tol; return
    end if
    if (.not. times_ok(t0, tout)) then
      status = ode_st_bad_times; return
    end if
    if (size(tout) == 0) return
    allocate(k(n, 0:15), y(n), ynew(n), f0(n), fnew(n), ys(n), e3(n), e5(n), sk(n), cont(n, 0:6))
    call pi_controller(m_dop853, -1.0_dp, expo1, beta, facc1, facc2, safe)   ! the one-phase DOP853's
    facold = 1.0e-4_dp
    tend = tout(size(tout))
    t = t0
    y = y0
    kout = 1
    do while (kout <= size(tout))
      if (tout(kout) /= t0) exit
      yout(:, kout) = y
      kout = kout + 1
    end do
    if (kout > size(tout)) return
    call sys%rhs(t, y, f0)
    stats%nfev = 1
    h = initial_step()
    reject = .false.
    last = .false.
    do
      status = step_guard(h, t, stats%nsteps, cancel)
      if (status /= st_ok) exit
      if (t + h >= tend) then
        h = tend - t
        last = .true.
      end if
      call step()
      stats%nsteps = stats%nsteps + 1
      err = dop853_error_norm(h, e3, e5, sk)
      if (.not. (err == err) .or. .not. all(abs(ynew) <= huge(1.0_dp))) then
        status = st_nonfinite; exit
      end if
      call pi_step_factor(err, expo1, beta, facold, safe, facc1, facc2, fac11, fac)
      hnew = h / fac
      if (err <= 1.0_dp) then
        facold = max(err, 1.0e-4_dp)
        stats%naccept = stats%naccept + 1
        tnew = t + h
        if (last) tnew = tend
        if (tout(kout) < tnew) call dense_coefficients()
        do while (kout <= size(tout))
          if (tout(kout) > tnew) exit
          if (tout(kout) == tnew) then
            yout(:, kout) = ynew
          else
            x = (tout(kout) - t) / h
            call dense(x, yout(:, kout))
          end if
          kout = kout + 1
        end do
        t = tnew
        y = ynew
        f0 = fnew
        if (kout > size(tout)) exit
        last = .false.
        if (abs(hnew) > abs(h) .and. reject) hnew = h
        reject = .false.
        h = hnew
      else
        stats%nreject = stats%nreject + 1
        h = h / min(facc1, fac11 / safe)
        reject = .true.
        last = .false.
      end if
    end do
    if (status /= st_ok) yout(:, kout:) = nan_dp

  contains

    !> Hairer's starting step: balance an explicit Euler step against f's change.
    function initial_step() result(h0)
      real(dp) :: h0, dnf, der2
      sk = atol + rtol * abs(y)
      dnf = sum((f0 / sk)**2)
      h0 = start_step_euler(sum((y / sk)**2), dnf, tend - t0)
      ys = y + h0 * f0
      call sys%rhs(t0 + h0, ys, fnew)
      stats%nfev = stats%nfev + 1
      der2 = sqrt(sum(((fnew - f0) / sk)**2)) / h0
      h0 = start_step_refined(h0, der2, dnf, 1.0_dp / 8.0_dp, tend - t0)
    end function initial_step

    !> One step of size h: the stages, ynew, fnew, the error estimates and scale.
    subroutine step()
      k(:, 0) = f0
      do s = 1, 11
        call combine(n, h, d8_at(:, s), s, k, ys, y)
        call sys%rhs(t + d8_c(s) * h, ys, k(:, s))
      end do
      call combine(n, h, d8_b, 12, k, ynew, y)
      call sys%rhs(t + h, ynew, fnew)
      k(:, 12) = fnew
      stats%nfev = stats%nfev + 12
      call combine(n, 1.0_dp, d8_e3, 13, k, e3)
      call combine(n, 1.0_dp, d8_e5, 13, k, e5)
      sk = atol + rtol * max(abs(y), abs(ynew))
    end subroutine step

    !> Hairer's 7th-order dense output on the accepted step [t, t + h].
    subroutine dense_coefficients()
      do s = 13, 15
        call combine(n, h, d8_at(:, s), s, k, ys, y)
        call sys%rhs(t + d8_c(s) * h, ys, k(:, s))
      end do
      stats%nfev = stats%nfev + 3
      cont(:, 0) = ynew - y
      cont(:, 1) = h * k(:, 0) - cont(:, 0)
      cont(:, 2) = 2.0_dp * cont(:, 0) - h * (k(:, 0) + k(:, 12))
      do s = 0, 3
        call combine(n, 1.0_dp, d8_dt(:, s), 16, k, ys)
        cont(:, 3 + s) = h * ys
      end do
    end subroutine dense_coefficients

    !> The state at t + xx h, 0 <= xx < 1 (Hairer's CONTD8).
    subroutine dense(xx, yo)
      real(dp), intent(in) :: xx
      real(dp), intent(out) :: yo(:)
      real(dp) :: xm
      xm = 1.0_dp - xx
      yo = cont(:, 0) + xm * (cont(:, 1) + xx * (cont(:, 2) + xm * (cont(:, 3) + xx * (cont(:, 4) &
           + xm * (cont(:, 5) + xx * cont(:, 6))))))
      yo = y + xx * yo
    end subroutine dense

  end subroutine ode_dop853

  ! ====================================================================
  ! Gauss-Legendre collocation (symplectic)
  ! ====================================================================

  !> Integrate sys from y0 at t0 with fixed steps h by the Gauss-Legendre
  !> method of `stages` stages (ode_gauss4 or ode_gauss6) and record the
  !> state after counts(k) more steps into yout(:, k) (counts >= 0: the
  !> outputs lie on the step grid, t0 + h * sum(counts(1:k))).  status st_ok,
  !> st_bad_step (h not > 0), st_bad_method, st_too_many_steps (the total
  !> above max_fixed_steps), st_nonfinite or st_cancelled.
  subroutine ode_gauss(sys, stages, t0, y0, h, counts, yout, stats, status, cancel)
    class(ode_system), intent(in) :: sys
    integer, intent(in) :: stages
    real(dp), intent(in) :: t0, y0(:), h
    integer(i8), intent(in) :: counts(:)
    real(dp), intent(out) :: yout(:, :)
    type(run_stats), intent(out) :: stats
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    real(dp), allocatable :: y(:), ye(:), el(:, :), eln(:, :), ys(:), z(:)
    real(dp) :: mu(3, 3), b(3), c(3), d, dold, t
    integer(i8) :: istep, j
    integer :: n, s, it, i, jj, kout

    n = sys%n
    yout = nan_dp
    status = st_ok
    s = stages
    select case (s)
    case (ode_gauss4)
      mu(1:2, 1:2) = g2_mu; b(1:2) = g2_b; c(1:2) = g2_c
    case (ode_gauss6)
      mu = g3_mu; b = g3_b; c = g3_c
    case default
      status = st_bad_method; return
    end select
    status = fixed_grid_status(h, counts)
    if (status /= st_ok) return
    if (sum(real(counts, dp)) > real(max_fixed_steps, dp)) then
      status = st_too_many_steps; return
    end if
    allocate(y(n), ye(n), el(n, s), eln(n, s), ys(n), z(n))
    y = y0; ye = 0.0_dp
    istep = 0
    do kout = 1, size(counts)
      do j = 1, counts(kout)
        if (cancel_polled(istep, cancel)) then
          status = st_cancelled; return
        end if
        t = t0 + real(istep, dp) * h
        el = 0.0_dp
        dold = huge(1.0_dp)
        do it = 1, 60
          do i = 1, s
            ys = y
            do jj = 1, s
              ys = ys + mu(i, jj) * el(:, jj)
            end do
            call sys%rhs(t + c(i) * h, ys, eln(:, i))
            eln(:, i) = (h * b(i)) * eln(:, i)
          end do
          stats%nfev = stats%nfev + s
          d = maxval(abs(eln - el))
          el = eln
          if (gauss_iteration_done(it, d, dold, maxval(abs(eln)) + maxval(abs(y)))) exit
          dold = d
        end do
        z = el(:, 1)
        do i = 2, s
          z = z + el(:, i)
        end do
        call kahan_add(y, ye, z)
        istep = istep + 1
        stats%nsteps = istep
        stats%naccept = istep
        if (.not. all(abs(y) <= huge(1.0_dp))) then
          status = st_nonfinite; return
        end if
      end do
      yout(:, kout) = y
    end do
  end subroutine ode_gauss

  ! ====================================================================
  ! BAOAB: Langevin dynamics of a mechanical system
  ! ====================================================================

  !> Integrate the mechanical system sys with thermal noise by BAOAB steps
  !> of size h from (q, v) = y0 at t0; yout(:, k) the state after counts(k)
  !> more steps.  s2(m): the equilibrium variance of each element's velocity
  !> (temperature over mass; 0: no noise on that element; an element with
  !> noise must have friction, gamma > 0).  Element i draws its normal numbers from the
  !> stream ode_noise_key(seed, point, i - 1), number j for step j.
  !> status st_ok, st_bad_step, ode_st_bad_times (a negative count),
  !> ode_st_undamped_noise, st_too_many_steps, st_nonfinite or st_cancelled.
  subroutine ode_baoab(sys, s2, seed, point, t0, y0, h, counts, yout, status, cancel)
    class(mechanical_system), intent(in) :: sys
    real(dp), intent(in) :: s2(:), t0, y0(:), h
    integer(i8), intent(in) :: seed, point
    integer(i8), intent(in) :: counts(:)
    real(dp), intent(out) :: yout(:, :)
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    integer, parameter :: nbuf = 64
    real(dp), allocatable :: q(:), v(:), a(:), c1(:), c2(:), z(:, :)
    integer(c_int64_t), allocatable :: key(:)
    real(dp) :: hh, t
    integer(i8) :: istep, j
    integer :: m, i, kout, pos

    m = sys%n / 2
    yout = nan_dp
    status = st_ok
    status = fixed_grid_status(h, counts)
    if (status /= st_ok) return
    if (any(s2 > 0.0_dp .and. .not. (sys%gamma > 0.0_dp))) then
      status = ode_st_undamped_noise; return
    end if
    if (sum(real(counts, dp)) > real(max_fixed_steps, dp)) then
      status = st_too_many_steps; return
    end if
    allocate(q(m), v(m), a(m), c1(m), c2(m), key(m), z(nbuf, m))
    hh = 0.5_dp * h
    c1 = exp(-sys%gamma * h)
    c2 = sqrt(max(s2, 0.0_dp) * (1.0_dp - c1**2))
    do i = 1, m
      key(i) = ode_noise_key(seed, point, int(i - 1, i8))
    end do
    q = y0(1:m); v = y0(m + 1:2 * m)
    t = t0
    call sys%accel(t, q, a)
    istep = 0
    pos = nbuf + 1
    do kout = 1, size(counts)
      do j = 1, counts(kout)
        if (cancel_polled(istep, cancel)) then
          status = st_cancelled; return
        end if
        if (pos > nbuf) then
          do i = 1, m
            if (c2(i) > 0.0_dp) call pendula_rng_normals(key(i), int(istep, c_int64_t), &
                                                         int(nbuf, c_int32_t), z(:, i))
          end do
          pos = 1
        end if
        v = v + hh * a
        q = q + hh * v
        do i = 1, m
          if (c2(i) > 0.0_dp) then
            v(i) = c1(i) * v(i) + c2(i) * z(pos, i)
          else
            v(i) = c1(i) * v(i)
          end if
        end do
        q = q + hh * v
        istep = istep + 1
        t = t0 + real(istep, dp) * h
        call sys%accel(t, q, a)
        v = v + hh * a
        pos = pos + 1
        if (.not. (all(abs(q) <= huge(1.0_dp)) .and. all(abs(v) <= huge(1.0_dp)))) then
          status = st_nonfinite; return
        end if
      end do
      yout(1:m, kout) = q
      yout(m + 1:2 * m, kout) = v
    end do
  end subroutine ode_baoab

end module pendula_ode
