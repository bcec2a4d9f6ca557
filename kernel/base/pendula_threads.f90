!> How many OpenMP threads a parallel kernel call runs on: the caller's
!> count when positive, otherwise OpenMP's default (OMP_NUM_THREADS, or all
!> cores), and never more than max_threads.  Every parallel loop of the
!> kernel (sweeps, attractor maps, Langevin path sets) takes its count here.
module pendula_threads
  implicit none
  private
  public :: max_threads, thread_count

  !> the most threads one call runs on (the sweeps' limit, read by the Python checker)
  integer, parameter :: max_threads = 256

contains

  function thread_count(nthreads) result(nt)
    !$ use omp_lib, only: omp_get_max_threads
    integer, intent(in) :: nthreads
    integer :: nt
    nt = 1
    !$ nt = omp_get_max_threads()
    if (nthreads > 0) nt = nthreads
    nt = max(1, min(nt, max_threads))
  end function thread_count

end module pendula_threads
