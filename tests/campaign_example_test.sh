#!/usr/bin/env bash
# The shipped example campaign (issue 21, "Done means"): campaigns/example.json, every shipped scene x every technique
# x both software devices, submitted in full to a private single-node Slurm (scripts/slurm_local.sh, stopped
# afterwards) as a job array, gathered; every job that runs passes bit for bit, the scene's refusals are skipped with
# their reason, and the report page is written with the matrix of every job.
# Usage: campaign_example_test.sh SHADETWIN SOURCE_DIR WORK_DIR
set -euo pipefail
bin=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
work=$(cd "$work" && pwd)
camp=$src/campaigns/example.json
fail() { echo "campaign example: FAIL: $*"; exit 1; }

"$bin" campaign plan "$camp" > "$work/plan.txt"
plan=$(grep '^plan:' "$work/plan.txt") || fail "no plan line"
read -r total torun skipped < <(sed -E 's/^plan: ([0-9]+) jobs \(([0-9]+) to run, ([0-9]+) skipped by the scene\)$/\1 \2 \3/' <<< "$plan")
[ "$total" -gt 300 ] && [ $((torun + skipped)) = "$total" ] || fail "plan: $plan"

trap 'bash "$src/scripts/slurm_local.sh" stop "$work/cluster"' EXIT
eval "$(bash "$src/scripts/slurm_local.sh" start "$work/cluster")"
start=$(date +%s)
set +e
"$bin" campaign submit "$camp" --out "$work/slurm" --chunk 10 --wait > "$work/submit.txt" 2>&1; rs=$?
"$bin" campaign gather "$camp" --out "$work/slurm" > "$work/gather.txt" 2>&1; rg=$?
set -e
tail -n 3 "$work/submit.txt"; cat "$work/gather.txt"
tasks=$(( (total + 9) / 10 ))
grep -q "$total jobs as $tasks Slurm array tasks" "$work/submit.txt" || fail "submit"
[ $rs = 0 ] || fail "sbatch --wait exit status $rs"
[ $rg = 0 ] || fail "gather exit status $rg"
grep -q "campaign example: $torun passed, 0 differ, 0 failed, 0 missing, $skipped skipped" "$work/gather.txt" || fail "gather"
[ "$(ls "$work/slurm/slurm/"task_*.out | wc -l)" = "$tasks" ] || fail "not one Slurm log per array task"
# The CSV, row by row: the statuses the plan promised, and every verify job identical over its whole total.
python3 - "$work/slurm/campaign.csv" "$total" "$torun" "$skipped" <<'PY' || fail "campaign.csv"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
total, torun, skipped = map(int, sys.argv[2:])
assert len(rows) == total, len(rows)
status = [r["status"] for r in rows]
assert status.count("passed") == torun and status.count("skipped") == skipped, set(status)
frames = [r for r in rows if r["suite"] == "frame" and r["status"] == "passed"]
assert frames and all(r["identical"] == r["total"] and int(r["total"]) > 0 for r in frames)
devices = {r["device"] for r in frames}
assert devices == {"lavapipe", "swiftshader"}, devices
assert all(r["skip_reason"] for r in rows if r["status"] == "skipped")
print(f"campaign example: {len(frames)} whole frames bit-identical on {len(devices)} devices, {skipped} refusals with reasons")
PY
grep -q 'class="passed"' "$work/slurm/report.html" || fail "report"
echo "campaign example: $torun jobs through Slurm ($tasks array tasks) in $(( $(date +%s) - start )) s, all passed"
