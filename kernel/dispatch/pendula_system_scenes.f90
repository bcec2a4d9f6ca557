!> The scene files of the systems built by their own class (&double, &foucault,
!> &network) as one table: each system's reader and run (pendula_*_scene), and
!> the columns and title of the table pendula-run writes.  The Python layer
!> reads and runs these files through here, so that both programs give a file
!> one verdict and one table.
module pendula_system_scenes
  use pendula_kinds, only: dp
  use pendula_group_file, only: scene_group
  use pendula_double_scene, only: double_scene_t, read_double_scene, run_double_scene
  use pendula_foucault_scene, only: foucault_scene_t, read_foucault_scene, run_foucault_scene
  use pendula_network_scene, only: network_scene_t, read_network_scene, run_network_scene
  implicit none
  private
  public :: system_scene_size, system_scene_table

contains

  !> Read and check the scene file `path` of a system: its group ('double', 'foucault' or 'network'), the
  !> rows and columns of its table; status 0, 1 (group blank) when the file holds no such group, or 2
  !> with msg naming the field, as pendula-run reports it.
  subroutine system_scene_size(path, group, nrows, ncols, status, msg)
    character(len=*), intent(in) :: path
    character(len=*), intent(out) :: group, msg
    integer, intent(out) :: nrows, ncols, status
    type(double_scene_t) :: ds
    type(foucault_scene_t) :: fs
    type(network_scene_t) :: ns
    group = scene_group(path)
    nrows = 0
    ncols = 0
    msg = ''
    select case (trim(group))
    case ('double')
      call read_double_scene(path, ds, status, msg)
      nrows = ds%n_samples
      ncols = 6
    case ('foucault')
      call read_foucault_scene(path, fs, status, msg)
      nrows = fs%n_samples
      ncols = 7
    case ('network')
      call read_network_scene(path, ns, status, msg)
      nrows = ns%n_samples
      ncols = 2 * ns%n + 1
    case default
      group = ''
      status = 1
      msg = path // ': not the scene file of a system (&double, &foucault, &network)'
    end select
    if (status /= 0) then
      nrows = 0
      ncols = 0
    end if
  end subroutine system_scene_size

  !> The table of the scene file `path` of a system (table(nrows, ncols) as system_scene_size gives them),
  !> its column names (comma-separated) and title as pendula-run writes them: status 0; 1 no system's
  !> group; 2 a bad scene, or a table of another shape; 4 the run failed; msg says why (as pendula-run).
  subroutine system_scene_table(path, table, heads, title, status, msg)
    character(len=*), intent(in) :: path
    real(dp), intent(out) :: table(:, :)
    character(len=*), intent(out) :: heads, title, msg
    integer, intent(out) :: status
    type(double_scene_t) :: ds
    type(foucault_scene_t) :: fs
    type(network_scene_t) :: ns
    character(len=16) :: group, num
    real(dp), allocatable :: th(:, :), w(:, :), y(:, :)
    integer :: nrows, ncols, cancel, k, st
    table = 0.0_dp
    heads = ''
    title = ''
    call system_scene_size(path, group, nrows, ncols, status, msg)
    if (status /= 0) return
    if (nrows /= size(table, 1) .or. ncols /= size(table, 2)) then
      status = 2
      write(msg, '(a, i0, a, i0, a)') path // ': the table has ', nrows, ' rows and ', ncols, ' columns'
      return
    end if
    cancel = 0
    select case (trim(group))
    case ('double')
      call read_double_scene(path, ds, st, msg)
      allocate(th(2, nrows), w(2, nrows))
      call run_double_scene(ds, table(:, 1), th, w, table(:, 6), st, cancel)
      table(:, 2) = th(1, :)
      table(:, 3) = th(2, :)
      table(:, 4) = w(1, :)
      table(:, 5) = w(2, :)
      title = 'double pendulum, method ' // trim(ds%method)
      heads = 't,theta1,theta2,omega1,omega2,energy'
    case ('foucault')
      call read_foucault_scene(path, fs, st, msg)
      allocate(y(6, nrows))
      call run_foucault_scene(fs, table(:, 1), y, st, cancel)
      table(:, 2:7) = transpose(y)
      title = 'Foucault pendulum, DOP853'
      heads = 't,x,y,z,vx,vy,vz'
    case default
      call read_network_scene(path, ns, st, msg)
      allocate(y(2 * ns%n, nrows))
      call run_network_scene(ns, table(:, 1), y, st, cancel)
      table(:, 2:) = transpose(y)
      heads = 't'
      do k = 1, 2 * ns%n
        write(num, '(i0)') mod(k - 1, ns%n) + 1
        heads = trim(heads) // ',' // trim(merge('phi_', 'v_  ', k <= ns%n)) // trim(num)
      end do
      write(num, '(i0)') ns%n
      title = 'network of ' // trim(num) // ' elements, ' // trim(ns%topology) // ', method ' // trim(ns%method)
    end select
    if (st /= 0) then
      status = 4
      write(num, '(i0)') st
      msg = path // ': the ' // trim(title) // ' run failed (integrator status ' // trim(num) // &
            '): loosen rtol or shorten t_end'
    end if
  end subroutine system_scene_table

end module pendula_system_scenes
