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
launch) on one core.

    python3 bench/build_cost.py LOG [--jobs 2] [--link-seconds 3]"""
import argparse
import heapq


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
    return end


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("log")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--link-seconds", type=float, default=3.0)
    parser.add_argument("--top", type=int, default=12, help="the most expensive compiles listed")
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


if __name__ == "__main__":
    main()
