!> Attractors of a driven pendulum's stroboscopic map by recurrence, with early stopping.
!>
!> In the spirit of Datseris & Wagemakers' AttractorsViaRecurrences (Attractors.jl;
!> "Effortless estimation of basins of attraction", Chaos 32, 2022): the orbit of
!> each grid point is sampled once per drive period T = 2 pi / Omega and every
!> sample is placed in a cell of a grid over the section (theta in [-pi, pi), v).
!> The orbit stops as soon as it is decided:
!>
!>  1. labelled: its samples lie in the cells of one known attractor (a table of
!>     sorted cell ids and attractor indices, made by the caller) for need(j)
!>     consecutive samples, and, for an attractor given a confirmation radius
!>     crad(j) > 0 (a periodic attractor close to another, whose cells cannot
!>     tell the two apart at the cells' resolution), the last sample lies within
!>     crad(j) of one of its cycle points (cth, cv with catt = j - 1); a sample
!>     within crad(j) of such a point counts as in attractor j's cells, whether
!>     or not the cells (shared with the close neighbour) say so;
!>  2. a new periodic attractor: the samples recur after k periods (k <= kmax)
!>     to within `near` for `nconf` consecutive samples; the recurrence is then
!>     refined by Newton on the stroboscopic map (GSL's hybrid Newton with the
!>     monodromy, pendula_gsl_periodic_orbit: the core behind
!>     pendula.periodic_orbit) and kept only when Newton converges, to an orbit
!>     within `near` of the sample whose Floquet multipliers lie inside the unit
!>     circle (a confirmed stable orbit); its k points are returned;
!>  3. a new chaotic attractor: `recurrences` consecutive samples fall in
!>     recurrence cells (`rcell` wide) the orbit has visited before, and they
!>     visit more than 2 kmax distinct cells; or they visit fewer (a slowly
!>     converging cycle, or a thin chaotic set in bands) and over the next such
!>     streak the smallest recurrence distance min_k |x_n - x_{n-k}| neither
!>     halves nor falls below `near` (a converging cycle is left to rule 2);
!>     the cells of the attractor are then collected over `collect` more samples;
!>  4. undecided: none of these by max_periods drive periods (status 1).
!>
!> Before these rules, from the sample after `inherit_from` periods on, an
!> orbit may take its label from a coarser basin map (a grid of decided
!> points over theta0 and v0 given by the caller): when the sample lies in a
!> rectangle of that grid whose corners, and `margin` more grid points on each
!> side, all carry the same attractor, the point is that attractor's (the
!> stroboscopic map is the same every period, so a sample's attractor is the
!> one of the initial states around it).  Cells inherited from decided
!> neighbours, as in Attractors.jl's basin cells, but from a finished coarser
!> map only, so the answer never depends on the order the points are run in.
!>
!> Thread safety: no module variables; each point works on its own locals.
!> Results never depend on the thread count: each point is computed by one
!> thread from its inputs and the table only.
module pendula_attractors
  use pendula_kinds, only: dp, pi, two_pi, nan_dp
  use pendula_threads, only: thread_count
  use pendula_integrators, only: pendulum_model
  use pendula_sweep, only: advance, forcing_omega, np_params
  use pendula_lyapunov, only: point_model
  use pendula_gsl_iface, only: pendula_gsl_periodic_orbit
  use, intrinsic :: iso_c_binding, only: c_loc
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private
  public :: attractor_points, at_ncfg, at_nfixed, at_cell_id

  !> configuration entries (cfg): cell, rcell, near, max_periods, kmax, recurrences,
  !> collect, newton rtol, newton tol, nconf, margin, inherit_from
  integer, parameter :: at_ncfg = 12
  !> fixed outputs per point before the cycle points (see attractor_points)
  integer, parameter :: at_nfixed = 12
  !> Newton's iterations on a recurrence (it starts within `near` of a stable cycle: a few suffice)
  integer, parameter :: newton_maxit = 10
  integer, parameter :: ps_decided = 0, ps_unsettled = 1, ps_not_applicable = 2, ps_cancelled = 5
  !> outcomes
  real(dp), parameter :: oc_known = 0.0_dp, oc_periodic = 1.0_dp, oc_chaotic = 2.0_dp, oc_inherited = 3.0_dp
  !> a hash set's empty slot
  integer(int64), parameter :: empty = -huge(1_int64)

