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
  use pendula_scene_type
  use pendula_scene_text
  use pendula_scene_rules
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private
  public :: scene_t, read_scene, parse_scene, scene_from_fields, scene_to_fields, scene_lists, check_scene, &
            scene_member, &
            scene_effects, scene_has_orbit_facts, scene_summary, max_sweep, max_outputs, number_fields, &
            n_number_fields, n_word_fields, max_words, c_read_kind

  interface
    !> kernel/glue/pendula_os.c: 0 for a regular file (its size), else -errno (-10001: not a regular file)
    function c_read_kind(path, size) bind(C, name='pendula_read_kind') result(k)
      use, intrinsic :: iso_c_binding, only: c_int, c_char, c_long_long
      character(kind=c_char), intent(in) :: path(*)
      integer(c_long_long), intent(out) :: size
      integer(c_int) :: k
    end function c_read_kind
  end interface

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

end module pendula_scene
