!> The one time-scale rule: every fast and slow time scale a pendulum's fields
!> create, as rates (1 / time).  Every rule that needs a time scale reads it
!> here: the Langevin default step, the integrators' up-front work check, the
!> sweeps' and the dynamics' work limits, and the Python layer's choice of an
!> interruptible run (through the binding's scene_time_scales_v).
!>
!>   oscillation   sqrt(eps s)        s: the field's largest stiffness relative to the uniform
!>                                    field's (field_stiffness): small oscillations and the
!>                                    passage of the top
!>   damping       beta               the velocity's relaxation (an overdamped orbit creeps on
!>                                    the slow scale eps / beta, which the integrators follow
!>                                    with long steps)
!>   drive         Omega              the drive's angular frequency (its period 2 pi / Omega)
!>   pivot         Omega_p            the vibrating pivot's
!>   pivot force   sqrt(|a|) Omega_p  the pivot's acceleration a Omega_p^2 as a stiffness
!>   torque        sqrt(|tau|)        a constant torque's own acceleration
!>   friction      sqrt(mu eps)       dry friction's deceleration mu eps
!>   drag          gamma |v0|         quadratic drag's rate at the starting speed
!>   rotation      |v0|               a fast rotation turns once in 2 pi / |v0|
!>
!> The fastest rate bounds the step of every method; the slowest non-zero one
!> the length of a transient.  Plain arguments only (the integrators sit below
!> the scene), so the integrators' model and the scene give the same numbers.
!>
!> A network of N phases (pendula_network: masses C_i, damping beta_i, sine
!> strengths eps_i, torques tau_i, drives A_i cos(Omega_i t + psi_i), springs
!> K_ij) has its own scales (network_time_rates), each the fastest over the
!> elements:
!>
!>   oscillation   sqrt(|eps_i| / C_i)        each element's own small oscillation
!>   coupling      sqrt(2 k_i / C_i)          k_i = sum_j K_ij: Gershgorin's bound of the
!>                                            springs' fastest normal mode (C^-1 times the
!>                                            springs' Laplacian)
!>   modes         sqrt((|eps_i| + 2 k_i) / C_i)  the bound of the linearised network's
!>                                            fastest normal mode (sine and springs)
!>   damping       beta_i / C_i               the velocity's relaxation
!>   drive         Omega_i                    where A_i /= 0
!>   drive force   sqrt(|A_i| / C_i)
!>   torque        sqrt(|tau_i| / C_i)        a constant torque's own acceleration
!>   running       (|tau_i| + |A_i|) / beta_i  the speed of a damped element driven over
!>                                            the top (its phase turns in 2 pi / speed)
!>   rotation      |v0_i|                     the starting speed
!>
!> and the default fixed steps of its methods (network_default_dt): 2 pi over
!> the fastest rate, divided by the method's steps per period.
module pendula_time_scales
  use pendula_kinds, only: dp, two_pi
  use pendula_gravity, only: gk_inverse_square, gk_linear
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  implicit none
  private
  public :: time_rates, fastest_rate, field_stiffness, langevin_step_rate, scale_names
  public :: network_time_rates, network_default_dt, network_scale_names

  integer, parameter, public :: n_scales = 9
  integer, parameter, public :: ts_oscillation = 1, ts_damping = 2, ts_drive = 3, ts_pivot = 4, &
    ts_pivot_force = 5, ts_torque = 6, ts_friction = 7, ts_drag = 8, ts_rotation = 9
  !> the scales' names, in the order of time_rates
  character(len=12), parameter :: scale_names(n_scales) = [character(len=12) :: 'oscillation', 'damping', &
    'drive', 'pivot', 'pivot_force', 'torque', 'friction', 'drag', 'rotation']

  integer, parameter, public :: n_network_scales = 9
  integer, parameter, public :: ns_oscillation = 1, ns_coupling = 2, ns_modes = 3, ns_damping = 4, &
    ns_drive = 5, ns_drive_force = 6, ns_torque = 7, ns_running = 8, ns_rotation = 9
  !> the network's scales' names, in the order of network_time_rates
  character(len=12), parameter :: network_scale_names(n_network_scales) = [character(len=12) :: &
    'oscillation', 'coupling', 'modes', 'damping', 'drive', 'drive_force', 'torque', 'running', 'rotation']
  !> the network's fixed-step methods (the codes of network_default_dt)
  integer, parameter, public :: nm_gauss4 = 1, nm_gauss6 = 2, nm_baoab = 3, n_network_methods = 3
  !> steps per period of the fastest rate, per method: BAOAB as the scene's Langevin rule (100: its
  !> equipartition error (h omega)^2 / 4 ~ 1e-3); Gauss-Legendre 4 and 6 100 too (measured on a chain
  !> of 3 with springs 1e4 over 64 fast periods: energy within 6e-6, 7e-6 relative; at 50 steps
  !> 2e-4 for both, as the stages' fixed-point iteration, not the order, limits them there)
  real(dp), parameter :: network_steps_per_period(n_network_methods) = [100.0_dp, 100.0_dp, 100.0_dp]

contains

  !> The largest stiffness of a gravity field relative to the uniform field's
  !> eps (an upper bound of |dA/dtheta| / eps over the circle): 1 uniform;
  !> 1 + 3 |kappa| for the linear field; g (1 + 3 g) / 4 ... bounded by
  !> (1 + 3 g) g with g = d / (d - 1) for the inverse-square field (1 as d -> infinity
  !> is approached from above; within a factor 4 of the true bound, which is all
  !> a time scale needs).
  elemental real(dp) function field_stiffness(gkind, gpar)
    integer, intent(in) :: gkind
    real(dp), intent(in) :: gpar
    real(dp) :: g
    select case (gkind)
    case (gk_linear)
      field_stiffness = 1.0_dp + 3.0_dp * abs(gpar)
    case (gk_inverse_square)
      g = gpar / (gpar - 1.0_dp)
      field_stiffness = g * max(1.0_dp, 3.0_dp * g - 2.0_dp)
    case default
      field_stiffness = 1.0_dp
    end select
    if (.not. (field_stiffness >= 1.0_dp)) field_stiffness = 1.0_dp
  end function field_stiffness

  !> The rates of the n_scales time scales (0 where a field is absent), in the
  !> order of scale_names.  omega, pomega: the drive's and the pivot's angular
  !> frequencies (their amplitudes amp, pamp: a frequency without an amplitude
  !> creates no scale).
  pure function time_rates(eps, beta, tau, amp, omega, pamp, pomega, gkind, gpar, mu, gamma, v0) result(r)
    real(dp), intent(in) :: eps, beta, tau, amp, omega, pamp, pomega, gpar, mu, gamma, v0
    integer, intent(in) :: gkind
    real(dp) :: r(n_scales)
    r = 0.0_dp
    r(ts_oscillation) = sqrt(max(eps, 0.0_dp) * field_stiffness(gkind, gpar))
    r(ts_damping) = abs(beta)
    if (amp /= 0.0_dp) r(ts_drive) = abs(omega)
    if (pamp /= 0.0_dp) then
      r(ts_pivot) = abs(pomega)
      r(ts_pivot_force) = sqrt(abs(pamp)) * abs(pomega)
    end if
    r(ts_torque) = sqrt(abs(tau))
    r(ts_friction) = sqrt(abs(mu) * max(eps, 0.0_dp))
    r(ts_drag) = abs(gamma) * abs(v0)
    r(ts_rotation) = abs(v0)
  end function time_rates

  !> The fastest of the rates (NaN when one is NaN: a caller's check then fails, never passes).
  pure real(dp) function fastest_rate(r)
    real(dp), intent(in) :: r(n_scales)
    integer :: i
    fastest_rate = 0.0_dp
    do i = 1, n_scales
      if (r(i) /= r(i)) then
        fastest_rate = r(i); return
      end if
      fastest_rate = max(fastest_rate, r(i))
    end do
  end function fastest_rate

  !> The rate that sets the Langevin integrator's default step (BAOAB, step
  !> 2 pi / rate / 100): the fastest of the oscillation (in the scene's field),
  !> the drive, the pivot and its force, and the damping, so that beta h <= 0.063
  !> (at beta h >> 1 BAOAB's stationary velocity under a torque is
  !> tau h/2 coth(beta h/2), not tau / beta).  Below the damping's rate
  !> (beta <= sqrt(eps), the usual junction) this is the small-oscillation and
  !> drive rule alone.
  pure real(dp) function langevin_step_rate(r)
    real(dp), intent(in) :: r(n_scales)
    langevin_step_rate = max(r(ts_oscillation), r(ts_drive), r(ts_pivot), r(ts_pivot_force), r(ts_damping))
  end function langevin_step_rate

  !> The rates of a network's n_network_scales time scales (0 where a field
  !> is absent; see the module's text), element data per element, springs
  !> ei(e) - ej(e) of stiffness ek(e) (1-based), starting speeds v0.
  pure function network_time_rates(c, beta, eps, tau, amp, omega, ei, ej, ek, v0) result(r)
    real(dp), intent(in) :: c(:), beta(:), eps(:), tau(:), amp(:), omega(:), ek(:), v0(:)
    integer, intent(in) :: ei(:), ej(:)
    real(dp) :: r(n_network_scales)
    real(dp) :: ksum(size(c))
    integer :: e
    r = 0.0_dp
    if (size(c) == 0) return
    ksum = 0.0_dp
    do e = 1, size(ei)
      ksum(ei(e)) = ksum(ei(e)) + abs(ek(e))
      ksum(ej(e)) = ksum(ej(e)) + abs(ek(e))
    end do
    r(ns_oscillation) = sqrt(maxval(abs(eps) / c))
    r(ns_coupling) = sqrt(maxval(2.0_dp * ksum / c))
    r(ns_modes) = sqrt(maxval((abs(eps) + 2.0_dp * ksum) / c))
    r(ns_damping) = maxval(abs(beta) / c)
    r(ns_drive) = maxval(merge(abs(omega), 0.0_dp, amp /= 0.0_dp))
    r(ns_drive_force) = sqrt(maxval(abs(amp) / c))
    r(ns_torque) = sqrt(maxval(abs(tau) / c))
    r(ns_running) = maxval(merge((abs(tau) + abs(amp)) / beta, 0.0_dp, beta > 0.0_dp))
    if (size(v0) > 0) r(ns_rotation) = maxval(abs(v0))
  end function network_time_rates

  !> The default step of a network's fixed-step method (nm_gauss4, nm_gauss6,
  !> nm_baoab) from its rates: 2 pi / fastest / steps per period (NaN for an
  !> unknown method; a network with no scale at all takes the unit rate).
  pure real(dp) function network_default_dt(r, method)
    real(dp), intent(in) :: r(n_network_scales)
    integer, intent(in) :: method
    real(dp) :: rate
    integer :: i
    rate = 0.0_dp
    do i = 1, n_network_scales
      rate = max(rate, r(i))
    end do
    if (.not. (rate > 0.0_dp)) rate = 1.0_dp
    if (method < 1 .or. method > n_network_methods) then
      network_default_dt = ieee_value(1.0_dp, ieee_quiet_nan)
      return
    end if
    network_default_dt = two_pi / rate / network_steps_per_period(method)
  end function network_default_dt

end module pendula_time_scales
