"""Geometry for tools/gen_lathe_model.py: small vector maths, placement frames, closed
triangle meshes of primitives with their OBJ output, and mass properties of composites.

Python 3 standard library only; every number is printed with fixed formatting so that the
output is deterministic.
"""

import math

SEG_BIG = 96     # segments of cylinders with radius >= 0.05 m
SEG_SMALL = 48   # segments of smaller cylinders


# --------------------------------------------------------------------------- small vector maths
def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def f6(x):
    """Mesh coordinates: fixed 6 decimals (micrometres), never '-0.000000'."""
    s = "%.6f" % x
    return "0.000000" if s == "-0.000000" else s


def fnum(x):
    """URDF numbers: 9 decimals, trailing zeros stripped, never '-0'."""
    s = ("%.9f" % x).rstrip("0").rstrip(".")
    return "0" if s in ("-0", "", "-") else s


def fvec(v):
    return " ".join(fnum(c) for c in v)


def deg(a):
    return math.radians(a)


class Frame:
    """Placement of a local primitive in its link frame: origin + rotation (columns ex ey ez)."""

    def __init__(self, origin=(0.0, 0.0, 0.0), ex=(1.0, 0.0, 0.0), ey=(0.0, 1.0, 0.0),
                 ez=(0.0, 0.0, 1.0)):
        self.o, self.ex, self.ey, self.ez = origin, ex, ey, ez

    def p(self, v):
        return add(self.o, add(add(scale(self.ex, v[0]), scale(self.ey, v[1])),
                               scale(self.ez, v[2])))

    def n(self, v):
        return normalize(add(add(scale(self.ex, v[0]), scale(self.ey, v[1])),
                             scale(self.ez, v[2])))


IDENT = Frame()


def rotz(angle, origin=(0.0, 0.0, 0.0)):
    """Frame rotated by `angle` about z: local x = radial ray at `angle`, local y = tangential."""
    c, s = math.cos(angle), math.sin(angle)
    return Frame(origin, (c, s, 0.0), (-s, c, 0.0), (0.0, 0.0, 1.0))


def axis_frame(origin, axis):
    """Frame whose local z is `axis` (for cylinders and cones along any direction)."""
    a = normalize(axis)
    helper = (0.0, 0.0, 1.0) if abs(a[2]) < 0.9 else (1.0, 0.0, 0.0)
    ex = normalize(cross(helper, a))
    ey = cross(a, ex)
    return Frame(origin, ex, ey, a)


