#!/usr/bin/env python3
"""Writes a synthetic DEM (a 16-bit grey PNG) and a glTF village to stand on it, for the DEM
loader's tests and for the hybrid measurements (docs/hybrid.md, docs/scenes.md).

    make_dem_scene.py OUTDIR [--size N] [--houses K] [--seed S]

OUTDIR/valley.png: N x N samples, 0..65535 (load with scale=0.002: 0 to 131 m), a river valley
between ridged hills; OUTDIR/valley.tif: the same heights in metres as 32-bit float samples (if
oiiotool is on the PATH); OUTDIR/village.gltf: K houses (one mesh each: four walls, a gable
roof, no floor) as instances of three house meshes, each node at y = 0, to be placed with
place=instances. Pure Python (zlib, struct): no numpy.
"""
import argparse
import base64
import json
import math
import os
import random
import shutil
import struct
import subprocess
import zlib


def value_noise(seed):
    rnd = random.Random(seed)
    table = [rnd.random() for _ in range(256 * 256)]

    def lattice(i, j):
        return table[(i & 255) * 256 + (j & 255)]

    def noise(x, y):
        i, j = math.floor(x), math.floor(y)
        fx, fy = x - i, y - j
        sx, sy = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy)
        a = lattice(i, j) + sx * (lattice(i + 1, j) - lattice(i, j))
        b = lattice(i, j + 1) + sx * (lattice(i + 1, j + 1) - lattice(i, j + 1))
        return a + sy * (b - a)

    return noise


def heights(n, seed):
    """Metres, n x n over a 1 km square: ridged fbm hills, a river valley along a sine."""
    noise = value_noise(seed)
    out = []
    for j in range(n):
        row = []
        for i in range(n):
            x, z = i / (n - 1), j / (n - 1)
            h, amp, freq = 0.0, 1.0, 4.0
            for octave in range(5):
                r = 1.0 - abs(2.0 * noise(x * freq + 17.3 * octave, z * freq) - 1.0)
                h += amp * r * r
                amp *= 0.5
                freq *= 2.03
            h = 70.0 * h
            river = 0.5 + 0.12 * math.sin(x * 7.0)
            dv = (z - river) / 0.08
            h = h * (1.0 - 0.85 * math.exp(-dv * dv)) + 8.0
            row.append(h)
        out.append(row)
    return out


