#!/usr/bin/python3
"""Brute-force contact checker: an independent reference for the contact rule.

Uses FreeCAD's Part module only (never the project's C++ core `contactcore` or the
`contactwb` workbench).  The rule (Iacob, Mitrouchev, Leon, sections 4-5):

    one contact per pair of maximal partitions (adjacent faces with the same surface
    parameters merged) of two different bodies with the same surface parameters,
    opposite material sides (opposite normals) and a common area > 0.

Types: PLF plane/plane, CLJ cylinder/cylinder, CJU cone/cone, SPF sphere/sphere,
TRF torus/torus, LAF convex sphere in a concave cylinder of the same radius (centre on
the axis), SPT ball in a torus groove (centre on the tube-centre circle, minor radius =
ball radius).  LAF and SPT touch along a circle, so their Boolean common area is 0:
for those two the check is distance based (points of the contact circle lying on both
faces).

Algorithm (deliberately plain, it is also the benchmark baseline "what a FreeCAD user
can script today"):
  1. body bounding boxes (sweep and prune on x) -> pairs of touching bodies;
  2. brute_force_face_pairs(): for every face pair of every touching body pair, compare
     surface type and parameters (analytic parameters, or for B-spline / other faces
     parameters recognised from sampled points and normals), face boxes, then a Boolean
     common of the two faces (`fa.common(fb)`), area > eps and opposite normals;
  3. group face-pair contacts into partition-pair contacts: faces of one body that
     share an edge and lie on the same surface (same parameters, same side) are one
     maximal partition (union-find).

Usage:
    /usr/bin/python3 tests/bruteforce_contacts.py Resources/samples/motor.FCStd
    /usr/bin/python3 tests/bruteforce_contacts.py Resources/samples/cases/inch.step \
        --expected Resources/samples/cases/inch.expected.json
"""
import json
import math
import os
import re
import sys
import time

FREECAD_LIB = '/usr/lib/freecad-python3/lib'
if FREECAD_LIB not in sys.path and os.path.isdir(FREECAD_LIB):
    sys.path.append(FREECAD_LIB)

import FreeCAD  # noqa: E402  (FreeCAD before Part)
import Part  # noqa: E402
import numpy as np  # noqa: E402

REL_TOL = 1e-6        # relative tolerance on surface parameters
ANG_TOL = 1e-6        # radians
REVOLUTION_TYPES = ('CLJ', 'CJU', 'SPF', 'LAF', 'SPT')


# =========================================================================== loading
def load_fcstd(path):
    """{Label: global shape} of every Part feature with a solid, in document order."""
    doc = FreeCAD.openDocument(path)
    try:
        out = {}
        for o in doc.Objects:
            if not o.isDerivedFrom('Part::Feature'):
                continue
            s = o.Shape
            if s.isNull() or not s.Solids:
                continue
            out[o.Label] = s.copy()
        return out
    finally:
        FreeCAD.closeDocument(doc.Name)


