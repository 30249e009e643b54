"""Sample assemblies: the generator output matches the committed files, and the
independent brute-force checker finds exactly the expected contacts.

    /usr/bin/python3 -m pytest tests/test_samples.py
"""
import glob
import json
import math
import os
import re
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
SAMPLES = os.path.join(REPO, 'Resources', 'samples')
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(REPO, 'tools'))

import bruteforce_contacts as bf  # noqa: E402  (imports FreeCAD, then Part)
import FreeCAD  # noqa: E402
import Part  # noqa: E402

MOTOR_NAMES = ['Axis', 'Rotor-front', 'Rotor-back', 'Magnet-1', 'Magnet-2', 'Magnet-3', 'Magnet-4',
               'Bearing-front', 'Bearing-back', 'Seal', 'Stator', 'Body', 'Back-cover',
               'Front-cover', 'Screw-1', 'Screw-2', 'Screw-3', 'Screw-4']


def paper_motor_list():
    """The paper's section 5 list, written out independently of the generator."""
    plf = [('Rotor-back', 'Magnet-%d' % k) for k in range(1, 5)]
    plf += [('Rotor-front', 'Rotor-back'), ('Rotor-front', 'Bearing-front'), ('Back-cover', 'Bearing-back'),
            ('Body', 'Back-cover'), ('Body', 'Stator'), ('Body', 'Front-cover')]
    plf += [('Screw-%d' % k, 'Front-cover') for k in range(1, 5)]
    clj = [('Axis', 'Rotor-front'), ('Axis', 'Rotor-back'), ('Axis', 'Bearing-front'), ('Axis', 'Bearing-back'),
           ('Axis', 'Seal'), ('Back-cover', 'Bearing-back'), ('Front-cover', 'Bearing-front'),
           ('Front-cover', 'Seal'), ('Stator', 'Body')]
    for k in range(1, 5):
        clj += [('Screw-%d' % k, 'Body'), ('Screw-%d' % k, 'Back-cover'), ('Screw-%d' % k, 'Front-cover')]
    tab = {}
    for typ, lst in (('PLF', plf), ('CLJ', clj)):
        for a, b in lst:
            d = tab.setdefault(frozenset((a, b)), {})
            d[typ] = d.get(typ, 0) + 1
    return tab


def load_json(path):
    with open(path) as f:
        return json.load(f)


def committed_sets():
    out = [os.path.join(SAMPLES, 'motor')]
    for sub in ('cases', 'families'):
        out += sorted(p[:-len('.expected.json')] for p in glob.glob(os.path.join(SAMPLES, sub, '*.expected.json')))
    return out


CASE_NAMES = sorted(os.path.basename(p)[:-len('.expected.json')]
                    for p in glob.glob(os.path.join(SAMPLES, 'cases', '*.expected.json')))


