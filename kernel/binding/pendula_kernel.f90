! The thin layer that f2py wraps into the private extension pendula._kernel.
! Plain subroutines, explicit-shape float64 arrays whose sizes derive from the
! inputs, no derived types.  The Python layer (python/pendula) broadcasts,
! checks arguments and maps status codes to exceptions and warnings.

subroutine gsl_init()
  use pendula_gsl_iface, only: pendula_gsl_init
  implicit none
  call pendula_gsl_init()
end subroutine gsl_init

! The complete integrals and the nome.  mc holds the complement for every
! element (nmc = n), or nmc = 1 and the kernel forms mc = 1 - m itself.
subroutine ellipk_v(n, nmc, m, mc, k)
  use pendula_elliptic, only: ellip_k_array
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n, nmc
  double precision, intent(in) :: m(n), mc(nmc)
  double precision, intent(out) :: k(n)
  !f2py intent(hide), depend(m) :: n = len(m)
  !f2py intent(hide), depend(mc) :: nmc = len(mc)
  if (nmc == n) then
    call ellip_k_array(m, k, mc)
  else
    call ellip_k_array(m, k)
  end if
end subroutine ellipk_v

subroutine ellipe_v(n, nmc, m, mc, e)
  use pendula_elliptic, only: ellip_e
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n, nmc
  double precision, intent(in) :: m(n), mc(nmc)
  double precision, intent(out) :: e(n)
  !f2py intent(hide), depend(m) :: n = len(m)
  !f2py intent(hide), depend(mc) :: nmc = len(mc)
  if (nmc == n) then
    e = ellip_e(m, mc)
  else
    e = ellip_e(m, 1.0d0 - m)
  end if
end subroutine ellipe_v

subroutine ellipf_v(n, phi, m, mc, f)
  use pendula_elliptic, only: ellip_f
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n
  double precision, intent(in) :: phi(n), m(n), mc(n)
  double precision, intent(out) :: f(n)
  !f2py intent(hide), depend(phi) :: n = len(phi)
  f = ellip_f(phi, m, mc)
end subroutine ellipf_v

subroutine ellipeinc_v(n, phi, m, mc, e)
  use pendula_elliptic, only: ellip_einc
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n
  double precision, intent(in) :: phi(n), m(n), mc(n)
  double precision, intent(out) :: e(n)
  !f2py intent(hide), depend(phi) :: n = len(phi)
  e = ellip_einc(phi, m, mc)
end subroutine ellipeinc_v

subroutine nome_v(n, nmc, m, mc, q)
  use pendula_elliptic, only: ellip_nome
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n, nmc
  double precision, intent(in) :: m(n), mc(nmc)
  double precision, intent(out) :: q(n)
  !f2py intent(hide), depend(m) :: n = len(m)
  !f2py intent(hide), depend(mc) :: nmc = len(mc)
  if (nmc == n) then
    q = ellip_nome(m, mc)
  else
    q = ellip_nome(m, 1.0d0 - m)
  end if
end subroutine nome_v

! Jacobi functions; nm = 1 means one parameter for all u (prepared once).
! sn, cn, dn, am are written into arrays the caller allocates (numpy.empty):
! f2py's own outputs would be zero-filled first, one more pass over 4 arrays
! (3 ns per element of the 58 with m per element).
subroutine ellipj_v(n, nm, u, m, mc, sn, cn, dn, am, status)
  use pendula_elliptic, only: jacobi_plan, jacobi_prepare, jacobi_eval_array, jacobi_eval_varm
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n, nm
  double precision, intent(in) :: u(n), m(nm), mc(nm)
  double precision, intent(inout) :: sn(n), cn(n), dn(n), am(n)
  integer, intent(out) :: status
  !f2py intent(hide), depend(u) :: n = len(u)
  !f2py intent(hide), depend(m) :: nm = len(m)
  type(jacobi_plan) :: plan
  status = 0
  if (nm /= 1 .and. nm /= n) then
    status = 1
    return
  end if
  if (nm == 1) then
    plan = jacobi_prepare(m(1), mc(1))
    call jacobi_eval_array(plan, u, sn, cn, dn, am)
  else
    call jacobi_eval_varm(u, m, mc, sn, cn, dn, am)
  end if
end subroutine ellipj_v

subroutine gsl_elljac_v(n, u, m, sn, cn, dn, bad)
  use pendula_gsl_iface, only: pendula_gsl_elljac
  implicit none
  integer, intent(in) :: n
  double precision, intent(in) :: u(n), m(n)
  double precision, intent(out) :: sn(n), cn(n), dn(n)
  integer, intent(out) :: bad
  !f2py intent(hide), depend(u) :: n = len(u)
  bad = pendula_gsl_elljac(n, u, m, sn, cn, dn)
end subroutine gsl_elljac_v

subroutine gsl_kcomp_v(n, m, k, bad)
  use pendula_gsl_iface, only: pendula_gsl_kcomp
  implicit none
  integer, intent(in) :: n
  double precision, intent(in) :: m(n)
  double precision, intent(out) :: k(n)
  integer, intent(out) :: bad
  !f2py intent(hide), depend(m) :: n = len(m)
  bad = pendula_gsl_kcomp(n, m, k)
end subroutine gsl_kcomp_v

! GSL's Mathieu characteristic values a_n(q) (kind 1) or b_n(q) (kind 2),
! one gsl_sf_mathieu_a_e/_b_e call per value: the peer of the benchmark.
subroutine gsl_mathieu_v(n, kind, order, q, val, bad)
  use pendula_gsl_iface, only: pendula_gsl_mathieu
  implicit none
  integer, intent(in) :: n, kind
  integer, intent(in) :: order(n)
  double precision, intent(in) :: q(n)
  double precision, intent(out) :: val(n)
  integer, intent(out) :: bad
  !f2py intent(hide), depend(q) :: n = len(q)
  bad = pendula_gsl_mathieu(kind, n, order, q, val)
end subroutine gsl_mathieu_v

! Exact motion of the conservative pendulum at the times t (status: 0 ok,
! 1 bad eps, 2 bad theta0, 3 bad v0).
subroutine exact_motion_v(n, theta0, v0, eps, t, theta, v, status)
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n
  double precision, intent(in) :: theta0, v0, eps, t(n)
  double precision, intent(out) :: theta(n), v(n)
  integer, intent(out) :: status
  !f2py intent(hide), depend(t) :: n = len(t)
  type(pendulum_orbit) :: o
  call orbit_setup(theta0, v0, eps, o, status)
  if (status /= 0) return
  call orbit_eval(o, t, theta, v)
end subroutine exact_motion_v

! Orbit facts: info = [regime, k, m, mc, period, theta_max, u0, mc_lo]
subroutine exact_info_v(theta0, v0, eps, info, status)
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_period, orbit_theta_max
  implicit none
  double precision, intent(in) :: theta0, v0, eps
  double precision, intent(out) :: info(8)
  integer, intent(out) :: status
  type(pendulum_orbit) :: o
  info = 0.0d0
  call orbit_setup(theta0, v0, eps, o, status)
  if (status /= 0) return
  info = [dble(o%regime), o%k, o%m, o%mch, orbit_period(o), orbit_theta_max(o), o%u0, o%mcl]
end subroutine exact_info_v

! ---------------------------------------------------------------- scenes and the dispatcher
! A scene crosses the binding as fields: x(31) the numbers in the order of
! pendula_scene's number_fields (scene_layout_v), the words one after another
! in `words` with their lengths wlen: cord, guide, gravity, method, sweep,
! measure, name, then nout outputs, then ngrid grid axes.

! The kernel's order of a scene's numbers and word fields (blank separated, numbers first, then '|').
subroutine scene_layout_v(names)
  use pendula_scene, only: number_fields
  implicit none
  character(len=1024), intent(out) :: names
  integer :: i
  names = ''
  do i = 1, size(number_fields)
    names = trim(names) // ' ' // trim(number_fields(i))
  end do
  names = trim(names) // ' | cord guide gravity method sweep measure name'
end subroutine scene_layout_v

! Read and check a scene's text (source: the file's name, for messages):
! status 0 and the scene's fields, or status 1 and msg naming the field
! (and the line).  With from_file = 1, source is a file's path and text is not
! used: the file is read as pendula-run reads it (read_scene), so that both
! programs give every file one verdict with one message (a folder, a device,
! UTF-16 text, a NUL byte, more than 16 MiB).
subroutine scene_read_v(text, source, x, words, wlen, nout, ngrid, sweep_values, nsweep, grid_values, grid_nv, &
                        grid_range, grid_nr, status, msg, from_file)
  use pendula_scene, only: scene_t, parse_scene, read_scene, scene_to_fields, scene_lists
  implicit none
  character(len=*), intent(in) :: text, source
  integer, intent(in) :: from_file
  !f2py integer optional, intent(in) :: from_file = 0
  double precision, intent(out) :: x(31), sweep_values(4096), grid_values(4096, 3), grid_range(3, 3)
  character(len=1024), intent(out) :: words
  integer, intent(out) :: wlen(26), nout, ngrid, nsweep, grid_nv(3), grid_nr(3), status
  character(len=2048), intent(out) :: msg
  type(scene_t), allocatable :: sc
  double precision :: g, length
  allocate(sc)
  x = 0; words = ''; wlen = 0; nout = 0; ngrid = 0; nsweep = 0; grid_nv = 0; grid_nr = 0
  sweep_values = 0; grid_values = 0; grid_range = 0
  if (from_file == 1) then
    call read_scene(source, sc, status, msg, g, length)
  else
    call parse_scene(text, source, sc, status, msg, g, length)
  end if
  if (status /= 0) return
  call scene_to_fields(sc, g, length, x, words, wlen, nout, ngrid)
  call scene_lists(sc, sweep_values, nsweep, grid_values, grid_nv, grid_range, grid_nr)
end subroutine scene_read_v

