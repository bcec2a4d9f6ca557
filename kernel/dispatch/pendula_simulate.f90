!> Run one scene: the exact solution whenever the scene allows it, otherwise
!> the integrator the scene names (or the cheapest one for its tolerance).
module pendula_simulate
  use pendula_kinds, only: dp, nan_dp, two_pi
  use pendula_scene, only: scene_t, scene_effects
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval
  use pendula_cycloid, only: cycloid_run, cycloid_omega2
  use pendula_gravity, only: gk_uniform, gk_inverse_square, gk_linear, gravity_energy, gravity_orbit, &
    gr_libration, gr_rotation
  use pendula_integrators, only: pendulum_model, make_model, event_spec, run_stats, integrate, m_rk4, m_verlet, &
    m_yoshida4, m_yoshida6, m_yoshida8, m_gauss4, m_gauss6, m_dopri5, m_dop853
  implicit none
  private
  public :: simulate_scene, simulate_status_text, scene_energy, scene_orbit13

  integer, parameter, public :: sim_ok = 0, sim_bad_state = 1, sim_unsupported = 10, &
    sim_needs_dt = 11, sim_unsorted = 12, sim_integrator_failed = 13, sim_cycloid_cusp = 14

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
    type(pendulum_model) :: model
    real(dp), allocatable :: s(:), sd(:)
    nsteps = 0
    nrhs = 0
    ! --- issue 13 hook: the cycloidal pendulum is closed form, never integrated ---
    if (sc%guide == 'cycloid') then
      allocate(s(size(t)), sd(size(t)))
      call cycloid_run(sc%eps, sc%cycloid_radius, sc%damping, sc%torque, sc%drive_amplitude, &
                       sc%drive_frequency, sc%drive_phase, sc%theta0, sc%v0, t, theta, v, s, sd, status)
      if (status == 4) then
        status = sim_cycloid_cusp
      else if (status /= 0) then
        status = sim_bad_state
      end if
      return
    end if
    ! --- end issue 13 hook ---
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
      model = make_model(sc%eps, sc%damping, sc%torque, sc%drive_amplitude, sc%drive_frequency, sc%drive_phase)
      ! --- issue 13 hook: non-uniform gravity in the model ---
      select case (trim(sc%gravity))
      case ('inverse-square'); model%gkind = gk_inverse_square; model%gpar = sc%gravity_distance
      case ('linear');         model%gkind = gk_linear;         model%gpar = sc%gravity_gradient
      case default;            model%gkind = gk_uniform
      end select
      ! --- end issue 13 hook ---
      call integrate(model, method, sc%theta0, sc%v0, t, sc%rtol, sc%atol, sc%dt, &
                     theta, v, st, status, ev, nev, tev, thev, vev)
      nsteps = int(st%nsteps)
      nrhs = int(st%nfev)
      if (status /= 0) status = sim_integrator_failed
    end if
  end subroutine simulate_scene

  !> Issue 13 hook: the energy of the scene's model along (theta, v) (per m l^2):
  !> rigid v^2/2 + V(theta) of its gravity field; on the cycloid s'^2/2 + w2 s^2/2 - tau s.
  function scene_energy(sc, theta, v) result(e)
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: theta(:), v(:)
    real(dp) :: e(size(theta))
    real(dp) :: r
    if (sc%guide == 'cycloid') then
      r = sc%cycloid_radius
      e = 0.5_dp * (4.0_dp * r * cos(theta) * v)**2 + 0.5_dp * cycloid_omega2(sc%eps, r) * &
          (4.0_dp * r * sin(theta))**2 - sc%torque * 4.0_dp * r * sin(theta)
    else
      select case (trim(sc%gravity))
      case ('inverse-square'); e = gravity_energy(gk_inverse_square, sc%gravity_distance, sc%eps, theta, v)
      case ('linear');         e = gravity_energy(gk_linear, sc%gravity_gradient, sc%eps, theta, v)
      case default;            e = 0.5_dp * v * v + 2.0_dp * sc%eps * sin(0.5_dp * theta)**2
      end select
    end if
  end function scene_energy

  !> Issue 13 hook: the orbit facts of a conservative cycloid scene (the guide, perhaps a torque)
  !> or a scene whose only effect is non-uniform gravity.  has = .false. for any other scene.
  !> k: sqrt(m) in libration, 1/sqrt(m) in rotation (the rigid pendulum's k in uniform gravity);
  !> NaN on the cycloid (no modulus there).  status /= 0: the orbit reaches a cusp or bad input.
  subroutine scene_orbit13(sc, has, regime, k, period, theta_max, status)
    type(scene_t), intent(in) :: sc
    logical, intent(out) :: has
    integer, intent(out) :: regime, status
    real(dp), intent(out) :: k, period, theta_max
    real(dp) :: w2, r, s0, sd0, c, a, e, m, mc, kk
    has = .false.; regime = 0; status = 0
    k = nan_dp; period = nan_dp; theta_max = nan_dp
    if (sc%guide == 'cycloid' .and. sc%damping == 0 .and. sc%drive_amplitude == 0) then
      has = .true.
      r = sc%cycloid_radius
      w2 = cycloid_omega2(sc%eps, r)
      s0 = 4.0_dp * r * sin(sc%theta0)
      sd0 = 4.0_dp * r * cos(sc%theta0) * sc%v0
      c = sc%torque / w2
      a = hypot(s0 - c, sd0 / sqrt(w2))
      period = two_pi / sqrt(w2)
      if (abs(c) + a > 4.0_dp * r) then
        status = sim_cycloid_cusp; return
      end if
      theta_max = asin((c + a) / (4.0_dp * r))
    else if (trim(scene_effects(sc)) == 'gravity') then
      has = .true.
      select case (trim(sc%gravity))
      case ('inverse-square')
        call gravity_orbit(gk_inverse_square, sc%gravity_distance, sc%eps, sc%theta0, sc%v0, e, regime, m, mc, &
                           kk, theta_max, period, status)
      case default
        call gravity_orbit(gk_linear, sc%gravity_gradient, sc%eps, sc%theta0, sc%v0, e, regime, m, mc, &
                           kk, theta_max, period, status)
      end select
      if (status /= 0) then
        status = sim_bad_state; return
      end if
      k = 1.0_dp
      if (regime == gr_libration) k = sqrt(m)
      if (regime == gr_rotation) k = 1.0_dp / sqrt(m)
    end if
  end subroutine scene_orbit13

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
    case (sim_cycloid_cusp);     s = 'the cycloidal pendulum reaches a cusp (|s| > 4R, the ends of the cheeks)'
    case default;                s = 'unknown failure'
    end select
  end function simulate_status_text

end module pendula_simulate
