"""The common regions of an analysis' contacts and the overlapping solids of
its interferences, as the core computes them (contactcore.find_contacts
with `regions`, Contact.region_mesh, Interference.solid_brep), cached with
the analysis for the paint (contactwb.gui.overlay).

Each body the analysis ran on has a fingerprint (ShapeStamp: its path, its
OCCT shape and its placement): a recompute asks the core for the regions of the
bodies whose fingerprint changed only (a moved part: its contacts), and
keeps the others' from the cache. The cache lives with the session, not in
the file: after opening a file the first paint asks the core for all of them
(region_meshes_of)."""
import math

from contactwb import core
from contactwb.core.kinds import CIRCLE_TYPES
from contactwb.document.shapes import CoreBodyCache, ShapeStamp

# The deflection of the regions' triangles: FreeCAD's for a body's view
# (ViewProviderPartExt: the box's size sum / 300 * Deviation %, Deviation 0.5
# by default), so that a region's triangles sag as the body's own faces do.
DEFAULT_DEVIATION = 0.5
ANGULAR_DEFLECTION = math.radians(28.5)  # FreeCAD's default AngularDeflection

_caches = {}  # (document name, analysis name) -> RegionCache


def body_deflection(shape, deviation=DEFAULT_DEVIATION):
    box = shape.BoundBox
    size = box.XLength + box.YLength + box.ZLength if box.isValid() else 1.0
    return max(size / 300.0 * deviation, 1e-4)


def fingerprint(body):
    """The body's ShapeStamp: a move or a change of shape changes it."""
    return ShapeStamp(body)


class RegionCache:
    """One analysis' regions: {contact key: [(points, triangles, deflection)]}
    (two contacts may share a key), interference solids by pair (BRep text),
    the bodies' fingerprints and settings they were computed with, and how
    many the core computed at the last recompute (`computed`)."""

    def __init__(self):
        self.meshes = {}
        self.solids = {}
        self.fingerprints = {}
        self.settings = None
        self.computed = 0
        self.pending = {}  # the fingerprints of the bodies of the recompute under way
        self.generation = 0  # stored results so far: a paint built from an older one is redrawn
        self.masses = None  # (body names, their stamps, lone flags, (volume, centre) each): reuse_masses
        self.core_bodies = CoreBodyCache()  # the core's bodies, kept: only changed ones cross as BRep
        self.memo = None  # contactcore.ContactsMemo: what the core reuses of the last search (memo_of)

    def changed_bodies(self, bodies, settings):
        """Indices of the bodies whose regions must be computed again (every
        one when the settings changed)."""
        self.pending = {b.name: fingerprint(b) for b in bodies}
        if settings != self.settings:
            return list(range(len(bodies)))
        return [i for i, b in enumerate(bodies) if self.fingerprints.get(b.name) != self.pending[b.name]]


def cache_of(group):
    key = (group.Document.Name, group.Name)
    if key not in _caches:
        _caches[key] = RegionCache()
    return _caches[key]


def forget(group):
    """Drops an analysis' regions (it was deleted, or its document closed)."""
    _caches.pop((group.Document.Name, group.Name), None)


def forget_document(doc_name):
    """Drops a document's regions: an undo or redo moved its bodies back
    without a recompute (the next paint asks the core again)."""
    for key in [k for k in _caches if k[0] == doc_name]:
        del _caches[key]


def region_bodies(group, bodies, settings):
    """find_contacts' `regions` for a recompute of `group` on `bodies`."""
    changed = cache_of(group).changed_bodies(bodies, settings)
    return True if len(changed) == len(bodies) else changed


def assembly_of(group, bodies):
    """The contactcore.Assembly of a recompute of `group` on `bodies` (after
    region_bodies, whose stamps it uses): the unchanged bodies' core Body
    kept from the last recompute, only the moved and changed ones read from
    BRep text (contactwb.document.shapes.CoreBodyCache)."""
    cache = cache_of(group)
    stamps = [cache.pending.get(b.name) or fingerprint(b) for b in bodies]
    return cache.core_bodies.assembly(bodies, stamps)


def memo_of(group):
    """The contactcore.ContactsMemo of `group`'s searches: find_contacts
    reuses what depends only on the bodies whose core Body is the last
    search's (assembly_of keeps them), and checks that itself."""
    cache = cache_of(group)
    if cache.memo is None:
        cache.memo = core.contactcore.ContactsMemo()
    return cache.memo


