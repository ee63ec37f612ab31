#!/usr/bin/env python3
"""A ray-cast oracle for the relation to infinity of `cairn blocking`, an
independent check of its graphs on a scene file (`cairn convert` writes one
from a STEP model): part i is blocked by j along the direction D when a ray
from a sample point of i (vertices, triangle centroids and edge midpoints)
along D passes through j's interior, or one from a sample of j along -D
through i's, where "through" is a stretch between two crossings longer than
2 EPS whose middle, and the points EPS beside it across the ray, lie inside
(by the parity of a skew ray). Prints each part with the parts that block
it. Brute force (numpy): minutes on the 61-part toy truck.
Usage: bench/blocking_oracle.py SCENE.json D [EPS]  (D as X,Y,Z; EPS in the
scene's length unit, default 1e-4)."""
import json, sys, numpy as np
d = np.array([float(x) for x in sys.argv[2].split(',')]); d /= np.linalg.norm(d)
scene = json.load(open(sys.argv[1]))
eps = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-4
parts = []
for p in scene['parts']:
    V = np.array(p['polyhedron']['vertices']); tris = []
    for f in p['polyhedron']['faces']:
        for k in range(1, len(f) - 1): tris.append((f[0], f[k], f[k + 1]))
    T = V[np.array(tris)]
    samples = [V, T.mean(axis=1)] + [(T[:, a] + T[:, b]) / 2 for a, b in ((0, 1), (1, 2), (2, 0))]
    parts.append((p['name'], V, T, np.vstack(samples)))
def hits(P, dirn, T):
    # Möller–Trumbore, all points P against all triangles T: times t > 0 per point
    e1 = T[:, 1] - T[:, 0]; e2 = T[:, 2] - T[:, 0]
    h = np.cross(dirn, e2); a = np.einsum('ij,ij->i', e1, h)
    ok = np.abs(a) > 1e-12
    e1, e2, h, a, T0 = e1[ok], e2[ok], h[ok], a[ok], T[ok, 0]
    s = P[:, None, :] - T0[None]
    u = np.einsum('pij,ij->pi', s, h) / a
    q = np.cross(s, e1[None])
    v = np.einsum('j,pij->pi', dirn, q) / a
    t = np.einsum('ij,pij->pi', e2, q) / a
    m = (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 1e-9)
    return [np.sort(t[i][m[i]]) for i in range(len(P))]
u = np.cross(d, [1, 0, 0] if abs(d[0]) < 0.9 else [0, 1, 0]); u /= np.linalg.norm(u); w = np.cross(d, u)
def inside(P, T):
    # parity of a ray along a skew direction (not an axis: no grazing)
    r = np.array([0.5773, 0.5774, 0.5773]); r /= np.linalg.norm(r)
    return np.array([len(ts) % 2 == 1 for ts in hits(P, r, T)])
def blocked(i, j, dirn):
    _, Vi, Ti, Si = parts[i]; _, Vj, Tj, Sj = parts[j]
    for S, T, sgn in ((Si, Tj, 1), (Sj, Ti, -1)):
        for s0, ts in zip(S, hits(S, sgn * dirn, T)):
            # consecutive hits: inside stretches (t0, t1) longer than 2 eps,
            # whose middle is inside with the points eps beside it (deep)
            for k in range(0, len(ts) - 1, 2):
                if ts[k + 1] - ts[k] <= 2 * eps: continue
                m = s0 + 0.5 * (ts[k] + ts[k + 1]) * sgn * dirn
                probe = np.array([m, m + eps * u, m - eps * u, m + eps * w, m - eps * w])
                if inside(probe, T).all(): return True
    return False
n = len(parts)
for i in range(n):
    out = [parts[j][0] for j in range(n) if j != i and blocked(i, j, d)]
    print(parts[i][0], 'by', ', '.join(out) if out else '-')
