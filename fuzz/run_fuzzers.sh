#!/usr/bin/env bash
# Runs each libFuzzer target for a bounded time on a working copy of its seed
# corpus (fuzz/corpus/<target>/ stays as committed), then prints one line of
# figures per target. Fails if any target found a crash, leak, timeout or
# out-of-memory input (saved in <build>/fuzz-artifacts/<target>/).
#   fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]
# FUZZ_MERGE=1: also merge (minimised) what each run found back into fuzz/corpus/<target>/.
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
  echo "== $target: ${seconds} s on $(ls "$corpus" | wc -l) inputs (log: $log)"
  # -close_fd_mask=1: OCCT may print to stdout; crash reports go to stderr.
  "$build_dir/fuzz/$target" "$corpus" "${dict[@]}" -max_total_time="$seconds" -timeout=30 \
    -rss_limit_mb=2048 -max_len=65536 -close_fd_mask=1 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" > "$log" 2>&1
  rc=$?
  runs=$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -oE '[0-9]+$')
  speed=$(grep -oE 'stat::average_exec_per_sec: *[0-9]+' "$log" | grep -oE '[0-9]+$')
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1)
  cov=$(grep -oE 'cov: [0-9]+' <<<"$last" | grep -oE '[0-9]+')
  ft=$(grep -oE 'ft: [0-9]+' <<<"$last" | grep -oE '[0-9]+')
  corp=$(grep -oE 'corp: [0-9]+/[0-9]+[a-zA-Z]*' <<<"$last" | cut -d' ' -f2)
  found=$(ls "$artifacts" | wc -l)
  line="$target: ${runs:-?} runs, ${speed:-?} exec/s, corpus ${corp:-?} (inputs/bytes), cov ${cov:-?}, ft ${ft:-?}, exit $rc, findings $found"
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
