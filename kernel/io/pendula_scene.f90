!> Scenes: the namelist group &scene, read and checked by one set of rules.
!>
!> A scene reaches the kernel in one of two ways, and both end in the same
!> check (check_scene):
!>   - as text (parse_scene; read_scene for a file): each "name = value"
!>     assignment is read on its own through an internal namelist read, so
!>     that an unknown field, a misspelling, a value of the wrong type or too
!>     many values is reported with the field's name and its line;
!>   - as fields (scene_from_fields): the numbers in a fixed order
!>     (number_fields) and the words one after another, as the Python layer's
!>     Scene holds them.
!> check_scene holds every rule about a scene: the ranges of the fields, the
!> models' combinations, the sweep and grid fields, and which outputs a scene
!> can have (spectrum, series, lindstedt, the orbit facts).  pendula-run and
!> the Python layer ask it alike, so they accept and refuse the same scenes
!> with the same message.
module pendula_scene
  use, intrinsic :: iso_c_binding, only: c_long_long, c_null_char
  use pendula_kinds, only: dp, nan_dp, half_pi, pi
  use pendula_outfile, only: out_errtext
  use pendula_exact, only: pendulum_orbit, orbit_setup, regime_separatrix
  use pendula_cycloid, only: cycloid_omega2
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private
  public :: scene_t, read_scene, parse_scene, scene_from_fields, scene_to_fields, scene_lists, check_scene, &
            scene_member, &
            scene_effects, scene_has_orbit_facts, scene_summary, max_sweep, max_outputs, number_fields, &
            n_number_fields, n_word_fields, max_words

  integer, parameter :: max_sweep = 4096, max_outputs = 16
  !> the largest scene file read (16 MiB: a scene with every list full is below 1 MiB)
  integer, parameter :: max_scene_bytes = 16777216

  interface
    !> kernel/glue/pendula_os.c: 0 for a regular file (its size), else -errno (-10001: not a regular file)
    function c_read_kind(path, size) bind(C, name='pendula_read_kind') result(k)
      use, intrinsic :: iso_c_binding, only: c_int, c_char, c_long_long
      character(kind=c_char), intent(in) :: path(*)
      integer(c_long_long), intent(out) :: size
      integer(c_int) :: k
    end function c_read_kind
  end interface
  !> the numbers of a scene in the order scene_from_fields takes them (whole
  !> numbers too: n_samples, max_flips, sweep_samples)
  integer, parameter :: n_number_fields = 31
  character(len=16), parameter :: number_fields(n_number_fields) = [character(len=16) :: 'eps', 'theta0', &
    'v0', 't_start', 't_end', 'n_samples', 'damping', 'torque', 'drive_amplitude', 'drive_frequency', &
    'drive_phase', 'rtol', 'atol', 'dt', 'g', 'length', 'cycloid_radius', 'gravity_distance', &
    'gravity_gradient', 'restitution', 'max_flips', 'min_flight', 'sweep_t_max', 'sweep_transient', &
    'sweep_samples', 'friction', 'drag', 'pivot_amplitude', 'pivot_frequency', 'noise', 'seed']
  !> the single words, in order; then the outputs, then the grid's axes
  integer, parameter :: n_word_fields = 7
  character(len=8), parameter :: word_fields(n_word_fields) = [character(len=8) :: 'cord', 'guide', 'gravity', &
    'method', 'sweep', 'measure', 'name']
  integer, parameter :: max_words = n_word_fields + max_outputs + 3
  !> |theta0| beyond 2^52: a double has no fraction left, the angle cannot be reduced mod 2 pi
  real(dp), parameter :: theta0_limit = 4503599627370496.0_dp
  !> |drive_phase| beyond 2^10 rad (163 turns): the phase's own rounding (half an ulp, up to 1.1e-13)
  !> would enter the drive cos(Omega t + phase) unseen; a phase is given reduced, as an angle of one turn
  real(dp), parameter :: drive_phase_limit = 1024.0_dp
  !> eps above 1e300 leaves no room for the exact path's double-double sqrt(eps)
  real(dp), parameter :: eps_limit = 1.0e300_dp
  !> the largest seed: 2^53, every whole number up to it is a double
  real(dp), parameter :: seed_limit = 9007199254740992.0_dp

  type :: scene_t
    real(dp) :: eps = 1.0_dp, theta0 = 0.0_dp, v0 = 0.0_dp
    real(dp) :: t_start = 0.0_dp, t_end = 20.0_dp
    integer :: n_samples = 1001
    real(dp) :: damping = 0.0_dp, torque = 0.0_dp
    real(dp) :: drive_amplitude = 0.0_dp, drive_frequency = 0.0_dp, drive_phase = 0.0_dp
    character(len=32) :: cord = 'rigid', guide = 'none', gravity = 'uniform', method = 'auto'
    real(dp) :: rtol = 1.0e-10_dp, atol = 1.0e-12_dp, dt = 0.0_dp
    character(len=16) :: outputs(max_outputs) = ''
    integer :: n_outputs = 0
    character(len=32) :: sweep = ''
    real(dp), allocatable :: sweep_values(:)        ! n_sweep values
    integer :: n_sweep = 0
    character(len=256) :: name = ''
    ! the cycloidal guide (R / l) and the gravity fields' parameters
    real(dp) :: cycloid_radius = 0.25_dp, gravity_distance = 0.0_dp, gravity_gradient = 0.0_dp
    ! the flexible cord (kernel/models/pendula_cord.f90)
    real(dp) :: restitution = 0.0_dp, min_flight = 0.0_dp
    integer :: max_flips = 100000
    ! sweeps over grids (kernel/sweep): axes, values or (start, stop, count), measure;
    ! grid_nv, grid_nr: how many values and range entries each axis was given;
    ! grid_values(:, k): axis k's values, NaN beyond them (at least one row: a
    ! range axis has NaN in its first)
    character(len=32) :: grid(3) = ''
    integer :: n_grid = 0
    real(dp), allocatable :: grid_values(:, :)
    real(dp) :: grid_range(3, 3) = nan_dp
    integer :: grid_n(3) = 0, grid_nv(3) = 0, grid_nr(3) = 0
    character(len=32) :: measure = ''
    real(dp) :: sweep_t_max = 2000.0_dp, sweep_transient = 200.0_dp
    integer :: sweep_samples = 100
    ! effects: dry (Coulomb) friction mu, quadratic drag gamma, a vertically vibrating pivot a cos(Omega t)
    real(dp) :: friction = 0.0_dp, drag = 0.0_dp, pivot_amplitude = 0.0_dp, pivot_frequency = 0.0_dp
    ! thermal noise (kernel/integrators/pendula_langevin.f90): the temperature T in units
    ! of eps, and the seed of its counter-based random numbers (0 .. 2^53)
    real(dp) :: noise = 0.0_dp
    integer(int64) :: seed = 0
  end type scene_t

