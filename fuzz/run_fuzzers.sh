#!/usr/bin/env bash
# Runs each libFuzzer target for a bounded time on a working copy of its seed
# corpus (fuzz/corpus/<target>/ stays as committed), then prints one line of
# figures per target. Fails if any target found a crash, leak, timeout or
# out-of-memory input (saved in <build>/fuzz-artifacts/<target>/).
#   fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]
# FUZZ_MERGE=1: also merge (minimised) what each run found back into fuzz/corpus/<target>/.
# FUZZ_FORK_TARGETS (default fuzz_step): targets run with libFuzzer's -fork=1, a fresh child process
# per job (job k runs min(k, 300) s: 1 s, 2 s, ... so about 10 jobs in 60 s), so that state OCCT's
# STEP reader keeps in a process (static sessions, caches, memory growth) cannot build up over a
# whole run and one input's leftovers cannot make a later one time out; crashes, timeouts and
# out-of-memory inputs still stop the run (-ignore_*=0) and land in the artifacts.
# FUZZ_STEP_SECONDS: fuzz_step's time when it should differ from SECONDS (docs/reliability.md:
# 60 s is the floor, 600 s a run that matters).
set -u
build_dir=$(realpath "${1:-build-fuzz}")
seconds=${2:-60}
shift 2 || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(fuzz_step fuzz_brep fuzz_hid)
repo=$(cd "$(dirname "$0")/.." && pwd)
work="$build_dir/fuzz-run"
mkdir -p "$work"
# OCCT's own allocations are not instrumented and it keeps caches for the
# process's life (fuzz/lsan.supp); UBSan stops at the first finding.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$repo/fuzz/lsan.supp:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-suppressions=$repo/fuzz/ubsan.supp:print_stacktrace=1:halt_on_error=1}"
fork_targets=" ${FUZZ_FORK_TARGETS-fuzz_step} "
status=0
summary="$work/summary.txt"
: > "$summary"
for target in "${targets[@]}"; do
  corpus="$work/corpus/$target"
  artifacts="$build_dir/fuzz-artifacts/$target"
  # What an earlier run found is kept aside (copy it into fuzz/regressions/).
  if [ -n "$(ls -A "$artifacts" 2>/dev/null)" ]; then
    mkdir -p "$build_dir/fuzz-artifacts/previous/$target"
    mv "$artifacts"/* "$build_dir/fuzz-artifacts/previous/$target/"
  fi
  mkdir -p "$corpus" "$artifacts"
  cp -n "$repo/fuzz/corpus/$target/"* "$corpus/"
  dict=()
  [ -f "$repo/fuzz/$target.dict" ] && dict=(-dict="$repo/fuzz/$target.dict")
  log="$work/$target.log"
  target_seconds=$seconds
  [ "$target" = fuzz_step ] && target_seconds=${FUZZ_STEP_SECONDS:-$seconds}
  fork=()
  mode="one process"
  if [[ "$fork_targets" == *" $target "* ]]; then
    fork=(-fork=1 -ignore_crashes=0 -ignore_timeouts=0 -ignore_ooms=0)
    mode="a child process per job (-fork=1)"
  fi
  echo "== $target: ${target_seconds} s on $(ls "$corpus" | wc -l) inputs, $mode (log: $log)"
  # -close_fd_mask=1: OCCT may print to stdout; crash reports go to stderr.
  "$build_dir/fuzz/$target" "$corpus" "${dict[@]}" "${fork[@]}" -max_total_time="$target_seconds" -timeout=30 \
    -rss_limit_mb=2048 -max_len=65536 -close_fd_mask=1 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" > "$log" 2>&1
  rc=$?
  if [ ${#fork[@]} -eq 0 ]; then
    runs=$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -oE '[0-9]+$')
    speed=$(grep -oE 'stat::average_exec_per_sec: *[0-9]+' "$log" | grep -oE '[0-9]+$')
    last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1)
    corp=$(grep -oE 'corp: [0-9]+/[0-9]+[a-zA-Z]*' <<<"$last" | cut -d' ' -f2)
    jobs=""
  else
    # The parent's progress lines: "#RUNS: cov: C ft: F corp: N exec/s S oom/timeout/crash: a/b/c time: Ts job: J".
    last=$(grep -E '^#[0-9]+: cov: ' "$log" | tail -1)
    runs=$(grep -oE '^#[0-9]+' <<<"$last" | tr -d '#')
    speed=$(grep -oE 'exec/s [0-9]+' <<<"$last" | grep -oE '[0-9]+')
    corp="$(grep -oE 'corp: [0-9]+' <<<"$last" | grep -oE '[0-9]+')/?"
    jobs=", $(grep -oE 'job: [0-9]+' <<<"$last" | grep -oE '[0-9]+') child processes, oom/timeout/crash $(grep -oE 'oom/timeout/crash: [0-9/]+' <<<"$last" | cut -d' ' -f2)"
  fi
  cov=$(grep -oE 'cov: [0-9]+' <<<"$last" | grep -oE '[0-9]+')
  ft=$(grep -oE 'ft: [0-9]+' <<<"$last" | grep -oE '[0-9]+')
  found=$(ls "$artifacts" | wc -l)
  line="$target: ${target_seconds} s, ${runs:-?} runs, ${speed:-?} exec/s, corpus ${corp:-?} (inputs/bytes), cov ${cov:-?}, ft ${ft:-?}${jobs}, exit $rc, findings $found"
  echo "$line" | tee -a "$summary"
  if [ "$rc" -ne 0 ] || [ "$found" -ne 0 ]; then
    status=1
    grep -E 'ERROR|SUMMARY|fuzz check failed|^    #[0-9]' "$log" | head -30
    ls "$artifacts"
  fi
  if [ "${FUZZ_MERGE:-0}" = 1 ]; then
    "$build_dir/fuzz/$target" -merge=1 -close_fd_mask=1 -timeout=30 -rss_limit_mb=2048 \
      "$repo/fuzz/corpus/$target" "$corpus" > "$work/$target.merge.log" 2>&1 || status=1
  fi
done
echo "Summary ($summary):"
cat "$summary"
exit $status
