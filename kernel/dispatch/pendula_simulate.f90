!> The dispatcher: scene -> model -> exact path or integrator.
!>
!> Every way of running a scene goes through simulate_scene: pendula-run and
!> the Python layer (through the binding's simulate_v) alike, so the decision
!> is taken once.  A scene's fields select one model from the registry below;
!> the model says whether its exact (closed-form) path answers the effects the
!> scene names; otherwise the integrator the scene names (or, for 'auto', the
!> fastest one for the scene's problem class and rtol in the work-precision
!> study: auto_method) integrates the model's right-hand side.
!>
!> The registry of models, select_model and the capability table are the
!> system contract's (pendula_system); adding a model: one module in
!> kernel/models, its entry and rows there, one case in simulate_scene.
module pendula_simulate
  use, intrinsic :: iso_c_binding, only: c_loc, c_funptr, c_f_procpointer, c_null_ptr, c_associated, &
    c_funloc
  use pendula_kinds, only: dp, i8, nan_dp, two_pi
  use, intrinsic :: iso_fortran_env, only: int64
  use pendula_scene, only: scene_t, scene_effects, scene_has_orbit_facts
  use pendula_rigid, only: rigid_has_exact, rigid_exact, rigid_energy
  use pendula_cycloid, only: cycloid_run, cycloid_omega2, cy_ok, cy_reaches_cusp
  use pendula_gravity, only: gk_uniform, gk_inverse_square, gk_linear, gravity_energy, gravity_orbit, &
    gr_libration, gr_rotation
  use pendula_integrators, only: pendulum_model, make_model, add_effects, event_spec, run_stats, integrate, m_rk4, m_verlet, &
    m_yoshida4, m_yoshida6, m_yoshida8, m_gauss4, m_gauss6, m_dopri5, m_dop853, st_too_many_steps, &
    st_cancelled, st_velocity_force, m_dprkn6, m_vern9, m_vern8, max_steps, max_fixed_steps
  use pendula_gsl_iface, only: pendula_gsl_rk8pd
  use pendula_stick_slip, only: stick_slip_run, switched, ss_backward, ss_release_failed
  use pendula_system, only: model_info_t, registry, select_model, mid_rigid, mid_cord, mid_cycloid, mid_gravity, &
    scene_rates, capability_check, cap_ok, cap_not_implemented, any_effect
  implicit none
  private
  public :: model_info_t, registry, select_model, mid_rigid, mid_cord, mid_cycloid, mid_gravity, &
            method_code, method_name, auto_method, simulate_scene, &
            simulate_status_text, &
            scene_energy, model_orbit_facts, cord_integrated, cord_scene_run, scene_model, attach_force

  integer, parameter, public :: sim_ok = 0, sim_bad_state = 1, sim_unsupported = 10, &
    sim_needs_dt = 11, sim_unsorted = 12, sim_integrator_failed = 13, sim_not_implemented = 14, &
    sim_model_clash = 15, sim_exact_refused = 16, sim_backward = 17, sim_gsl_failed = 18, &
    sim_too_many_steps = 19, sim_cancelled = 20, sim_closed_form_only = 21, sim_beyond_cusp = 22, &
    sim_nonfinite_t = 23, sim_cord_effects = 24, sim_velocity_force = 25, &
    sim_switch_backward = 26, sim_force_method = 27, sim_refused = 28, sim_release_failed = 29, &
    sim_noise_backward = 30, sim_force_noise = 31
  !> method codes: the integrators' 1..9, 11 (dprkn6), 12 (vern9) and 14 (vern8), then GSL's rk8pd, the
  !> exact path and the Langevin path
  integer, parameter, public :: m_gsl_rk8pd = 10, m_exact = 0, m_langevin = 13

contains

  !> The code of a method name (-1: unknown).
  pure integer function method_code(name)
    character(len=*), intent(in) :: name
    select case (trim(name))
    case ('exact');    method_code = m_exact
    case ('rk4');      method_code = m_rk4
    case ('verlet');   method_code = m_verlet
    case ('yoshida4'); method_code = m_yoshida4
    case ('yoshida6'); method_code = m_yoshida6
    case ('yoshida8'); method_code = m_yoshida8
    case ('gauss4');   method_code = m_gauss4
    case ('gauss6');   method_code = m_gauss6
    case ('dopri5');   method_code = m_dopri5
    case ('dop853');   method_code = m_dop853
    case ('gsl-rk8pd'); method_code = m_gsl_rk8pd
    case ('dprkn6');   method_code = m_dprkn6
    case ('vern9');    method_code = m_vern9
    case ('vern8');    method_code = m_vern8
    case default;      method_code = -1
    end select
  end function method_code

  !> The name of a method code (method_code's inverse; '' for an unknown code).
  pure function method_name(code) result(name)
    integer, intent(in) :: code
    character(len=16) :: name
    character(len=16), parameter :: names(15) = [character(len=16) :: 'exact', 'rk4', 'verlet', 'yoshida4', &
      'yoshida6', 'yoshida8', 'gauss4', 'gauss6', 'dopri5', 'dop853', 'gsl-rk8pd', 'dprkn6', 'vern9', 'vern8', 'auto']
    integer :: i
    name = ''
    do i = 1, size(names)
      if (method_code(names(i)) == code) name = names(i)
    end do
  end function method_name

  !> The integrator method='auto' picks for an integrated rigid-pendulum scene:
  !> the table pendula_auto_methods.inc (generated from the recorded
  !> work-precision study by data/bench/gen_auto_methods.py, committed) by the
  !> scene's problem class (auto_class) and the nearest decade of its rtol
  !> (clamped to the study's 1e-3 ... 1e-14); DOP853 for scenes outside the
  !> study's classes and with a user's force (forced).
  pure integer function auto_method(sc, forced)
    type(scene_t), intent(in) :: sc
    logical, intent(in) :: forced
    include 'pendula_auto_methods.inc'
    integer :: cls, k
    auto_method = m_dop853
    cls = auto_class(sc)
    if (forced .or. cls == 0 .or. .not. (sc%rtol > 0.0_dp .and. sc%rtol <= huge(1.0_dp))) return
    k = min(auto_last_decade, max(auto_first_decade, nint(-log10(sc%rtol))))
    auto_method = auto_methods(k, cls)
  end function auto_method

  !> The work-precision study's problem class of a rigid-pendulum scene under
  !> uniform gravity: 5 driven (a periodic drive, with anything else), 4
  !> torqued (a constant torque, damped or not), 3 damped, 2 a conservative
  !> rotation (energy above the separatrix, v0^2/2 + eps (1 - cos theta0) > 2
  !> eps), 1 a conservative libration; 0 for every other scene (friction, drag,
  !> a vibrating pivot, another gravity field: not in the study).
  pure integer function auto_class(sc)
    type(scene_t), intent(in) :: sc
    auto_class = 0
    if (sc%friction /= 0.0_dp .or. sc%drag /= 0.0_dp .or. sc%pivot_amplitude /= 0.0_dp .or. &
        trim(sc%gravity) /= 'uniform' .or. trim(sc%cord) /= 'rigid' .or. trim(sc%guide) /= 'none') return
    if (sc%drive_amplitude /= 0.0_dp) then
      auto_class = 5
    else if (sc%torque /= 0.0_dp) then
      auto_class = 4
    else if (sc%damping /= 0.0_dp) then
      auto_class = 3
    else if (0.5_dp * sc%v0**2 + sc%eps * (1.0_dp - cos(sc%theta0)) > 2.0_dp * sc%eps) then
      auto_class = 2
    else
      auto_class = 1
    end if
  end function auto_class

  !> Run one scene at the times t (sorted ascending when an integrator runs).
  !> energy: the model's invariant along the path; stats = [steps, accepted,
  !> rejected, rhs evaluations]; method: the code of what answered (m_exact
  !> for the exact path).  msg explains a non-zero status.
  subroutine simulate_scene(sc, t, theta, v, energy, stats, method, status, msg, cancel, force, fparams, land)
    type(scene_t), intent(in) :: sc
    !> non-zero (set by another thread) stops an integration: status sim_cancelled
    integer, intent(inout), volatile, optional :: cancel
    !> a user's force f(t, theta, v, params) (bind(C), pendula_integrators%user_force_fn) and the
    !> params it reads: the scene is then integrated with it added to the force law
    type(c_funptr), intent(in), optional :: force
    real(dp), intent(in), target, contiguous, optional :: fparams(:)
    !> the adaptive pairs end their steps on the output times (see pendula_integrators: integrate)
    logical, intent(in), optional :: land
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:), energy(:), stats(4)
    integer, intent(out) :: method, status
    character(len=*), intent(out) :: msg
    integer :: id
    theta = 0.0_dp
    v = 0.0_dp
    energy = 0.0_dp
    stats = 0.0_dp
    method = -1
    call select_model(sc, id, status, msg)
    if (status /= sim_ok) return
    ! what simulate honours on this model (the capability table); the scene's
    ! own rules have refused the combinations no model takes
    status = cap_ok
    if (any_effect(sc) .or. present(force)) call capability_check(sc, 'simulate', '', present(force), status, msg)
    if (status == cap_not_implemented) then
      status = sim_not_implemented; return
    else if (status /= cap_ok) then
      status = sim_refused; return
    end if
    select case (id)
    case (mid_rigid)
      if (sc%noise > 0.0_dp) then
        ! thermal noise: the Langevin integrator (the scene check allows it on the rigid pendulum only)
        if (present(force)) then
          status = sim_force_noise; msg = simulate_status_text(status); return
        end if
        call langevin_scene(sc, t, theta, v, stats, method, status, cancel)
      else if (rigid_has_exact(sc%damping, sc%torque, sc%drive_amplitude) .and. .not. present(force) .and. &
          sc%friction == 0 .and. sc%drag == 0 .and. sc%pivot_amplitude == 0 .and. &
          (sc%method == 'auto' .or. sc%method == 'exact')) then
        method = m_exact
        call rigid_exact(sc%theta0, sc%v0, sc%eps, t, theta, v, status)
        if (status /= 0) status = sim_bad_state
      else if (sc%method == 'exact') then
        status = sim_exact_refused
      else
        call integrated()
      end if
      if (status == sim_ok) energy = rigid_energy(sc%eps, theta, v)
    case (mid_cord)
      ! circle (exact elliptic arcs), free flight (parabola), jerk: all closed form without
      ! effects.  With damping, torque or drive (or an adaptive method named) the circle
      ! phases are integrated up to the tension event (pendula_cord_hybrid)
      call simulate_cord(sc, t, theta, v, stats, method, status, cancel)
      if (status == sim_ok) energy = rigid_energy(sc%eps, theta, v)
    case (mid_cycloid)
      ! a damped, driven harmonic oscillator in the arc length: never integrated
      if (sc%method /= 'auto' .and. sc%method /= 'exact') then
        status = sim_closed_form_only
      else
        method = m_exact
        call cycloid_path_motion(sc, t, theta, v, status)
        if (status == sim_ok) energy = scene_energy(sc, theta, v)
      end if
    case (mid_gravity)
      ! conservative and one-dimensional, but no closed form: the scene's integrator
      ! on the field's force law (the period comes from the energy integral: model_orbit_facts)
      if (sc%method == 'exact') then
        status = sim_exact_refused
      else
        call integrated()
        if (status == sim_ok) energy = scene_energy(sc, theta, v)
      end if
    end select
    if (status /= sim_ok) msg = simulate_status_text(status)
  contains
    !> The scene's integrator, with the user's force when there is one (an absent force and its
    !> params are not passed on: an absent contiguous array's descriptor would be read by the call).
    subroutine integrated()
      if (present(force)) then
        call integrate_model(sc, t, theta, v, stats, method, status, cancel, force, fparams, land=land)
      else
        call integrate_model(sc, t, theta, v, stats, method, status, cancel, land=land)
      end if
    end subroutine integrated
  end subroutine simulate_scene

  !> The right-hand side a scene calls for: the pendulum model of the
  !> integrators with exactly the effects the scene names (its field, damping,
  !> torque, drive).  The one map from a scene's fields to its force law: the
  !> dispatcher's integrations, the periodic orbits and their monodromy (the
  !> binding's periodic_orbit_v) and the events of the Python layer all take
  !> their model from here.
  pure function scene_model(sc) result(model)
    type(scene_t), intent(in) :: sc
    type(pendulum_model) :: model
    model = make_model(sc%eps, sc%damping, sc%torque, sc%drive_amplitude, sc%drive_frequency, sc%drive_phase)
    model = add_effects(model, sc%friction, sc%drag, sc%pivot_amplitude, sc%pivot_frequency)
    select case (trim(sc%gravity))
    case ('inverse-square'); model%gkind = gk_inverse_square; model%gpar = sc%gravity_distance
    case ('linear');         model%gkind = gk_linear;         model%gpar = sc%gravity_gradient
    case default;            model%gkind = gk_uniform
    end select
  end function scene_model

  !> The user's force f (a C function pointer, pendula_integrators%user_force_fn) added to the
  !> model's force law, reading params (which must outlive every use of m).
  subroutine attach_force(m, f, params)
    type(pendulum_model), intent(inout) :: m
    type(c_funptr), intent(in) :: f
    real(dp), intent(in), target, contiguous :: params(:)
    call c_f_procpointer(f, m%uforce)
    m%uparams = c_null_ptr
    if (size(params) > 0) m%uparams = c_loc(params)
    m%forced = .true.
  end subroutine attach_force

  !> The scene's integrator on the rigid pendulum's force law with its effects.
  subroutine integrate_model(sc, t, theta, v, stats, method, status, cancel, force, fparams, land)
    type(scene_t), intent(in) :: sc
    integer, intent(inout), volatile, optional :: cancel
    type(c_funptr), intent(in), optional :: force
    real(dp), intent(in), target, contiguous, optional :: fparams(:)
    logical, intent(in), optional :: land
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:), stats(4)
    integer, intent(out) :: method, status
    type(event_spec) :: ev
    type(run_stats) :: st
    integer :: nev
    real(dp) :: tev(1), thev(1), vev(1), gs(2)
    type(pendulum_model), target :: model
    method = method_code(sc%method)
    if (sc%method == 'auto') method = auto_method(sc, present(force))
    if (method < 1) then
      status = sim_unsupported; return
    end if
    if (method <= m_gauss6 .and. .not. (sc%dt > 0.0_dp)) then
      status = sim_needs_dt; return
    end if
    if (.not. all(abs(t) <= huge(1.0_dp))) then
      status = sim_nonfinite_t; return
    end if
    if (size(t) > 1) then
      if (any(t(2:) < t(:size(t) - 1))) then
        status = sim_unsorted; return
      end if
    end if
    model = scene_model(sc)
    if (present(force)) then
      ! a force of (t, theta, v): not for the splittings' position-only kicks
      if (method == m_dprkn6 .or. (method >= m_verlet .and. method <= m_yoshida8)) then
        status = sim_force_method; return
      end if
      call attach_force(model, force, fparams)
    end if
    if (switched(model)) then
      call switched_run()
      return
    end if
    if (method == m_gsl_rk8pd .and. trim(sc%gravity) /= 'uniform') then
      status = sim_unsupported; return
    end if
    if (method == m_gsl_rk8pd) then
      if (size(t) > 0) then
        if (t(1) < 0.0_dp) then
          status = sim_backward; return
        end if
      end if
      status = pendula_gsl_rk8pd(c_loc(model), sc%theta0, sc%v0, size(t), t, sc%rtol, sc%atol, theta, v, gs)
      stats = [gs(1), gs(1), 0.0_dp, gs(2)]
      if (status /= 0) status = sim_gsl_failed
      return
    end if
    call integrate(model, method, sc%theta0, sc%v0, t, sc%rtol, sc%atol, sc%dt, theta, v, st, status, &
                   ev, nev, tev, thev, vev, cancel, land=land)
    stats = [real(st%nsteps, dp), real(st%naccept, dp), real(st%nreject, dp), real(st%nfev, dp)]
    select case (status)
    case (0)
    case (st_too_many_steps); status = sim_too_many_steps
    case (st_cancelled);      status = sim_cancelled
    case (st_velocity_force); status = sim_velocity_force
    case default;             status = sim_integrator_failed
    end select
  contains
    !> friction or drag: the stretches between the switches at v = 0 (pendula_stick_slip)
    subroutine switched_run()
      integer(i8) :: nswitch
      call stick_slip_run(model, method, sc%theta0, sc%v0, t, sc%rtol, sc%atol, theta, v, stats, nswitch, &
                          status, cancel)
      select case (status)
      case (0)
      case (ss_backward);       status = sim_switch_backward
      case (ss_release_failed); status = sim_release_failed
      case (st_too_many_steps); status = sim_too_many_steps
      case (st_cancelled);      status = sim_cancelled
      case default;             status = sim_integrator_failed
      end select
    end subroutine switched_run
  end subroutine integrate_model

  !> A scene with thermal noise: the Langevin path (pendula_langevin, BAOAB)
  !> at the times t (>= 0, ascending) from (theta0, v0) at t = 0, step the
  !> scene's dt or its default (langevin_default_dt), noise from the seed.
  subroutine langevin_scene(sc, t, theta, v, stats, method, status, cancel)
    use pendula_langevin, only: langevin_path, langevin_default_dt, lv_ok, lv_backward, lv_too_many_steps, &
      lv_cancelled, lv_bad_argument
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:), stats(4)
    integer, intent(out) :: method, status
    integer, intent(inout), volatile, optional :: cancel
    integer, volatile :: no_cancel
    integer(int64) :: nsteps
    real(dp) :: h
    method = m_langevin
    h = sc%dt
    if (.not. (h > 0.0_dp)) h = langevin_default_dt(scene_rates(sc))
    no_cancel = 0
    if (present(cancel)) then
      call langevin_path(scene_model(sc), sc%noise, sc%seed, h, sc%theta0, sc%v0, t, theta, v, nsteps, status, &
                         cancel)
    else
      call langevin_path(scene_model(sc), sc%noise, sc%seed, h, sc%theta0, sc%v0, t, theta, v, nsteps, status, &
                         no_cancel)
    end if
    stats = [real(nsteps, dp), real(nsteps, dp), 0.0_dp, real(2 * nsteps, dp)]
    select case (status)
    case (lv_ok); status = sim_ok
    case (lv_backward); status = sim_noise_backward
    case (lv_too_many_steps); status = sim_too_many_steps
    case (lv_cancelled); status = sim_cancelled
    case (lv_bad_argument); status = sim_unsorted
    case default; status = sim_integrator_failed
    end select
  end subroutine langevin_scene

  !> The flexible cord through simulate_scene: theta and v (the bob's x, y, r and the
  !> flip log: cord_scene_run).
  subroutine simulate_cord(sc, t, theta, v, stats, method, status, cancel)
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:), stats(4)
    integer, intent(out) :: method, status
    integer, intent(inout), volatile, optional :: cancel
    real(dp), allocatable :: x(:), y(:), r(:), flips(:, :)
    integer :: nflips, stop_reason
    allocate(x(size(t)), y(size(t)), r(size(t)))
    call cord_scene_run(sc, t, theta, v, x, y, r, flips, nflips, stop_reason, stats, method, status, cancel)
  end subroutine simulate_cord

  !> The flexible cord: closed form without effects (kernel/models/pendula_cord.f90),
  !> integrated circles with them (kernel/dispatch/pendula_cord_hybrid.f90: dopri5 or
  !> dop853, 'auto' meaning dop853; fixed-step methods have no dense output to
  !> locate the tension event on).  x, y, r: the bob's position (r < 1 in flight);
  !> flips(8, nflips): the flip log (pendula_cord%cord_run); stop_reason:
  !> cord_stop_*; stats as simulate_scene; status sim_*.
  subroutine cord_scene_run(sc, t, theta, v, x, y, r, flips, nflips, stop_reason, stats, method, status, cancel)
    use pendula_cord, only: cord_run_all, cord_cancelled
    use pendula_cord_hybrid, only: cord_hybrid_all, cord_bad_method, cord_integrator_failed
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:), x(:), y(:), r(:), stats(4)
    real(dp), allocatable, intent(out) :: flips(:, :)
    integer, intent(out) :: nflips, stop_reason, method, status
    integer, intent(inout), volatile, optional :: cancel
    real(dp) :: work(2)
    stats = 0.0_dp
    if (.not. cord_integrated(sc)) then
      method = m_exact
      call cord_run_all(sc%eps, sc%theta0, sc%v0, sc%restitution, sc%max_flips, sc%min_flight, t, theta, v, &
                        x, y, r, flips, nflips, stop_reason, status, cancel)
      if (status == cord_cancelled) then
        status = sim_cancelled
      else if (status /= 0) then
        status = merge(sim_unsorted, sim_bad_state, status == 3)
      end if
      return
    end if
    method = merge(m_dop853, method_code(sc%method), sc%method == 'auto')
    if (method /= m_dopri5 .and. method /= m_dop853) then
      nflips = 0; stop_reason = 0; allocate(flips(8, 0))
      status = sim_cord_effects; return
    end if
    call cord_hybrid_all([sc%eps, sc%damping, sc%torque, sc%drive_amplitude, sc%drive_frequency, &
                          sc%drive_phase], method, sc%rtol, sc%atol, sc%theta0, sc%v0, sc%restitution, &
                          sc%max_flips, sc%min_flight, t, theta, v, x, y, r, flips, nflips, stop_reason, work, &
                          status, cancel)
    stats = [work(1), work(1), 0.0_dp, work(2)]
    if (status == cord_integrator_failed + st_too_many_steps) then
      status = sim_too_many_steps
    else if (status == cord_integrator_failed + st_cancelled .or. status == cord_cancelled) then
      status = sim_cancelled
    else if (status >= cord_integrator_failed) then
      status = sim_integrator_failed
    else if (status == cord_bad_method) then
      status = sim_cord_effects
    else if (status == 3) then
      status = sim_unsorted
    else if (status /= 0) then
      status = sim_bad_state
    end if
  end subroutine cord_scene_run

  !> Does a flexible-cord scene integrate its circles (effects, or an integrator named)?
  pure logical function cord_integrated(sc)
    type(scene_t), intent(in) :: sc
    cord_integrated = sc%damping /= 0.0_dp .or. sc%torque /= 0.0_dp .or. sc%drive_amplitude /= 0.0_dp .or. &
                      .not. (sc%method == 'auto' .or. sc%method == 'exact')
  end function cord_integrated

  !> The cycloidal guide's closed form (kernel/models/pendula_cycloid.f90).
  subroutine cycloid_path_motion(sc, t, theta, v, status)
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:)
    integer, intent(out) :: status
    real(dp), allocatable :: s(:), sd(:)
    allocate(s(size(t)), sd(size(t)))
    call cycloid_run(sc%eps, sc%cycloid_radius, sc%damping, sc%torque, sc%drive_amplitude, &
                     sc%drive_frequency, sc%drive_phase, sc%theta0, sc%v0, t, theta, v, s, sd, status)
    select case (status)
    case (cy_ok);           status = sim_ok
    case (cy_reaches_cusp); status = sim_beyond_cusp
    case default;           status = sim_bad_state
    end select
  end subroutine cycloid_path_motion

  !> The energy of the scene's model along (theta, v) (per m l^2):
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

  !> The orbit facts of a model other than the rigid pendulum: a conservative cycloid scene (the
  !> guide, perhaps a torque) or a scene whose only effect is non-uniform gravity
  !> (scene_has_orbit_facts).  has = .false. for any other scene.
  !> k: sqrt(m) in libration, 1/sqrt(m) in rotation (the rigid pendulum's k in uniform gravity);
  !> NaN on the cycloid (no modulus there).  status /= 0: the orbit reaches a cusp or bad input.
  subroutine model_orbit_facts(sc, has, regime, k, period, theta_max, status)
    type(scene_t), intent(in) :: sc
    logical, intent(out) :: has
    integer, intent(out) :: regime, status
    real(dp), intent(out) :: k, period, theta_max
    real(dp) :: w2, r, s0, sd0, c, a, e, m, mc, kk
    has = .false.; regime = 0; status = 0
    k = nan_dp; period = nan_dp; theta_max = nan_dp
    if (.not. scene_has_orbit_facts(sc)) return
    if (sc%guide == 'cycloid') then
      has = .true.
      r = sc%cycloid_radius
      w2 = cycloid_omega2(sc%eps, r)
      s0 = 4.0_dp * r * sin(sc%theta0)
      sd0 = 4.0_dp * r * cos(sc%theta0) * sc%v0
      c = sc%torque / w2
      a = hypot(s0 - c, sd0 / sqrt(w2))
      period = two_pi / sqrt(w2)
      if (abs(c) + a > 4.0_dp * r) then
        status = sim_beyond_cusp; return
      end if
      theta_max = asin((c + a) / (4.0_dp * r))
    else
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
  end subroutine model_orbit_facts

  function simulate_status_text(status) result(s)
    integer, intent(in) :: status
    character(len=160) :: s
    select case (status)
    case (sim_ok);               s = 'ok'
    case (sim_bad_state);        s = 'invalid initial state'
    case (sim_unsupported);      s = 'field ''method'': unknown method'
    case (sim_needs_dt);         s = 'field ''dt'': fixed-step methods need dt > 0'
    case (sim_unsorted);         s = 'output times must be increasing for integrators'
    case (sim_integrator_failed); s = 'the integrator failed (step size underflow or non-finite state)'
    case (sim_not_implemented);  s = 'the model the scene names is not implemented yet'
    case (sim_model_clash);      s = 'the scene names more than one model'
    case (sim_exact_refused);    s = 'field ''method'': ''exact'' answers only scenes whose model has an exact path &
                                      &for the effects named'
    case (sim_backward);         s = 'gsl-rk8pd integrates forward only: give times >= 0'
    case (sim_gsl_failed);       s = 'GSL odeiv2 (rk8pd) failed'
    case (sim_too_many_steps)
      write(s, '(a,es8.1,a,es8.1,a)') 'the run needs more steps than the work limit (', real(max_steps, dp), &
        ' adaptive,', real(max_fixed_steps, dp), ' fixed-step): shorten the span (t), or give a larger dt or rtol'
    case (sim_cancelled);        s = 'interrupted'
    case (sim_nonfinite_t);      s = 't must be finite for a scene that is integrated'
    case (sim_cord_effects);     s = 'field ''method'': a flexible cord with effects is integrated between ' // &
                                     'flights by dopri5 or dop853 (auto: dop853), whose dense output ' // &
                                     'locates the tension event'
    case (sim_closed_form_only); s = 'field ''method'': the cycloidal guide is answered in closed form; ' // &
                                     'use ''auto'' or ''exact'''
    case (sim_beyond_cusp);      s = 'the motion reaches the cusps of the cycloidal guide (|s| = 4R, ' // &
                                     '|theta| = pi/2): start lower, slower, or drive less'
    case (sim_velocity_force);   s = 'field ''method'': dprkn6 (a Runge-Kutta-Nystrom pair) integrates ' // &
                                     'theta'''' = f(t, theta) only; a damped scene needs another method (dop853)'
    case (sim_switch_backward);  s = 'fields ''friction''/''drag'': a scene with friction or drag runs ' // &
                                     'forward in time only: give times >= 0'
    case (sim_force_method);     s = 'field ''method'': a force of (t, theta, v) needs a method that ' // &
                                     'evaluates the whole right-hand side (not verlet, yoshida*, dprkn6)'
    case (sim_refused);          s = 'the capability table refuses a field of the scene on its model'
    case (sim_release_failed);   s = 'field ''friction'': the time the stuck bob breaks loose was not ' // &
                                     'located (GSL root finder failed)'
    case (sim_noise_backward);   s = 'a scene with noise runs forward from t = 0 only (a Langevin path has ' // &
                                     'no past): give times >= 0 (t_start >= 0)'
    case (sim_force_noise);      s = 'field ''noise'': a user force with thermal noise is not implemented ' // &
                                     '(the Langevin integrator takes the scene''s own force law only)'
    case default;                s = 'unknown failure'
    end select
  end function simulate_status_text


end module pendula_simulate