contains

  !> Read and check a scene file.  status 0: ok; otherwise msg names the problem.
  subroutine read_scene(path, sc, status, msg, g_out, length_out)
    character(len=*), intent(in) :: path
    type(scene_t), intent(out) :: sc
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    !> g and length as given (see parse_scene)
    real(dp), intent(out), optional :: g_out, length_out
    character(len=:), allocatable :: text
    integer :: unit, ios, k, kind
    integer(c_long_long) :: bytes
    status = 0
    msg = ''
    ! what the name is, before anything reads it: only a regular file of at most 16 MiB is read
    kind = c_read_kind(path // c_null_char, bytes)
    if (kind /= 0) then
      status = 1
      select case (-kind)
      case (2)        ! ENOENT
        msg = trim(path) // ': cannot read scene file (no such file)'
      case (21)       ! EISDIR
        msg = trim(path) // ': cannot read scene file (a folder, not a file)'
      case (10001)    ! a device, FIFO or socket
        msg = trim(path) // ': cannot read scene file (not a regular file: a device, FIFO or socket is never read)'
      case default
        msg = trim(path) // ': cannot read scene file (' // out_errtext(-kind) // ')'
      end select
      return
    end if
    if (bytes > max_scene_bytes) then
      status = 1; msg = trim(path) // ': cannot read scene file (larger than 16 MiB: not a scene)'; return
    end if
    open(newunit=unit, file=path, status='old', action='read', access='stream', form='unformatted', &
         iostat=ios)
    if (ios /= 0) then
      status = 1; msg = trim(path) // ': cannot read scene file (cannot open it)'; return
    end if
    inquire(unit=unit, size=k)
    allocate(character(len=max(k, 0)) :: text)
    if (k > 0) read(unit, iostat=ios) text
    close(unit)
    if (ios /= 0) then
      status = 1; msg = trim(path) // ': cannot read scene file (cannot open it)'; return
    end if
    call parse_scene(text, path, sc, status, msg, g_out, length_out)
  end subroutine read_scene

  !> Parse and check the text of a scene (the group &scene); messages start
  !> with source.  g_out, length_out: the fields g and length as given (NaN:
  !> not given; eps is settled from them).
  subroutine parse_scene(text_in, source, sc, status, msg, g_out, length_out)
    character(len=*), intent(in) :: text_in, source
    type(scene_t), intent(out) :: sc
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    real(dp), intent(out), optional :: g_out, length_out
    ! the namelist variables (same names as the fields)
    real(dp) :: eps, theta0, v0, t_start, t_end, damping, torque, drive_amplitude, &
                drive_frequency, drive_phase, rtol, atol, dt, g, length, cycloid_radius, gravity_distance, &
                gravity_gradient, restitution, min_flight, sweep_t_max, sweep_transient, &
                friction, drag, pivot_amplitude, pivot_frequency, noise
    integer :: n_samples, max_flips, sweep_samples
    integer(int64) :: seed
    real(dp) :: grid1(max_sweep), grid2(max_sweep), grid3(max_sweep), grid1_range(3), grid2_range(3), &
                grid3_range(3)
    ! far more characters than the scene holds: a longer string is refused
    ! with a message instead of being truncated
    character(len=1024) :: cord, guide, gravity, method, sweep, measure, name
    character(len=1024) :: outputs(max_outputs), grid(3)
    real(dp) :: sweep_values(max_sweep)
    namelist /scene/ eps, theta0, v0, t_start, t_end, n_samples, damping, torque, &
      drive_amplitude, drive_frequency, drive_phase, cord, guide, gravity, method, rtol, atol, dt, &
      outputs, sweep, sweep_values, name, g, length, cycloid_radius, gravity_distance, gravity_gradient, &
      restitution, max_flips, min_flight, &
      grid, grid1, grid2, grid3, grid1_range, grid2_range, grid3_range, measure, sweep_t_max, &
      sweep_transient, sweep_samples, friction, drag, pivot_amplitude, pivot_frequency, noise, seed
    character(len=:), allocatable :: text
    character(len=:), allocatable :: buf
    character(len=512) :: iom
    integer :: ios, i, j, k, start, line, nseen, jj, kk, nval, cap, eq
    logical :: nulls
    character(len=64) :: fname, seen(64)
    character(len=32) :: words(max_words)
    integer :: wlen(max_words), nout, ngrid
    character(len=1024) :: longw(max_words)
    integer, parameter :: n_known = 47
    character(len=16), parameter :: known_fields(n_known) = [character(len=16) :: 'eps', 'theta0', 'v0', &
      't_start', 't_end', 'n_samples', 'damping', 'torque', 'drive_amplitude', 'drive_frequency', &
      'drive_phase', 'cord', 'guide', 'gravity', 'method', 'rtol', 'atol', 'dt', 'outputs', 'sweep', &
      'sweep_values', 'name', 'g', 'length', 'cycloid_radius', 'gravity_distance', 'gravity_gradient', &
      'restitution', 'max_flips', 'min_flight', &
      'grid', 'grid1', 'grid2', 'grid3', 'grid1_range', 'grid2_range', 'grid3_range', 'measure', &
      'sweep_t_max', 'sweep_transient', 'sweep_samples', 'friction', 'drag', 'pivot_amplitude', &
      'pivot_frequency', 'noise', 'seed']
    ! how many values each field was given, and the line where it was
    integer :: given(n_known), given_line(n_known)

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
    friction = 0; drag = 0; pivot_amplitude = 0; pivot_frequency = 0
    noise = 0.0_dp; seed = 0
    given = 0
    given_line = 0
    if (present(g_out)) g_out = nan_dp
    if (present(length_out)) length_out = nan_dp

    k = utf8_error_at(text_in)
    if (k > 0) then
      status = 1
      write(msg, '(a,i0,a)') trim(source) // ': not UTF-8 text (byte ', k, ' is not part of a UTF-8 character)'
      return
    end if
    k = index(text_in, achar(0))
    if (k > 0) then
      status = 1
      write(msg, '(a,i0,a)') trim(source) // ': not a text file (byte ', k, ' is NUL)'
      return
    end if
    text = text_in
    ! a UTF-8 byte-order mark (Windows editors write one) is no text: read as blanks
    if (len(text) >= 3) then
      if (text(1:3) == achar(239) // achar(187) // achar(191)) text(1:3) = '   '
    end if
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
      if (.not. any(known_fields == fname)) then
        status = 1
        write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': unknown field ''' // trim(fname) // '''' // &
          suggest(fname, known_fields)
        return
      end if
      if (any(seen(1:nseen) == fname)) then
        status = 1
        write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // ''' is given twice'
        return
      end if
      nseen = min(nseen + 1, size(seen))
      seen(nseen) = fname
      eq = start + index(text(start:k - 1), '=')
      if (verify(text(eq:k - 1), ' ,' // new_line('a') // achar(9) // achar(13)) == 0) then
        status = 1
        write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // ''' has no value'
        return
      end if
      jj = bad_value_token(text(eq:k - 1))
      if (jj > 0) then
        status = 1
        if (text(eq + jj - 1:eq + jj - 1) == '*' .or. len_trim(token_at(text(eq:k - 1), jj)) == 0) then
          write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // &
            ''': a repeat count (r*) needs its value right after the ''*'''
        else
          write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // &
            ''': cannot read value ''' // token_at(text(eq:k - 1), jj) // ''''
        end if
        return
      end if
      call count_values(text(eq:k - 1), nval, nulls)
      if (nulls) then
        status = 1
        write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // &
          ''': an empty value between commas'
        return
      end if
      select case (trim(fname))
      case ('outputs');                               cap = max_outputs
      case ('grid', 'grid1_range', 'grid2_range', 'grid3_range'); cap = 3
      case ('sweep_values', 'grid1', 'grid2', 'grid3'); cap = max_sweep
      case default;                                   cap = 1
      end select
      if (nval > cap) then
        status = 1
        if (cap == 1) then
          write(msg, '(a,i0,a,i0)') trim(source) // ', line ', line, ': field ''' // trim(fname) // &
            ''' takes one value, got ', nval
        else
          write(msg, '(a,i0,a,i0,a,i0)') trim(source) // ', line ', line, ': field ''' // trim(fname) // &
            ''' holds at most ', cap, ' values, got ', nval
        end if
        return
      end if
      select case (trim(fname))
      case ('n_samples', 'max_flips', 'sweep_samples', 'seed')
        kk = first_token_not(text(eq:k - 1), 'i')
        iom = 'a whole number'
      case ('cord', 'guide', 'gravity', 'method', 'sweep', 'measure', 'name', 'outputs', 'grid')
        kk = first_token_not(text(eq:k - 1), 's')
        iom = 'a quoted string'
      case default
        kk = first_token_not(text(eq:k - 1), 'r')
        iom = 'a real number'
      end select
      if (kk > 0) then
        status = 1
        write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // ''' must be ' // &
          trim(iom) // ', got ' // token_at(text(eq:k - 1), kk)
        return
      end if
      given(findloc(known_fields, fname, dim=1)) = nval
      given_line(findloc(known_fields, fname, dim=1)) = line
      buf = '&scene ' // text(start:k - 1) // ' /'
      read(buf, nml=scene, iostat=ios, iomsg=iom)
      if (ios /= 0) then
        status = 1
        write(msg, '(a,i0,a)') trim(source) // ', line ', line, ': field ''' // trim(fname) // &
          ''': cannot read its value (' // trim(iom) // ')'
        return
      end if
    end do

    ! the words, as the fields path takes them: single words, outputs, grid axes
    longw = ''
    longw(1:n_word_fields) = [cord, guide, gravity, method, sweep, measure, name]
    nout = given(findloc(known_fields, 'outputs', dim=1))
    ngrid = given(findloc(known_fields, 'grid', dim=1))
    longw(n_word_fields + 1:n_word_fields + nout) = outputs(1:nout)
    longw(n_word_fields + nout + 1:n_word_fields + nout + ngrid) = grid(1:ngrid)
    do i = 1, n_word_fields + nout + ngrid
      wlen(i) = len_trim(longw(i))
      if (wlen(i) > word_limit(i, nout)) then
        status = 1
        msg = trim(source) // ': ' // too_long(i, nout)
        return
      end if
    end do
    words = ''
    sc%name = longw(7)
    do i = 1, n_word_fields + nout + ngrid
      if (i /= 7) words(i) = longw(i)
    end do
    sc%eps = eps; sc%theta0 = theta0; sc%v0 = v0; sc%t_start = t_start; sc%t_end = t_end
    sc%n_samples = n_samples; sc%damping = damping; sc%torque = torque
    sc%drive_amplitude = drive_amplitude; sc%drive_frequency = drive_frequency
    sc%drive_phase = drive_phase; sc%rtol = rtol; sc%atol = atol; sc%dt = dt
    sc%cycloid_radius = cycloid_radius; sc%gravity_distance = gravity_distance
    sc%gravity_gradient = gravity_gradient
    sc%restitution = restitution; sc%max_flips = max_flips; sc%min_flight = min_flight
    sc%sweep_t_max = sweep_t_max; sc%sweep_transient = sweep_transient; sc%sweep_samples = sweep_samples
    sc%friction = friction; sc%drag = drag; sc%pivot_amplitude = pivot_amplitude
    sc%pivot_frequency = pivot_frequency
    sc%noise = noise; sc%seed = seed
    call set_words(sc, words, nout, ngrid)
    sc%n_sweep = given(findloc(known_fields, 'sweep_values', dim=1))
    sc%sweep_values = sweep_values(1:sc%n_sweep)
    sc%grid_range(:, 1) = grid1_range; sc%grid_range(:, 2) = grid2_range; sc%grid_range(:, 3) = grid3_range
    do i = 1, 3
      sc%grid_nv(i) = given(findloc(known_fields, 'grid' // achar(48 + i), dim=1))
      sc%grid_nr(i) = given(findloc(known_fields, 'grid' // achar(48 + i) // '_range', dim=1))
    end do
    allocate(sc%grid_values(max(1, maxval(sc%grid_nv)), 3), source=nan_dp)
    sc%grid_values(1:sc%grid_nv(1), 1) = grid1(1:sc%grid_nv(1))
    sc%grid_values(1:sc%grid_nv(2), 2) = grid2(1:sc%grid_nv(2))
    sc%grid_values(1:sc%grid_nv(3), 3) = grid3(1:sc%grid_nv(3))
    if (present(g_out)) g_out = g
    if (present(length_out)) length_out = length
    call check_scene(sc, g, length, status, msg)
    if (status /= 0) then
      ! the line of the field the message names first, when the text gives it
      line = 0
      i = index(msg, 'field ''')
      if (i == 0) i = index(msg, 'fields ''')
      if (i > 0) then
        i = i + index(msg(i:), '''')
        j = index(msg(i:), '''')
        if (j > 1) then
          k = findloc(known_fields, msg(i:i + j - 2), dim=1)
          if (k > 0) line = given_line(k)
        end if
      end if
      if (line > 0) then
        buf = trim(source) // ', line ' // trim(int_text(line)) // ': ' // trim(msg)
        msg = buf
      else
        msg = trim(source) // ': ' // trim(msg)
      end if
    end if
  end subroutine parse_scene

  !> A scene from its fields (the Python layer's Scene): the numbers in the
  !> order of number_fields; the words one after another in `words` with
  !> their lengths in wlen: cord, guide, gravity, method, sweep, measure,
  !> name, then nout outputs, then ngrid grid axes; the lists of numbers.
  !> Checked by check_scene unless check is .false. (a scene checked before).
  subroutine scene_from_fields(x, words, wlen, nout, ngrid, sweep_values, grid1, grid2, grid3, grid1_range, &
                               grid2_range, grid3_range, check, sc, g, length, status, msg)
    real(dp), intent(in) :: x(n_number_fields)
    character(len=*), intent(in) :: words
    integer, intent(in) :: wlen(:), nout, ngrid
    real(dp), intent(in) :: sweep_values(:), grid1(:), grid2(:), grid3(:), grid1_range(:), grid2_range(:), &
                            grid3_range(:)
    logical, intent(in) :: check
    type(scene_t), intent(out) :: sc
    real(dp), intent(out) :: g, length
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    character(len=32) :: w(max_words)
    integer :: i, a, n
    status = 1
    g = x(15); length = x(16)
    n = n_word_fields + nout + ngrid
    if (nout < 0 .or. ngrid < 0 .or. size(wlen) < n .or. sum(wlen(1:n)) > len(words) .or. any(wlen(1:n) < 0)) then
      msg = 'the words of the scene do not match their lengths'; return
    end if
    if (nout > max_outputs) then
      write(msg, '(a,i0,a,i0)') 'field ''outputs'' holds at most ', max_outputs, ' values, got ', nout; return
    end if
    if (ngrid > 3) then
      write(msg, '(a,i0)') 'field ''grid'' holds at most 3 values, got ', ngrid; return
    end if
    if (size(sweep_values) > max_sweep) then
      write(msg, '(a,i0,a,i0)') 'field ''sweep_values'' holds at most ', max_sweep, ' values, got ', &
        size(sweep_values); return
    end if
    do i = 1, 3
      select case (i)
      case (1); a = size(grid1)
      case (2); a = size(grid2)
      case default; a = size(grid3)
      end select
      if (a > max_sweep) then
        write(msg, '(a,i0,a,i0,a,i0)') 'field ''grid', i, ''' holds at most ', max_sweep, ' values, got ', a; return
      end if
    end do
    if (size(grid1_range) > 3 .or. size(grid2_range) > 3 .or. size(grid3_range) > 3) then
      msg = 'fields ''grid1_range'', ''grid2_range'', ''grid3_range'' hold at most 3 values'; return
    end if
    w = ''
    a = 1
    do i = 1, n
      if (wlen(i) > word_limit(i, nout)) then
        msg = too_long(i, nout); return
      end if
      if (i == 7) then
        sc%name = words(a:a + wlen(i) - 1)
      else
        w(i) = words(a:a + wlen(i) - 1)
      end if
      a = a + wlen(i)
    end do
    sc%eps = x(1); sc%theta0 = x(2); sc%v0 = x(3); sc%t_start = x(4); sc%t_end = x(5)
    sc%damping = x(7); sc%torque = x(8); sc%drive_amplitude = x(9); sc%drive_frequency = x(10)
    sc%drive_phase = x(11); sc%rtol = x(12); sc%atol = x(13); sc%dt = x(14)
    sc%cycloid_radius = x(17); sc%gravity_distance = x(18); sc%gravity_gradient = x(19)
    sc%restitution = x(20); sc%min_flight = x(22); sc%sweep_t_max = x(23); sc%sweep_transient = x(24)
    sc%friction = x(26); sc%drag = x(27); sc%pivot_amplitude = x(28); sc%pivot_frequency = x(29)
    if (.not. whole(x(6), sc%n_samples, msg, 'n_samples')) return
    if (.not. whole(x(21), sc%max_flips, msg, 'max_flips')) return
    if (.not. whole(x(25), sc%sweep_samples, msg, 'sweep_samples')) return
    sc%noise = x(30)
    if (.not. (x(31) == aint(x(31)) .and. x(31) >= 0.0_dp .and. x(31) <= seed_limit)) then
      msg = 'field ''seed'' must be a whole number from 0 to 2^53, got ' // trim(num_text(x(31))); return
    end if
    sc%seed = int(x(31), int64)
    call set_words(sc, w, nout, ngrid)
    sc%n_sweep = size(sweep_values)
    sc%sweep_values = sweep_values
    sc%grid_nv = [size(grid1), size(grid2), size(grid3)]
    sc%grid_nr = [size(grid1_range), size(grid2_range), size(grid3_range)]
    allocate(sc%grid_values(max(1, maxval(sc%grid_nv)), 3), source=nan_dp)
    sc%grid_values(1:sc%grid_nv(1), 1) = grid1
    sc%grid_values(1:sc%grid_nv(2), 2) = grid2
    sc%grid_values(1:sc%grid_nv(3), 3) = grid3
    sc%grid_range(1:sc%grid_nr(1), 1) = grid1_range
    sc%grid_range(1:sc%grid_nr(2), 2) = grid2_range
    sc%grid_range(1:sc%grid_nr(3), 3) = grid3_range
    status = 0
    msg = ''
    if (check) call check_scene(sc, g, length, status, msg)
  contains
    logical function whole(v, iv, m, fname)
      real(dp), intent(in) :: v
      integer, intent(out) :: iv
      character(len=*), intent(inout) :: m
      character(len=*), intent(in) :: fname
      whole = v == aint(v)
      iv = 0
      if (.not. whole) then
        m = 'field ''' // fname // ''' must be a whole number, got ' // trim(num_text(v)); return
      end if
      iv = int(max(-2.0e9_dp, min(2.0e9_dp, v)))
    end function whole
  end subroutine scene_from_fields

  !> The lists of a (checked) scene, as the readers hand them on: the sweep's values, and each grid
  !> axis's values and range (NaN beyond what was given), with how many of each were given.
  subroutine scene_lists(sc, sweep_values, nsweep, grid_values, grid_nv, grid_range, grid_nr)
    type(scene_t), intent(in) :: sc
    real(dp), intent(out) :: sweep_values(:), grid_values(:, :), grid_range(3, 3)
    integer, intent(out) :: nsweep, grid_nv(3), grid_nr(3)
    sweep_values = 0; grid_values = 0
    nsweep = sc%n_sweep
    sweep_values(1:nsweep) = sc%sweep_values(1:nsweep)
    grid_nv = sc%grid_nv
    grid_nr = sc%grid_nr
    grid_values(1:size(sc%grid_values, 1), :) = sc%grid_values
    grid_range = sc%grid_range
  end subroutine scene_lists

  !> The numbers and words of a (checked) scene, as scene_from_fields takes
  !> them; wlen(max_words), words of length >= 7 * 32 + 256 + 16 * 16 + 3 * 32.
  subroutine scene_to_fields(sc, g, length, x, words, wlen, nout, ngrid)
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: g, length
    real(dp), intent(out) :: x(n_number_fields)
    character(len=*), intent(out) :: words
    integer, intent(out) :: wlen(max_words), nout, ngrid
    integer :: i, a
    character(len=256) :: w
    x = [sc%eps, sc%theta0, sc%v0, sc%t_start, sc%t_end, real(sc%n_samples, dp), sc%damping, sc%torque, &
         sc%drive_amplitude, sc%drive_frequency, sc%drive_phase, sc%rtol, sc%atol, sc%dt, g, length, &
         sc%cycloid_radius, sc%gravity_distance, sc%gravity_gradient, sc%restitution, real(sc%max_flips, dp), &
         sc%min_flight, sc%sweep_t_max, sc%sweep_transient, real(sc%sweep_samples, dp), &
         sc%friction, sc%drag, sc%pivot_amplitude, sc%pivot_frequency, sc%noise, &
         real(sc%seed, dp)]
    nout = sc%n_outputs
    ngrid = sc%n_grid
    words = ''
    wlen = 0
    a = 1
    do i = 1, n_word_fields + nout + ngrid
      select case (i)
      case (1); w = sc%cord
      case (2); w = sc%guide
      case (3); w = sc%gravity
      case (4); w = sc%method
      case (5); w = sc%sweep
      case (6); w = sc%measure
      case (7); w = sc%name
      case default
        if (i <= n_word_fields + nout) then
          w = sc%outputs(i - n_word_fields)
        else
          w = sc%grid(i - n_word_fields - nout)
        end if
      end select
      wlen(i) = len_trim(w)
      if (wlen(i) > 0) words(a:a + wlen(i) - 1) = w(1:wlen(i))
      a = a + wlen(i)
    end do
  end subroutine scene_to_fields

  !> The words into the scene (lower case but the name); nout outputs, ngrid axes.
  subroutine set_words(sc, w, nout, ngrid)
    type(scene_t), intent(inout) :: sc
    character(len=*), intent(in) :: w(:)
    integer, intent(in) :: nout, ngrid
    integer :: i
    sc%cord = lower(w(1)); sc%guide = lower(w(2)); sc%gravity = lower(w(3)); sc%method = lower(w(4))
    sc%sweep = lower(w(5)); sc%measure = lower(w(6))
    sc%n_outputs = nout
    do i = 1, nout
      sc%outputs(i) = lower(w(n_word_fields + i))
    end do
    sc%n_grid = ngrid
    do i = 1, ngrid
      sc%grid(i) = lower(w(n_word_fields + nout + i))
    end do
  end subroutine set_words

  !> The longest word field i may hold (i as in scene_from_fields).
  pure integer function word_limit(i, nout)
    integer, intent(in) :: i, nout
    if (i == 7) then
      word_limit = 256
    else if (i > n_word_fields .and. i <= n_word_fields + nout) then
      word_limit = 16
    else
      word_limit = 32
    end if
  end function word_limit

  function too_long(i, nout) result(m)
    integer, intent(in) :: i, nout
    character(len=96) :: m
    character(len=8) :: f
    if (i <= n_word_fields) then
      f = word_fields(i)
    else if (i <= n_word_fields + nout) then
      f = 'outputs'
    else
      f = 'grid'
    end if
    write(m, '(a,i0,a)') 'field ''' // trim(f) // ''' is longer than ', word_limit(i, nout), ' characters'
  end function too_long

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

  !> Every rule about a scene.  g and length (NaN: not given) settle eps.
  !> status 0: fine (eps set, outputs default to 'trajectory'); otherwise
  !> msg names the field.
  subroutine check_scene(sc, g, length, status, msg)
    type(scene_t), intent(inout) :: sc
    real(dp), intent(in) :: g, length
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    integer :: k
    character(len=512) :: m2
    type(scene_t), allocatable :: m
    call check_fields(sc, g, length, msg)
    if (len_trim(msg) == 0) call check_grid(sc, msg)
    if (len_trim(msg) == 0) then
      if (sc%n_sweep == 0) then
        call check_member(sc, msg)
      else
        allocate(m, source=sc)
        do k = 1, sc%n_sweep
          call set_swept(m, sc%sweep, sc%sweep_values(k))
          call check_member(m, m2)
          if (len_trim(m2) > 0) then
            msg = 'field ''sweep_values'': ' // trim(sc%sweep) // ' = ' // trim(num_text(sc%sweep_values(k))) // &
                  ': ' // trim(m2)
            exit
          end if
        end do
      end if
    end if
    status = merge(1, 0, len_trim(msg) > 0)
  end subroutine check_scene

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
    if (sc%seed < 0 .or. real(sc%seed, dp) > seed_limit) then
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
    real(dp) :: w2, s0, sd0, c
    msg = ''
    if (.not. (sc%cycloid_radius > 0)) then
      msg = 'field ''cycloid_radius'' must be positive (R / l), got ' // trim(num_text(sc%cycloid_radius)); return
    end if
    if (sc%guide /= 'cycloid' .and. sc%cycloid_radius /= 0.25_dp) then
      msg = 'field ''cycloid_radius'' is used only with guide = ''cycloid'''; return
    end if
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
    end if
    if (sc%cord == 'flexible') then
      if (.not. (sc%t_start >= 0 .and. sc%t_end >= sc%t_start)) then
        msg = 'field ''t_start'': a flexible cord runs forward only (0 <= t_start <= t_end)'; return
      end if
      if (sc%method /= 'auto' .and. sc%method /= 'exact' .and. sc%method /= 'dopri5' .and. &
          sc%method /= 'dop853') then
        msg = 'field ''method'': a flexible cord is integrated between flights by dopri5 or dop853 (auto: ' // &
              'dop853), whose dense output locates the tension event; got ''' // trim(sc%method) // ''''; return
      end if
    end if
    if (sc%gravity /= 'uniform' .and. sc%method == 'gsl-rk8pd') then
      msg = 'field ''method'': gsl-rk8pd does not take a non-uniform gravity field; use dop853 or auto'; return
    end if
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
  end subroutine model_rules

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

  !> ' (did you mean 'x'?)' when one of the choices is close to word (at
  !> most a third of its letters edited), '' otherwise.
  function suggest(word, choices) result(s)
    character(len=*), intent(in) :: word, choices(:)
    character(len=64) :: s
    integer :: i, d, best, lw
    s = ''
    best = huge(1)
    lw = len_trim(word)
    if (lw == 0 .or. lw > 64) return
    do i = 1, size(choices)
      d = edit_distance(word(1:lw), trim(choices(i)))
      if (d < best .and. 3 * d <= max(lw, len_trim(choices(i)))) then
        best = d
        s = ' (did you mean ''' // trim(choices(i)) // '''?)'
      end if
    end do
  end function suggest

  !> Edit distance: insertions, deletions, substitutions and transpositions
  !> of neighbours ('dop835' is one edit from 'dop853').
  pure integer function edit_distance(a, b) result(d)
    character(len=*), intent(in) :: a, b
    integer :: c(0:len(a), 0:len(b)), i, j
    do i = 0, len(a)
      c(i, 0) = i
    end do
    do j = 0, len(b)
      c(0, j) = j
    end do
    do i = 1, len(a)
      do j = 1, len(b)
        c(i, j) = min(c(i - 1, j) + 1, c(i, j - 1) + 1, c(i - 1, j - 1) + merge(0, 1, a(i:i) == b(j:j)))
        if (i > 1 .and. j > 1) then
          if (a(i:i) == b(j - 1:j - 1) .and. a(i - 1:i - 1) == b(j:j)) c(i, j) = min(c(i, j), c(i - 2, j - 2) + 1)
        end if
      end do
    end do
    d = c(len(a), len(b))
  end function edit_distance

  !> A number as a short text that reads back to the same double (1.5, 2e-05, 1e+308, inf).
  function num_text(x) result(s)
    real(dp), intent(in) :: x
    character(len=40) :: s
    character(len=40) :: t, f
    real(dp) :: y
    integer :: d, ios, e, p
    if (x /= x) then
      s = 'nan'; return
    else if (x > huge(x)) then
      s = 'inf'; return
    else if (x < -huge(x)) then
      s = '-inf'; return
    end if
    do d = 0, 16
      write(f, '(a,i0,a)') '(es30.', d, 'e3)'
      write(t, f) x
      read(t, *, iostat=ios) y
      if (ios == 0 .and. y == x) exit
    end do
    t = adjustl(t)
    p = index(t, 'E')
    read(t(p + 1:), *) e
    if (e >= -4 .and. e < 16) then
      do d = 0, 20
        write(f, '(a,i0,a)') '(f40.', d, ')'
        write(s, f) x
        read(s, *, iostat=ios) y
        if (ios == 0 .and. y == x) exit
      end do
      s = adjustl(s)
      if (s(1:1) == '.') s = '0' // s
      if (s(1:2) == '-.') s = '-0' // s(2:)
      if (s(len_trim(s):len_trim(s)) == '.') s = trim(s) // '0'
    else
      f = t(1:p - 1)
      if (f(len_trim(f):len_trim(f)) == '.') f = f(1:len_trim(f) - 1)
      write(s, '(a,a,i0)') trim(f), 'e', e
    end if
  end function num_text

  function int_text(i) result(s)
    integer, intent(in) :: i
    character(len=16) :: s
    write(s, '(i0)') i
  end function int_text

  !> The position of the first value in s that is not of the kind wanted
  !> ('r' a number, 'i' a whole number, 's' a quoted string), 0 if none.
  !> s holds values bad_value_token accepts.
  pure integer function first_token_not(s, kind) result(at)
    character(len=*), intent(in) :: s
    character(len=1), intent(in) :: kind
    integer :: i, e
    character(len=1) :: q, got
    character(len=*), parameter :: seps = ' ,' // achar(9) // achar(10) // achar(13)
    at = 0
    i = 1
    do while (i <= len(s))
      if (index(seps, s(i:i)) > 0) then
        i = i + 1
        cycle
      end if
      if (s(i:i) == '''' .or. s(i:i) == '"') then
        q = s(i:i)
        e = i + 1
        do while (e <= len(s))
          if (s(e:e) == q) then
            if (e < len(s)) then
              if (s(e + 1:e + 1) == q) then
                e = e + 2; cycle
              end if
            end if
            exit
          end if
          e = e + 1
        end do
        got = 's'
      else
        e = i
        do while (e < len(s))
          if (index(seps // '*', s(e + 1:e + 1)) > 0) exit
          e = e + 1
        end do
        if (e < len(s)) then
          if (s(e + 1:e + 1) == '*') then   ! a repeat count: the value follows
            i = e + 2
            cycle
          end if
        end if
        if (s(i:i) == '.' .and. scan(lower(s(i:e)), 'tf') > 0) then
          got = 'l'
        else if (verify(s(i:e), '+-0123456789') == 0) then
          got = 'i'
        else
          got = 'r'
        end if
      end if
      if (.not. (got == kind .or. (kind == 'r' .and. got == 'i'))) then
        at = i; return
      end if
      i = e + 1
    end do
  end function first_token_not

  !> How many values the text of an assignment holds (a repeat count r*
  !> counts r) and whether a comma stands with no value before it.
  pure subroutine count_values(s, n, nulls)
    character(len=*), intent(in) :: s
    integer, intent(out) :: n
    logical, intent(out) :: nulls
    integer :: i, e, r
    logical :: value_since_comma
    character(len=1) :: q
    character(len=*), parameter :: blanks = ' ' // achar(9) // achar(10) // achar(13)
    n = 0
    nulls = .false.
    value_since_comma = .false.
    i = 1
    do while (i <= len(s))
      if (index(blanks, s(i:i)) > 0) then
        i = i + 1
      else if (s(i:i) == ',') then
        if (.not. value_since_comma) nulls = .true.
        value_since_comma = .false.
        i = i + 1
      else if (s(i:i) == '''' .or. s(i:i) == '"') then
        q = s(i:i)
        e = i + 1
        do while (e <= len(s))
          if (s(e:e) == q) then
            if (e < len(s)) then
              if (s(e + 1:e + 1) == q) then
                e = e + 2; cycle
              end if
            end if
            exit
          end if
          e = e + 1
        end do
        n = n + 1
        value_since_comma = .true.
        i = e + 1
      else
        e = i
        do while (e <= len(s))
          if (index(blanks // ',', s(e:e)) > 0) exit
          if (s(e:e) == '*') exit
          e = e + 1
        end do
        if (e <= len(s)) then
          if (s(e:e) == '*' .and. e > i .and. e - i <= 9 .and. verify(s(i:e - 1), '0123456789') == 0) then
            read(s(i:e - 1), *) r
            n = n + r - 1   ! the value that follows counts the last one
            i = e + 1
            cycle
          else if (s(e:e) == '*') then
            n = n + huge(1) / 2   ! a repeat count beyond any list
            i = e + 1
            cycle
          end if
        end if
        n = n + 1
        value_since_comma = .true.
        i = e
      end if
      n = min(n, huge(1) / 4)
    end do
  end subroutine count_values

  ! ------------------------------------------------------------ helpers

  !> The lexicon of values: numbers [+-]digits[.digits][(e|d)[+-]digits], quoted strings,
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
            if (index(' ,' // achar(9) // achar(10) // achar(13), s(i:i)) > 0) then
              at = i; return   ! a repeat count needs its value at once
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

  pure elemental logical function finite(x)
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