contains

  !> The id of the cell of width w holding (th, v), th in [-pi, pi): the cell
  !> (i, j) = (floor((th + pi) / w), floor(v / w)) numbered j * ni + i with ni
  !> the cells across one turn; v beyond +-1e6 cells is clamped.
  elemental integer(int64) function at_cell_id(th, v, w) result(c)
    real(dp), intent(in) :: th, v, w
    integer(int64) :: i, j, ni
    ni = int(ceiling(two_pi / w), int64)
    i = min(max(int(floor((th + pi) / w), int64), 0_int64), ni - 1)
    j = int(floor(max(min(v / w, 1.0e6_dp), -1.0e6_dp)), int64)
    c = j * ni + i
  end function at_cell_id

  !> Label or classify npts points.  params(:, i) = eps, beta, tau, amp, omega,
  !> phase, theta0, v0.  cfg: see at_ncfg.  The table of known attractors:
  !> kcell(nk) sorted cell ids (width cfg(1)), klab(nk) their attractor
  !> (0 .. natt-1), need(natt) the consecutive samples that label a point;
  !> cth(ncp), cv(ncp) the cycle points of the periodic attractors, catt(ncp)
  !> their attractor (0 .. natt-1), crad(natt) the confirmation radius (<= 0: none).
  !> The coarser basin map: bth(nbt), bv(nbv) increasing, blab(nbt, nbv) the
  !> attractor of each of its points (< 0: none; nbt or nbv < 2: no map).
  !> out(nout, i), nout >= at_nfixed + 2: (1) outcome 0 known / 1 new periodic /
  !> 2 new chaotic / 3 inherited from the basin map; (2) the known attractor's index or -1; (3) period k; (4)
  !> turns per k periods; (5) drive periods integrated; (6:9) the monodromy
  !> (row-major); (10) Newton's residual; (11) the largest |multiplier|;
  !> (12) the cycle points returned; (13:) theta, v of the cycle points (a
  !> chaotic attractor: its last sample).  cells(:, i): a new chaotic
  !> attractor's cells (ncell(i) of them, at most maxc).  pstat: 0 decided,
  !> 1 undecided by max_periods, 2 not driven, 5 cancelled, 100 + s the
  !> integrator failed.
  subroutine attractor_points(npts, params, rtol, atol, cfg, nk, kcell, klab, natt, need, ncp, cth, cv, catt, crad, &
                              nbt, nbv, bth, bv, blab, nout, out, maxc, cells, ncell, pstat, nthreads, cancel)
    integer, intent(in) :: npts, nk, natt, ncp, nbt, nbv, nout, maxc, nthreads
    real(dp), intent(in) :: params(np_params, npts), rtol, atol, cfg(at_ncfg), bth(nbt), bv(nbv)
    real(dp), intent(in) :: cth(ncp), cv(ncp), crad(natt)
    integer(int64), intent(in) :: kcell(nk)
    integer, intent(in) :: klab(nk), need(natt), catt(ncp), blab(nbt, nbv)
    real(dp), intent(out) :: out(nout, npts)
    integer(int64), intent(out) :: cells(maxc, npts)
    integer, intent(out) :: ncell(npts), pstat(npts)
    integer, intent(inout), volatile :: cancel
    integer :: i, nt
    nt = thread_count(nthreads)
    !$omp parallel do schedule(dynamic, 4) default(none) num_threads(nt) &
    !$omp   shared(npts, params, rtol, atol, cfg, nk, kcell, klab, natt, need, ncp, cth, cv, catt, crad, nbt, nbv, &
    !$omp          bth, bv, blab, nout, out, maxc, cells, ncell, pstat, cancel)
    do i = 1, npts
      if (cancel /= 0) then
        out(:, i) = nan_dp; pstat(i) = ps_cancelled; ncell(i) = 0; cells(:, i) = 0
      else
        call one_point(params(:, i), rtol, atol, cfg, kcell, klab, need, cth, cv, catt, crad, bth, bv, blab, &
                       out(:, i), cells(:, i), ncell(i), pstat(i), cancel)
      end if
    end do
    !$omp end parallel do
  end subroutine attractor_points

  subroutine one_point(p, rtol, atol, cfg, kcell, klab, need, cth, cv, catt, crad, bth, bv, blab, o, cl, ncl, st, &
                       cancel)
    real(dp), intent(in) :: p(np_params), rtol, atol, cfg(at_ncfg), bth(:), bv(:), cth(:), cv(:), crad(:)
    integer(int64), intent(in) :: kcell(:)
    integer, intent(in) :: klab(:), need(:), catt(:), blab(:, :)
    real(dp), intent(out) :: o(:)
    integer(int64), intent(out) :: cl(:)
    integer, intent(out) :: ncl, st
    integer, intent(inout), volatile :: cancel
    real(dp) :: cell, rcell, near, tp, th, v, x(2), mono(4), info(3), mu, d, dlast, dnow, dstart
    integer :: nfail, nseen, natt_fill, kmax, nrec, ncollect, nconf, maxp, n, k, j, prev, cnt, revisits, ndist, retry, h, q, lab, s
    integer :: margin, from
    integer(int64) :: c, turns, w
    real(dp), allocatable :: hth(:), hv(:)
    integer(int64), allocatable :: hturn(:), seen(:), dist(:), att(:)
    logical :: ok, isnew
    type(pendulum_model), target :: m

    o = nan_dp; cl = 0; ncl = 0; st = ps_decided
    cell = cfg(1); rcell = cfg(2); near = cfg(3)
    maxp = int(min(cfg(4), 1.0e8_dp)); kmax = int(cfg(5)); nrec = int(cfg(6)); ncollect = int(cfg(7))
    nconf = max(1, int(cfg(10)))
    margin = int(min(max(cfg(11), 0.0_dp), 1.0e6_dp)); from = int(min(max(cfg(12), 1.0_dp), 1.0e8_dp))
    ! a periodic forcing (a drive, or a vibrating pivot) sets the stroboscopic map's period
    if (.not. (forcing_omega(p) > 0.0_dp) .or. (p(4) == 0.0_dp .and. p(9) == 0.0_dp) .or. &
        .not. (abs(p(7)) <= 4503599627370496.0_dp)) then
      st = ps_not_applicable; return
    end if
    tp = two_pi / forcing_omega(p)
    h = kmax + nconf + 1                       ! history ring of the last h samples
    allocate(hth(0:h - 1), hv(0:h - 1), hturn(0:h - 1), dist(0:2 * kmax))
    nseen = 0            ! the sets `seen` and `att` are made when rule 3 first needs them
    th = p(7) - two_pi * anint(p(7) / two_pi); v = p(8); turns = 0
    prev = -1; cnt = 0; revisits = 0; ndist = 0; retry = 0; nfail = 0; dstart = -1.0_dp
    do n = 1, maxp
      if (cancel /= 0) then
        o = nan_dp; st = ps_cancelled; return
      end if
      call period_step(p, tp, n - 1, rtol, atol, th, v, st, cancel)
      if (st /= ps_decided) then
        o = nan_dp; return
      end if
      w = int(anint(th / two_pi), int64)
      th = th - two_pi * real(w, dp)
      if (th >= pi) then
        th = th - two_pi; w = w + 1
      end if
      turns = turns + w
      ! 0. the coarser basin map
      if (n >= from .and. size(bth) >= 2 .and. size(bv) >= 2) then
        lab = basin_label(bth, bv, blab, th, v, margin)
        if (lab >= 0) then
          o(1) = oc_inherited; o(2) = real(lab, dp); o(3) = 0.0_dp; o(4) = 0.0_dp; o(5) = real(n, dp)
          o(12) = 1.0_dp; o(13) = th; o(14) = v
          return
        end if
      end if
      ! 1. the cells of a known attractor
      if (size(kcell) > 0) then
        ! within the confirmation radius of a close attractor's cycle point: that attractor, whatever
        ! the cells (which cannot tell it from its neighbour); else the cells' attractor
        lab = near_cycle(th, v, cth, cv, catt, crad)
        if (lab < 0) lab = lookup(kcell, klab, at_cell_id(th, v, cell))
        if (lab >= 0 .and. lab == prev) then
          cnt = cnt + 1
        else if (lab >= 0) then
          cnt = 1
        else
          cnt = 0
        end if
        prev = lab
        if (lab >= 0) then
          if (cnt >= need(lab + 1) .and. confirmed(lab, th, v, cth, cv, catt, crad)) then
            o(1) = oc_known; o(2) = real(lab, dp); o(3) = 0.0_dp; o(4) = 0.0_dp; o(5) = real(n, dp)
            o(12) = 1.0_dp; o(13) = th; o(14) = v
            return
          end if
        end if
      end if
      ! 2. a periodic recurrence, confirmed by Newton
      q = mod(n, h)
      hth(q) = th; hv(q) = v; hturn(q) = turns
      ! (not while the orbit sits in a known attractor's cells: it is about to be labelled, unless it waits
      ! there for a confirmation that may never come: a cycle of its own inside those cells)
      if (n > retry .and. (prev < 0 .or. cnt >= nconf + kmax)) then
        do k = 1, min(kmax, n - nconf)
          ok = .true.
          dlast = huge(1.0_dp)
          do j = nconf - 1, 0, -1
            d = sdist(hth(mod(n - j, h)), hv(mod(n - j, h)), hth(mod(n - j - k, h)), hv(mod(n - j - k, h)))
            ! below near, and not growing: an orbit closing in on a cycle (a chaotic orbit's close
            ! returns rarely are both)
            if (.not. (d < near) .or. (d > dlast .and. d > 1.0e-9_dp)) then
              ok = .false.; exit
            end if
            dlast = d
          end do
          if (.not. ok) cycle
          x = [th, v]
          m = point_model(p, p(6), 0.0_dp)
          s = pendula_gsl_periodic_orbit(c_loc(m), real(k, dp) * tp, real(turns - hturn(mod(n - k, h)), dp), &
                                         cfg(8), cfg(8), cfg(9), newton_maxit, x, mono, info)
          if (s == 0) then
            x(1) = x(1) - two_pi * anint(x(1) / two_pi)
            if (x(1) >= pi) x(1) = x(1) - two_pi
            mu = max_multiplier(mono)
            if (mu < 1.0_dp .and. sdist(x(1), x(2), th, v) < near) then
              o(1) = oc_periodic; o(2) = -1.0_dp; o(3) = real(k, dp)
              o(4) = real(turns - hturn(mod(n - k, h)), dp); o(5) = real(n, dp)
              o(6:9) = mono; o(10) = info(3); o(11) = mu
              call cycle_points(p, tp, k, cfg(8), x, o, st, cancel)
              if (st /= ps_decided) then
                o = nan_dp; return
              end if
              ! the smallest period: a recurrence after k periods may be a cycle of a divisor of k
              q = smallest_period(o, k, cfg(3) * 1.0e-3_dp)
              if (q < k) then
                w = (turns - hturn(mod(n - k, h))) / (k / q)
                s = pendula_gsl_periodic_orbit(c_loc(m), real(q, dp) * tp, real(w, dp), cfg(8), cfg(8), cfg(9), &
                                               newton_maxit, x, mono, info)
                if (s /= 0) then     ! cannot happen for a converged cycle; keep the k-period answer
                  q = k
                else
                  o(3) = real(q, dp); o(4) = real(w, dp); o(6:9) = mono; o(10) = info(3)
                  o(11) = max_multiplier(mono); o(12) = real(q, dp)
                end if
              end if
              return
            end if
          end if
          ! no new attempt before the orbit has moved on; longer after each failure
          nfail = nfail + 1
          retry = n + kmax * 2 ** min(nfail, 10)
          exit
        end do
      end if
      ! 3. recurrence in cells of its own: a chaotic attractor
      if (.not. allocated(seen)) then      ! most orbits are decided before they need it
        allocate(seen(0:8191)); seen = empty
      end if
      c = at_cell_id(th, v, rcell)
      if (hs_insert(seen, nseen, c)) then
        revisits = 0; ndist = 0
      else
        revisits = revisits + 1
        if (ndist <= 2 * kmax) then
          if (.not. any(dist(0:ndist - 1) == c)) then
            dist(ndist) = c; ndist = ndist + 1
          end if
        end if
      end if
      if (revisits >= nrec) then
        ! few cells: a slowly converging cycle, or a thin chaotic set (bands): a second streak tells
        ! them apart, the cycle's recurrence distance having halved at least (or fallen below near)
        dnow = huge(1.0_dp)
        do k = 1, min(kmax, n - 1, h - 1)
          dnow = min(dnow, sdist(th, v, hth(mod(n - k, h)), hv(mod(n - k, h))))
        end do
        if (ndist <= 2 * kmax .and. dstart >= 0.0_dp) then
          if (dnow >= 0.5_dp * dstart .and. dnow >= near) ndist = 2 * kmax + 1
        end if
        if (ndist > 2 * kmax) then
          ! the attractor's cells over `collect` more samples
          allocate(att(0:2 * size(cl) - 1))
          att = empty; natt_fill = 0
          isnew = hs_insert(att, natt_fill, at_cell_id(th, v, cell))
          do j = 1, ncollect
            if (cancel /= 0) then
              o = nan_dp; st = ps_cancelled; return
            end if
            call period_step(p, tp, n + j - 1, rtol, atol, th, v, st, cancel)
            if (st /= ps_decided) then
              o = nan_dp; return
            end if
            th = th - two_pi * anint(th / two_pi)
            if (th >= pi) th = th - two_pi
            isnew = hs_insert(att, natt_fill, at_cell_id(th, v, cell))
          end do
          do j = 0, size(att) - 1
            if (att(j) /= empty .and. ncl < size(cl)) then
              ncl = ncl + 1; cl(ncl) = att(j)
            end if
          end do
          o(1) = oc_chaotic; o(2) = -1.0_dp; o(3) = 0.0_dp; o(4) = 0.0_dp; o(5) = real(n + ncollect, dp)
          o(12) = 1.0_dp; o(13) = th; o(14) = v
          return
        end if
        revisits = 0; ndist = 0; dstart = dnow
      end if
    end do
    st = ps_unsettled
    o(5) = real(maxp, dp); o(12) = 1.0_dp; o(13) = th; o(14) = v
  end subroutine one_point

  !> One drive period from the section at n periods (time origin n tp: the drive
  !> phase is p(6) + Omega n tp), by the sweeps' window step.
  subroutine period_step(p, tp, n, rtol, atol, th, v, st, cancel)
    real(dp), intent(in) :: p(np_params), tp, rtol, atol
    integer, intent(in) :: n
    real(dp), intent(inout) :: th, v
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    real(dp) :: ths(1), vs(1)
    call advance(p, tp * real(n, dp), rtol, atol, [tp], th, v, ths, vs, st, cancel)
  end subroutine period_step

  !> The k points of a confirmed cycle from its point x (tight tolerance),
  !> into o(13:), as many as fit.
  subroutine cycle_points(p, tp, k, rtol, x, o, st, cancel)
    real(dp), intent(in) :: p(np_params), tp, rtol, x(2)
    integer, intent(in) :: k
    real(dp), intent(inout) :: o(:)
    integer, intent(out) :: st
    integer, intent(inout), volatile :: cancel
    real(dp) :: th, v
    integer :: j, nfit
    nfit = min(k, (size(o) - at_nfixed) / 2)
    th = x(1); v = x(2); st = ps_decided
    o(12) = real(nfit, dp)
    do j = 1, nfit
      o(at_nfixed + 2 * j - 1) = th; o(at_nfixed + 2 * j) = v
      if (j == nfit) exit
      call period_step(p, tp, j - 1, rtol, rtol, th, v, st, cancel)
      if (st /= ps_decided) return
      th = th - two_pi * anint(th / two_pi)
      if (th >= pi) th = th - two_pi
    end do
  end subroutine cycle_points

  !> The smallest d dividing k such that the k cycle points in o(at_nfixed+1:) repeat after d (to within tol).
  pure integer function smallest_period(o, k, tol) result(d)
    real(dp), intent(in) :: o(:), tol
    integer, intent(in) :: k
    integer :: j, nfit
    logical :: same
    nfit = min(k, (size(o) - at_nfixed) / 2)
    do d = 1, k - 1
      if (mod(k, d) /= 0 .or. nfit < k) cycle
      same = .true.
      do j = 1, k - d
        if (.not. (sdist(o(at_nfixed + 2 * j - 1), o(at_nfixed + 2 * j), o(at_nfixed + 2 * (j + d) - 1), &
                         o(at_nfixed + 2 * (j + d))) < tol)) then
          same = .false.; exit
        end if
      end do
      if (same) return
    end do
    d = k
  end function smallest_period

  !> The section's distance: max(|theta1 - theta2| mod 2 pi, |v1 - v2|).
  pure real(dp) function sdist(th1, v1, th2, v2) result(d)
    real(dp), intent(in) :: th1, v1, th2, v2
    real(dp) :: a
    a = th1 - th2
    a = a - two_pi * anint(a / two_pi)
    d = max(abs(a), abs(v1 - v2))
  end function sdist

  !> Whether a sample in attractor lab's cells confirms it: no confirmation radius, or the sample
  !> within it of one of the attractor's cycle points.
  pure logical function confirmed(lab, th, v, cth, cv, catt, crad) result(ok)
    integer, intent(in) :: lab, catt(:)
    real(dp), intent(in) :: th, v, cth(:), cv(:), crad(:)
    integer :: j
    ok = .not. (crad(lab + 1) > 0.0_dp)
    if (ok) return
    do j = 1, size(catt)
      if (catt(j) == lab) then
        if (sdist(th, v, cth(j), cv(j)) < crad(lab + 1)) then
          ok = .true.; return
        end if
      end if
    end do
  end function confirmed

  !> The attractor (0-based) one of whose cycle points lies within its confirmation radius of the
  !> sample, or -1.
  pure integer function near_cycle(th, v, cth, cv, catt, crad) result(lab)
    real(dp), intent(in) :: th, v, cth(:), cv(:), crad(:)
    integer, intent(in) :: catt(:)
    integer :: j
    lab = -1
    do j = 1, size(catt)
      if (catt(j) >= 0) then
        if (crad(catt(j) + 1) > 0.0_dp .and. sdist(th, v, cth(j), cv(j)) < crad(catt(j) + 1)) then
          lab = catt(j); return
        end if
      end if
    end do
  end function near_cycle

  !> The largest modulus of the eigenvalues of a row-major 2 x 2 matrix.
  pure real(dp) function max_multiplier(mono) result(r)
    real(dp), intent(in) :: mono(4)
    real(dp) :: tr, det, disc
    tr = mono(1) + mono(4); det = mono(1) * mono(4) - mono(2) * mono(3)
    disc = 0.25_dp * tr * tr - det
    if (disc >= 0.0_dp) then
      r = max(abs(0.5_dp * tr + sqrt(disc)), abs(0.5_dp * tr - sqrt(disc)))
    else
      r = sqrt(abs(det))
    end if
    if (.not. (r == r)) r = huge(1.0_dp)
  end function max_multiplier

  !> The attractor of the basin map's rectangle holding (th, v) when its
  !> corners and `margin` more grid points on each side (as far as the grid
  !> goes) all carry it; otherwise, or outside the grid, -1.
  pure integer function basin_label(bth, bv, blab, th, v, margin) result(lab)
    real(dp), intent(in) :: bth(:), bv(:), th, v
    integer, intent(in) :: blab(:, :), margin
    integer :: i, j
    lab = -1
    if (.not. (th >= bth(1) .and. th <= bth(size(bth)) .and. v >= bv(1) .and. v <= bv(size(bv)))) return
    i = interval(bth, th); j = interval(bv, v)
    associate (blk => blab(max(1, i - margin):min(size(bth), i + 1 + margin), &
                           max(1, j - margin):min(size(bv), j + 1 + margin)))
      if (blk(1, 1) >= 0) then
        if (all(blk == blk(1, 1))) lab = blk(1, 1)
      end if
    end associate
  end function basin_label

  !> The i in 1 .. size(x) - 1 with x(i) <= y <= x(i + 1) (x increasing, y within it).
  pure integer function interval(x, y) result(i)
    real(dp), intent(in) :: x(:), y
    integer :: hi, mid
    i = 1; hi = size(x)
    do while (hi - i > 1)
      mid = (i + hi) / 2
      if (x(mid) <= y) then
        i = mid
      else
        hi = mid
      end if
    end do
  end function interval

  !> The attractor of cell c in the sorted table, or -1.
  pure integer function lookup(kcell, klab, c) result(lab)
    integer(int64), intent(in) :: kcell(:), c
    integer, intent(in) :: klab(:)
    integer :: lo, hi, mid
    lab = -1
    lo = 1; hi = size(kcell)
    do while (lo <= hi)
      mid = lo + (hi - lo) / 2
      if (kcell(mid) == c) then
        lab = klab(mid); return
      else if (kcell(mid) < c) then
        lo = mid + 1
      else
        hi = mid - 1
      end if
    end do
  end function lookup

  !> Insert c into an open-addressing hash set; true when c was not there.  A
  !> set three quarters full takes nothing more (c counts as seen).
  logical function hs_insert(set, fill, c) result(added)
    integer(int64), intent(inout) :: set(0:)
    integer, intent(inout) :: fill
    integer(int64), intent(in) :: c
    integer :: slot, nset, used
    nset = size(set)
    slot = int(modulo(c * 40503_int64 + ishft(c, -11), int(nset, int64)))
    added = .false.
    do used = 1, nset
      if (set(slot) == c) return
      if (set(slot) == empty) exit
      slot = mod(slot + 1, nset)
    end do
    if (set(slot) /= empty) return
    if (4 * fill >= 3 * nset) return
    set(slot) = c
    fill = fill + 1
    added = .true.
  end function hs_insert

end module pendula_attractors
