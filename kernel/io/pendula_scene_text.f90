!> The text of scene files: tokens, values, names and messages (the lexing of
!> the namelist group &scene that pendula_scene's reader and rules share).
module pendula_scene_text
  use pendula_kinds, only: dp
  implicit none
  private
  public :: suggest, edit_distance, num_text, int_text, first_token_not, count_values, bad_value_token, &
            token_at, utf8_error_at, finite, lower, count_newlines, strip_comments, closing_slash, &
            next_assignment, find_name_eq, is_alpha, is_word

contains

  !> ' (did you mean 'x'?)' when one of the choices is close to word (at
  !> most a third of its letters edited), '' otherwise.
  function suggest(word, choices) result(s)
    character(len=*), intent(in) :: word, choices(:)
    character(len=64) :: s
    integer :: i, d, best, lw
    s = ''
    best = huge(1)
    lw = len_trim(word)
    if (lw == 0 .or. lw > 64) return
    do i = 1, size(choices)
      d = edit_distance(word(1:lw), trim(choices(i)))
      if (d < best .and. 3 * d <= max(lw, len_trim(choices(i)))) then
        best = d
        s = ' (did you mean ''' // trim(choices(i)) // '''?)'
      end if
    end do
  end function suggest

  !> Edit distance: insertions, deletions, substitutions and transpositions
  !> of neighbours ('dop835' is one edit from 'dop853').
  pure integer function edit_distance(a, b) result(d)
    character(len=*), intent(in) :: a, b
    integer :: c(0:len(a), 0:len(b)), i, j
    do i = 0, len(a)
      c(i, 0) = i
    end do
    do j = 0, len(b)
      c(0, j) = j
    end do
    do i = 1, len(a)
      do j = 1, len(b)
        c(i, j) = min(c(i - 1, j) + 1, c(i, j - 1) + 1, c(i - 1, j - 1) + merge(0, 1, a(i:i) == b(j:j)))
        if (i > 1 .and. j > 1) then
          if (a(i:i) == b(j - 1:j - 1) .and. a(i - 1:i - 1) == b(j:j)) c(i, j) = min(c(i, j), c(i - 2, j - 2) + 1)
        end if
      end do
    end do
    d = c(len(a), len(b))
  end function edit_distance

  !> A number as a short text that reads back to the same double (1.5, 2e-05, 1e+308, inf).
  function num_text(x) result(s)
    real(dp), intent(in) :: x
    character(len=40) :: s
    character(len=40) :: t, f
    integer :: e, p
    if (x /= x) then
      s = 'nan'; return
    else if (x > huge(x)) then
      s = 'inf'; return
    else if (x < -huge(x)) then
      s = '-inf'; return
    end if
    t = fewest_digits(x, '(es30.', 'e3)', 16)
    p = index(t, 'E')
    read(t(p + 1:), *) e
    if (e >= -4 .and. e < 16) then
      s = fewest_digits(x, '(f40.', ')', 20)
      if (s(1:1) == '.') s = '0' // s
      if (s(1:2) == '-.') s = '-0' // s(2:)
      if (s(len_trim(s):len_trim(s)) == '.') s = trim(s) // '0'
    else
      f = t(1:p - 1)
      if (f(len_trim(f):len_trim(f)) == '.') f = f(1:len_trim(f) - 1)
      write(s, '(a,a,i0)') trim(f), 'e', e
    end if
  end function num_text

  !> x written with the edit descriptor head // d // tail, d the fewest digits in 0..dmax that read
  !> back to x (dmax when none do), left-adjusted.
  function fewest_digits(x, head, tail, dmax) result(s)
    real(dp), intent(in) :: x
    character(len=*), intent(in) :: head, tail
    integer, intent(in) :: dmax
    character(len=40) :: s
    character(len=40) :: f
    real(dp) :: y
    integer :: d, ios
    do d = 0, dmax
      write(f, '(a,i0,a)') head, d, tail
      write(s, f) x
      read(s, *, iostat=ios) y
      if (ios == 0 .and. y == x) exit
    end do
    s = adjustl(s)
  end function fewest_digits

  function int_text(i) result(s)
    integer, intent(in) :: i
    character(len=16) :: s
    write(s, '(i0)') i
  end function int_text

  !> The position of the quote that closes the string opening at s(i:i) (a
  !> doubled quote inside stands for the quote itself); len(s) + 1 when the
  !> string is not closed.
  pure integer function quoted_end(s, i) result(e)
    character(len=*), intent(in) :: s
    integer, intent(in) :: i
    e = i + 1
    do while (e <= len(s))
      if (s(e:e) == s(i:i)) then
        if (e < len(s)) then
          if (s(e + 1:e + 1) == s(i:i)) then
            e = e + 2; cycle
          end if
        end if
        exit
      end if
      e = e + 1
    end do
  end function quoted_end

  !> The position of the first value in s that is not of the kind wanted
  !> ('r' a number, 'i' a whole number, 's' a quoted string), 0 if none.
  !> s holds values bad_value_token accepts.
  pure integer function first_token_not(s, kind) result(at)
    character(len=*), intent(in) :: s
    character(len=1), intent(in) :: kind
    integer :: i, e
    character(len=1) :: got
    character(len=*), parameter :: seps = ' ,' // achar(9) // achar(10) // achar(13)
    at = 0
    i = 1
    do while (i <= len(s))
      if (index(seps, s(i:i)) > 0) then
        i = i + 1
        cycle
      end if
      if (s(i:i) == '''' .or. s(i:i) == '"') then
        e = quoted_end(s, i)
        got = 's'
      else
        e = i
        do while (e < len(s))
          if (index(seps // '*', s(e + 1:e + 1)) > 0) exit
          e = e + 1
        end do
        if (e < len(s)) then
          if (s(e + 1:e + 1) == '*') then   ! a repeat count: the value follows
            i = e + 2
            cycle
          end if
        end if
        if (s(i:i) == '.' .and. scan(lower(s(i:e)), 'tf') > 0) then
          got = 'l'
        else if (verify(s(i:e), '+-0123456789') == 0) then
          got = 'i'
        else
          got = 'r'
        end if
      end if
      if (.not. (got == kind .or. (kind == 'r' .and. got == 'i'))) then
        at = i; return
      end if
      i = e + 1
    end do
  end function first_token_not

  !> How many values the text of an assignment holds (a repeat count r*
  !> counts r) and whether a comma stands with no value before it.
  pure subroutine count_values(s, n, nulls)
    character(len=*), intent(in) :: s
    integer, intent(out) :: n
    logical, intent(out) :: nulls
    integer :: i, e, r
    logical :: value_since_comma
    character(len=*), parameter :: blanks = ' ' // achar(9) // achar(10) // achar(13)
    n = 0
    nulls = .false.
    value_since_comma = .false.
    i = 1
    do while (i <= len(s))
      if (index(blanks, s(i:i)) > 0) then
        i = i + 1
      else if (s(i:i) == ',') then
        if (.not. value_since_comma) nulls = .true.
        value_since_comma = .false.
        i = i + 1
      else if (s(i:i) == '''' .or. s(i:i) == '"') then
        e = quoted_end(s, i)
        n = n + 1
        value_since_comma = .true.
        i = e + 1
      else
        e = i
        do while (e <= len(s))
          if (index(blanks // ',', s(e:e)) > 0) exit
          if (s(e:e) == '*') exit
          e = e + 1
        end do
        if (e <= len(s)) then
          if (s(e:e) == '*' .and. e > i .and. e - i <= 9 .and. verify(s(i:e - 1), '0123456789') == 0) then
            read(s(i:e - 1), *) r
            n = n + r - 1   ! the value that follows counts the last one
            i = e + 1
            cycle
          else if (s(e:e) == '*') then
            n = n + huge(1) / 2   ! a repeat count beyond any list
            i = e + 1
            cycle
          end if
        end if
        n = n + 1
        value_since_comma = .true.
        i = e
      end if
      n = min(n, huge(1) / 4)
    end do
  end subroutine count_values

  ! ------------------------------------------------------------ helpers

  !> The lexicon of values: numbers [+-]digits[.digits][(e|d)[+-]digits], quoted strings,
  !> logicals .true./.false./.t./.f., a repeat count r* before a value, and
  !> blanks or commas between them.  0 when s is made of these, otherwise the
  !> position where the first bad token starts.
  pure integer function bad_value_token(s) result(at)
    character(len=*), intent(in) :: s
    integer :: i, n, e
    character(len=1) :: q
    at = 0
    i = 1
    n = len(s)
    do while (i <= n)
      select case (s(i:i))
      case (' ', ',', achar(9), achar(10), achar(13))
        i = i + 1
      case ('''', '"', '.')
        ! a quoted string, or after a dot a logical or a number; e = 0: none that ends
        if (s(i:i) == '.') then
          e = logical_end(i)
          if (e == 0) e = number_end(i)
        else
          e = quoted_end(s, i)
          if (e > n) e = 0
        end if
        if (e == 0) then
          at = i; return
        end if
        i = e + 1
        if (.not. separated(i)) then
          at = i; return
        end if
      case default
        e = number_end(i)
        if (e == 0) then
          at = i; return
        end if
        q = 'n'
        if (verify(s(i:e), '0123456789') == 0) q = 'r'   ! digits only: may be a repeat count
        i = e + 1
        if (i <= n) then
          if (s(i:i) == '*' .and. q == 'r') then
            i = i + 1   ! a repeat count: the value follows at once
            if (i > n) then
              at = i - 1; return
            end if
            if (index(' ,' // achar(9) // achar(10) // achar(13), s(i:i)) > 0) then
              at = i; return   ! a repeat count needs its value at once
            end if
            cycle
          end if
        end if
        if (.not. separated(i)) then
          at = i; return
        end if
      end select
    end do
  contains
    pure logical function separated(k)
      integer, intent(in) :: k
      separated = .true.
      if (k <= n) separated = index(' ,' // achar(9) // achar(10) // achar(13), s(k:k)) > 0
    end function separated
    pure integer function logical_end(k)
      integer, intent(in) :: k
      integer :: m
      character(len=7), parameter :: words(4) = [character(len=7) :: '.true.', '.false.', '.t.', '.f.']
      logical_end = 0
      do m = 1, 4
        if (k + len_trim(words(m)) - 1 <= n) then
          if (lower(s(k:k + len_trim(words(m)) - 1)) == trim(words(m))) then
            logical_end = k + len_trim(words(m)) - 1; return
          end if
        end if
      end do
    end function logical_end
    !> end of the number starting at k (0: none)
    pure integer function number_end(k)
      integer, intent(in) :: k
      integer :: m, d1, d2
      number_end = 0
      m = k
      if (index('+-', s(m:m)) > 0) m = m + 1
      d1 = digits(m)
      m = m + d1
      d2 = 0
      if (m <= n) then
        if (s(m:m) == '.') then
          m = m + 1
          d2 = digits(m)
          m = m + d2
        end if
      end if
      if (d1 + d2 == 0) return
      if (m <= n) then
        if (index('eEdD', s(m:m)) > 0) then
          m = m + 1
          if (m <= n) then
            if (index('+-', s(m:m)) > 0) m = m + 1
          end if
          if (digits(m) == 0) return
          m = m + digits(m)
        end if
      end if
      number_end = m - 1
    end function number_end
    pure integer function digits(k)
      integer, intent(in) :: k
      digits = 0
      do while (k + digits <= n)
        if (index('0123456789', s(k + digits:k + digits)) == 0) exit
        digits = digits + 1
      end do
    end function digits
  end function bad_value_token

  !> The token of s starting at k (up to a blank or a comma), for messages.
  pure function token_at(s, k) result(t)
    character(len=*), intent(in) :: s
    integer, intent(in) :: k
    character(len=:), allocatable :: t
    integer :: e
    e = scan(s(k:), ' ,' // achar(10))
    if (e == 0) then
      t = s(k:min(len(s), k + 40))
    else
      t = s(k:k + e - 2)
    end if
  end function token_at

  !> 0 when s is valid UTF-8, otherwise the position of the first bad byte.
  pure integer function utf8_error_at(s)
    character(len=*), intent(in) :: s
    integer :: i, b, n, j
    utf8_error_at = 0
    i = 1
    do while (i <= len(s))
      b = iachar(s(i:i))
      if (b < 128) then
        n = 0
      else if (b >= 194 .and. b <= 223) then
        n = 1
      else if (b >= 224 .and. b <= 239) then
        n = 2
      else if (b >= 240 .and. b <= 244) then
        n = 3
      else
        utf8_error_at = i; return
      end if
      if (i + n > len(s)) then
        utf8_error_at = i; return
      end if
      do j = i + 1, i + n
        if (iand(iachar(s(j:j)), 192) /= 128) then
          utf8_error_at = j; return
        end if
      end do
      i = i + n + 1
    end do
  end function utf8_error_at

  pure elemental logical function finite(x)
    real(dp), intent(in) :: x
    finite = abs(x) <= huge(x)
  end function finite

  pure function lower(s) result(r)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: r
    integer :: i
    r = s
    do i = 1, len(s)
      if (r(i:i) >= 'A' .and. r(i:i) <= 'Z') r(i:i) = achar(iachar(r(i:i)) + 32)
    end do
  end function lower

  pure integer function count_newlines(s)
    character(len=*), intent(in) :: s
    integer :: i
    count_newlines = 0
    do i = 1, len(s)
      if (s(i:i) == new_line('a')) count_newlines = count_newlines + 1
    end do
  end function count_newlines

  !> Blank out '!' comments (outside quotes), keeping the newlines.
  pure subroutine strip_comments(s)
    character(len=*), intent(inout) :: s
    integer :: i
    character(len=1) :: q
    logical :: incomment
    q = ' '
    incomment = .false.
    do i = 1, len(s)
      if (s(i:i) == new_line('a')) then
        incomment = .false.
        cycle
      end if
      if (incomment) then
        s(i:i) = ' '
      else if (q /= ' ') then
        if (s(i:i) == q) q = ' '
      else if (s(i:i) == '''' .or. s(i:i) == '"') then
        q = s(i:i)
      else if (s(i:i) == '!') then
        incomment = .true.
        s(i:i) = ' '
      end if
    end do
  end subroutine strip_comments

  !> Position of the '/' that closes the group (outside quotes), or 0.
  pure integer function closing_slash(s, from)
    character(len=*), intent(in) :: s
    integer, intent(in) :: from
    integer :: i
    character(len=1) :: q
    q = ' '
    closing_slash = 0
    do i = from, len(s)
      if (q /= ' ') then
        if (s(i:i) == q) q = ' '
      else if (s(i:i) == '''' .or. s(i:i) == '"') then
        q = s(i:i)
      else if (s(i:i) == '/') then
        closing_slash = i
        return
      end if
    end do
  end function closing_slash

  !> From position k, find the next "name =" (outside quotes) and the end of
  !> its value (the next "name =" or the closing slash at stop).  On return
  !> start is where the name begins (0 if none) and k where the next begins.
  pure subroutine next_assignment(s, k, stop, start, fname)
    character(len=*), intent(in) :: s
    integer, intent(inout) :: k
    integer, intent(in) :: stop
    integer, intent(out) :: start
    character(len=*), intent(out) :: fname
    integer :: i, e
    start = 0
    fname = ''
    call find_name_eq(s, k, stop, i, e)
    if (i == 0) then
      k = stop
      return
    end if
    start = i
    fname = lower(s(i:e))
    call find_name_eq(s, e + 1, stop, i, e)
    if (i == 0) then
      k = stop
    else
      k = i
    end if
  end subroutine next_assignment

  !> First identifier followed by '=' at or after position from (outside quotes).
  pure subroutine find_name_eq(s, from, stop, first, last)
    character(len=*), intent(in) :: s
    integer, intent(in) :: from, stop
    integer, intent(out) :: first, last
    integer :: i, j
    character(len=1) :: q
    q = ' '
    first = 0
    last = 0
    i = from
    do while (i < stop)
      if (q /= ' ') then
        if (s(i:i) == q) q = ' '
        i = i + 1
        cycle
      end if
      if (s(i:i) == '''' .or. s(i:i) == '"') then
        q = s(i:i)
        i = i + 1
        cycle
      end if
      if (is_alpha(s(i:i)) .and. (i == 1 .or. .not. is_word(s(max(i - 1, 1):max(i - 1, 1))))) then
        j = i
        do while (j + 1 < stop .and. is_word(s(j + 1:j + 1)))
          j = j + 1
        end do
        last = j
        j = j + 1
        do while (j < stop .and. (s(j:j) == ' ' .or. s(j:j) == new_line('a') .or. s(j:j) == achar(9) &
                                  .or. s(j:j) == achar(13)))
          j = j + 1
        end do
        if (j < stop .and. s(j:j) == '=') then
          first = i
          return
        end if
        i = last + 1
        cycle
      end if
      i = i + 1
    end do
  end subroutine find_name_eq

  pure logical function is_alpha(c)
    character(len=1), intent(in) :: c
    is_alpha = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z') .or. c == '_'
  end function is_alpha

  pure logical function is_word(c)
    character(len=1), intent(in) :: c
    is_word = is_alpha(c) .or. (c >= '0' .and. c <= '9')
  end function is_word

end module pendula_scene_text