! Check a scene given as fields with the kernel's rules: status 0 and the
! checked scene's numbers and words (eps settled, words in lower case, the
! default output), or status 1 and msg naming the field.
subroutine scene_check_v(x, words, nw, wlen, nout, ngrid, ns, sweep_values, n1, grid1, n2, grid2, n3, grid3, &
                         nr1, grid1_range, nr2, grid2_range, nr3, grid3_range, x_out, words_out, wlen_out, &
                         nout_out, ngrid_out, status, msg)
  use pendula_scene, only: scene_t, scene_from_fields, scene_to_fields
  implicit none
  double precision, intent(in) :: x(31)
  character(len=*), intent(in) :: words
  integer, intent(in) :: nw, nout, ngrid, ns, n1, n2, n3, nr1, nr2, nr3
  integer, intent(in) :: wlen(nw)
  double precision, intent(in) :: sweep_values(ns), grid1(n1), grid2(n2), grid3(n3), grid1_range(nr1), &
                                  grid2_range(nr2), grid3_range(nr3)
  !f2py intent(hide), depend(wlen) :: nw = len(wlen)
  !f2py intent(hide), depend(sweep_values) :: ns = len(sweep_values)
  !f2py intent(hide), depend(grid1) :: n1 = len(grid1)
  !f2py intent(hide), depend(grid2) :: n2 = len(grid2)
  !f2py intent(hide), depend(grid3) :: n3 = len(grid3)
  !f2py intent(hide), depend(grid1_range) :: nr1 = len(grid1_range)
  !f2py intent(hide), depend(grid2_range) :: nr2 = len(grid2_range)
  !f2py intent(hide), depend(grid3_range) :: nr3 = len(grid3_range)
  double precision, intent(out) :: x_out(31)
  character(len=1024), intent(out) :: words_out
  integer, intent(out) :: wlen_out(26), nout_out, ngrid_out, status
  character(len=2048), intent(out) :: msg
  type(scene_t), allocatable :: sc
  double precision :: g, length
  allocate(sc)
  x_out = 0; words_out = ''; wlen_out = 0; nout_out = 0; ngrid_out = 0
  call scene_from_fields(x, words, wlen, nout, ngrid, sweep_values, grid1, grid2, grid3, grid1_range, &
                         grid2_range, grid3_range, .true., sc, g, length, status, msg)
  if (status /= 0) return
  call scene_to_fields(sc, g, length, x_out, words_out, wlen_out, nout_out, ngrid_out)
end subroutine scene_check_v

! A user's force crosses the binding as an address (f2py cannot wrap procedure pointers): faddr is
! the address of a C function double f(double t, double theta, double v, const double *params)
! (a ctypes function, a numba cfunc), converted by c_f_procpointer in the kernel; fparams(np) is
! passed to it as given.
!
! Run a checked scene (its fields, as scene_check_v returns them; no sweep)
! at the times t (sorted ascending when an integrator answers).  method: the
! code of what answered (0 = exact path); status 0 ok, otherwise msg says why
! (see pendula_simulate; 100: the fields do not form a scene).  recheck = 1: the
! kernel checks the fields first (check_scene, the one checker: a scene whose
! integrator knobs were changed without building a new Scene); land = 1: the
! adaptive pairs end their steps on the output times.
subroutine simulate_v(x, words, nw, wlen, nout, ngrid, n, t, faddr, np, fparams, cancel, recheck, land, theta, v, &
                      energy, stats, method, status, msg)
  use, intrinsic :: iso_c_binding, only: c_funptr, c_intptr_t
  use pendula_scene, only: scene_t, scene_from_fields
  use pendula_simulate, only: simulate_scene
  implicit none
  !f2py threadsafe
  double precision, intent(in) :: x(31)
  character(len=*), intent(in) :: words
  integer, intent(in) :: recheck, land
  !f2py integer optional, intent(in) :: recheck = 0
  !f2py integer optional, intent(in) :: land = 0
  integer, intent(in) :: nw, nout, ngrid, n, np
  integer, intent(in) :: wlen(nw)
  double precision, intent(in) :: t(n)
  !> a user's force added to the scene's force law (its address, as said above; 0: none) and the
  !> params it reads
  integer(8), intent(in) :: faddr
  double precision, intent(in), target :: fparams(np)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: theta(n), v(n), energy(n), stats(4)
  integer, intent(out) :: method, status
  character(len=512), intent(out) :: msg
  !f2py intent(hide), depend(wlen) :: nw = len(wlen)
  !f2py intent(hide), depend(t) :: n = len(t)
  !f2py intent(hide), depend(fparams) :: np = len(fparams)
  type(scene_t) :: sc
  type(c_funptr) :: f
  double precision :: g, length, none(0)
  method = -1
  theta = 0; v = 0; energy = 0; stats = 0
  call scene_from_fields(x, words, wlen, nout, ngrid, none, none, none, none, none, none, none, recheck /= 0, sc, &
                         g, length, status, msg)
  if (status /= 0) then
    status = 100
    return
  end if
  if (faddr == 0) then
    call simulate_scene(sc, t, theta, v, energy, stats, method, status, msg, cancel(1), land=land /= 0)
  else
    f = transfer(int(faddr, c_intptr_t), f)
    call simulate_scene(sc, t, theta, v, energy, stats, method, status, msg, cancel(1), f, fparams, land /= 0)
  end if
end subroutine simulate_v

! The model registry, one model per line of `table` (fields separated by '|':
! name, selector, effects, exact_with, path, implemented, summary, state, parameters, and
! 'scene' for a model a scene selects or 'class' for one built by its own class, time scales).
subroutine models_v(table)
  use pendula_system, only: registry, n_scene_models
  implicit none
  character(len=8192), intent(out) :: table
  integer :: i
  table = ''
  do i = 1, size(registry)
    table = trim(table) // trim(registry(i)%name) // '|' // trim(registry(i)%selector) // '|' // &
      trim(registry(i)%effects) // '|' // trim(registry(i)%exact_with) // '|' // trim(registry(i)%path) // &
      '|' // merge('yes', 'no ', registry(i)%implemented) // '|' // trim(registry(i)%summary) // '|' // &
      trim(registry(i)%state) // '|' // trim(registry(i)%parameters) // '|' // &
      trim(merge('scene', 'class', i <= n_scene_models)) // '|' // trim(registry(i)%time_scales) // new_line('a')
  end do
end subroutine models_v

! The capability table (pendula_system), one row per line: tool|system|honours|planned|needs|note.
subroutine capability_table_v(table)
  use pendula_system, only: capability_table
  implicit none
  character(len=16384), intent(out) :: table
  table = capability_table()
end subroutine capability_table_v

! Does `tool` honour every effect of the scene (and the fields named in
! `swept`, and a user's force when force /= 0)?  status 0; 2 refused, 3 not
! implemented, 4 unknown tool (msg names the field); 100 the fields do not
! form a scene.
subroutine capability_check_v(x, words, nw, wlen, nout, ngrid, tool, swept, force, status, msg)
  use pendula_scene, only: scene_t, scene_from_fields
  use pendula_system, only: capability_check
  implicit none
  double precision, intent(in) :: x(31)
  character(len=*), intent(in) :: words, tool, swept
  integer, intent(in) :: nw, nout, ngrid, force
  integer, intent(in) :: wlen(nw)
  integer, intent(out) :: status
  character(len=512), intent(out) :: msg
  !f2py intent(hide), depend(wlen) :: nw = len(wlen)
  type(scene_t) :: sc
  double precision :: g, length, none(0)
  call scene_from_fields(x, words, wlen, nout, ngrid, none, none, none, none, none, none, none, .false., sc, &
                         g, length, status, msg)
  if (status /= 0) then
    status = 100
    return
  end if
  call capability_check(sc, tool, swept, force /= 0, status, msg)
end subroutine capability_check_v

! Does `tool` honour every effect that the fields named in `fields` (blank-
! separated: the fields of `system` that are on) turn on?  For the systems
! built by their own class (pendula.Network, ...).  status 0; 2 refused, 3 not
! implemented (msg names the field); 4 a system, tool or field the table does
! not know.
subroutine capability_check_fields_v(system, tool, fields, status, msg)
  use pendula_system, only: capability_check_fields
  implicit none
  character(len=*), intent(in) :: system, tool, fields
  integer, intent(out) :: status
  character(len=512), intent(out) :: msg
  call capability_check_fields(system, tool, fields, status, msg)
end subroutine capability_check_fields_v

! The scene's time scales as rates (1 / time; pendula_time_scales, in the
! order of `names`, 12 characters each), the angular frequency of its
! periodic forcing (pendula_system's scene_forcing: fstatus 0 forced, 1
! autonomous, 2 a drive and a pivot at different frequencies), and the
! Langevin default step.  status 100: the fields do not form a scene.
subroutine scene_time_scales_v(x, words, nw, wlen, nout, ngrid, rates, names, omega, fstatus, langevin_dt, status)
  use pendula_scene, only: scene_t, scene_from_fields
  use pendula_system, only: scene_rates, scene_forcing
  use pendula_time_scales, only: scale_names
  use pendula_langevin, only: langevin_default_dt
  implicit none
  double precision, intent(in) :: x(31)
  character(len=*), intent(in) :: words
  integer, intent(in) :: nw, nout, ngrid
  integer, intent(in) :: wlen(nw)
  double precision, intent(out) :: rates(9), omega, langevin_dt
  character(len=108), intent(out) :: names
  integer, intent(out) :: fstatus, status
  !f2py intent(hide), depend(wlen) :: nw = len(wlen)
  type(scene_t) :: sc
  double precision :: g, length, none(0)
  character(len=512) :: msg
  integer :: i
  rates = 0; omega = 0; fstatus = 1; langevin_dt = 0
  names = ''
  do i = 1, size(scale_names)
    names(12 * (i - 1) + 1:12 * i) = scale_names(i)
  end do
  call scene_from_fields(x, words, wlen, nout, ngrid, none, none, none, none, none, none, none, .false., sc, &
                         g, length, status, msg)
  if (status /= 0) then
    status = 100
    return
  end if
  rates = scene_rates(sc)
  call scene_forcing(sc, omega, fstatus)
  langevin_dt = langevin_default_dt(rates)
end subroutine scene_time_scales_v

