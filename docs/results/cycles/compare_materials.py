#!/usr/bin/python3
"""Mean luminance per material of two renders of one glTF scene (conegraph's path_trace and Cycles),
over the pixels of an object-id image written by `cycles_reference.py --ids` (R = glTF material
index + 1 at the pixel centre, 0 = background):

    /usr/bin/python3 docs/results/cycles/compare_materials.py SCENE.gltf OURS.exr CYCLES.exr IDS.exr [--json OUT]

Prints, for the whole image, the background, every surface together and each material: pixels, mean luminance of each image (Rec. 709
weights on linear RGB) and ours / Cycles. `interior` leaves out the pixels with another id in
their 3x3 neighbourhood (silhouettes, where one pixel-centre ray may land on either object).
Needs numpy and OpenImageIO's Python module (Debian: python3-numpy, python3-openimageio).
"""
import json
import sys

import numpy as np
import OpenImageIO as oiio


def load(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"compare_materials.py: {path}: {buf.geterror()}")
    px = buf.get_pixels(oiio.FLOAT)
    return px[:, :, :3].astype(np.float64)


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def main():
    argv = sys.argv[1:]
    out_json = None
    if "--json" in argv:
        k = argv.index("--json")
        out_json = argv[k + 1]
        del argv[k:k + 2]
    if len(argv) != 4:
        sys.exit(__doc__)
    scene, ours_path, cyc_path, ids_path = argv
    with open(scene) as f:
        names = [m.get("name", f"material{k}") for k, m in enumerate(json.load(f).get("materials", []))]
    ours, cyc, ids_rgb = load(ours_path), load(cyc_path), load(ids_path)
    if ours.shape != cyc.shape or ours.shape != ids_rgb.shape:
        sys.exit("compare_materials.py: the three images differ in size")
    ids = np.rint(ids_rgb[:, :, 0]).astype(np.int64)
    pad = np.pad(ids, 1, mode="edge")
    h, w = ids.shape
    interior = np.ones_like(ids, dtype=bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            interior &= pad[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] == ids
    lo, lc = luminance(ours), luminance(cyc)
    rows = []

    def row(name, mask):
        n = int(mask.sum())
        if n == 0:
            return
        mo, mc = float(lo[mask].mean()), float(lc[mask].mean())
        rows.append({"region": name, "pixels": n, "ours": mo, "cycles": mc,
                     "ratio": mo / mc if mc > 0 else float("nan")})

    row("image", np.ones_like(ids, dtype=bool))
    row("background", ids == 0)
    row("surfaces", ids > 0)
    row("surfaces (interior)", (ids > 0) & interior)
    for k, name in enumerate(names):
        row(name, ids == k + 1)
        row(name + " (interior)", (ids == k + 1) & interior)
    print(f"{'region':34s} {'pixels':>7s} {'ours':>9s} {'cycles':>9s} {'ours/cycles':>11s}")
    for r in rows:
        print(f"{r['region']:34s} {r['pixels']:7d} {r['ours']:9.5f} {r['cycles']:9.5f} {r['ratio']:11.4f}")
    if out_json:
        with open(out_json, "w") as f:
            json.dump({"scene": scene, "ours": ours_path, "cycles": cyc_path, "rows": rows}, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