def step_part_names(path):
    """Part names of a flat STEP assembly written by Import.export, in file order.

    Import.export writes one NEXT_ASSEMBLY_USAGE_OCCURRENCE (NAUO) per object whose
    name is the object Label, and one PRODUCT per distinct shape (objects sharing a
    shape share one product, named after the first of them).  So the names are the
    NAUO names of the leaf occurrences; without NAUO (a single part) the PRODUCT
    names.  The order is the order Part.read returns the solids in."""
    with open(path, 'r', errors='replace') as f:
        txt = f.read()
    data = txt[txt.find('DATA;'):]
    ents = {}
    for m in re.finditer(r"#(\d+)\s*=\s*(.*?);\s*(?=#\d+\s*=|ENDSEC)", data, re.S):
        ents[int(m.group(1))] = re.sub(r'\s+', ' ', m.group(2))
    nauo = []
    for k, v in sorted(ents.items()):
        m = re.match(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE ?\( ?'(?:[^']|'')*' ?, ?'((?:[^']|'')*)'"
                     r" ?, ?'(?:[^']|'')*' ?, ?#(\d+) ?, ?#(\d+)", v)
        if m:
            nauo.append((m.group(1).replace("''", "'"), int(m.group(2)), int(m.group(3))))
    if nauo:
        parents = {rel for _, rel, _ in nauo}
        return [n for n, _, child in nauo if child not in parents]
    names = []
    for k, v in sorted(ents.items()):
        m = re.match(r"PRODUCT ?\( ?'((?:[^']|'')*)'", v)
        if m:
            names.append(m.group(1).replace("''", "'"))
    return names


def _distinct_solids(solids):
    """The solids without duplicates placed in place (readers that transfer every
    root return some solids twice): same volume and centre of mass."""
    out, seen = [], []
    for s in solids:
        c = s.CenterOfMass
        key = (s.Volume, c.x, c.y, c.z)
        scale = max(1.0, abs(s.Volume)) * 1e-9
        if any(abs(key[0] - k[0]) <= scale and math.dist(key[1:], k[1:]) <= 1e-7 * max(1.0, math.dist((0, 0, 0), key[1:]))
               for k in seen):
            continue
        seen.append(key)
        out.append(s)
    return out


def load_step(path):
    """{name: shape} for a STEP file.

    Part.read gives the solids in occurrence order but no names. For files
    written by Import.export (one product per part) the names come from
    step_part_names(); for any other file (names and solids differ in count:
    repeated instances, nested assemblies, duplicated roots) the solids are
    named by their rank, "solid1", "solid2", ..., after dropping duplicates.
    Compare such files with the core by body position (centre of mass)."""
    shape = Part.read(path)
    solids = _distinct_solids(shape.Solids)
    names = step_part_names(path)
    if len(names) != len(solids) or len(set(names)) != len(names):
        names = ['solid%d' % (i + 1) for i in range(len(solids))]
    return dict(zip(names, solids))


def load(path):
    if path.lower().endswith('.fcstd'):
        return load_fcstd(path)
    return load_step(path)


# =========================================================================== surfaces
def _vec(v):
    return np.array([v.x, v.y, v.z], dtype=float)


def _unit(a):
    n = np.linalg.norm(a)
    return a / n if n > 0 else a


def _canon_dir(u):
    """Sign-normalised direction (first significant component positive)."""
    for c in u:
        if abs(c) > 1e-9:
            return u if c > 0 else -u
    return u


def _sample_face(face, n=6):
    u0, u1, v0, v1 = face.ParameterRange
    pts, nrm = [], []
    for i in range(n):
        for j in range(n):
            u = u0 + (u1 - u0) * (0.1 + 0.8 * i / (n - 1))
            v = v0 + (v1 - v0) * (0.1 + 0.8 * j / (n - 1))
            try:
                p = face.valueAt(u, v)
                q = face.normalAt(u, v)
            except Exception:
                continue
            if q.Length < 0.5:
                continue
            pts.append(_vec(p))
            nrm.append(_vec(q))
    return np.array(pts), np.array(nrm)


def recognise(pts, nrm, lin_tol):
    """Analytic surface from sampled points and (oriented) normals, for B-spline and
    other non-analytic faces. Returns (kind, params) or ('other', {})."""
    if len(pts) < 6:
        return 'other', {}
    scale = max(1.0, float(np.max(np.abs(pts))))
    tol = max(lin_tol, 1e-9 * scale)
    # plane: constant normal
    n0 = nrm[0]
    if np.max(np.linalg.norm(nrm - n0, axis=1)) < 1e-7:
        d = pts @ n0
        if np.ptp(d) < tol:
            return 'plane', {'n': n0, 'd': float(np.mean(d))}
    # sphere: p = c + r n
    A = np.zeros((3 * len(pts), 4))
    b = pts.reshape(-1)
    for k in range(len(pts)):
        A[3 * k:3 * k + 3, :3] = np.eye(3)
        A[3 * k:3 * k + 3, 3] = nrm[k]
    x, *_ = np.linalg.lstsq(A, b, rcond=None)
    if np.max(np.abs(A @ x - b)) < tol and abs(x[3]) > tol:
        r = float(x[3])
        return 'sphere', {'c': x[:3], 'r': abs(r), 'convex': r > 0}
    # cylinder: all normals perpendicular to the axis
    _, sv, vt = np.linalg.svd(nrm)
    u = vt[2]
    if sv[2] < 1e-7 * max(1.0, sv[0]):
        # p = a + t u + r n  -> solve (a, t_k, r) in least squares via projection
        P = np.eye(3) - np.outer(u, u)
        q = pts @ P.T
        A = np.zeros((3 * len(pts), 4))
        for k in range(len(pts)):
            A[3 * k:3 * k + 3, :3] = P
            A[3 * k:3 * k + 3, 3] = nrm[k]
        x, *_ = np.linalg.lstsq(A, q.reshape(-1), rcond=None)
        if np.max(np.abs(A @ x - q.reshape(-1))) < tol:
            r = float(x[3])
            a = P @ x[:3]
            return 'cylinder', {'a': a, 'u': _canon_dir(u), 'r': abs(r), 'convex': r > 0}
    # cone: apex on every tangent plane; normals at constant angle to the axis
    x, *_ = np.linalg.lstsq(nrm, np.sum(nrm * pts, axis=1), rcond=None)
    apex = x
    if np.max(np.abs(nrm @ apex - np.sum(nrm * pts, axis=1))) < tol:
        M = np.hstack([nrm, -np.ones((len(nrm), 1))])
        _, sv, vt = np.linalg.svd(M)
        w = vt[-1]
        u = _unit(w[:3])
        if np.linalg.norm(w[:3]) > 1e-9 and np.max(np.abs(nrm @ u - np.mean(nrm @ u))) < 1e-7:
            return _cone_params(apex, u, pts, nrm)
    return 'other', {}


def _cone_params(apex, u, pts, nrm):
    rel = pts - apex
    if np.mean(rel @ u) < 0:
        u = -u
    g = rel[np.argmax(np.linalg.norm(rel, axis=1))]
    alpha = math.acos(max(-1.0, min(1.0, float(g @ u) / np.linalg.norm(g))))
    radial = g - (g @ u) * u
    k = int(np.argmax(np.linalg.norm(rel, axis=1)))
    convex = float(nrm[k] @ _unit(radial)) > 0
    return 'cone', {'apex': apex, 'u': u, 'alpha': alpha, 'convex': convex}


class FaceInfo(object):
    __slots__ = ('body', 'index', 'face', 'kind', 'p', 'bb', 'area')

    def __init__(self, body, index, face, kind, p):
        self.body = body
        self.index = index
        self.face = face
        self.kind = kind
        self.p = p
        self.bb = face.BoundBox
        self.area = None


def describe_face(face, lin_tol):
    s = face.Surface
    name = s.__class__.__name__
    u0, u1, v0, v1 = face.ParameterRange
    um, vm = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
    try:
        p = _vec(face.valueAt(um, vm))
        n = _unit(_vec(face.normalAt(um, vm)))
    except Exception:
        return 'other', {}
    if name == 'Plane':
        return 'plane', {'n': n, 'd': float(n @ p)}
    if name == 'Cylinder':
        u = _unit(_vec(s.Axis))
        a0 = _vec(s.Center)
        a = a0 - (a0 @ u) * u
        radial = (p - a0) - ((p - a0) @ u) * u
        return 'cylinder', {'a': a, 'u': _canon_dir(u), 'r': float(s.Radius),
                            'convex': float(n @ radial) > 0}
    if name == 'Sphere':
        c = _vec(s.Center)
        return 'sphere', {'c': c, 'r': float(s.Radius), 'convex': float(n @ (p - c)) > 0}
    if name == 'Cone':
        apex = _vec(s.Apex)
        u = _unit(_vec(s.Axis))
        pts, nrm = _sample_face(face, 3)
        if len(pts) == 0:
            pts, nrm = np.array([p]), np.array([n])
        return _cone_params(apex, u, pts, nrm)
    if name == 'Toroid':
        return 'torus', {'c': _vec(s.Center), 'u': _canon_dir(_unit(_vec(s.Axis))),
                         'R': float(s.MajorRadius), 'r': float(s.MinorRadius)}
    pts, nrm = _sample_face(face)
    return recognise(pts, nrm, lin_tol)


def _close(a, b, tol):
    return abs(a - b) <= tol


def _par(u, v):
    return abs(abs(float(u @ v)) - 1.0) < ANG_TOL


def _dist_point_line(p, a, u):
    d = p - a
    return float(np.linalg.norm(d - (d @ u) * u))


def same_surface(fa, fb, tol):
    """Same underlying surface (ignoring the material side)."""
    if fa.kind != fb.kind:
        return False
    a, b = fa.p, fb.p
    k = fa.kind
    if k == 'plane':
        return _par(a['n'], b['n']) and _close(a['d'], float(a['n'] @ b['n']) * b['d'], tol)
    if k == 'cylinder':
        return (_close(a['r'], b['r'], max(tol, REL_TOL * a['r'])) and _par(a['u'], b['u'])
                and _dist_point_line(b['a'], a['a'], a['u']) < tol)
    if k == 'cone':
        return (np.linalg.norm(a['apex'] - b['apex']) < tol and float(a['u'] @ b['u']) > 1 - ANG_TOL
                and _close(a['alpha'], b['alpha'], ANG_TOL))
    if k == 'sphere':
        return np.linalg.norm(a['c'] - b['c']) < tol and _close(a['r'], b['r'], max(tol, REL_TOL * a['r']))
    if k == 'torus':
        return (np.linalg.norm(a['c'] - b['c']) < tol and _par(a['u'], b['u'])
                and _close(a['R'], b['R'], max(tol, REL_TOL * a['R']))
                and _close(a['r'], b['r'], max(tol, REL_TOL * a['r'])))
    return False


def same_partition_surface(fa, fb, tol):
    """Same surface and same material side (for merging faces of one body)."""
    if not same_surface(fa, fb, tol):
        return False
    if fa.kind == 'plane':
        return float(fa.p['n'] @ fb.p['n']) > 0
    if fa.kind in ('cylinder', 'cone', 'sphere'):
        return fa.p['convex'] == fb.p['convex']
    return True


def candidate_type(fa, fb, tol):
    """Contact type if the two faces (of different bodies) may touch by the rule."""
    ka, kb = fa.kind, fb.kind
    if ka == kb:
        if not same_surface(fa, fb, tol):
            return None
        if ka == 'plane':
            return 'PLF' if float(fa.p['n'] @ fb.p['n']) < 0 else None
        if ka in ('cylinder', 'cone', 'sphere'):
            if fa.p['convex'] == fb.p['convex']:
                return None
            return {'cylinder': 'CLJ', 'cone': 'CJU', 'sphere': 'SPF'}[ka]
        if ka == 'torus':
            return 'TRF'
        return None
    pair = {ka: fa, kb: fb}
    if set(pair) == {'sphere', 'cylinder'}:
        s, c = pair['sphere'].p, pair['cylinder'].p
        if (s['convex'] and not c['convex'] and _close(s['r'], c['r'], max(tol, REL_TOL * s['r']))
                and _dist_point_line(s['c'], c['a'], c['u']) < tol):
            return 'LAF'
    if set(pair) == {'sphere', 'torus'}:
        s, t = pair['sphere'].p, pair['torus'].p
        d = s['c'] - t['c']
        h = float(d @ t['u'])
        rho = float(np.linalg.norm(d - h * t['u']))
        if (s['convex'] and abs(h) < tol and _close(rho, t['R'], tol)
                and _close(s['r'], t['r'], max(tol, REL_TOL * s['r']))):
            return 'SPT'
    return None


def _bb_overlap(a, b, tol):
    return not (a.XMin > b.XMax + tol or b.XMin > a.XMax + tol or a.YMin > b.YMax + tol
                or b.YMin > a.YMax + tol or a.ZMin > b.ZMax + tol or b.ZMin > a.ZMax + tol)


# =========================================================================== contacts
def _normal_at(face, p):
    u, v = face.Surface.parameter(FreeCAD.Vector(*p))
    return _unit(_vec(face.normalAt(u, v)))


def _face_mid_point(face):
    u0, u1, v0, v1 = face.ParameterRange
    return _vec(face.valueAt(0.5 * (u0 + u1), 0.5 * (v0 + v1)))


def _circle(typ, fa, fb):
    """Contact circle (centre, axis, radius) of a LAF/SPT candidate."""
    s = fa if fa.kind == 'sphere' else fb
    o = fb if s is fa else fa
    c = s.p['c']
    if typ == 'LAF':
        u = o.p['u']
    else:
        t = o.p
        d = c - t['c']
        radial = _unit(d - (d @ t['u']) * t['u'])
        u = _unit(np.cross(t['u'], radial))
    return c, u, s.p['r']


def _circle_points(c, u, r, n=360):
    e1 = _unit(np.cross(u, [1.0, 0, 0] if abs(u[0]) < 0.9 else [0, 1.0, 0]))
    e2 = np.cross(u, e1)
    ang = np.arange(n) * (2 * math.pi / n)
    return c + r * (np.outer(np.cos(ang), e1) + np.outer(np.sin(ang), e2)), ang


def angular_span(points, c, u):
    """Angular span (degrees) covered by points around the axis (c, u): 360 minus
    the largest empty angular gap."""
    if len(points) == 0:
        return 0.0
    e1 = _unit(np.cross(u, [1.0, 0, 0] if abs(u[0]) < 0.9 else [0, 1.0, 0]))
    e2 = np.cross(u, e1)
    d = np.asarray(points) - c
    x, y = d @ e1, d @ e2
    keep = np.hypot(x, y) > 1e-9
    if not np.any(keep):
        return 0.0
    a = np.sort(np.degrees(np.arctan2(y[keep], x[keep])) % 360.0)
    gaps = np.diff(np.concatenate([a, [a[0] + 360.0]]))
    return float(360.0 - np.max(gaps))


def brute_force_face_pairs(shapes_by_name, lin_tol=None, area_eps=None, stats=None):
    """Plain O(all face pairs of touching bodies) search.

    Returns a list of face-pair contacts dicts {a, b, fa, fb, type, area, points, axis}
    where fa/fb are FaceInfo; `stats` (dict) receives counters and timings."""
    t0 = time.time()
    names = list(shapes_by_name)
    shapes = [shapes_by_name[n] for n in names]
    bbs = [s.BoundBox for s in shapes]
    diag = max(1.0, max(b.DiagonalLength for b in bbs)) if bbs else 1.0
    if lin_tol is None:
        lin_tol = max(1e-7, REL_TOL * min(diag, 1000.0))
    if area_eps is None:
        area_eps = 1e-6
    # 1. body pairs (sweep and prune on x)
    order = sorted(range(len(shapes)), key=lambda i: bbs[i].XMin)
    body_pairs = []
    active = []
    for i in order:
        b = bbs[i]
        active = [j for j in active if bbs[j].XMax + lin_tol >= b.XMin]
        for j in active:
            if _bb_overlap(b, bbs[j], lin_tol):
                body_pairs.append((min(i, j), max(i, j)))
        active.append(i)
    body_pairs.sort()
    t1 = time.time()
    # 2. face descriptors (lazy, only for bodies in a pair)
    infos = {}

    def face_infos(i):
        if i not in infos:
            lst = []
            # work on a deep copy: Boolean operations add p-curves to the edges of their
            # arguments, and solids read from STEP share one TShape per part kind, so
            # without the copy every common() makes the next ones slower (3000 bolted
            # plates: 1.8 ms -> 4.5 ms per common) and the caller's shapes change
            for k, f in enumerate(shapes[i].copy().Faces):
                kind, p = describe_face(f, lin_tol)
                lst.append(FaceInfo(i, k, f, kind, p))
            infos[i] = lst
        return infos[i]

    results = []
    n_face_pairs = n_param = n_common = 0
    t_common = 0.0
    for i, j in body_pairs:
        fi, fj = face_infos(i), face_infos(j)
        for a in fi:
            if a.kind == 'other':
                n_face_pairs += len(fj)
                continue
            for b in fj:
                n_face_pairs += 1
                if b.kind == 'other':
                    continue
                typ = candidate_type(a, b, lin_tol)
                if typ is None:
                    continue
                n_param += 1
                if not _bb_overlap(a.bb, b.bb, lin_tol):
                    continue
                n_common += 1
                tc = time.time()
                if typ in ('LAF', 'SPT'):
                    c, u, r = _circle(typ, a, b)
                    pts, ang = _circle_points(c, u, r, 360)
                    on = []
                    for p in pts:
                        v = Part.Vertex(FreeCAD.Vector(*p))
                        if a.face.distToShape(v)[0] <= 10 * lin_tol and b.face.distToShape(v)[0] <= 10 * lin_tol:
                            on.append(p)
                    t_common += time.time() - tc
                    if on:
                        results.append({'a': names[i], 'b': names[j], 'fa': a, 'fb': b, 'type': typ,
                                        'area': 0.0, 'points': np.array(on), 'axis': (c, u)})
                    continue
                try:
                    com = a.face.common(b.face)
                except Exception:
                    com = None
                t_common += time.time() - tc
                if com is None or com.isNull() or not com.Faces:
                    continue
                area = precise_area(com)
                if area <= area_eps:
                    continue
                cf = max(com.Faces, key=lambda f: f.Area)
                pm = _face_mid_point(cf)
                try:
                    if float(_normal_at(a.face, pm) @ _normal_at(b.face, pm)) > -0.5:
                        continue    # same material side (e.g. torus outer/inner halves)
                except Exception:
                    pass
                pts = []
                for f in com.Faces:
                    for e in f.Edges:
                        try:
                            pts += [_vec(q) for q in e.discretize(Number=48)]
                        except Exception:
                            pass
                results.append({'a': names[i], 'b': names[j], 'fa': a, 'fb': b, 'type': typ,
                                'area': area, 'points': np.array(pts), 'axis': _axis_of(typ, a, pts)})
    t2 = time.time()
    if stats is not None:
        stats.update({'bodies': len(shapes), 'body_pairs': len(body_pairs),
                      'faces_described': sum(len(v) for v in infos.values()),
                      'face_pairs': n_face_pairs, 'same_parameter_pairs': n_param,
                      'booleans': n_common, 'face_pair_contacts': len(results),
                      't_body_pairs': t1 - t0, 't_face_pairs': t2 - t1, 't_booleans': t_common,
                      'lin_tol': lin_tol, 'infos': infos})
    return results


ANALYTIC_SURFACES = ('Plane', 'Cylinder', 'Cone', 'Sphere', 'Toroid')


def precise_area(shape):
    """Area of a Boolean result: OCCT's Gauss rule (Shape.Area) is exact on analytic
    surfaces but up to 0.5 % off on B-spline faces; those are summed from a
    triangulation instead (deflection 1e-3 of the face's size: within 1e-4 of the
    exact area on the nurbs case's cylinders, 2 pi r h)."""
    total = 0.0
    for f in shape.Faces:
        if f.Surface.__class__.__name__ in ANALYTIC_SURFACES:
            total += f.Area
            continue
        points, triangles = f.tessellate(1e-3 * f.BoundBox.DiagonalLength)
        p = np.array([[q.x, q.y, q.z] for q in points])
        t = np.array(triangles, dtype=int).reshape(-1, 3)
        total += 0.5 * float(np.sum(np.linalg.norm(np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]), axis=1)))
    return total


