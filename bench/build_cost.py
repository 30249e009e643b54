"""The CPU a cold build of the extension costs, per translation unit and per
target, and its wall time on idle cores estimated from those figures.

Input: the log a compiler launcher writes, one line per compile,
"USER_S SYS_S WALL_S OUTPUT" (bench/timecc.sh as CMAKE_CXX_COMPILER_LAUNCHER,
with TIMECC_LOG set and CCACHE_DISABLE=1). Wall time measured on a loaded
machine means nothing; the estimate schedules each compile's CPU time (user +
sys) on JOBS idle cores, the way the generator runs them:

- Make (CMake's Unix Makefiles): target after target (contactcore, then
  contactcore_haptics, then contactcore_py), each starting with its
  precompiled header alone, then its sources in list order, a free core taking
  the next one;
- Ninja: one pool; a source waits only for its own target's precompiled header.

Then the link (--link-seconds, not in the log: the linker is no compiler
launch) on one core. Two bounds beside the estimate: the CPU bound (all the
CPU spread evenly on the cores) and the critical path (the longest chain of
compiles that wait for each other: a target's precompiled header, then its
most expensive source), and the time the Ninja schedule leaves a core idle at
the end (the last compile finishing alone).

With --compare OTHER_LOG: the two builds side by side, per object (e.g. the
same sources before and after a change, or g++ against clang).

    python3 bench/build_cost.py LOG [--jobs 2] [--link-seconds 3] [--compare OTHER_LOG]"""
import argparse
import heapq
import re


def read_log(path):
    """[(output, cpu seconds)] in the order the compiles started."""
    rows = []
    for line in open(path):
        parts = line.split()
        if len(parts) != 4:
            continue  # "Command exited with non-zero status" and the like
        user, system, _, output = parts
        rows.append((output, float(user) + float(system)))
    return rows


def object_key(output):
    """The object's name without the compiler's suffix for a precompiled
    header (g++ writes .gch, clang .pch), so two builds' logs line up."""
    return re.sub(r"cmake_pch\.hxx\.(gch|pch)$", "cmake_pch.hxx", output)


def target_of(output):
    for name in ("contactcore_haptics", "contactcore_py", "contactcore"):
        if f"{name}.dir/" in output:
            return name
    return "other"


def is_pch(output):
    return "cmake_pch" in output


def schedule(jobs, cores, ready_at=None):
    """Greedy list schedule: each job (name, seconds, earliest start) to the core
    free first, in order. Returns the time the last one ends."""
    free = [0.0] * cores
    heapq.heapify(free)
    end = 0.0
    for _, seconds, earliest in jobs:
        start = max(heapq.heappop(free), earliest)
        heapq.heappush(free, start + seconds)
        end = max(end, start + seconds)
    return end


TARGETS = ("contactcore", "contactcore_haptics", "contactcore_py")


def make_estimate(rows, cores):
    clock = 0.0
    for target in TARGETS:
        mine = [r for r in rows if target_of(r[0]) == target]
        pch = sum(s for o, s in mine if is_pch(o))
        clock += pch
        clock = schedule([(o, s, clock) for o, s in mine if not is_pch(o)], cores) or clock
    return clock


def ninja_estimate(rows, cores):
    return ninja_schedule(rows, cores)[0]


def ninja_schedule(rows, cores):
    """(end, idle tail): when the last compile ends, and for how long before
    that at least one core has nothing left to do."""
    # The three headers first (nothing else is ready before them), each
    # target's sources as soon as its header is there.
    free = [0.0] * cores
    heapq.heapify(free)
    pch_done = {}
    for target in TARGETS:
        for output, seconds in rows:
            if target_of(output) == target and is_pch(output):
                start = heapq.heappop(free)
                heapq.heappush(free, start + seconds)
                pch_done[target] = start + seconds
    end = max(pch_done.values(), default=0.0)
    for output, seconds in rows:
        if is_pch(output):
            continue
        start = max(heapq.heappop(free), pch_done.get(target_of(output), 0.0))
        heapq.heappush(free, start + seconds)
        end = max(end, start + seconds)
    # A core is idle from the moment it finishes its last compile.
    return end, end - min(free)


def shared_schedule(rows, cores, beside_cpu=0.0, beside_start=0.0):
    """When the last compile ends if Ninja runs `cores` compiles at a time
    while another process (the packages `make run` installs beside the
    build: dpkg, about one core) needs `beside_cpu` seconds of CPU from
    `beside_start` on. The cores are shared evenly among whatever runs (three
    processes on two cores: two thirds of a core each, as Linux's scheduler
    gives them); Ninja starts, whenever one of its compiles ends, the first
    compile in log order whose target's precompiled header is there.
    Returns (end of the compiles, end of the process beside)."""
    pending = list(range(len(rows)))
    with_pch = {target_of(o) for o, _ in rows if is_pch(o)}
    done_pch = set()
    running = {}  # index in rows -> CPU seconds left
    beside_left = beside_cpu
    beside_end = beside_start if beside_cpu <= 0 else None
    clock = 0.0
    while True:
        while len(running) < cores:
            ready = next((i for i in pending if is_pch(rows[i][0]) or target_of(rows[i][0]) not in with_pch
                          or target_of(rows[i][0]) in done_pch), None)
            if ready is None:
                break
            pending.remove(ready)
            running[ready] = rows[ready][1]
        beside_on = beside_left > 0 and clock >= beside_start
        if not running and not pending:
            if beside_left > 0:
                start = max(clock, beside_start)
                beside_end = start + beside_left
            return clock, beside_end
        share = min(1.0, cores / (len(running) + beside_on))
        steps = [left / share for left in running.values()]
        if beside_on:
            steps.append(beside_left / share)
        elif beside_left > 0:
            steps.append(beside_start - clock)
        step = min(steps)
        clock += step
        for i in list(running):
            running[i] -= step * share
            if running[i] <= 1e-9:
                del running[i]
                if is_pch(rows[i][0]):
                    done_pch.add(target_of(rows[i][0]))
        if beside_on:
            beside_left -= step * share
            if beside_left <= 1e-9:
                beside_left = 0.0
                beside_end = clock


