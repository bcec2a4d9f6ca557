!> The Foucault pendulum: a spherical pendulum (a point mass on a rod of
!> length l) in the frame of the Earth, which turns at the rate Omega_E
!> about its axis.  Local axes at the pivot: x east, y north, z up; the
!> Earth's rotation there is Omega = Omega_E (0, cos(lat), sin(lat)).  The
!> bob's position r (abs(r) = l) and velocity v obey
!>
!>   r'' = -g z^ - 2 Omega x v - Omega x (Omega x r) - gamma v
!>         - (g / l) (ae x, an y, 0) + lambda r,
!>
!> g the apparent gravity at the pivot, gamma >= 0 a viscous drag rate, ae
!> and an an anisotropic support (a small swing east or north has omega^2 =
!> (g / l) (1 + ae) or (g / l) (1 + an)), and
!> lambda r the rod's tension, fixed by the constraint (r . r)'' = 0:
!> lambda = -(v . v + r . F) / l^2, F the other forces (Landau and
!> Lifshitz, "Mechanics", section 39).  Cartesian coordinates have no
!> singularity at the bottom, through which a Foucault pendulum swings.
module pendula_foucault
  use pendula_kinds, only: dp, pi
  implicit none
  private
  public :: foucault, make_foucault, foucault_rhs

  !> the entries of the parameter vector of make_foucault
  integer, parameter, public :: fp_g = 1, fp_l = 2, fp_rate = 3, fp_lat = 4, fp_gamma = 5, fp_ae = 6, fp_an = 7, &
    fp_size = 7
  !> status: a latitude (degrees) outside [-90, 90]; g or l not positive; rate or gamma negative;
  !> an anisotropy not finite or at most -1 (no restoring force along its axis)
  integer, parameter, public :: fst_ok = 0, fst_latitude = 1, fst_gl = 2, fst_rate = 3, fst_aniso = 4

  type :: foucault
    real(dp) :: g = 1.0_dp, l = 1.0_dp, om(3) = 0.0_dp, gamma = 0.0_dp, ke = 0.0_dp, kn = 0.0_dp
  end type foucault

contains

  !> The pendulum of p = (g, l, Omega_E, latitude in degrees, gamma, ae, an), status fst_*.
  pure subroutine make_foucault(p, fc, status)
    real(dp), intent(in) :: p(fp_size)
    type(foucault), intent(out) :: fc
    integer, intent(out) :: status
    real(dp) :: lat
    status = fst_ok
    if (.not. (abs(p(fp_lat)) <= 90.0_dp)) then
      status = fst_latitude; return
    end if
    if (.not. (p(fp_g) > 0.0_dp .and. p(fp_l) > 0.0_dp .and. p(fp_g) <= huge(1.0_dp) &
               .and. p(fp_l) <= huge(1.0_dp))) then
      status = fst_gl; return
    end if
    if (.not. (p(fp_rate) >= 0.0_dp .and. p(fp_gamma) >= 0.0_dp .and. p(fp_rate) <= huge(1.0_dp) &
               .and. p(fp_gamma) <= huge(1.0_dp))) then
      status = fst_rate; return
    end if
    if (.not. (p(fp_ae) > -1.0_dp .and. p(fp_an) > -1.0_dp .and. p(fp_ae) <= huge(1.0_dp) &
               .and. p(fp_an) <= huge(1.0_dp))) then
      status = fst_aniso; return
    end if
    lat = p(fp_lat) * (pi / 180.0_dp)
    fc%g = p(fp_g); fc%l = p(fp_l); fc%gamma = p(fp_gamma)
    fc%ke = p(fp_ae) * p(fp_g) / p(fp_l); fc%kn = p(fp_an) * p(fp_g) / p(fp_l)
    fc%om = p(fp_rate) * [0.0_dp, cos(lat), sin(lat)]
    if (abs(p(fp_lat)) == 90.0_dp) fc%om(2) = 0.0_dp    ! cos(pi/2) is 6e-17 in doubles
  end subroutine make_foucault

  pure function cross(a, b) result(c)
    real(dp), intent(in) :: a(3), b(3)
    real(dp) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross

  !> y = (r, v), f = y'.
  pure subroutine foucault_rhs(fc, y, f)
    type(foucault), intent(in) :: fc
    real(dp), intent(in) :: y(6)
    real(dp), intent(out) :: f(6)
    real(dp) :: force(3), lam
    force = -2.0_dp * cross(fc%om, y(4:6)) - cross(fc%om, cross(fc%om, y(1:3))) - fc%gamma * y(4:6)
    force(3) = force(3) - fc%g
    force(1) = force(1) - fc%ke * y(1)
    force(2) = force(2) - fc%kn * y(2)
    lam = -(dot_product(y(4:6), y(4:6)) + dot_product(y(1:3), force)) / dot_product(y(1:3), y(1:3))
    f(1:3) = y(4:6)
    f(4:6) = force + lam * y(1:3)
  end subroutine foucault_rhs

end module pendula_foucault
