!> pendula-run: run a scene file, write its outputs as CSV.
!>
!> Usage: pendula-run SCENE.nml [-o OUT.csv]
!> The trajectory table (t, theta, v, energy; with a first column for the swept
!> value when the scene sweeps a field) goes to OUT (standard output when -o
!> is absent).  When the scene asks for period, omega or theta_max, the orbit
!> table goes to OUT with "_orbits" before ".csv" (or follows on standard
!> output).  The header records the scene.  A bad scene is reported on
!> standard error naming the field, the exit status is 2, and no output file
!> is written.  Scenes whose effects need an integrator are run by the
!> integrators of the kernel.
program pendula_run
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use pendula_kinds, only: dp, two_pi
  use pendula_scene, only: scene_t, read_scene, scene_effects, scene_summary, max_outputs
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval, orbit_period, orbit_theta_max
  use pendula_simulate, only: simulate_scene, simulate_status_text
  use pendula_sweep, only: sweep_scene_csv
  implicit none
  character(len=4096) :: path, out, arg, orbit_out
  character(len=1024) :: msg
  type(scene_t) :: sc, member
  type(pendulum_orbit) :: o
  integer :: nargs, i, j, status, unit, ounit, nmem
  real(dp), allocatable :: t(:), theta(:), v(:), e(:), values(:)
  logical :: want_traj, want_orbit, swept
  integer :: nsteps, nrhs
  character(len=10), parameter :: regime_names(0:2) = [character(len=10) :: 'libration', 'separatrix', &
                                                       'rotation']

  nargs = command_argument_count()
  path = ''
  out = ''
  i = 1
  do while (i <= nargs)
    call get_command_argument(i, arg)
    if (arg == '-o' .or. arg == '--output') then
      if (i == nargs) call fail('option -o needs a file name')
      call get_command_argument(i + 1, out)
      i = i + 2
    else if (arg == '-h' .or. arg == '--help') then
      write(output_unit, '(a)') 'usage: pendula-run SCENE.nml [-o OUT.csv]'
      stop
    else if (len_trim(path) == 0) then
      path = arg
      i = i + 1
    else
      call fail('unexpected argument "' // trim(arg) // '" (usage: pendula-run SCENE.nml [-o OUT.csv])')
    end if
  end do
  if (len_trim(path) == 0) call fail('usage: pendula-run SCENE.nml [-o OUT.csv]')

  call read_scene(trim(path), sc, status, msg)
  if (status /= 0) call fail(trim(msg))
  if (sc%cord /= 'rigid' .or. sc%guide /= 'none' .or. sc%gravity /= 'uniform') &
    call fail(trim(path) // ': the effect(s) ' // trim(scene_effects(sc)) // &
              ' are not implemented in pendula yet', 3)

  ! --- sweeps (issue 14): a scene with a grid is run by pendula_sweep (OpenMP), CSV to OUT
  if (sc%n_grid > 0) then
    if (len_trim(out) > 0) then
      open(newunit=unit, file=trim(out), status='replace', action='write', iostat=status)
      if (status /= 0) call fail('cannot write "' // trim(out) // '"')
    else
      unit = output_unit
    end if
    call sweep_scene_csv(sc, unit, status, msg)
    if (unit /= output_unit) close(unit)
    if (status /= 0) call fail(trim(path) // ': ' // trim(msg), status)
    stop
  end if
  ! --- end sweeps
  want_traj = .false.
  want_orbit = .false.
  do i = 1, max_outputs
    select case (trim(sc%outputs(i)))
    case ('trajectory', 'theta_t', 'v_t', 'phase', 'energy', 'spectrum')
      want_traj = .true.
    case ('period', 'omega', 'theta_max', 'series')
      want_orbit = .true.
    end select
  end do
  if (want_orbit .and. len_trim(scene_effects(sc)) > 0) &
    call fail(trim(path) // ': outputs period/omega/theta_max are exact-orbit facts; the scene names ' // &
              trim(scene_effects(sc)))

  swept = sc%n_sweep > 0
  nmem = max(1, sc%n_sweep)
  allocate(values(nmem))
  if (swept) values = sc%sweep_values(1:nmem)
  allocate(t(sc%n_samples), theta(sc%n_samples), v(sc%n_samples), e(sc%n_samples))
  do j = 1, sc%n_samples
    if (sc%n_samples == 1) then
      t(j) = sc%t_start
    else
      t(j) = sc%t_start + (sc%t_end - sc%t_start) * real(j - 1, dp) / real(sc%n_samples - 1, dp)
    end if
  end do
  ! every member is checked before anything is written
  do i = 1, nmem
    member = member_of(sc, i)
    call orbit_setup(member%theta0, member%v0, member%eps, o, status)
    if (status /= 0) call fail(trim(path) // ': sweep value makes the initial state invalid (eps <= 0?)')
  end do

  if (len_trim(out) > 0) then
    open(newunit=unit, file=trim(out), status='replace', action='write', iostat=status)
    if (status /= 0) call fail('cannot write "' // trim(out) // '"')
  else
    unit = output_unit
  end if
  if (want_traj) then
    call header(unit)
    if (swept) then
      write(unit, '(a)') trim(sc%sweep) // ',t,theta,v,energy'
    else
      write(unit, '(a)') 't,theta,v,energy'
    end if
    do i = 1, nmem
      member = member_of(sc, i)
      call simulate_scene(member, t, theta, v, nsteps, nrhs, status)
      if (status /= 0) call fail(trim(path) // ': ' // trim(simulate_status_text(status)), 4)
      e = 0.5_dp * v * v + 2.0_dp * member%eps * sin(0.5_dp * theta)**2
      do j = 1, size(t)
        if (swept) then
          write(unit, '(es24.16e3,4(",",es24.16e3))') values(i), t(j), theta(j), v(j), e(j)
        else
          write(unit, '(es24.16e3,3(",",es24.16e3))') t(j), theta(j), v(j), e(j)
        end if
      end do
    end do
  end if
  if (want_orbit) then
    ounit = unit
    if (want_traj .and. len_trim(out) > 0) then
      j = index(out, '.csv', back=.true.)
      if (j > 0) then
        orbit_out = out(1:j - 1) // '_orbits.csv'
      else
        orbit_out = trim(out) // '_orbits.csv'
      end if
      open(newunit=ounit, file=trim(orbit_out), status='replace', action='write', iostat=status)
      if (status /= 0) call fail('cannot write "' // trim(orbit_out) // '"')
    else if (want_traj) then
      write(unit, '(a)') ''
    end if
    call header(ounit)
    write(ounit, '(a)') 'theta0,v0,eps,regime,k,period,omega,theta_max'
    do i = 1, nmem
      member = member_of(sc, i)
      call orbit_setup(member%theta0, member%v0, member%eps, o, status)
      write(ounit, '(3(es24.16e3,","),a,4(",",es24.16e3))') member%theta0, member%v0, member%eps, &
        trim(regime_names(o%regime)), o%k, orbit_period(o), merge(0.0_dp, two_pi / orbit_period(o), &
        orbit_period(o) > huge(1.0_dp)), orbit_theta_max(o)
    end do
    if (ounit /= unit) close(ounit)
  end if
  if (unit /= output_unit) close(unit)

contains

  function member_of(s, k) result(m)
    type(scene_t), intent(in) :: s
    integer, intent(in) :: k
    type(scene_t) :: m
    m = s
    if (s%n_sweep == 0) return
    select case (trim(s%sweep))
    case ('v0');              m%v0 = s%sweep_values(k)
    case ('theta0');          m%theta0 = s%sweep_values(k)
    case ('eps');             m%eps = s%sweep_values(k)
    case ('damping');         m%damping = s%sweep_values(k)
    case ('torque');          m%torque = s%sweep_values(k)
    case ('drive_amplitude'); m%drive_amplitude = s%sweep_values(k)
    case ('drive_frequency'); m%drive_frequency = s%sweep_values(k)
    end select
  end function member_of

  subroutine header(u)
    integer, intent(in) :: u
    write(u, '(a)') '# pendula-run ' // trim(path)
    write(u, '(a)') '# ' // trim(scene_summary(sc))
    if (len_trim(scene_effects(sc)) > 0) then
      write(u, '(a)') '# effects = ' // trim(scene_effects(sc))
      if (sc%method == 'auto') then
        write(u, '(a)') '# solver = dop853 (method auto: the scene names effects)'
      else
        write(u, '(a)') '# solver = ' // trim(sc%method)
      end if
    else
      write(u, '(a)') '# effects = none (conservative rigid pendulum: exact solution)'
    end if
  end subroutine header

  subroutine fail(text, code)
    character(len=*), intent(in) :: text
    integer, intent(in), optional :: code
    write(error_unit, '(a)') 'pendula-run: ' // trim(text)
    if (present(code)) then
      if (code == 3) stop 3, quiet=.true.
      if (code == 4) stop 4, quiet=.true.
    end if
    stop 2, quiet=.true.
  end subroutine fail

end program pendula_run
