!> Scenes for the batch executables: the namelist group &scene, read natively.
!>
!> Each "name = value" assignment is read on its own through an internal
!> namelist read, so that an unknown field, a misspelling or a value of the
!> wrong type is reported with the field's name and its line; then the ranges
!> are checked with the same rules as the Python layer (pendula/scene.py).
module pendula_scene
  use pendula_kinds, only: dp, nan_dp, half_pi
  implicit none
  private
  public :: scene_t, read_scene, parse_scene, scene_effects, scene_summary, max_sweep, max_outputs

  integer, parameter :: max_sweep = 4096, max_outputs = 16

  type :: scene_t
    real(dp) :: eps = 1.0_dp, theta0 = 0.0_dp, v0 = 0.0_dp
    real(dp) :: t_start = 0.0_dp, t_end = 20.0_dp
    integer :: n_samples = 1001
    real(dp) :: damping = 0.0_dp, torque = 0.0_dp
    real(dp) :: drive_amplitude = 0.0_dp, drive_frequency = 0.0_dp, drive_phase = 0.0_dp
    character(len=32) :: cord = 'rigid', guide = 'none', gravity = 'uniform', method = 'auto'
    real(dp) :: rtol = 1.0e-10_dp, atol = 1.0e-12_dp, dt = 0.0_dp
    character(len=16) :: outputs(max_outputs) = ''
    character(len=32) :: sweep = ''
    real(dp) :: sweep_values(max_sweep) = nan_dp
    integer :: n_sweep = 0
    character(len=256) :: name = ''
    ! issue 13: the cycloidal guide (R / l) and the gravity fields' parameters
    real(dp) :: cycloid_radius = 0.25_dp, gravity_distance = 0.0_dp, gravity_gradient = 0.0_dp
    ! the flexible cord (kernel/models/pendula_cord.f90)
    real(dp) :: restitution = 0.0_dp, min_flight = 0.0_dp
    integer :: max_flips = 100000
    ! sweeps over grids (issue 14): axes, values or (start, stop, count), measure
    character(len=32) :: grid(3) = ''
    integer :: n_grid = 0
    real(dp) :: grid_values(max_sweep, 3) = nan_dp, grid_range(3, 3) = nan_dp
    integer :: grid_n(3) = 0
    character(len=32) :: measure = ''
    real(dp) :: sweep_t_max = 2000.0_dp, sweep_transient = 200.0_dp
    integer :: sweep_samples = 100
  end type scene_t

