!> The rigid pendulum, the first model of pendula:
!>   theta'' + beta theta' + eps sin(theta) = tau + A cos(Omega t + phase).
!>
!> Without effects (beta = tau = A = 0) it has an exact path: the Jacobi
!> elliptic solution of pendula_exact, in every regime.  With effects its
!> right-hand side is the integrators' pendulum force law (make_model/accel),
!> and its invariant is the energy v^2/2 + eps (1 - cos theta), conserved
!> only without effects.  Its events are the integrators' (turning points,
!> angle levels).
module pendula_rigid
  use pendula_kinds, only: dp
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval
  implicit none
  private
  public :: rigid_has_exact, rigid_exact, rigid_energy

contains

  !> Does the exact path answer the rigid pendulum with these effects?
  pure logical function rigid_has_exact(beta, tau, amp)
    real(dp), intent(in) :: beta, tau, amp
    rigid_has_exact = beta == 0.0_dp .and. tau == 0.0_dp .and. amp == 0.0_dp
  end function rigid_has_exact

  !> theta(t), v(t) from the exact solution (status 1: bad eps, 2: bad theta0, 3: bad v0).
  pure subroutine rigid_exact(theta0, v0, eps, t, theta, v, status)
    real(dp), intent(in) :: theta0, v0, eps, t(:)
    real(dp), intent(out) :: theta(:), v(:)
    integer, intent(out) :: status
    type(pendulum_orbit) :: o
    call orbit_setup(theta0, v0, eps, o, status)
    if (status /= 0) return
    call orbit_eval(o, t, theta, v)
  end subroutine rigid_exact

  !> E = v^2/2 + eps (1 - cos theta), written without cancellation.
  elemental function rigid_energy(eps, theta, v) result(e)
    real(dp), intent(in) :: eps, theta, v
    real(dp) :: e
    e = 0.5_dp * v * v + 2.0_dp * eps * sin(0.5_dp * theta)**2
  end function rigid_energy

end module pendula_rigid
