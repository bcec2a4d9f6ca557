! a_n(q) of the points in a file (argument 1: the count, then "n q" a line), argument 2 times: pendula's kernel alone
program pendula_values
  use pendula_kinds, only: dp
  use pendula_mathieu, only: mathieu_char
  implicit none
  integer :: i, n, st, reps, r
  integer, allocatable :: ord(:)
  real(dp), allocatable :: q(:)
  real(dp) :: val, bnd, acc
  character(len=256) :: fname, arg
  call get_command_argument(1, fname)
  call get_command_argument(2, arg)
  read(arg, *) reps
  open(10, file=fname, status='old')
  read(10, *) n
  allocate(ord(n), q(n))
  do i = 1, n
    read(10, *) ord(i), q(i)
  end do
  acc = 0
  do r = 1, reps
    do i = 1, n
      call mathieu_char(1, real(ord(i), dp), q(i), val, bnd, st)
      acc = acc + val
    end do
  end do
  print *, acc
end program pendula_values