# --------------------------------------------------------------------------------------- meshes
class Mesh:
    def __init__(self, name):
        self.name = name
        self.tris = []

    def tri(self, a, b, c, na, nb, nc):
        # Wind counter-clockwise seen from outside: the face normal must agree with the
        # vertex normals (which the primitives compute as outward normals).
        fn = cross(sub(b, a), sub(c, a))
        if dot(fn, add(add(na, nb), nc)) < 0.0:
            b, c, nb, nc = c, b, nc, nb
        self.tris.append(((a, na), (b, nb), (c, nc)))

    def quad(self, a, b, c, d, na, nb, nc, nd):
        self.tri(a, b, c, na, nb, nc)
        self.tri(a, c, d, na, nc, nd)

    # ---------------------------------------------------------------------------- primitives
    def prism(self, poly, z0, z1, frame=IDENT):
        """Convex polygon `poly` (local x, y) extruded from local z0 to z1; flat shading."""
        area = 0.0
        for i in range(len(poly)):
            x0, y0 = poly[i]
            x1, y1 = poly[(i + 1) % len(poly)]
            area += x0 * y1 - x1 * y0
        if area < 0.0:
            poly = list(reversed(poly))
        n = len(poly)
        bot = [frame.p((x, y, z0)) for x, y in poly]
        top = [frame.p((x, y, z1)) for x, y in poly]
        nb, nt = frame.n((0, 0, -1)), frame.n((0, 0, 1))
        for i in range(1, n - 1):
            self.tri(bot[0], bot[i], bot[i + 1], nb, nb, nb)
            self.tri(top[0], top[i], top[i + 1], nt, nt, nt)
        for i in range(n):
            j = (i + 1) % n
            dx = poly[j][0] - poly[i][0]
            dy = poly[j][1] - poly[i][1]
            ns = frame.n((dy, -dx, 0.0))
            self.quad(bot[i], bot[j], top[j], top[i], ns, ns, ns, ns)

    def box(self, x0, x1, y0, y1, z0, z1, frame=IDENT):
        self.prism([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], z0, z1, frame)

    def ngon_prism(self, n, circumradius, z0, z1, frame=IDENT, phase=0.0):
        poly = [(circumradius * math.cos(phase + 2 * math.pi * i / n),
                 circumradius * math.sin(phase + 2 * math.pi * i / n)) for i in range(n)]
        self.prism(poly, z0, z1, frame)

    def frustum(self, r0, r1, z0, z1, nseg, frame=IDENT, cap0=True, cap1=True):
        """Solid of revolution about local z: radius r0 at z0 to r1 at z1; smooth sides,
        flat caps (fan around the centre). r0 or r1 may be 0 (cone apex)."""
        h = z1 - z0
        ang = [2.0 * math.pi * i / nseg for i in range(nseg)]
        ring0 = [frame.p((r0 * math.cos(a), r0 * math.sin(a), z0)) for a in ang]
        ring1 = [frame.p((r1 * math.cos(a), r1 * math.sin(a), z1)) for a in ang]

        def side_n(a):
            return frame.n((h * math.cos(a), h * math.sin(a), r0 - r1))

        for i in range(nseg):
            j = (i + 1) % nseg
            ni, nj = side_n(ang[i]), side_n(ang[j])
            if r0 == 0.0:
                nm = side_n(ang[i] + math.pi / nseg)
                self.tri(ring0[i], ring1[i], ring1[j], nm, ni, nj)
            elif r1 == 0.0:
                nm = side_n(ang[i] + math.pi / nseg)
                self.tri(ring0[i], ring0[j], ring1[i], ni, nj, nm)
            else:
                self.quad(ring0[i], ring0[j], ring1[j], ring1[i], ni, nj, nj, ni)
        if cap0 and r0 > 0.0:
            c, nc = frame.p((0, 0, z0)), frame.n((0, 0, -1))
            for i in range(nseg):
                self.tri(c, ring0[i], ring0[(i + 1) % nseg], nc, nc, nc)
        if cap1 and r1 > 0.0:
            c, nc = frame.p((0, 0, z1)), frame.n((0, 0, 1))
            for i in range(nseg):
                self.tri(c, ring1[i], ring1[(i + 1) % nseg], nc, nc, nc)

    def cylinder(self, r, z0, z1, frame=IDENT, nseg=None):
        if nseg is None:
            nseg = SEG_BIG if r >= 0.05 else SEG_SMALL
        self.frustum(r, r, z0, z1, nseg, frame)

    def sphere(self, centre, r, nlon=32, nlat=16):
        def pt(i, j):
            th = math.pi * i / nlat                  # from +z pole
            ph = 2.0 * math.pi * (j % nlon) / nlon
            n = (math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th))
            return add(centre, scale(n, r)), n

        top, ntop = add(centre, (0, 0, r)), (0.0, 0.0, 1.0)
        bot, nbot = add(centre, (0, 0, -r)), (0.0, 0.0, -1.0)
        for j in range(nlon):
            a, na = pt(1, j)
            b, nb = pt(1, j + 1)
            self.tri(top, a, b, ntop, na, nb)
            a, na = pt(nlat - 1, j)
            b, nb = pt(nlat - 1, j + 1)
            self.tri(bot, a, b, nbot, na, nb)
        for i in range(1, nlat - 1):
            for j in range(nlon):
                a, na = pt(i, j)
                b, nb = pt(i, j + 1)
                c, nc = pt(i + 1, j + 1)
                d, nd = pt(i + 1, j)
                self.quad(a, b, c, d, na, nb, nc, nd)

    # ---------------------------------------------------------------------------- output
    def ply_text(self, model):
        """ASCII PLY text of a mesh of `model` (lathe-c1, ...): each triangle's three corners
        as vertices of their own, position and normal. Assimp reads a PLY file at its size,
        where its OBJ reader fills a fixed 16 MB buffer per file (half of a short run's start
        with 66 meshes); the corners and their printed numbers are those an OBJ of shared
        positions and normals gave, so the imported arrays are the same floats."""
        n = len(self.tris)
        head = ["ply", "format ascii 1.0",
                "comment %s mesh %s -- generated by tools/gen_lathe_model.py, do not edit" %
                (model, self.name), "comment units: metres, link frame; %d triangles" % n,
                "element vertex %d" % (3 * n)]
        head += ["property float %s" % c for c in ("x", "y", "z", "nx", "ny", "nz")]
        head += ["element face %d" % n, "property list uchar int vertex_indices", "end_header"]
        corners = ["%s %s %s %s %s %s" % (f6(p[0]), f6(p[1]), f6(p[2]), f6(q[0]), f6(q[1]),
                                          f6(q[2])) for t in self.tris for p, q in t]
        faces = ["3 %d %d %d" % (3 * k, 3 * k + 1, 3 * k + 2) for k in range(n)]
        return "\n".join(head + corners + faces) + "\n"

    def check_closed(self):
        """Every edge used exactly once in each direction (closed, consistently wound), and
        positive enclosed volume (outward winding). Uses the printed coordinates."""
        key = {}
        edges = {}
        vol = 0.0
        pts = []
        for t in self.tris:
            ids = []
            for p, _ in t:
                k = (f6(p[0]), f6(p[1]), f6(p[2]))
                if k not in key:
                    key[k] = len(pts)
                    pts.append(tuple(float(c) for c in k))
                ids.append(key[k])
            for a, b in ((ids[0], ids[1]), (ids[1], ids[2]), (ids[2], ids[0])):
                edges[(a, b)] = edges.get((a, b), 0) + 1
            a, b, c = (pts[i] for i in ids)
            vol += dot(a, cross(b, c)) / 6.0
        for (a, b), cnt in edges.items():
            if cnt != 1 or edges.get((b, a), 0) != 1:
                raise SystemExit("mesh %s: not closed / inconsistent winding at edge %r"
                                 % (self.name, (a, b)))
        if vol <= 0.0:
            raise SystemExit("mesh %s: non-positive volume %g" % (self.name, vol))
        return vol


