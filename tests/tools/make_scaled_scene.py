#!/usr/bin/env python3
"""A glTF scene S times larger or smaller, lit as conegraph lights a scene without lights, for
comparing renderers at two scales (docs/results/cycles/README.md, "Scale").

    python3 tests/tools/make_scaled_scene.py IN.gltf OUT.gltf S [--lambert]

IN is a .gltf with embedded buffers (`conegraph export` writes one). OUT puts IN's scene under a
root node of scale S (its cameras with it: a camera node's scale changes no image), adds
conegraph's default sun as a KHR_lights_punctual directional light (3 W/m^2, white, travelling
along (-0.287, -0.819, -0.497)), and names each material after its index as well, since
tests/tools/cycles_reference.py needs unique names. --lambert gives every material
KHR_materials_specular's specularFactor 0: glTF's dielectric without its specular layer, a
Lambertian surface in both renderers.
"""
import json
import math
import sys


def main():
    argv = sys.argv[1:]
    lambert = "--lambert" in argv
    argv = [a for a in argv if a != "--lambert"]
    if len(argv) != 3:
        sys.exit(__doc__)
    src, out, s = argv[0], argv[1], float(argv[2])
    with open(src) as f:
        doc = json.load(f)
    scene = doc["scenes"][doc.get("scene", 0)]
    doc["nodes"].append({"name": "scale", "scale": [s, s, s], "children": scene["nodes"]})
    root = len(doc["nodes"]) - 1
    # A directional light shines along its node's -z: the rotation taking -z to d.
    d = [-0.287, -0.819, -0.497]
    n = math.sqrt(sum(x * x for x in d))
    d = [x / n for x in d]
    q = [d[1], -d[0], 0.0, 1.0 - d[2]]   # axis (-z) x d, w = 1 + (-z).d: half the angle
    n = math.sqrt(sum(x * x for x in q))
    q = [x / n for x in q]
    doc.setdefault("extensions", {})["KHR_lights_punctual"] = {
        "lights": [{"type": "directional", "color": [1, 1, 1], "intensity": 3.0}]}
    used = doc.setdefault("extensionsUsed", [])
    used.append("KHR_lights_punctual")
    doc["nodes"].append({"name": "sun", "rotation": q, "extensions": {"KHR_lights_punctual": {"light": 0}}})
    scene["nodes"] = [root, len(doc["nodes"]) - 1]
    for k, m in enumerate(doc.get("materials", [])):
        m["name"] = f"{m.get('name', 'material')}_{k}"
        if lambert:
            m.setdefault("extensions", {})["KHR_materials_specular"] = {"specularFactor": 0.0}
    if lambert and "KHR_materials_specular" not in used:
        used.append("KHR_materials_specular")
    with open(out, "w") as f:
        json.dump(doc, f)


if __name__ == "__main__":
    main()