def _axis_of(typ, fa, pts):
    p = fa.p
    if typ == 'CLJ':
        return p['a'], p['u']
    if typ == 'CJU':
        return p['apex'], p['u']
    if typ == 'SPF':
        c = p['c']
        m = np.mean(np.asarray(pts), axis=0) - c if pts else np.array([0, 0, 1.0])
        if np.linalg.norm(m) < 1e-9 * max(1.0, p['r']):
            m = np.array([0, 0, 1.0])
        return c, _unit(m)
    if typ == 'TRF':
        return p['c'], p['u']
    return None


def partitions(infos_of_body, lin_tol):
    """Maximal partitions of one body: union of faces sharing an edge and lying on
    the same surface with the same material side. Returns {face index: partition id}."""
    faces = infos_of_body
    parent = list(range(len(faces)))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    edge_faces = {}
    for fi in faces:
        for e in fi.face.Edges:
            edge_faces.setdefault(e.hashCode(), []).append(fi.index)
    for lst in edge_faces.values():
        for x in range(len(lst)):
            for y in range(x + 1, len(lst)):
                a, b = faces[lst[x]], faces[lst[y]]
                if a.kind != 'other' and same_partition_surface(a, b, lin_tol):
                    ra, rb = find(a.index), find(b.index)
                    if ra != rb:
                        parent[ra] = rb
    return {fi.index: find(fi.index) for fi in faces}


