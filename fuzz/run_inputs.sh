#!/usr/bin/env bash
# Runs a fuzz target once on every file of the given folders (the seeds, the regression inputs); folders that do not
# exist are skipped. Usage: run_inputs.sh FUZZ_TARGET DIR...
set -euo pipefail
bin=$1
shift
files=()
for d in "$@"; do
  [ -d "$d" ] || continue
  for f in "$d"/*; do [ -f "$f" ] && files+=("$f"); done
done
[ ${#files[@]} -gt 0 ] || { echo "no inputs in $*"; exit 1; }
echo "running $(basename "$bin") on ${#files[@]} inputs"
exec "$bin" "${files[@]}"
