!> Scene files of the systems built by their own class: a file holds one
!> namelist group named for its system (&double, &foucault).  This module
!> finds the group's name, and names the fields of the line that does not
!> read when the namelist reader's own message names none; each system's
!> scene module (kernel/dispatch/pendula_*_scene.f90) keeps its fields and
!> their checks.
module pendula_group_file
  use, intrinsic :: iso_c_binding, only: c_null_char, c_long_long
  use pendula_scene, only: c_read_kind
  use pendula_scene_type, only: max_scene_bytes
  implicit none
  private
  public :: scene_group, read_group_file, name_bad_line, line_reader, unit_reader

  abstract interface
    !> Read '&GROUP ' // text // ' /' into the system's namelist group: ios 0 or the error, iom its message.
    subroutine line_reader(text, ios, iom)
      character(len=*), intent(in) :: text
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: iom
    end subroutine line_reader
    !> Read the system's namelist group from the unit u: ios 0 or the error, iom its message.
    subroutine unit_reader(u, ios, iom)
      integer, intent(in) :: u
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: iom
    end subroutine unit_reader
  end interface

contains

  !> The name of the first namelist group of the file (lower case; blank when none, or when the file is
  !> not a regular file of at most 16 MiB: a FIFO or a device is never read; read_scene says why).
  function scene_group(path) result(name)
    character(len=*), intent(in) :: path
    character(len=32) :: name
    character(len=512) :: ln
    integer :: u, ios, b, k
    integer(c_long_long) :: bytes
    name = ''
    if (c_read_kind(path // c_null_char, bytes) /= 0) return
    if (bytes > max_scene_bytes) return
    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read(u, '(a)', iostat=ios) ln
      if (ios /= 0) exit
      ln = adjustl(ln)
      if (ln(1:1) /= '&') cycle
      b = scan(ln(2:), ' ,/')
      if (b == 0) b = len_trim(ln)
      name = ln(2:b)
      do k = 1, len_trim(name)
        if (name(k:k) >= 'A' .and. name(k:k) <= 'Z') name(k:k) = achar(iachar(name(k:k)) + 32)
      end do
      exit
    end do
    close(u)
  end function scene_group

  !> Read the group &group of the file through read_unit (the system's namelist read): msg blank, or
  !> why it does not read, the line and its fields named (name_bad_line, each line through read_line).
  subroutine read_group_file(path, group, read_unit, read_line, msg)
    character(len=*), intent(in) :: path, group
    procedure(unit_reader) :: read_unit
    procedure(line_reader) :: read_line
    character(len=*), intent(out) :: msg
    character(len=256) :: iom
    integer :: u, ios
    msg = ''
    open(newunit=u, file=path, status='old', action='read', iostat=ios, iomsg=iom)
    if (ios /= 0) then
      msg = 'cannot read "' // path // '": ' // trim(iom); return
    end if
    iom = ''
    call read_unit(u, ios, iom)
    close(u)
    if (ios /= 0) then
      msg = path // ': &' // group // ': ' // trim(iom)
      call name_bad_line(path, group, read_line, msg)
    end if
  end subroutine read_group_file

  !> The first line of the group &group in the file that does not read alone (read_line), as
  !> "PATH: &GROUP, line N: field 'NAME': cannot read its value (...)" in msg; msg unchanged when
  !> every line reads.
  subroutine name_bad_line(path, group, read_line, msg)
    character(len=*), intent(in) :: path, group
    procedure(line_reader) :: read_line
    character(len=*), intent(inout) :: msg
    character(len=1024) :: ln, names, num
    character(len=256) :: iom
    integer :: v, st, nline, k, a
    logical :: inside
    open(newunit=v, file=path, status='old', action='read', iostat=st)
    if (st /= 0) return
    inside = .false.
    nline = 0
    do
      read(v, '(a)', iostat=st) ln
      if (st /= 0) exit
      nline = nline + 1
      k = index(ln, '!')
      if (k > 0) ln(k:) = ''
      ln = adjustl(ln)
      if (.not. inside) then
        if (ln(1:1) /= '&') cycle
        inside = .true.
        ln = adjustl(ln(len_trim(group) + 2:))
      end if
      if (ln(1:1) == '/') exit
      k = index(ln, '/', back=.true.)
      if (k > 0) ln(k:) = ''
      if (len_trim(ln) == 0) cycle
      iom = ''
      call read_line(trim(ln), st, iom)
      if (st == 0) cycle
      ! the names before each '=' on the line
      names = ''
      a = 1
      do
        k = index(ln(a:), '=')
        if (k == 0) exit
        k = a + k - 1
        if (len_trim(names) > 0) names = trim(names) // ','
        names = trim(names) // ' ''' // trim(last_word(ln(1:k - 1))) // ''''
        a = k + 1
      end do
      write(num, '(i0)') nline
      msg = path // ': &' // group // ', line ' // trim(num) // ': ' // &
            trim(merge('fields', 'field ', index(names, ',') > 0)) // trim(names) // ': cannot read its value (' // &
            trim(iom) // ')'
      exit
    end do
    close(v)
  end subroutine name_bad_line

  !> The last blank- or comma-separated word of s.
  pure function last_word(s) result(w)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: w
    integer :: b, a
    b = len_trim(s)
    a = scan(s(1:b), ' ,', back=.true.)
    w = s(a + 1:b)
  end function last_word

end module pendula_group_file