def write_png16(path, rows):
    raw = b"".join(b"\x00" + struct.pack(">%dH" % len(r), *r) for r in rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    ihdr = struct.pack(">IIBBBBB", len(rows[0]), len(rows), 16, 0, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def house_mesh(hx, hz, height, pitch):
    """Walls (no floor) and a gable roof; vertices per face, outward normals."""
    pos, nrm, idx = [], [], []

    def quad(a, b, c, d):
        e1 = [b[k] - a[k] for k in range(3)]
        e2 = [c[k] - a[k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        l = math.sqrt(sum(v * v for v in n))
        n = [v / l for v in n]
        base = len(pos) // 3
        for p in (a, b, c, d):
            pos.extend(p)
            nrm.extend(n)
        idx.extend([base, base + 1, base + 2, base, base + 2, base + 3])

    def tri(a, b, c):
        e1 = [b[k] - a[k] for k in range(3)]
        e2 = [c[k] - a[k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        l = math.sqrt(sum(v * v for v in n))
        base = len(pos) // 3
        for p in (a, b, c):
            pos.extend(p)
            nrm.extend([v / l for v in n])
        idx.extend([base, base + 1, base + 2])

    b = -3.0  # walls reach 3 m below the node: buried where the ground slopes
    v = [[sx * hx, y, sz * hz] for y in (b, height) for sz in (-1, 1) for sx in (-1, 1)]
    # v: 0 (-,b,-) 1 (+,b,-) 2 (-,b,+) 3 (+,b,+) 4..7 the same at the eaves
    quad(v[2], v[3], v[7], v[6])  # +z
    quad(v[1], v[0], v[4], v[5])  # -z
    quad(v[3], v[1], v[5], v[7])  # +x
    quad(v[0], v[2], v[6], v[4])  # -x
    rise = hz * math.tan(math.radians(pitch))
    r0, r1 = [-hx, height + rise, 0.0], [hx, height + rise, 0.0]
    quad(v[6], v[7], r1, r0)  # slope facing +z
    quad(v[5], v[4], r0, r1)  # slope facing -z
    tri(v[7], v[5], r1)       # gable +x
    tri(v[4], v[6], r0)       # gable -x
    return pos, nrm, idx


def write_village(path, houses, seed):
    rnd = random.Random(seed)
    shapes = [(5, 4, 6, 35), (8, 5, 9, 30), (4, 4, 12, 40)]
    colours = [[0.75, 0.12, 0.08, 1], [0.80, 0.80, 0.78, 1], [0.85, 0.70, 0.15, 1]]
    buf = bytearray()
    views, accessors, meshes = [], [], []
    for k, (hx, hz, h, pitch) in enumerate(shapes):
        pos, nrm, idx = house_mesh(hx, hz, h, pitch)
        for data, fmt, kind, target in ((pos, "f", "VEC3", 34962), (nrm, "f", "VEC3", 34962), (idx, "I", "SCALAR", 34963)):
            while len(buf) % 4:
                buf.append(0)
            offset = len(buf)
            buf += struct.pack("<%d%s" % (len(data), fmt), *data)
            views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(buf) - offset, "target": target})
            acc = {"bufferView": len(views) - 1, "componentType": 5126 if fmt == "f" else 5125,
                   "count": len(data) // (3 if kind == "VEC3" else 1), "type": kind}
            if data is pos:
                acc["min"] = [min(pos[c::3]) for c in range(3)]
                acc["max"] = [max(pos[c::3]) for c in range(3)]
            accessors.append(acc)
        a = 3 * k
        meshes.append({"name": "house%d" % k, "primitives": [{"attributes": {"POSITION": a, "NORMAL": a + 1},
                                                              "indices": a + 2, "material": k}]})
    nodes, placed = [], []
    tries = 0
    while len(nodes) < houses and tries < houses * 100:
        tries += 1
        x, z = rnd.uniform(-380, 380), rnd.uniform(-380, 380)
        # On the hills' side of the river (z below it), clear of each other.
        if z > 0.5 * 1000 - 500 + 120 * math.sin((x + 500) / 1000 * 7.0) - 90:
            continue
        if any((x - px) ** 2 + (z - pz) ** 2 < 22 ** 2 for px, pz in placed):
            continue
        yaw = rnd.uniform(-math.pi, math.pi)
        placed.append((x, z))
        nodes.append({"mesh": rnd.randrange(3), "translation": [x, 0, z],
                      "rotation": [0, math.sin(yaw / 2), 0, math.cos(yaw / 2)]})
    gltf = {
        "asset": {"version": "2.0", "generator": "conegraph tests/tools/make_dem_scene.py"},
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": c, "metallicFactor": 0}} for c in colours],
        "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}],
    }
    with open(path, "w") as f:
        json.dump(gltf, f, indent=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("--size", type=int, default=513)
    ap.add_argument("--houses", type=int, default=60)
    ap.add_argument("--seed", type=int, default=3)
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    h = heights(a.size, a.seed)
    write_png16(os.path.join(a.outdir, "valley.png"), [[max(0, min(65535, round(v / 0.002))) for v in r] for r in h])
    if shutil.which("oiiotool"):
        # The same heights as float metres: PNG -> float TIFF through OIIO, x 0.002 (exact).
        subprocess.run(["oiiotool", os.path.join(a.outdir, "valley.png"), "--ch", "0", "-d", "float",
                        "--mulc", str(65535 * 0.002), "-o", os.path.join(a.outdir, "valley.tif")], check=True)
    write_village(os.path.join(a.outdir, "village.gltf"), a.houses, a.seed)


if __name__ == "__main__":
    main()
