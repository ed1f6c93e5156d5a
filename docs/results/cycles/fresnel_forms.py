#!/usr/bin/python3
"""How much of the red dielectric block's difference (glossy_room, conegraph / Cycles) is the two
BSDFs' forms rather than either tracer: the sun's direct light on the block, per pixel, with glTF's
BSDF (Schlick's F on v.h for the diffuse weight (1 - F) and the GGX lobe, height-correlated Smith)
and with the Cycles set-up of tests/tools/cycles_reference.py (Mix Shader by Schlick on n.v,
Cycles 3.4's separable Smith G1(v) G1(l)), from the scene's own numbers; then the rest of each
render (sky and bounce light) with that term taken away.

    /usr/bin/python3 docs/results/cycles/fresnel_forms.py OURS.exr CYCLES.exr IDS.exr

(the images of glossy_room.gltf: path_trace, Cycles, `cycles_reference.py --ids`). The block's
pixels are found by casting the camera's pixel-centre rays at the box here; the count must equal
the id image's (a check of the camera model). The sun is not shadowed on the block (no object lies
between it and the sun).
"""
import math
import os
import sys

import numpy as np
import OpenImageIO as oiio

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../../tests/tools"))
import make_material_scenes as ms  # noqa: E402

LUM = np.array([0.2126, 0.7152, 0.0722])


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    imgs = [oiio.ImageBuf(p).get_pixels(oiio.FLOAT) for p in sys.argv[1:]]
    h, w = imgs[0].shape[:2]
    eye, target, fov = (np.array(ms.ROOM_CAMERA[0]), np.array(ms.ROOM_CAMERA[1]), ms.ROOM_CAMERA[2])
    f = (target - eye) / np.linalg.norm(target - eye)
    z = -f
    x = np.cross([0.0, 1.0, 0.0], z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    t = math.tan(math.radians(fov) / 2)
    px, py = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    d = ((2 * px / w - 1) * t * w / h)[..., None] * x + ((1 - 2 * py / h) * t)[..., None] * y - z
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    centre, size, yaw = ms.RED_BLOCK
    c, s = math.cos(math.radians(yaw)), math.sin(math.radians(yaw))
    rot = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])  # box space to world (columns)
    half = 0.5 * np.array(size)
    o_b, d_b = (eye - np.array(centre)) @ rot, d @ rot
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (-half - o_b) / d_b, (half - o_b) / d_b
    tmin = np.minimum(t1, t2)
    hit = (tmin.max(-1) < np.maximum(t1, t2).min(-1)) & (np.maximum(t1, t2).min(-1) > 0)
    axis = tmin.argmax(-1)
    n_b = np.zeros_like(d_b)
    iy, ix = np.indices(axis.shape)
    n_b[iy, ix, axis] = -np.sign(d_b[iy, ix, axis])
    n = n_b @ rot.T
    red = 5  # glossy_room's materials: floor, wall, left_wall, gold, chrome, red_dielectric
    idmask = np.rint(imgs[2][:, :, 0]) == red + 1
    print(f"block pixels: ray cast {int(hit.sum())}, id image {int(idmask.sum())}, both {int((hit & idmask).sum())}")
    mask = hit & idmask

    v = -d
    l = -np.array(ms.SUN_DIRECTION) / np.linalg.norm(ms.SUN_DIRECTION)
    rho = np.array(ms.RED_BASE)
    a2 = (ms.RED_ROUGHNESS ** 2) ** 2
    nl = np.clip(n @ l, 0.0, None)
    nv = np.clip((n * v).sum(-1), 1e-6, None)
    hv = v + l
    hv /= np.linalg.norm(hv, axis=-1, keepdims=True)
    nh, vh = (n * hv).sum(-1), (v * hv).sum(-1)
    D = a2 / (np.pi * (nh * nh * (a2 - 1) + 1) ** 2)

    def lam(cos):
        cos = np.maximum(cos, 1e-6)
        return (-1 + np.sqrt(1 + a2 * (1 - cos * cos) / (cos * cos))) / 2

    denom = 4 * nv * np.maximum(nl, 1e-6)
    v_corr = 1 / (1 + lam(nv) + lam(nl)) / denom
    v_sep = 1 / ((1 + lam(nv)) * (1 + lam(nl))) / denom
    f_vh = 0.04 + 0.96 * (1 - np.abs(vh)) ** 5
    f_nv = 0.04 + 0.96 * (1 - nv) ** 5
    E = ms.SUN_INTENSITY
    sun_gltf = E * nl[..., None] * (rho / np.pi * (1 - f_vh)[..., None] + (f_vh * D * v_corr)[..., None])
    sun_cyc = E * nl[..., None] * (rho / np.pi * (1 - f_nv)[..., None] + (f_nv * D * v_sep)[..., None])
    sg, sc = float((sun_gltf @ LUM)[mask].mean()), float((sun_cyc @ LUM)[mask].mean())
    ours, cyc = [float((im[:, :, :3] @ LUM)[mask].mean()) for im in imgs[:2]]
    print(f"sun's direct light, mean luminance: glTF BSDF {sg:.5f}, Cycles set-up {sc:.5f}, ratio {sg / sc:.4f}")
    print(f"renders: ours {ours:.5f}, Cycles {cyc:.5f}, ratio {ours / cyc:.4f}, difference {ours - cyc:.5f} "
          f"(the sun term's {sg - sc:.5f})")
    print(f"renders less their sun term: ours {ours - sg:.5f}, Cycles {cyc - sc:.5f}, ratio {(ours - sg) / (cyc - sc):.4f}")


if __name__ == "__main__":
    main()