def brute_force_contacts(shapes_by_name, details=False, lin_tol=None, stats=None):
    """{(a, b): {type: count}} with a before b in the input order.

    `stats` receives 'areas': [(a, b, type, area)], one per partition-pair
    contact, its area the sum of the Boolean common areas of its face pairs
    (0 for LAF and SPT): the area oracle of the tests.

    With details=True returns (contacts, partial, stats) where partial is
    {(a, b): {type: count of partial contacts}}."""
    st = {} if stats is None else stats
    t0 = time.time()
    fps = brute_force_face_pairs(shapes_by_name, lin_tol=lin_tol, stats=st)
    lin_tol = st['lin_tol']
    infos = st.pop('infos')
    part_of = {}
    groups = {}
    for r in fps:
        fa, fb = r['fa'], r['fb']
        for fi in (fa, fb):
            if fi.body not in part_of:
                part_of[fi.body] = partitions(infos[fi.body], lin_tol)
        key = (r['a'], r['b'], part_of[fa.body][fa.index], part_of[fb.body][fb.index], r['type'])
        g = groups.setdefault(key, {'points': [], 'axis': r['axis'], 'area': 0.0})
        g['area'] += r['area']
        if len(r['points']):
            g['points'].append(r['points'])
    contacts, partial = {}, {}
    st['areas'] = sorted((a, b, typ, g['area']) for (a, b, pa, pb, typ), g in groups.items())
    for (a, b, pa, pb, typ), g in groups.items():
        d = contacts.setdefault((a, b), {})
        d[typ] = d.get(typ, 0) + 1
        if typ in REVOLUTION_TYPES and g['axis'] is not None and g['points']:
            c, u = g['axis']
            span = angular_span(np.vstack(g['points']), c, u)
            if span < 180.0 - 1.0:
                dp = partial.setdefault((a, b), {})
                dp[typ] = dp.get(typ, 0) + 1
    st['partition_pairs'] = sum(sum(v.values()) for v in contacts.values())
    st['t_total'] = time.time() - t0
    if details:
        return contacts, partial, st
    return contacts


