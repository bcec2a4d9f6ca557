!> The double pendulum's scene file for pendula-run: the namelist group
!> &double, its fields and their checks (each refusal names the field),
!> and its run on the n-dimensional driver (pendula_double_run).
!>
!>   &double
!>     m1 = 1, m2 = 1, l1 = 1, l2 = 1, g = 1, rods = .false., damping = 0, 0
!>     theta1 = 2.0, theta2 = 1.0, omega1 = 0, omega2 = 0
!>     t_end = 20, n_samples = 201, method = 'dop853', dt = 0.01, rtol = 1e-12, atol = 1e-12
!>   /
!>
!> method 'dop853' (error control at rtol, atol) or 'gauss6' / 'gauss4'
!> (Gauss-Legendre with the fixed step dt, which must divide the output
!> spacing t_end / (n_samples - 1)).  The path is output at n_samples times
!> from 0 to t_end: t, theta1, theta2, omega1, omega2, energy (zero at rest
!> at the bottom).
module pendula_double_scene
  use pendula_kinds, only: dp, i8
  use pendula_integrators, only: run_stats
  use pendula_double, only: double_pendulum, make_double, double_energy, double_velocities, dpp_size
  use pendula_double_run, only: double_simulate
  use pendula_group_file, only: read_group_file
  use pendula_nd_run, only: nd_output_times, nd_method_code, nd_check_run, nd_output_counts
  implicit none
  private
  public :: double_scene_t, read_double_scene, run_double_scene

  !> The fields of &double (defaults as pendula.DoublePendulum's).
  type :: double_scene_t
    real(dp) :: m1 = 1.0_dp, m2 = 1.0_dp, l1 = 1.0_dp, l2 = 1.0_dp, g = 1.0_dp, damping(2) = 0.0_dp
    logical :: rods = .false.
    real(dp) :: theta1 = 0.0_dp, theta2 = 0.0_dp, omega1 = 0.0_dp, omega2 = 0.0_dp
    real(dp) :: t_end = 10.0_dp, dt = 0.01_dp, rtol = 1.0e-12_dp, atol = 1.0e-12_dp
    integer :: n_samples = 101
    character(len=16) :: method = 'dop853'
  end type double_scene_t

contains

  !> Read and check the group &double of the file `path`: status 0, or 2 with msg naming the field.
  subroutine read_double_scene(path, ds, status, msg)
    character(len=*), intent(in) :: path
    type(double_scene_t), intent(out) :: ds
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    real(dp) :: m1, m2, l1, l2, g, damping(2), theta1, theta2, omega1, omega2, t_end, dt, rtol, atol
    logical :: rods
    integer :: n_samples
    character(len=16) :: method
    namelist /double/ m1, m2, l1, l2, g, rods, damping, theta1, theta2, omega1, omega2, t_end, n_samples, &
      method, dt, rtol, atol
    m1 = ds%m1; m2 = ds%m2; l1 = ds%l1; l2 = ds%l2; g = ds%g; rods = ds%rods; damping = ds%damping
    theta1 = ds%theta1; theta2 = ds%theta2; omega1 = ds%omega1; omega2 = ds%omega2
    t_end = ds%t_end; n_samples = ds%n_samples; method = ds%method; dt = ds%dt; rtol = ds%rtol; atol = ds%atol
    status = 2
    call read_group_file(path, 'double', read_unit, read_line, msg)
    if (len_trim(msg) > 0) return
    ds = double_scene_t(m1, m2, l1, l2, g, damping, rods, theta1, theta2, omega1, omega2, t_end, dt, rtol, &
                        atol, n_samples, method)
    call check_double_scene(ds, msg)
    if (len_trim(msg) > 0) then
      msg = path // ': &double: ' // trim(msg); return
    end if
    status = 0

  contains

    subroutine read_unit(u, ios, iom)
      integer, intent(in) :: u
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: iom
      read(u, nml=double, iostat=ios, iomsg=iom)
    end subroutine read_unit

    subroutine read_line(text, ios, iom)
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: iom
      character(len=len(text) + 12) :: buf
      buf = '&double ' // text // ' /'
      read(buf, nml=double, iostat=ios, iomsg=iom)
    end subroutine read_line

  end subroutine read_double_scene


  !> The first field of ds that is out of its domain, as "field 'NAME' ...", or blank.
  pure subroutine check_double_scene(ds, msg)
    type(double_scene_t), intent(in) :: ds
    character(len=*), intent(out) :: msg
    msg = ''
    if (.not. positive(ds%m1)) then
      msg = 'field ''m1'' must be positive and finite'
    else if (.not. positive(ds%m2)) then
      msg = 'field ''m2'' must be positive and finite'
    else if (.not. positive(ds%l1)) then
      msg = 'field ''l1'' must be positive and finite'
    else if (.not. positive(ds%l2)) then
      msg = 'field ''l2'' must be positive and finite'
    else if (.not. positive(ds%g)) then
      msg = 'field ''g'' must be positive and finite'
    else if (.not. all(ds%damping >= 0.0_dp .and. ds%damping <= huge(1.0_dp))) then
      msg = 'field ''damping'' must be two finite numbers >= 0'
    else if (.not. all(abs([ds%theta1, ds%theta2, ds%omega1, ds%omega2]) <= huge(1.0_dp))) then
      msg = 'fields ''theta1'', ''theta2'', ''omega1'', ''omega2'' must be finite'
    else
      call nd_check_run(ds%method, ds%t_end, ds%n_samples, ds%dt, ds%rtol, ds%atol, msg)
    end if
  end subroutine check_double_scene

  pure logical function positive(x)
    real(dp), intent(in) :: x
    positive = x > 0.0_dp .and. x <= huge(1.0_dp)
  end function positive

  !> The path of a checked scene at its n_samples times t: the rates w(2, :) and the energy;
  !> status as pendula_ode's.
  subroutine run_double_scene(ds, t, theta, w, energy, status, cancel)
    type(double_scene_t), intent(in) :: ds
    real(dp), intent(out) :: t(:), theta(:, :), w(:, :), energy(:)
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    type(double_pendulum) :: dpd
    type(run_stats) :: st
    real(dp) :: p(dpp_size), y0(4), cd
    real(dp), allocatable :: yout(:, :)
    integer(i8), allocatable :: counts(:)
    integer :: j, n
    n = size(t)
    p = [ds%m1, ds%m2, ds%l1, ds%l2, ds%g, merge(1.0_dp, 0.0_dp, ds%rods), ds%damping(1), ds%damping(2)]
    dpd = make_double(p)
    call nd_output_times(ds%t_end, t)
    ! the canonical momenta p = M(theta1 - theta2) w
    cd = cos(ds%theta1 - ds%theta2)
    y0 = [ds%theta1, ds%theta2, dpd%a * ds%omega1 + dpd%b * cd * ds%omega2, dpd%b * cd * ds%omega1 + dpd%c * ds%omega2]
    allocate(yout(4, n), counts(n))
    call nd_output_counts(ds%method, ds%t_end, ds%dt, counts)
    call double_simulate(dpd, nd_method_code(ds%method), y0, t, counts, ds%rtol, ds%atol, ds%dt, yout, st, status, &
                         cancel)
    theta = yout(1:2, :)
    do j = 1, n
      call double_velocities(dpd, yout(:, j), w(:, j))
      energy(j) = double_energy(dpd, yout(:, j))
    end do
  end subroutine run_double_scene

end module pendula_double_scene
