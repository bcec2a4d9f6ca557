!> Harmonic spectra with FFTW (its Fortran 2003 interface).
!>
!> One in-place real-to-complex plan per signal length, made once (the Python
!> layer keeps it for later calls of the same length) and executed on a fresh
!> aligned buffer for every call (new-array execution is thread-safe in FFTW;
!> planning is not, and the caller serialises it).  Optional
!> Hann window.  Amplitudes are normalised so that a sin(w t) sampled over a
!> whole number of periods gives |A| = a in its bin: A_k = 2 X_k / sum(w),
!> A_0 = X_0 / sum(w); the power is |A_k|^2.
module pendula_spectrum
  use, intrinsic :: iso_c_binding
  use pendula_kinds, only: dp, two_pi
  implicit none
  private
  public :: power_spectra, spectrum_plan, spectrum_plan_free, wisdom_import, wisdom_export

  include 'fftw3.f03'

  integer, parameter, public :: window_none = 0, window_hann = 1
  integer, parameter, public :: spec_ok = 0, spec_too_short = 1, spec_bad_window = 2, &
                                spec_no_memory = 3, spec_cancelled = 5
  !> measured planning of one length stops after this many seconds with the best
  !> plan found so far (FFTW's time limit): a 2^22-sample FFTW_MEASURE takes minutes
  real(c_double), parameter, public :: plan_seconds = 10.0_c_double

contains

  !> A real-to-complex plan for n samples, made on FFTW-aligned buffers (which
  !> are freed again: FFTW executes the plan on any buffers with the same
  !> alignment).  Returns the plan as an address (0 on failure).  Planning is
  !> not thread-safe in FFTW: callers serialise it.
  function spectrum_plan(n, measure) result(handle)
    integer, intent(in) :: n
    logical, intent(in) :: measure
    integer(c_intptr_t) :: handle
    type(c_ptr) :: plan, pin, pout
    real(c_double), pointer :: buf(:)
    complex(c_double_complex), pointer :: spec(:)
    integer(c_int) :: flags
    handle = 0
    ! in place: the n samples in a buffer of n/2 + 1 complex numbers, transformed
    ! where they lie (2^20 samples: 5 ms against 15 ms out of place at
    ! FFTW_ESTIMATE, the buffers touched once instead of twice)
    pin = fftw_alloc_complex(int(n / 2 + 1, c_size_t))
    pout = pin
    if (.not. c_associated(pin)) return
    call c_f_pointer(pin, buf, [2 * (n / 2 + 1)])
    call c_f_pointer(pout, spec, [n / 2 + 1])
    ! measure: plan by measuring (seconds for long records; the result goes
    ! into FFTW's wisdom).  Otherwise use a measured plan if the wisdom (loaded
    ! from the cache file) has one for n, else estimate.
    if (measure) then
      call fftw_set_timelimit(plan_seconds)
      plan = fftw_plan_dft_r2c_1d(int(n, c_int), buf, spec, FFTW_MEASURE)
      call fftw_set_timelimit(-1.0_c_double)
    else
      flags = ior(FFTW_MEASURE, FFTW_WISDOM_ONLY)
      plan = fftw_plan_dft_r2c_1d(int(n, c_int), buf, spec, flags)
      if (.not. c_associated(plan)) &
        plan = fftw_plan_dft_r2c_1d(int(n, c_int), buf, spec, FFTW_ESTIMATE)
    end if
    call fftw_free(pin)
    handle = transfer(plan, handle)
  end function spectrum_plan

  !> Load FFTW wisdom from a file (a NUL-terminated path in the caller's
  !> character string).  Returns .true. on success; a corrupt or foreign file
  !> is refused by FFTW and leaves the wisdom as it was.  Not thread-safe
  !> (planner state): callers serialise it with planning.
  function wisdom_import(path) result(ok)
    character(len=*), intent(in) :: path
    logical :: ok
    ok = fftw_import_wisdom_from_filename(trim(path) // c_null_char) /= 0
  end function wisdom_import

  !> Save FFTW's accumulated wisdom to a file; .true. on success.
  function wisdom_export(path) result(ok)
    character(len=*), intent(in) :: path
    logical :: ok
    ok = fftw_export_wisdom_to_filename(trim(path) // c_null_char) /= 0
  end function wisdom_export

  subroutine spectrum_plan_free(handle)
    integer(c_intptr_t), intent(in) :: handle
    if (handle /= 0) call fftw_destroy_plan(transfer(handle, c_null_ptr))
  end subroutine spectrum_plan_free

  !> Power spectra |A_k|^2 of the columns of signals (n samples, spacing dt each)
  !> with a plan made by spectrum_plan for this n, reused for every column.
  !> omega(k) = 2 pi k / (n dt), k = 0 .. n/2.
  !> cancel (optional): read before each signal; non-zero stops with status
  !> spec_cancelled.
  subroutine power_spectra(handle, signals, dt, window, omega, power, status, cancel)
    integer(c_intptr_t), intent(in) :: handle
    real(dp), intent(in) :: signals(:, :), dt
    integer, intent(in) :: window
    real(dp), intent(out) :: omega(:), power(:, :)
    integer, intent(out) :: status
    integer, intent(inout), volatile, optional :: cancel
    type(c_ptr) :: plan, pin, pout
    real(c_double), pointer :: buf(:)
    complex(c_double_complex), pointer :: spec(:)
    real(dp), allocatable :: w(:)
    real(dp) :: wsum, scale
    integer :: n, nh, j, k

    n = size(signals, 1)
    nh = n / 2 + 1
    status = spec_ok
    if (n < 4) then
      status = spec_too_short; return
    end if
    if (window /= window_none .and. window /= window_hann) then
      status = spec_bad_window; return
    end if
    if (handle == 0) then
      status = spec_no_memory; return
    end if
    plan = transfer(handle, plan)
    if (window == window_hann) then
      allocate(w(n))
      do k = 1, n
        w(k) = 0.5_dp - 0.5_dp * cos(two_pi * real(k - 1, dp) / real(n, dp))   ! periodic Hann
      end do
      wsum = sum(w)
    else
      wsum = real(n, dp)
    end if
    scale = 4.0_dp / (wsum * wsum)
    ! one buffer: the plan transforms in place (spectrum_plan)
    pin = fftw_alloc_complex(int(nh, c_size_t))
    pout = pin
    if (.not. c_associated(pin)) then
      status = spec_no_memory; return
    end if
    call c_f_pointer(pin, buf, [2 * nh])
    call c_f_pointer(pout, spec, [nh])
    do k = 1, nh
      omega(k) = two_pi * real(k - 1, dp) / (real(n, dp) * dt)
    end do
    do j = 1, size(signals, 2)
      if (present(cancel)) then
        if (cancel /= 0) then
          status = spec_cancelled; exit
        end if
      end if
      if (window == window_none) then
        buf(1:n) = signals(:, j)
      else
        buf(1:n) = signals(:, j) * w
      end if
      call fftw_execute_dft_r2c(plan, buf, spec)
      ! |A|^2 from the real and imaginary parts (no hypot), one pass
      do k = 1, nh
        power(k, j) = scale * (real(spec(k), dp)**2 + aimag(spec(k))**2)
      end do
      power(1, j) = 0.25_dp * power(1, j)
      if (mod(n, 2) == 0) power(nh, j) = 0.25_dp * power(nh, j)
    end do
    call fftw_free(pin)
  end subroutine power_spectra

end module pendula_spectrum
