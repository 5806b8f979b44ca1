#!/usr/bin/env python3
"""Convert a PDS3 small-body plate model (``v``/``f`` ASCII table) to the
Wavefront OBJ form kept under ``bodies/``, and check the mesh.

Usage:
    python3 bodies/convert.py SOURCE.TAB OUT.obj HEADER.txt
    python3 bodies/convert.py --check OUT.obj

The PDS3 radar shape models (EAR-A-5-DDR-RADARSHAPE-MODELS) are already
OBJ-like: ``v x y z`` records (kilometres) then ``f i j k`` records (1-based).
The conversion
  * multiplies every coordinate by 1000 exactly (decimal arithmetic, no
    rounding: km -> m),
  * keeps the vertex order and the facet order and the 1-based indices
    unchanged, and the vertex order within each facet unchanged,
  * writes LF line ends and a ``#`` comment header (the text of HEADER.txt).
Then, and with ``--check`` on any OBJ, it checks the mesh and prints its
numbers: every undirected edge in exactly two facets (closed, manifold),
every directed edge exactly once (consistently oriented), positive signed
volume (normals outward by the right-hand rule), no facet with a repeated
vertex or zero area, no unused vertex; and the vertex/facet counts, area,
volume, equivalent radius, extents, and the centre of mass and principal
moments of inertia for a constant density.  Standard library only.
"""
import math
import sys
from decimal import Decimal


def read_tab(path):
    verts, faces = [], []
    with open(path, newline="") as fh:
        for line in fh:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                verts.append([Decimal(x) for x in p[1:4]])
            elif p[0] == "f":
                faces.append([int(x) for x in p[1:4]])
            else:
                raise SystemExit(f"unexpected record: {line!r}")
    return verts, faces


def read_obj(path):
    verts, faces = [], []
    with open(path) as fh:
        for line in fh:
            p = line.split()
            if not p or p[0].startswith("#"):
                continue
            if p[0] == "v":
                verts.append([float(x) for x in p[1:4]])
            elif p[0] == "f":
                faces.append([int(x.split("/")[0]) for x in p[1:]])
    return verts, faces


def fmt_m(d):
    """A km Decimal as metres, exactly, without exponent."""
    s = format(d * 1000, "f")
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def jacobi_eig(m):
    """Eigenvalues/vectors of a symmetric 3x3 (cyclic Jacobi)."""
    a = [row[:] for row in m]
    v = [[1.0 if i == j else 0.0 for j in range(3)] for i in range(3)]
    for _ in range(50):
        off = sum(a[i][j] ** 2 for i in range(3) for j in range(3) if i != j)
        if off < 1e-30 * (sum(a[i][i] ** 2 for i in range(3)) + 1e-300):
            break
        for p in range(3):
            for q in range(p + 1, 3):
                if a[p][q] == 0.0:
                    continue
                th = (a[q][q] - a[p][p]) / (2 * a[p][q])
                t = (1.0 if th >= 0 else -1.0) / (abs(th) + math.sqrt(th * th + 1))
                c = 1 / math.sqrt(t * t + 1)
                s = t * c
                for k in range(3):
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(3):
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
                for k in range(3):
                    vkp, vkq = v[k][p], v[k][q]
                    v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    vals = [a[i][i] for i in range(3)]
    vecs = [[v[k][i] for k in range(3)] for i in range(3)]
    order = sorted(range(3), key=lambda i: vals[i])
    return [vals[i] for i in order], [vecs[i] for i in order]


