#!/usr/bin/env python3
"""Writes the glossy and glass test scenes of the Cycles check (docs/results/cycles/README.md)
as small glTF 2.0 files (.gltf, buffers embedded as base64), in pure Python:

    python3 tests/tools/make_material_scenes.py OUTDIR

writes OUTDIR/glossy_room.gltf, OUTDIR/glass.gltf, OUTDIR/spheres.gltf and OUTDIR/spheres_sun.gltf:

- glossy_room: a Lambertian floor, back wall and left wall (KHR_materials_specular
  specularFactor 0: glTF's dielectric otherwise has a specular lobe), a gold metal block
  (metallic 1, roughness 0.3, base (1.0, 0.78, 0.34)), a chrome block (metallic 1, roughness
  0.05, base 0.95) and a polished red dielectric block (metallic 0, roughness 0.1, ior 1.5),
  under a sun (KHR_lights_punctual directional, intensity 5: irradiance 5 W/m^2). The sky is
  not in the file (glTF has none): render with a uniform sky of SKY below.
- glass: a checkered Lambertian floor and a back wall, a solid glass block
  (KHR_materials_transmission 1, KHR_materials_ior 1.5, KHR_materials_volume thickness 0.9 m,
  roughness 0) and a thin glass pane (transmission 1, no volume: thin-walled), same sun.
- spheres: spheres alone under the uniform sky (a furnace: no light, no floor): a white
  Lambertian one (the control: radiance = sky), white metals of roughness 1 and 0.3 (F0 = 1:
  Schlick's F is 1 whatever its angle, so only the GGX lobe is compared), gold 0.3, chrome
  0.05, the red dielectric 0.1 and solid glass: the Fresnel forms' difference alone.
- spheres_sun: the same spheres under glossy_room's sun and sky: metals that reflect each other's
  sunlit sides (what a metal's voxel returns of a punctual light).

Every scene has one camera (the first, which conegraph uses), 16:9. Metres, Y up.
The numbers below are read by tests/tools/cycles_reference.py too (it imports this file).
"""
import base64
import json
import math
import os
import struct
import sys

SKY = (0.15, 0.18, 0.25)      # uniform sky radiance for glossy_room and glass, W/(m^2 sr)
FURNACE_SKY = (1.0, 1.0, 1.0)  # for spheres
SUN_INTENSITY = 5.0            # W/m^2 (KHR_lights_punctual directional: intensity x color = E)
SUN_DIRECTION = (-0.45, -0.75, -0.48)  # the direction the light travels
ROOM_CAMERA = ((0.0, 1.4, 3.0), (0.0, 0.45, -0.8), 42.0)  # eye, target, vertical fov (degrees)
RED_BLOCK = ((1.35, 0.35, -0.5), (0.7, 0.7, 0.7), 40.0)   # centre, size, yaw (degrees)
RED_BASE, RED_ROUGHNESS = (0.8, 0.08, 0.06), 0.1


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def quat_from_basis(x, y, z):
    """Unit quaternion (x, y, z, w) of the rotation whose matrix has columns x, y, z."""
    m00, m10, m20 = x
    m01, m11, m21 = y
    m02, m12, m22 = z
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        q = (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        q = ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2
        q = ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q)


def look_rotation(forward, up_hint=(0.0, 1.0, 0.0)):
    """Rotation taking local -Z to `forward` (glTF cameras and lights look down -Z)."""
    f = normalize(forward)
    z = tuple(-c for c in f)
    x = normalize(cross(up_hint, z))
    y = cross(z, x)
    return quat_from_basis(x, y, z)


def lambert(name, rgb):
    return {"name": name,
            "pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1.0], "metallicFactor": 0.0,
                                     "roughnessFactor": 1.0},
            "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}


def metal(name, rgb, roughness):
    return {"name": name,
            "pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1.0], "metallicFactor": 1.0,
                                     "roughnessFactor": roughness}}


def dielectric(name, rgb, roughness, ior=1.5):
    return {"name": name,
            "pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1.0], "metallicFactor": 0.0,
                                     "roughnessFactor": roughness},
            "extensions": {"KHR_materials_ior": {"ior": ior}}}


def glass(name, thickness, roughness=0.0, ior=1.5):
    ext = {"KHR_materials_transmission": {"transmissionFactor": 1.0},
           "KHR_materials_ior": {"ior": ior}}
    if thickness > 0:
        ext["KHR_materials_volume"] = {"thicknessFactor": thickness}
    m = {"name": name,
         "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0,
                                  "roughnessFactor": roughness},
         "extensions": ext}
    if thickness == 0:
        m["doubleSided"] = True
    return m


# Geometry: (positions, normals, indices) in world space (nodes carry no transform, so the
# Blender import and conegraph see the same numbers).

def quad(corner, edge_u, edge_v):
    """A parallelogram corner, corner + u, corner + u + v, corner + v; normal u x v."""
    n = normalize(cross(edge_u, edge_v))
    p = [corner, tuple(a + b for a, b in zip(corner, edge_u)),
         tuple(a + b + c for a, b, c in zip(corner, edge_u, edge_v)),
         tuple(a + b for a, b in zip(corner, edge_v))]
    return p, [n] * 4, [0, 1, 2, 0, 2, 3]


