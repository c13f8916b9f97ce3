"""Lattice sums of the 2D SPH kernels for the shallow-water depth (docs/kernels.md, "Shallow water").

For each kernel and kappa (h = kappa sqrt(A)), on a square and a hexagonal lattice of area A per
particle: the depth the self-consistent summation d = sum_j V_j W(r_j, kappa sqrt(V/d)) gives at
a particle, relative to the water depth; the range of the plain sum at points between the
particles (the gridded depth); and the neighbours within the support.

    /usr/bin/python3 tools/kernel_lattice_sums.py
"""
import numpy as np
pi=np.pi
def spiky(q): return 5/(16*pi)*np.clip(2-q,0,None)**3
def m4(q):
    s=10/(7*pi); return s*np.where(q<1,1-1.5*q**2+0.75*q**3,np.where(q<2,0.25*(2-q)**3,0))
def wc2(q): t=np.clip(1-q/2,0,None); return 7/(4*pi)*t**4*(2*q+1)
def wc4(q): t=np.clip(1-q/2,0,None); return 9/(4*pi)*t**6*(35/12*q**2+3*q+1)
def quintic(q):  # support 3
    s=7/(478*pi)
    return s*(np.clip(3-q,0,None)**5-6*np.clip(2-q,0,None)**5+15*np.clip(1-q,0,None)**5)
kern={'spiky':(spiky,2),'m4':(m4,2),'wc2':(wc2,2),'wc4':(wc4,2),'quintic':(quintic,3)}
def lattice(kind,n=14):
    i,j=np.meshgrid(np.arange(-n,n+1),np.arange(-n,n+1))
    if kind=='square': return i.ravel().astype(float), j.ravel().astype(float), 1.0
    a=1.0; x=(i+0.5*(j%2))*a; y=j*a*np.sqrt(3)/2
    return x.ravel(),y.ravel(),np.sqrt(3)/2
def S(f,x,y,A,H,px=0,py=0):
    r=np.hypot(x-px,y-py)/H; return A*f(r).sum()/H**2
for kind in ['square','hex']:
    x,y,A=lattice(kind); dx=np.sqrt(A)
    print(kind)
    for name,(f,sup) in kern.items():
        for kappa in [1.0,1.1,1.2,1.3,1.4,1.5,1.6,1.8]:
            # fixed point s = S(kappa dx / sqrt(s))
            s=1.0
            for it in range(100): s=S(f,x,y,A,kappa*dx/np.sqrt(s))
            H=kappa*dx
            offs=[S(f,x,y,A,H,px,py) for px in np.linspace(0,0.5,6) for py in np.linspace(0,0.5,6)]
            nb=(np.hypot(x,y)<sup*kappa*dx/np.sqrt(s)).sum()-1
            print(f"  {name:8s} k={kappa:.1f} particle {100*(s-1):+7.3f}%  grid {100*(min(offs)-1):+7.3f}..{100*(max(offs)-1):+7.3f}%  nbrs {nb}")
