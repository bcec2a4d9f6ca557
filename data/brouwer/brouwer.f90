! Gauss6 round-off experiment (scratch, not part of pendula): which ingredient
! makes the energy drift?  form 0 = pendula's (a, b, final f evaluation);
! form 1 = mu form (Antonana, Makazaga, Murua 2017): L_j = h b_j f(Y_j),
! Y_i = y + sum mu_ij L_j with mu_ij + mu_ji = 1 exactly, y1 = y + sum L_j.
! stop 0 = stop when increments stop decreasing; 1 = also require d == 0 or 2 rises.
! sine 0 = libm sin; 1 = sin in x87 extended, rounded (near correctly rounded).
program brouwer
  implicit none
  integer, parameter :: dp = kind(1.0d0), ep = 10
  include 'coef.inc'   ! written by gen.py (coefficients rounded to double, and the mu form)
  integer :: form, stopr, sinr, k, nrec, rec
  integer(8) :: nsteps, n, nextrec
  integer :: ndiv
  real(dp) :: h, th, the, v, ve, P
  real(ep) :: E0, E
  character(len=32) :: arg
  call get_command_argument(1, arg); read(arg, *) form
  call get_command_argument(2, arg); read(arg, *) stopr
  call get_command_argument(3, arg); read(arg, *) sinr
  call get_command_argument(4, arg); read(arg, *) nsteps
  P = 6.743001419250385_dp
  call get_command_argument(5, arg); read(arg, *) ndiv
  h = P / ndiv
  th = 0; the = 0; v = 1; ve = 0
  E0 = 0.5_ep
  nrec = 400; rec = 0
  nextrec = 200
  do n = 1, nsteps
    if (form == 0) then
      call step_ab()
    else
      call step_mu()
    end if
    if (n >= nextrec) then
      E = 2 * sin(0.5_ep * (real(th, ep) + the))**2 + 0.5_ep * (real(v, ep) + ve)**2
      write(*, '(i0, 1x, es24.16)') n, real(E - E0, dp)
      rec = rec + 1
      nextrec = max(nextrec + 1, int(200.0_dp * (real(nsteps, dp) / 200) ** (real(rec, dp) / nrec), 8))
    end if
  end do
contains
  real(dp) function sn(x)
    real(dp), intent(in) :: x
    if (sinr == 0) then
      sn = sin(x)
    else
      sn = real(sin(real(x, ep)), dp)
    end if
  end function
  subroutine kahan(y, e, d)
    real(dp), intent(inout) :: y, e
    real(dp), intent(in) :: d
    real(dp) :: dd, s
    dd = d + e; s = y + dd; e = dd - (s - y); y = s
  end subroutine
  logical function done(it, d, dold)
    integer, intent(in) :: it
    real(dp), intent(in) :: d, dold
    done = d == 0 .or. (it > 2 .and. d >= dold)
  end function
  !> the fixed-point iteration's stopping rule of both forms (stopr, above)
  logical function stop_now(it, d, dold, rises)
    integer, intent(in) :: it
    real(dp), intent(in) :: d, dold
    integer, intent(inout) :: rises
    if (stopr == 0) then
      stop_now = done(it, d, dold)
    else
      if (it > 2 .and. d >= dold) rises = rises + 1
      stop_now = d == 0 .or. rises >= 2
    end if
  end function
  subroutine step_ab()
    real(dp) :: z(3, 2), f(3, 2), zn(3, 2), d, dold, st, sv
    integer :: it, i, j, rises
    z = 0; dold = huge(1.0_dp); rises = 0
    do it = 1, 60
      do i = 1, 3
        f(i, 1) = v + z(i, 2); f(i, 2) = -sn(th + z(i, 1))
      end do
      do i = 1, 3
        st = 0; sv = 0
        do j = 1, 3
          st = st + ga(i, j) * f(j, 1); sv = sv + ga(i, j) * f(j, 2)
        end do
        zn(i, 1) = h * st; zn(i, 2) = h * sv
      end do
      d = maxval(abs(zn - z)); z = zn
      if (stop_now(it, d, dold, rises)) exit
      dold = d
    end do
    do i = 1, 3
      f(i, 1) = v + z(i, 2); f(i, 2) = -sn(th + z(i, 1))
    end do
    st = 0; sv = 0
    do i = 1, 3
      st = st + gb(i) * f(i, 1); sv = sv + gb(i) * f(i, 2)
    end do
    call kahan(th, the, h * st); call kahan(v, ve, h * sv)
  end subroutine
  subroutine step_mu()
    real(dp) :: L(3, 2), Ln(3, 2), hb(3), d, dold, yt, yv, st, sv
    integer :: it, i, j, rises
    hb = h * gbb
    L = 0; dold = huge(1.0_dp); rises = 0
    do it = 1, 60
      do i = 1, 3
        yt = 0; yv = 0
        do j = 1, 3
          yt = yt + mu(i, j) * L(j, 1); yv = yv + mu(i, j) * L(j, 2)
        end do
        Ln(i, 1) = hb(i) * (v + yv)
        Ln(i, 2) = -hb(i) * sn(th + yt)
      end do
      d = maxval(abs(Ln - L)); L = Ln
      if (stop_now(it, d, dold, rises)) exit
      dold = d
    end do
    st = 0; sv = 0
    do i = 1, 3
      st = st + L(i, 1); sv = sv + L(i, 2)
    end do
    call kahan(th, the, st); call kahan(v, ve, sv)
  end subroutine
end program
