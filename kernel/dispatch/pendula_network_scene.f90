!> A network's scene file for pendula-run: the namelist group &network, its
!> fields and their checks (each refusal names the field), and its run on
!> the n-dimensional driver (pendula_network_run).
!>
!>   &network
!>     n = 4, topology = 'chain', strength = 0.5,
!>     eps = 1.0, damping = 0.1, mass = 1.0, bias = 0.0,
!>     drive_amplitude = 0.0, drive_frequency = 0.0, drive_phase = 0.0,
!>     phi0 = 0.5, 0.0, 0.0, 0.0, v0 = 0.0,
!>     t_end = 20, n_samples = 201, method = 'dop853', dt = 0.01, rtol = 1e-10, atol = 1e-12
!>   /
!>
!> A per-element field takes one value (every element) or n values.  The
!> topology is 'pair', 'chain', 'ring' or 'ladder' (the springs of
!> pendula.Network's named topologies, in its order), every spring of
!> stiffness `strength`.  The path is output at n_samples times from 0 to
!> t_end: t, then phi and v of each element.
module pendula_network_scene
  use pendula_kinds, only: dp, i8, nan_dp
  use pendula_integrators, only: run_stats
  use pendula_network, only: network, make_network, np_rows
  use pendula_network_run, only: network_simulate, nd_dop853
  use pendula_group_file, only: read_group_file
  use pendula_nd_run, only: nd_output_times, nd_method_code, nd_check_run, nd_output_counts
  implicit none
  private
  public :: network_scene_t, read_network_scene, run_network_scene, max_elements

  !> the most elements a scene file names (larger networks: pendula.Network)
  integer, parameter :: max_elements = 1000
  integer, parameter :: n_per_element = 9
  character(len=16), parameter :: per_element_names(n_per_element) = [character(len=16) :: 'mass', 'damping', &
    'eps', 'bias', 'drive_amplitude', 'drive_frequency', 'drive_phase', 'phi0', 'v0']

  !> The fields of &network (defaults as pendula.Network's); per(:, k) the per-element field k.
  type :: network_scene_t
    integer :: n = 2, n_samples = 101
    character(len=16) :: topology = 'pair', method = 'dop853'
    real(dp) :: strength = 1.0_dp, t_end = 10.0_dp, dt = 0.01_dp, rtol = 1.0e-10_dp, atol = 1.0e-12_dp
    real(dp), allocatable :: per(:, :)
  end type network_scene_t

contains

  !> Read and check the group &network of the file `path`: status 0, or 2 with msg naming the field.
  subroutine read_network_scene(path, ns, status, msg)
    character(len=*), intent(in) :: path
    type(network_scene_t), intent(out) :: ns
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    integer :: n, n_samples, k, m
    character(len=16) :: topology, method
    real(dp) :: strength, t_end, dt, rtol, atol
    real(dp), dimension(max_elements) :: mass, damping, eps, bias, drive_amplitude, drive_frequency, drive_phase, &
      phi0, v0
    real(dp) :: given(max_elements, n_per_element), deflt(n_per_element)
    namelist /network/ n, topology, strength, mass, damping, eps, bias, drive_amplitude, drive_frequency, &
      drive_phase, phi0, v0, t_end, n_samples, method, dt, rtol, atol
    n = ns%n; n_samples = ns%n_samples; topology = ns%topology; method = ns%method; strength = ns%strength
    t_end = ns%t_end; dt = ns%dt; rtol = ns%rtol; atol = ns%atol
    ! a per-element field not given stays NaN: its default, or the count of values given
    mass = nan_dp; damping = nan_dp; eps = nan_dp; bias = nan_dp; drive_amplitude = nan_dp
    drive_frequency = nan_dp; drive_phase = nan_dp; phi0 = nan_dp; v0 = nan_dp
    status = 2
    call read_group_file(path, 'network', read_unit, read_line, msg)
    if (len_trim(msg) > 0) return
    ns%n = n; ns%n_samples = n_samples; ns%topology = topology; ns%method = method; ns%strength = strength
    ns%t_end = t_end; ns%dt = dt; ns%rtol = rtol; ns%atol = atol
    msg = ''
    if (n < 1 .or. n > max_elements) then
      write(msg, '(a, i0, a)') 'field ''n'' must lie in [1, ', max_elements, '] (larger networks: pendula.Network)'
    else
      given = reshape([mass, damping, eps, bias, drive_amplitude, drive_frequency, drive_phase, phi0, v0], &
                      [max_elements, n_per_element])
      deflt = [1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
      allocate(ns%per(n, n_per_element))
      do k = 1, n_per_element
        m = count_given(given(:, k))
        if (m == 0) then
          ns%per(:, k) = deflt(k)
        else if (m == 1) then
          ns%per(:, k) = given(1, k)
        else if (m == n) then
          ns%per(:, k) = given(1:n, k)
        else
          write(msg, '(a, i0, a, i0)') 'field ''' // trim(per_element_names(k)) // ''' takes one value or n = ', &
            n, ' (one per element), got ', m
          exit
        end if
      end do
      if (len_trim(msg) == 0) call check_network_scene(ns, msg)
    end if
    if (len_trim(msg) > 0) then
      msg = path // ': &network: ' // trim(msg); return
    end if
    status = 0

  contains

    subroutine read_unit(u, ios, iom)
      integer, intent(in) :: u
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: iom
      read(u, nml=network, iostat=ios, iomsg=iom)
    end subroutine read_unit

    subroutine read_line(text, ios, iom)
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: iom
      character(len=len(text) + 13) :: buf
      buf = '&network ' // text // ' /'
      read(buf, nml=network, iostat=ios, iomsg=iom)
    end subroutine read_line

  end subroutine read_network_scene

  !> How many values of a per-element field were given: those before the first NaN (not given).
  pure integer function count_given(x)
    real(dp), intent(in) :: x(:)
    count_given = 0
    do while (count_given < size(x))
      if (x(count_given + 1) /= x(count_given + 1)) exit
      count_given = count_given + 1
    end do
  end function count_given

  !> The first field of ns out of its domain, as "field 'NAME' ...", or blank.
  pure subroutine check_network_scene(ns, msg)
    type(network_scene_t), intent(in) :: ns
    character(len=*), intent(out) :: msg
    integer :: j
    msg = ''
    do j = 1, n_per_element
      if (.not. all(abs(ns%per(:, j)) <= huge(1.0_dp))) then
        msg = 'field ''' // trim(per_element_names(j)) // ''' must be finite'; return
      end if
    end do
    if (.not. all(ns%per(:, 1) > 0.0_dp)) then
      msg = 'field ''mass'' must be > 0'
    else if (.not. all(ns%per(:, 2) >= 0.0_dp)) then
      msg = 'field ''damping'' must be >= 0'
    else if (ns%topology /= 'pair' .and. ns%topology /= 'chain' .and. ns%topology /= 'ring' .and. &
             ns%topology /= 'ladder') then
      msg = 'field ''topology'' must be ''pair'', ''chain'', ''ring'' or ''ladder'', got ''' // trim(ns%topology) // ''''
    else if (ns%topology == 'pair' .and. ns%n /= 2) then
      msg = 'field ''topology'': ''pair'' has 2 elements (n = 2)'
    else if (ns%topology == 'ring' .and. ns%n < 3) then
      msg = 'field ''topology'': ''ring'' needs n >= 3'
    else if (ns%topology == 'ladder' .and. (ns%n < 4 .or. mod(ns%n, 2) /= 0)) then
      msg = 'field ''topology'': ''ladder'' needs an even n >= 4 (two rails)'
    else if (.not. (ns%strength >= 0.0_dp .and. ns%strength <= huge(1.0_dp))) then
      msg = 'field ''strength'' must be finite and >= 0'
    else
      call nd_check_run(ns%method, ns%t_end, ns%n_samples, ns%dt, ns%rtol, ns%atol, msg)
    end if
  end subroutine check_network_scene

  !> The springs (ei < ej, 1-based) of a named topology on n elements, in pendula.Network's order.
  pure subroutine topology_springs(name, n, ei, ej)
    character(len=*), intent(in) :: name
    integer, intent(in) :: n
    integer, allocatable, intent(out) :: ei(:), ej(:)
    integer :: i, m
    select case (trim(name))
    case ('pair')
      ei = [1]; ej = [2]
    case ('chain')
      ei = [(i, i = 1, n - 1)]; ej = ei + 1
    case ('ring')
      ei = [(i, i = 1, n - 1), 1]; ej = [(i + 1, i = 1, n - 1), n]
    case default   ! ladder: two rails of m joined by rungs
      m = n / 2
      ei = [(i, i = 1, m - 1), (m + i, i = 1, m - 1), (i, i = 1, m)]
      ej = [(i + 1, i = 1, m - 1), (m + i + 1, i = 1, m - 1), (m + i, i = 1, m)]
    end select
  end subroutine topology_springs

  !> The path of a checked scene at its n_samples times t: yout(2n, :) = (phi, v); status as pendula_ode's.
  subroutine run_network_scene(ns, t, yout, status, cancel)
    type(network_scene_t), intent(in) :: ns
    real(dp), intent(out) :: t(:), yout(:, :)
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    type(run_stats) :: st
    integer, allocatable :: ei(:), ej(:)
    integer(i8), allocatable :: counts(:)
    real(dp) :: p(np_rows, ns%n), h
    call nd_output_times(ns%t_end, t)
    call topology_springs(ns%topology, ns%n, ei, ej)
    p = transpose(ns%per(:, 1:np_rows))
    allocate(counts(size(t)))
    call nd_output_counts(ns%method, ns%t_end, ns%dt, counts)
    h = merge(0.0_dp, ns%dt, nd_method_code(ns%method) == nd_dop853)
    call network_simulate(make_network(p, ei, ej, spread(ns%strength, 1, size(ei)), spread(0.0_dp, 1, size(ei))), &
                          nd_method_code(ns%method), [ns%per(:, 8), ns%per(:, 9)], t, counts, ns%rtol, ns%atol, h, &
                          yout, st, status, cancel)
  end subroutine run_network_scene

end module pendula_network_scene
