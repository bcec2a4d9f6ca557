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
module pendula_time_scales
  use pendula_kinds, only: dp, two_pi
  use pendula_gravity, only: gk_inverse_square, gk_linear
  implicit none
  private
  public :: time_rates, fastest_rate, field_stiffness, langevin_step_rate, scale_names

  integer, parameter, public :: n_scales = 9
  integer, parameter, public :: ts_oscillation = 1, ts_damping = 2, ts_drive = 3, ts_pivot = 4, &
    ts_pivot_force = 5, ts_torque = 6, ts_friction = 7, ts_drag = 8, ts_rotation = 9
  !> the scales' names, in the order of time_rates
  character(len=12), parameter :: scale_names(n_scales) = [character(len=12) :: 'oscillation', 'damping', &
    'drive', 'pivot', 'pivot_force', 'torque', 'friction', 'drag', 'rotation']

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

end module pendula_time_scales
