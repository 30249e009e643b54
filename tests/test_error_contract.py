"""The extension's error contract (issue 23): one exception class per
StatusCode, every one a contactcore.ContactsError; argument errors one class
(ArgumentError, also a ValueError) in every binding; keyword options checked
by name; the CLI's exit code of each class."""
import os
import sys

import pytest

from conftest import REPO, SAMPLES

sys.path.append("/usr/lib/freecad-python3/lib")
try:
    import FreeCAD  # noqa: F401  (must come before Part)
    import Part
except ImportError:  # pragma: no cover - depends on the machine
    pytest.skip("FreeCAD's Python modules are not available", allow_module_level=True)

sys.path.insert(0, os.environ.get("CONTACTS_PYTHON_DIR", os.path.join(REPO, "build", "python")))
import contactcore as cc  # noqa: E402

MOTOR = os.path.join(SAMPLES, "motor.step")

# Written out by hand from errors.h: StatusCode -> (class, the classes it
# also derives from besides ContactsError).
EXPECTED = {
    "InvalidInput": ("InputError", ()),
    "ReadError": ("ReadError", ("InputError",)),
    "GeometryError": ("GeometryError", ()),
    "Cancelled": ("Cancelled", ()),
    "InvalidArgument": ("ArgumentError", (ValueError,)),
    "OutOfMemory": ("OutOfMemoryError", (MemoryError,)),
    "Internal": ("InternalError", ()),
}


def test_every_status_code_has_its_own_class():
    codes = {name: code for name, code in cc.StatusCode.__members__.items() if name != "Ok"}
    assert set(codes) == set(EXPECTED)
    assert cc.exception_for(cc.StatusCode.Ok) is None
    assert issubclass(cc.ContactsError, RuntimeError)
    classes = set()
    for name, code in codes.items():
        class_name, also = EXPECTED[name]
        error = cc.exception_for(code)
        assert error is getattr(cc, class_name), name
        assert error.__name__ == class_name and error.__module__ == "contactcore"
        assert issubclass(error, cc.ContactsError), name
        for base in also:
            assert issubclass(error, getattr(cc, base) if isinstance(base, str) else base), (name, base)
        assert error.__doc__, name
        classes.add(error)
    assert len(classes) == len(EXPECTED)
    # Only ReadError is an InputError; nothing else is another code's class.
    for error in classes - {cc.ReadError, cc.InputError}:
        assert not issubclass(error, cc.InputError), error


def test_missing_file_is_a_read_error(tmp_path):
    with pytest.raises(cc.ReadError, match="no such file"):
        cc.read_step(str(tmp_path / "nowhere.step"))


def test_unreadable_brep_is_an_input_error():
    with pytest.raises(cc.InputError, match="unreadable BRep") as raised:
        cc.bodies_from_brep("this is not a BRep", ["a"])
    assert type(raised.value) is cc.InputError


def box_assembly():
    boxes = [Part.makeBox(10, 10, 10), Part.makeBox(10, 10, 5, FreeCAD.Vector(0, 0, 10))]
    return cc.bodies_from_brep(Part.makeCompound(boxes).exportBrepToString(), ["a", "b"])


def test_cancelled_by_the_progress_callback():
    with pytest.raises(cc.Cancelled):
        cc.find_contacts(box_assembly(), progress=lambda stage, fraction: False)


def test_argument_errors_are_one_class_in_every_binding():
    """Before: InputError from simulation_models, plain ValueError from the
    collision binding, ArgumentError from find_contacts."""
    assembly = box_assembly()
    cases = {
        "check_solids": lambda: cc.find_contacts(assembly, check_solids="fast"),
        "envelope": lambda: cc.simulation_models(assembly, feature_size=1.0, envelope=0.0),
        "body number": lambda: cc.simulation_models(assembly, bodies=[5]),
    }
    (mesh,) = [r.mesh for r in cc.mesh_assembly(box_assembly())][:1]
    pair = cc.CollisionPair(cc.build_collision_model(mesh), cc.build_collision_model(mesh))
    cases["query kind"] = lambda: pair.query(kind="sideways")
    cases["placement"] = lambda: pair.query(place_a=((1, 0, 0), (0, 0, 0)))
    for what, call in cases.items():
        with pytest.raises(cc.ArgumentError) as raised:
            call()
        assert type(raised.value) is cc.ArgumentError, what
        assert isinstance(raised.value, ValueError), what


