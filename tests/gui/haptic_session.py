"""Runs inside the FreeCAD GUI (freecad tests/gui/haptic_session.py under Xvfb).

Opens the bundled motor, selects its Axis, opens the haptic trial panel
(Contacts_HapticTrial), plays the scripted insertion of the axis into its
bearings in real time (the 1 kHz loop on its thread, the panel at 30 Hz),
records the path, takes screenshots on the way and at the end, commits with
OK, checks the undo, and writes what it saw to $CONTACTS_GUI_RESULT."""
import json
import os
import sys

import FreeCAD
import FreeCADGui
from PySide2 import QtWidgets

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # the shared session helpers
import session_helpers  # noqa: E402
from session_helpers import wait  # noqa: E402

out_dir = os.environ["CONTACTS_GUI_OUT"]
report = {"errors": []}


def placement_offset(placement):
    return [placement.Base.x, placement.Base.y, placement.Base.z], list(placement.Rotation.toEuler())


def save_view(name):
    path = os.path.join(out_dir, name)
    FreeCADGui.activeDocument().activeView().saveImage(path, 800, 600, "White")
    return path


def grab_window_with_view(name):
    path, pasted = session_helpers.grab_window_with_view(out_dir, name)
    if pasted:
        report["view_pasted"] = True
    return path


def pick_joints(doc, axis):
    """Reopens the panel, holds the axis to a chosen joint (not the one found)
    and checks that the running loop holds it there, then back to the found one."""
    panel = session_helpers.open_haptic_panel(axis)
    report["joint_choices"] = [c["label"] for c in panel.joint_choices]
    report["joint_combo_items"] = [panel.joint_combo.itemText(i) for i in range(panel.joint_combo.count())]
    wait(0.3)
    found = panel.session.snapshot()
    report["found_joint"] = {"held": found.held, "with": found.joint_with, "joint": found.joint}
    index = next(i for i, c in enumerate(panel.joint_choices) if c["with"] == "Bearing-back")
    panel.joint_combo.setCurrentIndex(index + 1)  # as the user does
    wait(0.3)
    chosen = panel.session.snapshot()
    report["chosen_joint"] = {"held": chosen.held, "with": chosen.joint_with, "joint": chosen.joint,
                              "axis": chosen.joint_axis, "point": chosen.joint_point,
                              "label": panel.joint_label.text()}
    # The hand pulls it out along the axis and sideways: held, it slides out on the chosen axis.
    panel.session.set_hand_target([0.2, 0.1, 12.0], [0.0, 0.0, 0.0])
    # Real time: how far it gets in a given wall time depends on the machine's load (a tick in
    # contact costs ms here), so wait until it has slid out to the hand, 20 s at most.
    for _ in range(200):
        wait(0.1)
        pulled = panel.session.snapshot()
        if pulled.translate[2] > 11.95:
            break
    report["chosen_pulled"] = {"translate": pulled.translate, "rotate_deg": pulled.rotate_deg,
                               "held": pulled.held}
    FreeCADGui.activeDocument().activeView().fitAll()
    report["picker_png"] = grab_window_with_view("haptic_trial_joint_picker.png")
    panel.choose_joint(None)
    wait(0.3)
    back = panel.session.snapshot()
    report["released_joint"] = {"held": back.held, "with": back.joint_with}
    panel.reject()
    FreeCADGui.updateGui()


def containers():
    """A block inside a turned App::Part and a link to it: the panel picks each
    through its selection path and commits the placement to the right object,
    in its own (local) frame."""
    from contactwb import bodies as document_bodies
    from contactwb.gui import haptic_panel
    doc = FreeCAD.newDocument("Containers")
    part = doc.addObject("App::Part", "Assembly")
    part.Placement = FreeCAD.Placement(FreeCAD.Vector(100, 0, 0), FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 90))
    plate = doc.addObject("Part::Box", "Plate")
    plate.Length, plate.Width, plate.Height = 40, 40, 5
    plate.Placement.Base = FreeCAD.Vector(-20, -15, -5)
    block = doc.addObject("Part::Box", "Block")
    block.Placement.Base = FreeCAD.Vector(0, 5, 0)
    part.addObject(plate)
    part.addObject(block)
    link = doc.addObject("App::Link", "BlockLink")
    link.LinkedObject = block
    link.Placement = FreeCAD.Placement(FreeCAD.Vector(0, 0, 50), FreeCAD.Rotation())
    doc.recompute()
    FreeCADGui.activeDocument().activeView().viewIsometric()
    FreeCADGui.activeDocument().activeView().fitAll()
    block_local = FreeCAD.Placement(block.Placement)

    def move(selection, subname, hand):
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(selection, subname) if subname else FreeCADGui.Selection.addSelection(selection)
        FreeCADGui.runCommand("Contacts_HapticTrial")
        wait(0.5)
        panel = haptic_panel.active_panel
        FreeCADGui.Selection.clearSelection()
        panel.session.set_hand_target(hand, [0, 0, 0])
        wait(1.5)
        shot = grab_window_with_view(f"haptic_trial_{selection.Name.lower()}.png")
        seen = {"object": panel.obj.Name, "global_move": panel.session.snapshot().translate, "png": shot}
        panel.accept()
        FreeCADGui.updateGui()
        return seen

    # The block, picked inside the part: a global +5 mm along x is -5 mm along its local y.
    seen = move(part, "Block.", [5, 0, 0])
    report["container_block"] = dict(seen, local=list(block.Placement.Base),
                                     local_angle=block.Placement.Rotation.Angle, link=list(link.Placement.Base))
    import Part
    report["container_block"]["global_base"] = list(Part.getShape(part, "Block.", needSubElement=False,
                                                                  transform=True).Placement.Base)
    report["container_block"]["expected_local"] = list(block_local.Base + FreeCAD.Vector(0, -5, 0))
    doc.undo()
    report["container_undo"] = (block.Placement.Base - block_local.Base).Length < 1e-9
    # The link: its own placement moves, not the block it shows.
    seen = move(link, "", [0, 3, 0])
    report["container_link"] = dict(seen, link=list(link.Placement.Base), block=list(block.Placement.Base))
    # Through a link to the container, the block is every instance's original: refused, with why.
    part_link = doc.addObject("App::Link", "AssemblyLink")
    part_link.LinkedObject = part
    part_link.Placement.Base = FreeCAD.Vector(0, 200, 0)
    doc.recompute()
    _, bodies = document_bodies.assembly_from_document(doc)
    try:
        haptic_panel._body_to_move(bodies, (part_link, "Block."))
        report["linked_container_refused"] = ""
    except Exception as error:  # ContactsError
        report["linked_container_refused"] = str(error)