! Integrate a checked scene's model (its fields, as scene_check_v returns
! them) from its theta0, v0: method codes 1..9, 11, 12 (see
! pendula_integrators), 10 = GSL rk8pd.  t must be sorted ascending.
! stats = [steps, accepted, rejected, rhs evaluations]; status 100: the
! fields do not form a scene.
subroutine integrate_v(x, words, nw, wlen, nout, ngrid, n, method, t, ev_kind, ev_level, &
                       ev_dir, ev_terminal, max_ev, cancel, theta, v, stats, status, nev, tev, thev, vev)
  use, intrinsic :: iso_c_binding, only: c_loc
  use pendula_kinds, only: dp
  use pendula_scene, only: scene_t, scene_from_fields
  use pendula_simulate, only: scene_model
  use pendula_integrators, only: pendulum_model, event_spec, run_stats, integrate
  use pendula_gsl_iface, only: pendula_gsl_rk8pd
  implicit none
  !f2py threadsafe
  double precision, intent(in) :: x(31)
  character(len=*), intent(in) :: words
  integer, intent(in) :: nw, nout, ngrid, n, method, ev_kind, ev_dir, ev_terminal, max_ev
  integer, intent(in) :: wlen(nw)
  double precision, intent(in) :: t(n), ev_level
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: theta(n), v(n), stats(4)
  integer, intent(out) :: status, nev
  double precision, intent(out) :: tev(max_ev), thev(max_ev), vev(max_ev)
  !f2py intent(hide), depend(wlen) :: nw = len(wlen)
  !f2py intent(hide), depend(t) :: n = len(t)
  type(scene_t) :: sc
  type(pendulum_model), target :: m
  type(event_spec) :: ev
  type(run_stats) :: st
  double precision :: gs(2), g, length, none(0)
  character(len=512) :: msg
  tev = 0; thev = 0; vev = 0
  theta = 0; v = 0; stats = 0
  nev = 0
  call scene_from_fields(x, words, wlen, nout, ngrid, none, none, none, none, none, none, none, .false., sc, &
                         g, length, status, msg)
  if (status /= 0) then
    status = 100
    return
  end if
  m = scene_model(sc)
  if (method == 10) then
    if (n > 0) then
      if (t(1) < 0) then
        status = 11
        return
      end if
    end if
    status = pendula_gsl_rk8pd(c_loc(m), sc%theta0, sc%v0, n, t, sc%rtol, sc%atol, theta, v, gs)
    if (status /= 0) status = 100 + status
    stats = [gs(1), gs(1), 0.0d0, gs(2)]
    return
  end if
  ev%kind = ev_kind; ev%level = ev_level; ev%direction = ev_dir; ev%terminal = ev_terminal /= 0
  call integrate(m, method, sc%theta0, sc%v0, t, sc%rtol, sc%atol, sc%dt, theta, v, st, status, ev, nev, &
                 tev, thev, vev, cancel(1))
  stats = [dble(st%nsteps), dble(st%naccept), dble(st%nreject), dble(st%nfev)]
end subroutine integrate_v

! FFTW plans for n samples, kept by the Python layer as an address (0 = failure).
subroutine spectrum_plan_v(n, measure, handle)
  use, intrinsic :: iso_c_binding, only: c_intptr_t
  use pendula_spectrum, only: spectrum_plan
  implicit none
  integer, intent(in) :: n, measure
  integer(8), intent(out) :: handle
  handle = int(spectrum_plan(n, measure /= 0), 8)
end subroutine spectrum_plan_v

subroutine spectrum_plan_free_v(handle)
  use, intrinsic :: iso_c_binding, only: c_intptr_t
  use pendula_spectrum, only: spectrum_plan_free
  implicit none
  integer(8), intent(in) :: handle
  call spectrum_plan_free(int(handle, c_intptr_t))
end subroutine spectrum_plan_free_v

! Power spectra of nsig signals of n samples (columns) with the plan handle for n.
! window: 0 none, 1 Hann; nh must be n/2 + 1.
subroutine spectra_v(handle, n, nsig, signals, dt, window, nh, cancel, omega, power, status)
  use, intrinsic :: iso_c_binding, only: c_intptr_t
  use pendula_spectrum, only: power_spectra
  implicit none
  !f2py threadsafe
  integer(8), intent(in) :: handle
  integer, intent(in) :: n, nsig, window, nh
  double precision, intent(in) :: signals(n, nsig), dt
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: omega(nh), power(nh, nsig)
  integer, intent(out) :: status
  !f2py intent(hide), depend(signals) :: n = shape(signals, 0)
  !f2py intent(hide), depend(signals) :: nsig = shape(signals, 1)
  !f2py threadsafe
  ! threadsafe: f2py releases the GIL around the call (the kernel touches no
  ! Python object; the plan is kept alive by the caller while in use).
  if (nh /= n / 2 + 1) then
    status = 4
    return
  end if
  call power_spectra(int(handle, c_intptr_t), signals, dt, window, omega, power, status, cancel(1))
end subroutine spectra_v

! ===============================================
! Huygens' cycloidal pendulum, non-uniform gravity, the density of the angle
! ====================================================================

! The cycloidal pendulum in closed form.  params = [eps, beta, tau, amp, Omega, phase],
! r = R / l.  status: see pendula_cycloid (0 ok, 1 bad eps/r, 3 bad state, 4 reaches a cusp).
subroutine cycloid_run_v(n, params, r, theta0, v0, t, theta, v, s, sd, status)
  use pendula_cycloid, only: cycloid_run
  implicit none
  integer, intent(in) :: n
  double precision, intent(in) :: params(6), r, theta0, v0, t(n)
  double precision, intent(out) :: theta(n), v(n), s(n), sd(n)
  integer, intent(out) :: status
  !f2py intent(hide), depend(t) :: n = len(t)
  call cycloid_run(params(1), r, params(2), params(3), params(4), params(5), params(6), theta0, v0, t, &
                   theta, v, s, sd, status)
end subroutine cycloid_run_v

! Potential V(theta) and acceleration -V'(theta) of a gravity field (kind 0, 1, 2; see pendula_gravity).
subroutine gravity_field_v(n, kind, par, eps, theta, pot, acc, status)
  use pendula_gravity, only: gravity_check, gravity_potential, gravity_accel
  implicit none
  integer, intent(in) :: n, kind
  double precision, intent(in) :: par, eps, theta(n)
  double precision, intent(out) :: pot(n), acc(n)
  integer, intent(out) :: status
  !f2py intent(hide), depend(theta) :: n = len(theta)
  status = gravity_check(kind, par, eps)
  pot = gravity_potential(kind, par, eps, theta)
  acc = gravity_accel(kind, par, eps, theta)
end subroutine gravity_field_v

! The orbit in a gravity field: info = [regime, E, m, K, theta_max, period, mc].
subroutine gravity_orbit_v(kind, par, eps, theta0, v0, info, status)
  use pendula_gravity, only: gravity_orbit
  implicit none
  integer, intent(in) :: kind
  double precision, intent(in) :: par, eps, theta0, v0
  double precision, intent(out) :: info(7)
  integer, intent(out) :: status
  integer :: regime
  call gravity_orbit(kind, par, eps, theta0, v0, info(2), regime, info(3), info(7), info(4), info(5), info(6), &
                     status)
  info(1) = regime
end subroutine gravity_orbit_v

! F(phi|m) from s = sin(phi), c = cos(phi) (never forming phi: next to a turning point
! dF/dphi ~ 1/sqrt(mc) would amplify the rounding of phi); the angle density uses it.
subroutine gravity_f_sc_v(n, s, c, m, mc, f)
  use pendula_elliptic, only: ellip_f_sc
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n
  double precision, intent(in) :: s(n), c(n), m, mc
  double precision, intent(out) :: f(n)
  !f2py intent(hide), depend(s) :: n = len(s)
  f = ellip_f_sc(s, c, m, mc)
end subroutine gravity_f_sc_v

! theta = 2 pi turns + w, w in [-pi, pi] reduced exactly; s = sin(w/2), c = cos(w/2)
! (NaN beyond 2^52); the angle density of a rotation uses it.
subroutine half_angle_v(n, theta, turns, s, c)
  use pendula_exact, only: half_angle
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n
  double precision, intent(in) :: theta(n)
  double precision, intent(out) :: turns(n), s(n), c(n)
  !f2py intent(hide), depend(theta) :: n = len(theta)
  call half_angle(theta, turns, s, c)
end subroutine half_angle_v

! The integrand h(u) of t = int h du at the nodes u (regime 0 libration, 2 rotation).
subroutine gravity_h_v(n, kind, par, eps, regime, m, mc, e, u, h)
  use pendula_gravity, only: gravity_h
  implicit none
  integer, intent(in) :: n, kind, regime
  double precision, intent(in) :: par, eps, m, mc, e, u(n)
  double precision, intent(out) :: h(n)
  !f2py intent(hide), depend(u) :: n = len(u)
  h = gravity_h(kind, par, eps, regime, m, mc, e, u)
end subroutine gravity_h_v

! ==================== flexible cord (Garfinkel): kernel/models/pendula_cord.f90 ====================
! Garfinkel's flip map, elementwise.
subroutine cord_flip_map_v(n, x, f)
  use pendula_cord, only: flip_map
  implicit none
  integer, intent(in) :: n
  double precision, intent(in) :: x(n)
  double precision, intent(out) :: f(n)
  !f2py intent(hide), depend(x) :: n = len(x)
  f = flip_map(x)
end subroutine cord_flip_map_v