# ------------------------------------------------------------------------------ mass properties
def _prim(kind, *a):
    """(volume, centre, (Ixx, Iyy, Izz) per unit mass about own centre) of a primitive."""
    if kind == "box":
        x0, x1, y0, y1, z0, z1 = a
        sx, sy, sz = x1 - x0, y1 - y0, z1 - z0
        return (sx * sy * sz, ((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2),
                ((sy * sy + sz * sz) / 12, (sx * sx + sz * sz) / 12, (sx * sx + sy * sy) / 12))
    if kind in ("cylz", "cylx"):
        # cylz: centre (cx, cy), r, z0, z1 (axis z); cylx: centre (cy, cz), r, x0, x1 (axis x)
        c1, c2, r, s0, s1 = a
        h = s1 - s0
        ia, ip = r * r / 2, (3 * r * r + h * h) / 12
        if kind == "cylz":
            return (math.pi * r * r * h, (c1, c2, (s0 + s1) / 2), (ip, ip, ia))
        return (math.pi * r * r * h, ((s0 + s1) / 2, c1, c2), (ia, ip, ip))
    raise ValueError(kind)


def composite(mass, parts, izz=None):
    """Uniform-density composite of primitives scaled to `mass`: (mass, com, diag inertia about
    the com in link axes). Products of inertia are neglected. `izz` overrides Izz (rotor values
    given by the machine data)."""
    ps = [_prim(*p) for p in parts]
    vol = sum(p[0] for p in ps)
    com = (0.0, 0.0, 0.0)
    for v, c, _ in ps:
        com = add(com, scale(c, v / vol))
    ixx = iyy = izz_c = 0.0
    for v, c, i in ps:
        m = mass * v / vol
        d = sub(c, com)
        ixx += m * (i[0] + d[1] ** 2 + d[2] ** 2)
        iyy += m * (i[1] + d[0] ** 2 + d[2] ** 2)
        izz_c += m * (i[2] + d[0] ** 2 + d[1] ** 2)
    if izz is not None:
        izz_c = izz
    inertia = (ixx, iyy, izz_c)
    a, b, c = inertia
    if not (a + b >= c and a + c >= b and b + c >= a and min(inertia) > 0):
        raise SystemExit("inertia %r violates the triangle inequality" % (inertia,))
    return mass, com, inertia
