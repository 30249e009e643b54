#!/bin/bash
# Compiler launcher for bench/build_cost.py: appends "user sys wall output" of each
# compile to $TIMECC_LOG (CMAKE_CXX_COMPILER_LAUNCHER=bench/timecc.sh, CCACHE_DISABLE=1).
out=""; prev=""
for a in "$@"; do [ "$prev" = "-o" ] && out=$a; prev=$a; done
exec /usr/bin/time -a -o "${TIMECC_LOG:-/dev/null}" -f "%U %S %e $out" "$@"