def merge(parts):
    pos, nor, idx = [], [], []
    for p, n, i in parts:
        base = len(pos)
        pos += p
        nor += n
        idx += [base + k for k in i]
    return pos, nor, idx


def box(center, size, yaw_deg):
    """An axis-aligned box of `size` turned by yaw about +Y, its faces outwards."""
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))

    def rot(v):
        return (c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2])

    hx, hy, hz = (0.5 * a for a in size)
    faces = []
    # each face: corner, u, v (u x v points outwards), in box space
    for corner, u, v in [((hx, -hy, hz), (0, 0, -2 * hz), (0, 2 * hy, 0)),     # +x
                         ((-hx, -hy, -hz), (0, 0, 2 * hz), (0, 2 * hy, 0)),    # -x
                         ((-hx, hy, hz), (2 * hx, 0, 0), (0, 0, -2 * hz)),     # +y
                         ((-hx, -hy, -hz), (2 * hx, 0, 0), (0, 0, 2 * hz)),    # -y
                         ((-hx, -hy, hz), (2 * hx, 0, 0), (0, 2 * hy, 0)),     # +z
                         ((hx, -hy, -hz), (-2 * hx, 0, 0), (0, 2 * hy, 0))]:   # -z
        p, n, i = quad(rot(corner), rot(u), rot(v))
        faces.append(([tuple(a + b for a, b in zip(q, center)) for q in p], n, i))
    return merge(faces)


def sphere(center, radius, rings=32, segments=64):
    pos, nor, idx = [], [], []
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s in range(segments + 1):
            ph = 2 * math.pi * s / segments
            n = (math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph))
            nor.append(n)
            pos.append(tuple(c + radius * a for c, a in zip(center, n)))
    w = segments + 1
    for r in range(rings):
        for s in range(segments):
            a, b = r * w + s, (r + 1) * w + s
            if r > 0:
                idx += [a, b, a + 1]
            if r < rings - 1:
                idx += [a + 1, b, b + 1]
    return pos, nor, idx


class Writer:
    def __init__(self):
        self.blob = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "conegraph make_material_scenes.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                    "materials": [], "accessors": [], "bufferViews": [], "buffers": [],
                    "cameras": []}
        self.material_index = {}

    def material(self, m):
        if m["name"] not in self.material_index:
            self.material_index[m["name"]] = len(self.doc["materials"])
            self.doc["materials"].append(m)
        return self.material_index[m["name"]]

    def _view(self, data, target):
        while len(self.blob) % 4:
            self.blob.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.blob),
                                        "byteLength": len(data), "target": target})
        self.blob += data
        return len(self.doc["bufferViews"]) - 1

    def _vec3(self, values):
        data = b"".join(struct.pack("<3f", *v) for v in values)
        acc = {"bufferView": self._view(data, 34962), "componentType": 5126,
               "count": len(values), "type": "VEC3"}
        acc["min"] = [min(v[k] for v in values) for k in range(3)]
        acc["max"] = [max(v[k] for v in values) for k in range(3)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def mesh(self, name, geometry, material):
        pos, nor, idx = geometry
        ia = len(self.doc["accessors"])
        self.doc["accessors"].append({"bufferView": self._view(struct.pack(f"<{len(idx)}I", *idx), 34963),
                                      "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        prim = {"attributes": {"POSITION": self._vec3(pos), "NORMAL": self._vec3(nor)},
                "indices": ia, "material": self.material(material)}
        self.doc["meshes"].append({"name": name, "primitives": [prim]})
        self._node({"name": name, "mesh": len(self.doc["meshes"]) - 1})

    def _node(self, node):
        self.doc["nodes"].append(node)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def camera(self, eye, target, yfov_deg, aspect=16 / 9):
        self.doc["cameras"].append({"type": "perspective", "perspective": {
            "yfov": math.radians(yfov_deg), "aspectRatio": aspect, "znear": 0.05, "zfar": 100.0}})
        self._node({"name": "camera", "camera": len(self.doc["cameras"]) - 1,
                    "translation": list(eye), "rotation": list(look_rotation(sub(target, eye)))})

    def sun(self, direction, intensity, color=(1.0, 1.0, 1.0)):
        ext = self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})
        ext["lights"].append({"name": "sun", "type": "directional", "color": list(color),
                              "intensity": intensity})
        self._node({"name": "sun", "rotation": list(look_rotation(direction, (0.0, 0.0, 1.0))),
                    "extensions": {"KHR_lights_punctual": {"light": len(ext["lights"]) - 1}}})

    def write(self, path):
        used = set()
        for m in self.doc["materials"]:
            used |= set(m.get("extensions", {}))
        if "extensions" in self.doc:
            used.add("KHR_lights_punctual")
        if used:
            self.doc["extensionsUsed"] = sorted(used)
        self.doc["buffers"] = [{"byteLength": len(self.blob), "uri": "data:application/octet-stream;base64,"
                                + base64.b64encode(bytes(self.blob)).decode("ascii")}]
        with open(path, "w") as f:
            json.dump(self.doc, f, indent=1)
            f.write("\n")