def test_pair_query_still_answers():
    (mesh,) = [r.mesh for r in cc.mesh_assembly(box_assembly())][:1]
    pair = cc.CollisionPair(cc.build_collision_model(mesh), cc.build_collision_model(mesh))
    far = ((1, 0, 0, 0, 1, 0, 0, 0, 1), (100, 0, 0))
    result = pair.query(place_b=far, kind="distance")
    assert not result.intersecting
    assert result.distance == pytest.approx(90.0)


@pytest.fixture(scope="module")
def motor_scene():
    if not hasattr(cc, "haptics"):
        pytest.skip("this build has no haptic trials")
    return cc.haptics.TrialScene(cc.read_step(MOTOR), "Axis")


SCRIPT = {"hand": [{"t": 0.0, "translate": [0, 0, 0]}, {"t": 0.01, "translate": [0, 0, 0]}]}


def test_misspelt_servo_option_is_named(motor_scene):
    with pytest.raises(cc.ArgumentError, match="'stifness'"):
        cc.haptics.run_trial(motor_scene, SCRIPT, stifness=2.0)
    with pytest.raises(cc.ArgumentError, match="'rate'"):
        cc.haptics.HapticSession(motor_scene, rate=500.0)
    # Spelt right, the same option is taken.
    result = cc.haptics.run_trial(motor_scene, SCRIPT, settle=0.0, rate_hz=500.0, stiffness=2.0)
    # Lockstep: the measured rate is null (issue 20's honest metrics); the ticks say the period.
    assert result.mode == "lockstep" and result.rate_hz is None
    assert result.sim_time_s == pytest.approx(result.ticks / 500.0)


def test_bad_trial_script_is_an_argument_error(motor_scene):
    with pytest.raises(cc.ArgumentError, match="'hand'"):
        cc.haptics.run_trial(motor_scene, {"start": {}})
    with pytest.raises(cc.ArgumentError, match="unknown device"):
        cc.haptics.HapticSession(motor_scene, device="joystick")


def test_cli_exit_code_of_an_internal_error(monkeypatch, capsys):
    """InternalError (a C++ exception the core did not expect) is the CLI's
    exit 5; a GeometryError stays exit 4."""
    from contactwb.cli import contacts as cli
    from contactwb.core import analysis

    def fail_with(error):
        def find(*args, **kwargs):
            raise error("the core's own message")
        return find

    monkeypatch.setattr(analysis, "find_contacts_in_step", fail_with(cc.InternalError))
    assert cli.main([MOTOR]) == 5
    assert "internal error (the core's own message)" in capsys.readouterr().err
    monkeypatch.setattr(analysis, "find_contacts_in_step", fail_with(cc.GeometryError))
    assert cli.main([MOTOR]) == 4
    monkeypatch.setattr(analysis, "find_contacts_in_step", fail_with(cc.ReadError))
    assert cli.main([MOTOR]) == 3


def test_every_result_field_is_documented():
    """Results are classes whose every field says what it holds (and its
    unit): all classes of the module except the haptics submodule's."""
    undocumented = []
    classes = [value for value in vars(cc).values()
               if isinstance(value, type) and not issubclass(value, BaseException)
               and not hasattr(value, "__members__")]  # enums document themselves by name
    assert len(classes) >= 30
    for cls in classes:
        for name, attribute in vars(cls).items():
            if isinstance(attribute, property) and not name.startswith("_") and not (attribute.__doc__ or "").strip():
                undocumented.append(f"{cls.__name__}.{name}")
    assert undocumented == []
