#!/usr/bin/env python3
"""Writes a binary glTF (.glb) UV sphere with 2 * rings * sectors triangles (issue 20 item 6's stress mesh: 1000 x 1000
gives 2,000,000), positions and normals float32, indices uint32. Standard library only.

usage: make_stress_mesh.py OUT.glb [--rings R] [--sectors S]"""
import argparse
import array
import json
import math
import struct
import sys


def sphere(rings, sectors):
    pos, nrm = array.array("f"), array.array("f")
    for r in range(rings + 1):
        th = math.pi * r / rings
        st, ct = math.sin(th), math.cos(th)
        for s in range(sectors + 1):
            ph = 2 * math.pi * s / sectors
            x, y, z = st * math.cos(ph), ct, st * math.sin(ph)
            pos.extend((x, y, z))
            nrm.extend((x, y, z))
    idx = array.array("I")
    row = sectors + 1
    for r in range(rings):
        for s in range(sectors):
            a, b = r * row + s, (r + 1) * row + s
            # Counter-clockwise seen from outside (+y up, sectors turning from +x towards +z).
            idx.extend((a, a + 1, b))
            idx.extend((a + 1, b + 1, b))
    return pos, nrm, idx


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--rings", type=int, default=1000)
    ap.add_argument("--sectors", type=int, default=1000)
    a = ap.parse_args()
    pos, nrm, idx = sphere(a.rings, a.sectors)
    if sys.byteorder != "little":
        for arr in (pos, nrm, idx):
            arr.byteswap()
    blobs = [pos.tobytes(), nrm.tobytes(), idx.tobytes()]
    offsets, o = [], 0
    for b in blobs:
        offsets.append(o)
        o += len(b)
    nv = len(pos) // 3
    gltf = {
        "asset": {"version": "2.0", "generator": "shadetwin scripts/make_stress_mesh.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "mode": 4}]}],
        "buffers": [{"byteLength": o}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": offsets[0], "byteLength": len(blobs[0]), "target": 34962},
            {"buffer": 0, "byteOffset": offsets[1], "byteLength": len(blobs[1]), "target": 34962},
            {"buffer": 0, "byteOffset": offsets[2], "byteLength": len(blobs[2]), "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
            {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"},
        ],
    }
    js = json.dumps(gltf, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    bin_ = b"".join(blobs)
    bin_ += b"\0" * (-len(bin_) % 4)
    with open(a.out, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(bin_)))
        f.write(struct.pack("<II", len(js), 0x4E4F534A) + js)
        f.write(struct.pack("<II", len(bin_), 0x004E4942) + bin_)
    print(f"{a.out}: {len(idx) // 3} triangles, {nv} vertices, {12 + 16 + len(js) + len(bin_)} bytes")


if __name__ == "__main__":
    main()
