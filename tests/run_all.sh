#!/usr/bin/env bash
# Runs every test suite (GoogleTest via ctest, pytest headless, pytest GUI
# under Xvfb), keeps going after a failure, and ends with one summary line
# and the totals ("N passed, N failed, N skipped").
set -u
build_dir=$(realpath "${1:-build}")
cd "$(dirname "$0")/.."
export CONTACTS_BUILD_DIR="$build_dir"
export CONTACTS_PYTHON_DIR="$build_dir/python"
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
status=0
declare -A result

run_suite() {  # name, command...
  local name=$1
  shift
  if "$@" 2>&1 | tee "$logs/$name.log"; [ "${PIPESTATUS[0]}" -eq 0 ]; then
    result[$name]=ok
  else
    result[$name]=FAILED
    status=1
  fi
}

echo "== GoogleTest (ctest)"
run_suite cpp bash -c "cd '$build_dir' && ctest --output-on-failure"
echo "== pytest (headless, FreeCAD as a library)"
run_suite python /usr/bin/python3 -m pytest -q -rs -p no:cacheprovider tests --ignore=tests/gui
echo "== pytest (FreeCAD GUI under Xvfb)"
run_suite gui /usr/bin/python3 -m pytest -q -rs -p no:cacheprovider tests/gui

# Totals: ctest prints "N tests failed out of M"; pytest "N passed, N failed, N skipped".
count() {  # pattern file
  grep -oE "$1" "$2" | tail -1 | grep -oE '^[0-9]+' || echo 0
}
ctest_total=$(grep -oE 'tests failed out of [0-9]+' "$logs/cpp.log" | grep -oE '[0-9]+$' || echo 0)
ctest_failed=$(count '[0-9]+ tests failed' "$logs/cpp.log")
passed=$((ctest_total - ctest_failed)) failed=$ctest_failed skipped=0
# A suite whose tests were all skipped is not "ok": it says so, and why
# (pytest -rs lists "SKIPPED [n] file:line: reason").
for suite in python gui; do
  suite_passed=$(count '[0-9]+ passed' "$logs/$suite.log")
  suite_skipped=$(count '[0-9]+ skipped' "$logs/$suite.log")
  passed=$((passed + suite_passed))
  failed=$((failed + $(count '[0-9]+ failed' "$logs/$suite.log") + $(count '[0-9]+ error' "$logs/$suite.log")))
  skipped=$((skipped + suite_skipped))
  if [ "$suite_skipped" -gt 0 ]; then
    reasons=$(grep -E '^SKIPPED \[' "$logs/$suite.log" | sed -E 's/^SKIPPED \[[0-9]+\] [^ ]*: //' | sort -u | head -3 | paste -sd ';' -)
    if [ "${result[$suite]}" = ok ] && [ "$suite_passed" -eq 0 ]; then result[$suite]="not run"; fi
    result[$suite]="${result[$suite]} ($suite_skipped skipped: $reasons)"
  fi
done

echo "Summary: C++ ${result[cpp]}, Python ${result[python]}, GUI ${result[gui]}"
echo "$passed passed, $failed failed, $skipped skipped"
exit $status
