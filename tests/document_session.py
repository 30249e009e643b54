"""Opens an .FCStd in a FreeCAD started as a library by tests/test_documents.py
(its own process, with the HOME the test chose: the workbench installed there
or not), reports what came back as JSON and saves it under a new name.

    /usr/bin/python3 tests/document_session.py IN.FCStd OUT.FCStd REPORT.json [--move-block]

--move-block: then moves the part "Block" away and recomputes (does the
restored analysis still work?). This script imports nothing from contactwb
itself: without the workbench it must not be importable."""
import importlib.util
import json
import sys

sys.path.append("/usr/lib/freecad-python3/lib")
import FreeCAD  # noqa: E402  (FreeCAD before Part)
import Part  # noqa: E402,F401


def plain(value):
    """A property value as JSON (objects by name, quantities by value)."""
    if hasattr(value, "TypeId") and hasattr(value, "Name") and hasattr(value, "Document"):
        return value.Name
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, FreeCAD.Vector):
        return [round(c, 9) for c in value]
    if isinstance(value, FreeCAD.Placement):
        return [plain(value.Base), [round(c, 9) for c in value.Rotation.Q]]
    if hasattr(value, "Value") and hasattr(value, "Unit"):
        return round(value.Value, 9)
    if isinstance(value, float):
        return round(value, 9)
    if isinstance(value, (bool, int, str)) or value is None:
        return value
    return repr(value)


def snapshot(obj):
    skip = {"Proxy", "Shape", "ExpressionEngine"}
    return {name: plain(getattr(obj, name)) for name in obj.PropertiesList if name not in skip}


def proxy_name(obj):
    proxy = getattr(obj, "Proxy", None)
    return None if proxy is None else f"{type(proxy).__module__}.{type(proxy).__name__}"


def main():
    source, target, report_path = sys.argv[1:4]
    report = {"workbench_importable": importlib.util.find_spec("contactwb") is not None}
    doc = FreeCAD.openDocument(source)
    report["objects"] = {obj.Name: {"type": obj.TypeId, "proxy": proxy_name(obj), "state": list(obj.State),
                                    "properties": snapshot(obj),
                                    "volume": round(obj.Shape.Volume, 6) if hasattr(obj, "Shape") else None}
                         for obj in doc.Objects}
    if "--move-block" in sys.argv:
        doc.Block.Placement.Base = FreeCAD.Vector(100, 100, 10)
        doc.recompute()
        analysis = doc.getObject("Contacts")
        report["after_move"] = {"labels": sorted(c.Label for c in analysis.Group),
                                "ContactCount": getattr(analysis, "ContactCount", None),
                                "invalid": [o.Name for o in doc.Objects if "Invalid" in o.State]}
    else:
        doc.saveAs(target)
    FreeCAD.closeDocument(doc.Name)
    with open(report_path, "w") as stream:
        json.dump(report, stream, indent=1)


if __name__ == "__main__":
    main()
