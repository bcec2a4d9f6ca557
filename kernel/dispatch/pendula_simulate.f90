!> Run one scene: the exact solution whenever the scene allows it, otherwise
!> the integrator the scene names (or the cheapest one for its tolerance).
module pendula_simulate
  use pendula_kinds, only: dp
  use pendula_scene, only: scene_t, scene_effects
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval
  use pendula_integrators, only: make_model, event_spec, run_stats, integrate, m_rk4, m_verlet, &
    m_yoshida4, m_yoshida6, m_yoshida8, m_gauss4, m_gauss6, m_dopri5, m_dop853
  implicit none
  private
  public :: simulate_scene, simulate_status_text

  integer, parameter, public :: sim_ok = 0, sim_bad_state = 1, sim_unsupported = 10, &
    sim_needs_dt = 11, sim_unsorted = 12, sim_integrator_failed = 13

contains

  subroutine simulate_scene(sc, t, theta, v, nsteps, nrhs, status)
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:)
    integer, intent(out) :: nsteps, nrhs, status
    type(pendulum_orbit) :: o
    type(event_spec) :: ev
    type(run_stats) :: st
    integer :: method, nev
    real(dp) :: tev(1), thev(1), vev(1)
    nsteps = 0
    nrhs = 0
    ! ---- flexible cord (Garfinkel): kernel/models/pendula_cord.f90; conservative case only ----
    if (sc%cord == 'flexible') then
      call simulate_cord(sc, t, theta, v, status)
      return
    end if
    ! ---- end flexible cord ----
    if (len_trim(scene_effects(sc)) == 0 .and. (sc%method == 'auto' .or. sc%method == 'exact')) then
      call orbit_setup(sc%theta0, sc%v0, sc%eps, o, status)
      if (status /= 0) then
        status = sim_bad_state
        return
      end if
      call orbit_eval(o, t, theta, v)
      status = sim_ok
    else
      ! 'auto' with effects: DOP853, the cheapest at the default tolerances (see README)
      select case (trim(sc%method))
      case ('rk4');      method = m_rk4
      case ('verlet');   method = m_verlet
      case ('yoshida4'); method = m_yoshida4
      case ('yoshida6'); method = m_yoshida6
      case ('yoshida8'); method = m_yoshida8
      case ('gauss4');   method = m_gauss4
      case ('gauss6');   method = m_gauss6
      case ('dopri5');   method = m_dopri5
      case ('dop853', 'auto', 'exact'); method = m_dop853
      case default
        status = sim_unsupported; return
      end select
      if (method <= m_gauss6 .and. .not. (sc%dt > 0.0_dp)) then
        status = sim_needs_dt; return
      end if
      if (any(t(2:) < t(:size(t) - 1))) then
        status = sim_unsorted; return
      end if
      call integrate(make_model(sc%eps, sc%damping, sc%torque, sc%drive_amplitude, sc%drive_frequency, &
                                sc%drive_phase), method, sc%theta0, sc%v0, t, sc%rtol, sc%atol, sc%dt, &
                     theta, v, st, status, ev, nev, tev, thev, vev)
      nsteps = int(st%nsteps)
      nrhs = int(st%nfev)
      if (status /= 0) status = sim_integrator_failed
    end if
  end subroutine simulate_scene

  function simulate_status_text(status) result(s)
    integer, intent(in) :: status
    character(len=128) :: s
    select case (status)
    case (sim_ok);               s = 'ok'
    case (sim_bad_state);        s = 'invalid initial state'
    case (sim_unsupported);      s = 'method not available in pendula-run (gsl-rk8pd: use the Python API)'
    case (sim_needs_dt);         s = 'field ''dt'': fixed-step methods need dt > 0'
    case (sim_unsorted);         s = 'output times must be increasing for integrators'
    case (sim_integrator_failed); s = 'the integrator failed (step size underflow or non-finite state)'
    case default;                s = 'unknown failure'
    end select
  end function simulate_status_text

  !> The flexible cord through the dispatcher: theta and v only (pendula-run writes x, y, r and the
  !> flip log itself).  Damping, torque or drive with a flexible cord: sim_unsupported (Python only).
  subroutine simulate_cord(sc, t, theta, v, status)
    use pendula_cord, only: cord_run_all
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:)
    integer, intent(out) :: status
    real(dp), allocatable :: x(:), y(:), r(:), flips(:, :)
    integer :: nflips, stop_reason
    if (sc%damping /= 0.0_dp .or. sc%torque /= 0.0_dp .or. sc%drive_amplitude /= 0.0_dp .or. &
        .not. (sc%method == 'auto' .or. sc%method == 'exact')) then
      status = sim_unsupported; return
    end if
    allocate(x(size(t)), y(size(t)), r(size(t)))
    call cord_run_all(sc%eps, sc%theta0, sc%v0, sc%restitution, sc%max_flips, sc%min_flight, t, theta, v, &
                      x, y, r, flips, nflips, stop_reason, status)
    if (status /= 0) status = merge(sim_unsorted, sim_bad_state, status == 3)
  end subroutine simulate_cord

end module pendula_simulate
