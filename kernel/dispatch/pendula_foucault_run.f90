!> The Foucault pendulum (pendula_foucault) on the n-dimensional driver
!> (pendula_nd_run): DOP853 with error control, the path output at the times
!> asked for.
module pendula_foucault_run
  use pendula_kinds, only: dp, i8, nan_dp
  use pendula_integrators, only: run_stats
  use pendula_ode, only: ode_system
  use pendula_nd_run, only: nd_run, nd_dop853
  use pendula_foucault, only: foucault, foucault_rhs
  implicit none
  private
  public :: foucault_simulate

  type, extends(ode_system) :: foucault_ode
    type(foucault) :: fc
  contains
    procedure :: rhs => foucault_ode_rhs
  end type foucault_ode

contains

  pure subroutine foucault_ode_rhs(self, t, y, f)
    class(foucault_ode), intent(in) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: f(:)
    call foucault_rhs(self%fc, y(1:6), f(1:6))
  end subroutine foucault_ode_rhs

  !> The path from y0 = (r, v) at t = 0 to the times tout by DOP853 (rtol, atol).
  subroutine foucault_simulate(fc, y0, tout, rtol, atol, yout, stats, status, cancel)
    type(foucault), intent(in) :: fc
    real(dp), intent(in) :: y0(6), tout(:), rtol, atol
    real(dp), intent(out) :: yout(:, :)
    type(run_stats), intent(out) :: stats
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    yout = nan_dp
    call nd_run(foucault_ode(n=6, fc=fc), nd_dop853, 0.0_dp, y0, tout, [integer(i8) ::], rtol, atol, 0.0_dp, &
                yout, stats, status, cancel)
  end subroutine foucault_simulate

end module pendula_foucault_run
