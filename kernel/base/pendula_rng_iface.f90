!> The Fortran interface of the counter-based normal numbers (pendula_rng.c),
!> declared once for every noisy integrator: the key of a stream (seed, index)
!> and the normals of a key from a counter on.
module pendula_rng_iface
  use, intrinsic :: iso_c_binding, only: c_int64_t, c_int32_t, c_double
  implicit none
  private
  public :: pendula_rng_key, pendula_rng_normals

  interface
    !> The key of stream `index` of `seed`.
    function pendula_rng_key(seed, index) bind(C, name="pendula_rng_key") result(key)
      import :: c_int64_t
      integer(c_int64_t), value, intent(in) :: seed, index
      integer(c_int64_t) :: key
    end function pendula_rng_key
    !> n standard normal numbers of stream `key`, counters first .. first + n - 1.
    subroutine pendula_rng_normals(key, first, n, z) bind(C, name="pendula_rng_normals")
      import :: c_int64_t, c_int32_t, c_double
      integer(c_int64_t), value, intent(in) :: key, first
      integer(c_int32_t), value, intent(in) :: n
      real(c_double), intent(out) :: z(*)
    end subroutine pendula_rng_normals
  end interface
end module pendula_rng_iface