def run():
    main = FreeCADGui.getMainWindow()
    doc = session_helpers.open_sample_in_workbench()
    axis = next(o for o in doc.Objects if o.Label == "Axis")
    for o in doc.Objects:  # show the shaft and what it goes through, cut open by hiding the rest
        if o.Label in ("Body", "Stator", "Front-cover", "Back-cover") or o.Label.startswith(("Screw", "Magnet")):
            o.ViewObject.Visibility = False
    view = FreeCADGui.activeDocument().activeView()
    view.viewFront()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(axis)
    original = FreeCAD.Placement(axis.Placement)
    report["command_listed"] = "Contacts_HapticTrial" in FreeCADGui.listCommands()
    FreeCADGui.runCommand("Contacts_HapticTrial")
    wait(0.5)
    from contactwb.gui import haptic_panel
    panel = haptic_panel.active_panel
    report["panel_open"] = panel is not None
    if panel is None:
        return
    report["device_message"] = panel.device_message.text()
    report["stiffness_max"] = panel.stiffness_spin.maximum()
    with open(os.environ["CONTACTS_TRIAL_SCRIPT"]) as stream:
        script = json.load(stream)
    dock = next((d for d in main.findChildren(QtWidgets.QDockWidget) if d.windowTitle() == "Combo View"), None)
    if dock is not None:
        from PySide2 import QtCore
        main.resizeDocks([dock], [430], QtCore.Qt.Horizontal)
    panel.start_recording()
    panel.play_script(script)
    wait(0.1)
    FreeCADGui.Selection.clearSelection()  # the axis in its own colour, not the selection's
    view.fitAll()
    wait(1.1)
    report["mid_offset"] = placement_offset(axis.Placement)[0]
    report["mid_joint"] = panel.joint_label.text()
    report["mid_png"] = save_view("haptic_trial_mid.png")
    report["panel_png"] = grab_window_with_view("haptic_trial_panel.png")
    while not panel.script_done():
        wait(0.05)
    wait(2.0)  # settle
    report["readouts"] = {k: v.text() for k, v in panel.readouts.items()}
    samples = panel.stop_recording()
    report["samples"] = len(samples)
    report["recorded_span_s"] = samples[-1]["t"] - samples[0]["t"] if samples else 0.0
    report["recorded_times_increase"] = all(a["t"] <= b["t"] for a, b in zip(samples, samples[1:]))
    report["max_penetration"] = max(s["penetration"] for s in samples)
    report["engaged_all"] = all(s["engaged"] for s in samples[1:])
    report["z_first"] = samples[0]["translate"][2]
    view.fitAll()
    report["end_png"] = save_view("haptic_trial_end.png")
    undo_before = list(doc.UndoNames)
    panel.accept()
    FreeCADGui.updateGui()
    report["panel_closed"] = haptic_panel.active_panel is None
    final = FreeCAD.Placement(axis.Placement)
    report["final_offset_mm"] = (final.Base - original.Base).Length
    report["final_angle_deg"] = abs(final.Rotation.multiply(original.Rotation.inverted()).Angle) * 180 / 3.141592653589793
    report["undo_added"] = [n for n in doc.UndoNames if n not in undo_before] or list(doc.UndoNames)[:1]
    doc.undo()
    report["undo_restores"] = (axis.Placement.Base - original.Base).Length < 1e-9
    pick_joints(doc, axis)
    containers()


session_helpers.run_and_report(run, report)
