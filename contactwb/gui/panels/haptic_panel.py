"""The haptic trial panel (its command: contactwb.gui.commands.haptics): grab the selected part
with a device (the simulated hand, or a SpaceMouse through hidapi) and insert
or extract it. The C++ loop runs at 1 kHz on its own thread; this panel reads
its snapshot at display rate (40 Hz asked, the view redrawn only when the part
moved), moves the part in the 3D view, shows the
readouts (the active constraints: the joint held and its stops), records or
replays the path (or a trial script, or a recording of raw HID reports), and
commits the final placement as one undoable transaction (or resets it). The
simulated hand can be driven from the panel, one slider per axis, or by
dragging its handle in the 3D view (hand_handle.py, polled here each frame),
so a trial needs no hardware. While the panel is open, the contact overlays do not redraw
for each move of the part (only its placement changes)."""
import time

import FreeCAD
import FreeCADGui

from contactwb import core

# 40 Hz asked (a precise timer): a 33 ms period could never give 30 Hz once
# a frame is late; the view renders only when the part moved (see update).
DISPLAY_PERIOD_MS = 25
active_panel = None  # the open panel (for scripts and tests)
# The simulated hand's sliders: (key, label, range, unit); offsets from the
# part's assembled placement, like a trial script's keys.
HAND_AXES = [("x", "X", 100.0, "mm"), ("y", "Y", 100.0, "mm"), ("z", "Z", 100.0, "mm"),
             ("rx", "Rx", 90.0, "deg"), ("ry", "Ry", 90.0, "deg"), ("rz", "Rz", 180.0, "deg")]
SLIDER_STEPS_PER_UNIT = 10  # 0.1 mm, 0.1 degree
# The measured readouts (loop rate, jitter, force) while the part is still: 2 Hz.
READOUT_PERIOD_S = 0.5


def _body_to_move(bodies, picked):
    """The document body the selection picks: `picked` is a document object or
    an (object, subname) pair from the 3D view or the tree."""
    from contactwb.document import bodies as document_bodies
    if isinstance(picked, tuple):
        chosen = document_bodies.bodies_of_selection(bodies, [(picked[0], [picked[1]])])
        label = picked[0].getSubObject(picked[1], retType=1).Label if picked[1] else picked[0].Label
    else:
        chosen = [b for b in bodies if b.obj is picked]
        label = picked.Label
    if not chosen:
        raise core.ContactsError(f"'{label}' is not a visible solid of the document")
    if len(chosen) != 1 or len([b for b in bodies if b.obj is chosen[0].obj]) != 1:
        raise core.ContactsError(f"'{label}': the haptic trial moves parts made of one solid")
    body = chosen[0]
    # Reached through a link to a container, the part is the original every
    # instance shows: moving it would move them all.
    for container in [body.root] + list(body.containers):
        if container.isDerivedFrom("App::Link") and container is not body.obj:
            raise core.ContactsError(
                f"'{body.obj.Label}' is inside the linked container '{container.Label}': move the link "
                f"or open the original")
    return body


def _joint_choices(assembly, scene, part):
    """The part's assembled joints the loop can hold it to (from the joints
    stage, contactwb/core/joints.py): [{"label", "type", "with", "axis", "pair"}]."""
    from contactwb.core import joints
    _, found = joints.joints_in_assembly(assembly)
    choices = []
    for record, pair in zip(found.joints, found.raw[1].joints):
        if part not in (record.a, record.b):
            continue
        held = scene.joint_of_pair(pair)
        if held is None:
            continue
        other = record.b if record.a == part else record.a
        axis = ", ".join(f"{v + 0.0:.3g}" for v in held.axis)  # + 0.0: no "-0"
        choices.append({"label": f"{held.kind} with {other} (axis {axis})", "type": held.kind,
                        "with": other, "axis": held.axis, "pair": pair})
    return choices


