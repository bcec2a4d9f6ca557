!> Output files for the batch programs: lines formatted in Fortran, written
!> through the C glue (kernel/glue/pendula_os.c) with every error checked,
!> all or nothing (a temporary name renamed into place at the end; only
!> regular files written or replaced; temporaries removed on every exit path,
!> SIGINT and SIGTERM included once out_guard_signals is called).
!> Numbers go into lines through out_real / out_reals: one format for every
!> CSV (17 significant digits, as the Python layer's '%.17g').
!>
!> gfortran 12 ignores ENOSPC from write(2) (a run with -o /dev/full exited 0),
!> which is why the bytes do not go through Fortran units.
module pendula_outfile
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_long, c_null_char, c_double
  implicit none
  private
  public :: outfile_t, out_open, out_line, out_close, out_abandon
  public :: out_real, out_reals, out_errtext, out_guard_signals, out_abandon_all

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
    function c_fmt_real(x, buf, n) bind(C, name='pendula_fmt_real') result(k)
      import :: c_int, c_char, c_double
      real(c_double), value, intent(in) :: x
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_int), value, intent(in) :: n
      integer(c_int) :: k
    end function c_fmt_real
    subroutine c_errtext(err, buf, n) bind(C, name='pendula_out_errtext')
      import :: c_int, c_char
      integer(c_int), value, intent(in) :: err
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_int), value, intent(in) :: n
    end subroutine c_errtext
    subroutine out_guard_signals() bind(C, name='pendula_out_guard_signals')
    end subroutine out_guard_signals
    subroutine out_abandon_all() bind(C, name='pendula_out_abandon_all')
    end subroutine out_abandon_all
  end interface

contains

  !> x as CSV text: 17 significant digits (reads back as the same double),
  !> trailing zeros dropped; 'nan', 'inf', '-inf'.
  function out_real(x) result(t)
    real(c_double), intent(in) :: x
    character(len=:), allocatable :: t
    character(kind=c_char) :: b(40)
    integer :: k, i
    k = c_fmt_real(x, b, size(b, kind=c_int))
    allocate(character(len=k) :: t)
    do i = 1, k
      t(i:i) = b(i)
    end do
  end function out_real

  !> The reals of xs as CSV fields joined by commas.
  function out_reals(xs) result(t)
    real(c_double), intent(in) :: xs(:)
    character(len=:), allocatable :: t
    integer :: i
    t = ''
    do i = 1, size(xs)
      if (i > 1) t = t // ','
      t = t // out_real(xs(i))
    end do
  end function out_reals

  !> The words for an error code of out_open / out_close.
  function out_errtext(err) result(t)
    integer, intent(in) :: err
    character(len=:), allocatable :: t
    character(kind=c_char) :: b(256)
    integer :: i
    b = c_null_char
    call c_errtext(int(err, c_int), b, size(b, kind=c_int))
    t = ''
    do i = 1, size(b)
      if (b(i) == c_null_char) exit
      t = t // b(i)
    end do
  end function out_errtext

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
