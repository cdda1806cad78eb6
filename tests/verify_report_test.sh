#!/usr/bin/env bash
# verify --junit / --json (issue 21 item 3): a passing and a failing suite, each report validated against its schema
# (tests/junit.xsd with xmllint, tests/verify_report.schema.json with python3-jsonschema), and a broken report that the
# schema rejects (the validation can fail). Usage: verify_report_test.sh SHADETWIN SOURCE_DIR WORK_DIR
set -euo pipefail
bin=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
py=python3
$py -c "import jsonschema" 2>/dev/null || py=/usr/bin/python3
check_json() { $py -c "import json,sys,jsonschema; jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))" "$1" "$src/tests/verify_report.schema.json"; }
"$bin" verify frame --scene "$src/scenes/spheres.json" --width 32 --height 16 --junit "$work/ok.xml" --json "$work/ok.json" \
  --heatmap "$work/ok.png" > "$work/ok.txt"
xmllint --noout --schema "$src/tests/junit.xsd" "$work/ok.xml"
check_json "$work/ok.json"
grep -q '"passed": true' "$work/ok.json"
grep -q 'failures="0"' "$work/ok.xml"
set +e
"$bin" verify raster --scene "$src/scenes/bunny.json" --width 64 --height 64 --profile-set rasterSetup=reactor \
  --junit "$work/bad.xml" --json "$work/bad.json" --heatmap "$work/bad.png" > "$work/bad.txt"
rc=$?
set -e
[ "$rc" = 1 ] || { echo "a differing suite must exit 1, got $rc"; exit 1; }
xmllint --noout --schema "$src/tests/junit.xsd" "$work/bad.xml"
check_json "$work/bad.json"
grep -q '"passed": false' "$work/bad.json"
grep -q 'first difference at pixel (' "$work/bad.xml"
# --heatmap (item 4): nothing written when nothing differs; a PNG when something does, a panel per differing channel
# (16 of raster's 18 differ under the reactor set-up: coverage and one more stay identical).
[ ! -e "$work/ok.png" ] && grep -q 'heat map: not written (nothing differs)' "$work/ok.txt"
grep -q "heat map: $work/bad.png (16 differing channels)" "$work/bad.txt"
oiiotool --info "$work/bad.png" | grep -q ' 3 channel, uint8 png'
# The identical pixels (the background, 0.12 grey) and the differing ones (not grey) both show: the panels are images.
oiiotool "$work/bad.png" --printstats | grep -q 'Monochrome: No' || { echo "heat map has no colour"; exit 1; }
sed 's/ classname="verify.frame"//' "$work/ok.xml" > "$work/broken.xml"
if xmllint --noout --schema "$src/tests/junit.xsd" "$work/broken.xml" 2>/dev/null; then echo "schema accepted a testcase without classname"; exit 1; fi
echo "verify reports: JUnit and JSON valid, failures reported, heat map written"
