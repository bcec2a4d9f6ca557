"""Gauss6 coefficients for brouwer.f90 from mpmath: the a/b form rounded to
double (the same as kernel/integrators/pendula_rk_tables.inc) with the exact
residual of its symplecticity condition, and the mu form mu_ij = a_ij / b_j,
mu_ii = 1/2, mu_ji = 1 - mu_ij exactly (Sterbenz), after Antonana, Makazaga
and Murua (2017)."""
import mpmath as mp
from fractions import Fraction as F
mp.mp.dps = 50
s15 = mp.sqrt(15)
c = [mp.mpf(1)/2 - s15/10, mp.mpf(1)/2, mp.mpf(1)/2 + s15/10]
b = [mp.mpf(5)/18, mp.mpf(4)/9, mp.mpf(5)/18]
A = [[mp.mpf(5)/36, mp.mpf(2)/9 - s15/15, mp.mpf(5)/36 - s15/30],
     [mp.mpf(5)/36 + s15/24, mp.mpf(2)/9, mp.mpf(5)/36 - s15/24],
     [mp.mpf(5)/36 + s15/30, mp.mpf(2)/9 + s15/15, mp.mpf(5)/36]]
ad = [[float(A[i][j]) for j in range(3)] for i in range(3)]
bd = [float(x) for x in b]
# symplecticity residual of the rounded coefficients, exactly
res = max(abs(F(bd[i])*F(ad[i][j]) + F(bd[j])*F(ad[j][i]) - F(bd[i])*F(bd[j])) for i in range(3) for j in range(3))
print("! max |b_i a_ij + b_j a_ji - b_i b_j| of rounded coefficients:", float(res))
print("! sum b - 1 =", float(sum(F(x) for x in bd) - 1))
# mu form: mu_ij = a_ij / b_j, mu_ii = 1/2, mu_ij + mu_ji = 1 exactly
mu = [[None]*3 for _ in range(3)]
for i in range(3):
    mu[i][i] = 0.5
    for j in range(i+1, 3):
        x, y = A[i][j]/b[j], A[j][i]/b[i]
        # store the one in [0.5, 2] (1 - it is then exact, Sterbenz)
        if 0.5 <= x <= 2: big, small = (i, j), (j, i); v = float(x)
        else: big, small = (j, i), (i, j); v = float(y)
        mu[big[0]][big[1]] = v
        mu[small[0]][small[1]] = 1.0 - v
        assert F(1.0 - v) == 1 - F(v), (i, j)
print("! mu:", mu)
def f90(x): return repr(float(x)) + "_dp"
print("real(dp), parameter :: ga(3,3) = reshape([" + ", ".join(f90(ad[i][j]) for j in range(3) for i in range(3)) + "], [3,3])")
print("real(dp), parameter :: gb(3) = [" + ", ".join(f90(x) for x in bd) + "]")
print("real(dp), parameter :: mu(3,3) = reshape([" + ", ".join(f90(mu[i][j]) for j in range(3) for i in range(3)) + "], [3,3])")
print("real(dp), parameter :: gbb(3) = [" + ", ".join(f90(x) for x in bd) + "]")
