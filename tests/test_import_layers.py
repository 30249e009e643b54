"""Issue 23: the Python package in layers. Walks every module of contactwb/
(parsed with `ast`, never imported: module-level and function-local imports,
absolute and relative), builds the module graph and fails on

- a cycle between modules;
- an import from a lower layer into a higher one: core < document < objects <
  make < gui, and cli beside gui (it may import core, document, objects and
  make, never gui; gui never imports cli);
- core importing FreeCAD, FreeCADGui, Part, PySide2 or pivy (it stays usable
  without FreeCAD, as freecad.gears keeps its math);
- a module using another module's private names (`from m import _x`, `m._x`);
- new code importing a compatibility shim (the modules at the paths of
  earlier releases, listed below), or a shim importing anything but its new
  homes.

test_checker_catches_violations runs the same checks on a small package
with an upward import, a cycle, a FreeCAD import in core and a private name,
so the checks are known to fail when they should."""
import ast
import os

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGE = "contactwb"

LAYERS = ["core", "document", "objects", "make", "gui", "cli"]
# What each layer may import (besides the package root, contactwb/__init__.py).
ALLOWED = {
    "core": {"core"},
    "document": {"core", "document"},
    "objects": {"core", "document", "objects"},
    "make": {"core", "document", "objects", "make"},
    "gui": {"core", "document", "objects", "make", "gui"},
    "cli": {"core", "document", "objects", "make", "cli"},
}
# Modules outside the layer folders, with the layer they count as.
TOP_LEVEL = {
    "contactwb.freecad_tests": "cli",  # FreeCAD's test runner's module: headless, like the CLI
}
FREECAD_MODULES = {"FreeCAD", "FreeCADGui", "Part", "PySide2", "PySide", "pivy"}

# Compatibility shims: the module paths of earlier releases (saved documents
# name the view providers' ones; scripts and the README the others), each
# importing only its new homes (layers). Nothing else may import them.
SHIMS = {
    "contactwb.analysis": {"core", "document"},
    "contactwb.joints": {"core", "document"},
    "contactwb.meshes": {"core", "document"},
    "contactwb.trial": {"core", "document"},
    "contactwb.bodies": {"document"},
    "contactwb.export": {"document"},
    "contactwb.freecad_setup": {"document"},
    "contactwb.cli_mesh": {"cli"},
    "contactwb.cli_trial": {"cli"},
    "contactwb.gui.view_providers": {"core", "gui"},
    "contactwb.gui.joint_view": {"gui"},
    "contactwb.gui.simulation_model_view": {"gui"},
    "contactwb.gui.task_panel": {"gui"},
    "contactwb.gui.contact_table": {"gui"},
    "contactwb.gui.haptic_panel": {"gui"},
    "contactwb.gui.partitions_view": {"gui"},
}


def find_modules(root):
    """{module name: file path} of every .py file under root/contactwb."""
    modules = {}
    base = os.path.join(root, PACKAGE)
    for folder, dirs, files in os.walk(base):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__")
        for name in sorted(files):
            if not name.endswith(".py"):
                continue
            path = os.path.join(folder, name)
            parts = os.path.relpath(path, root)[:-3].split(os.sep)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            modules[".".join(parts)] = path
    return modules


def _is_package(path):
    return os.path.basename(path) == "__init__.py"


def _from_base(package, node):
    """The absolute module a `from ... import` node of a module of `package` names
    (relative levels resolved)."""
    if not node.level:
        return node.module
    parts = package.split(".")
    parts = parts[:len(parts) - (node.level - 1)]
    return ".".join(parts + ([node.module] if node.module else []))


def imports_of(name, path, modules):
    """[(target, imported name or None, line)]: every import in the file, at
    any depth (function-local ones too), relative ones resolved. `target` is
    the module imported (for `from m import x`, m.x when that is a module);
    imported name is x when x is a name of m rather than a module."""
    tree = ast.parse(open(path, encoding="utf-8").read(), filename=path)
    package = name if _is_package(path) else name.rpartition(".")[0]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                found.append((alias.name, None, node.lineno))
        elif isinstance(node, ast.ImportFrom):
            base = _from_base(package, node)
            for alias in node.names:
                candidate = f"{base}.{alias.name}"
                if candidate in modules:
                    found.append((candidate, None, node.lineno))
                else:
                    found.append((base, alias.name, node.lineno))
    return found


