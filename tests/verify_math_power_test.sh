#!/usr/bin/env bash
# verify math must be able to fail: with lavapipe's fragment-stage denormals taken as preserved instead of flushed
# (--profile-set denormFragment=preserve), fewer than all 260,000 results are identical, and every function that
# differs names in its JSON report a first difference whose emulator and device values differ (the report used to give
# the scalar build against the compute stage whatever comparison differed).
# Usage: verify_math_power_test.sh SHADETWIN WORK_DIR
set -uo pipefail
bin=$1 work=$2
mkdir -p "$work"
"$bin" verify math --count 20000 --seed 1 --profile-set denormFragment=preserve --json "$work/math.json" | tail -n 1
[ "${PIPESTATUS[0]}" != 0 ] || { echo "verify math: FAIL: exit status 0 with the wrong denormal mode"; exit 1; }
python3 - "$work/math.json" <<'PY'
import json, sys
cases = [c for c in json.load(open(sys.argv[1]))["cases"] if c["first_difference"]]
assert cases, "no case with a difference"
for c in cases:
    d = c["first_difference"]
    assert d["emulator_bits"] != d["device_bits"], (c["name"], d)
print(f"verify math power: {len(cases)} functions differ, each first difference names two different values")
PY
