!> A network of pendula (phases) coupled by springs (inductances):
!>
!>   C_i phi_i'' + beta_i phi_i' + eps_i sin phi_i
!>     = tau_i + A_i cos(Omega_i t + phase_i) + sum_j K_ij (phi_j - phi_i - offset_ij),
!>
!> K symmetric, offset antisymmetric (offset_ji = -offset_ij).  The couplings
!> are an edge list: edge e joins elements ei(e) < ej(e) with stiffness ek(e)
!> and offset eoff(e) (= offset_{ei,ej}), so a chain costs O(N) a force and a
!> dense matrix costs its nonzeros.  Its potential energy is
!>
!>   U = sum_i [eps_i (1 - cos phi_i) - tau_i phi_i]
!>       + sum_e ek_e / 2 (phi_ej - phi_ei - eoff_e)^2,
!>
!> the force the negative gradient of U plus the drive; with no damping and
!> no drive sum_i C_i phi_i'^2 / 2 + U is conserved.
module pendula_network
  use pendula_kinds, only: dp
  implicit none
  private
  public :: network, make_network, network_force, network_jacobian, network_energy

  !> The fixed data of a network of nel elements and ne edges.
  type :: network
    integer :: nel = 0, ne = 0
    real(dp), allocatable :: c(:), beta(:), eps(:), tau(:), amp(:), omega(:), phase(:)
    integer, allocatable :: ei(:), ej(:)
    real(dp), allocatable :: ek(:), eoff(:)
    logical :: driven = .false.
  end type network

  !> the rows of the parameter block p(7, nel) of make_network
  integer, parameter, public :: np_c = 1, np_beta = 2, np_eps = 3, np_tau = 4, np_amp = 5, &
    np_omega = 6, np_phase = 7, np_rows = 7

contains

  !> The network of the parameter block p(np_rows, nel) (rows np_*) and the
  !> edges (ei, ej, ek, eoff), element indices 1-based.
  pure function make_network(p, ei, ej, ek, eoff) result(net)
    real(dp), intent(in) :: p(:, :), ek(:), eoff(:)
    integer, intent(in) :: ei(:), ej(:)
    type(network) :: net
    net%nel = size(p, 2)
    net%ne = size(ei)
    net%c = p(np_c, :); net%beta = p(np_beta, :); net%eps = p(np_eps, :); net%tau = p(np_tau, :)
    net%amp = p(np_amp, :); net%omega = p(np_omega, :); net%phase = p(np_phase, :)
    net%ei = ei; net%ej = ej; net%ek = ek; net%eoff = eoff
    net%driven = any(net%amp /= 0.0_dp)
  end function make_network

  !> The force on each element at time t (all but inertia and damping).
  pure subroutine network_force(net, t, q, f)
    type(network), intent(in) :: net
    real(dp), intent(in) :: t, q(:)
    real(dp), intent(out) :: f(:)
    real(dp) :: s
    integer :: e, i, j
    f = net%tau - net%eps * sin(q)
    if (net%driven) f = f + net%amp * cos(net%omega * t + net%phase)
    do e = 1, net%ne
      i = net%ei(e); j = net%ej(e)
      s = net%ek(e) * (q(j) - q(i) - net%eoff(e))
      f(i) = f(i) + s
      f(j) = f(j) - s
    end do
  end subroutine network_force

  !> The Jacobian of the force in the phases, dense: jac(i, j) = df_i / dphi_j
  !> (symmetric: minus the Hessian of U).
  pure subroutine network_jacobian(net, q, jac)
    type(network), intent(in) :: net
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: jac(:, :)
    integer :: e, i, j
    jac = 0.0_dp
    do i = 1, net%nel
      jac(i, i) = -net%eps(i) * cos(q(i))
    end do
    do e = 1, net%ne
      i = net%ei(e); j = net%ej(e)
      jac(i, i) = jac(i, i) - net%ek(e)
      jac(j, j) = jac(j, j) - net%ek(e)
      jac(i, j) = jac(i, j) + net%ek(e)
      jac(j, i) = jac(j, i) + net%ek(e)
    end do
  end subroutine network_jacobian

  !> The energy sum_i C_i v_i^2 / 2 + U(q) (see the module's text); the
  !> kinetic and potential parts summed separately, then added.
  pure function network_energy(net, q, v) result(en)
    type(network), intent(in) :: net
    real(dp), intent(in) :: q(:), v(:)
    real(dp) :: en, kin, pot, d
    integer :: e
    kin = 0.5_dp * sum(net%c * v**2)
    ! 1 - cos q = 2 sin^2(q/2): no cancellation near the bottom
    pot = sum(2.0_dp * net%eps * sin(0.5_dp * q)**2 - net%tau * q)
    do e = 1, net%ne
      d = q(net%ej(e)) - q(net%ei(e)) - net%eoff(e)
      pot = pot + 0.5_dp * net%ek(e) * d**2
    end do
    en = kin + pot
  end function network_energy

end module pendula_network
