!> Run one scene: the exact solution whenever the scene allows it, otherwise
!> the integrator the scene names (or the cheapest one for its tolerance).
module pendula_simulate
  use pendula_kinds, only: dp
  use pendula_scene, only: scene_t, scene_effects
  use pendula_exact, only: pendulum_orbit, orbit_setup, orbit_eval
  implicit none
  private
  public :: simulate_scene, simulate_status_text

  integer, parameter, public :: sim_ok = 0, sim_bad_state = 1, sim_needs_integrator = 10

contains

  subroutine simulate_scene(sc, t, theta, v, nsteps, nrhs, status)
    type(scene_t), intent(in) :: sc
    real(dp), intent(in) :: t(:)
    real(dp), intent(out) :: theta(:), v(:)
    integer, intent(out) :: nsteps, nrhs, status
    type(pendulum_orbit) :: o
    nsteps = 0
    nrhs = 0
    if (len_trim(scene_effects(sc)) == 0 .and. (sc%method == 'auto' .or. sc%method == 'exact')) then
      call orbit_setup(sc%theta0, sc%v0, sc%eps, o, status)
      if (status /= 0) then
        status = sim_bad_state
        return
      end if
      call orbit_eval(o, t, theta, v)
      status = sim_ok
    else
      status = sim_needs_integrator
    end if
  end subroutine simulate_scene

  function simulate_status_text(status) result(s)
    integer, intent(in) :: status
    character(len=128) :: s
    select case (status)
    case (sim_ok);               s = 'ok'
    case (sim_bad_state);        s = 'invalid initial state'
    case (sim_needs_integrator); s = 'this scene needs an integrator, which pendula-run does not have yet'
    case default;                s = 'unknown failure'
    end select
  end function simulate_status_text

end module pendula_simulate
