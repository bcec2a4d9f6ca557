!> The Foucault pendulum's scene file for pendula-run: the namelist group
!> &foucault, its fields and their checks (each refusal names the field),
!> and its run on the n-dimensional driver (pendula_foucault_run).
!>
!>   &foucault
!>     latitude = 48.85, length = 67, g = 9.81, earth_rate = 7.292115e-5, damping = 0,
!>     anisotropy = 0, 0, theta0 = 0.05, azimuth = 0, theta_dot0 = 0, phi_dot0 = 0,
!>     t_end = 600, n_samples = 601, rtol = 1e-12
!>   /
!>
!> Units SI (latitude in degrees, north positive).  The bob starts at the
!> polar angle theta0 from the downward vertical at the azimuth (from east
!> towards north), with the rates theta_dot0 and phi_dot0; the path is
!> integrated by DOP853 at rtol (atol = rtol length) and output at
!> n_samples times from 0 to t_end: t, x, y, z (east, north, up), theta, phi.
module pendula_foucault_scene
  use pendula_kinds, only: dp, pi
  use pendula_integrators, only: run_stats
  use pendula_foucault, only: foucault, make_foucault, fp_size, fst_ok, fst_latitude, fst_gl, fst_rate
  use pendula_foucault_run, only: foucault_simulate
  use pendula_group_file, only: read_group_file
  use pendula_nd_run, only: nd_output_times, nd_check_run
  implicit none
  private
  public :: foucault_scene_t, read_foucault_scene, run_foucault_scene

  !> The fields of &foucault (defaults as pendula.FoucaultPendulum's).
  type :: foucault_scene_t
    real(dp) :: latitude = 45.0_dp, length = 67.0_dp, g = 9.81_dp, earth_rate = 7.292115e-5_dp, damping = 0.0_dp
    real(dp) :: anisotropy(2) = 0.0_dp, theta0 = 0.05_dp, azimuth = 0.0_dp, theta_dot0 = 0.0_dp, phi_dot0 = 0.0_dp
    real(dp) :: t_end = 600.0_dp, rtol = 1.0e-12_dp
    integer :: n_samples = 601
  end type foucault_scene_t

contains

  !> Read and check the group &foucault of the file `path`: status 0, or 2 with msg naming the field.
  subroutine read_foucault_scene(path, fs, status, msg)
    character(len=*), intent(in) :: path
    type(foucault_scene_t), intent(out) :: fs
    integer, intent(out) :: status
    character(len=*), intent(out) :: msg
    real(dp) :: latitude, length, g, earth_rate, damping, anisotropy(2), theta0, azimuth, theta_dot0, phi_dot0, &
      t_end, rtol
    integer :: n_samples
    namelist /foucault/ latitude, length, g, earth_rate, damping, anisotropy, theta0, azimuth, theta_dot0, &
      phi_dot0, t_end, n_samples, rtol
    latitude = fs%latitude; length = fs%length; g = fs%g; earth_rate = fs%earth_rate; damping = fs%damping
    anisotropy = fs%anisotropy; theta0 = fs%theta0; azimuth = fs%azimuth; theta_dot0 = fs%theta_dot0
    phi_dot0 = fs%phi_dot0; t_end = fs%t_end; n_samples = fs%n_samples; rtol = fs%rtol
    status = 2
    call read_group_file(path, 'foucault', read_unit, read_line, msg)
    if (len_trim(msg) > 0) return
    fs = foucault_scene_t(latitude, length, g, earth_rate, damping, anisotropy, theta0, azimuth, theta_dot0, &
                          phi_dot0, t_end, rtol, n_samples)
    call check_foucault_scene(fs, msg)
    if (len_trim(msg) > 0) then
      msg = path // ': &foucault: ' // trim(msg); return
    end if
    status = 0

  contains

    subroutine read_unit(u, ios, iom)
      integer, intent(in) :: u
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: iom
      read(u, nml=foucault, iostat=ios, iomsg=iom)
    end subroutine read_unit

    subroutine read_line(text, ios, iom)
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: iom
      character(len=len(text) + 14) :: buf
      buf = '&foucault ' // text // ' /'
      read(buf, nml=foucault, iostat=ios, iomsg=iom)
    end subroutine read_line

  end subroutine read_foucault_scene

  !> The pendulum's parameters as make_foucault takes them.
  pure function params(fs) result(p)
    type(foucault_scene_t), intent(in) :: fs
    real(dp) :: p(fp_size)
    p = [fs%g, fs%length, fs%earth_rate, fs%latitude, fs%damping, fs%anisotropy(1), fs%anisotropy(2)]
  end function params

  !> The first field of fs out of its domain, as "field 'NAME' ...", or blank (the pendulum's own
  !> fields are checked by make_foucault, the start and the run's here).
  pure subroutine check_foucault_scene(fs, msg)
    type(foucault_scene_t), intent(in) :: fs
    character(len=*), intent(out) :: msg
    type(foucault) :: fc
    integer :: st
    msg = ''
    call make_foucault(params(fs), fc, st)
    if (st == fst_latitude) then
      msg = 'field ''latitude'' must lie in [-90, 90] degrees'
    else if (st == fst_gl) then
      msg = 'fields ''g'', ''length'' must be positive and finite'
    else if (st == fst_rate) then
      msg = 'fields ''earth_rate'', ''damping'' must be finite and >= 0'
    else if (st /= fst_ok) then
      msg = 'field ''anisotropy'' must be two finite numbers > -1 (east, north)'
    else if (.not. (fs%theta0 >= 0.0_dp .and. fs%theta0 < 0.5_dp * pi)) then
      msg = 'field ''theta0'' must lie in [0, pi/2) (the bob below the pivot)'
    else if (.not. all(abs([fs%azimuth, fs%theta_dot0, fs%phi_dot0]) <= huge(1.0_dp))) then
      msg = 'fields ''azimuth'', ''theta_dot0'', ''phi_dot0'' must be finite'
    else if (fs%theta0 == 0.0_dp .and. fs%phi_dot0 /= 0.0_dp) then
      msg = 'field ''phi_dot0'' must be 0 at the bottom theta0 = 0: the azimuth is undefined there'
    else
      call nd_check_run('dop853', fs%t_end, fs%n_samples, 0.0_dp, fs%rtol, fs%rtol * fs%length, msg)
    end if
  end subroutine check_foucault_scene

  !> The path of a checked scene at its n_samples times t: yout(6, :) = (x, y, z, vx, vy, vz);
  !> status as pendula_ode's.
  subroutine run_foucault_scene(fs, t, yout, status, cancel)
    type(foucault_scene_t), intent(in) :: fs
    real(dp), intent(out) :: t(:), yout(:, :)
    integer, intent(out) :: status
    integer, intent(inout), volatile :: cancel
    type(foucault) :: fc
    type(run_stats) :: st
    real(dp) :: y0(6), el, sth, cth, sph, cph, thd, phd
    call make_foucault(params(fs), fc, status)
    call nd_output_times(fs%t_end, t)
    ! the start in Cartesian coordinates, as pendula.FoucaultPendulum takes it
    el = fs%length
    sth = sin(fs%theta0); cth = cos(fs%theta0); sph = sin(fs%azimuth); cph = cos(fs%azimuth)
    thd = fs%theta_dot0; phd = fs%phi_dot0
    y0 = [el * (sth * cph), el * (sth * sph), el * (-cth), el * (thd * cth * cph - sth * sph * phd), &
          el * (thd * cth * sph + sth * cph * phd), el * (thd * sth)]
    call foucault_simulate(fc, y0, t, fs%rtol, fs%rtol * el, yout, st, status, cancel)
  end subroutine run_foucault_scene

end module pendula_foucault_scene
