!> pendula-ellip: Jacobi elliptic functions for rows of "u m" or "u m mc".
!>
!> Usage: pendula-ellip [FILE]   (standard input when FILE is absent or "-")
!> Each row gives u and m, and optionally mc = 1 - m (then mc is the
!> parameter, and m must agree with 1 - mc to rounding).  '#' starts a comment.
!> Output: one row "sn cn dn am" per input row, 17 significant digits.
!> A malformed row is reported with its line number on standard error, the
!> exit status is 2, and nothing is written to standard output.
program pendula_ellip
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit, input_unit
  use pendula_kinds, only: dp
  use pendula_elliptic, only: jacobi_eval_varm
  use pendula_text, only: strip_comment, split_tokens, parse_real, max_tokens, command_arg
  implicit none
  character(len=4096) :: line
  character(len=:), allocatable :: path
  character(len=512) :: argmsg
  character(len=:), allocatable :: body
  real(dp), allocatable :: u(:), m(:), mc(:), tmp(:,:), sn(:), cn(:), dn(:), am(:)
  real(dp) :: x(3)
  integer :: unit, ios, lineno, nrows, ntok, i, first(max_tokens), last(max_tokens), nnan
  logical :: ok

  unit = input_unit
  if (command_argument_count() > 1) call fail(0, 'usage: pendula-ellip [FILE]')
  if (command_argument_count() == 1) then
    call command_arg(1, path, argmsg)
    if (path == '-h' .or. path == '--help') then
      write(output_unit, '(a)') 'usage: pendula-ellip [FILE]   rows "u m" or "u m mc" -> "sn cn dn am"'
      stop
    end if
    if (len_trim(argmsg) > 0) call fail(0, trim(argmsg))
    if (path /= '-') then
      open(newunit=unit, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) call fail(0, 'cannot open input file "' // path // '"')
    end if
  end if

  allocate(u(1024), m(1024), mc(1024))
  nrows = 0
  lineno = 0
  do
    read(unit, '(a)', iostat=ios) line
    if (ios /= 0) exit
    lineno = lineno + 1
    if (len_trim(line) >= len(line) - 1) call fail(lineno, 'line too long')
    body = strip_comment(line)
    call split_tokens(body, ntok, first, last)
    if (ntok == 0) cycle
    if (ntok < 2 .or. ntok > 3) call fail(lineno, 'expected 2 or 3 numbers (u m [mc])')
    do i = 1, ntok
      call parse_real(body(first(i):last(i)), x(i), ok)
      if (.not. ok) call fail(lineno, 'not a number: "' // body(first(i):last(i)) // '"')
    end do
    if (nrows == size(u)) then
      allocate(tmp(3, 2 * nrows))
      tmp(1, 1:nrows) = u; tmp(2, 1:nrows) = m; tmp(3, 1:nrows) = mc
      u = tmp(1, :); m = tmp(2, :); mc = tmp(3, :)
      deallocate(tmp)
    end if
    nrows = nrows + 1
    u(nrows) = x(1)
    if (ntok == 3) then
      if (abs(x(2) - (1.0_dp - x(3))) > 4.0_dp * epsilon(1.0_dp) * max(1.0_dp, abs(x(2)))) &
        call fail(lineno, 'm and mc disagree: mc must be 1 - m')
      mc(nrows) = x(3)
      m(nrows) = 1.0_dp - x(3)
    else
      m(nrows) = x(2)
      mc(nrows) = 1.0_dp - x(2)
    end if
  end do

  ! all rows at once, through the kernel's vectorized path
  allocate(sn(nrows), cn(nrows), dn(nrows), am(nrows))
  call jacobi_eval_varm(u(1:nrows), m(1:nrows), mc(1:nrows), sn, cn, dn, am)
  nnan = count(sn /= sn .and. u(1:nrows) == u(1:nrows) .and. m(1:nrows) == m(1:nrows))
  write(output_unit, '(a)') '# sn cn dn am'
  do i = 1, nrows
    write(output_unit, '(4(es25.17e3,1x))') sn(i), cn(i), dn(i), am(i)
  end do
  if (nnan > 0) write(error_unit, '(a,i0,a)') 'pendula-ellip: warning: ', nnan, &
    ' row(s) outside the domain (or u beyond 2**48 half periods) gave NaN'

contains

  subroutine fail(ln, msg)
    integer, intent(in) :: ln
    character(len=*), intent(in) :: msg
    if (ln > 0) then
      write(error_unit, '(a,i0,a)') 'pendula-ellip: line ', ln, ': ' // msg
    else
      write(error_unit, '(a)') 'pendula-ellip: ' // msg
    end if
    stop 2, quiet=.true.
  end subroutine fail

end program pendula_ellip
