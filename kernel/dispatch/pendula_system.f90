!> The system contract, declared once: the systems (models) a scene can
!> select, the effects a scene can turn on, the time scales its fields create,
!> what counts as a periodic forcing, and which tool honours which effect on
!> which system (the capability table).
!>
!> Every door reads this module: the dispatcher (simulate_scene), the sweeps,
!> pendula-run (its scenes are the rows 'simulate' and 'sweep:MEASURE'), and
!> the Python layer through the binding (capability_check_v,
!> capability_table_v, scene_time_scales_v, scene_forcing_v).  No tool keeps
!> its own list of the fields it takes: a tool asks capability_check, which
!> answers "honoured", or refuses with a message naming the field.
!>
!> A row of the table says, for one tool on one system, the effects it
!> honours (they change its answer), those it will honour but does not yet
!> ('planned': NotImplementedError in Python), the effects it needs (at least
!> one of them on: 'drive pivot' for the tools of the stroboscopic map), and
!> why the rest are refused.  A tool with no row for a system does not run
!> that system.  A user's force ('force') is an argument of some tools, not a
!> scene field; it is honoured where the row says so.
!>
!> Adding a system: one kernel module (kernel/models), one entry in
!> `registry`, its rows in `capabilities`, one case in simulate_scene.
module pendula_system
  use pendula_kinds, only: dp, two_pi
  use pendula_scene, only: scene_t, scene_effects
  use pendula_gravity, only: gk_uniform, gk_inverse_square, gk_linear
  use pendula_time_scales, only: time_rates, fastest_rate, n_scales, scale_names
  implicit none
  private
  public :: model_info_t, registry, select_model, capability_t, capabilities, capability_check, &
    capability_check_fields, &
    capability_table, scene_forcing, scene_rates, scene_gravity, effect_names, effect_fields, scene_effect_on, &
    any_effect

  integer, parameter, public :: sys_ok = 0, sys_model_clash = 15, sys_not_implemented = 14
  !> capability_check's answers: honoured, refused (a ValueError naming the field), not implemented (for
  !> a system the tool does not run, or an effect it will honour: NotImplementedError)
  integer, parameter, public :: cap_ok = 0, cap_refused = 2, cap_not_implemented = 3, cap_unknown_tool = 4

  !> What a model is, for users (`pendula models`) and for the dispatcher.
  type :: model_info_t
    character(len=16) :: name = ''
    !> the scene fields that select it
    character(len=48) :: selector = ''
    !> the effects it accepts, and those under which its exact path still answers
    character(len=64) :: effects = '', exact_with = ''
    !> 'exact', 'integrated' or 'hybrid' (exact pieces joined at events)
    character(len=12) :: path = ''
    logical :: implemented = .false.
    character(len=72) :: summary = ''
    !> the state's size and what it holds
    character(len=32) :: state = ''
    !> the parameters (scene fields, or the arguments of the system's class)
    character(len=160) :: parameters = ''
    !> which of its fields turns each effect on ('effect:field' pairs; blank: the scene's fields, effect_fields)
    character(len=80) :: effect_map = ''
    !> the time scales its fields create (the scene's models: pendula_time_scales computes them)
    character(len=96) :: time_scales = ''
  end type model_info_t

  integer, parameter, public :: mid_rigid = 1, mid_cord = 2, mid_cycloid = 3, mid_gravity = 4, &
    mid_network = 5, mid_double = 6, mid_foucault = 7, mid_spherical = 8
  !> the systems a Scene selects (the rest are built by their own class: pendula.Network, ...)
  integer, parameter, public :: n_scene_models = 4
  character(len=*), parameter :: state2 = '2: theta, dtheta/dt', &
    forced = 'damping torque drive_amplitude drive_frequency', &
    smooth_fields = 'friction drag pivot_amplitude pivot_frequency', &
    scene_scales = 'the scene''s (pendula.time_scales): oscillation, damping, drive, pivot, torque, ...'
  type(model_info_t), parameter :: registry(8) = [ &
    model_info_t('rigid', "cord='rigid' guide='none' gravity='uniform'", &
                 'damping torque drive friction drag pivot noise force', &
                 '(none)', 'exact', .true., 'rigid pendulum, Jacobi elliptic solution in every regime', &
                 state2, 'eps theta0 v0 ' // forced // ' ' // smooth_fields // ' noise seed', '', scene_scales), &
    model_info_t('cord', "cord='flexible'", 'damping torque drive', '(none)', 'hybrid', .true., &
                 'bob on a flexible cord (Garfinkel): circle, free flight, jerk', &
                 '2 or 4: theta, dtheta/dt; x, y', 'cord eps theta0 v0 ' // forced, '', scene_scales), &
    model_info_t('cycloid', "guide='cycloid'", 'damping torque drive', 'damping torque drive', 'exact', &
                 .true., 'cycloidal guide (Huygens): isochronous, closed form', state2, &
                 'guide eps theta0 v0 ' // forced, '', scene_scales), &
    model_info_t('gravity', "gravity='inverse-square' or 'linear'", &
                 'damping torque drive friction drag pivot force', '(none)', &
                 'integrated', .true., 'non-uniform gravity: energy, quadrature period, integrators', &
                 state2, 'gravity gravity_distance gravity_gradient eps theta0 v0 ' // forced // ' ' // smooth_fields, &
                 '', scene_scales), &
    model_info_t('network', 'pendula.Network(n, coupling or topology)', 'damping torque drive noise', '(none)', &
                 'integrated', .true., 'N phases coupled by springs (junction arrays, SQUIDs)', &
                 '2N: phi, dphi/dt', 'n eps damping mass bias drive_amplitude drive_frequency drive_phase ' // &
                 'coupling topology strength offset temperature', &
                 'damping:damping torque:bias drive:drive_amplitude noise:temperature', &
                 'network_time_rates: sqrt(eps/C), sqrt((eps+2k)/C), beta/C, Omega, sqrt(A/C), sqrt(tau/C), v'), &
    model_info_t('double', 'pendula.DoublePendulum(m1, m2, l1, l2, g)', 'damping', '(none)', 'integrated', &
                 .true., 'double pendulum: chaos, flip-time map, Lyapunov spectrum', &
                 '4: theta1, theta2, p1, p2', 'm1 m2 l1 l2 g rods damping', 'damping:damping', &
                 'double_time_rates: the fast normal mode, the damping rate, the whirl sqrt(2H / lambda_min)'), &
    model_info_t('foucault', 'pendula.FoucaultPendulum(latitude, ...)', 'damping', '(none)', 'integrated', &
                 .true., 'spherical pendulum on the turning Earth: Coriolis and Airy precession', &
                 '6: r, dr/dt (cartesian)', 'latitude length g earth_rate damping anisotropy', 'damping:damping', &
                 'sqrt(g / length), the Earth''s rate times sin(latitude), the damping rate'), &
    model_info_t('spherical', 'pendula.spherical_orbit(theta0, ...)', '(none)', '(none)', 'exact', .true., &
                 'spherical pendulum: Jacobi elliptic and Carlson R_J closed form', &
                 '4: theta, phi and their rates', 'theta0 theta_dot0 phi_dot0 eps', '', &
                 'sqrt(eps): the polar period (closed form, any t at one cost)')]

  !> The effects, and the scene field that turns each on ('force' is a tool's argument).
  integer, parameter, public :: n_effects = 8
  character(len=8), parameter :: effect_names(n_effects) = [character(len=8) :: 'damping', 'torque', 'drive', &
    'friction', 'drag', 'pivot', 'noise', 'force']
  character(len=16), parameter :: effect_fields(n_effects) = [character(len=16) :: 'damping', 'torque', &
    'drive_amplitude', 'friction', 'drag', 'pivot_amplitude', 'noise', 'force']

  !> One row of the capability table: one tool on one system.
  type :: capability_t
    character(len=24) :: tool = ''
    character(len=12) :: system = ''
    !> the effects it honours, those planned (not implemented yet), those it needs (one of them on)
    character(len=56) :: honours = '', planned = '', needs = ''
    !> why the other effects are refused (completes "TOOL does not honour field 'F' (E) on the S model: ")
    character(len=120) :: note = ''
  end type capability_t

  character(len=*), parameter :: all8 = 'damping torque drive friction drag pivot noise force', &
    deterministic = 'damping torque drive friction drag pivot force', &
    conservative = 'a fact of the conservative orbit (its motion with effects: simulate; periods by events: numerical_period)', &
    smooth = 'its Newton and monodromy need a smooth deterministic flow (dry friction jumps at v = 0; noise is random)', &
    density_note = 'the density of the angle is a property of a periodic conservative orbit', &
    sweep_note = 'the measure asks a deterministic question of the flow (noise: measure ''mean_velocity'')'

  integer, parameter :: n_rows = 53
  type(capability_t), parameter :: capabilities(n_rows) = [ &
    capability_t('simulate', 'rigid', all8, '', '', ''), &
    capability_t('simulate', 'cord', 'damping torque drive', '', '', 'the flexible cord takes damping, torque, drive'), &
    capability_t('simulate', 'cycloid', 'damping torque drive', '', '', 'the cycloid is solved in closed form'), &
    capability_t('simulate', 'gravity', deterministic, '', '', 'noise is implemented for the rigid pendulum'), &
    capability_t('find_events', 'rigid', 'damping torque drive drag pivot', 'friction', '', &
                 'events are located on the deterministic flow (noise: pendula.simulate)'), &
    capability_t('find_events', 'cord', 'damping torque drive', '', '', 'events are located on the deterministic flow'), &
    capability_t('find_events', 'cycloid', 'damping torque drive', '', '', 'events are located on the closed form'), &
    capability_t('find_events', 'gravity', 'damping torque drive drag pivot', 'friction', '', &
                 'events are located on the deterministic flow'), &
    capability_t('period', 'rigid', '', '', '', conservative), &
    capability_t('period', 'cycloid', 'torque', '', '', conservative), &
    capability_t('period', 'gravity', '', '', '', conservative), &
    capability_t('numerical_period', 'rigid', '', '', '', conservative), &
    capability_t('numerical_period', 'cord', '', '', '', conservative), &
    capability_t('numerical_period', 'cycloid', 'torque', '', '', conservative), &
    capability_t('numerical_period', 'gravity', '', '', '', conservative), &
    capability_t('equilibria', 'rigid', 'damping torque drag', '', '', &
                 'rest points need an autonomous smooth deterministic flow'), &
    capability_t('equilibria', 'cord', 'damping torque', '', '', 'rest points need an autonomous flow'), &
    capability_t('equilibria', 'cycloid', 'damping torque', '', '', 'rest points need an autonomous flow'), &
    capability_t('equilibria', 'gravity', 'damping torque drag', '', '', &
                 'rest points need an autonomous smooth deterministic flow'), &
    capability_t('continue_equilibria', 'rigid', 'damping torque drag', '', '', &
                 'rest points need an autonomous smooth deterministic flow'), &
    capability_t('continue_equilibria', 'cord', 'damping torque', '', '', 'rest points need an autonomous flow'), &
    capability_t('continue_equilibria', 'cycloid', 'damping torque', '', '', 'rest points need an autonomous flow'), &
    capability_t('continue_equilibria', 'gravity', 'damping torque drag', '', '', &
                 'rest points need an autonomous smooth deterministic flow'), &
    capability_t('periodic_orbit', 'rigid', 'damping torque drive drag pivot force', '', 'drive pivot', smooth), &
    capability_t('continue_orbit', 'rigid', 'damping torque drive drag pivot', '', '', smooth), &
    capability_t('attractor_map', 'rigid', 'damping torque drive friction drag pivot', '', 'drive pivot', &
                 'attractors are those of the deterministic stroboscopic map'), &
    capability_t('attractor_continuation', 'rigid', 'damping torque drive friction drag pivot', '', 'drive pivot', &
                 'attractors are those of the deterministic stroboscopic map'), &
    capability_t('sweep:final_well', 'rigid', 'damping torque friction drag', '', '', &
                 'a final well is where an undriven orbit settles, judged by its energy'), &
    capability_t('sweep:mean_velocity', 'rigid', all8, '', '', ''), &
    capability_t('sweep:locked', 'rigid', 'damping torque friction drag', '', '', &
                 'locked asks whether an undriven orbit comes to rest, judged by its energy'), &
    capability_t('sweep:poincare', 'rigid', deterministic, '', 'drive pivot', sweep_note), &
    capability_t('sweep:lyapunov', 'rigid', 'damping torque drive drag pivot force', '', '', &
                 'its variational equations need a smooth deterministic flow (dry friction sticks; noise is random)'), &
    capability_t('sweep:attractor', 'rigid', 'damping torque drive friction drag pivot', '', 'drive pivot', &
                 'attractors are those of the deterministic stroboscopic map'), &
    capability_t('iv_curve', 'rigid', 'damping drive friction drag pivot noise', '', '', &
                 'iv_curve sets the torque itself (its torques argument): give the scene torque = 0'), &
    capability_t('angle_density', 'rigid', '', 'torque', '', density_note), &
    capability_t('angle_density', 'cycloid', 'torque', '', '', density_note), &
    capability_t('angle_density', 'gravity', '', 'torque', '', density_note), &
    capability_t('angle_cdf', 'rigid', '', 'torque', '', density_note), &
    capability_t('angle_cdf', 'cycloid', 'torque', '', '', density_note), &
    capability_t('angle_cdf', 'gravity', '', 'torque', '', density_note), &
    capability_t('gravity_orbit', 'rigid', '', '', '', conservative), &
    capability_t('gravity_orbit', 'gravity', '', '', '', conservative), &
    capability_t('friction_turning_points', 'rigid', 'friction torque', '', 'friction', &
                 'the exact energy balance holds for dry friction and a torque alone'), &
    capability_t('simulate', 'network', 'damping torque drive noise', '', '', ''), &
    capability_t('equilibrium', 'network', 'damping torque', '', '', 'a driven network has no rest points'), &
    capability_t('normal_modes', 'network', 'torque', '', '', &
                 'normal modes are those of the undriven, undamped network (damped: equilibrium''s eigenvalues)'), &
    capability_t('simulate', 'double', 'damping', '', '', ''), &
    capability_t('flip_map', 'double', 'damping', '', '', ''), &
    capability_t('lyapunov', 'double', 'damping', '', '', ''), &
    capability_t('poincare', 'double', 'damping', '', '', ''), &
    capability_t('simulate', 'foucault', 'damping', '', '', ''), &
    capability_t('precession', 'foucault', 'damping', '', '', ''), &
    capability_t('spherical_orbit', 'spherical', '', '', '', 'the closed form is of the conservative pendulum')]

contains

  !> The model a scene selects (status sys_model_clash when two are named;
  !> sys_not_implemented, with msg, when the model is not built yet).
  subroutine select_model(sc, id, status, msg)
    type(scene_t), intent(in) :: sc
    integer, intent(out) :: id, status
    character(len=*), intent(out) :: msg
    integer :: n
    status = sys_ok
    msg = ''
    id = mid_rigid
    n = 0
    if (sc%cord /= 'rigid') then
      id = mid_cord; n = n + 1
    end if
    if (sc%guide /= 'none') then
      id = mid_cycloid; n = n + 1
    end if
    if (sc%gravity /= 'uniform') then
      id = mid_gravity; n = n + 1
    end if
    if (n > 1) then
      status = sys_model_clash
      msg = 'the scene names more than one model (cord = ''' // trim(sc%cord) // ''', guide = ''' // &
            trim(sc%guide) // ''', gravity = ''' // trim(sc%gravity) // '''); pendula runs one at a time'
    else if (.not. registry(id)%implemented) then
      status = sys_not_implemented
      msg = 'the effect(s) ' // trim(scene_effects(sc)) // ' are not implemented in pendula yet (model ''' // &
            trim(registry(id)%name) // ''': cord = ''' // trim(sc%cord) // ''', guide = ''' // &
            trim(sc%guide) // ''', gravity = ''' // trim(sc%gravity) // ''')'
    end if
  end subroutine select_model

  !> Does the scene turn any effect on?  (A scene without one has nothing a tool could refuse.)
  pure logical function any_effect(sc)
    type(scene_t), intent(in) :: sc
    any_effect = sc%damping /= 0.0_dp .or. sc%torque /= 0.0_dp .or. sc%drive_amplitude /= 0.0_dp .or. &
                 sc%friction /= 0.0_dp .or. sc%drag /= 0.0_dp .or. sc%pivot_amplitude /= 0.0_dp .or. &
                 sc%noise /= 0.0_dp
  end function any_effect

  !> Is effect k on in the scene, or swept (its field named in `swept`, words separated by blanks)?
  !> force: a user's force is given.
  pure logical function scene_effect_on(sc, k, swept, force)
    type(scene_t), intent(in) :: sc
    integer, intent(in) :: k
    character(len=*), intent(in) :: swept
    logical, intent(in) :: force
    select case (k)
    case (1); scene_effect_on = sc%damping /= 0.0_dp
    case (2); scene_effect_on = sc%torque /= 0.0_dp
    case (3); scene_effect_on = sc%drive_amplitude /= 0.0_dp
    case (4); scene_effect_on = sc%friction /= 0.0_dp
    case (5); scene_effect_on = sc%drag /= 0.0_dp
    case (6); scene_effect_on = sc%pivot_amplitude /= 0.0_dp
    case (7); scene_effect_on = sc%noise /= 0.0_dp
    case default; scene_effect_on = force
    end select
    if (k < n_effects) scene_effect_on = scene_effect_on .or. has_word(swept, trim(effect_fields(k)))
  end function scene_effect_on

  !> Does `tool` honour every effect the scene turns on (and the fields swept
  !> over, and a user's force)?  status cap_ok, or cap_refused /
  !> cap_not_implemented with msg naming the field; cap_unknown_tool for a
  !> tool the table does not name.
  subroutine capability_check(sc, tool, swept, force, status, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(in) :: tool, swept
    logical, intent(in) :: force
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    integer :: id, r, k
    logical :: known, on(n_effects)
    character(len=16) :: sys
    msg = ''
    known = .false.
    do r = 1, n_rows
      if (capabilities(r)%tool == tool) known = .true.
    end do
    if (.not. known) then
      status = cap_unknown_tool
      msg = 'the capability table names no tool ''' // trim(tool) // ''''; return
    end if
    call select_model(sc, id, status, msg)
    if (status /= sys_ok) then
      status = cap_not_implemented; return
    end if
    sys = registry(id)%name
    do r = 1, n_rows
      if (capabilities(r)%tool == tool .and. capabilities(r)%system == sys) exit
    end do
    if (r > n_rows) then
      status = cap_not_implemented
      msg = trim(tool) // ' does not run the model ''' // trim(sys) // ''' (cord = ''' // trim(sc%cord) // &
            ''', guide = ''' // trim(sc%guide) // ''', gravity = ''' // trim(sc%gravity) // '''): ' // &
            trim(runs_on(tool))
      return
    end if
    do k = 1, n_effects
      on(k) = scene_effect_on(sc, k, swept, force)
    end do
    call row_verdict(r, id, on, status, msg)
  end subroutine capability_check

  !> Does `tool` honour every effect that the fields named in `fields` (blank-separated: the system's
  !> fields or arguments that are on, i.e. non-zero) turn on in `system`, a system built by its own class
  !> (pendula.Network, ...)?  The system's effect_map says which field turns which effect on.  status
  !> cap_ok, or cap_refused / cap_not_implemented with msg naming the field; cap_unknown_tool for a system,
  !> tool or field the table does not know (a fault of the caller, not of the user).
  subroutine capability_check_fields(system, tool, fields, status, msg)
    character(len=*), intent(in) :: system, tool, fields
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    integer :: id, r, k, a, b
    logical :: on(n_effects)
    msg = ''
    status = cap_unknown_tool
    do id = 1, size(registry)
      if (registry(id)%name == system) exit
    end do
    if (id > size(registry)) then
      msg = 'the registry names no system ''' // trim(system) // ''''; return
    end if
    do r = 1, n_rows
      if (capabilities(r)%tool == tool .and. capabilities(r)%system == system) exit
    end do
    if (r > n_rows) then
      msg = 'the capability table has no row for ' // trim(tool) // ' on the ' // trim(system) // ' model'; return
    end if
    on = .false.
    b = 0
    do
      call next_word(fields, b, a)
      if (a == 0) exit
      k = mapped_effect(id, fields(a:b))
      if (k > 0) then
        on(k) = .true.
      else if (.not. has_word(registry(id)%parameters, fields(a:b))) then
        msg = 'the ' // trim(system) // ' model has no field ''' // fields(a:b) // ''''; return
      end if
    end do
    call row_verdict(r, id, on, status, msg)
  end subroutine capability_check_fields

  !> The verdict of row r (tool on system id) on the effects turned on (on).
  subroutine row_verdict(r, id, on, status, msg)
    integer, intent(in) :: r, id
    logical, intent(in) :: on(n_effects)
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    type(capability_t) :: row
    character(len=16) :: sys
    character(len=24) :: tool
    logical :: any_need
    integer :: k
    msg = ''
    row = capabilities(r)
    sys = row%system
    tool = row%tool
    any_need = len_trim(row%needs) == 0
    do k = 1, n_effects
      if (.not. on(k)) cycle
      if (has_word(row%needs, trim(effect_names(k)))) any_need = .true.
      if (has_word(row%honours, trim(effect_names(k)))) cycle
      if (has_word(row%planned, trim(effect_names(k)))) then
        status = cap_not_implemented
        msg = trim(system_field_text(id, k)) // ': ' // trim(tool) // ' on the ' // trim(sys) // ' model with ' // &
              trim(effect_names(k)) // ' is not implemented yet (' // trim(row%note) // ')'
        return
      end if
      status = cap_refused
      if (k == 7 .and. id <= n_scene_models) then
        msg = trim(field_text(k)) // ': ' // trim(tool) // ' does not honour thermal noise (noise = T > 0): ' // &
              'it asks a deterministic question; set noise = 0 (noisy runs: pendula.simulate, ' // &
              'sweep(measure=''mean_velocity''), iv_curve)'
      else
        msg = trim(system_field_text(id, k)) // ': ' // trim(tool) // ' does not honour ' // &
              trim(merge('a user force', effect_names(k) // '    ', k == n_effects)) // &
              ' on the ' // trim(sys) // ' model: ' // trim(row%note)
      end if
      return
    end do
    if (.not. any_need) then
      status = cap_refused
      msg = trim(needs_text(row%needs)) // ': ' // trim(tool) // ' needs ' // trim(needs_words(row%needs)) // &
            '; the scene has none'
      return
    end if
    status = cap_ok
  end subroutine row_verdict

  !> The field of system id that turns effect k on, as a message names it.
  pure function system_field_text(id, k) result(s)
    integer, intent(in) :: id, k
    character(len=40) :: s
    integer :: a, b, c
    character(len=80) :: map
    s = field_text(k)
    map = registry(id)%effect_map
    b = 0
    do
      call next_word(map, b, a)
      if (a == 0) exit
      c = a + index(map(a:b), ':') - 1
      if (map(a:c - 1) == effect_names(k)) then
        s = 'field ''' // map(c + 1:b) // ''''
        return
      end if
    end do
  end function system_field_text

  !> The effect that field `f` of system id turns on (its effect_map), 0 for none.
  pure integer function mapped_effect(id, f)
    integer, intent(in) :: id
    character(len=*), intent(in) :: f
    integer :: a, b, c, k
    character(len=80) :: map
    mapped_effect = 0
    map = registry(id)%effect_map
    b = 0
    do
      call next_word(map, b, a)
      if (a == 0) exit
      c = a + index(map(a:b), ':') - 1
      if (map(c + 1:b) /= f) cycle
      do k = 1, n_effects
        if (map(a:c - 1) == effect_names(k)) mapped_effect = k
      end do
      return
    end do
  end function mapped_effect

  !> The next blank-separated word of `list` after position b: list(a:b); a = 0 when there is none.
  pure subroutine next_word(list, b, a)
    character(len=*), intent(in) :: list
    integer, intent(inout) :: b
    integer, intent(out) :: a
    integer :: i
    a = 0
    do i = b + 1, len(list)
      if (list(i:i) /= ' ') exit
    end do
    if (i > len(list)) return
    a = i
    b = index(list(a:) // ' ', ' ') + a - 2
  end subroutine next_word

  !> The systems a tool runs, for its refusal.
  function runs_on(tool) result(s)
    character(len=*), intent(in) :: tool
    character(len=96) :: s
    integer :: r
    s = 'it runs the model(s)'
    do r = 1, n_rows
      if (capabilities(r)%tool == tool) s = trim(s) // ' ' // trim(capabilities(r)%system)
    end do
    s = trim(s) // ' (`pendula models` prints the whole table)'
  end function runs_on

  pure function field_text(k) result(s)
    integer, intent(in) :: k
    character(len=40) :: s
    if (k == 3) then
      s = 'field ''drive_amplitude'''
    else if (k == 6) then
      s = 'field ''pivot_amplitude'''
    else if (k == n_effects) then
      s = 'argument ''force'''
    else
      s = 'field ''' // trim(effect_fields(k)) // ''''
    end if
  end function field_text

  pure function needs_text(needs) result(s)
    character(len=*), intent(in) :: needs
    character(len=64) :: s
    if (has_word(needs, 'drive')) then
      s = 'fields ''drive_amplitude'', ''pivot_amplitude'''
    else
      s = 'field ''' // trim(needs) // ''''
    end if
  end function needs_text

  pure function needs_words(needs) result(s)
    character(len=*), intent(in) :: needs
    character(len=120) :: s
    if (has_word(needs, 'drive')) then
      s = 'a periodic forcing (a drive, drive_amplitude and drive_frequency non-zero, or a vibrating pivot)'
    else
      s = trim(needs) // ' non-zero'
    end if
  end function needs_words

  !> Is `w` one of the blank-separated words of `list`?
  pure logical function has_word(list, w)
    character(len=*), intent(in) :: list, w
    integer :: i, n
    has_word = .false.
    n = len_trim(w)
    if (n == 0) return
    i = index(' ' // trim(list) // ' ', ' ' // w // ' ')
    has_word = i > 0
  end function has_word

  !> The capability table as text, one row per line: tool|system|honours|planned|needs|note.
  function capability_table() result(t)
    character(len=16384) :: t
    integer :: r
    t = ''
    do r = 1, n_rows
      t = trim(t) // trim(capabilities(r)%tool) // '|' // trim(capabilities(r)%system) // '|' // &
          trim(capabilities(r)%honours) // '|' // trim(capabilities(r)%planned) // '|' // &
          trim(capabilities(r)%needs) // '|' // trim(capabilities(r)%note) // new_line('a')
    end do
  end function capability_table

  !> The one definition of a periodically forced scene: omega, the angular
  !> frequency of its forcing (a drive with drive_amplitude and
  !> drive_frequency non-zero, a vibrating pivot with pivot_amplitude and
  !> pivot_frequency non-zero, or both at one frequency); status 0, or 1 (no
  !> forcing: autonomous, omega = 0) or 2 (a drive and a pivot at different
  !> frequencies: no common period, omega = 0).
  pure subroutine scene_forcing(sc, omega, status)
    type(scene_t), intent(in) :: sc
    real(dp), intent(out) :: omega
    integer, intent(out) :: status
    logical :: d, p
    d = sc%drive_amplitude /= 0.0_dp .and. sc%drive_frequency /= 0.0_dp
    p = sc%pivot_amplitude /= 0.0_dp .and. sc%pivot_frequency /= 0.0_dp
    omega = 0.0_dp
    status = 0
    if (d .and. p .and. abs(sc%drive_frequency) /= abs(sc%pivot_frequency)) then
      status = 2
    else if (d) then
      omega = abs(sc%drive_frequency)
    else if (p) then
      omega = abs(sc%pivot_frequency)
    else
      status = 1
    end if
  end subroutine scene_forcing

  !> The gravity field's kind and parameter (pendula_gravity) of a scene.
  pure subroutine scene_gravity(sc, kind, par)
    type(scene_t), intent(in) :: sc
    integer, intent(out) :: kind
    real(dp), intent(out) :: par
    select case (trim(sc%gravity))
    case ('inverse-square')
      kind = gk_inverse_square; par = sc%gravity_distance
    case ('linear')
      kind = gk_linear; par = sc%gravity_gradient
    case default
      kind = gk_uniform; par = 0.0_dp
    end select
  end subroutine scene_gravity

  !> The scene's time-scale rates (pendula_time_scales, in the order of its scale_names).
  pure function scene_rates(sc) result(r)
    type(scene_t), intent(in) :: sc
    real(dp) :: r(n_scales)
    integer :: gk
    real(dp) :: gp
    call scene_gravity(sc, gk, gp)
    r = time_rates(sc%eps, sc%damping, sc%torque, sc%drive_amplitude, sc%drive_frequency, sc%pivot_amplitude, &
                   sc%pivot_frequency, gk, gp, sc%friction, sc%drag, sc%v0)
  end function scene_rates

end module pendula_system
