"""Render the motor sample (assembled and exploded) to docs/images/motor_*.png.

Run with the FreeCAD GUI under a virtual X server:
    QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a -s '-screen 0 1280x1024x24' \
        freecad tools/render_motor.py
The exploded view only moves the objects in memory; motor.FCStd is not modified.
"""
import os
import sys
import traceback

import FreeCAD
import FreeCADGui

HERE = os.path.dirname(os.path.abspath(__file__)) if '__file__' in globals() else os.getcwd()
REPO = os.path.dirname(HERE) if os.path.basename(HERE) == 'tools' else HERE
SRC = os.path.join(REPO, 'Resources', 'samples', 'motor.FCStd')
OUT = os.path.join(REPO, 'docs', 'images')
W, H = 800, 600

# offsets along the motor axis (+Z towards the output shaft), mm
EXPLODE_Z = {
    'Back-cover': -32, 'Bearing-back': -14, 'Body': 0, 'Stator': 0,
    'Axis': 42, 'Rotor-back': 42, 'Rotor-front': 48, 'Magnet': 42,
    'Bearing-front': 66, 'Front-cover': 80, 'Seal': 98, 'Screw': 112,
}
MAGNET_RADIAL = 12.0


def _settle(n=20):
    for _ in range(n):
        FreeCADGui.updateGui()


def _offset(label):
    for key, dz in EXPLODE_Z.items():
        if label == key or label.startswith(key + '-') and key in ('Magnet', 'Screw'):
            return dz
    return 0


def main():
    doc = FreeCAD.openDocument(SRC)
    FreeCADGui.activateWorkbench('PartWorkbench')
    _settle()
    gdoc = FreeCADGui.getDocument(doc.Name)
    for o in doc.Objects:
        vo = gdoc.getObject(o.Name)
        if vo is None:
            continue
        vo.Visibility = True    # documents saved headless have no GuiDocument.xml
        if 'PartColor' in o.PropertiesList:
            c = o.PartColor
            vo.ShapeColor = (c[0], c[1], c[2])
        vo.LineColor = (0.1, 0.1, 0.1)
        vo.Deviation = 0.1
    view = FreeCADGui.activeDocument().activeView()
    try:
        FreeCADGui.getMainWindow().resize(1200, 900)
    except Exception:
        pass
    os.makedirs(OUT, exist_ok=True)
    view.viewIsometric()
    view.fitAll()
    _settle()
    view.saveImage(os.path.join(OUT, 'motor_assembled.png'), W, H, 'White')
    for o in doc.Objects:
        if not hasattr(o, 'Placement'):
            continue
        dz = _offset(o.Label)
        pl = o.Placement
        base = pl.Base + FreeCAD.Vector(0, 0, dz)
        if o.Label.startswith('Magnet-'):
            # push magnets radially out of the rotor (their seat direction)
            d = pl.Rotation.multVec(FreeCAD.Vector(1, 0, 0))
            base = base + d * MAGNET_RADIAL
        o.Placement = FreeCAD.Placement(base, pl.Rotation)
    doc.recompute()
    view.viewIsometric()
    view.fitAll()
    _settle()
    view.saveImage(os.path.join(OUT, 'motor_exploded.png'), W, H, 'White')
    FreeCAD.closeDocument(doc.Name)


try:
    main()
    print('render_motor: wrote', OUT)
    code = 0
except Exception:
    traceback.print_exc()
    code = 1
sys.stdout.flush()
os._exit(code)
