!> Fortran interfaces to the C glue in pendula_gsl.c.
module pendula_gsl_iface
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_long
  implicit none
  private
  public :: pendula_gsl_init, pendula_gsl_elljac, pendula_gsl_kcomp, pendula_gsl_mathieu, &
            pendula_gsl_rk8pd, pendula_gsl_flow_monodromy, &
            pendula_gsl_periodic_orbit

  interface
    subroutine pendula_gsl_init() bind(C, name="pendula_gsl_init")
    end subroutine pendula_gsl_init

    function pendula_gsl_elljac(n, u, m, sn, cn, dn) bind(C, name="pendula_gsl_elljac") result(bad)
      import :: c_int, c_double
      integer(c_int), value, intent(in) :: n
      real(c_double), intent(in) :: u(*), m(*)
      real(c_double), intent(out) :: sn(*), cn(*), dn(*)
      integer(c_int) :: bad
    end function pendula_gsl_elljac

    function pendula_gsl_kcomp(n, m, k) bind(C, name="pendula_gsl_kcomp") result(bad)
      import :: c_int, c_double
      integer(c_int), value, intent(in) :: n
      real(c_double), intent(in) :: m(*)
      real(c_double), intent(out) :: k(*)
      integer(c_int) :: bad
    end function pendula_gsl_kcomp

    function pendula_gsl_mathieu(kind, n, order, q, val) bind(C, name="pendula_gsl_mathieu") result(bad)
      import :: c_int, c_double
      integer(c_int), value, intent(in) :: kind, n
      integer(c_int), intent(in) :: order(*)
      real(c_double), intent(in) :: q(*)
      real(c_double), intent(out) :: val(*)
      integer(c_int) :: bad
    end function pendula_gsl_mathieu

    !> model: c_loc of the pendulum_model to integrate (pendula_capi reads it back)
    function pendula_gsl_rk8pd(model, theta0, v0, n, tout, rtol, atol, theta, v, stats) &
        bind(C, name="pendula_gsl_rk8pd") result(status)
      import :: c_int, c_double, c_ptr
      type(c_ptr), value, intent(in) :: model
      real(c_double), value, intent(in) :: theta0, v0
      integer(c_int), value, intent(in) :: n
      real(c_double), intent(in) :: tout(*)
      real(c_double), value, intent(in) :: rtol, atol
      real(c_double), intent(out) :: theta(*), v(*), stats(2)
      integer(c_int) :: status
    end function pendula_gsl_rk8pd

    !> The flow with its monodromy through the times tout (pendula_gsl.c); status 0 ok, 1 the flow
    !> failed, 2 more than nmax steps, 3 cancelled (cancel read every 256 steps).
    function pendula_gsl_flow_monodromy(model, theta0, v0, nt, tout, rtol, atol, nmax, cancel, ends, monos, &
                                        fend, nfev) bind(C, name="pendula_gsl_flow_monodromy") result(status)
      import :: c_int, c_double, c_ptr, c_long
      type(c_ptr), value, intent(in) :: model
      real(c_double), value, intent(in) :: theta0, v0
      integer(c_int), value, intent(in) :: nt
      real(c_double), intent(in) :: tout(*)
      real(c_double), value, intent(in) :: rtol, atol
      integer(c_long), value, intent(in) :: nmax
      integer(c_int), intent(inout), volatile :: cancel
      real(c_double), intent(out) :: ends(*), monos(*), fend(*), nfev
      integer(c_int) :: status
    end function pendula_gsl_flow_monodromy

    !> A fixed point of the map over period that advances theta by 2 pi winding (GSL's hybridsj on the
    !> flow and monodromy above): the attractor finder's Newton; status 0 ok, 1 no convergence, 2 the
    !> flow failed, 3 stalled; info = [iterations, rhs evaluations, residual].
    function pendula_gsl_periodic_orbit(model, period, winding, rtol, atol, tol, maxit, x, mono, info) &
        bind(C, name="pendula_gsl_periodic_orbit") result(status)
      import :: c_int, c_double, c_ptr
      type(c_ptr), value, intent(in) :: model
      real(c_double), value, intent(in) :: period, winding, rtol, atol, tol
      integer(c_int), value, intent(in) :: maxit
      real(c_double), intent(inout) :: x(2)
      real(c_double), intent(out) :: mono(4), info(3)
      integer(c_int) :: status
    end function pendula_gsl_periodic_orbit
  end interface
end module pendula_gsl_iface
