#!/usr/bin/env python3
"""Writes the courtyard scene of the Cycles check as glTF 2.0 (no dependencies):

    python3 courtyard.py OUT.gltf [SCALE [ZNEAR]]

A 20 m ground, an 8 m x 8 m courtyard of 3 m walls (one red, an entrance in the front
wall), a block, and one lamp: a 1 m x 1 m panel facing down, 2.6 m up in a corner,
emitting radiance (1, 0.9, 0.7) x 40 (KHR_materials_emissive_strength); a sun of irradiance
1.5 W/m^2 44 degrees above the horizon (KHR_lights_punctual); a camera looking in from
outside. SCALE (default 1) multiplies every length (geometry, camera, clip planes) except
ZNEAR when given: SCALE 100 is a 2 km model seen from 1.9 km, and ZNEAR 0.05 puts the near
plane at 5 cm there. Radiance and irradiance do not depend on SCALE, so every scale must
give the same image.
"""
import base64
import json
import math
import struct
import sys


def box(x0, y0, z0, x1, y1, z1):
    """Six faces, outward normals, counter-clockwise seen from outside."""
    p, n, idx = [], [], []
    faces = [
        ((1, 0, 0), [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)]),
        ((-1, 0, 0), [(x0, y0, z1), (x0, y1, z1), (x0, y1, z0), (x0, y0, z0)]),
        ((0, 1, 0), [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)]),
        ((0, -1, 0), [(x0, y0, z1), (x0, y0, z0), (x1, y0, z0), (x1, y0, z1)]),
        ((0, 0, 1), [(x1, y0, z1), (x1, y1, z1), (x0, y1, z1), (x0, y0, z1)]),
        ((0, 0, -1), [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)]),
    ]
    for normal, quad in faces:
        base = len(p)
        p += quad
        n += [normal] * 4
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return p, n, idx


def quad_down(x0, z0, x1, z1, y):
    """A horizontal quad facing -y."""
    p = [(x0, y, z0), (x1, y, z0), (x1, y, z1), (x0, y, z1)]
    return p, [(0, -1, 0)] * 4, [0, 1, 2, 0, 2, 3]


def quad_up(x0, z0, x1, z1, y):
    p = [(x0, y, z0), (x0, y, z1), (x1, y, z1), (x1, y, z0)]
    return p, [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3]


def look_at_rotation(eye, target):
    """Quaternion (x, y, z, w) turning the camera's -z towards target, +y up."""
    f = [t - e for t, e in zip(target, eye)]
    fl = math.sqrt(sum(c * c for c in f))
    f = [c / fl for c in f]
    up = (0.0, 1.0, 0.0)
    r = (f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0])
    rl = math.sqrt(sum(c * c for c in r))
    r = [c / rl for c in r]
    u = (r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0])
    b = [-c for c in f]  # camera +z
    m = [[r[0], u[0], b[0]], [r[1], u[1], b[1]], [r[2], u[2], b[2]]]  # columns r, u, b
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s]
    if m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        return [0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s]
    if m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        return [(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s]
    s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
    return [(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s]


def main():
    out = sys.argv[1]
    k = float(sys.argv[2]) if len(sys.argv) > 2 else 1.0
    znear = float(sys.argv[3]) if len(sys.argv) > 3 else 0.05 * k
    materials = [
        ("ground", (0.5, 0.5, 0.5), None),
        ("wall", (0.7, 0.7, 0.7), None),
        ("red_wall", (0.6, 0.15, 0.1), None),
        ("block", (0.3, 0.5, 0.7), None),
        ("lamp", (0.0, 0.0, 0.0), ((1.0, 0.9, 0.7), 40.0)),
    ]
    t = 0.3  # wall thickness
    meshes = [
        ("ground", 0, quad_up(-10, -10, 10, 10, 0)),
        ("back_wall", 2, box(-4 - t, 0, -4 - t, 4 + t, 3, -4)),
        ("left_wall", 1, box(-4 - t, 0, -4, -4, 3, 4)),
        ("right_wall", 1, box(4, 0, -4, 4 + t, 3, 4)),
        ("front_wall_a", 1, box(-4 - t, 0, 4, -1, 3, 4 + t)),
        ("front_wall_b", 1, box(1.2, 0, 4, 4 + t, 3, 4 + t)),
        ("block", 3, box(-1.5, 0, -1.8, -0.3, 1.2, -0.6)),
        ("lamp", 4, quad_down(2.8, -3.9, 3.8, -2.9, 2.6)),
    ]
    blob = bytearray()
    accessors, views, gl_meshes, nodes = [], [], [], []

    def add_view(data, target):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(views) - 1

    for name, mat, (pos, nrm, idx) in meshes:
        pos = [tuple(c * k for c in v) for v in pos]
        pv = add_view(b"".join(struct.pack("<3f", *v) for v in pos), 34962)
        lo = [min(v[i] for v in pos) for i in range(3)]
        hi = [max(v[i] for v in pos) for i in range(3)]
        accessors.append({"bufferView": pv, "componentType": 5126, "count": len(pos), "type": "VEC3",
                          "min": lo, "max": hi})
        nv = add_view(b"".join(struct.pack("<3f", *v) for v in nrm), 34962)
        accessors.append({"bufferView": nv, "componentType": 5126, "count": len(nrm), "type": "VEC3"})
        iv = add_view(b"".join(struct.pack("<I", i) for i in idx), 34963)
        accessors.append({"bufferView": iv, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        a = len(accessors) - 3
        gl_meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": a, "NORMAL": a + 1},
                                                        "indices": a + 2, "material": mat}]})
        nodes.append({"name": name, "mesh": len(gl_meshes) - 1})
    gl_materials = []
    for name, colour, emission in materials:
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(colour) + [1.0],
                                                    "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        if emission:
            m["emissiveFactor"] = list(emission[0])
            m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": emission[1]}}
        gl_materials.append(m)
    sun_dir = (0.5, -0.7, -0.5)
    nodes.append({"name": "sun", "rotation": look_at_rotation((0, 0, 0), sun_dir),
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    eye, target = (11.0 * k, 8.0 * k, 13.0 * k), (0.0, 0.6 * k, 0.0)
    nodes.append({"name": "camera", "camera": 0, "translation": list(eye),
                  "rotation": look_at_rotation(eye, target)})
    doc = {
        "asset": {"version": "2.0", "generator": "conegraph docs/results/blender/courtyard.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "sun", "type": "directional", "color": [1.0, 0.95, 0.85], "intensity": 1.5}]}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": gl_meshes,
        "materials": gl_materials,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.75, "znear": znear, "zfar": 60.0 * k}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)


if __name__ == "__main__":
    main()
