!> pendula-run: run a scene file, write its outputs as CSV.
!>
!> Usage: pendula-run SCENE.nml [-o OUT.csv] [--check]
!> (--check: read and check the scene only; exit 0 or 2.)
!> A file whose group is &double, &foucault or &network (not &scene) is the
!> scene of that system (pendula_double_scene, pendula_foucault_scene,
!> pendula_network_scene): its path as t, theta1, theta2, omega1, omega2,
!> energy; t, x, y, z, vx, vy, vz; or t, phi_1..phi_n, v_1..v_n.
!> The trajectory table (t, theta, v, energy; with a first column for the swept
!> value when the scene sweeps a field) goes to OUT (standard output when -o
!> is absent).  When the scene asks for period, omega or theta_max, the orbit
!> table goes to OUT with "_orbits" before ".csv" (or follows on standard
!> output).  The header records the scene.  A bad scene is reported on
!> standard error naming the field, the exit status is 2, and no output file
!> is written.  Every scene goes through the kernel's dispatcher (the same
!> as the Python layer's).  Files are written under a temporary name and
!> renamed into place at the end: a failure leaves no partial or stray file.
!> Only regular files are written (a device or FIFO under OUT is refused, exit
!> 5; '-' is standard output); a missing folder is an error; temporaries are
!> removed on every exit path, SIGINT and SIGTERM included.  Numbers are
!> written with 17 significant digits, as the Python layer writes them.
!> Exit status: 0 ok, 2 bad scene or arguments, 3 model not implemented,
!> 4 the computation failed, 5 a write error.
program pendula_run
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use pendula_outfile, only: outfile_t, out_open, out_line, out_close, out_abandon, out_reals, out_errtext, &
    out_guard_signals, out_abandon_all
  use pendula_kinds, only: dp, two_pi
  use pendula_scene, only: scene_t, read_scene, scene_effects, scene_summary, scene_member, max_outputs
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval, orbit_period, orbit_theta_max
  use pendula_simulate, only: simulate_scene, select_model, sim_ok, simulate_status_text, model_orbit_facts, &
    auto_method, method_name
  use pendula_sweep, only: sweep_scene_csv
  use pendula_text, only: command_arg
  use pendula_group_file, only: scene_group
  implicit none
  character(len=:), allocatable :: path, out, arg, orbit_out
  character(len=512) :: argmsg
  character(len=512) :: line
  type(outfile_t) :: f_out, f_orbit
  character(len=512), allocatable :: log_rows(:)
  character(len=1024) :: msg
  type(scene_t) :: sc, member
  type(pendulum_orbit) :: o
  integer :: nargs, i, j, status, nmem
  logical :: two_files
  real(dp), allocatable :: t(:), theta(:), v(:), e(:), values(:)
  logical :: want_traj, want_orbit, swept, check_only = .false.
  integer :: method
  real(dp) :: stats(4)
  logical :: has_facts                               ! the cycloid's and gravity's orbit facts
  integer :: regime
  real(dp) :: orbit_k, orbit_period_value, orbit_theta_max_value
  character(len=10), parameter :: regime_names(0:2) = [character(len=10) :: 'libration', 'separatrix', &
                                                       'rotation']

  ! SIGINT, SIGTERM, SIGHUP: the temporary files are removed before the program dies
  call out_guard_signals()
  nargs = command_argument_count()
  path = ''
  out = ''
  i = 1
  do while (i <= nargs)
    call command_arg(i, arg, argmsg)
    if (arg == '-o' .or. arg == '--output') then
      if (i == nargs) call fail('option -o needs a file name')
      call command_arg(i + 1, out, argmsg)
      if (len_trim(argmsg) > 0) call fail(trim(argmsg))
      i = i + 2
    else if (arg == '-h' .or. arg == '--help') then
      write(output_unit, '(a)') 'usage: pendula-run SCENE.nml [-o OUT.csv] [--check]'
      stop, quiet=.true.
    else if (arg == '--check') then
      check_only = .true.
      i = i + 1
    else if (len(path) == 0) then
      if (len_trim(argmsg) > 0) call fail(trim(argmsg))
      path = arg
      i = i + 1
    else
      call fail('unexpected argument "' // trim(arg) // '" (usage: pendula-run SCENE.nml [-o OUT.csv] [--check])')
    end if
  end do
  if (len(path) == 0) call fail('usage: pendula-run SCENE.nml [-o OUT.csv] [--check]')

  ! a file whose namelist group is a system built by its own class: that system's reader and run
  select case (scene_group(path))
  case ('double', 'foucault', 'network')
    call run_system_file()
    stop, quiet=.true.
  end select
  call read_scene(path, sc, status, msg)
  if (status /= 0) call fail(trim(msg))
  ! quiet: no gfortran note on the IEEE flags a literal such as 1e-400 raised (it reads as 0, by the rule)
  if (check_only) stop, quiet=.true.   ! --check: read and check the scene, run nothing
  call select_model(sc, i, status, msg)
  if (status /= sim_ok) call fail(path // ': ' // trim(msg), 3)

  ! a scene with a grid is run by pendula_sweep (OpenMP), CSV to OUT through
  ! the checked writer (a temporary name renamed at the end; a write error,
  ! such as a full disk, is exit 5 and leaves nothing)
  if (sc%n_grid > 0) then
    if (len(out) == 0) out = '-'
    call out_open(f_out, out, status)
    if (status /= 0) call fail_io('cannot write "' // out // '"', status)
    call sweep_scene_csv(sc, f_out, status, msg)
    if (status == 5) call fail_io('cannot write "' // out // '"', f_out%err)
    if (status /= 0) call fail(path // ': ' // trim(msg), status)
    call out_close(f_out, status)
    if (status /= 0) call fail_io('cannot write "' // out // '"', status)
    stop, quiet=.true.
  end if
  want_traj = .false.
  want_orbit = .false.
  ! which outputs may go with which scene is the scene's rule (check_scene):
  ! every scene read here can have the outputs it names
  do i = 1, sc%n_outputs
    select case (trim(sc%outputs(i)))
    case ('trajectory', 'theta_t', 'v_t', 'phase', 'energy', 'spectrum')
      want_traj = .true.
    case ('period', 'omega', 'theta_max', 'series')
      want_orbit = .true.
    end select
  end do

  swept = sc%n_sweep > 0
  nmem = max(1, sc%n_sweep)
  allocate(values(nmem))
  if (swept) values = sc%sweep_values(1:nmem)
  ! a scene at the limits (n_samples = 1e8) needs GBs: too little memory is exit 4, one line
  allocate(t(sc%n_samples), theta(sc%n_samples), v(sc%n_samples), e(sc%n_samples), stat=status)
  if (status /= 0) call fail_memory(sc%n_samples)
  ! the times as numpy.linspace forms them (the Python layer's), so that both
  ! programs write the same trajectory to the digit: start + j * step, the last one t_end
  do j = 1, sc%n_samples
    if (sc%n_samples == 1) then
      t(j) = sc%t_start
    else
      t(j) = real(j - 1, dp) * ((sc%t_end - sc%t_start) / real(sc%n_samples - 1, dp)) + sc%t_start
    end if
  end do
  if (sc%n_samples > 1) t(sc%n_samples) = sc%t_end

  ! the flexible cord writes its own table (with x, y, r) and a flip log
  if (sc%cord == 'flexible') then
    call run_cord()
    stop, quiet=.true.
  end if
  ! everything goes through the checked writer: OUT (or standard output, '-')
  if (len(out) == 0) out = '-'
  call out_open(f_out, out, status)
  if (status /= 0) call fail_io('cannot write "' // out // '"', status)
  two_files = want_traj .and. want_orbit .and. out /= '-'
  if (two_files) then
    orbit_out = beside(out, '_orbits.csv')
    call out_open(f_orbit, orbit_out, status)
    if (status /= 0) call fail_io('cannot write "' // orbit_out // '"', status)
  end if
  if (want_traj) then
    call header(f_out)
    if (swept) then
      call out_line(f_out, trim(sc%sweep) // ',t,theta,v,energy')
    else
      call out_line(f_out, 't,theta,v,energy')
    end if
    do i = 1, nmem
      member = scene_member(sc, i)
      call simulate_scene(member, t, theta, v, e, stats, method, status, msg)
      if (status /= sim_ok) call fail(path // ': ' // trim(msg), 4)
      do j = 1, size(t)
        if (swept) then
          call out_line(f_out, out_reals([values(i), t(j), theta(j), v(j), e(j)]))
        else
          call out_line(f_out, out_reals([t(j), theta(j), v(j), e(j)]))
        end if
      end do
    end do
  end if
  if (want_orbit) then
    if (two_files) then
      call orbit_table(f_orbit)
    else
      if (want_traj) call out_line(f_out, '')
      call orbit_table(f_out)
    end if
  end if
  ! written, made durable and renamed into place only now; errors are exit 5
  if (two_files) then
    call out_close(f_orbit, status)
    if (status /= 0) call fail_io('cannot write "' // orbit_out // '"', status)
  end if
  call out_close(f_out, status)
  if (status /= 0) then
    if (out == '-') call fail_io('cannot write to standard output', status)
    call fail_io('cannot write "' // out // '"', status)
  end if

contains

  !> A second output file beside OUT, in its folder: OUT without a final
  !> '.csv', then the suffix ('_orbits.csv', '_flips.csv').
  pure function beside(path, suffix) result(name)
    character(len=*), intent(in) :: path, suffix
    character(len=len(path) + len(suffix)) :: name
    integer :: j
    j = len(path)
    if (j > 4) then
      if (path(j - 3:j) == '.csv') j = j - 4
    end if
    name = path(1:j) // suffix
  end function beside

  !> The flexible cord: its table (t, theta, v, energy, x, y, r) and its flip log
  !> (OUT_flips.csv beside OUT, or following on standard output), through the
  !> checked writer like every other output.
  !> With or without effects, through the dispatcher (cord_scene_run), as pendula.simulate.
  subroutine run_cord()
    use pendula_simulate, only: cord_scene_run, cord_integrated, sim_cord_effects
    real(dp), allocatable :: x(:), y(:), r(:), flips(:, :)
    real(dp) :: stats(4)
    type(outfile_t) :: f_flips
    integer :: k, m, nfl, stp, st, meth
    logical :: two
    character(len=:), allocatable :: flips_out
    character(len=64) :: pre
    character(len=10), parameter :: stops(0:2) = [character(len=10) :: 't_end', 'max_flips', 'min_flight']
    allocate(x(size(t)), y(size(t)), r(size(t)), stat=st)
    if (st /= 0) call fail_memory(size(t))
    if (len(out) == 0) out = '-'
    call out_open(f_out, out, st)
    if (st /= 0) call fail_io('cannot write "' // out // '"', st)
    two = out /= '-'
    if (two) then
      flips_out = beside(out, '_flips.csv')
      call out_open(f_flips, flips_out, st)
      if (st /= 0) call fail_io('cannot write "' // flips_out // '"', st)
    end if
    call header(f_out)
    if (cord_integrated(sc)) then
      pre = sc%method
      if (sc%method == 'auto') pre = 'dop853'
      write(line, '(a, f0.6, a)') '# flexible cord: circle phases integrated to the tension event (' // &
        trim(pre) // '), parabolic flights, jerk (restitution = ', sc%restitution, ')'
    else
      write(line, '(a, f0.6, a)') '# flexible cord: exact circle phases, parabolic flights, jerk (restitution = ', &
        sc%restitution, ')'
    end if
    call out_line(f_out, line)
    if (swept) then
      call out_line(f_out, trim(sc%sweep) // ',t,theta,v,energy,x,y,r')
    else
      call out_line(f_out, 't,theta,v,energy,x,y,r')
    end if
    allocate(log_rows(0))
    do m = 1, nmem
      member = scene_member(sc, m)
      call cord_scene_run(member, t, theta, v, x, y, r, flips, nfl, stp, stats, meth, st)
      if (st == sim_cord_effects) call fail(path // ': ' // trim(simulate_status_text(st)))
      if (st /= 0) call fail(path // ': ' // trim(simulate_status_text(st)), 4)
      e = 0.5_dp * v * v + 2.0_dp * member%eps * sin(0.5_dp * theta)**2
      pre = ''
      if (swept) pre = out_reals([values(m)]) // ','
      do k = 1, size(t)
        call out_line(f_out, trim(pre) // out_reals([t(k), theta(k), v(k), e(k), x(k), y(k), r(k)]))
      end do
      ! the flip log: one line per flip, or one line naming the stop reason of a member without flips
      if (nfl == 0) then
        write(line, '(i0,a)') m, ',,,,,,,,,' // trim(stops(stp))
        log_rows = [character(len=512) :: log_rows, line]
      end if
      do k = 1, nfl
        write(line, '(i0)') m
        line = trim(line) // ',' // out_reals(flips(:, k)) // ',' // trim(stops(stp))
        log_rows = [character(len=512) :: log_rows, line]
      end do
    end do
    if (.not. two) then
      call out_line(f_out, '')
      call flip_log(f_out)
    else
      call flip_log(f_flips)
      call out_close(f_flips, st)
      if (st /= 0) call fail_io('cannot write "' // flips_out // '"', st)
    end if
    call out_close(f_out, st)
    if (st /= 0) call fail_io('cannot write "' // out // '"', st)
  end subroutine run_cord

  !> The flip log of the flexible cord's runs (rows gathered in log_rows).
  subroutine flip_log(f)
    type(outfile_t), intent(inout) :: f
    integer :: i
    call out_line(f, '# pendula-run flip log ' // path)
    call out_line(f, 'member,t_leave,theta_leave,t_return,theta_return,xi_before,xi_after,v_leave,v_return,' // &
      'run_stop_reason')
    do i = 1, size(log_rows)
      call out_line(f, log_rows(i))
    end do
  end subroutine flip_log

  subroutine orbit_table(f)
    type(outfile_t), intent(inout) :: f
    call header(f)
    call out_line(f, 'theta0,v0,eps,regime,k,period,omega,theta_max')
    do i = 1, nmem
      member = scene_member(sc, i)
      call model_orbit_facts(member, has_facts, regime, orbit_k, orbit_period_value, orbit_theta_max_value, status)
      if (has_facts) then   ! the cycloid and gravity models' orbit facts
        if (status /= 0) call fail(path // ': ' // trim(simulate_status_text(status)), 4)
        call out_line(f, out_reals([member%theta0, member%v0, member%eps]) // ',' // &
          trim(regime_names(regime)) // ',' // &
          out_reals([orbit_k, orbit_period_value, merge(0.0_dp, two_pi / orbit_period_value, &
          orbit_period_value > huge(1.0_dp)), orbit_theta_max_value]))
        cycle
      end if
      call orbit_setup(member%theta0, member%v0, member%eps, o, status)
      call out_line(f, out_reals([member%theta0, member%v0, member%eps]) // ',' // &
        trim(regime_names(o%regime)) // ',' // out_reals([o%k, orbit_period(o), &
        merge(0.0_dp, two_pi / orbit_period(o), orbit_period(o) > huge(1.0_dp)), orbit_theta_max(o)]))
    end do
  end subroutine orbit_table

  subroutine header(f)
    type(outfile_t), intent(inout) :: f
    character(len=:), allocatable :: summary
    integer :: a, b
    call out_line(f, '# pendula-run ' // path)
    ! the summary holds several lines: one out_line each
    summary = '# ' // trim(scene_summary(sc)) // new_line('a')
    a = 1
    do
      b = index(summary(a:), new_line('a'))
      if (b == 0) exit
      call out_line(f, summary(a:a + b - 2))
      a = a + b
    end do
    if (len_trim(scene_effects(sc)) > 0) then
      call out_line(f, '# effects = ' // trim(scene_effects(sc)))
      if (sc%guide == 'cycloid') then   ! closed form
        call out_line(f, '# solver = exact (the cycloidal pendulum: a harmonic oscillator in s, closed form)')
      else if (sc%method == 'auto') then
        call out_line(f, '# solver = ' // trim(method_name(auto_method(sc, .false.))) // &
                      ' (method auto: the work-precision study''s pick for the scene''s class and rtol)')
      else
        call out_line(f, '# solver = ' // trim(sc%method))
      end if
    else
      call out_line(f, '# effects = none (conservative rigid pendulum: exact solution)')
    end if
  end subroutine header

  !> A scene of a system built by its own class (&double, &foucault, &network; pendula_system_scenes, the
  !> Python layer's reader and run too): its table t, theta1, theta2, omega1, omega2, energy; t, x, y, z,
  !> vx, vy, vz; or t, phi_1 ... phi_n, v_1 ... v_n.  A bad scene is exit 2, a failed run exit 4.
  subroutine run_system_file()
    use pendula_system_scenes, only: system_scene_size, system_scene_table
    real(dp), allocatable :: table(:, :)
    character(len=16) :: group
    character(len=24000) :: heads
    character(len=256) :: title
    integer :: st, nrows, ncols, k
    call system_scene_size(path, group, nrows, ncols, st, msg)
    if (st /= 0) call fail(trim(msg))
    if (check_only) stop, quiet=.true.
    allocate(table(nrows, ncols), stat=st)
    if (st /= 0) call fail_memory(nrows)
    call system_scene_table(path, table, heads, title, st, msg)
    if (st == 4) call fail(trim(msg), 4)
    if (st /= 0) call fail(trim(msg))
    if (len(out) == 0) out = '-'
    call out_open(f_out, out, st)
    if (st /= 0) call fail_io('cannot write "' // out // '"', st)
    call out_line(f_out, '# pendula-run ' // path)
    call out_line(f_out, '# ' // trim(title))
    call out_line(f_out, trim(heads))
    do k = 1, nrows
      call out_line(f_out, out_reals(table(k, :)))
    end do
    call out_close(f_out, st)
    if (st /= 0) then
      if (out == '-') call fail_io('cannot write to standard output', st)
      call fail_io('cannot write "' // out // '"', st)
    end if
  end subroutine run_system_file

  !> Too little memory for the arrays of n samples: the computation failed (exit 4).
  subroutine fail_memory(n)
    integer, intent(in) :: n
    character(len=32) :: num
    write(num, '(i0)') n
    call fail(path // ': not enough memory for the arrays of ' // trim(num) // ' samples', 4)
  end subroutine fail_memory

  subroutine fail_io(text, err)
    character(len=*), intent(in) :: text
    integer, intent(in) :: err
    call fail(trim(text) // ': ' // out_errtext(err), 5)
  end subroutine fail_io

  !> Report on standard error, remove any temporary file, exit with code (default 2).
  subroutine fail(text, code)
    character(len=*), intent(in) :: text
    integer, intent(in), optional :: code
    write(error_unit, '(a)') 'pendula-run: ' // trim(text)
    call out_abandon(f_out)
    call out_abandon(f_orbit)
    call out_abandon_all()   ! any other file still open (the flip log)
    if (present(code)) then
      if (code == 3) stop 3, quiet=.true.
      if (code == 4) stop 4, quiet=.true.
      if (code == 5) stop 5, quiet=.true.
    end if
    stop 2, quiet=.true.
  end subroutine fail

end program pendula_run
