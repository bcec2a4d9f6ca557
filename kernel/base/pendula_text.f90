!> Small text utilities for the batch executables: tokens and number parsing.
module pendula_text
  use pendula_kinds, only: dp
  implicit none
  private
  public :: strip_comment, split_tokens, parse_real, max_tokens, command_arg

  integer, parameter :: max_tokens = 16

contains

  !> The part of a line before the first '#'.
  pure function strip_comment(line) result(s)
    character(len=*), intent(in) :: line
    character(len=:), allocatable :: s
    integer :: k
    k = index(line, '#')
    if (k > 0) then
      s = line(1:k-1)
    else
      s = line
    end if
  end function strip_comment

  !> Whitespace-separated tokens: their start and end positions, and how many.
  pure subroutine split_tokens(line, ntok, first, last)
    character(len=*), intent(in) :: line
    integer, intent(out) :: ntok
    integer, intent(out) :: first(max_tokens), last(max_tokens)
    integer :: i
    logical :: inside
    ntok = 0
    inside = .false.
    first = 0; last = 0
    do i = 1, len(line)
      if (line(i:i) == ' ' .or. line(i:i) == achar(9) .or. line(i:i) == achar(13)) then
        if (inside) then
          if (ntok <= max_tokens) last(ntok) = i - 1
          inside = .false.
        end if
      else if (.not. inside) then
        inside = .true.
        ntok = ntok + 1
        if (ntok <= max_tokens) first(ntok) = i
      end if
    end do
    if (inside .and. ntok <= max_tokens) last(ntok) = len(line)
  end subroutine split_tokens

  !> A real number from one token: digits, sign, point and exponent only, or
  !> inf / nan (any case).  ok is false for anything else.
  subroutine parse_real(tok, x, ok)
    character(len=*), intent(in) :: tok
    real(dp), intent(out) :: x
    logical, intent(out) :: ok
    integer :: i, ios, ndig
    character(len=1) :: ch
    character(len=len(tok)) :: low
    x = 0.0_dp
    ok = .false.
    if (len_trim(tok) == 0) return
    low = tok
    do i = 1, len(low)
      if (low(i:i) >= 'A' .and. low(i:i) <= 'Z') low(i:i) = achar(iachar(low(i:i)) + 32)
    end do
    if (any(trim(adjustl(low)) == [character(len=9) :: 'inf', '+inf', '-inf', 'nan', &
                                   'infinity', '+infinity', '-infinity'])) then
      read(tok, *, iostat=ios) x
      ok = ios == 0
      return
    end if
    ndig = 0
    do i = 1, len_trim(tok)
      ch = low(i:i)
      if (ch >= '0' .and. ch <= '9') then
        ndig = ndig + 1
      else if (index('+-.ed', ch) == 0) then
        return
      end if
    end do
    if (ndig == 0) return
    read(tok, *, iostat=ios) x
    ok = ios == 0
  end subroutine parse_real

  !> Command-line argument i, exactly as given (its length from the system), and
  !> msg /= '' when it cannot be used as a file name: Fortran drops the trailing
  !> blanks of a file name on open, so "out.csv " would name out.csv, another
  !> file than the one given (the batch programs refuse it, naming it).
  subroutine command_arg(i, arg, msg)
    integer, intent(in) :: i
    character(len=:), allocatable, intent(out) :: arg
    character(len=*), intent(out) :: msg
    integer :: n, st
    msg = ''
    call get_command_argument(i, length=n, status=st)
    allocate(character(len=max(n, 0)) :: arg)
    if (n > 0) call get_command_argument(i, arg, status=st)
    if (n > 0) then
      if (arg(n:n) == ' ') msg = 'argument "' // arg // '" ends in a blank: a file name must not (the ' // &
        'blank would be dropped and another file named)'
    end if
  end subroutine command_arg

end module pendula_text
