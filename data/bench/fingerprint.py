"""Bit fingerprints of pendula's main outputs, to compare two builds (for
example the native build against `-Csetup-args=-Dnative=false`): run it in
each, diff the two listings.  README's statement that the native build gives
the same numbers to the bit (except K(m) of an array, through glibc's libmvec)
comes from this comparison.

    .venv/bin/python data/bench/fingerprint.py > native.txt
"""
import sys, numpy as np, pendula, hashlib, warnings
warnings.simplefilter("ignore")
rng=np.random.default_rng(5)
u=rng.uniform(-1e3,1e3,200000); m=rng.uniform(-2,2,200000)
out={}
out['ellipj']=np.concatenate(pendula.ellipj(u,m))
out['ellipj_fixed']=np.concatenate(pendula.ellipj(u,0.7))
out['ellipk']=pendula.ellipk(rng.uniform(-5,1,10000))
out['ellipf']=pendula.ellipf(rng.uniform(-3,3,10000), rng.uniform(-2,1.5,10000))
t=np.linspace(-500,500,100001)
for v0 in (0.3,1.9,2-1e-12,2.5): out[f'exact{v0}']=np.concatenate(pendula.exact_motion(0.3,v0,1.3,t))
sc=pendula.Scene(v0=1.9, damping=0.1, drive_amplitude=1.2, drive_frequency=0.667, t_end=200, n_samples=2001)
for meth in ('dop853','dopri5','gauss6','yoshida8','rk4'):
    s=sc.replace(method=meth, dt=0.01)
    tr=pendula.simulate(s); out['sim'+meth]=np.concatenate([tr.theta,tr.v])
tt = np.arange(4096) * 0.1
sp = pendula.spectrum(tt, np.sin(tt) ** 3)
out["spec"] = np.asarray(sp.power if hasattr(sp, "power") else sp[1])
tr=pendula.simulate(pendula.Scene(cord='flexible', v0=3.0, damping=0.02, t_end=100, n_samples=1001)); out['cord']=np.concatenate([tr.theta,tr.v])
for k,v in out.items():
    print(k, hashlib.sha256(np.ascontiguousarray(v).tobytes()).hexdigest()[:16])
