!> The rules of a scene: the ranges of its fields, each model's combinations
!> (the rigid pendulum, the flexible cord, the cycloidal guide, the gravity
!> fields, each in its own routine), thermal noise, the sweep and grid fields,
!> and which outputs a scene can have.  check_scene (pendula_scene) asks them;
!> pendula-run and the Python layer alike.
module pendula_scene_rules
  use pendula_kinds, only: dp, nan_dp, half_pi, pi
  use pendula_exact, only: pendulum_orbit, orbit_setup, regime_separatrix
  use pendula_cycloid, only: cycloid_omega2
  use pendula_scene_type
  use pendula_scene_text
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private
  public :: scene_member, set_swept, set_field, check_fields, value_rules, check_member, check_grid, &
            scene_has_orbit_facts, scene_effects, scene_summary

contains

  !> Member k of a scene's sweep: the scene with the swept field set to its
  !> k-th value (the scene itself when it sweeps nothing).
  pure function scene_member(s, k) result(m)
    type(scene_t), intent(in) :: s
    integer, intent(in) :: k
    type(scene_t) :: m
    m = s
    if (s%n_sweep == 0) return
    call set_swept(m, s%sweep, s%sweep_values(k))
  end function scene_member

  !> The field a sweep runs over, set to one of its values.
  pure subroutine set_swept(m, field, value)
    type(scene_t), intent(inout) :: m
    character(len=*), intent(in) :: field
    real(dp), intent(in) :: value
    select case (trim(field))
    case ('v0');              m%v0 = value
    case ('theta0');          m%theta0 = value
    case ('eps');             m%eps = value
    case ('damping');         m%damping = value
    case ('torque');          m%torque = value
    case ('drive_amplitude'); m%drive_amplitude = value
    case ('drive_frequency'); m%drive_frequency = value
    end select
  end subroutine set_swept

  !> Any field a grid can sweep, set to a value (the griddable fields of check_grid).
  pure subroutine set_field(m, field, value)
    type(scene_t), intent(inout) :: m
    character(len=*), intent(in) :: field
    real(dp), intent(in) :: value
    select case (trim(field))
    case ('drive_phase');     m%drive_phase = value
    case ('pivot_amplitude'); m%pivot_amplitude = value
    case ('pivot_frequency'); m%pivot_frequency = value
    case ('friction');        m%friction = value
    case ('drag');            m%drag = value
    case default;             call set_swept(m, field, value)
    end select
  end subroutine set_field

  !> The fields one by one and the sweep's (msg = '' when fine).
  subroutine check_fields(sc, g, length, msg)
    type(scene_t), intent(inout) :: sc
    real(dp), intent(in) :: g, length
    character(len=*), intent(out) :: msg
    character(len=16), parameter :: known_outputs(11) = [character(len=16) :: 'trajectory', 'theta_t', &
      'v_t', 'phase', 'energy', 'period', 'omega', 'theta_max', 'series', 'lindstedt', 'spectrum']
    character(len=16), parameter :: methods(15) = [character(len=16) :: 'auto', 'exact', 'rk4', 'verlet', &
      'yoshida4', 'yoshida6', 'yoshida8', 'gauss4', 'gauss6', 'dopri5', 'dop853', 'gsl-rk8pd', 'dprkn6', 'vern9', &
      'vern8']
    character(len=16), parameter :: sweepable(7) = [character(len=16) :: 'v0', 'theta0', 'eps', &
      'damping', 'torque', 'drive_amplitude', 'drive_frequency']
    character(len=16), parameter :: cords(2) = [character(len=16) :: 'rigid', 'flexible'], &
      guides(2) = [character(len=16) :: 'none', 'cycloid'], &
      gravities(3) = [character(len=16) :: 'uniform', 'inverse-square', 'linear']
    real(dp) :: vals(26)
    integer :: i
    character(len=16), parameter :: finite_names(26) = [character(len=16) :: 'friction', 'drag', &
      'pivot_amplitude', 'pivot_frequency', 'theta0', 'v0', 't_start', 't_end', &
      'damping', 'torque', 'drive_amplitude', 'drive_frequency', 'drive_phase', 'rtol', 'atol', 'dt', &
      'cycloid_radius', 'gravity_distance', 'gravity_gradient', 'restitution', 'min_flight', 'sweep_t_max', &
      'sweep_transient', 'eps', 'g', 'length']
    msg = ''
    if ((g /= g) .neqv. (length /= length)) then
      msg = 'fields ''g'' and ''length'' go together (eps = g / length): give both or neither'; return
    end if
    vals = [sc%friction, sc%drag, sc%pivot_amplitude, sc%pivot_frequency, &
            sc%theta0, sc%v0, sc%t_start, sc%t_end, sc%damping, sc%torque, sc%drive_amplitude, &
            sc%drive_frequency, sc%drive_phase, sc%rtol, sc%atol, sc%dt, sc%cycloid_radius, sc%gravity_distance, &
            sc%gravity_gradient, sc%restitution, sc%min_flight, sc%sweep_t_max, sc%sweep_transient, sc%eps, g, &
            length]
    do i = 1, size(vals)
      if (i >= 24 .and. vals(i) /= vals(i)) cycle   ! eps, g, length: NaN is 'not given'
      if (.not. finite(vals(i))) then
        msg = 'field ''' // trim(finite_names(i)) // ''' must be finite, got ' // trim(num_text(vals(i))); return
      end if
    end do
    if (g == g) then
      if (.not. (g > 0 .and. length > 0)) then
        msg = 'fields ''g'' and ''length'' must be positive and finite'; return
      end if
      if (sc%eps == sc%eps .and. sc%eps /= g / length) then
        msg = 'fields ''eps'' = ' // trim(num_text(sc%eps)) // ' and ''g'' / ''length'' = ' // &
              trim(num_text(g / length)) // ' contradict each other: give eps, or g and length'; return
      end if
      sc%eps = g / length
    else if (sc%eps /= sc%eps) then
      sc%eps = 1.0_dp
    end if
    if (sc%n_samples < 1 .or. sc%n_samples > 100000000) then
      msg = 'field ''n_samples'' must be between 1 and 1e8, got ' // trim(int_text(sc%n_samples)); return
    end if
    if (.not. (sc%rtol > 0) .or. .not. (sc%atol >= 0)) then
      msg = 'fields ''rtol'' must be > 0 and ''atol'' >= 0'; return
    end if
    if (.not. (sc%dt >= 0)) then
      msg = 'field ''dt'' must be >= 0 (0: chosen by the method), got ' // trim(num_text(sc%dt)); return
    end if
    if (.not. (sc%restitution >= 0 .and. sc%restitution < 1)) then
      msg = 'field ''restitution'' must be in [0, 1), got ' // trim(num_text(sc%restitution)); return
    end if
    if (sc%max_flips < 0 .or. sc%max_flips > 100000000) then
      msg = 'field ''max_flips'' must be between 0 and 1e8, got ' // trim(int_text(sc%max_flips)); return
    end if
    if (.not. (sc%min_flight >= 0)) then
      msg = 'field ''min_flight'' must be >= 0, got ' // trim(num_text(sc%min_flight)); return
    end if
    if (.not. any(cords == sc%cord)) then
      msg = 'field ''cord'' must be one of rigid, flexible; got ''' // trim(sc%cord) // '''' // &
            suggest(sc%cord, cords); return
    end if
    if (.not. any(guides == sc%guide)) then
      msg = 'field ''guide'' must be one of none, cycloid; got ''' // trim(sc%guide) // '''' // &
            suggest(sc%guide, guides); return
    end if
    if (.not. any(gravities == sc%gravity)) then
      msg = 'field ''gravity'' must be one of uniform, inverse-square, linear; got ''' // trim(sc%gravity) // &
            '''' // suggest(sc%gravity, gravities); return
    end if
    if (.not. any(methods == sc%method)) then
      msg = 'field ''method'' must be one of auto, exact, rk4, verlet, yoshida4, yoshida6, yoshida8, gauss4, ' // &
            'gauss6, dopri5, dop853, gsl-rk8pd; got ''' // trim(sc%method) // '''' // suggest(sc%method, methods)
      return
    end if
    do i = 1, sc%n_outputs
      if (.not. any(known_outputs == sc%outputs(i))) then
        msg = 'field ''outputs'': unknown output ''' // trim(sc%outputs(i)) // '''; known: trajectory, ' // &
              'theta_t, v_t, phase, energy, period, omega, theta_max, series, lindstedt, spectrum' // &
              suggest(sc%outputs(i), known_outputs); return
      end if
    end do
    if (sc%n_outputs == 0) then
      sc%n_outputs = 1
      sc%outputs(1) = 'trajectory'
    end if
    if (len_trim(sc%sweep) > 0) then
      if (.not. any(sweepable == sc%sweep)) then
        msg = 'field ''sweep'' must name one of v0, theta0, eps, damping, torque, drive_amplitude, ' // &
              'drive_frequency; got ''' // trim(sc%sweep) // '''' // suggest(sc%sweep, sweepable); return
      end if
      if (sc%n_sweep == 0) then
        msg = 'field ''sweep_values'' is empty but ''sweep'' names a field'; return
      end if
      if (.not. all(finite(sc%sweep_values(1:sc%n_sweep)))) then
        msg = 'field ''sweep_values'' must be finite numbers'; return
      end if
    else if (sc%n_sweep > 0) then
      msg = 'field ''sweep_values'' is given but ''sweep'' does not name a field'; return
    end if
    call value_rules(sc, msg)
  end subroutine check_fields

  !> The rules on the fields a sweep may change, and on the models' fields.
  subroutine value_rules(sc, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(out) :: msg
    msg = ''
    if (.not. (sc%eps > 0 .and. sc%eps <= eps_limit)) then
      msg = 'field ''eps'' must be positive and at most 1e300 (eps = g/l), got ' // trim(num_text(sc%eps)); return
    end if
    if (.not. (abs(sc%theta0) <= theta0_limit)) then
      msg = 'field ''theta0'' must be at most 2^52 in magnitude (beyond, a double holds no fraction of a ' // &
            'turn), got ' // trim(num_text(sc%theta0)); return
    end if
    if (.not. (sc%damping >= 0)) then
      msg = 'field ''damping'' must be >= 0, got ' // trim(num_text(sc%damping)); return
    end if
    if (.not. (sc%drive_frequency >= 0)) then
      msg = 'field ''drive_frequency'' must be >= 0, got ' // trim(num_text(sc%drive_frequency)); return
    end if
    if (.not. (abs(sc%drive_phase) <= drive_phase_limit)) then
      msg = phase_text('field ''drive_phase''', sc%drive_phase); return
    end if
    if (len_trim(msg) == 0) call effect_rules(sc, msg)
    if (len_trim(msg) == 0) call noise_rules(sc, msg)
    if (len_trim(msg) == 0) call model_rules(sc, msg)
  end subroutine value_rules

  !> The message for a drive phase beyond drive_phase_limit.
  function phase_text(what, x) result(t)
    character(len=*), intent(in) :: what
    real(dp), intent(in) :: x
    character(len=:), allocatable :: t
    t = what // ' must be at most 1024 in magnitude (a phase is an angle: give it reduced mod 2 pi; ' // &
        'beyond, its own rounding enters the drive), got ' // trim(num_text(x))
  end function phase_text

  !> The effects friction, drag and the vibrating pivot: their ranges and the
  !> models and methods they combine with (msg = '' when fine).  Friction and
  !> drag switch at v = 0: an event on the dense output of dopri5 or dop853.
  subroutine effect_rules(sc, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(out) :: msg
    character(len=16) :: what
    msg = ''
    if (.not. (sc%friction >= 0)) then
      msg = 'field ''friction'' must be >= 0 (the Coulomb coefficient mu, an acceleration), got ' // &
            trim(num_text(sc%friction)); return
    end if
    if (.not. (sc%drag >= 0)) then
      msg = 'field ''drag'' must be >= 0 (gamma of -gamma v |v|), got ' // trim(num_text(sc%drag)); return
    end if
    if (.not. (sc%pivot_frequency >= 0)) then
      msg = 'field ''pivot_frequency'' must be >= 0, got ' // trim(num_text(sc%pivot_frequency)); return
    end if
    if (sc%pivot_amplitude /= 0 .and. .not. (sc%pivot_frequency > 0)) then
      msg = 'field ''pivot_frequency'' must be > 0 when ''pivot_amplitude'' is set (a vibrating pivot ' // &
            'needs its frequency Omega)'; return
    end if
    what = ''
    if (sc%pivot_amplitude /= 0) what = 'pivot_amplitude'
    if (sc%drag /= 0) what = 'drag'
    if (sc%friction /= 0) what = 'friction'
    if (len_trim(what) == 0) return
    if (sc%cord /= 'rigid') then
      msg = 'fields ''' // trim(what) // ''' and ''cord'': the flexible cord does not take ' // trim(what) // &
            ' (only damping, torque, drive)'; return
    end if
    if (sc%guide /= 'none') then
      msg = 'fields ''' // trim(what) // ''' and ''guide'': the cycloidal guide is solved in closed form ' // &
            'and does not take ' // trim(what); return
    end if
    if (sc%friction /= 0 .or. sc%drag /= 0) then
      what = merge('friction', 'drag    ', sc%friction /= 0)
      if (sc%method /= 'auto' .and. sc%method /= 'dopri5' .and. sc%method /= 'dop853') then
        msg = 'fields ''' // trim(what) // ''' and ''method'': ' // trim(what) // ' switches where v = 0, ' // &
              'an event located on the dense output of dopri5 or dop853 (auto: dop853); got ''' // &
              trim(sc%method) // ''''; return
      end if
    end if
  end subroutine effect_rules

  !> Thermal noise: a temperature, which needs its damping (the force
  !> sqrt(2 beta T) xi of the fluctuation-dissipation theorem), on the rigid
  !> pendulum, run by the Langevin integrator (msg = '' when fine).
  subroutine noise_rules(sc, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(out) :: msg
    msg = ''
    if (.not. (sc%noise >= 0 .and. sc%noise <= huge(1.0_dp))) then
      msg = 'field ''noise'' must be a finite temperature >= 0 (in units of eps), got ' // &
            trim(num_text(sc%noise)); return
    end if
    if (sc%seed < 0_int64 .or. sc%seed > 9007199254740992_int64) then   ! 2^53 (seed_limit), compared whole
      msg = 'field ''seed'' must be a whole number from 0 to 2^53'; return
    end if
    if (sc%noise == 0) return
    if (.not. (sc%damping > 0)) then
      msg = 'field ''noise'' needs damping > 0: the thermal force sqrt(2 damping noise) xi(t) comes with ' // &
            'the friction (fluctuation-dissipation); without damping there is no temperature'; return
    end if
    if (sc%cord /= 'rigid' .or. sc%guide /= 'none' .or. sc%gravity /= 'uniform') then
      msg = 'field ''noise'': thermal noise is implemented for the rigid pendulum only (cord = ''rigid'', ' // &
            'guide = ''none'', gravity = ''uniform'')'; return
    end if
    if (sc%friction /= 0 .or. sc%drag /= 0) then
      msg = 'fields ''noise'' and ''' // trim(merge('friction', 'drag    ', sc%friction /= 0)) // ''': the ' // &
            'Langevin integrator splits off the linear damping only; a velocity-dependent friction or drag ' // &
            'with thermal noise is not implemented'; return
    end if
    if (sc%method /= 'auto') then
      msg = 'field ''method'': a scene with noise runs the Langevin integrator (BAOAB, fixed step dt); ' // &
            'method must be ''auto'', got ''' // trim(sc%method) // ''''; return
    end if
  end subroutine noise_rules

  !> The cycloidal guide, the gravity fields, the flexible cord, and the
  !> method 'exact' (msg = '' when fine).
  subroutine model_rules(sc, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(out) :: msg
    call cycloid_rules(sc, msg)
    if (len_trim(msg) == 0) call gravity_rules(sc, msg)
    if (len_trim(msg) == 0) call cord_rules(sc, msg)
    if (len_trim(msg) == 0) call method_rules(sc, msg)
  end subroutine model_rules

  !> Huygens' cycloidal guide (kernel/models/pendula_cycloid.f90): its radius, the models it excludes,
  !> its closed form only, its amplitude below the cusps.
  subroutine cycloid_rules(sc, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(out) :: msg
    real(dp) :: w2, s0, sd0, c
    msg = ''
    if (.not. (sc%cycloid_radius > 0)) then
      msg = 'field ''cycloid_radius'' must be positive (R / l), got ' // trim(num_text(sc%cycloid_radius)); return
    end if
    if (sc%guide /= 'cycloid' .and. sc%cycloid_radius /= 0.25_dp) then
      msg = 'field ''cycloid_radius'' is used only with guide = ''cycloid'''; return
    end if
    if (sc%guide /= 'cycloid') return
    if (sc%cord /= 'rigid') then
      msg = 'field ''cord'': the cycloidal guide wraps an inextensible cord of length 4R; ' // &
            'cord = ''flexible'' has no meaning on it'; return
    end if
    if (sc%gravity /= 'uniform') then
      msg = 'field ''gravity'': the cycloidal guide is isochronous only in uniform gravity; ' // &
            'non-uniform gravity with guide = ''cycloid'' is not a model of pendula'; return
    end if
    if (sc%method /= 'auto' .and. sc%method /= 'exact') then
      msg = 'field ''method'': the cycloidal pendulum is solved in closed form (method ''auto'' or ' // &
            '''exact''), never integrated; got ''' // trim(sc%method) // ''''; return
    end if
    if (.not. (abs(sc%theta0) <= half_pi)) then
      msg = 'field ''theta0'': on the cycloid |theta0| <= pi/2 (the cusps, |s| = 4R), got ' // &
            trim(num_text(sc%theta0)); return
    end if
    if (sc%damping == 0 .and. sc%drive_amplitude == 0) then
      ! without damping or drive the amplitude about the torque's centre c is constant
      w2 = cycloid_omega2(sc%eps, sc%cycloid_radius)
      s0 = 4.0_dp * sc%cycloid_radius * sin(sc%theta0)
      sd0 = 4.0_dp * sc%cycloid_radius * cos(sc%theta0) * sc%v0
      c = sc%torque / w2
      if (abs(c) + hypot(s0 - c, sd0 / sqrt(w2)) > 4.0_dp * sc%cycloid_radius) then
        msg = 'field ''v0'': the cycloidal pendulum''s orbit (no damping, no drive) reaches the cusps ' // &
              '(|s| = 4R, |theta| = pi/2): start lower, slower, or with less torque'; return
      end if
    end if
  end subroutine cycloid_rules

  !> The gravity fields (kernel/models/pendula_gravity.f90): each field's parameter, only with its field.
  subroutine gravity_rules(sc, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(out) :: msg
    msg = ''
    if (sc%gravity == 'inverse-square') then
      if (.not. (sc%gravity_distance > 1)) then
        msg = 'field ''gravity_distance'' (D / l, the point mass below the pivot) must be > 1 with ' // &
              'gravity = ''inverse-square'', got ' // trim(num_text(sc%gravity_distance)); return
      end if
    else if (sc%gravity_distance /= 0) then
      msg = 'field ''gravity_distance'' is used only with gravity = ''inverse-square'''; return
    end if
    if (sc%gravity == 'linear') then
      if (.not. (sc%gravity_gradient < 0.5_dp)) then
        msg = 'field ''gravity_gradient'' (kappa in g (1 - kappa h / l)) must be < 0.5 so that gravity ' // &
              'points down at the top, got ' // trim(num_text(sc%gravity_gradient)); return
      end if
    else if (sc%gravity_gradient /= 0) then
      msg = 'field ''gravity_gradient'' is used only with gravity = ''linear'''; return
    end if
    if (sc%gravity /= 'uniform' .and. sc%method == 'gsl-rk8pd') then
      msg = 'field ''method'': gsl-rk8pd does not take a non-uniform gravity field; use dop853 or auto'; return
    end if
  end subroutine gravity_rules

  !> Garfinkel's flexible cord (kernel/models/pendula_cord.f90): forward in time, integrated between
  !> flights by a method with dense output.
  subroutine cord_rules(sc, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(out) :: msg
    msg = ''
    if (sc%cord /= 'flexible') return
    if (.not. (sc%t_start >= 0 .and. sc%t_end >= sc%t_start)) then
      msg = 'field ''t_start'': a flexible cord runs forward only (0 <= t_start <= t_end)'; return
    end if
    if (sc%method /= 'auto' .and. sc%method /= 'exact' .and. sc%method /= 'dopri5' .and. &
        sc%method /= 'dop853') then
      msg = 'field ''method'': a flexible cord is integrated between flights by dopri5 or dop853 (auto: ' // &
            'dop853), whose dense output locates the tension event; got ''' // trim(sc%method) // ''''; return
    end if
  end subroutine cord_rules

  !> The method's own needs: a step for the fixed-step methods, a model with a closed form for 'exact'.
  subroutine method_rules(sc, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(out) :: msg
    msg = ''
    select case (trim(sc%method))
    case ('rk4', 'verlet', 'yoshida4', 'yoshida6', 'yoshida8', 'gauss4', 'gauss6')
      if (.not. (sc%dt > 0)) then
        msg = 'field ''dt'': fixed-step methods need dt > 0 (method ''' // trim(sc%method) // ''')'; return
      end if
    end select
    if (sc%method == 'exact') then
      if (sc%gravity /= 'uniform' .or. (sc%guide /= 'cycloid' .and. (sc%damping /= 0 .or. sc%torque /= 0 .or. &
          sc%drive_amplitude /= 0 .or. sc%pivot_amplitude /= 0))) then
        msg = 'field ''method'': ''exact'' answers only the conservative rigid pendulum, the flexible cord ' // &
              'and the cycloidal guide, but the scene names ' // trim(scene_effects(sc)); return
      end if
    end if
  end subroutine method_rules

  !> The rules of one run of the scene (the scene itself, or each member of
  !> its sweep): its fields' values and what its outputs need.
  subroutine check_member(m, msg)
    type(scene_t), intent(in) :: m
    character(len=*), intent(out) :: msg
    type(pendulum_orbit) :: o
    integer :: st
    call value_rules(m, msg)
    if (len_trim(msg) > 0) return
    if (wants(m, 'period') .or. wants(m, 'omega') .or. wants(m, 'theta_max')) then
      if (len_trim(scene_effects(m)) > 0 .and. .not. scene_has_orbit_facts(m)) then
        msg = 'field ''outputs'': period/omega/theta_max are facts of the exact conservative orbit; the ' // &
              'scene names ' // trim(scene_effects(m)); return
      end if
    end if
    if (wants(m, 'series') .or. wants(m, 'lindstedt')) then
      if (len_trim(scene_effects(m)) > 0) then
        msg = 'field ''outputs'': series/lindstedt are the conservative rigid pendulum''s in uniform gravity; ' // &
              'the scene names ' // trim(scene_effects(m)); return
      end if
      if (m%sweep /= 'theta0' .or. m%v0 /= 0) then
        msg = 'field ''outputs'': series/lindstedt compare the period or motion released from rest over ' // &
              'amplitudes: sweep theta0 with v0 = 0'; return
      end if
      if (wants(m, 'lindstedt') .and. .not. (abs(m%theta0) < pi)) then
        msg = 'field ''outputs'': lindstedt''s amplitude theta0 must satisfy |theta0| < pi (a libration)'; return
      end if
    end if
    if (wants(m, 'spectrum') .and. len_trim(scene_effects(m)) == 0) then
      call orbit_setup(m%theta0, m%v0, m%eps, o, st)
      if (st /= 0) then
        msg = 'field ''outputs'': ''spectrum'': the initial state has no orbit'; return
      end if
      if (o%regime == regime_separatrix) then
        msg = 'field ''outputs'': ''spectrum'': the separatrix has no spectrum (infinite period)'; return
      end if
    end if
  contains
    pure logical function wants(s, what)
      type(scene_t), intent(in) :: s
      character(len=*), intent(in) :: what
      wants = any(s%outputs(1:s%n_outputs) == what)
    end function wants
  end subroutine check_member

  !> The sweep grid's fields (msg = '' when fine).
  subroutine check_grid(sc, msg)
    type(scene_t), intent(inout) :: sc
    character(len=*), intent(out) :: msg
    character(len=16), parameter :: griddable(12) = [character(len=16) :: 'v0', 'theta0', 'eps', &
      'damping', 'torque', 'drive_amplitude', 'drive_frequency', 'drive_phase', 'pivot_amplitude', &
      'pivot_frequency', 'friction', 'drag']
    character(len=16), parameter :: measures(5) = [character(len=16) :: 'final_well', 'mean_velocity', &
      'locked', 'poincare', 'lyapunov']
    character(len=1) :: kc
    integer :: k, nv, nr, j
    real(dp) :: ends(2)
    character(len=512) :: m2
    type(scene_t), allocatable :: m
    msg = ''
    do k = 1, sc%n_grid
      if (.not. any(griddable == sc%grid(k))) then
        msg = 'field ''grid'': cannot sweep ''' // trim(sc%grid(k)) // '''; one of v0, theta0, eps, damping, ' // &
              'torque, drive_amplitude, drive_frequency, drive_phase, pivot_amplitude, pivot_frequency, ' // &
              'friction, drag' // &
              suggest(sc%grid(k), griddable); return
      end if
      if (any(sc%grid(1:k - 1) == sc%grid(k))) then
        msg = 'field ''grid'' names an axis twice'; return
      end if
    end do
    do k = 1, 3
      write(kc, '(i1)') k
      nv = sc%grid_nv(k)
      nr = sc%grid_nr(k)
      if (k > sc%n_grid) then
        if (nv + nr > 0) then
          msg = 'field ''grid' // kc // ''' or ''grid' // kc // '_range'' is given but ''grid'' names fewer axes'
          return
        end if
        cycle
      end if
      if ((nv > 0) .eqv. (nr > 0)) then
        msg = 'axis ' // kc // ' (''' // trim(sc%grid(k)) // '''): give exactly one of ''grid' // kc // &
              ''' (values) or ''grid' // kc // '_range'' (start, stop, count)'; return
      end if
      if (nv > 0) then
        if (.not. all(finite(sc%grid_values(1:nv, k)))) then
          msg = 'field ''grid' // kc // ''' must be finite numbers'; return
        end if
        if (sc%grid(k) == 'drive_phase' .and. .not. all(abs(sc%grid_values(1:nv, k)) <= drive_phase_limit)) then
          msg = phase_text('field ''grid' // kc // ''' (drive_phase)', &
                           sc%grid_values(maxloc(abs(sc%grid_values(1:nv, k)), 1), k)); return
        end if
        sc%grid_n(k) = nv
      else
        if (nr /= 3) then
          msg = 'field ''grid' // kc // '_range'' must be start, stop, count (count a whole number >= 1)'; return
        end if
        if (.not. all(finite(sc%grid_range(:, k)))) then
          msg = 'field ''grid' // kc // '_range'' must be finite numbers'; return
        end if
        if (sc%grid_range(3, k) /= aint(sc%grid_range(3, k)) .or. sc%grid_range(3, k) < 1.0_dp .or. &
            sc%grid_range(3, k) > 1.0e8_dp) then
          msg = 'field ''grid' // kc // '_range'' must be start, stop, count (count a whole number >= 1)'; return
        end if
        if (sc%grid(k) == 'drive_phase' .and. .not. all(abs(sc%grid_range(1:2, k)) <= drive_phase_limit)) then
          msg = phase_text('field ''grid' // kc // '_range'' (drive_phase)', &
                           sc%grid_range(maxloc(abs(sc%grid_range(1:2, k)), 1), k)); return
        end if
        sc%grid_n(k) = nint(sc%grid_range(3, k))
      end if
      ! every grid value must make a valid scene, as a member of the grid (the rules of value_rules: the
      ! same refusal as pendula.sweep's, which asks them of Scene.replace): the ends of each axis
      if (nv > 0) then
        ends = [minval(sc%grid_values(1:nv, k)), maxval(sc%grid_values(1:nv, k))]
      else
        ends = sc%grid_range(1:2, k)
      end if
      do j = 1, 2
        allocate(m, source=sc)
        call set_field(m, sc%grid(k), ends(j))
        call value_rules(m, m2)
        deallocate(m)
        if (len_trim(m2) > 0) then
          msg = 'field ''grid' // kc // ''' (' // trim(sc%grid(k)) // ' = ' // trim(num_text(ends(j))) // '): ' // &
                trim(m2); return
        end if
      end do
    end do
    if (len_trim(sc%measure) > 0 .and. .not. any(measures == sc%measure)) then
      msg = 'field ''measure'' must be one of final_well, mean_velocity, locked, poincare, lyapunov; got ''' &
            // trim(sc%measure) // '''' // suggest(sc%measure, measures); return
    end if
    if (sc%n_grid > 0 .and. len_trim(sc%measure) == 0) then
      msg = 'field ''grid'' is given but ''measure'' is not'; return
    end if
    if (.not. (sc%sweep_t_max > 0.0_dp)) then
      msg = 'field ''sweep_t_max'' must be > 0, got ' // trim(num_text(sc%sweep_t_max)); return
    end if
    if (.not. (sc%sweep_transient >= 0.0_dp)) then
      msg = 'field ''sweep_transient'' must be >= 0, got ' // trim(num_text(sc%sweep_transient)); return
    end if
    if (sc%sweep_samples < 1 .or. sc%sweep_samples > 10000000) then
      msg = 'field ''sweep_samples'' must be between 1 and 1e7, got ' // trim(int_text(sc%sweep_samples)); return
    end if
  end subroutine check_grid

  !> Does the scene's model give the facts of its orbit (period, omega,
  !> theta_max) in closed form or by quadrature?  A conservative cycloid
  !> (the guide, perhaps a torque) or a scene whose only effect is a
  !> non-uniform gravity field; the rigid pendulum without effects too
  !> (not asked here: its facts are the exact orbit's).
  pure logical function scene_has_orbit_facts(sc)
    type(scene_t), intent(in) :: sc
    scene_has_orbit_facts = (sc%guide == 'cycloid' .and. sc%damping == 0 .and. sc%drive_amplitude == 0) .or. &
                            trim(scene_effects(sc)) == 'gravity'
  end function scene_has_orbit_facts

  !> The effects a scene names, comma separated ('' when none).
  pure function scene_effects(sc) result(s)
    type(scene_t), intent(in) :: sc
    character(len=128) :: s
    s = ''
    if (sc%damping /= 0) call add('damping')
    if (sc%torque /= 0) call add('torque')
    if (sc%drive_amplitude /= 0) call add('drive')
    if (sc%cord /= 'rigid') call add('cord')
    if (sc%guide /= 'none') call add('guide')
    if (sc%gravity /= 'uniform') call add('gravity')
    if (sc%friction /= 0) call add('friction')
    if (sc%drag /= 0) call add('drag')
    if (sc%pivot_amplitude /= 0) call add('pivot')
    if (sc%noise /= 0) call add('noise')
  contains
    pure subroutine add(w)
      character(len=*), intent(in) :: w
      if (len_trim(s) > 0) then
        s = trim(s) // ', ' // w
      else
        s = w
      end if
    end subroutine add
  end function scene_effects

  !> One line per field, for the header of output files.
  function scene_summary(sc) result(s)
    type(scene_t), intent(in) :: sc
    character(len=2048) :: s
    character(len=1024) :: tmp
    integer :: i
    write(s, '(a, es24.16e3, a, es24.16e3, a, es24.16e3, a, es24.16e3, a, es24.16e3, a, i0)') &
      'eps = ', sc%eps, ', theta0 = ', sc%theta0, ', v0 = ', sc%v0, ', t_start = ', sc%t_start, &
      ', t_end = ', sc%t_end, ', n_samples = ', sc%n_samples
    write(tmp, '(a, es24.16e3, a, es24.16e3, a, es24.16e3, a, es24.16e3, a, es24.16e3)') &
      'damping = ', sc%damping, ', torque = ', sc%torque, ', drive_amplitude = ', sc%drive_amplitude, &
      ', drive_frequency = ', sc%drive_frequency, ', drive_phase = ', sc%drive_phase
    s = trim(s) // new_line('a') // '# ' // trim(tmp)
    s = trim(s) // new_line('a') // '# cord = ' // trim(sc%cord) // ', guide = ' // trim(sc%guide) // &
        ', gravity = ' // trim(sc%gravity) // ', method = ' // trim(sc%method)
    tmp = ''
    do i = 1, sc%n_outputs
      if (len_trim(sc%outputs(i)) > 0) tmp = trim(tmp) // ' ' // trim(sc%outputs(i))
    end do
    s = trim(s) // new_line('a') // '# outputs =' // trim(tmp)
    if (sc%n_sweep > 0) then
      write(tmp, '(a, i0, a)') 'sweep = ' // trim(sc%sweep) // ' over ', sc%n_sweep, ' values'
      s = trim(s) // new_line('a') // '# ' // trim(tmp)
    end if
    if (sc%friction /= 0 .or. sc%drag /= 0 .or. sc%pivot_amplitude /= 0) then
      write(tmp, '(a, es24.16e3, a, es24.16e3, a, es24.16e3, a, es24.16e3)') 'friction = ', sc%friction, &
        ', drag = ', sc%drag, ', pivot_amplitude = ', sc%pivot_amplitude, ', pivot_frequency = ', sc%pivot_frequency
      s = trim(s) // new_line('a') // '# ' // trim(tmp)
    end if
    if (sc%noise /= 0) then
      write(tmp, '(a, es24.16e3, a, i0, a, es24.16e3)') 'noise = ', sc%noise, ', seed = ', sc%seed, ', dt = ', sc%dt
      s = trim(s) // new_line('a') // '# ' // trim(tmp)
    end if
    if (len_trim(sc%name) > 0) s = trim(s) // new_line('a') // '# name = ' // trim(sc%name)
  end function scene_summary

end module pendula_scene_rules