def packages_run_by(name, path, modules):
    """Packages whose __init__ runs for this file's `from package import x`:
    the cycle check counts them, as Python runs a package's __init__ before
    any module of it (a package __init__ that imports its own modules would
    otherwise hide a cycle: gui/__init__ -> hooks -> ... -> `from gui import settings`)."""
    tree = ast.parse(open(path, encoding="utf-8").read(), filename=path)
    package = name if _is_package(path) else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = _from_base(package, node)
            if base in modules and _is_package(modules[base]):
                found.add(base)
    return found


def private_attribute_uses(path, modules, imported):
    """[(module, attribute, line)]: `alias._x` where alias names a contactwb module."""
    tree = ast.parse(open(path, encoding="utf-8").read(), filename=path)
    aliases = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.asname and alias.name in modules:
                    aliases[alias.asname] = alias.name
        elif isinstance(node, ast.ImportFrom):
            for alias in node.names:
                target = next((t for t, n, _ in imported if n is None and t.endswith("." + alias.name)), None)
                if target in modules:
                    aliases[alias.asname or alias.name] = target
    uses = []
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases
                and node.attr.startswith("_") and not node.attr.startswith("__")):
            uses.append((aliases[node.value.id], node.attr, node.lineno))
    return uses


def layer_of(name):
    if name == PACKAGE:
        return "root"
    if name in TOP_LEVEL:
        return TOP_LEVEL[name]
    parts = name.split(".")
    if len(parts) > 1 and parts[1] in LAYERS:
        return parts[1]
    return None


def graph(root, shims):
    """(modules, {module: [(target module, imported name, line)]} within contactwb)."""
    modules = find_modules(root)
    edges = {}
    for name, path in modules.items():
        edges[name] = [(target, imported, line) for target, imported, line in imports_of(name, path, modules)
                       if target == PACKAGE or target.startswith(PACKAGE + ".")]
    return modules, edges