def store(group, bodies, settings, assembly, raw, records, contact_key):
    """Keeps the regions of a core result `raw` (found with region_bodies'
    `regions`) for `records` (its contacts as analysis records, in order):
    the new ones replace the changed bodies'; a contact whose region is
    neither new nor cached (first seen between unchanged bodies) is computed
    now. Returns the cache."""
    cache = cache_of(group)
    if settings != cache.settings:
        cache.meshes, cache.solids = {}, {}
    computed = raw.regions_computed
    now = {b.name: cache.pending.get(b.name) or fingerprint(b) for b in bodies}
    changed = {name for name, fp in now.items() if cache.fingerprints.get(name) != fp}
    missing = {c.body_a for c, r in zip(raw.contacts, records)
               if not c.has_region and r.type not in CIRCLE_TYPES and
               (r.a in changed or r.b in changed or contact_key(r) not in cache.meshes)}
    if missing:
        computed += core.contactcore.find_common_regions(assembly, raw, sorted(missing))
    kept = {}
    for contact, record in zip(raw.contacts, records):
        key = contact_key(record)
        if contact.has_region:
            deflection = body_deflection(bodies[contact.body_a].shape)
            points, triangles = contact.region_mesh(deflection, ANGULAR_DEFLECTION)
            kept.setdefault(key, []).append((points, triangles, deflection))
        elif key in cache.meshes and key not in kept:
            kept[key] = cache.meshes[key]
    names = [b.name for b in bodies]
    solids = {}
    for overlap in raw.interferences:
        pair = (names[overlap.body_a], names[overlap.body_b])
        if overlap.has_solid:
            solids[pair] = overlap.solid_brep
        elif pair in cache.solids and pair[0] not in changed and pair[1] not in changed:
            solids[pair] = cache.solids[pair]
    # The same regions as before (nothing computed, every contact's meshes and
    # every solid the ones already held): the paint drawn from them still is
    # right, and is not drawn again (a Find contacts again with nothing changed).
    same = (computed == 0 and settings == cache.settings and kept.keys() == cache.meshes.keys()
            and all(kept[key] is cache.meshes[key] for key in kept) and solids == cache.solids)
    cache.meshes, cache.solids = kept, solids
    cache.fingerprints, cache.pending = now, {}
    cache.settings = settings
    cache.computed = computed
    if not same:
        cache.generation += 1
    return cache


def meshes_of(group, key):
    """[(points, triangles, deflection)] of a contact key, [] when none is cached."""
    cache = _caches.get((group.Document.Name, group.Name))
    return cache.meshes.get(key, []) if cache is not None else []


def generation(group):
    """How many results the analysis' cache has stored (None: no cache)."""
    cache = _caches.get((group.Document.Name, group.Name))
    return cache.generation if cache is not None else None


def has_regions(group):
    cache = _caches.get((group.Document.Name, group.Name))
    return cache is not None and cache.settings is not None


def _lone_bodies(bodies):
    """For each body whether no other body shares its OCCT geometry (an
    instance, as the core finds them: isPartner, whatever the placement).
    Compared within groups of equal face counts only."""
    buckets = {}
    for index, body in enumerate(bodies):
        buckets.setdefault(len(body.shape.Faces), []).append(index)
    lone = [True] * len(bodies)
    for members in buckets.values():
        for k, i in enumerate(members):
            for j in members[k + 1:]:
                if bodies[i].shape.isPartner(bodies[j].shape):
                    lone[i] = lone[j] = False
    return lone


def reuse_masses(group, bodies, assembly, result):
    """Sets the volume and centre of each of `result`'s bodies (an Analysis
    found on `bodies` and `assembly`, after store()) without asking the core
    again for the bodies that did not change since the last recompute: the
    values it gave then. A changed body is computed alone (contactcore's
    Body.volume, the computation compute_mass_properties makes for a body
    that is nobody's instance, so the figures are the same to the last bit)
    when it has no instance (no other body sharing its geometry) now or
    before; else, or when the bodies are not the same list, every body is
    computed as before (compute_mass_properties: instances' centres moved
    from their first's)."""
    from contactwb.core.analysis import StoredMass
    cache = cache_of(group)
    names = [b.name for b in bodies]
    if [b.name for b in result.bodies] != names:  # a body the core skipped (no solid): as before
        cache.masses = None
        return
    stamps = [cache.fingerprints.get(name) or fingerprint(b) for name, b in zip(names, bodies)]
    lone = _lone_bodies(bodies)
    values = None
    if cache.masses is not None and cache.masses[0] == names:
        _, old_stamps, old_lone, old_values = cache.masses
        changed = [i for i in range(len(bodies)) if old_stamps[i] != stamps[i]]
        if all(lone[i] and old_lone[i] for i in changed):
            values = list(old_values)
            core_bodies = assembly.bodies if changed else []
            for i in changed:
                values[i] = (core_bodies[i].volume, core_bodies[i].center)
    if values is None:
        values = [(b.volume, b.center) for b in result.bodies]  # the core, every body at once
    stored = StoredMass(values)
    for body in result.bodies:
        body._mass = stored
    cache.masses = (names, stamps, lone, values)