# =========================================================================== helpers
def expected_table(expected):
    """{frozenset(a, b): {type: count}} and partial counts from an expected JSON."""
    tab, par = {}, {}
    for c in expected['contacts']:
        k = frozenset((c['a'], c['b']))
        tab.setdefault(k, {})
        tab[k][c['type']] = tab[k].get(c['type'], 0) + c['count']
        if c.get('partial'):
            par.setdefault(k, {})
            par[k][c['type']] = par[k].get(c['type'], 0) + c['partial']
    return tab, par


def as_table(contacts):
    return {frozenset(k): dict(v) for k, v in contacts.items()}


def totals(contacts):
    t = {}
    for v in contacts.values():
        for typ, n in v.items():
            t[typ] = t.get(typ, 0) + n
    return dict(sorted(t.items()))


def compare(found, expected):
    """List of human readable differences (empty when equal)."""
    diffs = []
    keys = set(found) | set(expected)
    for k in sorted(keys, key=lambda s: sorted(s)):
        a, b = found.get(k, {}), expected.get(k, {})
        if a != b:
            diffs.append('%s: found %s expected %s' % (' <-> '.join(sorted(k)), a, b))
    return diffs


def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('file', help='.FCStd or .step/.stp (Import.export product names)')
    ap.add_argument('--expected', help='expected JSON to compare with (exit 1 on mismatch)')
    ap.add_argument('--tol', type=float, default=None, help='linear tolerance (default 1e-6 x size)')
    args = ap.parse_args(argv)
    t = time.time()
    shapes = load(args.file)
    t_load = time.time() - t
    contacts, partial, st = brute_force_contacts(shapes, details=True, lin_tol=args.tol)
    print('%-16s %-16s %s' % ('body A', 'body B', 'contacts'))
    for (a, b) in sorted(contacts, key=lambda k: (list(shapes).index(k[0]), list(shapes).index(k[1]))):
        v = contacts[(a, b)]
        pv = partial.get((a, b), {})
        txt = ', '.join('%d %s%s' % (n, typ, (' (%d partial)' % pv[typ]) if pv.get(typ) else '')
                        for typ, n in sorted(v.items()))
        print('%-16s %-16s %s' % (a, b, txt))
    print('totals:', totals(contacts), 'partial:', totals(partial))
    print('timings: load %.3fs, body pairs %.3fs, face pairs %.3fs (booleans %.3fs), total %.3fs'
          % (t_load, st['t_body_pairs'], st['t_face_pairs'], st['t_booleans'], st['t_total']))
    print('counts: %d bodies, %d body pairs, %d faces, %d face pairs, %d same-parameter pairs, '
          '%d booleans, %d face-pair contacts, %d partition-pair contacts'
          % (st['bodies'], st['body_pairs'], st['faces_described'], st['face_pairs'],
             st['same_parameter_pairs'], st['booleans'], st['face_pair_contacts'], st['partition_pairs']))
    if args.expected:
        with open(args.expected) as f:
            exp = json.load(f)
        tab, par = expected_table(exp)
        diffs = compare(as_table(contacts), tab) + ['partial ' + d for d in compare(as_table(partial), par)]
        if diffs:
            print('MISMATCH with %s:' % args.expected)
            for d in diffs:
                print('  ' + d)
            return 1
        print('OK: equals %s' % args.expected)
    return 0


if __name__ == '__main__':
    sys.exit(main())
