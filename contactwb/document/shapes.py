"""Part shapes into the extension and back (BRep text), and the core's
bodies of an analysis kept between its recomputes (CoreBodyCache: only the
moved and changed bodies cross as BRep text again)."""
from contactwb import core


def shape_to_brep(shape):
    """BRep text of a Part.Shape (with its placement)."""
    return shape.exportBrepToString()


def shape_from_brep(text):
    """A Part.Shape from BRep text (needs FreeCAD's Part module)."""
    import Part
    shape = Part.Shape()
    shape.importBrepFromString(text)
    return shape


def assembly_from_shapes(named_shapes):
    """A contactcore.Assembly from (name, Part.Shape) pairs, shapes already
    placed globally. They cross into C++ as one compound (instances share
    geometry in the BRep stream, so this is cheap even for thousands)."""
    import Part
    named_shapes = list(named_shapes)
    if not named_shapes:
        raise core.ContactsError("no bodies given")
    compound = Part.makeCompound([shape for _, shape in named_shapes])
    try:
        return core.contactcore.bodies_from_brep(compound.exportBrepToString(), [name for name, _ in named_shapes])
    except core.InputError as error:
        # FreeCAD wrote this text into memory just now: cut short, it ran out
        # of memory writing it (it does not say so).
        if "text cut short" in str(error):
            raise MemoryError(f"out of memory (FreeCAD's BRep export of the shapes came back cut short: {error})") \
                from error
        raise


class ShapeStamp:
    """Where a body is and what it is, in a few calls: its path in the
    document, its placed shape, that shape's placement and orientation. Equal
    to another when the path is, the shape is the same OCCT shape (isPartner:
    the same geometry object; a recomputed feature gets a new one) and the
    placement and orientation are (a move changes them): then the shape's
    BRep text is the same too. The shape is held, so that its geometry stays
    alive and a new shape can never take its place in memory. Replaces a
    fingerprint of the box and the area (OCCT's surface integration of every
    face: most of the cost of looking, at each recompute)."""
    __slots__ = ("path", "shape", "placement", "orientation")

    def __init__(self, body):
        shape = body.shape
        self.path = (body.root.Name, body.subname, body.name)
        self.shape = shape
        self.placement = tuple(shape.Placement.toMatrix().A)
        self.orientation = shape.Orientation

    def __eq__(self, other):
        return (isinstance(other, ShapeStamp) and self.path == other.path and self.placement == other.placement
                and self.orientation == other.orientation and self.shape.isPartner(other.shape))

    def __ne__(self, other):
        return not self.__eq__(other)

    __hash__ = None


class CoreBodyCache:
    """The core's Body of each body of an analysis' last assembly, with the
    ShapeStamp it was read with. The next assembly takes an unchanged body's
    Body as it is (contactcore.assembly_of_bodies) and reads only the others
    from BRep text: the moved and changed bodies, and every body sharing
    their geometry (an instance: the core finds instances by their shared
    OCCT shape, so they cross together, as in one compound). The Assembly is
    the one assembly_from_shapes gives for all of them: the same text read the
    same way, body by body. A read that skipped or reported anything (a child
    without a solid, an open shell) is not kept: the next assembly reads
    every body again. `crossed`: the names whose text crossed last time."""

    def __init__(self):
        self.held = {}  # body name -> (ShapeStamp, contactcore.Body)
        self.names = []  # the bodies of the last assembly, in order
        self.crossed = []

    def assembly(self, bodies, stamps=None):
        """A contactcore.Assembly of `bodies` (DocumentBody: name, shape,
        root, subname), `stamps` their ShapeStamps (made when None)."""
        bodies = list(bodies)
        if stamps is None:
            stamps = [ShapeStamp(b) for b in bodies]
        names = [b.name for b in bodies]
        if len(set(names)) != len(names):  # kept by name: names must tell the bodies apart
            self.held, self.names, self.crossed = {}, [], names
            return assembly_from_shapes((b.name, b.shape) for b in bodies)
        crossing = [i for i, (name, stamp) in enumerate(zip(names, stamps))
                    if name not in self.held or self.held[name][0] != stamp]
        if names != self.names:  # bodies added, removed or reordered: the instances may pair anew
            crossing = list(range(len(bodies)))
        if crossing and len(crossing) < len(bodies):
            # The bodies sharing a crossing body's geometry, now or before its
            # change (partners of one body are each other's: one OCCT shape):
            # read with it, they share it in the core too, and their volumes
            # are computed anew, as the core computes instances' (moved from
            # the first's).
            shapes = [bodies[i].shape for i in crossing] + \
                [self.held[names[i]][0].shape for i in crossing if names[i] in self.held]
            chosen = set(crossing)
            for j, body in enumerate(bodies):
                if j not in chosen and any(body.shape.isPartner(shape) for shape in shapes):
                    chosen.add(j)
            crossing = sorted(chosen)
        read = None
        if crossing and len(crossing) < len(bodies):
            read = assembly_from_shapes((names[i], bodies[i].shape) for i in crossing)
            if len(read.bodies) != len(crossing) or read.messages:
                crossing, read = list(range(len(bodies))), None  # as a first read: every body
        if len(crossing) == len(bodies):
            assembly = assembly_from_shapes((b.name, b.shape) for b in bodies)
            self.crossed, self.names = names, names
            self.held = {}
            if len(assembly.bodies) == len(bodies) and not assembly.messages:
                self.held = {name: (stamp, body) for name, stamp, body in zip(names, stamps, assembly.bodies)}
            return assembly
        core_bodies = [self.held[name][1] if name in self.held else None for name in names]
        for i, body in zip(crossing, read.bodies if read is not None else []):
            core_bodies[i] = body
        assembly = core.contactcore.assembly_of_bodies(core_bodies, names)
        self.held = {name: (stamp, body) for name, stamp, body in zip(names, stamps, assembly.bodies)}
        self.crossed, self.names = [names[i] for i in crossing], names
        return assembly