def cycles(nodes, edges):
    """Strongly connected components of more than one module (or a module importing itself)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []
    counter = [0]

    def visit(node):  # Tarjan, iterative enough for a few hundred modules
        index[node] = low[node] = counter[0]
        counter[0] += 1
        stack.append(node)
        on_stack.add(node)
        for target in edges.get(node, ()):
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1 or node in edges.get(node, ()):
                found.append(sorted(component))

    for node in sorted(nodes):
        if node not in index:
            visit(node)
    return found


def check(root, shims=SHIMS):
    """Every violation of the layering, as readable lines ([] when none)."""
    modules, edges = graph(root, shims)
    problems = []
    for shim in shims:
        if shim not in modules:
            problems.append(f"{shim}: listed as a compatibility shim, but there is no such module")
    for name, path in modules.items():
        relative = os.path.relpath(path, root)
        layer = layer_of(name)
        if name in shims:
            for target, _, line in edges[name]:
                home = layer_of(target)
                if target in shims or target == PACKAGE or home not in shims[name]:
                    problems.append(f"{relative}:{line}: the shim {name} imports {target}, not one of its "
                                    f"new homes ({', '.join(sorted(shims[name]))})")
            continue
        if layer is None:
            problems.append(f"{relative}: {name} is in no layer (put it in one, or list it as a shim)")
            continue
        for target, imported, line in edges[name]:
            if target in shims:
                problems.append(f"{relative}:{line}: {name} imports the compatibility shim {target}: "
                                f"import its new home")
                continue
            target_layer = layer_of(target)
            if layer == "root" and target != PACKAGE:
                problems.append(f"{relative}:{line}: the package root imports {target}")
            elif target_layer not in ALLOWED.get(layer, set()) | {"root"}:
                problems.append(f"{relative}:{line}: {name} ({layer}) imports {target} ({target_layer}): "
                                f"imports go core -> document -> objects -> make -> gui (cli beside gui)")
            if imported and imported.startswith("_") and not imported.startswith("__"):
                problems.append(f"{relative}:{line}: {name} imports the private name {imported} of {target}")
        for target, attribute, line in private_attribute_uses(path, modules, edges[name]):
            if target != name:
                problems.append(f"{relative}:{line}: {name} uses the private name {attribute} of {target}")
        if layer in ("core", "root"):
            for target, _, line in imports_of(name, path, modules):
                if target.split(".")[0] in FREECAD_MODULES:
                    problems.append(f"{relative}:{line}: {name} imports {target}: core never imports FreeCAD "
                                    f"or its GUI (FreeCAD adapters go in contactwb/document)")
    layered = {name: [t for t, _, _ in targets if t in modules and t not in shims]
               + sorted(packages_run_by(name, modules[name], modules) - {name} - set(shims))
               for name, targets in edges.items() if name not in shims}
    for component in cycles(layered, layered):
        problems.append("import cycle: " + " <-> ".join(component))
    return problems


def test_contactwb_is_layered_without_cycles():
    problems = check(REPO)
    assert not problems, "\n".join(problems)


def test_every_module_is_in_a_layer_or_a_shim():
    modules = find_modules(REPO)
    assert {layer_of(name) for name in modules if name not in SHIMS} <= set(LAYERS) | {"root"}
    # the layers exist, and the graph sees function-local imports (the CLI's are all local)
    for layer in LAYERS:
        assert any(layer_of(name) == layer for name in modules), layer
    _, edges = graph(REPO, SHIMS)
    assert any(target.startswith("contactwb.document") for target, _, _ in edges["contactwb.cli.contacts"])


def _write(root, name, text):
    path = os.path.join(root, *name.split("/"))
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as stream:
        stream.write(text)


def test_checker_catches_violations(tmp_path):
    root = str(tmp_path)
    for folder in ("", "core/", "document/", "objects/", "make/", "gui/", "cli/"):
        _write(root, f"contactwb/{folder}__init__.py", "")
    _write(root, "contactwb/core/kinds.py", "def f():\n    import FreeCAD\n")                 # FreeCAD in core
    _write(root, "contactwb/document/bodies.py", "from contactwb.objects import proxies\n")  # upward
    _write(root, "contactwb/objects/proxies.py", "from ..document import bodies\n")           # cycle (relative)
    _write(root, "contactwb/make/maker.py", "def g():\n    from contactwb.gui import view\n")  # upward, local
    _write(root, "contactwb/gui/view.py", "from contactwb.core.kinds import _private\n")      # private name
    _write(root, "contactwb/gui/panel.py", "from contactwb.core import kinds\nkinds._hidden()\n")  # private use
    _write(root, "contactwb/cli/tool.py", "import contactwb.gui.view\nfrom contactwb import old\n")  # gui; shim
    _write(root, "contactwb/old.py", "from contactwb.gui import view as _home\n")  # shim outside its home
    problems = check(root, shims={"contactwb.old": {"core"}})
    text = "\n".join(problems)
    assert "contactwb.core.kinds imports FreeCAD" in text
    assert "contactwb.document.bodies (document) imports contactwb.objects.proxies (objects)" in text
    assert "import cycle: contactwb.document.bodies <-> contactwb.objects.proxies" in text
    assert "contactwb.make.maker (make) imports contactwb.gui.view (gui)" in text
    assert "imports the private name _private of contactwb.core.kinds" in text
    assert "uses the private name _hidden of contactwb.core.kinds" in text
    assert "contactwb.cli.tool (cli) imports contactwb.gui.view (gui)" in text
    assert "contactwb.cli.tool imports the compatibility shim contactwb.old" in text
    assert "the shim contactwb.old imports contactwb.gui.view" in text
    assert len(problems) == 9, text


def test_cycle_through_a_package_init_is_caught(tmp_path):
    """A package __init__ importing its own module, which imports from the package, is a cycle."""
    root = str(tmp_path)
    _write(root, "contactwb/__init__.py", "")
    _write(root, "contactwb/gui/__init__.py", "from contactwb.gui import hooks\n")
    _write(root, "contactwb/gui/hooks.py", "from contactwb.gui import settings\n")
    _write(root, "contactwb/gui/settings.py", "")
    problems = check(root, shims={})
    assert problems == ["import cycle: contactwb.gui <-> contactwb.gui.hooks"], problems