def room(w, wall_rgb=(0.8, 0.8, 0.8), left_rgb=(0.35, 0.55, 0.35), floor_rgb=(0.5, 0.5, 0.5)):
    w.mesh("floor", quad((-4.0, 0.0, 3.0), (8.0, 0.0, 0.0), (0.0, 0.0, -7.0)), lambert("floor", floor_rgb))
    w.mesh("back_wall", quad((-4.0, 0.0, -2.0), (8.0, 0.0, 0.0), (0.0, 3.0, 0.0)), lambert("wall", wall_rgb))
    w.mesh("left_wall", quad((-3.2, 0.0, 3.0), (0.0, 0.0, -5.0), (0.0, 3.0, 0.0)),
           lambert("left_wall", left_rgb))


def glossy_room(path):
    w = Writer()
    room(w)
    w.mesh("gold_block", box((-1.35, 0.4, -0.6), (0.7, 0.8, 0.7), 30.0),
           metal("gold", (1.0, 0.78, 0.34), 0.3))
    w.mesh("chrome_block", box((0.0, 0.5, -1.0), (0.7, 1.0, 0.7), -25.0),
           metal("chrome", (0.95, 0.95, 0.95), 0.05))
    w.mesh("red_block", box(*RED_BLOCK), dielectric("red_dielectric", RED_BASE, RED_ROUGHNESS))
    w.camera(*ROOM_CAMERA)
    w.sun(SUN_DIRECTION, SUN_INTENSITY)
    w.write(path)


def glass_scene(path):
    w = Writer()
    light, dark = lambert("floor_light", (0.7, 0.7, 0.7)), lambert("floor_dark", (0.15, 0.15, 0.2))
    n, size = 8, 1.0
    tiles = {0: [], 1: []}
    for i in range(n):
        for j in range(7):
            x0, z0 = -4.0 + i * size, 3.0 - j * size
            tiles[(i + j) % 2].append(quad((x0, 0.0, z0), (size, 0.0, 0.0), (0.0, 0.0, -size)))
    w.mesh("floor_light", merge(tiles[0]), light)
    w.mesh("floor_dark", merge(tiles[1]), dark)
    w.mesh("back_wall", quad((-4.0, 0.0, -3.5), (8.0, 0.0, 0.0), (0.0, 3.0, 0.0)), lambert("wall", (0.8, 0.8, 0.8)))
    # 2 mm above the floor: a bottom face on the floor's plane leaves which of the two a ray
    # leaving the glass downwards meets to rounding (speckles where the floor shows through)
    w.mesh("glass_block", box((-0.9, 0.452, -0.4), (0.9, 0.9, 0.9), 20.0), glass("glass_solid", 0.9))
    # the pane: 1.3 m x 1.1 m, standing on the floor, turned 30 degrees about +Y
    c, s = math.cos(math.radians(-30.0)), math.sin(math.radians(-30.0))
    u = (1.3 * c, 0.0, -1.3 * s)
    corner = (0.45, 0.02, -0.1)
    w.mesh("glass_pane", quad(corner, u, (0.0, 1.1, 0.0)), glass("glass_thin", 0.0))
    w.camera((0.0, 1.4, 3.0), (0.0, 0.45, -0.5), 42.0)
    w.sun(SUN_DIRECTION, SUN_INTENSITY)
    w.write(path)


def spheres_scene(path, sun=False):
    w = Writer()
    spheres = [(lambert("white_lambert", (1.0, 1.0, 1.0)), (-2.4, 0.55)),
               (metal("white_metal_r1", (1.0, 1.0, 1.0), 1.0), (-1.2, 0.55)),
               (metal("white_metal_r03", (1.0, 1.0, 1.0), 0.3), (0.0, 0.55)),
               (metal("gold_r03", (1.0, 0.78, 0.34), 0.3), (1.2, 0.55)),
               (metal("chrome_r005", (0.95, 0.95, 0.95), 0.05), (2.4, 0.55)),
               (dielectric("red_dielectric_r01", RED_BASE, RED_ROUGHNESS), (-1.2, -0.65)),
               (dielectric("white_dielectric_r05", (1.0, 1.0, 1.0), 0.5), (0.0, -0.65)),
               (glass("glass_solid", 1.0), (1.2, -0.65))]
    for m, (x, y) in spheres:
        w.mesh(m["name"], sphere((x, y, 0.0), 0.5), m)
    w.camera((0.0, 0.0, 6.0), (0.0, 0.0, 0.0), 32.0)
    if sun:
        w.sun(SUN_DIRECTION, SUN_INTENSITY)
    w.write(path)


SCENES = {"glossy_room": (glossy_room, SKY), "glass": (glass_scene, SKY),
          "spheres": (spheres_scene, FURNACE_SKY),
          "spheres_sun": (lambda path: spheres_scene(path, sun=True), SKY)}


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_material_scenes.py OUTDIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, (make, sky) in SCENES.items():
        path = os.path.join(out, name + ".gltf")
        make(path)
        print(f"{path}  (sky {','.join(str(c) for c in sky)})")


if __name__ == "__main__":
    main()
