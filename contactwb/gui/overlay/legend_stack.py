"""Legends of one document stacked in the view's corner, never drawn over
each other: each legend (an analysis' contacts, the partitions, a simulation
model) registers under a key with its number of lines; every legend starts
below the ones registered before it, one blank line apart. A legend rebuilt
keeps its place; one removed gives its room back."""
LINE_HEIGHT = 0.055   # one text line, in the legend camera's -1..1 height (coin_nodes.legend_node)
TOP = 0.9             # the first line's baseline

_stacks = {}  # document name -> {key: [start SoTranslation, line count]} in registration order


def register(doc_name, key, start, lines):
    """Places a legend (its start SoTranslation, `lines` lines) in its
    document's stack and moves the others to fit."""
    stack = _stacks.setdefault(doc_name, {})
    stack[key] = [start, lines]
    relayout(doc_name)


def unregister(doc_name, key):
    stack = _stacks.get(doc_name, {})
    if stack.pop(key, None) is not None:
        relayout(doc_name)


def relayout(doc_name):
    y = TOP
    for start, lines in _stacks.get(doc_name, {}).values():
        start.translation.setValue(-0.96, y, 0)
        y -= (lines + 1) * LINE_HEIGHT


def extents(doc_name):
    """{key: (top y, bottom y)} of the document's legends (for tests)."""
    out = {}
    for key, (start, lines) in _stacks.get(doc_name, {}).items():
        top = start.translation.getValue()[1]
        out[key] = (top, top - (lines - 1) * LINE_HEIGHT)
    return out


def forget(doc_name):
    _stacks.pop(doc_name, None)
