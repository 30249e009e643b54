#!/usr/bin/env bash
# Runs every test suite (GoogleTest via ctest, pytest headless, pytest GUI
# under Xvfb), keeps going after a failure, and ends with one summary line.
set -u
build_dir=$(realpath "${1:-build}")
cd "$(dirname "$0")/.."
export CONTACTS_BUILD_DIR="$build_dir"
export CONTACTS_PYTHON_DIR="$build_dir/python"
status=0
declare -A result

echo "== GoogleTest (ctest)"
if (cd "$build_dir" && ctest --output-on-failure); then result[cpp]=ok; else result[cpp]=FAILED; status=1; fi

echo "== pytest (headless, FreeCAD as a library)"
/usr/bin/python3 -m pytest -q -p no:cacheprovider tests --ignore=tests/gui
rc=$?
if [ $rc -eq 0 ]; then result[python]=ok; else result[python]=FAILED; status=1; fi

echo "== pytest (FreeCAD GUI under Xvfb)"
/usr/bin/python3 -m pytest -q -p no:cacheprovider tests/gui
rc=$?
if [ $rc -eq 0 ]; then result[gui]=ok; else result[gui]=FAILED; status=1; fi

echo "Summary: C++ ${result[cpp]}, Python ${result[python]}, GUI ${result[gui]}"
exit $status