! A flexible-cord scene (its fields, as simulate_v takes them) through the dispatcher at sorted times t >= 0: closed
! form without effects, the hybrid loop with them.  flips(8, maxf): t_leave, theta_leave, t_return, theta_return, xi_before, xi_after, v_leave,
! v_return; nflips may
! exceed maxf (then only maxf rows are returned: call again with room).  status: the
! dispatcher's (0 ok; 100: the fields do not form a scene), msg says why.
subroutine cord_scene_v(fields, words, nw, wlen, nout, ngrid, n, maxf, t, cancel, theta, v, x, y, r, flips, &
                        nflips, stop_reason, stats, &
                        method, status, msg)
  use pendula_scene, only: scene_t, scene_from_fields
  use pendula_simulate, only: cord_scene_run, simulate_status_text
  implicit none
  !f2py threadsafe
  double precision, intent(in) :: fields(31)
  character(len=*), intent(in) :: words
  integer, intent(in) :: nw, nout, ngrid, n, maxf
  integer, intent(in) :: wlen(nw)
  double precision, intent(in) :: t(n)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: theta(n), v(n), x(n), y(n), r(n), flips(8, maxf), stats(4)
  integer, intent(out) :: nflips, stop_reason, method, status
  character(len=512), intent(out) :: msg
  !f2py intent(hide), depend(wlen) :: nw = len(wlen)
  !f2py intent(hide), depend(t) :: n = len(t)
  type(scene_t) :: sc
  double precision :: g, length, none(0)
  double precision, allocatable :: fl(:, :)
  integer :: k
  theta = 0; v = 0; x = 0; y = 0; r = 0; flips = 0; stats = 0
  nflips = 0; stop_reason = 0; method = -1; msg = ''
  call scene_from_fields(fields, words, wlen, nout, ngrid, none, none, none, none, none, none, none, .false., sc, &
                         g, length, status, msg)
  if (status /= 0) then
    status = 100
    return
  end if
  call cord_scene_run(sc, t, theta, v, x, y, r, fl, nflips, stop_reason, stats, method, status, cancel(1))
  if (status /= 0) then
    msg = simulate_status_text(status)
    return
  end if
  k = min(nflips, maxf)
  flips(:, 1:k) = fl(:, 1:k)
end subroutine cord_scene_v
! ====================================================================
! Sweeps: one call per block of grid points, OpenMP inside.
! ====================================================================

! params(12, npts): eps, beta, tau, amp, omega, phase, theta0, v0, pivot amplitude and frequency, friction,
! drag per point.
! nthreads <= 0: OpenMP's default (OMP_NUM_THREADS, else all cores).
! cancel(1) non-zero (set by another thread) stops the block: status 5.
subroutine sweep_block(measure, npts, params, rtol, atol, t_tr, t_max, nout, nthreads, faddr, np, fparams, cancel, &
                       out, pstat)
  use, intrinsic :: iso_c_binding, only: c_funptr, c_intptr_t
  use pendula_sweep, only: sweep_points
  implicit none
  integer, intent(in) :: measure, npts, nout, nthreads, np
  double precision, intent(in) :: params(12, npts), rtol, atol, t_tr, t_max
  !> a user's force, called from every thread (its address; 0: none) and the params it reads
  integer(8), intent(in) :: faddr
  double precision, intent(in), target :: fparams(np)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: out(nout, npts)
  integer, intent(out) :: pstat(npts)
  !f2py threadsafe
  !f2py intent(hide), depend(params) :: npts = shape(params, 1)
  !f2py intent(hide), depend(fparams) :: np = len(fparams)
  type(c_funptr) :: f
  if (faddr == 0) then
    call sweep_points(measure, npts, params, rtol, atol, t_tr, t_max, nout, out, pstat, nthreads, cancel(1))
  else
    f = transfer(int(faddr, c_intptr_t), f)
    call sweep_points(measure, npts, params, rtol, atol, t_tr, t_max, nout, out, pstat, nthreads, cancel(1), &
                      f, fparams)
  end if
end subroutine sweep_block

! One adiabatic I-V branch (torques in the order given, state carried over).
subroutine sweep_iv_branch(params, ntau, taus, rtol, atol, t_tr, t_avg, temp, seed, first, dt, cancel, vm, err, &
                           step, pstat, th, v)
  use pendula_sweep, only: iv_branch
  implicit none
  integer, intent(in) :: ntau
  double precision, intent(in) :: params(12), taus(ntau), rtol, atol, t_tr, t_avg, temp, dt
  integer(8), intent(in) :: seed, first
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: vm(ntau), err(ntau), step(ntau), th, v
  integer, intent(out) :: pstat(ntau)
  !f2py threadsafe
  !f2py intent(hide), depend(taus) :: ntau = len(taus)
  call iv_branch(params, ntau, taus, rtol, atol, t_tr, t_avg, temp, seed, first, dt, vm, err, step, pstat, th, v, &
                 cancel(1))
end subroutine sweep_iv_branch


! The sweep's limits: [max threads, max t_max and transient, max |theta0|].
subroutine sweep_limits_v(lim)
  use pendula_sweep, only: sweep_limits
  implicit none
  double precision, intent(out) :: lim(3)
  call sweep_limits(lim)
