# power series of sn, cn, dn in u with coefficients polynomial in m (lists of Fractions)
from fractions import Fraction as F
N=16
def padd(a,b):
    n=max(len(a),len(b)); return [ (a[i] if i<len(a) else 0)+(b[i] if i<len(b) else 0) for i in range(n)]
def pmul(a,b):
    r=[F(0)]*(len(a)+len(b)-1)
    for i,x in enumerate(a):
        for j,y in enumerate(b): r[i+j]+=x*y
    return r
def pscale(a,c): return [x*c for x in a]
s=[[F(0)] for _ in range(N)]; c=[[F(0)] for _ in range(N)]; d=[[F(0)] for _ in range(N)]
c[0]=[F(1)]; d[0]=[F(1)]
def mulser(A,B,k):  # coefficient k of A*B
    r=[F(0)]
    for i in range(k+1): r=padd(r,pmul(A[i],B[k-i]))
    return r
for k in range(N-1):
    cd=[mulser(c,d,k)]
    s[k+1]=pscale(mulser(c,d,k),F(1,k+1))
    c[k+1]=pscale(mulser(s,d,k),F(-1,k+1))
    d[k+1]=pscale(pmul([F(0),F(1)],mulser(s,c,k)),F(-1,k+1))
import math
for k in range(2,15,2):
    print(k, [x*math.factorial(k) for x in c[k]], [x*math.factorial(k) for x in d[k]])

# Series of T = tn^2 = sn^2/cn^2 in t = u^2: T = sum_k b_k(m) t^k (used by the kernel).
def ser_div(A, B, n):  # power series A/B (coefficients are polynomials in m)
    # B[0] = [1]
    Q = []
    for k in range(n):
        r = A[k] if k < len(A) else [F(0)]
        for i in range(1, k + 1):
            r = padd(r, pscale(pmul(B[i], Q[k - i]), F(-1)))
        Q.append(r)
    return Q
tn = ser_div(s, c, N)
T = [mulser(tn, tn, k) for k in range(N)]
print("tn^2 coefficients of u^(2k), as polynomials in m (low to high power):")
for k in range(2, 15, 2):
    print(k // 2, [str(x) for x in T[k]])