@pytest.fixture(scope='module')
def generated(tmp_path_factory):
    """Run the generator headless (motor + cases + grids 10 and 100) into a tmp dir."""
    out = str(tmp_path_factory.mktemp('samples'))
    r = subprocess.run([sys.executable, os.path.join(REPO, 'tools', 'make_samples.py'), '--out', out],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    return out


# ------------------------------------------------------------------ generator vs committed
def test_committed_files_present():
    assert len(committed_sets()) >= 17
    for base in committed_sets():
        for ext in ('.step', '.FCStd', '.expected.json'):
            assert os.path.isfile(base + ext), base + ext


@pytest.mark.parametrize('base', committed_sets(), ids=lambda p: os.path.relpath(p, SAMPLES))
def test_generated_matches_committed(generated, base):
    rel = os.path.relpath(base, SAMPLES)
    new = os.path.join(generated, rel)
    for ext in ('.step', '.FCStd', '.expected.json'):
        assert os.path.isfile(new + ext), 'generator did not write ' + rel + ext
    old_j, new_j = load_json(base + '.expected.json'), load_json(new + '.expected.json')
    assert new_j == old_j, 'expected JSON changed: regenerate and review ' + rel
    old_s, new_s = bf.load_step(base + '.step'), bf.load_step(new + '.step')
    assert list(new_s) == list(old_s) == old_j['bodies']
    for name in old_s:
        a, b = old_s[name], new_s[name]
        assert len(a.Solids) == len(b.Solids) == 1, name
        assert abs(a.Volume - b.Volume) <= 1e-6 * abs(a.Volume), (name, a.Volume, b.Volume)
        assert len(a.Faces) == len(b.Faces), (name, len(a.Faces), len(b.Faces))
        assert (a.BoundBox.Center - b.BoundBox.Center).Length <= 1e-6 * max(1.0, a.BoundBox.DiagonalLength), name
    fc = bf.load_fcstd(base + '.FCStd')
    assert list(fc) == old_j['bodies']
    for name in fc:
        assert abs(fc[name].Volume - old_s[name].Volume) <= 1e-6 * fc[name].Volume, name
        c1, c2 = fc[name].BoundBox.Center, old_s[name].BoundBox.Center
        assert (c1 - c2).Length <= 1e-4, (name, c1, c2)


# ------------------------------------------------------------------ motor
def test_motor_structure():
    exp = load_json(os.path.join(SAMPLES, 'motor.expected.json'))
    assert exp['bodies'] == MOTOR_NAMES
    assert exp['totals'] == {'CLJ': 21, 'PLF': 14}
    tab, par = bf.expected_table(exp)
    assert tab == paper_motor_list()
    assert par == {}
    with open(os.path.join(SAMPLES, 'motor.step')) as f:
        txt = f.read()
    products = set(re.findall(r"PRODUCT\('([^']*)'", txt))
    assert set(MOTOR_NAMES) <= products
    shapes = bf.load_fcstd(os.path.join(SAMPLES, 'motor.FCStd'))
    assert list(shapes) == MOTOR_NAMES
    bb = shapes['Body'].BoundBox
    assert 40 <= bb.XLength <= 60 and 40 <= bb.YLength <= 60
    # faces are split as CAD exports split them: partition merging matters
    axis_cyl = [f for f in shapes['Axis'].Faces
                if f.Surface.__class__.__name__ == 'Cylinder' and abs(f.Surface.Radius - 4) < 1e-9]
    assert len(axis_cyl) >= 4
    body_bore = [f for f in shapes['Body'].Faces
                 if f.Surface.__class__.__name__ == 'Cylinder' and abs(f.Surface.Radius - 17) < 1e-9]
    assert len(body_bore) == 4


@pytest.mark.parametrize('ext', ['.FCStd', '.step'])
def test_motor_bruteforce(ext):
    shapes = bf.load(os.path.join(SAMPLES, 'motor' + ext))
    contacts, partial, st = bf.brute_force_contacts(shapes, details=True)
    exp, _ = bf.expected_table(load_json(os.path.join(SAMPLES, 'motor.expected.json')))
    assert bf.compare(bf.as_table(contacts), exp) == []
    assert bf.compare(bf.as_table(contacts), paper_motor_list()) == []
    assert partial == {}
    assert st['face_pair_contacts'] > st['partition_pairs']   # merging did something


def test_motor_no_interference():
    shapes = bf.load_fcstd(os.path.join(SAMPLES, 'motor.FCStd'))
    names = list(shapes)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            if shapes[a].BoundBox.intersect(shapes[b].BoundBox):
                v = shapes[a].common(shapes[b]).Volume
                assert v < 1e-6, (a, b, v)


def test_checker_can_fail():
    """Moving one screw by 0.05 mm must lose its three CLJ (and the checker says so)."""
    shapes = bf.load_fcstd(os.path.join(SAMPLES, 'motor.FCStd'))
    shapes['Screw-1'] = shapes['Screw-1'].translated(FreeCAD.Vector(0.05, 0, 0))
    found = bf.as_table(bf.brute_force_contacts(shapes))
    exp, _ = bf.expected_table(load_json(os.path.join(SAMPLES, 'motor.expected.json')))
    diffs = bf.compare(found, exp)
    assert len(diffs) == 3 and all('Screw-1' in d for d in diffs), diffs


# ------------------------------------------------------------------ cases
@pytest.mark.parametrize('name', CASE_NAMES)
def test_case_bruteforce(name):
    base = os.path.join(SAMPLES, 'cases', name)
    exp = load_json(base + '.expected.json')
    shapes = bf.load_step(base + '.step')
    assert list(shapes) == exp['bodies']
    contacts, partial, _ = bf.brute_force_contacts(shapes, details=True)
    tab, par = bf.expected_table(exp)
    assert bf.compare(bf.as_table(contacts), tab) == []
    assert bf.compare(bf.as_table(partial), par) == []


def test_case_expectations():
    t = {n: load_json(os.path.join(SAMPLES, 'cases', n + '.expected.json'))['totals'] for n in CASE_NAMES}
    assert t['ball_joint'] == {'SPF': 1} and t['taper_pin'] == {'CJU': 1}
    assert t['ball_in_bore'] == {'LAF': 1} and t['cradle_120'] == {'CLJ': 1}
    assert t['ball_bearing'] == {'SPT': 16} and t['oring_groove'] == {'TRF': 1}
    for n in ('clearance', 'interference', 'line_contact'):
        assert t[n] == {}
    assert t['coplanar_same_normal'] == {'PLF': 2}
    for n in ('split_faces', 'nurbs', 'inch'):
        assert t[n] == t['pin_block'] == {'CLJ': 2, 'PLF': 2}
    par = load_json(os.path.join(SAMPLES, 'cases', 'cradle_120.expected.json'))['partial']
    assert par == {'CLJ': 1}


def test_hard_case_properties():
    cases = os.path.join(SAMPLES, 'cases')
    ref = bf.load_step(os.path.join(cases, 'pin_block.step'))
    split = bf.load_step(os.path.join(cases, 'split_faces.step'))
    for n in ref:
        assert len(split[n].Faces) > len(ref[n].Faces)
        assert abs(split[n].Volume - ref[n].Volume) < 1e-6 * ref[n].Volume
    nurbs = bf.load_step(os.path.join(cases, 'nurbs.step'))
    for n, s in nurbs.items():
        assert {f.Surface.__class__.__name__ for f in s.Faces} == {'BSplineSurface'}, n
    with open(os.path.join(cases, 'inch.step')) as f:
        txt = f.read()
    assert "CONVERSION_BASED_UNIT('INCH'" in txt
    inch = bf.load_step(os.path.join(cases, 'inch.step'))
    for n in ref:
        a, b = ref[n].BoundBox, inch[n].BoundBox
        assert abs(a.XMin - b.XMin) < 1e-6 and abs(a.ZMax - b.ZMax) < 1e-6, n
    assert Part.exportUnits()['write.step.unit'] == 'MM'   # preference restored


# ------------------------------------------------------------------ grids
@pytest.mark.parametrize('n', [10, 100])
def test_grid_formula_and_bruteforce(n):
    base = os.path.join(SAMPLES, 'families', 'bolted_grid_%d' % n)
    exp = load_json(base + '.expected.json')
    L = 2 * int(math.ceil(math.sqrt(n / 2.0)))
    rows = int(math.ceil(n / float(L)))
    assert len(exp['bodies']) == n
    assert exp['totals'] == {'CLJ': n - rows, 'PLF': n - rows}
    shapes = bf.load_step(base + '.step')
    assert list(shapes) == exp['bodies']
    contacts = bf.brute_force_contacts(shapes)
    tab, _ = bf.expected_table(exp)
    assert bf.compare(bf.as_table(contacts), tab) == []


def test_grid_generator_counts():
    import samples_families as sf
    for n in (1, 2, 3, 7, 19, 250, 1001):
        parts, contacts, f = sf.bolted_grid(n)
        assert len(parts) == n
        assert len({p.label for p in parts}) == n
        tot = {}
        for c in contacts:
            tot[c['type']] = tot.get(c['type'], 0) + c['count']
        assert tot.get('PLF', 0) == tot.get('CLJ', 0) == n - f['rows']