def make_run_estimate(rows, cores, before, beside_cpu, beside_start, link, after):
    """The whole `make run` on idle cores: the package step before the build
    (`before`: apt-get update, the build's packages downloaded and
    installed), the compiles shared with the packages installed beside them,
    the link, then `after` (installing the workbench, the motor's contacts).
    The link waits for the compiles, `after` for the packages beside too."""
    compiles, beside = shared_schedule(rows, cores, beside_cpu, beside_start)
    return before + max(compiles + link, beside) + after


def cpu_bound(rows, cores):
    return sum(s for _, s in rows) / cores


def critical_path(rows):
    """(seconds, target): the longest chain, a target's precompiled header
    then its most expensive source."""
    best = (0.0, "")
    for target in TARGETS:
        mine = [(o, s) for o, s in rows if target_of(o) == target]
        pch = sum(s for o, s in mine if is_pch(o))
        longest = max((s for o, s in mine if not is_pch(o)), default=0.0)
        best = max(best, (pch + longest, target))
    return best


def compare(rows, other_rows):
    """[(object, seconds here, seconds there)] for the objects of both logs, in
    this log's order."""
    there = {object_key(o): s for o, s in other_rows}
    return [(object_key(o), s, there[object_key(o)]) for o, s in rows if object_key(o) in there]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("log")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--link-seconds", type=float, default=3.0)
    parser.add_argument("--top", type=int, default=12, help="the most expensive compiles listed")
    parser.add_argument("--compare", help="a second log: both builds' CPU per object")
    parser.add_argument("--packages-before", type=float, metavar="S",
                        help="the whole `make run`: seconds of the package step before the build")
    parser.add_argument("--packages-beside", type=float, default=0.0, metavar="CPU_S",
                        help="CPU seconds of the packages installed beside the build (one process)")
    parser.add_argument("--beside-start", type=float, default=0.0, metavar="S",
                        help="when, after the build's start, those packages start installing (their download)")
    parser.add_argument("--after", type=float, default=0.0, metavar="S",
                        help="seconds after the build: installing the workbench, the motor's contacts")
    args = parser.parse_args()
    rows = read_log(args.log)
    total = sum(s for _, s in rows)
    print(f"{len(rows)} compiles, {total:.0f} s of CPU (user + sys)")
    for target in TARGETS:
        print(f"  {target}: {sum(s for o, s in rows if target_of(o) == target):.0f} s")
    print(f"the {args.top} most expensive:")
    for output, seconds in sorted(rows, key=lambda r: -r[1])[:args.top]:
        print(f"  {seconds:6.1f} s  {output}")
    for name, estimate in (("Make", make_estimate), ("Ninja", ninja_estimate)):
        wall = estimate(rows, args.jobs) + args.link_seconds
        print(f"idle wall at -j{args.jobs}, {name}: {wall:.0f} s ({wall / 60:.1f} min)")
    _, tail = ninja_schedule(rows, args.jobs)
    print(f"  Ninja's last {tail:.0f} s with a core idle")
    path, target = critical_path(rows)
    print(f"bounds: CPU / {args.jobs} cores + link {cpu_bound(rows, args.jobs) + args.link_seconds:.0f} s;"
          f" critical path {path + args.link_seconds:.0f} s ({target}: header, its most expensive source, link)")
    if args.packages_before is not None:
        compiles, beside = shared_schedule(rows, args.jobs, args.packages_beside, args.beside_start)
        total = make_run_estimate(rows, args.jobs, args.packages_before, args.packages_beside,
                                  args.beside_start, args.link_seconds, args.after)
        print(f"make run on {args.jobs} idle cores: {args.packages_before:.0f} s of packages, then the"
              f" compiles end at {compiles:.0f} s with {args.packages_beside:.0f} s of CPU installed beside"
              f" (done at {beside:.0f} s), link {args.link_seconds:.0f} s, after {args.after:.0f} s:"
              f" {total:.0f} s ({total / 60:.1f} min)")
    if args.compare:
        pairs = compare(rows, read_log(args.compare))
        print(f"per object: {args.log}, {args.compare}, the second's change:")
        for output, here, there in pairs:
            print(f"  {here:6.1f} s  {there:6.1f} s  {there / here - 1:+6.0%}  {output}" if here
                  else f"  {here:6.1f} s  {there:6.1f} s  {output}")
        here_total, there_total = sum(p[1] for p in pairs), sum(p[2] for p in pairs)
        print(f"  {here_total:6.1f} s  {there_total:6.1f} s  {there_total / here_total - 1:+6.0%}  "
              f"all {len(pairs)} objects of both")


if __name__ == "__main__":
    main()
