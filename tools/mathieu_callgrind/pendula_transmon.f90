! The transmon E_J/E_C = 50: its 10 lowest levels at 1,000 offset charges, argument 1 times: pendula's kernel alone
program pendula_transmon
  use pendula_kinds, only: dp
  use pendula_mathieu, only: mathieu_levels
  implicit none
  integer :: i, r, reps, sts(10)
  real(dp) :: vals(10), bnds(10), acc, nu
  character(len=32) :: arg
  call get_command_argument(1, arg)
  read(arg, *) reps
  acc = 0
  do r = 1, reps
    do i = 1, 1000
      nu = 2.0_dp * (-1.0_dp + 2.0_dp * real(i - 1, dp) / 999.0_dp)
      call mathieu_levels(nu, -25.0_dp, 10, vals, bnds, sts)
      acc = acc + sum(vals)
    end do
  end do
  print *, acc
end program pendula_transmon