end subroutine sweep_limits_v
! ---------------------------------------------------------------- spectra: FFTW wisdom (spec)
! Load (save) FFTW wisdom from (to) a file; ok = 1 on success.  Serialised by the
! caller with planning (FFTW's planner state is not thread-safe).
subroutine spectrum_wisdom_v(path, save, ok)
  use pendula_spectrum, only: wisdom_import, wisdom_export
  implicit none
  character(len=*), intent(in) :: path
  integer, intent(in) :: save
  integer, intent(out) :: ok
  logical :: done
  if (save /= 0) then
    done = wisdom_export(path)
  else
    done = wisdom_import(path)
  end if
  ok = merge(1, 0, done)
end subroutine spectrum_wisdom_v
! ---------------------------------------------------------------- Jacobi: argument in double-double (jac)
! sn, cn, dn, am at u + ul for one parameter (m, mc as in ellipj_v): the
! exact motion's phases are double-double, and the tests check the relative
! accuracy of small cn, dn there against mpmath.
subroutine ellipj_dd_v(n, u, ul, m, mc, sn, cn, dn, am)
  use pendula_elliptic, only: jacobi_plan, jacobi_prepare, jacobi_eval_array
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n
  double precision, intent(in) :: u(n), ul(n), m, mc
  double precision, intent(out) :: sn(n), cn(n), dn(n), am(n)
  !f2py intent(hide), depend(u) :: n = len(u)
  type(jacobi_plan) :: plan
  plan = jacobi_prepare(m, mc)
  call jacobi_eval_array(plan, u, sn, cn, dn, am, ul)
end subroutine ellipj_dd_v

! ---------------------------------------------------------------- timing
! The work-precision study's clock: run one integration nrep times inside the
! kernel and return the process CPU time of one run (seconds = total / nrep),
! measured by the kernel around the integration alone (no argument conversion
! or Python call inside the interval).  method: 0 = the exact path (eps =
! params(1), conservative only), 1.. = the integrators' codes, 10 = GSL rk8pd.
! theta, v, stats: those of the last run.  status as integrate_v.  Options of
! the adaptive pairs: pi_beta, the PI term of the step-size controller
! (negative: the method's default; 0: pure I control, Hairer's DOP853 as
! published); land = 1: the steps end on the output times instead of
! interpolating (DOPRI5, DOP853, Verner's 9(8)).
subroutine integrate_timed_v(nrep, n, method, params, theta0, v0, t, rtol, atol, dt, pi_beta, land, theta, v, &
                             stats, seconds, status)
  use, intrinsic :: iso_c_binding, only: c_loc
  use pendula_kinds, only: dp
  use pendula_integrators, only: pendulum_model, make_model, event_spec, run_stats, integrate
  use pendula_gsl_iface, only: pendula_gsl_rk8pd
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval
  implicit none
  integer, intent(in) :: nrep, n, method
  double precision, intent(in) :: params(6), theta0, v0, t(n), rtol, atol, dt
  double precision, intent(in) :: pi_beta
  !f2py double precision optional, intent(in) :: pi_beta = -1.0
  integer, intent(in) :: land
  !f2py integer optional, intent(in) :: land = 0
  double precision, intent(out) :: theta(n), v(n), stats(4), seconds
  integer, intent(out) :: status
  !f2py intent(hide), depend(t) :: n = len(t)
  type(pendulum_model), target :: m
  type(event_spec) :: ev
  type(run_stats) :: st
  type(pendulum_orbit) :: o
  double precision :: gs(2), tev(1), thev(1), vev(1), c0, c1
  integer :: rep, nev
  stats = 0; seconds = 0; status = 0
  theta = 0; v = 0
  if (nrep < 1) then
    status = 1
    return
  end if
  m = make_model(params(1), params(2), params(3), params(4), params(5), params(6))
  call cpu_time(c0)
  do rep = 1, nrep
    select case (method)
    case (0)
      call orbit_setup(theta0, v0, params(1), o, status)
      if (status /= 0) exit
      call orbit_eval(o, t, theta, v)
    case (10)
      status = pendula_gsl_rk8pd(c_loc(m), theta0, v0, n, t, rtol, atol, theta, v, gs)
      if (status /= 0) status = 100 + status
      stats = [gs(1), gs(1), 0.0d0, gs(2)]
    case default
      call integrate(m, method, theta0, v0, t, rtol, atol, dt, theta, v, st, status, ev, nev, tev, thev, vev, &
                     pi_beta=pi_beta, land=land /= 0)
      stats = [dble(st%nsteps), dble(st%naccept), dble(st%nreject), dble(st%nfev)]
    end select
    if (status /= 0) exit
  end do
  call cpu_time(c1)
  seconds = (c1 - c0) / nrep
end subroutine integrate_timed_v

! ==================== equilibria and periodic orbits: kernel/models/pendula_equilibria.f90 ====================
! Equilibria of a model in lo < theta <= hi (model 1 rigid, 2 cord, 3 cycloid; kind, par: the gravity field;
! r: the cycloid's R / l): theta, the eigenvalues (re1, im1, re2, im2) and the kind code of each.
! status 0 ok, 1 bad parameters, 2 more than nmax equilibria in the window.
subroutine equilibria_v(nmax, model, kind, par, eps, r, beta, tau, lo, hi, theta, eig, ekind, count, status)
  use pendula_equilibria, only: model_equilibria, linear_stability
  implicit none
  integer, intent(in) :: nmax, model, kind
  double precision, intent(in) :: par, eps, r, beta, tau, lo, hi
  double precision, intent(out) :: theta(nmax), eig(4, nmax)
  integer, intent(out) :: ekind(nmax), count, status
  double precision :: cs(nmax)
  integer :: i
  call model_equilibria(model, kind, par, eps, r, tau, lo, hi, theta, cs, count, status)
  eig = 0.0d0
  ekind = 0
  do i = 1, count
    call linear_stability(beta, cs(i), eig(1, i), eig(2, i), eig(3, i), eig(4, i), ekind(i))
  end do
end subroutine equilibria_v

! The flow of a checked scene's model (its fields, as scene_check_v returns them; the model is the
! dispatcher's scene_model) from x0 at t = 0 through the times (one sign, in order away from 0) with
! its monodromy: ends(:, i) the state, monos(:, i) the row-major monodromy, fend(:, i) the right-hand
! side (theta', v') at times(i); nfev the right-hand side evaluations.  The one core of the periodic
! orbits and their continuation.  At most nmax steps; cancel(1) non-zero (set by another thread) stops
! it.  status 0 ok, 1 the flow failed (non-finite, or rk8pd's error), 2 more than nmax steps,
! 3 cancelled, 100 the fields do not form a scene.
subroutine flow_monodromy_v(x, words, nw, wlen, nout, ngrid, nt, times, x0, rtol, atol, nmax, faddr, np, fparams, &
                            cancel, ends, monos, fend, nfev, status)
  use, intrinsic :: iso_c_binding, only: c_loc, c_long, c_funptr, c_intptr_t
  use pendula_scene, only: scene_t, scene_from_fields
  use pendula_simulate, only: scene_model, attach_force
  use pendula_integrators, only: pendulum_model
  use pendula_gsl_iface, only: pendula_gsl_flow_monodromy
  implicit none
  !f2py threadsafe
  double precision, intent(in) :: x(31)
  character(len=*), intent(in) :: words
  integer, intent(in) :: nw, nout, ngrid, nt, np
  integer, intent(in) :: wlen(nw)
  double precision, intent(in) :: times(nt), x0(2), rtol, atol, nmax
  !> a user's force (its address, as simulate_v; 0: none) and the params it reads
  integer(8), intent(in) :: faddr
  double precision, intent(in), target :: fparams(np)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: ends(2, nt), monos(4, nt), fend(2, nt), nfev
  integer, intent(out) :: status
  !f2py intent(hide), depend(wlen) :: nw = len(wlen)
  !f2py intent(hide), depend(times) :: nt = len(times)
  !f2py intent(hide), depend(fparams) :: np = len(fparams)
  type(scene_t) :: sc
  type(pendulum_model), target :: m
  type(c_funptr) :: f
  double precision :: g, length, none(0)
  character(len=512) :: msg
  ends = 0; monos = 0; fend = 0; nfev = 0
  call scene_from_fields(x, words, wlen, nout, ngrid, none, none, none, none, none, none, none, .false., sc, &
                         g, length, status, msg)
  if (status /= 0) then
    status = 100
    return
  end if
  m = scene_model(sc)
  if (faddr /= 0) then
    f = transfer(int(faddr, c_intptr_t), f)
    call attach_force(m, f, fparams)
  end if
  status = pendula_gsl_flow_monodromy(c_loc(m), x0(1), x0(2), nt, times, rtol, atol, &
                                      int(min(nmax, 9.0d18), c_long), cancel(1), ends, monos, fend, nfev)
end subroutine flow_monodromy_v

! ==================== effects: dry friction's energy balance ====================

! The turning points of the rigid pendulum with dry friction mu (and a torque tau) from (theta0, v0):
! times(1:count), angles(1:count) where v = 0; stuck = 1 when it sticks at the last one.  status as
! pendula_friction%friction_turning (0 ok, 1 bad input, 2 runs away, 3 more than nmax, 4 GSL failed).
subroutine friction_turning_v(eps, tau, mu, theta0, v0, nmax, times, angles, count, stuck, status)
  use pendula_friction, only: friction_turning
  implicit none
  double precision, intent(in) :: eps, tau, mu, theta0, v0
  integer, intent(in) :: nmax
  double precision, intent(out) :: times(nmax), angles(nmax)
  integer, intent(out) :: count, stuck, status
  logical :: st
  call friction_turning(eps, tau, mu, theta0, v0, times, angles, count, st, status)
  stuck = merge(1, 0, st)
end subroutine friction_turning_v
! ---------------------------------------------------------------- thermal noise (pendula_langevin)

! The sweep's mean_velocity with thermal noise at temperature temp: point i
! on the noise stream (seed, first + i - 1) (first: the block's index in the
! whole grid, so chunks do not change a point), Langevin step dt (<= 0: the
! default).  out(:, i) = <v>, its standard error, NaN; pstat as sweep_block.
subroutine sweep_block_noisy(npts, params, temp, seed, first, dt, t_tr, t_max, nthreads, cancel, out, pstat)
  use pendula_sweep, only: sweep_points_noisy
  implicit none
  integer, intent(in) :: npts, nthreads
  double precision, intent(in) :: params(12, npts), temp, dt, t_tr, t_max
  integer(8), intent(in) :: seed, first
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: out(3, npts)
  integer, intent(out) :: pstat(npts)
  !f2py threadsafe
  !f2py intent(hide), depend(params) :: npts = shape(params, 1)
  call sweep_points_noisy(npts, params, temp, seed, first, dt, t_tr, t_max, out, pstat, nthreads, cancel(1))
end subroutine sweep_block_noisy

! Batch means of v^2 and cos(theta) of one equilibrium Langevin path (the
! checks of the thermal distribution): model (eps, beta, tau), temperature
! temp, stream (seed, index), step h, nburn steps, nbatch batches of nper.
subroutine langevin_moments_v(eps, beta, tau, temp, seed, index, h, nburn, nbatch, nper, cancel, v2, cth, status)
  use pendula_langevin, only: langevin_moments
  use pendula_integrators, only: make_model
  implicit none
  double precision, intent(in) :: eps, beta, tau, temp, h
  integer(8), intent(in) :: seed, index, nburn, nper
  integer, intent(in) :: nbatch
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: v2(nbatch), cth(nbatch)
  integer, intent(out) :: status
  !f2py threadsafe
  call langevin_moments(make_model(eps, beta, tau, 0.0d0, 0.0d0, 0.0d0), temp, seed, index, h, nburn, nbatch, &
                        nper, v2, cth, status, cancel(1))
end subroutine langevin_moments_v

! First-passage times out of the tilted well (eps, beta, tau) at temp: n
! paths from the well's bottom until theta >= theta_exit (NaN after t_max).
subroutine langevin_escape_v(eps, beta, tau, temp, seed, h, theta_exit, t_max, n, nthreads, cancel, times, status)
  use pendula_langevin, only: langevin_escape_times
  use pendula_integrators, only: make_model
  implicit none
  double precision, intent(in) :: eps, beta, tau, temp, h, theta_exit, t_max
  integer(8), intent(in) :: seed
  integer, intent(in) :: n, nthreads
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: times(n)
  integer, intent(out) :: status
  !f2py threadsafe
  call langevin_escape_times(make_model(eps, beta, tau, 0.0d0, 0.0d0, 0.0d0), temp, seed, h, theta_exit, t_max, &
                             n, times, status, nthreads, cancel(1))
end subroutine langevin_escape_v

! Switching currents (reduced: bias / critical current) of n ramps i = rate t
! with damping beta at temp; path k on the stream (seed, k - 1); NaN when a
! path has not switched by i_max.
subroutine junction_switching_v(beta, temp, rate, seed, h, i_max, n, nthreads, cancel, isw, status)
  use pendula_langevin, only: langevin_switching
  implicit none
  double precision, intent(in) :: beta, temp, rate, h, i_max
  integer(8), intent(in) :: seed
  integer, intent(in) :: n, nthreads
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: isw(n)
  integer, intent(out) :: status
  !f2py threadsafe
  call langevin_switching(beta, temp, rate, seed, h, i_max, n, isw, status, nthreads, cancel(1))
end subroutine junction_switching_v

! Attractors of the stroboscopic map by recurrence (pendula_attractors%attractor_points): label npts points
! against a table of known attractors' cells (kcell sorted, klab their attractor, need the consecutive samples
! per attractor) or find a new attractor; cfg as pendula_attractors documents (at_ncfg entries).
subroutine attractor_block(npts, params, rtol, atol, cfg, nk, kcell, klab, natt, need, ncp, cth, cv, catt, crad, &
                           nbt, nbv, bth, bv, blab, nout, maxc, nthreads, cancel, out, cells, ncell, pstat)
  use pendula_attractors, only: attractor_points
  implicit none
  integer, intent(in) :: npts, nk, natt, ncp, nbt, nbv, nout, maxc, nthreads
  double precision, intent(in) :: params(12, npts), rtol, atol, cfg(12), bth(nbt), bv(nbv)
  double precision, intent(in) :: cth(ncp), cv(ncp), crad(natt)
  integer(kind=8), intent(in) :: kcell(nk)
  integer, intent(in) :: klab(nk), need(natt), catt(ncp), blab(nbt, nbv)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: out(nout, npts)
  integer(kind=8), intent(out) :: cells(maxc, npts)
  integer, intent(out) :: ncell(npts), pstat(npts)
  !f2py threadsafe
  !f2py intent(hide), depend(params) :: npts = shape(params, 1)
  !f2py intent(hide), depend(kcell) :: nk = len(kcell)
  !f2py intent(hide), depend(need) :: natt = len(need)
  !f2py intent(hide), depend(cth) :: ncp = len(cth)
  !f2py intent(hide), depend(bth) :: nbt = len(bth)
  !f2py intent(hide), depend(bv) :: nbv = len(bv)
  call attractor_points(npts, params, rtol, atol, cfg, nk, kcell, klab, natt, need, ncp, cth, cv, catt, crad, &
                        nbt, nbv, bth, bv, blab, nout, out, maxc, cells, ncell, pstat, nthreads, cancel(1))
end subroutine attractor_block


! One step of Verner's 9(8) pair (method 12) or 8(7) pair (method 14) of size h
! from (theta0, v0) at t = 0 on the model (params as integrate_timed_v) and its
! order-8 interpolant at the fractions x of the step: the state at t = x h (x =
! 1: the step's own end).
subroutine verner_interpolant_v(method, nx, params, theta0, v0, h, x, theta, v)
  use pendula_kinds, only: dp
  use pendula_integrators, only: pendulum_model, make_model, verner_one_step_dense
  implicit none
  integer, intent(in) :: method, nx
  double precision, intent(in) :: params(6), theta0, v0, h, x(nx)
  double precision, intent(out) :: theta(nx), v(nx)
  !f2py intent(hide), depend(x) :: nx = len(x)
  type(pendulum_model) :: m
  m = make_model(params(1), params(2), params(3), params(4), params(5), params(6))
  call verner_one_step_dense(m, method, theta0, v0, h, x, theta, v)
end subroutine verner_interpolant_v



! ---------------------------------------------------------------------------
! Mathieu characteristic values (kernel/mathieu): elementwise over arrays,
! OpenMP over the elements.  status per element: 0 ok, 1 outside the domain,
! 2 the truncation bound was not met (the value is then NaN).
! ---------------------------------------------------------------------------

! a_nu(q) (kind 1) or b_nu(q) (kind 2) and the truncation bound of each
subroutine mathieu_char_v(n, kind, nu, q, val, bound, status)
  use pendula_mathieu, only: mathieu_char
  use pendula_threads, only: thread_count
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n, kind
  double precision, intent(in) :: nu(n), q(n)
  double precision, intent(out) :: val(n), bound(n)
  integer, intent(out) :: status(n)
  !f2py intent(hide), depend(nu) :: n = len(nu)
  integer :: i
  !$omp parallel do schedule(dynamic, 8) num_threads(thread_count(0)) if (n >= 64)
  do i = 1, n
    call mathieu_char(kind, nu(i), q(i), val(i), bound(i), status(i))
  end do
  !$omp end parallel do
end subroutine mathieu_char_v

! the lowest nlev levels at each (nu, q) from one window each (the spectrum
! of the quantum pendulum at many offset charges)
subroutine mathieu_levels_v(n, nlev, nu, q, val, bound, status)
  use pendula_mathieu, only: mathieu_levels
  use pendula_threads, only: thread_count
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n, nlev
  double precision, intent(in) :: nu(n), q(n)
  double precision, intent(out) :: val(nlev, n), bound(nlev, n)
  integer, intent(out) :: status(nlev, n)
  !f2py intent(hide), depend(nu) :: n = len(nu)
  integer :: i
  !$omp parallel do schedule(dynamic, 4) num_threads(thread_count(0)) if (n >= 8)
  do i = 1, n
    call mathieu_levels(nu(i), q(i), nlev, val(:, i), bound(:, i), status(:, i))
  end do
  !$omp end parallel do
end subroutine mathieu_levels_v

! the same levels to double-double precision (hi + lo)
subroutine mathieu_level_dd_v(n, nu, q, m, vh, vl, bound, status)
  use pendula_mathieu, only: mathieu_level_dd
  use pendula_threads, only: thread_count
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n
  double precision, intent(in) :: nu(n), q(n)
  integer, intent(in) :: m(n)
  double precision, intent(out) :: vh(n), vl(n), bound(n)
  integer, intent(out) :: status(n)
  !f2py intent(hide), depend(nu) :: n = len(nu)
  integer :: i
  !$omp parallel do schedule(dynamic, 4) num_threads(thread_count(0)) if (n >= 16)
  do i = 1, n
    call mathieu_level_dd(nu(i), q(i), m(i), vh(i), vl(i), bound(i), status(i))
  end do
  !$omp end parallel do
end subroutine mathieu_level_dd_v

! the characteristic exponent nu(a, q): NaN (status 0) where unstable
subroutine mathieu_nu_v(n, a, q, nu, status)
  use pendula_mathieu, only: mathieu_nu
  use pendula_threads, only: thread_count
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n
  double precision, intent(in) :: a(n), q(n)
  double precision, intent(out) :: nu(n)
  integer, intent(out) :: status(n)
  !f2py intent(hide), depend(a) :: n = len(a)
  integer :: i
  !$omp parallel do schedule(dynamic, 8) num_threads(thread_count(0)) if (n >= 64)
  do i = 1, n
    call mathieu_nu(a(i), q(i), nu(i), status(i))
  end do
  !$omp end parallel do
end subroutine mathieu_nu_v

! the m(i)-th level at offset nu(i) and its eigenvector on the rows
! kmin .. kmin + nk - 1 (one column a level); lost: the norm outside
subroutine mathieu_level_vector_v(n, nk, nu, q, m, kmin, val, c, lost, status)
  use pendula_mathieu, only: mathieu_level_vector
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n, nk, kmin
  double precision, intent(in) :: nu(n), q(n)
  integer, intent(in) :: m(n)
  double precision, intent(out) :: val(n), c(nk, n), lost(n)
  integer, intent(out) :: status(n)
  !f2py intent(hide), depend(nu) :: n = len(nu)
  integer :: i
  do i = 1, n
    call mathieu_level_vector(nu(i), q(i), m(i), kmin, nk, val(i), c(:, i), lost(i), status(i))
  end do
end subroutine mathieu_level_vector_v

! ce_n(z, q) (kind 1) or se_n(z, q) (kind 2) and the derivative at the points z
subroutine mathieu_function_v(nz, kind, n, q, z, val, dval, status)
  use pendula_mathieu, only: mathieu_function
  implicit none
  !f2py threadsafe
  integer, intent(in) :: nz, kind, n
  double precision, intent(in) :: q, z(nz)
  double precision, intent(out) :: val(nz), dval(nz)
  integer, intent(out) :: status
  !f2py intent(hide), depend(z) :: nz = len(z)
  call mathieu_function(kind, n, q, nz, z, val, dval, status)
end subroutine mathieu_function_v
! ---------------------------------------------------------------------
! Networks of pendula (kernel/models/pendula_network.f90 and
! kernel/dispatch/pendula_network_run.f90).  p(7, nel): the rows C, beta,
! eps, tau, A, Omega, phase of each element; the couplings as edges
! (ei < ej, 1-based) with stiffness ek and offset eoff.
! ---------------------------------------------------------------------

! The network from y0 = (phi, phi') at t = 0: method 1 DOP853 (rtol, atol;
! outputs at tout), 2 or 3 Gauss-Legendre of order 4 or 6 (step dt; output k
! after counts(k) more steps).  stats: steps, accepted, rejected, evaluations.
subroutine network_simulate_v(nel, ne, p, ei, ej, ek, eoff, method, y0, nout, tout, counts, rtol, atol, dt, &
                              cancel, yout, stats, status)
  use pendula_kinds, only: dp
  use pendula_integrators, only: run_stats
  use pendula_network, only: network, make_network
  use pendula_network_run, only: network_simulate
  implicit none
  integer, intent(in) :: nel, ne, method, nout
  double precision, intent(in) :: p(7, nel), ek(ne), eoff(ne), y0(2 * nel), tout(nout), rtol, atol, dt
  integer, intent(in) :: ei(ne), ej(ne)
  integer(8), intent(in) :: counts(nout)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: yout(2 * nel, nout)
  integer(8), intent(out) :: stats(4)
  integer, intent(out) :: status
  !f2py threadsafe
  !f2py intent(hide), depend(p) :: nel = shape(p, 1)
  !f2py intent(hide), depend(ei) :: ne = len(ei)
  !f2py intent(hide), depend(tout) :: nout = len(tout)
  type(network) :: net
  type(run_stats) :: st
  net = make_network(p, ei, ej, ek, eoff)
  call network_simulate(net, method, y0, tout, counts, rtol, atol, dt, yout, st, status, cancel(1))
  stats = [st%nsteps, st%naccept, st%nreject, st%nfev]
end subroutine network_simulate_v

! A batch of nrun deterministic runs of the network from y0(:, k) (network_simulate_v per run) on
! nthreads OpenMP threads: yout(:, :, k), stats(:, k), status(k) run k's results.
subroutine network_simulate_batch_v(nel, ne, p, ei, ej, ek, eoff, method, nrun, y0, nout, tout, counts, &
                                    rtol, atol, dt, nthreads, cancel, yout, stats, status)
  use pendula_network, only: network, make_network
  use pendula_network_run, only: network_simulate_batch
  implicit none
  integer, intent(in) :: nel, ne, method, nrun, nout, nthreads
  double precision, intent(in) :: p(7, nel), ek(ne), eoff(ne), y0(2 * nel, nrun), tout(nout), rtol, atol, dt
  integer, intent(in) :: ei(ne), ej(ne)
  integer(8), intent(in) :: counts(nout)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: yout(2 * nel, nout, nrun)
  integer(8), intent(out) :: stats(4, nrun)
  integer, intent(out) :: status(nrun)
  !f2py threadsafe
  !f2py intent(hide), depend(p) :: nel = shape(p, 1)
  !f2py intent(hide), depend(ei) :: ne = len(ei)
  !f2py intent(hide), depend(y0) :: nrun = shape(y0, 1)
  !f2py intent(hide), depend(tout) :: nout = len(tout)
  type(network) :: net
  net = make_network(p, ei, ej, ek, eoff)
  call network_simulate_batch(net, method, y0, tout, counts, rtol, atol, dt, nthreads, yout, stats, status, &
                              cancel(1))
end subroutine network_simulate_batch_v

! npath Langevin paths (BAOAB, step h) of the network at temperatures temp;
! path k from y0(:, k) on the noise streams of point first + k - 1 of seed;
! yout(:, j, k) after counts(j) more steps; status(k) each path's status.
subroutine network_langevin_v(nel, ne, p, ei, ej, ek, eoff, temp, seed, first, h, npath, y0, nout, counts, &
                              nthreads, cancel, yout, status)
  use pendula_network, only: network, make_network
  use pendula_network_run, only: network_langevin
  implicit none
  integer, intent(in) :: nel, ne, npath, nout, nthreads
  double precision, intent(in) :: p(7, nel), ek(ne), eoff(ne), temp(nel), h, y0(2 * nel, npath)
  integer, intent(in) :: ei(ne), ej(ne)
  integer(8), intent(in) :: seed, first, counts(nout)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: yout(2 * nel, nout, npath)
  integer, intent(out) :: status(npath)
  !f2py threadsafe
  !f2py intent(hide), depend(p) :: nel = shape(p, 1)
  !f2py intent(hide), depend(ei) :: ne = len(ei)
  !f2py intent(hide), depend(y0) :: npath = shape(y0, 1)
  !f2py intent(hide), depend(counts) :: nout = len(counts)
  type(network) :: net
  net = make_network(p, ei, ej, ek, eoff)
  call network_langevin(net, temp, seed, first, h, y0, counts, nthreads, yout, status, cancel(1))
end subroutine network_langevin_v

! The force on each element at time t for nq sets of phases q(:, k), and its
! Jacobian in the phases at the first set (dense, nel x nel).
subroutine network_force_v(nel, ne, p, ei, ej, ek, eoff, t, nq, q, f, jac)
  use pendula_network, only: network, make_network, network_force, network_jacobian
  implicit none
  integer, intent(in) :: nel, ne, nq
  double precision, intent(in) :: p(7, nel), ek(ne), eoff(ne), t, q(nel, nq)
  integer, intent(in) :: ei(ne), ej(ne)
  double precision, intent(out) :: f(nel, nq), jac(nel, nel)
  !f2py threadsafe
  !f2py intent(hide), depend(p) :: nel = shape(p, 1)
  !f2py intent(hide), depend(ei) :: ne = len(ei)
  !f2py intent(hide), depend(q) :: nq = shape(q, 1)
  type(network) :: net
  integer :: k
  net = make_network(p, ei, ej, ek, eoff)
  do k = 1, nq
    call network_force(net, t, q(:, k), f(:, k))
  end do
  jac = 0.0d0
  if (nq > 0) call network_jacobian(net, q(:, 1), jac)
end subroutine network_force_v

! The energy of each of ns states y(:, k) = (phi, phi').
subroutine network_energy_v(nel, ne, p, ei, ej, ek, eoff, ns, y, en)
  use pendula_network, only: network, make_network, network_energy
  implicit none
  integer, intent(in) :: nel, ne, ns
  double precision, intent(in) :: p(7, nel), ek(ne), eoff(ne), y(2 * nel, ns)
  integer, intent(in) :: ei(ne), ej(ne)
  double precision, intent(out) :: en(ns)
  !f2py threadsafe
  !f2py intent(hide), depend(p) :: nel = shape(p, 1)
  !f2py intent(hide), depend(ei) :: ne = len(ei)
  !f2py intent(hide), depend(y) :: ns = shape(y, 1)
  type(network) :: net
  integer :: k
  net = make_network(p, ei, ej, ek, eoff)
  do k = 1, ns
    en(k) = network_energy(net, y(1:nel, k), y(nel + 1:2 * nel, k))
  end do
end subroutine network_energy_v

! The network's time scales as rates (1 / time; pendula_time_scales's
! network_time_rates, in the order of `names`, 12 characters each) with the
! elements' starting speeds v0 (the springs' offsets create none), and the default steps of its fixed-step
! methods: dts = (Gauss-Legendre 4, Gauss-Legendre 6, BAOAB).
subroutine network_time_scales_v(nel, ne, p, ei, ej, ek, v0, rates, names, dts)
  use pendula_network, only: np_c, np_beta, np_eps, np_tau, np_amp, np_omega
  use pendula_time_scales, only: network_time_rates, network_default_dt, network_scale_names, &
    n_network_scales, nm_gauss4, nm_gauss6, nm_baoab
  implicit none
  integer, intent(in) :: nel, ne
  double precision, intent(in) :: p(7, nel), ek(ne), v0(nel)
  integer, intent(in) :: ei(ne), ej(ne)
  double precision, intent(out) :: rates(9), dts(3)
  character(len=108), intent(out) :: names
  !f2py intent(hide), depend(p) :: nel = shape(p, 1)
  !f2py intent(hide), depend(ei) :: ne = len(ei)
  integer :: i
  names = ''
  do i = 1, n_network_scales
    names(12 * (i - 1) + 1:12 * i) = network_scale_names(i)
  end do
  rates = network_time_rates(p(np_c, :), p(np_beta, :), p(np_eps, :), p(np_tau, :), p(np_amp, :), &
                             p(np_omega, :), ei, ej, ek, v0)
  dts = [network_default_dt(rates, nm_gauss4), network_default_dt(rates, nm_gauss6), &
         network_default_dt(rates, nm_baoab)]
end subroutine network_time_scales_v
! ---------------------------------------------------------------- the spherical pendulum
! The exact path of the spherical pendulum (pendula_spherical) from the state
! (theta0, theta_dot0, phi_dot0) and azimuth phi0 at t = 0, g / l = eps: theta,
! phi and their rates at the times t; status as pendula_spherical's sph_*.
subroutine spherical_path_v(n, theta0, theta_dot0, phi_dot0, phi0, eps, t, theta, phi, theta_dot, phi_dot, status)
  use pendula_spherical, only: spherical_orbit, spherical_setup, spherical_eval
  implicit none
  !f2py threadsafe
  integer, intent(in) :: n
  double precision, intent(in) :: theta0, theta_dot0, phi_dot0, phi0, eps, t(n)
  double precision, intent(out) :: theta(n), phi(n), theta_dot(n), phi_dot(n)
  integer, intent(out) :: status
  !f2py intent(hide), depend(t) :: n = len(t)
  type(spherical_orbit) :: o
  theta = 0.0d0; phi = 0.0d0; theta_dot = 0.0d0; phi_dot = 0.0d0
  call spherical_setup(theta0, theta_dot0, phi_dot0, phi0, eps, o, status)
  if (status /= 0) return
  call spherical_eval(o, t, theta, phi, theta_dot, phi_dot)
end subroutine spherical_path_v

! The spherical orbit's facts (pendula_spherical%spherical_facts): period, azimuth
! advance, apsidal angle, precession rate, theta_min, theta_max, energy, L, m, mc,
! planar, polar frequency.
subroutine spherical_facts_v(theta0, theta_dot0, phi_dot0, eps, facts, status)
  use pendula_spherical, only: spherical_orbit, spherical_setup, spherical_facts
  implicit none
  double precision, intent(in) :: theta0, theta_dot0, phi_dot0, eps
  double precision, intent(out) :: facts(12)
  integer, intent(out) :: status
  type(spherical_orbit) :: o
  facts = 0.0d0
  call spherical_setup(theta0, theta_dot0, phi_dot0, 0.0d0, eps, o, status)
  if (status /= 0) return
  facts = spherical_facts(o)
end subroutine spherical_facts_v
! ---------------------------------------------------------------- the overdamped (RSJ) junction
! Mean phase velocity <phi'> of phi' = i + a cos(omega t) - sin(phi) at each bias (units of omega_c):
! vm, its error bound err (0 when locked), the Shapiro step where locked (else NaN), status 0 decided,
! 6 locked, 1 the integration failed, 5 cancelled (pendula_rsj).
subroutine rsj_mean_velocity_v(n, bias, a, omega, rtol, atol, periods, nthreads, cancel, vm, err, step, status)
  use pendula_rsj, only: rsj_mean_velocity
  implicit none
  integer, intent(in) :: n, nthreads
  double precision, intent(in) :: bias(n), a, omega, rtol, atol
  integer(8), intent(in) :: periods
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: vm(n), err(n), step(n)
  integer, intent(out) :: status(n)
  !f2py threadsafe
  !f2py intent(hide), depend(bias) :: n = len(bias)
  call rsj_mean_velocity(n, bias, a, omega, rtol, atol, periods, vm, err, step, status, nthreads, cancel(1))
end subroutine rsj_mean_velocity_v

! The extrema of g(x) = F(x) - x of the RSJ stroboscopic map at each bias (pendula_rsj).
subroutine rsj_gap_ranges_v(n, bias, a, omega, rtol, atol, nthreads, gmin, gmax, status)
  use pendula_rsj, only: rsj_gap_ranges
  implicit none
  integer, intent(in) :: n, nthreads
  double precision, intent(in) :: bias(n), a, omega, rtol, atol
  double precision, intent(out) :: gmin(n), gmax(n)
  integer, intent(out) :: status(n)
  !f2py threadsafe
  !f2py intent(hide), depend(bias) :: n = len(bias)
  call rsj_gap_ranges(n, bias, a, omega, rtol, atol, gmin, gmax, status, nthreads)
end subroutine rsj_gap_ranges_v
! ---------------------------------------------------------------- the double pendulum
! The double pendulum (kernel/models/pendula_double.f90 and
! kernel/dispatch/pendula_double_run.f90).  p(8) = (m1, m2, l1, l2, g, rods,
! k1, k2); states y = (theta1, theta2, p1, p2), p the canonical momenta.

! The path from y0 at t = 0: method 1 DOP853 (rtol, atol; outputs at tout),
! 2 or 3 Gauss-Legendre of order 4 or 6 (step dt; output k after counts(k)
! more steps).  stats: steps, accepted, rejected, evaluations.
subroutine double_simulate_v(p, method, y0, nout, tout, counts, rtol, atol, dt, cancel, yout, stats, status)
  use pendula_integrators, only: run_stats
  use pendula_double, only: make_double
  use pendula_double_run, only: double_simulate
  implicit none
  integer, intent(in) :: method, nout
  double precision, intent(in) :: p(8), y0(4), tout(nout), rtol, atol, dt
  integer(8), intent(in) :: counts(nout)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: yout(4, nout)
  integer(8), intent(out) :: stats(4)
  integer, intent(out) :: status
  !f2py threadsafe
  !f2py intent(hide), depend(tout) :: nout = len(tout)
  type(run_stats) :: st
  call double_simulate(make_double(p), method, y0, tout, counts, rtol, atol, dt, yout, st, status, cancel(1))
  stats = [st%nsteps, st%naccept, st%nreject, st%nfev]
end subroutine double_simulate_v

! The double pendulum's time scales as rates (pendula_double's
! double_time_rates, names 12 characters each) at the canonical state y0 =
! (theta1, theta2, p1, p2), and its default Gauss-Legendre step.
subroutine double_time_scales_v(p, y0, rates, names, dt)
  use pendula_double, only: double_pendulum, make_double, double_time_rates, double_default_dt, &
    double_scale_names, n_double_scales
  implicit none
  double precision, intent(in) :: p(8), y0(4)
  double precision, intent(out) :: rates(3), dt
  character(len=36), intent(out) :: names
  type(double_pendulum) :: dpd
  integer :: i
  names = ''
  do i = 1, n_double_scales
    names(12 * (i - 1) + 1:12 * i) = double_scale_names(i)
  end do
  dpd = make_double(p)
  rates = double_time_rates(dpd, y0)
  dt = double_default_dt(rates)
end subroutine double_time_scales_v

! For ns states y(:, k): the energy, the angular velocities w(:, k) and the
! right-hand side f(:, k); jac the Jacobian of the right-hand side at y(:, 1).
subroutine double_state_v(p, ns, y, en, w, f, jac)
  use pendula_double, only: double_pendulum, make_double, double_energy, double_velocities, double_rhs, &
    double_jacobian
  implicit none
  integer, intent(in) :: ns
  double precision, intent(in) :: p(8), y(4, ns)
  double precision, intent(out) :: en(ns), w(2, ns), f(4, ns), jac(4, 4)
  !f2py threadsafe
  !f2py intent(hide), depend(y) :: ns = shape(y, 1)
  type(double_pendulum) :: dpd
  integer :: k
  dpd = make_double(p)
  do k = 1, ns
    en(k) = double_energy(dpd, y(:, k))
    call double_velocities(dpd, y(:, k), w(:, k))
    call double_rhs(dpd, y(:, k), f(:, k))
  end do
  jac = 0.0d0
  if (ns > 0) call double_jacobian(dpd, y(:, 1), jac)
end subroutine double_state_v

! The flip-time map from rest at (th1(k), th2(k)); skip(k) /= 0: cannot flip
! (inf); tflip at (rtol, atol), tcheck at a tenth of both; the search up to
! tmax on an output grid of spacing hg; on nthreads threads.
subroutine double_flip_map_v(p, n, th1, th2, skip, tmax, hg, rtol, atol, nthreads, cancel, tflip, tcheck, status)
  use pendula_double, only: make_double
  use pendula_double_run, only: double_flip_map
  implicit none
  integer, intent(in) :: n, nthreads
  double precision, intent(in) :: p(8), th1(n), th2(n), tmax, hg, rtol, atol
  integer, intent(in) :: skip(n)
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: tflip(n), tcheck(n)
  integer, intent(out) :: status(n)
  !f2py threadsafe
  !f2py intent(hide), depend(th1) :: n = len(th1)
  call double_flip_map(make_double(p), th1, th2, skip, tmax, hg, rtol, atol, nthreads, tflip, tcheck, status, &
                       cancel(1))
end subroutine double_flip_map_v

! The Lyapunov spectrum from y0 (see double_lyapunov): nren
! re-orthonormalisations, each after `every` steps of h (Gauss-Legendre,
! method 2 or 3) or a span h * every of DOP853 (method 1, rtol, atol).
subroutine double_lyapunov_v(p, method, y0, h, every, nren, rtol, atol, cancel, lam, yend, status)
  use pendula_double, only: make_double
  use pendula_double_run, only: double_lyapunov
  implicit none
  integer, intent(in) :: method
  double precision, intent(in) :: p(8), y0(4), h, rtol, atol
  integer(8), intent(in) :: every, nren
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: lam(4), yend(4)
  integer, intent(out) :: status
  !f2py threadsafe
  call double_lyapunov(make_double(p), method, y0, h, every, nren, rtol, atol, lam, yend, status, cancel(1))
end subroutine double_lyapunov_v

! The Poincare section theta1 = 0 (mod 2 pi), theta1 increasing, of norb
! orbits from y0s(:, k) up to tmax: pts(:, 1:npts(k), k) the crossings (see
! double_section); method 3 Gauss-Legendre of order 6 with step hg, 1 DOP853.
subroutine double_section_v(p, method, norb, y0s, tmax, hg, rtol, atol, maxpts, nthreads, cancel, pts, npts, status)
  use pendula_double, only: make_double
  use pendula_double_run, only: double_section
  implicit none
  integer, intent(in) :: method, norb, maxpts, nthreads
  double precision, intent(in) :: p(8), y0s(4, norb), tmax, hg, rtol, atol
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: pts(4, maxpts, norb)
  integer, intent(out) :: npts(norb), status(norb)
  !f2py threadsafe
  !f2py intent(hide), depend(y0s) :: norb = shape(y0s, 1)
  call double_section(make_double(p), method, y0s, tmax, hg, rtol, atol, nthreads, pts, npts, status, cancel(1))
end subroutine double_section_v
! ---------------------------------------------------------------- the Foucault pendulum
! The Foucault pendulum (kernel/models/pendula_foucault.f90): p = (g, l,
! Omega_E, latitude in degrees, gamma, ae, an); y = (r, v) in local axes (x east,
! y north, z up), the path at tout by DOP853.  pstatus the parameters'
! status (pendula_foucault's fst_*), status the integrator's.
subroutine foucault_simulate_v(p, y0, nout, tout, rtol, atol, cancel, yout, stats, pstatus, status)
  use pendula_kinds, only: nan_dp
  use pendula_integrators, only: run_stats
  use pendula_foucault, only: foucault, make_foucault
  use pendula_foucault_run, only: foucault_simulate
  implicit none
  integer, intent(in) :: nout
  double precision, intent(in) :: p(7), y0(6), tout(nout), rtol, atol
  integer, intent(inout), volatile :: cancel(1)
  double precision, intent(out) :: yout(6, nout)
  integer(8), intent(out) :: stats(4)
  integer, intent(out) :: pstatus, status
  !f2py threadsafe
  !f2py intent(hide), depend(tout) :: nout = len(tout)
  type(foucault) :: fc
  type(run_stats) :: st
  yout = nan_dp
  stats = 0
  status = 0
  call make_foucault(p, fc, pstatus)
  if (pstatus /= 0) return
  call foucault_simulate(fc, y0, tout, rtol, atol, yout, st, status, cancel(1))
  stats = [st%nsteps, st%naccept, st%nreject, st%nfev]
end subroutine foucault_simulate_v

! The scene file of a system built by its own class (&double, &foucault, &network), read and checked as
! pendula-run reads it: its group (blank: none of them, status 1), the rows and columns of its table;
! status 0, or 2 with msg naming the field.
subroutine system_scene_size_v(path, group, nrows, ncols, status, msg)
  use pendula_system_scenes, only: system_scene_size
  implicit none
  character(len=*), intent(in) :: path
  character(len=16), intent(out) :: group
  integer, intent(out) :: nrows, ncols, status
  character(len=1024), intent(out) :: msg
  call system_scene_size(path, group, nrows, ncols, status, msg)
end subroutine system_scene_size_v

! That file's table (nrows x ncols from system_scene_size_v), its column names (comma-separated) and
! title, as pendula-run writes them: status 0, 1 no system's group, 2 bad scene, 4 the run failed (msg).
subroutine system_scene_table_v(path, nrows, ncols, table, heads, title, status, msg)
  use pendula_system_scenes, only: system_scene_table
  implicit none
  character(len=*), intent(in) :: path
  integer, intent(in) :: nrows, ncols
  double precision, intent(out) :: table(nrows, ncols)
  character(len=24000), intent(out) :: heads
  character(len=256), intent(out) :: title
  integer, intent(out) :: status
  character(len=1024), intent(out) :: msg
  call system_scene_table(path, table, heads, title, status, msg)
end subroutine system_scene_table_v

! The fields of a &double scene file, read and checked as pendula-run reads them: x = m1, m2, l1, l2, g,
! rods (1 or 0), damping(2), theta1, theta2, omega1, omega2, t_end, dt, rtol, atol, n_samples; status 0,
! or 2 with msg naming the field.
subroutine double_scene_fields_v(path, x, method, status, msg)
  use pendula_double_scene, only: double_scene_t, read_double_scene
  implicit none
  character(len=*), intent(in) :: path
  double precision, intent(out) :: x(17)
  character(len=16), intent(out) :: method
  integer, intent(out) :: status
  character(len=1024), intent(out) :: msg
  type(double_scene_t) :: ds
  call read_double_scene(path, ds, status, msg)
  x = [ds%m1, ds%m2, ds%l1, ds%l2, ds%g, merge(1.0d0, 0.0d0, ds%rods), ds%damping, ds%theta1, ds%theta2, &
       ds%omega1, ds%omega2, ds%t_end, ds%dt, ds%rtol, ds%atol, dble(ds%n_samples)]
  method = ds%method
end subroutine double_scene_fields_v

! The fields of a &foucault scene file: x = latitude, length, g, earth_rate, damping, anisotropy(2), theta0,
! azimuth, theta_dot0, phi_dot0, t_end, rtol, n_samples; status 0, or 2 with msg naming the field.
subroutine foucault_scene_fields_v(path, x, status, msg)
  use pendula_foucault_scene, only: foucault_scene_t, read_foucault_scene
  implicit none
  character(len=*), intent(in) :: path
  double precision, intent(out) :: x(14)
  integer, intent(out) :: status
  character(len=1024), intent(out) :: msg
  type(foucault_scene_t) :: fs
  call read_foucault_scene(path, fs, status, msg)
  x = [fs%latitude, fs%length, fs%g, fs%earth_rate, fs%damping, fs%anisotropy, fs%theta0, fs%azimuth, &
       fs%theta_dot0, fs%phi_dot0, fs%t_end, fs%rtol, dble(fs%n_samples)]
end subroutine foucault_scene_fields_v

! The fields of a &network scene file: n, x = strength, t_end, dt, rtol, atol, n_samples, per(1:n, k) the
! per-element fields mass, damping, eps, bias, drive_amplitude, drive_frequency, drive_phase, phi0, v0
! (nmax >= n rows); status 0, or 2 with msg naming the field.
subroutine network_scene_fields_v(path, nmax, n, x, per, topology, method, status, msg)
  use pendula_network_scene, only: network_scene_t, read_network_scene
  implicit none
  character(len=*), intent(in) :: path
  integer, intent(in) :: nmax
  integer, intent(out) :: n
  double precision, intent(out) :: x(6), per(nmax, 9)
  character(len=16), intent(out) :: topology, method
  integer, intent(out) :: status
  character(len=1024), intent(out) :: msg
  type(network_scene_t) :: ns
  call read_network_scene(path, ns, status, msg)
  n = 0; x = 0; per = 0; topology = ''; method = ''
  if (status /= 0) return
  if (ns%n > nmax) then
    status = 2; msg = path // ': &network: more elements than nmax'; return
  end if
  n = ns%n
  x = [ns%strength, ns%t_end, ns%dt, ns%rtol, ns%atol, dble(ns%n_samples)]
  per(1:n, :) = ns%per
  topology = ns%topology
  method = ns%method
end subroutine network_scene_fields_v
