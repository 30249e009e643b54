"""pytest setup: FreeCAD as a library (FreeCAD before Part), the workbench
from this checkout and the extension from the build folder."""
import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED_DATA = os.path.join(os.path.dirname(REPO), "shared", "data")
SAMPLES = os.path.join(REPO, "Resources", "samples")

sys.path.insert(0, REPO)
os.environ.setdefault("CONTACTS_PYTHON_DIR", os.path.join(REPO, "build", "python"))

from contactwb import freecad_setup  # noqa: E402

freecad_setup.import_freecad()


@pytest.fixture(scope="session")
def shared_step():
    """Path of a file of ../shared/data/step; skips when the folder is absent."""
    def locate(name):
        path = os.path.join(SHARED_DATA, "step", name)
        if not os.path.isfile(path):
            pytest.skip(f"shared data absent: {path}")
        return path
    return locate


@pytest.fixture(scope="session")
def shared_fcstd():
    def locate(name):
        path = os.path.join(SHARED_DATA, "fcstd", name)
        if not os.path.isfile(path):
            pytest.skip(f"shared data absent: {path}")
        return path
    return locate


@pytest.fixture(scope="session")
def sample():
    def locate(name):
        path = os.path.join(SAMPLES, name)
        assert os.path.isfile(path), f"bundled sample missing: {path} (make samples)"
        return path
    return locate
