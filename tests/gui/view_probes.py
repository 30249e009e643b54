"""Probes of the 3D view and of the workbench's results, used by the GUI
sessions under Xvfb (tests/gui/haptic_hand_session.py) and the GUI benchmark
(bench/gui_bench_session.py): how often the view renders, and what touches
the contact results while a part moves (issue 20 item 6)."""
import time

import FreeCAD


class RenderCounter:
    """Counts the 3D view's renders: a SoCallback first in its scene graph,
    called by every SoGLRenderAction (times on time.perf_counter). Only the
    traversal of the whole graph counts: the passes a frame makes afterwards
    over its delayed paths (annotations such as the contacts' legend,
    transparent shapes) traverse this node again (it affects the state, so
    Coin visits it off the path) and would count one frame two or more times."""

    def __init__(self, view):
        from pivy import coin
        self.times = []
        self.root = view.getSceneGraph()
        self.node = coin.SoCallback()
        self.node.setCallback(self._called)
        self.root.insertChild(self.node, 0)
        self.render_type = coin.SoGLRenderAction.getClassTypeId()
        self.whole_graph = coin.SoAction.NO_PATH

    def _called(self, _, action):
        if action.isOfType(self.render_type) and action.getCurPathCode() == self.whole_graph:
            self.times.append(time.perf_counter())

    def rate(self, since):
        """(renders per second, renders) since a time.perf_counter() value."""
        renders = [t for t in self.times if t >= since]
        return len(renders) / max(1e-9, time.perf_counter() - since), len(renders)

    def remove(self):
        self.root.removeChild(self.node)


class ResultTouches:
    """What touches the contact results while the part moves: property
    changes of the workbench's objects (analyses, contacts, joints,
    interferences; a document observer), calls of their view providers'
    updateData and onChanged ("Object.method", wrapped on each proxy), and
    rebuilds of the analyses' paint."""

    def __init__(self, doc):
        from contactwb.document.identify import is_workbench_result
        self.is_result = is_workbench_result
        self.changes, self.provider_calls, self.paint_builds = [], [], 0
        self.wrapped = []
        for obj in doc.Objects:
            proxy = getattr(getattr(obj, "ViewObject", None), "Proxy", None)
            if not is_workbench_result(obj) or proxy is None:
                continue
            for name in ("updateData", "onChanged"):
                if hasattr(proxy, name):
                    self._wrap(proxy, name, f"{obj.Name}.{name}")
            if hasattr(proxy, "overlay"):
                self._wrap(proxy.overlay, "build", None)
        FreeCAD.addDocumentObserver(self)

    def _wrap(self, owner, name, call_name):
        original = getattr(owner, name)
        # what stop() puts back: another probe's wrapper set on the instance, or nothing
        own = owner.__dict__.get(name) if hasattr(owner, "__dict__") else None

        def counting(*args, **kwargs):
            if call_name is None:
                self.paint_builds += 1
            else:
                self.provider_calls.append(call_name)
            return original(*args, **kwargs)
        setattr(owner, name, counting)  # an instance attribute: FreeCAD looks the method up on the proxy
        self.wrapped.append((owner, name, own))

    def slotChangedObject(self, obj, prop):
        if self.is_result(obj):
            self.changes.append(f"{obj.Name}.{prop}")

    def stop(self):
        FreeCAD.removeDocumentObserver(self)
        for owner, name, own in reversed(self.wrapped):
            if own is None:
                delattr(owner, name)
            else:
                setattr(owner, name, own)


def view_viewport():
    """The active 3D view's OpenGL widget (Quarter's viewport in FreeCAD 0.20):
    what renders, and what gets the mouse."""
    from PySide2 import QtWidgets
    import FreeCADGui
    main = FreeCADGui.getMainWindow()
    active = main.findChild(QtWidgets.QMdiArea).activeSubWindow()
    (viewer,) = [w for w in (active or main).findChildren(QtWidgets.QWidget)
                 if w.metaObject().className() == "SIM::Coin3D::Quarter::QuarterWidget" and w.isVisible()]
    return viewer.viewport()


def forced_render_rate(seconds=3.0):
    """The active 3D view rendered back to back for `seconds` (each a
    synchronous repaint of its OpenGL widget: Coin's render, Qt composing the
    window, the swap): (renders per second, renders, [width, height] of the
    view in device pixels). What the renderer can do for this scene, with
    nothing else asking for time."""
    from PySide2 import QtWidgets
    import FreeCADGui
    viewport = view_viewport()
    QtWidgets.QApplication.processEvents()
    counter = RenderCounter(FreeCADGui.activeDocument().activeView())
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        viewport.repaint()
    rate, renders = counter.rate(start)
    counter.remove()
    ratio = viewport.devicePixelRatioF()
    return rate, renders, [round(viewport.width() * ratio), round(viewport.height() * ratio)]
