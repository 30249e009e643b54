"""Issue 25, the fuzz_brep hang: a FreeCAD document whose two bodies are the
fuzzer's damaged ball and cup (fuzz/regressions/fuzz_brep/
open_wire_face_face_intersection_hang.brep). Before the fix a contact test's
Boolean between them never returned (OCCT's face-face intersection, polling
no progress); the ball's sphere face has a boundary that does not close.
Through the path the workbench uses (FreeCAD's shapes, one BRep compound into
the core), every command refuses it in seconds with exit 3, naming the file,
the body and the face."""
import os
import subprocess
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HANG_INPUT = os.path.join(REPO, "fuzz", "regressions", "fuzz_brep", "open_wire_face_face_intersection_hang.brep")
CLI = [sys.executable, "-m", "contactwb.cli"]
BOUND = 60  # seconds: a hang fails the test (the refusal itself takes under a second after FreeCAD's start)
MESSAGE = ("damaged topology: the face's boundary does not close (wire 1 has 2 loose end(s)); "
           "OCCT's Booleans may never return on such a face")

# Written by FreeCAD in a process of its own: the damaged compound's two solids as Part::Features.
MAKE_DOCUMENT = """
import sys
sys.path.insert(0, {repo!r})
from contactwb.document import freecad_setup
FreeCAD = freecad_setup.import_freecad()
import Part
compound = Part.read({brep!r})
doc = FreeCAD.newDocument("BallInCup")
for name, shape in zip(("Ball", "Cup"), compound.childShapes()):
    doc.addObject("Part::Feature", name).Shape = shape
doc.recompute()
doc.saveAs({out!r})
"""


def environment():
    env = dict(os.environ)
    env["PYTHONPATH"] = REPO + os.pathsep + env.get("PYTHONPATH", "")
    return env


@pytest.fixture(scope="module")
def document(tmp_path_factory):
    out = str(tmp_path_factory.mktemp("open_wire") / "ball_in_cup_hang.FCStd")
    subprocess.run([sys.executable, "-c", MAKE_DOCUMENT.format(repo=REPO, brep=HANG_INPUT, out=out)],
                   check=True, capture_output=True, timeout=120, env=environment())
    return out


@pytest.mark.parametrize("command", [[], ["--json"], ["--disassembly"], ["mesh", "--out", "{tmp}/meshes"]])
def test_every_command_refuses_the_hang_document_naming_body_and_face(document, tmp_path, command):
    argv = [a.format(tmp=tmp_path) for a in command]
    argv = argv[:1] + [document] + argv[1:] if argv[:1] == ["mesh"] else [document] + argv
    done = subprocess.run(CLI + argv, capture_output=True, timeout=BOUND, env=environment())
    err = done.stderr.decode()
    assert done.returncode == 3, err
    assert MESSAGE in err
    assert "body 'Ball'" in err and "Face1" in err and "ball_in_cup_hang.FCStd" in err, err
    assert "Traceback" not in err
    assert done.stdout == b""
    assert not (tmp_path / "meshes" / "meshes.json").exists()
