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
# the systems built by their own class, on the n-dimensional driver (every method of each)
net=pendula.Network(6, topology='chain', strength=0.4, damping=0.1, bias=0.3, drive_amplitude=0.2, drive_frequency=0.9)
tn=np.arange(0,40.0,0.5); phi0=np.linspace(0.1,0.6,6)
for meth in ('dop853','gauss4','gauss6'):
    out['network_'+meth]=net.simulate(tn, phi0=phi0, method=meth, dt=0.01).phi.values
out['network_baoab']=net.simulate(tn, phi0=phi0, dt=0.01, temperature=0.05, seed=3, paths=2).phi.values
dpd=pendula.DoublePendulum(); dpk=pendula.DoublePendulum(damping=0.05)
for meth in ('dop853','gauss4','gauss6'):
    out['double_'+meth]=dpd.simulate(np.linspace(0,20,41), theta1=2.0, theta2=1.0, method=meth, dt=0.01).theta1.values
out['double_damped']=dpk.simulate(np.linspace(0,20,41), theta1=2.0, theta2=1.0).theta1.values
th=np.linspace(-3,3,9); out['double_flip']=dpd.flip_map(th, th, t_max=20.0).time
out['double_lyapunov']=dpd.lyapunov(2.0, 1.0, t=50.0).exponents
out['double_lyapunov_dop853']=dpk.lyapunov(2.0, 1.0, t=50.0).exponents
out['double_poincare']=dpd.poincare(1.0, [0.0,0.3], [0.0,0.1], t_max=100.0).theta2.values
fp=pendula.FoucaultPendulum(latitude=45.0, length=10.0, damping=0.01, anisotropy=(1e-4, 0.0))
out['foucault']=fp.simulate(np.linspace(0,60,31), 0.1).x.values
for k,v in out.items():
    print(k, hashlib.sha256(np.ascontiguousarray(v).tobytes()).hexdigest()[:16])
