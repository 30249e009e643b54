"""Issue 21 item 7 in the real FreeCAD GUI under Xvfb (tests/gui/table_session.py):
the contact table at 500 contacts on a generated grid of blocks and pins.
Expected values are derived by hand from the grid: 16 x 16 blocks of
10 x 10 x 6 mm side by side share 2 x 16 x 15 = 480 whole 10 x 6 faces
(PLF), and 20 pins of radius 2 in bores of radius 2 make 20 CLJ."""
import pytest

from freecad_session import run_session  # tests/gui is on sys.path

PLF_COUNT = 2 * 16 * 15
CLJ_COUNT = 20


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    report = run_session(tmp_path_factory, "table_session.py", "table_report.json", screen="1400x1050x24",
                         timeout=560)
    print("\nGUI step times (s, Xvfb):", report["times"])
    return report


def no_error(report, *steps):
    for name in steps:
        assert name not in report["errors"], report["errors"][name]


def test_grid_has_500_contacts(run):
    no_error(run, "open_grid", "find_contacts")
    assert run["find"]["accepted"]
    assert run["find"]["by_type"] == {"PLF": PLF_COUNT, "CLJ": CLJ_COUNT}
    assert run["find"]["count"] == PLF_COUNT + CLJ_COUNT


def test_table_opens_sorted_by_type_then_pair(run):
    no_error(run, "table_at_500")
    table = run["table"]
    assert table["rows"] == PLF_COUNT + CLJ_COUNT
    assert table["sort_column"] == 1
    order = [tuple(entry) for entry in table["order"]]
    # the types in the table's (the paper's) order: PLF before CLJ; pairs by name within a type
    rank = {"PLF": 0, "CLJ": 1}
    assert order == sorted(order, key=lambda e: (rank[e[0]], e[1], e[2], e[3]))


def test_summary_in_its_own_pane_and_the_table_keeps_its_rows(run):
    table = run["table"]
    assert "By pair" in table["summary"] and "PLF: 480" in table["summary"]
    # 480 pairs listed, yet the table shows many rows and the summary pane stays small
    assert table["table_rows_shown"] >= 12, table
    assert table["summary_height"] <= 0.35 * table["widget_height"], table
    # folded, the summary gives the table its room
    assert table["folded_rows_shown"] > table["table_rows_shown"]
    assert table["folded_summary_height"] < 40


def test_dock_leaves_the_3d_view_its_room(run):
    table = run["table"]
    assert table["dock_area"] == 2  # Qt.RightDockWidgetArea
    assert table["dock_width"] <= 0.35 * table["main_width"], table
    assert table["view_width"] >= 0.5 * table["main_width"], table
    assert table["view_width"] >= 600


def test_plane_contacts_show_their_extent(run):
    cells = run["table"]["cells"]
    # a PLF: no span, no radius, its common face's 10 x 6 mm (FreeCAD's Standard schema, 2 decimals)
    assert cells["PLF"] == [["", "", "10.00 mm \u00d7 6.00 mm"]]
    # a pin's CLJ: the whole turn, its radius, no plane extent
    assert cells["CLJ"] == [["360.00 \u00b0", "2.00 mm", ""]]
    assert run["table"]["headers"][4:8] == ["Area", "Span / DOF", "Radius", "Extent"]


@pytest.mark.parametrize("kind", ["PLF", "CLJ"])
def test_zoom_to_frames_the_contact(run, kind):
    no_error(run, "zoom_to")
    zoom = run["zoom"][kind]
    width, height = zoom["size"]
    xmin, ymin, xmax, ymax = zoom["after"]
    # the whole box on the screen ...
    assert 0 <= xmin and xmax <= width and 0 <= ymin and ymax <= height, zoom
    # ... filling a good part of it (the whole grid was in view before: a few per cent)
    span = max(xmax - xmin, ymax - ymin)
    before = zoom["before"]
    assert span >= 0.3 * min(width, height), zoom
    assert span >= 4 * max(before[2] - before[0], before[3] - before[1]), zoom
    assert zoom["undo"] == ["Find contacts"]  # view only


def test_isolate_ghosts_everything_else_and_shows_the_contact(run):
    no_error(run, "isolate")
    isolate = run["isolate"]
    assert isolate["pair"] == ["Block-07-08", "Block-08-08"]
    assert len(isolate["shown"]) == isolate["parts"]  # nothing hidden: everything else ghosted
    assert isolate["transparency"] == [85]  # the two parts see-through (actions.GHOST_TRANSPARENCY)
    assert isolate["others_transparency"] == [95]  # the others fainter (actions.ISOLATE_OTHERS_TRANSPARENCY)
    assert isolate["contacts_shown"] == [isolate["contact"]] and isolate["overlay_visible"] is True
    # the paint, hidden inside the opaque blocks before (the legend's text only), shows through the ghosted ones
    assert isolate["before_pixels"] < 0.01 * isolate["image_pixels"], isolate
    assert isolate["after_pixels"] - isolate["before_pixels"] > 0.05 * isolate["image_pixels"], isolate
    assert isolate["undo_same"]
    # Show all: every part and contact back, opaque
    assert isolate["after_show_all"] == {"hidden": 0, "transparency": [0], "contacts_shown": PLF_COUNT + CLJ_COUNT}
