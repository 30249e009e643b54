#!/usr/bin/python3
"""Generate the sample assemblies with known contacts (headless FreeCAD).

    /usr/bin/python3 tools/make_samples.py                       # everything committed
    /usr/bin/python3 tools/make_samples.py --only motor          # motor only
    /usr/bin/python3 tools/make_samples.py --only families       # grids 10/100 + cases
    /usr/bin/python3 tools/make_samples.py --only cases          # contact-type + hard cases
    /usr/bin/python3 tools/make_samples.py --grid 10000 --out build/samples   # one grid

Outputs (default --out Resources/samples):
    motor.step / motor.FCStd / motor.expected.json
    families/bolted_grid_N.{step,FCStd,expected.json}   (N = 10, 100)
    cases/NAME.{step,FCStd,expected.json}

Every STEP file has one product per part (product name = part name); the .FCStd beside
it has one Part::Feature per part (Label = name, global Placement) and is what
tests/bruteforce_contacts.py reads when names matter. The expected JSON schema is
described in samples_common.write_expected (and docs in the JSON itself).
"""
import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
if HERE not in sys.path:
    sys.path.insert(0, HERE)

import samples_common as sc  # noqa: E402  (imports FreeCAD then Part)

REPO = os.path.dirname(HERE)
STEP_NAMES = ('one PRODUCT and one NEXT_ASSEMBLY_USAGE_OCCURRENCE per part, both named after '
              'the part; Part.read returns the solids in this order')
STEP_NAMES_SHARED = ('parts of one kind share one PRODUCT (named after its first instance); the part '
                     'names are the NEXT_ASSEMBLY_USAGE_OCCURRENCE names, in Part.read solid order')


def make_motor(out):
    import samples_motor as sm
    t = time.time()
    parts = sm.motor_parts()
    sc.export_assembly(parts, out, 'motor')
    sc.write_expected(os.path.join(out, 'motor.expected.json'), 'motor', sm.NAMES,
                      sm.motor_expected(), notes=sm.MOTOR_NOTES, extra={'step_names': STEP_NAMES})
    return time.time() - t


def make_grid(n, out, fcstd=True):
    import samples_families as sf
    t = time.time()
    parts, contacts, formula = sf.bolted_grid(n)
    name = 'bolted_grid_%d' % n
    t_build = time.time() - t
    tm = {}
    sc.export_assembly(parts, out, name, write_fcstd=fcstd, share_shapes=True, timings_out=tm)
    tm['build'] = t_build
    sc.write_expected(os.path.join(out, name + '.expected.json'), name, [p.label for p in parts],
                      contacts, extra={'formula': formula, 'step_names': STEP_NAMES_SHARED})
    return time.time() - t, tm


def make_cases(out, only=None):
    import samples_families as sf
    t = time.time()
    for name, builder in sf.CASES.items():
        if only and name not in only:
            continue
        parts, contacts, notes, unit = builder()
        sc.export_assembly(parts, out, name, unit=unit)
        sc.write_expected(os.path.join(out, name + '.expected.json'), name,
                          [p.label for p in parts], contacts, notes=notes,
                          extra={'step_unit': unit or 'MM', 'step_names': STEP_NAMES})
    return time.time() - t


def _fmt(tm):
    return ', '.join('%s %.2fs' % (k, tm[k]) for k in ('build', 'objects', 'import_export', 'fcstd') if k in tm)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--out', default=os.path.join(REPO, 'Resources', 'samples'))
    ap.add_argument('--only', choices=['motor', 'families', 'grids', 'cases'], action='append',
                    help='generate only these groups (repeatable)')
    ap.add_argument('--grid', type=int, action='append',
                    help='generate bolted_grid_N directly into --out (no other output)')
    ap.add_argument('--no-fcstd', action='store_true', help='with --grid: STEP + JSON only')
    args = ap.parse_args(argv)
    out = os.path.abspath(args.out)
    if args.grid:
        for n in args.grid:
            total, tm = make_grid(n, out, fcstd=not args.no_fcstd)
            print('bolted_grid_%d: %.2fs (%s) -> %s' % (n, total, _fmt(tm), out))
        return 0
    only = set(args.only or ['motor', 'families'])
    if 'families' in only:
        only |= {'grids', 'cases'}
    if 'motor' in only:
        print('motor: %.2fs' % make_motor(out))
    if 'grids' in only:
        for n in (10, 100):
            total, tm = make_grid(n, os.path.join(out, 'families'))
            print('bolted_grid_%d: %.2fs (%s)' % (n, total, _fmt(tm)))
    if 'cases' in only:
        print('cases: %.2fs' % make_cases(os.path.join(out, 'cases')))
    return 0


if __name__ == '__main__':
    sys.exit(main())
