#!/usr/bin/env python3
"""The validation table of docs/RESULTS.md from `shadetwin model --validate --csv FILE`: per pass and device the
number of runs, the mean absolute error and the range of signed errors, then per device and overall, and the whole
frames (each scene x technique x device's passes summed). Prints Markdown.

usage: scripts/model_table.py docs/model_validate.csv
"""
import collections
import csv
import sys


def main(path):
    rows = [r for r in csv.DictReader(open(path)) if float(r["measured_ms"]) > 0]
    if not rows:
        sys.exit(f"model_table: {path}: no measured rows")
    devices = sorted({r["device"] for r in rows})
    order = []
    for r in rows:
        if r["pass"] not in order:
            order.append(r["pass"])
    err = collections.defaultdict(list)
    frames = collections.defaultdict(lambda: [0.0, 0.0])
    for r in rows:
        e = 100.0 * (float(r["predicted_ms"]) - float(r["measured_ms"])) / float(r["measured_ms"])
        err[(r["pass"], r["device"])].append(e)
        f = frames[(r["scene"], r["technique"], r["device"])]
        f[0] += float(r["predicted_ms"])
        f[1] += float(r["measured_ms"])
    print("| pass | " + " | ".join(f"{d}: n, mean abs error, range" for d in devices) + " |")
    print("| --- " * (len(devices) + 1) + "|")
    for p in order:
        cells = []
        for d in devices:
            v = err.get((p, d), [])
            cells.append(f"{len(v)}, {sum(map(abs, v)) / len(v):.0f}%, {min(v):+.0f}..{max(v):+.0f}%" if v else "–")
        print(f"| {p} | " + " | ".join(cells) + " |")
    print()
    every = [e for v in err.values() for e in v]
    for d in devices:
        v = [e for (p, dd), vs in err.items() if dd == d for e in vs]
        within = sum(abs(e) <= 35.0 for e in v)
        print(f"- {d}: mean abs error {sum(map(abs, v)) / len(v):.1f}% over {len(v)} passes, {within} within 35%")
    fe = [100.0 * (p - m) / m for p, m in frames.values()]
    print(f"- all: mean abs error {sum(map(abs, every)) / len(every):.1f}% over {len(every)} passes (worst "
          f"{max(map(abs, every)):.1f}%), {sum(abs(e) <= 35.0 for e in every)} within 35%")
    print(f"- frames: mean abs error {sum(map(abs, fe)) / len(fe):.1f}% over {len(fe)} (worst {max(map(abs, fe)):.1f}%)")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