class HapticTrialPanel:
    """Task panel: device, enable, part and joint, stiffness and damping,
    readouts, record / replay, reset; OK commits the placement, Cancel resets."""

    DEVICES = [("Simulated hand", "sim"), ("SpaceMouse (hidapi)", "spacemouse"),
               ("HID force feedback (PID)", "hid-ff")]

    def __init__(self, doc, picked, device="sim"):
        """`picked`: the part to move, a document object or an (object,
        subname) selection path (a part inside an App::Part, or a link)."""
        global active_panel
        import Part
        from contactwb.core import trial
        from contactwb.document import bodies as document_bodies
        self.doc = doc
        assembly, bodies = document_bodies.assembly_from_document(doc)
        body = _body_to_move(bodies, picked)
        # The loop moves the part in the global frame; the object's Placement is
        # local to its containers (App::Part, a link's placement): keep both.
        self.obj = body.obj
        shape = Part.getShape(body.root, body.subname, needSubElement=False, transform=True)
        self.global_placement = shape.Placement
        self.body_name = body.name
        self.trial = trial
        self.scene = trial.make_scene(assembly, body.name)
        # The joints the part could be held to instead of the one engagement finds.
        self.joint_choices = _joint_choices(assembly, self.scene, body.name)
        self.chosen = None  # index into joint_choices, or None: the joint found
        self.original = FreeCAD.Placement(self.obj.Placement)
        self.session = None
        self.script = None        # (checked script, start time) played as hand targets
        self.recording = None     # list of samples while recording
        self.last = None
        self.shown_matrix = None  # the loop's displacement last shown (the view redraws only on a change)
        self.frame_times = []     # monotonic time of each display update (the panel's rate)
        self.update_seconds = []  # time spent in each update (the panel's own cost per frame)
        self.numbers_shown_at = -1e9  # monotonic time the measured readouts were last shown
        self.handle = None  # the hand's handle in the 3D view (hand_handle.py), made once the session runs
        self.form = self._build_form()
        # The overlays must not redraw every contact each time the part moves.
        try:
            from contactwb.gui.overlay import watcher
            watcher.moving_bodies.add((self.obj.Document.Name, self.obj.Name))
        except ImportError:
            pass
        self._start_session(device)
        self.handle = self._make_handle(shape.BoundBox)
        from PySide2 import QtCore
        self.timer = QtCore.QTimer()
        self.timer.setTimerType(QtCore.Qt.PreciseTimer)
        self.timer.timeout.connect(self.update)
        self.timer.start(DISPLAY_PERIOD_MS)
        active_panel = self

    def _make_handle(self, box):
        """The simulated hand's handle on the part in the document's 3D view (None: no 3D view)."""
        from contactwb.gui.panels.hand_handle import HandHandle
        view = FreeCADGui.getDocument(self.obj.Document.Name).activeView()
        if not hasattr(view, "getSceneGraph"):
            return None
        handle = HandHandle(view, self.scene.centre, box)
        translate, rotate = self.hand_slider_values()
        handle.set(translate, rotate)
        handle.show(self.hand_box.isEnabled())
        return handle

    # ---- form
    def _build_form(self):
        from PySide2 import QtCore, QtWidgets
        form = QtWidgets.QWidget()
        form.setWindowTitle("Haptic trial")
        layout = QtWidgets.QVBoxLayout(form)

        device_box = QtWidgets.QGroupBox("Device")
        grid = QtWidgets.QGridLayout(device_box)
        self.device_combo = QtWidgets.QComboBox()
        for label, _ in self.DEVICES:
            self.device_combo.addItem(label)
        self.device_combo.currentIndexChanged.connect(self._device_changed)
        self.enable_check = QtWidgets.QCheckBox("Enabled")
        self.enable_check.setChecked(True)
        self.enable_check.toggled.connect(lambda on: self.session and self.session.set_enabled(on))
        self.device_message = QtWidgets.QLabel()
        self.device_message.setWordWrap(True)
        self.axes_label = QtWidgets.QLabel()
        self.axes_label.setWordWrap(True)  # six signed values: wrap rather than widen the panel
        grid.addWidget(self.device_combo, 0, 0)
        grid.addWidget(self.enable_check, 0, 1)
        grid.addWidget(self.device_message, 1, 0, 1, 2)
        grid.addWidget(QtWidgets.QLabel("Axes"), 2, 0)
        grid.addWidget(self.axes_label, 2, 1)
        layout.addWidget(device_box)

        part_box = QtWidgets.QGroupBox("Part and joint")
        grid = QtWidgets.QGridLayout(part_box)
        grid.addWidget(QtWidgets.QLabel("Part"), 0, 0)
        grid.addWidget(QtWidgets.QLabel(self.obj.Label), 0, 1)
        grid.addWidget(QtWidgets.QLabel("Hold to"), 1, 0)
        self.joint_combo = QtWidgets.QComboBox()
        self.joint_combo.addItem("the joint found (engagement)")
        for choice in self.joint_choices:
            self.joint_combo.addItem(choice["label"])
        # Long labels must not widen the task panel past its dock.
        self.joint_combo.setSizeAdjustPolicy(QtWidgets.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        self.joint_combo.setMinimumContentsLength(18)
        self.joint_combo.setToolTip("Hold the part to one of its assembled joints instead of the one its "
                                    "contacts engage on the way")
        self.joint_combo.currentIndexChanged.connect(lambda index: self.choose_joint(index - 1 if index else None))
        grid.addWidget(self.joint_combo, 1, 1)
        grid.addWidget(QtWidgets.QLabel("Joint"), 4, 0)
        self.joint_label = QtWidgets.QLabel("free")
        self.joint_label.setWordWrap(True)
        grid.addWidget(self.joint_label, 4, 1)
        grid.addWidget(QtWidgets.QLabel("Stiffness"), 2, 0)
        self.stiffness_spin = QtWidgets.QDoubleSpinBox()
        self.stiffness_spin.setDecimals(2)
        self.stiffness_spin.setSingleStep(0.1)
        self.stiffness_spin.setSuffix(" N/mm")
        grid.addWidget(self.stiffness_spin, 2, 1)
        grid.addWidget(QtWidgets.QLabel("Damping"), 3, 0)
        self.damping_spin = QtWidgets.QDoubleSpinBox()
        self.damping_spin.setDecimals(4)
        self.damping_spin.setSingleStep(0.001)
        self.damping_spin.setSuffix(" N s/mm")
        grid.addWidget(self.damping_spin, 3, 1)
        self.stiffness_spin.valueChanged.connect(self._gains_changed)
        self.damping_spin.valueChanged.connect(self._gains_changed)
        grid.addWidget(QtWidgets.QLabel("Friction"), 5, 0)
        self.friction_spin = QtWidgets.QDoubleSpinBox()
        self.friction_spin.setDecimals(2)
        self.friction_spin.setRange(0.0, 2.0)
        self.friction_spin.setSingleStep(0.05)
        self.friction_spin.setToolTip("Coulomb friction coefficient at the part's contacts (0: none): the part "
                                      "sticks while the hand pulls along a surface less than this times it "
                                      "pushes into it")
        self.friction_spin.valueChanged.connect(lambda mu: self.session and self.session.set_friction(mu))
        grid.addWidget(self.friction_spin, 5, 1)
        layout.addWidget(part_box)

        hand_box = QtWidgets.QGroupBox("Simulated hand")
        grid = QtWidgets.QGridLayout(hand_box)
        self.hand_sliders = {}
        self.hand_values = {}
        for row, (key, label, extent, unit) in enumerate(HAND_AXES):
            slider = QtWidgets.QSlider()
            slider.setOrientation(QtCore.Qt.Horizontal)
            steps = int(extent * SLIDER_STEPS_PER_UNIT)
            slider.setRange(-steps, steps)
            slider.setToolTip(f"The simulated hand's target {label}, {unit} from the part's assembled placement")
            slider.valueChanged.connect(self._hand_moved)
            value = QtWidgets.QLabel(f"0.0 {unit}")
            value.setMinimumWidth(70)
            grid.addWidget(QtWidgets.QLabel(label), row, 0)
            grid.addWidget(slider, row, 1)
            grid.addWidget(value, row, 2)
            self.hand_sliders[key] = slider
            self.hand_values[key] = value
        hand_box.setToolTip("Drive the simulated hand with these sliders, or drag its handle (the box around "
                            "the part) in the 3D view. While the handle is shown, only it can be picked in the "
                            "view, also where other bodies hide it.")
        self.hand_box = hand_box
        layout.addWidget(hand_box)

        readout_box = QtWidgets.QGroupBox("Readouts")
        grid = QtWidgets.QGridLayout(readout_box)
        self.readouts = {}
        for row, (key, label) in enumerate([("constraints", "Constraints"), ("depth", "Depth"),
                                            ("force", "Force"), ("offset", "Offset"),
                                            ("penetration", "Penetration"), ("rate", "Loop rate"),
                                            ("jitter", "Jitter"), ("watchdog", "Watchdog")]):
            grid.addWidget(QtWidgets.QLabel(label), row, 0)
            value = QtWidgets.QLabel("-")
            value.setWordWrap(True)
            grid.addWidget(value, row, 1)
            self.readouts[key] = value
        layout.addWidget(readout_box)

        buttons = QtWidgets.QHBoxLayout()
        self.record_button = QtWidgets.QPushButton("Record")
        self.record_button.setCheckable(True)
        self.record_button.toggled.connect(self._record_toggled)
        replay_button = QtWidgets.QPushButton("Replay...")
        replay_button.clicked.connect(self._replay_clicked)
        reset_button = QtWidgets.QPushButton("Reset")
        reset_button.clicked.connect(self.reset)
        for b in (self.record_button, replay_button, reset_button):
            buttons.addWidget(b)
        layout.addLayout(buttons)
        layout.addStretch(1)
        return form

    # ---- session
    def _start_session(self, device, translate=(0, 0, 0), rotate_deg=(0, 0, 0), hid_file=None):
        if self.session is not None:
            self.session.stop()
        h = self.trial.haptics()
        # A real-time class for the loop thread when the system grants it (else it runs as it is).
        self.session = h.HapticSession(self.scene, device, list(translate), list(rotate_deg), hid_file=hid_file,
                                       realtime_priority=80)
        caps = self.session.capabilities
        self.device_message.setText(self.session.message)
        # The sliders drive the simulated hand (none with hardware), from where the part starts.
        self.hand_box.setEnabled(caps.name == h.simulated_capabilities().name)
        if self.handle is not None:
            self.handle.show(self.hand_box.isEnabled())
        self.set_hand_sliders(list(translate) + list(rotate_deg), drive=False)
        # Gains within what the device renders (a rate device renders none: keep the defaults).
        k_max = caps.max_stiffness or 5.0
        b_max = caps.max_damping or 0.05
        self.stiffness_spin.blockSignals(True)
        self.damping_spin.blockSignals(True)
        self.stiffness_spin.setRange(0.05, k_max)
        self.damping_spin.setRange(0.0, b_max)
        self.stiffness_spin.setValue(min(1.0, k_max))
        self.damping_spin.setValue(min(0.005, b_max))
        self.stiffness_spin.blockSignals(False)
        self.damping_spin.blockSignals(False)
        self._gains_changed()
        self.session.set_friction(self.friction_spin.value())
        self.session.set_enabled(self.enable_check.isChecked())
        self._apply_joint()
        self.session.start()

    def choose_joint(self, index):
        """Holds the part to joint_choices[index], or (None) to the joint found."""
        self.chosen = index
        self.joint_combo.blockSignals(True)
        self.joint_combo.setCurrentIndex(0 if index is None else index + 1)
        self.joint_combo.blockSignals(False)
        self._apply_joint()

    def _apply_joint(self):
        if self.session is None:
            return
        if self.chosen is None:
            self.session.release_joint()
        else:
            self.session.hold_to_pair(self.joint_choices[self.chosen]["pair"])

    # ---- the simulated hand's sliders
    def hand_slider_values(self):
        """The sliders' target: [x, y, z] mm and [rx, ry, rz] degrees."""
        values = [self.hand_sliders[key].value() / SLIDER_STEPS_PER_UNIT for key, *_ in HAND_AXES]
        return values[:3], values[3:]

    def set_hand_sliders(self, values, drive=True, show_handle=True):
        """Moves the sliders (six values, mm and degrees) as the user would;
        `drive`: the hand follows; `show_handle`: the 3D view's handle too."""
        for (key, _, _, unit), v in zip(HAND_AXES, values):
            slider = self.hand_sliders[key]
            slider.blockSignals(True)
            slider.setValue(int(round(v * SLIDER_STEPS_PER_UNIT)))
            slider.blockSignals(False)
            self.hand_values[key].setText(f"{slider.value() / SLIDER_STEPS_PER_UNIT:.1f} {unit}")
        if show_handle and self.handle is not None:
            self.handle.set(values[:3], values[3:])
        if drive:
            self._hand_moved()

    def _hand_moved(self, *_):
        translate, rotate = self.hand_slider_values()
        for (key, _, _, unit), v in zip(HAND_AXES, translate + rotate):
            self.hand_values[key].setText(f"{v:.1f} {unit}")
        if self.handle is not None:
            self.handle.set(translate, rotate)
        if self.session is not None:
            self.script = None  # the user takes over from a playing script
            self.session.set_hand_target(translate, rotate)

    def _poll_handle(self):
        """The hand follows the 3D view's handle when the designer dragged it
        (read each frame: no callback from Coin), the sliders show where."""
        if self.handle is None or not self.hand_box.isEnabled():
            return
        dragged = self.handle.poll()
        if dragged is None:
            return
        translate, rotate = dragged
        self.script = None  # the user takes over from a playing script
        self.session.set_hand_target(translate, rotate)
        self.set_hand_sliders(translate + rotate, drive=False, show_handle=False)

    def _device_changed(self, index):
        self._start_session(self.DEVICES[index][1])

    def _gains_changed(self, *_):
        if self.session is None:
            return
        k = self.stiffness_spin.value()
        self.session.set_stiffness(k, 3000.0 * k)
        self.session.set_damping(self.damping_spin.value(), 5.0)

    # ---- display rate
    def update(self):
        if self.session is None:
            return
        self._poll_handle()
        if self.script is not None:
            self._drive_script()
        began = time.monotonic()
        s = self.session.snapshot()
        self.last = s
        self.frame_times.append(began)
        if len(self.frame_times) > 2000:
            del self.frame_times[:1000]
            del self.update_seconds[:1000]
        matrix = [list(row) for row in s.matrix]
        moved = matrix != self.shown_matrix
        if moved:  # a Placement set, even unchanged, redraws the whole view
            self.shown_matrix = matrix
            self._show_placement(s.matrix)
        # Any label repainted makes Qt compose the whole window again with the
        # 3D view's image (a QOpenGLWidget): with a software renderer that is a
        # frame's cost. The numbers that flicker while the part is still (loop
        # rate, jitter, force) are shown at READOUT_PERIOD_S; with a move they
        # go with the view's own frame. The joint and constraints when they change.
        numbers = moved or began - self.numbers_shown_at >= READOUT_PERIOD_S
        self._show_readouts(s, numbers)
        if numbers:
            self.numbers_shown_at = began
        self.update_seconds.append(time.monotonic() - began)
        if self.recording is not None:
            self.recording.append({"t": s.time, "translate": s.translate, "rotate_deg": s.rotate_deg,
                                   "force": s.force, "engaged": s.engaged, "penetration": s.penetration})

    def _show_readouts(self, s, numbers):
        """The readouts of snapshot s; `numbers`: the measured figures too
        (QLabel.setText does nothing when the text is unchanged)."""
        if s.engaged:
            how = "chosen" if s.held else "found"
            self.joint_label.setText(f"{s.joint} with {', '.join(s.joint_with)} ({how})")
        else:
            self.joint_label.setText("free (stopped only by collisions)")
        r = self.readouts
        r["constraints"].setText(self.constraints_text(s))
        if not numbers:
            return
        self.axes_label.setText(" ".join(f"{a:+.2f}" for a in s.axes))
        r["depth"].setText(f"{s.insertion_depth:.3f} mm" if s.engaged else "-")
        r["force"].setText(f"{s.force_n:.2f} N")
        # A coordinate that rounds to zero reads 0.000, not "-0.000".
        r["offset"].setText("[" + ", ".join(f"{v:.3f}".replace("-0.000", "0.000") for v in s.translate) + "] mm")
        r["penetration"].setText(f"{s.penetration:.4f} mm (max {s.max_penetration:.4f})")
        r["rate"].setText(f"{s.rate_hz:.0f} Hz")
        r["jitter"].setText(f"{s.jitter_us:.0f} us")
        r["watchdog"].setText(s.watchdog if s.watchdog != "none" else "ok")

    @staticmethod
    def constraints_text(s):
        """The active constraints in words: the joint held (found or chosen)
        with its bodies, and its one-sided stops (active: the part is on it)."""
        if not s.engaged:
            return "none: free, stopped only by collisions" + (" (blocked)" if s.blocked else "")
        how = "chosen" if s.held else "found"
        text = f"{s.joint} joint with {', '.join(s.joint_with) or '?'} ({how})"
        stops = s.stops
        if stops:
            active = [st for st in stops if st.active]
            text += f"; stops: {len(active)} of {len(stops)} active"
            for st in active:
                n = st.normal
                text += f" [n {n[0]:+.2f} {n[1]:+.2f} {n[2]:+.2f}]"
        else:
            text += "; no stops"
        return text

    def update_rate_hz(self, last_seconds=2.0):
        """The panel's measured display rate over the last seconds (frames / time)."""
        if len(self.frame_times) < 2:
            return 0.0
        end = self.frame_times[-1]
        recent = [t for t in self.frame_times if t >= end - last_seconds]
        if len(recent) < 2 or recent[-1] <= recent[0]:
            return 0.0
        return (len(recent) - 1) / (recent[-1] - recent[0])

    def _local_placement(self, rows):
        """The object's Placement for the loop's global displacement D (rows):
        globally D G, locally L G^-1 D G (L its own Placement, G its global one)."""
        moved = FreeCAD.Placement(FreeCAD.Matrix(*[v for row in rows for v in row]))
        g = self.global_placement
        return self.original.multiply(g.inverse()).multiply(moved).multiply(g)

    def _show_placement(self, rows):
        self.obj.Placement = self._local_placement(rows)

    # ---- scripts, record, replay
    def play_script(self, script):
        """Plays a trial script (see `contacts trial`) in real time: the part
        restarts at the script's start offset and the simulated hand follows
        the script's targets."""
        checked = self.trial.check_script(script)
        self.device_combo.blockSignals(True)
        self.device_combo.setCurrentIndex(0)
        self.device_combo.blockSignals(False)
        start = checked["start"]
        self._start_session("sim", start["translate"], start["rotate_deg"])
        self.script = (checked["hand"], time.monotonic())
        self._drive_script()

    def script_done(self):
        return self.script is None

    def _drive_script(self):
        keys, started = self.script
        t = time.monotonic() - started
        if t >= keys[-1]["t"]:
            key = keys[-1]
            self.script = None
            self.session.set_hand_target(key["translate"], key["rotate_deg"])
            self.set_hand_sliders(key["translate"] + key["rotate_deg"], drive=False)  # where the hand is now
            return
        after = next(i for i, k in enumerate(keys) if k["t"] > t)
        a, b = keys[max(0, after - 1)], keys[after]
        s = 0.0 if b["t"] <= a["t"] else (t - a["t"]) / (b["t"] - a["t"])
        mix = [[x + s * (y - x) for x, y in zip(a[field], b[field])] for field in ("translate", "rotate_deg")]
        self.session.set_hand_target(*mix)
        if self.handle is not None:
            self.handle.set(*mix)

    def start_recording(self):
        self.recording = []

    def stop_recording(self):
        samples, self.recording = self.recording or [], None
        return samples

    def _record_toggled(self, on):
        from PySide2 import QtWidgets
        if on:
            self.start_recording()
            self.record_button.setText("Stop")
            return
        self.record_button.setText("Record")
        samples = self.stop_recording()
        if not samples:
            return
        path, _ = QtWidgets.QFileDialog.getSaveFileName(self.form, "Save path", "path.csv", "Path (*.csv *.json)")
        if path:
            self.trial.write_path(samples, path)

    def replay(self, samples):
        """Replays a recorded path as the hand's script (from its first placement)."""
        t0 = samples[0]["t"]
        hand = [{"t": s["t"] - t0, "translate": s["translate"], "rotate_deg": s["rotate_deg"]} for s in samples]
        self.play_script({"start": {"translate": hand[0]["translate"], "rotate_deg": hand[0]["rotate_deg"]},
                          "hand": hand})

    def replay_file(self, path):
        """Replays a file: a trial script (JSON with "hand", like the bundled
        Resources/trials/*.json), a recorded path (CSV or a JSON list), or raw
        HID reports (`contacts trial --record-hid`, played through the device's
        parser)."""
        import json
        if path.lower().endswith((".hid", ".txt")):
            self.script = None
            self._start_session("replay", hid_file=path)
            return
        if path.lower().endswith(".json"):
            with open(path, encoding="utf-8") as stream:
                data = json.load(stream)
            if isinstance(data, dict):
                self.play_script(data)  # a trial script (checked there, with clear errors)
                return
            samples = data
        else:
            samples = self.trial.read_path(path)
        if not samples:
            raise core.ContactsError(f"'{path}': no samples to replay")
        self.replay(samples)

    def _replay_clicked(self):
        from PySide2 import QtWidgets
        path, _ = QtWidgets.QFileDialog.getOpenFileName(
            self.form, "Replay", "", "Scripts and paths (*.json *.csv);;HID recordings (*.hid *.txt)")
        if path:
            try:
                self.replay_file(path)
            except (core.ContactsError, OSError, ValueError) as error:
                _show_error(f"cannot replay '{path}': {error}")

    def reset(self):
        """Back to the placement the part had when the panel opened."""
        self.script = None
        self.shown_matrix = None
        self.set_hand_sliders([0.0] * 6, drive=False)
        self._start_session(self.DEVICES[self.device_combo.currentIndex()][1])
        self.obj.Placement = self.original

    # ---- task dialog
    def _close(self):
        global active_panel
        self.timer.stop()
        if self.handle is not None:
            self.handle.remove()
            self.handle = None
        if self.session is not None:
            self.session.stop()
            self.session = None
        active_panel = None
        try:
            from contactwb.gui.overlay import watcher
            watcher.follow_body_again(self.obj.Document.Name, self.obj.Name)
        except ImportError:
            pass

    def accept(self):
        final = FreeCAD.Placement(self.obj.Placement)
        if self.session is not None:
            self.session.stop()
            s = self.session.snapshot()
            final = self._local_placement(s.matrix)
        self._close()
        # The moves shown during the trial are not in the undo stack: one transaction for the result.
        self.obj.Placement = self.original
        doc = self.obj.Document  # the moved object's (a link's own, not its target's)
        doc.openTransaction("Haptic trial")
        self.obj.Placement = final
        doc.recompute()  # inside: the contacts found again are part of this one undo entry
        doc.commitTransaction()
        FreeCADGui.Control.closeDialog()
        return True

    def reject(self):
        self._close()
        self.obj.Placement = self.original
        FreeCADGui.Control.closeDialog()
        return True

    def getStandardButtons(self):
        from PySide2 import QtWidgets
        return int(QtWidgets.QDialogButtonBox.Ok | QtWidgets.QDialogButtonBox.Cancel)

