"""The C++ core's stage folders include one another one way only: the arrows
of docs/architecture.md (and docs/images/architecture.dot), read from the
#include lines of cpp_module/src and cpp_module/include."""
import os
import re

from conftest import REPO

CPP = os.path.join(REPO, "cpp_module")
STAGES = ["common", "bodies", "partitions", "contacts", "joints", "simulation", "haptics"]
# Which stages each stage may include (besides itself), as drawn in docs/architecture.md.
ALLOWED = {
    "common": set(),
    "bodies": {"common"},
    "partitions": {"common"},
    "contacts": {"common", "bodies", "partitions"},
    "joints": {"common", "contacts"},
    "simulation": {"common", "bodies", "partitions", "contacts", "joints"},
    "haptics": {"common", "bodies", "partitions", "contacts", "joints", "simulation"},
}
INCLUDE = re.compile(r'^#include "(?:contactcore/)?([a-z_]+)/[^"]+"', re.M)


def stage_includes():
    found = {stage: {} for stage in STAGES}
    for stage in STAGES:
        for folder in (os.path.join(CPP, "src", stage), os.path.join(CPP, "include", "contactcore", stage)):
            for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
                if not name.endswith((".h", ".cpp")):
                    continue
                with open(os.path.join(folder, name), encoding="utf-8") as stream:
                    for used in INCLUDE.findall(stream.read()):
                        if used != stage:
                            found[stage].setdefault(used, []).append(f"{stage}/{name}")
    return found


def test_every_stage_has_its_folders():
    for stage in STAGES:
        assert os.path.isdir(os.path.join(CPP, "src", stage)), stage
        assert os.path.isfile(os.path.join(CPP, "src", stage, "README.md")), stage


def test_stages_include_only_earlier_stages():
    found = stage_includes()
    for stage, used in found.items():
        assert set(used) <= set(STAGES), (stage, used)
        wrong = {other: files for other, files in used.items() if other not in ALLOWED[stage]}
        assert not wrong, f"{stage} includes {wrong}"
    # The rule the table encodes: no stage includes a later one.
    for stage, allowed in ALLOWED.items():
        assert all(STAGES.index(other) < STAGES.index(stage) for other in allowed), stage


def test_the_drawing_has_the_same_arrows():
    with open(os.path.join(REPO, "docs", "images", "architecture.dot"), encoding="utf-8") as stream:
        dot = stream.read()
    drawn = {stage: set() for stage in STAGES}
    for source, targets in re.findall(r"^\s*(\w+) -> \{?([\w ]+)\}?;", dot, re.M):
        drawn[source] |= set(targets.split())
    found = stage_includes()
    for stage in STAGES:
        # Every stage includes common; the drawing leaves those arrows out.
        assert drawn[stage] == set(found[stage]) - {"common"}, stage
