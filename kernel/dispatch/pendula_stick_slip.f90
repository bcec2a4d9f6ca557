!> Friction and drag: the integrator between the switches at v = 0.
!>
!> Dry friction -mu sgn(v) jumps where v = 0 and quadratic drag -gamma v |v|
!> has a jump in its second derivative there; neither is smoothed.  Between
!> two zeros of v the sign s of v is known, the force law is smooth
!> (-mu s, -gamma s v^2: pendula_integrators' vsign) and the scene's adaptive
!> method (dopri5, dop853) integrates it up to the terminal event v = 0,
!> located on its dense output to the integrator's precision (as the cord's
!> tension event, pendula_cord_hybrid).  At an event (or at rest at t = 0):
!>   F = theta'' without friction at v = 0 (gravity, torque, drive, pivot, the
!>   user's force);
!>   |F| <= mu: the bob sticks (static = kinetic coefficient); it stays at rest
!>   until |F(t, theta)| > mu, a time found by sampling F and refining with
!>   GSL's Brent method; with no time-dependent force it sticks for good;
!>   otherwise: a new stretch with s = sgn(F).
!> Each stretch restarts the integrator at local time 0: the drive's and the
!> pivot's phases and the user force's time origin carry the elapsed time.
!> No module state.
module pendula_stick_slip
  use, intrinsic :: iso_c_binding, only: c_double, c_ptr, c_funloc, c_loc, c_f_pointer
  use pendula_kinds, only: dp, i8, nan_dp, two_pi
  use pendula_integrators, only: pendulum_model, free_accel, event_spec, run_stats, integrate, st_ok, &
    st_stopped, st_too_many_steps, st_cancelled, max_steps
  use pendula_friction, only: gsl_root
  implicit none
  private
  public :: stick_slip_run, switched

  !> status beyond the integrators' st_*: output times before 0, the release not located
  integer, parameter, public :: ss_backward = 101, ss_release_failed = 102
  !> samples of the force per period of its fastest time dependence, looking for a release
  integer, parameter :: release_samples = 64
  integer(i8), parameter :: release_poll = 65536_i8

  !> the stuck bob's context for the release root (|F(t, theta)| - mu)
  type :: stuck_t
    type(pendulum_model) :: m
    real(dp) :: th = 0.0_dp
  end type stuck_t

contains

  !> Does the model switch at v = 0 (friction or drag)?
  pure logical function switched(m)
    type(pendulum_model), intent(in) :: m
    switched = m%rubbed .or. m%dragged
  end function switched

  !> Integrate the switching model m from (theta0, v0) at t = 0 to the ascending times t >= 0 by
  !> method (dopri5 or dop853): theta, v; stats [steps, accepted, rejected, rhs evaluations];
  !> nswitch: the events (stops, turns, restarts); status st_ok or the integrators' st_*,
  !> ss_backward, ss_release_failed.
  subroutine stick_slip_run(m, method, theta0, v0, t, rtol, atol, theta, v, stats, nswitch, status, cancel)
    type(pendulum_model), intent(in) :: m
    integer, intent(in) :: method
    real(dp), intent(in) :: theta0, v0, t(:), rtol, atol
    real(dp), intent(out) :: theta(:), v(:), stats(4)
    integer(i8), intent(out) :: nswitch
    integer, intent(out) :: status
    integer, intent(inout), volatile, optional :: cancel
    type(pendulum_model) :: ms
    type(event_spec) :: ev
    type(run_stats) :: rs
    real(dp) :: tc, th, vv, f, tr, tev(1), thev(1), vev(1)
    real(dp), allocatable :: ts(:)
    integer :: n, k, nev, kk
    integer, volatile :: no_cancel
    no_cancel = 0
    n = size(t)
    theta = nan_dp; v = nan_dp; stats = 0.0_dp; nswitch = 0; status = st_ok
    if (n == 0) return
    if (t(1) < 0.0_dp) then
      status = ss_backward; return
    end if
    ev%kind = 1; ev%terminal = .true.; ev%direction = 0
    tc = 0.0_dp; th = theta0; vv = v0; k = 1
    do while (k <= n)
      ms = m
      if (vv == 0.0_dp) then
        f = free_accel(m, tc, th, 0.0_dp)
        if (m%rubbed .and. abs(f) <= m%mu) then
          ! stuck: at rest until the force overcomes the friction
          if (present(cancel)) then
            call release_time(m, th, tc, t(n), tr, status, cancel)
          else
            call release_time(m, th, tc, t(n), tr, status, no_cancel)
          end if
          if (status /= st_ok) return
          do while (k <= n)
            if (t(k) > tr) exit
            theta(k) = th; v(k) = 0.0_dp; k = k + 1
          end do
          if (k > n) exit
          tc = tr
          f = free_accel(m, tc, th, 0.0_dp)
        end if
        ms%vsign = sign(1.0_dp, f)
        if (f == 0.0_dp) ms%vsign = 0.0_dp   ! at rest at an equilibrium of a drag-only model
      else
        ms%vsign = sign(1.0_dp, vv)
      end if
      ! the stretch from tc: the time-dependent terms carry the elapsed time
      ms%phase = m%phase + m%omega * tc
      ms%pphase = m%pphase + m%pomega * tc
      ms%ut0 = m%ut0 + tc
      ts = t(k:n) - tc
      if (present(cancel)) then
        call integrate(ms, method, th, vv, ts, rtol, atol, 0.0_dp, theta(k:n), v(k:n), rs, status, ev, nev, &
                       tev, thev, vev, cancel)
      else
        call integrate(ms, method, th, vv, ts, rtol, atol, 0.0_dp, theta(k:n), v(k:n), rs, status, ev, nev, &
                       tev, thev, vev, no_cancel)
      end if
      stats = stats + [real(rs%nsteps, dp), real(rs%naccept, dp), real(rs%nreject, dp), real(rs%nfev, dp)]
      if (status == st_ok) exit
      if (status /= st_stopped) return
      status = st_ok
      nswitch = nswitch + 1
      if (stats(1) >= real(max_steps, dp)) then
        status = st_too_many_steps; return
      end if
      ! the outputs up to the event are filled; the rest continue from it at rest
      kk = count(ts <= tev(1))
      k = k + kk
      tc = tc + tev(1); th = thev(1); vv = 0.0_dp
    end do
  end subroutine stick_slip_run

  !> The time after tc when the stuck bob at th breaks loose: the first |F(t, th)| > mu, sampled
  !> release_samples times per period of the fastest time-dependent force and refined by GSL's
  !> Brent method; huge() when it sticks for good (no time-dependent force, or none before tend).
  subroutine release_time(m, th, tc, tend, tr, status, cancel)
    type(pendulum_model), intent(in) :: m
    real(dp), intent(in) :: th, tc, tend
    real(dp), intent(out) :: tr
    integer, intent(out) :: status
    !> read every release_poll samples: non-zero stops with st_cancelled
    integer, intent(inout), volatile :: cancel
    type(stuck_t), target :: ctx
    real(dp) :: hs, ta, tb, wmax
    integer(i8) :: j
    integer :: i
    status = st_ok
    tr = huge(1.0_dp)
    if (.not. (m%driven .or. m%vibrated .or. m%forced)) return
    wmax = sqrt(m%eps)
    if (m%driven) wmax = max(wmax, m%omega)
    if (m%vibrated) wmax = max(wmax, m%pomega)
    hs = two_pi / wmax / release_samples
    ctx%m = m; ctx%th = th
    ta = tc
    do j = 1_i8, max_steps
      if (mod(j, release_poll) == 0) then
        if (cancel /= 0) then
          status = st_cancelled; return
        end if
      end if
      tb = tc + real(j, dp) * hs
      if (gap(ctx, tb) > 0.0_dp) then
        if (gsl_root(c_funloc(gap_c), c_loc(ctx), ta, tb, 0.0_dp, 200, tr) /= 0) then
          status = ss_release_failed; return
        end if
        ! the release: the first double after the root where the force exceeds friction
        do i = 1, 60
          if (gap(ctx, tr) > 0.0_dp .or. tr >= tb) exit
          tr = min(tb, tr + spacing(tr) * 2.0_dp**(i / 4))
        end do
        return
      end if
      if (ta > tend) return
      ta = tb
    end do
    status = st_too_many_steps
  end subroutine release_time

  pure function gap(ctx, t) result(g)
    type(stuck_t), intent(in) :: ctx
    real(dp), intent(in) :: t
    real(dp) :: g
    g = abs(free_accel(ctx%m, t, ctx%th, 0.0_dp)) - ctx%m%mu
  end function gap

  function gap_c(t, p) bind(C) result(g)
    real(c_double), value, intent(in) :: t
    type(c_ptr), value, intent(in) :: p
    real(c_double) :: g
    type(stuck_t), pointer :: ctx
    call c_f_pointer(p, ctx)
    g = gap(ctx, t)
  end function gap_c

end module pendula_stick_slip