def check(verts, faces, unit="m"):
    n_v, n_f = len(verts), len(faces)
    ok = True
    # indices, repeated vertices
    for k, f in enumerate(faces):
        if len(f) != 3 or min(f) < 1 or max(f) > n_v:
            print(f"BAD facet {k + 1}: {f}")
            ok = False
        if len(set(f)) != 3:
            print(f"DEGENERATE facet {k + 1}: repeated vertex {f}")
            ok = False
    used = set(i for f in faces for i in f)
    unused = n_v - len(used)
    # edges
    directed, undirected = {}, {}
    for k, (a, b, c) in enumerate(faces):
        for e in ((a, b), (b, c), (c, a)):
            directed[e] = directed.get(e, 0) + 1
            u = (min(e), max(e))
            undirected[u] = undirected.get(u, 0) + 1
    bad_u = [(e, n) for e, n in undirected.items() if n != 2]
    bad_d = [(e, n) for e, n in directed.items() if n != 1 or (e[1], e[0]) not in directed]
    closed = not bad_u
    oriented = not bad_d
    ok = ok and closed and oriented and unused == 0
    # area, volume, centroid, inertia (tetrahedra from the origin)
    area = 0.0
    vol = 0.0
    mx = [0.0, 0.0, 0.0]
    # second moments  int x_i x_j dV
    S = [[0.0] * 3 for _ in range(3)]
    min_area = float("inf")
    for (i, j, k) in faces:
        a, b, c = verts[i - 1], verts[j - 1], verts[k - 1]
        n = cross(sub(b, a), sub(c, a))
        ar = 0.5 * math.sqrt(dot(n, n))
        area += ar
        min_area = min(min_area, ar)
        dv = dot(a, cross(b, c)) / 6.0
        vol += dv
        for d in range(3):
            mx[d] += dv * (a[d] + b[d] + c[d]) / 4.0
        for p in range(3):
            for q in range(3):
                S[p][q] += dv / 20.0 * (
                    a[p] * a[q] + b[p] * b[q] + c[p] * c[q]
                    + (a[p] + b[p] + c[p]) * (a[q] + b[q] + c[q])
                )
    edge_lengths = [math.dist(verts[e[0] - 1], verts[e[1] - 1]) for e in undirected]
    com = [m / vol for m in mx]
    # central second moments, then inertia per unit density
    C = [[S[p][q] - vol * com[p] * com[q] for q in range(3)] for p in range(3)]
    tr = C[0][0] + C[1][1] + C[2][2]
    inertia = [[(tr if p == q else 0.0) - C[p][q] for q in range(3)] for p in range(3)]
    vals, vecs = jacobi_eig(inertia)
    lo = [min(v[d] for v in verts) for d in range(3)]
    hi = [max(v[d] for v in verts) for d in range(3)]
    r_eq = (3 * vol / (4 * math.pi)) ** (1 / 3)
    print(f"vertices {n_v}  facets {n_f}  edges {len(undirected)}  "
          f"Euler V-E+F = {n_v - len(undirected) + n_f}  unused vertices {unused}")
    print(f"closed (each edge in exactly 2 facets): {closed}"
          + ("" if closed else f"  first bad edge {bad_u[0]}"))
    print(f"consistently oriented (each directed edge once): {oriented}"
          + ("" if oriented else f"  first bad edge {bad_d[0]}"))
    print(f"signed volume {vol:.6g} {unit}^3  (outward: {vol > 0})")
    print(f"smallest facet area {min_area:.4g} {unit}^2  (degenerate: {min_area <= 0})")
    print(f"edge length min/mean/max {min(edge_lengths):.4g} / "
          f"{sum(edge_lengths) / len(edge_lengths):.4g} / {max(edge_lengths):.4g} {unit}")
    print(f"surface area {area:.6g} {unit}^2")
    print(f"equivalent-volume sphere radius {r_eq:.6g} {unit}  (diameter {2 * r_eq:.6g})")
    print("extents x {:.2f}..{:.2f}  y {:.2f}..{:.2f}  z {:.2f}..{:.2f} {}".format(
        lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], unit))
    print("bounding box {:.2f} x {:.2f} x {:.2f} {}".format(*(h - l for h, l in zip(hi, lo)), unit))
    print("centre of mass (constant density) ({:.4g}, {:.4g}, {:.4g}) {}".format(*com, unit))
    print("inertia tensor / (rho V) about the centre of mass, " + unit + "^2:")
    for row in inertia:
        print("   " + "  ".join(f"{x / vol:12.5g}" for x in row))
    print("principal moments / (rho V): " + ", ".join(f"{x / vol:.6g}" for x in vals))
    for val, vec in zip(vals, vecs):
        print(f"   axis for {val / vol:10.6g}: ({vec[0]:+.5f}, {vec[1]:+.5f}, {vec[2]:+.5f})")
    print("ALL CHECKS PASS" if ok and vol > 0 and min_area > 0 else "CHECKS FAILED")
    return ok and vol > 0 and min_area > 0


def main(argv):
    if len(argv) == 3 and argv[1] == "--check":
        verts, faces = read_obj(argv[2])
        return 0 if check(verts, faces) else 1
    if len(argv) != 4:
        raise SystemExit(__doc__)
    src, out, header = argv[1:]
    verts, faces = read_tab(src)
    with open(header) as fh:
        head = [ln.rstrip("\n") for ln in fh]
    with open(out, "w", newline="\n") as fh:
        for ln in head:
            fh.write(("# " + ln).rstrip() + "\n")
        for v in verts:
            fh.write("v " + " ".join(fmt_m(x) for x in v) + "\n")
        for f in faces:
            fh.write("f {} {} {}\n".format(*f))
    verts, faces = read_obj(out)
    return 0 if check(verts, faces) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
