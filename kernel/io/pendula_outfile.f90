!> Output files for the batch programs: lines formatted in Fortran, written
!> through the C glue (kernel/glue/pendula_os.c) with every error checked,
!> all or nothing (a temporary name renamed into place at the end).
!>
!> gfortran 12 ignores ENOSPC from write(2) (a run with -o /dev/full exited 0),
!> which is why the bytes do not go through Fortran units.
module pendula_outfile
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_long, c_null_char
  implicit none
  private
  public :: outfile_t, out_open, out_line, out_close, out_abandon

  integer, parameter :: chunk = 1048576

  type :: outfile_t
    integer :: fd = -1
    character(len=4096) :: path = '', tmp = ''
    character(len=:), allocatable :: buf
    integer :: n = 0
    !> first error (errno), 0 if none
    integer :: err = 0
  end type outfile_t

  interface
    function c_open(path, tmp, tmplen) bind(C, name='pendula_out_open') result(fd)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      character(kind=c_char), intent(out) :: tmp(*)
      integer(c_int), value, intent(in) :: tmplen
      integer(c_int) :: fd
    end function c_open
    function c_write(fd, buf, n) bind(C, name='pendula_out_write') result(err)
      import :: c_int, c_char, c_long
      integer(c_int), value, intent(in) :: fd
      character(kind=c_char), intent(in) :: buf(*)
      integer(c_long), value, intent(in) :: n
      integer(c_int) :: err
    end function c_write
    function c_close(fd, tmp, path, abandon) bind(C, name='pendula_out_close') result(err)
      import :: c_int, c_char
      integer(c_int), value, intent(in) :: fd
      character(kind=c_char), intent(in) :: tmp(*), path(*)
      integer(c_int), value, intent(in) :: abandon
      integer(c_int) :: err
    end function c_close
  end interface

contains

  !> Open path ('-' = standard output) for writing; status 0 or errno.
  subroutine out_open(f, path, status)
    type(outfile_t), intent(inout) :: f
    character(len=*), intent(in) :: path
    integer, intent(out) :: status
    character(kind=c_char) :: t(4097)
    integer :: i, fd
    f%path = path
    fd = c_open(trim(path) // c_null_char, t, size(t, kind=c_int))
    f%tmp = ''
    do i = 1, size(t)
      if (t(i) == c_null_char) exit
      f%tmp(i:i) = t(i)
    end do
    if (fd < 0) then
      status = -fd
      f%fd = -1
      return
    end if
    f%fd = fd
    if (.not. allocated(f%buf)) allocate(character(len=chunk) :: f%buf)
    f%n = 0
    f%err = 0
    status = 0
  end subroutine out_open

  !> Append one line (trailing blanks removed, a newline added).
  subroutine out_line(f, line)
    type(outfile_t), intent(inout) :: f
    character(len=*), intent(in) :: line
    integer :: k
    k = len_trim(line)
    if (f%n + k + 1 > len(f%buf)) call drain(f)
    if (k + 1 > len(f%buf)) then
      if (f%err == 0) f%err = c_write(f%fd, line(1:k) // new_line('a'), int(k + 1, c_long))
      return
    end if
    f%buf(f%n + 1:f%n + k) = line(1:k)
    f%buf(f%n + k + 1:f%n + k + 1) = new_line('a')
    f%n = f%n + k + 1
  end subroutine out_line

  subroutine drain(f)
    type(outfile_t), intent(inout) :: f
    if (f%n > 0 .and. f%err == 0) f%err = c_write(f%fd, f%buf(1:f%n), int(f%n, c_long))
    f%n = 0
  end subroutine drain

  !> Write what is left, make it durable and rename it into place; status 0 or errno.
  subroutine out_close(f, status)
    type(outfile_t), intent(inout) :: f
    integer, intent(out) :: status
    integer :: e
    status = 0
    if (f%fd < 0) return
    call drain(f)
    e = c_close(f%fd, trim(f%tmp) // c_null_char, trim(f%path) // c_null_char, merge(1, 0, f%err /= 0))
    status = f%err
    if (status == 0) status = e
    f%fd = -1
  end subroutine out_close

  !> Give up: close and remove the temporary file; the real name is untouched.
  subroutine out_abandon(f)
    type(outfile_t), intent(inout) :: f
    integer :: e
    if (f%fd < 0) return
    e = c_close(f%fd, trim(f%tmp) // c_null_char, trim(f%path) // c_null_char, 1)
    f%fd = -1
  end subroutine out_abandon

end module pendula_outfile
