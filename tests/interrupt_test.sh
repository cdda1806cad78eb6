#!/usr/bin/env bash
# An interrupted run (issue 20, item 4): `shadetwin sweep` is stopped by SIGINT (then SIGTERM) while its CSV is being
# written; afterwards the output folder holds no partial or hidden file and the previous sweep.csv is intact.
# Usage: interrupt_test.sh SHADETWIN SCENE OUT_DIR
set -u -m  # -m: the background run gets its own process group and keeps SIGINT (non-interactive shells ignore it)
bin=$1 scene=$2 out=$3
fail() { echo "FAIL: $*"; exit 1; }
for sig in INT TERM; do
  rm -rf "$out" && mkdir -p "$out" || fail "cannot make $out"
  echo "previous result" > "$out/sweep.csv"
  "$bin" sweep --scene "$scene" --technique fis --samples 64,128,256,512,1024,2048 --reference-spp 4 --width 128 --height 96 \
    --out "$out" > "$out.log" 2>&1 &
  pid=$!
  seen=""
  for _ in $(seq 1200); do  # until the sweep's CSV temporary exists (at most 120 s)
    seen=$(find "$out" -name '.tmp-*' | head -1)
    [ -n "$seen" ] && break
    kill -0 "$pid" 2> /dev/null || break
    sleep 0.1
  done
  [ -n "$seen" ] || { kill "$pid" 2> /dev/null; fail "SIG$sig: no temporary appeared in $out (log: $(tail -3 "$out.log"))"; }
  kill -"$sig" "$pid"
  wait "$pid"
  status=$?
  want=$((128 + $(kill -l "$sig")))
  [ "$status" -eq "$want" ] || fail "SIG$sig: exit status $status, expected $want (killed by the signal)"
  left=$(find "$out" -mindepth 1 ! -name sweep.csv ! -name reference.exr)  # reference.exr: completed before the CSV began
  [ -z "$left" ] || fail "SIG$sig: left behind: $left"
  [ "$(cat "$out/sweep.csv")" = "previous result" ] || fail "SIG$sig: the previous sweep.csv was changed"
  echo "SIG$sig: stopped while writing $(basename "$seen"); exit $status; $out holds the previous sweep.csv and no temporary"
done
echo "interrupt: ok"
