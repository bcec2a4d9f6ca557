!> The scene's type and the limits of its fields (one place for both programs:
!> the reader, the rules and the Python layer's field order).
module pendula_scene_type
  use pendula_kinds, only: dp, nan_dp
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private
  public :: scene_t, max_sweep, max_outputs, max_scene_bytes, n_number_fields, number_fields, n_word_fields, &
            word_fields, max_words, theta0_limit, drive_phase_limit, eps_limit, seed_limit

  integer, parameter :: max_sweep = 4096, max_outputs = 16
  !> the largest scene file read (16 MiB: a scene with every list full is below 1 MiB)
  integer, parameter :: max_scene_bytes = 16777216
  !> the numbers of a scene in the order scene_from_fields takes them (whole
  !> numbers too: n_samples, max_flips, sweep_samples)
  integer, parameter :: n_number_fields = 31
  character(len=16), parameter :: number_fields(n_number_fields) = [character(len=16) :: 'eps', 'theta0', &
    'v0', 't_start', 't_end', 'n_samples', 'damping', 'torque', 'drive_amplitude', 'drive_frequency', &
    'drive_phase', 'rtol', 'atol', 'dt', 'g', 'length', 'cycloid_radius', 'gravity_distance', &
    'gravity_gradient', 'restitution', 'max_flips', 'min_flight', 'sweep_t_max', 'sweep_transient', &
    'sweep_samples', 'friction', 'drag', 'pivot_amplitude', 'pivot_frequency', 'noise', 'seed']
  !> the single words, in order; then the outputs, then the grid's axes
  integer, parameter :: n_word_fields = 7
  character(len=8), parameter :: word_fields(n_word_fields) = [character(len=8) :: 'cord', 'guide', 'gravity', &
    'method', 'sweep', 'measure', 'name']
  integer, parameter :: max_words = n_word_fields + max_outputs + 3
  !> |theta0| beyond 2^52: a double has no fraction left, the angle cannot be reduced mod 2 pi
  real(dp), parameter :: theta0_limit = 4503599627370496.0_dp
  !> |drive_phase| beyond 2^10 rad (163 turns): the phase's own rounding (half an ulp, up to 1.1e-13)
  !> would enter the drive cos(Omega t + phase) unseen; a phase is given reduced, as an angle of one turn
  real(dp), parameter :: drive_phase_limit = 1024.0_dp
  !> eps above 1e300 leaves no room for the exact path's double-double sqrt(eps)
  real(dp), parameter :: eps_limit = 1.0e300_dp
  !> the largest seed: 2^53, every whole number up to it is a double
  real(dp), parameter :: seed_limit = 9007199254740992.0_dp

  type :: scene_t
    real(dp) :: eps = 1.0_dp, theta0 = 0.0_dp, v0 = 0.0_dp
    real(dp) :: t_start = 0.0_dp, t_end = 20.0_dp
    integer :: n_samples = 1001
    real(dp) :: damping = 0.0_dp, torque = 0.0_dp
    real(dp) :: drive_amplitude = 0.0_dp, drive_frequency = 0.0_dp, drive_phase = 0.0_dp
    character(len=32) :: cord = 'rigid', guide = 'none', gravity = 'uniform', method = 'auto'
    real(dp) :: rtol = 1.0e-10_dp, atol = 1.0e-12_dp, dt = 0.0_dp
    character(len=16) :: outputs(max_outputs) = ''
    integer :: n_outputs = 0
    character(len=32) :: sweep = ''
    real(dp), allocatable :: sweep_values(:)        ! n_sweep values
    integer :: n_sweep = 0
    character(len=256) :: name = ''
    ! the cycloidal guide (R / l) and the gravity fields' parameters
    real(dp) :: cycloid_radius = 0.25_dp, gravity_distance = 0.0_dp, gravity_gradient = 0.0_dp
    ! the flexible cord (kernel/models/pendula_cord.f90)
    real(dp) :: restitution = 0.0_dp, min_flight = 0.0_dp
    integer :: max_flips = 100000
    ! sweeps over grids (kernel/sweep): axes, values or (start, stop, count), measure;
    ! grid_nv, grid_nr: how many values and range entries each axis was given;
    ! grid_values(:, k): axis k's values, NaN beyond them (at least one row: a
    ! range axis has NaN in its first)
    character(len=32) :: grid(3) = ''
    integer :: n_grid = 0
    real(dp), allocatable :: grid_values(:, :)
    real(dp) :: grid_range(3, 3) = nan_dp
    integer :: grid_n(3) = 0, grid_nv(3) = 0, grid_nr(3) = 0
    character(len=32) :: measure = ''
    real(dp) :: sweep_t_max = 2000.0_dp, sweep_transient = 200.0_dp
    integer :: sweep_samples = 100
    ! effects: dry (Coulomb) friction mu, quadratic drag gamma, a vertically vibrating pivot a cos(Omega t)
    real(dp) :: friction = 0.0_dp, drag = 0.0_dp, pivot_amplitude = 0.0_dp, pivot_frequency = 0.0_dp
    ! thermal noise (kernel/integrators/pendula_langevin.f90): the temperature T in units
    ! of eps, and the seed of its counter-based random numbers (0 .. 2^53)
    real(dp) :: noise = 0.0_dp
    integer(int64) :: seed = 0
  end type scene_t

end module pendula_scene_type
