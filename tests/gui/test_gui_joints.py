"""Issue 21 items 9 and 10 in the real FreeCAD GUI under Xvfb
(tests/gui/joints_session.py): the motor's joints labelled, pickable and
selected both ways with the joints panel, the DOF count explained, the
liaison graph zoomable, the joint arrows far from the selection green."""
import math

import pytest

from freecad_session import run_session  # tests/gui is on sys.path

MOTOR_JOINTS = 29


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return run_session(tmp_path_factory, "joints_session.py", "joints_report.json", screen="1400x1050x24",
                       timeout=500)


def no_error(report, *steps):
    for name in steps:
        assert name not in report["errors"], report["errors"][name]


def test_dof_count_explained(run):
    no_error(run, "derive_joints")
    derive = run["derive"]
    assert derive["joints"] == MOTOR_JOINTS and derive["panel"]
    mobility = derive["mobility"]
    # 26 DOF, 9 of them passive spins: which parts spin, and what the other 17 move
    assert mobility[1].startswith("Degrees of freedom: 26 (9 passive spins): 17 that move rigid groups")
    assert ("(Bearing-back, Bearing-front, Rotor-front, Screw-1, Screw-2, Screw-3, Screw-4, Seal, Stator)"
            in mobility[1])
    # the axis turns about and slides along the motor's axis (z through the origin's axis)
    axis = next(line for line in mobility if line.startswith("Rigid group") and ": Axis (" in line)
    assert axis.startswith("Rigid group 2: Axis (cylindrical, 2 DOF): 1 rotation about z through (0, 0, ")
    assert axis.endswith("; 1 translation along z")
    seal = next(line for line in mobility if ": Seal (" in line)
    assert seal.endswith("(prismatic, 1 DOF): 1 translation along z; passive spins: Seal about z")
    assert "Rigid group 2: Axis (cylindrical, 2 DOF)" in derive["mobility_text"]
    # every joint listed with its motions
    assert len(derive["rows"]) == MOTOR_JOINTS
    assert all(" DOF): " in row for row in derive["rows"])


def test_liaison_graph_zooms_with_the_wheel(run):
    no_error(run, "graph_zoom")
    graph = run["graph"]
    assert graph["has_graph"]
    assert graph["scale_open"] == 1.0          # natural size: Graphviz's 14 pt labels, not shrunk to 560 px
    assert graph["scene"][0] > 560
    assert graph["after_2_up"] == pytest.approx(1.25 ** 2)
    assert graph["after_4_down"] == pytest.approx(1.25 ** -2)
    assert graph["actual"] == pytest.approx(1.0)


def test_joint_selected_both_ways_and_highlighted(run):
    no_error(run, "selection_both_ways")
    selection = run["selection"]
    assert selection["selected"] == [selection["joint"]]
    assert selection["highlighted"]
    # every glyph of the selected joint in FreeCAD's selection colour
    assert selection["glyph_colours"] == [selection["selection_colour"]]
    assert selection["rows_selected"] == [selection["other"]]
    assert selection["old_unhighlighted"]


def test_glyphs_labelled_and_pickable(run):
    no_error(run, "glyph_pick_and_labels")
    pick = run["pick"]
    # a point of the seal's arrow picks the seal's joint ...
    assert any(hit[2] == pick["joint"] for hit in pick["hits"]), pick["hits"]
    # ... and a click there selects it, in the view and the panel
    assert pick["clicked"] == [pick["joint"]]
    assert pick["rows_after_click"] == [pick["joint"]]
    for label, texts in pick["labels"]:
        number, kind = label.split(" ", 2)[:2]
        assert texts == [f"{number} {kind.rstrip(':')}"]


def test_joint_arrows_far_from_the_selection_green(run):
    no_error(run, "arrow_colour")
    arrow = run["arrow"]
    for colour in (arrow["translation"], arrow["rotation"]):
        euclidean = math.dist(colour, arrow["selection"])
        channel = max(abs(a - b) for a, b in zip(colour, arrow["selection"]))
        assert euclidean >= 0.4 and channel >= 0.3, (colour, euclidean, channel)


def test_partitions_in_their_contact_types_families_and_legends_apart(run):
    no_error(run, "palette_and_legends")
    palette = run["palette"]
    # planes in the planar fit's hue, cylinders in the cylindrical joint's (every shade)
    for key, hue in palette["hues"].items():
        kind = key.split("/")[0]
        difference = abs((hue - palette["type_hues"][kind] + 180) % 360 - 180)
        assert difference <= 12, (key, hue, palette["type_hues"])
    # adjacent partitions of one type (found with OCCT's edge ancestors) differ in shade
    assert palette["adjacent_pairs"], "the axis has adjacent partitions of one type (its key flat)"
    for label, i, j, (kind_i, shade_i), (kind_j, shade_j) in palette["adjacent_pairs"]:
        assert kind_i == kind_j and shade_i != shade_j, (label, i, j)
    # two analyses' legends and the partitions legend, stacked without overlap
    extents = sorted(palette["legends"].values(), reverse=True)
    assert len(extents) == 3
    for (top, bottom), (next_top, _) in zip(extents, extents[1:]):
        assert next_top < bottom, extents
    assert palette["legends_after_hide"] == 2
