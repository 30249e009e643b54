"""GUI tests: the real FreeCAD GUI under Xvfb, with the workbench installed in
a throwaway home, driven by tests/gui/gui_session.py."""
import csv
import json
import os

import pytest

from freecad_session import REPO, run_session  # tests/gui is on sys.path

ORANGE = (255, 140, 26)  # the highlight colour of the workbench's icons
SO_SWITCH_NONE, SO_SWITCH_ALL = -1, -3  # Coin's SoSwitch.whichChild values
MOTOR_CONTACTS = 35


def hex_rgb(colour):
    return tuple(int(colour[i:i + 2], 16) for i in (1, 3, 5))


def count_near(image, colour, tolerance=50):
    """Pixels within `tolerance` of `colour` on every channel."""
    return sum(1 for p in image.getdata() if max(abs(a - b) for a, b in zip(p, colour)) < tolerance)


@pytest.fixture(scope="module")
def gui_report(tmp_path_factory):
    report = run_session(tmp_path_factory, "gui_session.py", "gui_report.json",
                         {"CONTACTS_SAMPLE": os.path.join(REPO, "Resources", "samples", "motor.FCStd")})
    assert not report["errors"], "\n".join(report["errors"])
    return report


def test_workbench_is_listed_and_activates(gui_report):
    assert gui_report["workbench_listed"]
    assert gui_report["active_workbench"] == "ContactsWorkbench"


def test_toolbar_shows_only_working_commands(gui_report):
    assert gui_report["toolbar_visible"]
    assert gui_report["toolbar_actions"] == [
        "Find contacts...", "Contact table", "Isolate contact", "Show all", "Ghost parts",
        "Show partitions", "Derive joints", "Joints and liaison graph", "Export contacts...", "Open sample motor",
        "Import STEP assembly...",
        "Show simulation model"]


def test_find_contacts_command_fills_the_tree(gui_report):
    assert gui_report["panel_scope"] == "Document"
    assert gui_report["analyses"] == 1
    assert gui_report["contacts"] == 35
    assert sorted(gui_report["summary"]) == ["CLJ: 21", "PLF: 14"]
    assert "Find contacts" in gui_report["undo_names"]
    assert gui_report["selected_faces"] >= 2


def test_screenshot_shows_the_toolbar(gui_report):
    from PIL import Image
    window_png, view_png = gui_report["screenshots"]
    image = Image.open(window_png).convert("RGB")
    scale = image.width / gui_report["window_width"]
    x, y, w, h = (round(v * scale) for v in gui_report["first_button_rect"])
    button = image.crop((x, y, x + w, y + h))
    orange = sum(1 for p in button.getdata() if all(abs(a - b) < 40 for a, b in zip(p, ORANGE)))
    assert orange >= 10, f"the Find contacts icon is not visible at {x},{y} in {window_png}"
    view = Image.open(view_png).convert("RGB")
    colours = len(set(view.resize((100, 75)).getdata()))
    assert colours > 20, f"the 3D view looks empty: {view_png}"


def test_overlay_draws_every_contact_face(gui_report):
    overlay = gui_report["overlay"]
    assert overlay["provider"] == "ViewProviderContactAnalysis"
    assert overlay["child_providers"] == ["ViewProviderContact"]
    assert overlay["contacts_drawn"] == MOTOR_CONTACTS
    assert overlay["layers"] == ["Contacts_CLJ", "Contacts_PLF"]  # one per type present, no partial
    assert overlay["face_sets"] == 2 * MOTOR_CONTACTS           # both sides of every contact
    # every contact painted as the area its two sides share (bug 7: not whole faces)
    assert overlay["common_contacts"] == MOTOR_CONTACTS
    assert overlay["triangles"] == overlay["proxy_triangles"] > 1000
    assert overlay["line_sets"] == 0  # contact circles only for LAF and SPT


def test_overlay_follows_visibility_and_selection(gui_report):
    first, second = gui_report["contact_names"]
    assert gui_report["hidden_contact_switch"] == SO_SWITCH_NONE
    assert gui_report["other_contact_switch"] == 0
    assert gui_report["shown_again_switch"] == 0
    assert gui_report["group_hidden_switch"] == SO_SWITCH_NONE
    assert gui_report["group_shown_switch"] == SO_SWITCH_ALL
    # a side is drawn while its body is shown
    assert 0 < gui_report["sides_shown"] < gui_report["sides_shown_all_bodies"] == 2 * MOTOR_CONTACTS
    assert gui_report["highlight_tree"] == [second]
    assert gui_report["highlight_faces"] == [first]
    assert gui_report["highlight_cleared"] == []


def test_screenshot_shows_the_contact_colours(gui_report):
    from PIL import Image
    legend = gui_report["legend"]
    assert legend["PLF"] == "#ff8c1a"
    assert len(set(legend.values())) == len(legend) == 7
    shown = Image.open(gui_report["contacts_png"]).convert("RGB")
    hidden = Image.open(gui_report["no_contacts_png"]).convert("RGB")
    for kind, least in (("PLF", 10000), ("CLJ", 2000)):
        colour = hex_rgb(legend[kind])
        assert count_near(shown, colour) >= least, f"too few {kind} pixels in {gui_report['contacts_png']}"
        # the same view with the analysis hidden: the colour came from the overlay
        assert count_near(hidden, colour) < 50, f"{kind} colour without the overlay in {gui_report['no_contacts_png']}"


def test_contact_icons_use_the_legend(gui_report):
    for kind, path in gui_report["icons"].items():
        assert os.path.basename(path) == f"Contacts_{kind}.svg"
        with open(path) as stream:
            assert gui_report["legend"][kind] in stream.read().lower()


def test_export_command_and_files(gui_report):
    assert gui_report["export_active_before"] is False
    assert gui_report["export_active"] is True
    json_path, json_count = gui_report["exports"]["json"]
    csv_path, csv_count = gui_report["exports"]["csv"]
    assert json_count == csv_count == MOTOR_CONTACTS
    with open(json_path) as stream:
        data = json.load(stream)
    assert data["totals"] == {"CLJ": 21, "PLF": 14}
    assert len(data["contacts"]) == MOTOR_CONTACTS
    with open(csv_path, newline="") as stream:
        rows = list(csv.DictReader(stream))
    assert [(r["type"], r["a"], r["b"]) for r in rows] == [(c["type"], c["a"], c["b"]) for c in data["contacts"]]


def test_reopened_document_draws_the_contacts_again(gui_report):
    reopened, first = gui_report["reopened"], gui_report["overlay"]
    assert reopened["provider"] == "ViewProviderContactAnalysis"
    assert reopened["child_providers"] == ["ViewProviderContact"]
    assert reopened["contacts_drawn"] == MOTOR_CONTACTS
    assert reopened["face_sets"] == first["face_sets"]
    assert reopened["proxy_faces"] == first["proxy_faces"]
    assert reopened["triangles"] > 1000


def test_overlay_follows_moved_bodies(gui_report):
    from PIL import Image
    low, high = gui_report["z_range_assembled"]
    exploded_low, exploded_high = gui_report["z_range_exploded"]
    # screws moved up 112 mm (their top face at 56 before), back cover down 32:
    # their contact faces went along
    assert exploded_high > high + 90
    assert exploded_low < low - 25
    picture = Image.open(gui_report["exploded_png"]).convert("RGB")
    for kind in ("PLF", "CLJ"):
        assert count_near(picture, hex_rgb(gui_report["legend"][kind])) >= 2000, gui_report["exploded_png"]
