#!/usr/bin/env python3
"""The performance model's growth tables (issue 19, docs/RESULTS.md "Growth"): `shadetwin model` on one device as
the image size, the FIS sample count N and the number of shadow maps K grow in x2 steps, predicted against measured
per pass, and the growth from the first step to the last. Prints Markdown tables.

usage: scripts/model_growth.py [--device lavapipe] [--repeat 3] [--bin build/shadetwin] [--scene scenes/bunny.json]
"""
import argparse
import re
import subprocess
import sys

ROW = re.compile(r"^\s+(\S+)\s+predicted\s+([0-9.]+) ms .*?measured\s+([0-9.]+) ms")


def run(args, extra):
    cmd = [args.bin, "model", "--scene", args.scene, "--technique", "fis", "--device", args.device,
           "--repeat", str(args.repeat)] + extra
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"model_growth: {' '.join(cmd)} failed ({out.returncode}):\n{out.stdout}{out.stderr}")
    passes = {}
    for line in out.stdout.splitlines():
        m = ROW.match(line)
        if m:
            passes[m.group(1)] = (float(m.group(2)), float(m.group(3)))
    if "frame" not in passes:
        sys.exit(f"model_growth: no frame line from {' '.join(cmd)}:\n{out.stdout}")
    return passes


def table(title, label, steps, extra_of, passes):
    runs = [run(ARGS, extra_of(s)) for s in steps]
    print(f"| {title} | " + " | ".join(label(s) for s in steps) + " | growth first → last (predicted / measured) |")
    print("| --- " * (len(steps) + 2) + "|")
    for p in passes:
        cells = [f"{r[p][0]:.3g} / {r[p][1]:.3g}" for r in runs]
        gp, gm = runs[-1][p][0] / runs[0][p][0], runs[-1][p][1] / runs[0][p][1]
        print(f"| {p} (ms) | " + " | ".join(cells) + f" | ×{gp:.3g} / ×{gm:.3g} |")
    print()


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--device", default="lavapipe")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--bin", default="build/shadetwin")
    ap.add_argument("--scene", default="scenes/bunny.json")
    ARGS = ap.parse_args()
    table("image (N = 40, K = 16 maps of 1024²)", lambda s: f"{s}²", [32, 64, 128, 256, 512],
          lambda s: ["--width", str(s), "--height", str(s)], ["shade", "visibility-fit", "shadow", "frame"])
    table("samples N (128², K = 16)", str, [10, 20, 40, 80, 160],
          lambda n: ["--width", "128", "--height", "128", "--samples", str(n)], ["shade", "frame"])
    table("shadow maps K (128², N = 40)", str, [4, 8, 16, 32, 64],
          lambda k: ["--width", "128", "--height", "128", "--vis-maps", str(k)], ["shadow", "visibility-fit", "frame"])