contains

  !> Read and check a scene file.  status 0: ok; otherwise msg names the problem.
  subroutine read_scene(path, sc, status, msg)
    character(len=*), intent(in) :: path
    type(scene_t), intent(out) :: sc
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    character(len=:), allocatable :: text
    integer :: unit, ios, k
    logical :: inq
    status = 0
    msg = ''
    inquire(file=path, exist=inq)
    if (.not. inq) then
      status = 1; msg = trim(path) // ': cannot read scene file (no such file)'; return
    end if
    open(newunit=unit, file=path, status='old', action='read', access='stream', form='unformatted', &
         iostat=ios)
    if (ios /= 0) then
      status = 1; msg = trim(path) // ': cannot open scene file'; return
    end if
    inquire(unit=unit, size=k)
    allocate(character(len=max(k, 0)) :: text)
    if (k > 0) read(unit, iostat=ios) text
    close(unit)
    call parse_scene(text, path, sc, status, msg)
  end subroutine read_scene

  !> Parse and check the text of a scene (the group &scene); messages start
  !> with source.  The Python layer hands scenes to the kernel this way, so
  !> that both sides run one set of rules.
  subroutine parse_scene(text_in, source, sc, status, msg)
    character(len=*), intent(in) :: text_in, source
    type(scene_t), intent(out) :: sc
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    ! the namelist variables (same names as the fields)
    real(dp) :: eps, theta0, v0, t_start, t_end, damping, torque, drive_amplitude, &
                drive_frequency, drive_phase, rtol, atol, dt, g, length, cycloid_radius, gravity_distance, &
                gravity_gradient, restitution, min_flight, sweep_t_max, sweep_transient
    integer :: n_samples, max_flips, sweep_samples
    character(len=32) :: grid(3), measure
    real(dp) :: grid1(max_sweep), grid2(max_sweep), grid3(max_sweep), grid1_range(3), grid2_range(3), &
                grid3_range(3)
    ! one more element and far more characters than the scene holds: a longer
    ! list or string is refused with a message instead of being truncated
    character(len=1024) :: cord, guide, gravity, method, sweep
    character(len=1024) :: outputs(max_outputs + 1)
    real(dp) :: sweep_values(max_sweep + 1)
    character(len=1024) :: name
    namelist /scene/ eps, theta0, v0, t_start, t_end, n_samples, damping, torque, &
      drive_amplitude, drive_frequency, drive_phase, cord, guide, gravity, method, rtol, atol, dt, &
      outputs, sweep, sweep_values, name, g, length, cycloid_radius, gravity_distance, gravity_gradient, &
      restitution, max_flips, min_flight, &
      grid, grid1, grid2, grid3, grid1_range, grid2_range, grid3_range, measure, sweep_t_max, &
      sweep_transient, sweep_samples
    character(len=:), allocatable :: text
    character(len=:), allocatable :: buf
    character(len=512) :: iom
    integer :: ios, i, j, k, start, line, nseen, jj, kk
    character(len=64) :: fname, seen(64)
    character(len=16), parameter :: known_fields(41) = [character(len=16) :: 'eps', 'theta0', 'v0', &
      't_start', 't_end', 'n_samples', 'damping', 'torque', 'drive_amplitude', 'drive_frequency', &
      'drive_phase', 'cord', 'guide', 'gravity', 'method', 'rtol', 'atol', 'dt', 'outputs', 'sweep', &
      'sweep_values', 'name', 'g', 'length', 'cycloid_radius', 'gravity_distance', 'gravity_gradient', &
      'restitution', 'max_flips', 'min_flight', &
      'grid', 'grid1', 'grid2', 'grid3', 'grid1_range', 'grid2_range', 'grid3_range', 'measure', &
      'sweep_t_max', 'sweep_transient', 'sweep_samples']

    status = 0
    msg = ''
    eps = nan_dp; theta0 = sc%theta0; v0 = sc%v0; t_start = sc%t_start; t_end = sc%t_end
    n_samples = sc%n_samples; damping = 0; torque = 0; drive_amplitude = 0; drive_frequency = 0
    drive_phase = 0; cord = sc%cord; guide = sc%guide; gravity = sc%gravity; method = sc%method
    rtol = sc%rtol; atol = sc%atol; dt = 0; outputs = ''; sweep = ''; sweep_values = nan_dp
    name = ''; g = nan_dp; length = nan_dp
    cycloid_radius = 0.25_dp; gravity_distance = 0.0_dp; gravity_gradient = 0.0_dp
    restitution = 0.0_dp; max_flips = 100000; min_flight = 0.0_dp
    grid = ''; grid1 = nan_dp; grid2 = nan_dp; grid3 = nan_dp; grid1_range = nan_dp; grid2_range = nan_dp
    grid3_range = nan_dp; measure = ''; sweep_t_max = 2000.0_dp; sweep_transient = 200.0_dp
    sweep_samples = 100

    k = utf8_error_at(text_in)
    if (k > 0) then
      status = 1
      write(msg, '(a,i0,a)') trim(source) // ': not UTF-8 text (byte ', k, ' is not part of a UTF-8 character)'
      return
    end if
    text = text_in
    call strip_comments(text)
    ! the group: from '&scene' to the closing '/'
    i = index(lower(text), '&scene')
    if (i == 0) then
      status = 1; msg = trim(source) // ': a scene file must start with the group ''&scene'''; return
    end if
    if (verify(text(1:i - 1), ' ' // new_line('a') // achar(9) // achar(13)) > 0) then
      status = 1; msg = trim(source) // ': a scene file must start with the group ''&scene'''; return
    end if
    j = closing_slash(text, i + 6)
    if (j == 0) then
      status = 1; msg = trim(source) // ': the group ''&scene'' is not closed with ''/'''; return
    end if
    k = verify(text(j + 1:), ' ' // new_line('a') // achar(9) // achar(13))
    if (k > 0) then
      line = 1 + count_newlines(text(1:j + k))
      status = 1
      write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': text after the end ''/'' of the group ' // &
        '''&scene''; a scene file holds one group'
      return
    end if
    ! split the body into assignments at each "name =" outside quotes, read each alone
    start = 0
    nseen = 0
    k = i + 6
    do while (k < j)
      call next_assignment(text, k, j, start, fname)
      if (nseen == 0) then
        ! nothing but blanks and commas may stand before the first "name ="
        jj = merge(j, start, start == 0)
        kk = verify(text(i + 6:jj - 1), ' ,' // new_line('a') // achar(9) // achar(13))
        if (kk > 0) then
          status = 1
          write(msg, '(a,i0,a)') trim(source) // ', line ', 1 + count_newlines(text(1:i + 5 + kk)), &
            ': expected a field name followed by ''='''
          return
        end if
      end if
      if (start == 0) exit
      line = 1 + count_newlines(text(1:start))
      if (any(seen(1:nseen) == fname)) then
        status = 1
        write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // ''' is given twice'
        return
      end if
      nseen = min(nseen + 1, size(seen))
      seen(nseen) = fname
      ios = index(text(start:k - 1), '=')
      if (verify(text(start + ios:k - 1), ' ,' // new_line('a') // achar(9) // achar(13)) == 0) then
        status = 1
        write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // ''' has no value'
        return
      end if
      jj = bad_value_token(text(start + index(text(start:k - 1), '='):k - 1))
      if (jj > 0) then
        status = 1
        write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // &
          ''': cannot read value ''' // token_at(text(start + index(text(start:k - 1), '='):k - 1), jj) // ''''
        return
      end if
      buf = '&scene ' // text(start:k - 1) // ' /'
      read(buf, nml=scene, iostat=ios, iomsg=iom)
      if (ios /= 0) then
        status = 1
        if (.not. any(known_fields == fname)) then
          write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': unknown field ''' // trim(fname) // ''''
        else
          write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // &
            ''': cannot read its value (' // trim(iom) // ')'
        end if
        return
      end if
    end do

    if (count(sweep_values == sweep_values) > max_sweep) then
      status = 1
      write(msg, '(a,i0)') trim(source) // ': field ''sweep_values'' holds too many values; at most ', max_sweep
      return
    end if
    if (any(len_trim(outputs) > len(sc%outputs)) .or. len_trim(outputs(max_outputs + 1)) > 0) then
      status = 1
      write(msg, '(a,i0,a,i0,a)') trim(source) // ': field ''outputs'': at most ', max_outputs, &
        ' outputs of at most ', len(sc%outputs), ' characters'
      return
    end if
    if (len_trim(name) > len(sc%name)) then
      status = 1; msg = trim(source) // ': field ''name'' is longer than 256 characters'; return
    end if
    do i = 1, 5
      select case (i)
      case (1); fname = 'cord'; buf = cord
      case (2); fname = 'guide'; buf = guide
      case (3); fname = 'gravity'; buf = gravity
      case (4); fname = 'method'; buf = method
      case (5); fname = 'sweep'; buf = sweep
      end select
      if (len_trim(buf) > 32) then
        status = 1; msg = trim(source) // ': field ''' // trim(fname) // ''' is longer than 32 characters'; return
      end if
    end do
    sc%eps = eps; sc%theta0 = theta0; sc%v0 = v0; sc%t_start = t_start; sc%t_end = t_end
    sc%n_samples = n_samples; sc%damping = damping; sc%torque = torque
    sc%drive_amplitude = drive_amplitude; sc%drive_frequency = drive_frequency
    sc%drive_phase = drive_phase; sc%cord = lower(cord); sc%guide = lower(guide)
    sc%gravity = lower(gravity); sc%method = lower(method); sc%rtol = rtol; sc%atol = atol
    sc%dt = dt; sc%outputs = outputs(1:max_outputs); sc%sweep = lower(sweep); sc%sweep_values = sweep_values(1:max_sweep)
    sc%name = name
    sc%cycloid_radius = cycloid_radius; sc%gravity_distance = gravity_distance
    sc%gravity_gradient = gravity_gradient
    sc%restitution = restitution; sc%max_flips = max_flips; sc%min_flight = min_flight
    sc%n_sweep = count(sweep_values(1:max_sweep) == sweep_values(1:max_sweep))
    do i = 1, 3
      sc%grid(i) = lower(grid(i))
    end do
    sc%n_grid = count(len_trim(sc%grid) > 0)
    sc%grid_values(:, 1) = grid1; sc%grid_values(:, 2) = grid2; sc%grid_values(:, 3) = grid3
    sc%grid_range(:, 1) = grid1_range; sc%grid_range(:, 2) = grid2_range; sc%grid_range(:, 3) = grid3_range
    sc%measure = lower(measure); sc%sweep_t_max = sweep_t_max; sc%sweep_transient = sweep_transient
    sc%sweep_samples = sweep_samples
    call check(sc, g, length, status, msg)
    if (status == 0) call check_grid(sc, status, msg)
    if (status /= 0) msg = trim(source) // ': ' // trim(msg)
  end subroutine parse_scene

  !> Sweep grid fields (issue 14): the same rules as _validate_grid in pendula/scene.py.
  subroutine check_grid(sc, status, msg)
    type(scene_t), intent(inout) :: sc
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    character(len=16), parameter :: griddable(8) = [character(len=16) :: 'v0', 'theta0', 'eps', &
      'damping', 'torque', 'drive_amplitude', 'drive_frequency', 'drive_phase']
    character(len=16), parameter :: measures(5) = [character(len=16) :: 'final_well', 'mean_velocity', &
      'locked', 'poincare', 'lyapunov']
    character(len=1) :: kc
    integer :: k, nv, nr
    status = 1
    if (any(len_trim(sc%grid(1:sc%n_grid)) == 0)) then
      msg = 'field ''grid'': axis names one after another'; return
    end if
    do k = 1, sc%n_grid
      if (.not. any(griddable == sc%grid(k))) then
        msg = 'field ''grid'': cannot sweep ''' // trim(sc%grid(k)) // ''''; return
      end if
      if (any(sc%grid(1:k - 1) == sc%grid(k))) then
        msg = 'field ''grid'' names an axis twice'; return
      end if
    end do
    do k = 1, 3
      write(kc, '(i1)') k
      nv = count(sc%grid_values(:, k) == sc%grid_values(:, k))
      nr = count(sc%grid_range(:, k) == sc%grid_range(:, k))
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
        if (any(sc%grid_values(1:nv, k) /= sc%grid_values(1:nv, k)) .or. &
            any(abs(sc%grid_values(1:nv, k)) > huge(1.0_dp))) then
          msg = 'field ''grid' // kc // ''' must be finite numbers, one after another'; return
        end if
        sc%grid_n(k) = nv
      else
        if (nr /= 3 .or. any(abs(sc%grid_range(:, k)) > huge(1.0_dp))) then
          msg = 'field ''grid' // kc // '_range'' must be start, stop, count (count a whole number >= 1)'; return
        end if
        if (sc%grid_range(3, k) /= aint(sc%grid_range(3, k)) .or. sc%grid_range(3, k) < 1.0_dp .or. &
            sc%grid_range(3, k) > 1.0e8_dp) then
          msg = 'field ''grid' // kc // '_range'' must be start, stop, count (count a whole number >= 1)'; return
        end if
        sc%grid_n(k) = nint(sc%grid_range(3, k))
      end if
    end do
    if (len_trim(sc%measure) > 0 .and. .not. any(measures == sc%measure)) then
      msg = 'field ''measure'' must be one of final_well, mean_velocity, locked, poincare, lyapunov; got ''' &
            // trim(sc%measure) // ''''; return
    end if
    if (sc%n_grid > 0 .and. len_trim(sc%measure) == 0) then
      msg = 'field ''grid'' is given but ''measure'' is not'; return
    end if
    if (.not. (sc%sweep_t_max > 0.0_dp)) then
      msg = 'field ''sweep_t_max'' must be > 0'; return
    end if
    if (.not. (sc%sweep_transient >= 0.0_dp)) then
      msg = 'field ''sweep_transient'' must be >= 0'; return
    end if
    if (sc%sweep_samples < 1 .or. sc%sweep_samples > 10000000) then
      msg = 'field ''sweep_samples'' must be between 1 and 1e7'; return
    end if
    status = 0
    msg = ''
  end subroutine check_grid

  !> The same range rules as pendula/scene.py.
  subroutine check(sc, g, length, status, msg)
    type(scene_t), intent(inout) :: sc
    real(dp), intent(in) :: g, length
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    character(len=16), parameter :: known_outputs(11) = [character(len=16) :: 'trajectory', 'theta_t', &
      'v_t', 'phase', 'energy', 'period', 'omega', 'theta_max', 'series', 'lindstedt', 'spectrum']
    character(len=16), parameter :: methods(14) = [character(len=16) :: 'auto', 'exact', 'rk4', 'verlet', &
      'yoshida4', 'yoshida6', 'yoshida8', 'gauss4', 'gauss6', 'dopri5', 'dop853', 'gsl-rk8pd', 'dprkn6', 'vern9']
    character(len=16), parameter :: sweepable(7) = [character(len=16) :: 'v0', 'theta0', 'eps', &
      'damping', 'torque', 'drive_amplitude', 'drive_frequency']
    integer :: i
    status = 1
    if ((g /= g) .neqv. (length /= length)) then
      msg = 'fields ''g'' and ''length'' go together (eps = g / length): give both or neither'; return
    end if
    if (g == g) then
      if (.not. (g > 0 .and. length > 0 .and. g <= huge(g) .and. length <= huge(g))) then
        msg = 'fields ''g'' and ''length'' must be positive and finite'; return
      end if
      if (sc%eps == sc%eps .and. sc%eps /= g / length) then
        msg = 'fields ''eps'' and ''g'' / ''length'' contradict each other: give eps, or g and length'; return
      end if
      sc%eps = g / length
    else if (sc%eps /= sc%eps) then
      sc%eps = 1.0_dp
    end if
    if (.not. finite(sc%eps) .or. sc%eps <= 0) then
      msg = 'field ''eps'' must be positive and finite (eps = g/l)'; return
    end if
    if (.not. (finite(sc%theta0) .and. finite(sc%v0) .and. finite(sc%t_start) .and. finite(sc%t_end))) then
      msg = 'fields ''theta0'', ''v0'', ''t_start'', ''t_end'' must be finite'; return
    end if
    if (sc%n_samples < 1 .or. sc%n_samples > 100000000) then
      msg = 'field ''n_samples'' must be between 1 and 1e8'; return
    end if
    if (.not. finite(sc%damping) .or. sc%damping < 0) then
      msg = 'field ''damping'' must be >= 0'; return
    end if
    if (.not. (finite(sc%torque) .and. finite(sc%drive_amplitude) .and. finite(sc%drive_phase))) then
      msg = 'fields ''torque'', ''drive_amplitude'', ''drive_phase'' must be finite'; return
    end if
    if (.not. finite(sc%drive_frequency) .or. sc%drive_frequency < 0) then
      msg = 'field ''drive_frequency'' must be >= 0'; return
    end if
    if (.not. (sc%rtol > 0) .or. .not. (sc%atol >= 0)) then
      msg = 'fields ''rtol'' must be > 0 and ''atol'' >= 0'; return
    end if
    if (.not. (sc%dt >= 0)) then
      msg = 'field ''dt'' must be >= 0 (0: chosen by the method)'; return
    end if
    if (.not. (sc%restitution >= 0 .and. sc%restitution < 1)) then
      msg = 'field ''restitution'' must be in [0, 1)'; return
    end if
    if (sc%max_flips < 0 .or. sc%max_flips > 100000000) then
      msg = 'field ''max_flips'' must be between 0 and 1e8'; return
    end if
    if (.not. (finite(sc%min_flight) .and. sc%min_flight >= 0)) then
      msg = 'field ''min_flight'' must be >= 0'; return
    end if
    if (sc%cord /= 'rigid' .and. sc%cord /= 'flexible') then
      msg = 'field ''cord'' must be one of rigid, flexible; got ''' // trim(sc%cord) // ''''; return
    end if
    if (sc%guide /= 'none' .and. sc%guide /= 'cycloid') then
      msg = 'field ''guide'' must be one of none, cycloid; got ''' // trim(sc%guide) // ''''; return
    end if
    if (sc%gravity /= 'uniform' .and. sc%gravity /= 'inverse-square' .and. sc%gravity /= 'linear') then
      msg = 'field ''gravity'' must be one of uniform, inverse-square, linear; got ''' // trim(sc%gravity) // ''''
      return
    end if
    if (.not. any(methods == sc%method)) then
      msg = 'field ''method'': unknown method ''' // trim(sc%method) // ''''; return
    end if
    do i = 1, max_outputs
      if (len_trim(sc%outputs(i)) == 0) cycle
      if (.not. any(known_outputs == lower(sc%outputs(i)))) then
        msg = 'field ''outputs'': unknown output ''' // trim(sc%outputs(i)) // ''''; return
      end if
      sc%outputs(i) = lower(sc%outputs(i))
    end do
    if (all(len_trim(sc%outputs) == 0)) sc%outputs(1) = 'trajectory'
    if (len_trim(sc%sweep) > 0) then
      if (.not. any(sweepable == sc%sweep)) then
        msg = 'field ''sweep'' must name one of v0, theta0, eps, damping, torque, drive_amplitude, ' // &
              'drive_frequency; got ''' // trim(sc%sweep) // ''''; return
      end if
      if (sc%n_sweep == 0) then
        msg = 'field ''sweep_values'' is empty but ''sweep'' names a field'; return
      end if
      if (any(sc%sweep_values(1:sc%n_sweep) /= sc%sweep_values(1:sc%n_sweep)) .or. &
          count(sc%sweep_values == sc%sweep_values) /= sc%n_sweep) then
        msg = 'field ''sweep_values'' must be finite numbers, one after another'; return
      end if
      select case (trim(sc%sweep))
      case ('eps')
        if (any(sc%sweep_values(1:sc%n_sweep) <= 0)) then
          msg = 'field ''sweep_values'': eps must be > 0'; return
        end if
      case ('damping', 'drive_frequency')
        if (any(sc%sweep_values(1:sc%n_sweep) < 0)) then
          msg = 'field ''sweep_values'': ' // trim(sc%sweep) // ' must be >= 0'; return
        end if
      end select
    else if (sc%n_sweep > 0) then
      msg = 'field ''sweep_values'' is given but ''sweep'' does not name a field'; return
    end if
    call check_issue13(sc, msg)
    if (len_trim(msg) > 0) return
    if (sc%method == 'exact' .and. len_trim(scene_effects(sc)) > 0 .and. sc%guide /= 'cycloid') then
      msg = 'field ''method'': ''exact'' answers only the conservative rigid pendulum, but the scene names ' &
            // trim(scene_effects(sc)); return
    end if
    status = 0
    msg = ''
  end subroutine check

  !> Issue 13: the cycloidal guide and the gravity fields (same rules as scene.py).  msg = '' when fine.
  subroutine check_issue13(sc, msg)
    type(scene_t), intent(in) :: sc
    character(len=*), intent(out) :: msg
    msg = ''
    if (.not. (sc%cycloid_radius > 0 .and. finite(sc%cycloid_radius))) then
      msg = 'field ''cycloid_radius'' must be positive (R / l)'; return
    end if
    if (sc%guide /= 'cycloid' .and. sc%cycloid_radius /= 0.25_dp) then
      msg = 'field ''cycloid_radius'' is used only with guide = ''cycloid'''; return
    end if
    if (.not. (finite(sc%gravity_distance) .and. finite(sc%gravity_gradient))) then
      msg = 'fields ''gravity_distance'', ''gravity_gradient'' must be finite'; return
    end if
    if (sc%gravity == 'inverse-square') then
      if (.not. (sc%gravity_distance > 1)) then
        msg = 'field ''gravity_distance'' (D / l, the point mass below the pivot) must be > 1 with ' // &
              'gravity = ''inverse-square'''; return
      end if
    else if (sc%gravity_distance /= 0) then
      msg = 'field ''gravity_distance'' is used only with gravity = ''inverse-square'''; return
    end if
    if (sc%gravity == 'linear') then
      if (.not. (sc%gravity_gradient < 0.5_dp)) then
        msg = 'field ''gravity_gradient'' (kappa in g (1 - kappa h / l)) must be < 0.5 so that gravity ' // &
              'points down at the top'; return
      end if
    else if (sc%gravity_gradient /= 0) then
      msg = 'field ''gravity_gradient'' is used only with gravity = ''linear'''; return
    end if
    if (sc%guide == 'cycloid') then
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
              '''exact''), never integrated'; return
      end if
      if (.not. (abs(sc%theta0) <= half_pi)) then
        msg = 'field ''theta0'': on the cycloid |theta0| <= pi/2 (the cusps, |s| = 4R)'; return
      end if
    end if
  end subroutine check_issue13

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
    do i = 1, max_outputs
      if (len_trim(sc%outputs(i)) > 0) tmp = trim(tmp) // ' ' // trim(sc%outputs(i))
    end do
    s = trim(s) // new_line('a') // '# outputs =' // trim(tmp)
    if (sc%n_sweep > 0) then
      write(tmp, '(a, i0, a)') 'sweep = ' // trim(sc%sweep) // ' over ', sc%n_sweep, ' values'
      s = trim(s) // new_line('a') // '# ' // trim(tmp)
    end if
    if (len_trim(sc%name) > 0) s = trim(s) // new_line('a') // '# name = ' // trim(sc%name)
  end function scene_summary

  ! ------------------------------------------------------------ helpers

  !> The lexicon of values both readers share (python/pendula/scene.py,
  !> _TOKEN): numbers [+-]digits[.digits][(e|d)[+-]digits], quoted strings,
  !> logicals .true./.false./.t./.f., a repeat count r* before a value, and
  !> blanks or commas between them.  0 when s is made of these, otherwise the
  !> position where the first bad token starts.
  pure integer function bad_value_token(s) result(at)
    character(len=*), intent(in) :: s
    integer :: i, n, e
    character(len=1) :: q
    at = 0
    i = 1
    n = len(s)
    do while (i <= n)
      select case (s(i:i))
      case (' ', ',', achar(9), achar(10), achar(13))
        i = i + 1
      case ('''', '"')
        q = s(i:i)
        e = i + 1
        do
          if (e > n) then
            at = i; return
          end if
          if (s(e:e) == q) then
            if (e < n) then
              if (s(e + 1:e + 1) == q) then
                e = e + 2; cycle
              end if
            end if
            exit
          end if
          e = e + 1
        end do
        i = e + 1
        if (.not. separated(i)) then
          at = i; return
        end if
      case ('.')
        e = logical_end(i)
        if (e == 0) e = number_end(i)
        if (e == 0) then
          at = i; return
        end if
        i = e + 1
        if (.not. separated(i)) then
          at = i; return
        end if
      case default
        e = number_end(i)
        if (e == 0) then
          at = i; return
        end if
        q = 'n'
        if (verify(s(i:e), '0123456789') == 0) q = 'r'   ! digits only: may be a repeat count
        i = e + 1
        if (i <= n) then
          if (s(i:i) == '*' .and. q == 'r') then
            i = i + 1   ! a repeat count: the value follows at once
            if (i > n) then
              at = i - 1; return
            end if
            if (index(' ,', s(i:i)) > 0) then
              at = i; return
            end if
            cycle
          end if
        end if
        if (.not. separated(i)) then
          at = i; return
        end if
      end select
    end do
  contains
    pure logical function separated(k)
      integer, intent(in) :: k
      separated = .true.
      if (k <= n) separated = index(' ,' // achar(9) // achar(10) // achar(13), s(k:k)) > 0
    end function separated
    pure integer function logical_end(k)
      integer, intent(in) :: k
      integer :: m
      character(len=7), parameter :: words(4) = [character(len=7) :: '.true.', '.false.', '.t.', '.f.']
      logical_end = 0
      do m = 1, 4
        if (k + len_trim(words(m)) - 1 <= n) then
          if (lower(s(k:k + len_trim(words(m)) - 1)) == trim(words(m))) then
            logical_end = k + len_trim(words(m)) - 1; return
          end if
        end if
      end do
    end function logical_end
    !> end of the number starting at k (0: none)
    pure integer function number_end(k)
      integer, intent(in) :: k
      integer :: m, d1, d2
      number_end = 0
      m = k
      if (index('+-', s(m:m)) > 0) m = m + 1
      d1 = digits(m)
      m = m + d1
      d2 = 0
      if (m <= n) then
        if (s(m:m) == '.') then
          m = m + 1
          d2 = digits(m)
          m = m + d2
        end if
      end if
      if (d1 + d2 == 0) return
      if (m <= n) then
        if (index('eEdD', s(m:m)) > 0) then
          m = m + 1
          if (m <= n) then
            if (index('+-', s(m:m)) > 0) m = m + 1
          end if
          if (digits(m) == 0) return
          m = m + digits(m)
        end if
      end if
      number_end = m - 1
    end function number_end
    pure integer function digits(k)
      integer, intent(in) :: k
      digits = 0
      do while (k + digits <= n)
        if (index('0123456789', s(k + digits:k + digits)) == 0) exit
        digits = digits + 1
      end do
    end function digits
  end function bad_value_token

  !> The token of s starting at k (up to a blank or a comma), for messages.
  pure function token_at(s, k) result(t)
    character(len=*), intent(in) :: s
    integer, intent(in) :: k
    character(len=:), allocatable :: t
    integer :: e
    e = scan(s(k:), ' ,' // achar(10))
    if (e == 0) then
      t = s(k:min(len(s), k + 40))
    else
      t = s(k:k + e - 2)
    end if
  end function token_at

  !> 0 when s is valid UTF-8, otherwise the position of the first bad byte.
  pure integer function utf8_error_at(s)
    character(len=*), intent(in) :: s
    integer :: i, b, n, j
    utf8_error_at = 0
    i = 1
    do while (i <= len(s))
      b = iachar(s(i:i))
      if (b < 128) then
        n = 0
      else if (b >= 194 .and. b <= 223) then
        n = 1
      else if (b >= 224 .and. b <= 239) then
        n = 2
      else if (b >= 240 .and. b <= 244) then
        n = 3
      else
        utf8_error_at = i; return
      end if
      if (i + n > len(s)) then
        utf8_error_at = i; return
      end if
      do j = i + 1, i + n
        if (iand(iachar(s(j:j)), 192) /= 128) then
          utf8_error_at = j; return
        end if
      end do
      i = i + n + 1
    end do
  end function utf8_error_at

  pure logical function finite(x)
    real(dp), intent(in) :: x
    finite = abs(x) <= huge(x)
  end function finite

  pure function lower(s) result(r)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: r
    integer :: i
    r = s
    do i = 1, len(s)
      if (r(i:i) >= 'A' .and. r(i:i) <= 'Z') r(i:i) = achar(iachar(r(i:i)) + 32)
    end do
  end function lower

  pure integer function count_newlines(s)
    character(len=*), intent(in) :: s
    integer :: i
    count_newlines = 0
    do i = 1, len(s)
      if (s(i:i) == new_line('a')) count_newlines = count_newlines + 1
    end do
  end function count_newlines

  !> Blank out '!' comments (outside quotes), keeping the newlines.
  pure subroutine strip_comments(s)
    character(len=*), intent(inout) :: s
    integer :: i
    character(len=1) :: q
    logical :: incomment
    q = ' '
    incomment = .false.
    do i = 1, len(s)
      if (s(i:i) == new_line('a')) then
        incomment = .false.
        cycle
      end if
      if (incomment) then
        s(i:i) = ' '
      else if (q /= ' ') then
        if (s(i:i) == q) q = ' '
      else if (s(i:i) == '''' .or. s(i:i) == '"') then
        q = s(i:i)
      else if (s(i:i) == '!') then
        incomment = .true.
        s(i:i) = ' '
      end if
    end do
  end subroutine strip_comments

  !> Position of the '/' that closes the group (outside quotes), or 0.
  pure integer function closing_slash(s, from)
    character(len=*), intent(in) :: s
    integer, intent(in) :: from
    integer :: i
    character(len=1) :: q
    q = ' '
    closing_slash = 0
    do i = from, len(s)
      if (q /= ' ') then
        if (s(i:i) == q) q = ' '
      else if (s(i:i) == '''' .or. s(i:i) == '"') then
        q = s(i:i)
      else if (s(i:i) == '/') then
        closing_slash = i
        return
      end if
    end do
  end function closing_slash

  !> From position k, find the next "name =" (outside quotes) and the end of
  !> its value (the next "name =" or the closing slash at stop).  On return
  !> start is where the name begins (0 if none) and k where the next begins.
  pure subroutine next_assignment(s, k, stop, start, fname)
    character(len=*), intent(in) :: s
    integer, intent(inout) :: k
    integer, intent(in) :: stop
    integer, intent(out) :: start
    character(len=*), intent(out) :: fname
    integer :: i, e
    start = 0
    fname = ''
    call find_name_eq(s, k, stop, i, e)
    if (i == 0) then
      k = stop
      return
    end if
    start = i
    fname = lower(s(i:e))
    call find_name_eq(s, e + 1, stop, i, e)
    if (i == 0) then
      k = stop
    else
      k = i
    end if
  end subroutine next_assignment

  !> First identifier followed by '=' at or after position from (outside quotes).
  pure subroutine find_name_eq(s, from, stop, first, last)
    character(len=*), intent(in) :: s
    integer, intent(in) :: from, stop
    integer, intent(out) :: first, last
    integer :: i, j
    character(len=1) :: q
    q = ' '
    first = 0
    last = 0
    i = from
    do while (i < stop)
      if (q /= ' ') then
        if (s(i:i) == q) q = ' '
        i = i + 1
        cycle
      end if
      if (s(i:i) == '''' .or. s(i:i) == '"') then
        q = s(i:i)
        i = i + 1
        cycle
      end if
      if (is_alpha(s(i:i)) .and. (i == 1 .or. .not. is_word(s(max(i - 1, 1):max(i - 1, 1))))) then
        j = i
        do while (j + 1 < stop .and. is_word(s(j + 1:j + 1)))
          j = j + 1
        end do
        last = j
        j = j + 1
        do while (j < stop .and. (s(j:j) == ' ' .or. s(j:j) == new_line('a') .or. s(j:j) == achar(9) &
                                  .or. s(j:j) == achar(13)))
          j = j + 1
        end do
        if (j < stop .and. s(j:j) == '=') then
          first = i
          return
        end if
        i = last + 1
        cycle
      end if
      i = i + 1
    end do
  end subroutine find_name_eq

  pure logical function is_alpha(c)
    character(len=1), intent(in) :: c
    is_alpha = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z') .or. c == '_'
  end function is_alpha

  pure logical function is_word(c)
    character(len=1), intent(in) :: c
    is_word = is_alpha(c) .or. (c >= '0' .and. c <= '9')
  end function is_word

end module pendula_scene
