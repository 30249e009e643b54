"""The best run of each file from bench_contacts (bench/bench_contacts.cpp),
for the scripts that time the contact pipeline (run_benchmarks.py,
bench_interferences.py)."""
import json
import subprocess


def best_runs(exe, files, repeat, rows=None, extra_args=()):
    """Runs `exe [extra_args] --repeat N files` and keeps, per file and per run
    kind ("bare" XDE read, "ours" pipeline), the fastest row of its JSON lines
    (bare by "seconds", ours by "total") in rows {file: {kind: row}}, which it
    returns. A row with an "error" ends the script with its message."""
    rows = {} if rows is None else rows
    out = subprocess.run([exe, *extra_args, "--repeat", str(repeat), *files], capture_output=True, text=True)
    for line in out.stdout.splitlines():
        if not line.startswith("{"):
            continue
        row = json.loads(line)
        if "error" in row:
            raise SystemExit(f"bench_contacts failed on {row['file']}: {row['error']}")
        key = "seconds" if row["run"] == "bare" else "total"
        best = rows.setdefault(row["file"], {}).get(row["run"])
        if best is None or row[key] < best[key]:
            rows[row["file"]][row["run"]] = row
    return rows
