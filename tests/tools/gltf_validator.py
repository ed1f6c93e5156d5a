#!/usr/bin/env python3
"""Test gltf_validator (TAP): conegraph against the Khronos glTF-Validator.

Over the malformed corpus (tests/data/gltf/malformed), the fuzz seeds (tests/fuzz/corpus/gltf),
Debian's assimp glTF test models when installed (package assimp-testmodels; not needed), and
every file `conegraph export` writes here:

  - every exported file must validate with 0 errors;
  - wherever the validator reports an error, `conegraph export FILE OUT` must exit 2 with a
    message naming the file, and write nothing (no OUT, no temporary file beside it);
  - where conegraph accepts a file the validator rejects, every error the validator reports
    must be one that ACCEPTED below explains (each reason is documented in docs/gltf.md,
    "What the glTF checks leave out"); any other is a failure.

The validator (npm package gltf-validator, pinned) is installed once under the build
directory. Only when npm cannot install it (no npm, no registry) is the test skipped, with
the reason. usage: gltf_validator.py CONEGRAPH SOURCE_ROOT CACHE_DIR
"""
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

VALIDATOR = "gltf-validator@2.0.0-dev.3.10"

# Validator errors on parts conegraph does not read: (code, JSON-pointer prefix or None, reason).
# A pointer prefix None matches anywhere. Keep in step with docs/gltf.md.
NOT_READ = "not read by conegraph (docs/gltf.md, 'What the glTF checks leave out')"
ACCEPTED = [
    ("MESH_PRIMITIVE_NO_TANGENT_SPACE", None,
     "a normal-mapped primitive without normals: conegraph generates normals, then tangents (docs/gltf.md)"),
    ("MESH_PRIMITIVE_GENERATED_TANGENT_SPACE", None,
     "tangents generated where a file has none (docs/gltf.md, Materials: Lengyel's method, not MikkTSpace)"),
    (None, "/skins", "skins are " + NOT_READ),
    ("NODE_SKIN_WITH_NON_SKINNED_MESH", None, "skins are " + NOT_READ),
    ("NODE_SKIN_NO_SCENE", None, "skins are " + NOT_READ),
    ("MESH_PRIMITIVE_JOINTS_WEIGHTS_MISMATCH", None, "skins are " + NOT_READ),
    ("MESH_PRIMITIVE_MORPH_TARGET_INVALID_ATTRIBUTE_COUNT", None, "morph targets are " + NOT_READ),
    ("MESH_PRIMITIVE_MORPH_TARGET_NO_BASE_ACCESSOR", None, "morph targets are " + NOT_READ),
    ("MESH_INVALID_WEIGHTS_COUNT", None, "morph targets are " + NOT_READ),
    ("MESH_PRIMITIVES_UNEQUAL_TARGETS_COUNT", None, "morph targets are " + NOT_READ),
    ("NODE_WEIGHTS_INVALID", None, "morph targets are " + NOT_READ),
]
# Data errors on an accessor conegraph never reads (one that is not the POSITION, NORMAL,
# TEXCOORD_0 or indices of a primitive, nor the input or output of a sampler that a channel on
# a node's translation, rotation or scale uses): its data is not checked.
UNREAD_ACCESSOR = "the data of accessors conegraph does not read (TANGENT, COLOR_n, JOINTS_n, " \
                  "WEIGHTS_n, TEXCOORD_1+, morph targets, samplers of morph target weights only, skins) is not checked"
# Errors on an animation channel that animates morph target weights (ignored, with a warning).
WEIGHTS_CHANNEL = "channels on morph target weights are " + NOT_READ
# Data errors on an image no texture uses.
UNUSED_IMAGE = "images no texture uses are " + NOT_READ


def gltf_json(path):
    """The JSON of a .gltf or .glb, or None when it cannot be read."""
    try:
        data = open(path, "rb").read()
        if data[:4] == b"glTF" and len(data) >= 20:
            length = struct.unpack_from("<I", data, 12)[0]
            data = data[20:20 + length]
        return json.loads(data.decode("utf-8"))
    except (OSError, ValueError, UnicodeDecodeError, struct.error):
        return None


def channel_path(doc, animation, channel):
    """The target path of animations[animation].channels[channel], or None."""
    try:
        return doc["animations"][animation]["channels"][channel]["target"]["path"]
    except (KeyError, IndexError, TypeError):
        return None


def read_accessors(doc):
    read = set()
    for anim in doc.get("animations", []) if isinstance(doc, dict) else []:
        samplers = anim.get("samplers", []) if isinstance(anim, dict) else []
        for ch in anim.get("channels", []) if isinstance(anim, dict) else []:
            target = ch.get("target", {}) if isinstance(ch, dict) else {}
            if not isinstance(target, dict) or target.get("node") is None or target.get("path") == "weights":
                continue
            s = ch.get("sampler")
            if isinstance(s, int) and 0 <= s < len(samplers) and isinstance(samplers[s], dict):
                for key in ("input", "output"):
                    if isinstance(samplers[s].get(key), int):
                        read.add(samplers[s][key])
    for mesh in doc.get("meshes", []) if isinstance(doc, dict) else []:
        for prim in mesh.get("primitives", []) if isinstance(mesh, dict) else []:
            if not isinstance(prim, dict):
                continue
            attrs = prim.get("attributes", {})
            for name in ("POSITION", "NORMAL", "TEXCOORD_0"):
                if isinstance(attrs, dict) and isinstance(attrs.get(name), int):
                    read.add(attrs[name])
            if isinstance(prim.get("indices"), int):
                read.add(prim["indices"])
    return read


def used_images(doc):
    used = set()
    for tex in doc.get("textures", []) if isinstance(doc, dict) else []:
        if isinstance(tex, dict) and isinstance(tex.get("source"), int):
            used.add(tex["source"])
    return used


def explain(issue, doc):
    """The documented reason conegraph may accept a file with this validator error, or None."""
    code, pointer = issue["code"], issue["pointer"]
    for c, prefix, reason in ACCEPTED:
        if (c is None or c == code) and (prefix is None or pointer.startswith(prefix)):
            return reason
    parts = pointer.split("/")
    if len(parts) > 4 and parts[1] == "animations" and parts[3] == "channels" and parts[2].isdigit() \
            and parts[4].isdigit() and channel_path(doc, int(parts[2]), int(parts[4])) == "weights":
        return WEIGHTS_CHANNEL
    if code.startswith("ACCESSOR_") and len(parts) > 2 and parts[1] == "accessors" and parts[2].isdigit():
        if doc is not None and int(parts[2]) not in read_accessors(doc):
            return UNREAD_ACCESSOR
    if code.startswith("IMAGE_") and len(parts) > 2 and parts[1] == "images" and parts[2].isdigit():
        if doc is not None and int(parts[2]) not in used_images(doc):
            return UNUSED_IMAGE
    return None


def skip(reason):
    print(f"1..0 # SKIP {reason}")
    sys.exit(0)


def install_validator(cache):
    marker = os.path.join(cache, "node_modules", "gltf-validator", "package.json")
    if os.path.exists(marker) and VALIDATOR.split("@")[1] in open(marker).read():
        return
    if not shutil.which("npm") or not shutil.which("node"):
        skip("npm and node are needed to install the Khronos glTF-Validator (npm package gltf-validator)")
    os.makedirs(cache, exist_ok=True)
    r = subprocess.run(["npm", "install", "--prefix", cache, "--no-audit", "--no-fund", "--loglevel=error", VALIDATOR],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0 or not os.path.exists(marker):
        last = (r.stdout.strip().splitlines() or ["no output"])[-1]
        skip(f"npm could not install {VALIDATOR}: {last}")


def main():
    conegraph, source, cache = sys.argv[1:4]
    install_validator(cache)
    work = tempfile.mkdtemp(prefix="conegraph-gltf-validator-")
    try:
        run(conegraph, source, cache, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def run(conegraph, source, cache, work):
    tests = []  # (ok, description, diagnostics)

    # Every file conegraph export writes here: the built-in scenes (and the animated variants)
    # and loaded glTF files with textures, emissive strength, lights of every type, both camera
    # types (one with zfar left out, that is infinite), a height field, and animations (LINEAR,
    # STEP, CUBICSPLINE; a light and a camera on animated nodes).
    exports = []
    sources = ["builtin:cornell", "builtin:furnace", "builtin:openworld?triangles=5000",
               "builtin:openworld?triangles=5000&motion=sun", "builtin:openworld?triangles=5000&motion=one",
               "builtin:openworld?triangles=5000&motion=all",
               os.path.join(source, "tests", "fuzz", "corpus", "gltf", "animated.gltf"),
               os.path.join(source, "tests", "fuzz", "corpus", "gltf", "datauri.gltf"),
               os.path.join(source, "tests", "fuzz", "corpus", "gltf", "binary.glb"),
               os.path.join(source, "tests", "fuzz", "corpus", "gltf", "external_bin.gltf")]
    os.makedirs(os.path.join(work, "export"))
    for i, scene in enumerate(sources):
        for ext in ("gltf", "glb"):
            out = os.path.join(work, "export", f"export{i}.{ext}")
            r = subprocess.run([conegraph, "export", scene, out], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
            if r.returncode != 0:
                tests.append((False, f"conegraph export {scene} {os.path.basename(out)}", r.stderr.strip()))
            else:
                exports.append((scene, out))

    corpus = []
    for d in [os.path.join(source, "tests", "data", "gltf", "malformed"),
              os.path.join(source, "tests", "fuzz", "corpus", "gltf"),
              "/usr/share/assimp/models/glTF2", "/usr/share/assimp/models/glTF"]:
        for root, _, files in os.walk(d):
            corpus += [os.path.join(root, f) for f in sorted(files) if f.endswith((".gltf", ".glb"))]
    corpus.sort()

    files = [out for _, out in exports] + corpus
    r = subprocess.run(["node", os.path.join(source, "tests", "tools", "gltf_validate.js"), cache] + files,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    reports = {}
    for line in r.stdout.splitlines():
        rep = json.loads(line)
        reports[rep["file"]] = rep
    if len(reports) != len(files):
        print("1..1")
        print(f"not ok 1 - the validator reported on {len(reports)} of {len(files)} files")
        print("# " + r.stderr.strip().replace("\n", "\n# "))
        return

    for scene, out in exports:
        rep = reports[out]
        codes = ", ".join(f"{i['code']} at {i['pointer']}" for i in rep["issues"])
        tests.append((rep["errors"] == 0, f"export of {scene} as .{out.rsplit('.', 1)[1]} validates with 0 errors",
                      codes))

    accepted_with_reason = stricter = 0
    for path in corpus:
        rep = reports[path]
        name = os.path.relpath(path, source) if path.startswith(source) else path
        outdir = os.path.join(work, "out")
        os.makedirs(outdir, exist_ok=True)
        out = os.path.join(outdir, "out.glb")
        r = subprocess.run([conegraph, "export", path, out], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        left = os.listdir(outdir)
        for f in left:
            os.remove(os.path.join(outdir, f))
        lines = r.stderr.strip().splitlines()
        errors = [l for l in lines if l.startswith("conegraph export:")]
        message = errors[-1] if errors else (lines[-1] if lines else "")
        if rep["errors"] > 0:
            if r.returncode == 2:
                ok = os.path.basename(path) in message and not left
                tests.append((ok, f"{name}: refused, as the validator's {rep['errors']} error(s) ask",
                              f"{message}" + (f"; left behind: {left}" if left else "")))
                continue
            if r.returncode != 0:
                tests.append((False, f"{name}: exit {r.returncode}, expected 2", message))
                continue
            doc = gltf_json(path)
            reasons, unexplained = set(), []
            for issue in rep["issues"]:
                why = explain(issue, doc)
                if why:
                    reasons.add(why)
                else:
                    unexplained.append(f"{issue['code']} at {issue['pointer']}: {issue['message']}")
            if unexplained:
                tests.append((False, f"{name}: accepted, but the validator reports errors no documented reason covers",
                              "\n".join(unexplained)))
            else:
                accepted_with_reason += 1
                tests.append((True, f"{name}: accepted though the validator reports {rep['errors']} error(s)",
                              "\n".join(sorted(reasons))))
        else:
            if r.returncode not in (0, 2):
                tests.append((False, f"{name}: exit {r.returncode}", message))
            elif r.returncode == 2:
                stricter += 1
                tests.append((os.path.basename(path) in message, f"{name}: valid glTF that conegraph refuses",
                              message))
            else:
                tests.append((True, f"{name}: valid, loads", ""))

    print(f"1..{len(tests)}")
    for i, (ok, what, diag) in enumerate(tests, 1):
        print(f"{'ok' if ok else 'not ok'} {i} - {what}")
        for line in diag.splitlines():
            print(f"# {line}")
    print(f"# {len(exports)} exported files, {len(corpus)} corpus files ({accepted_with_reason} accepted with a "
          f"documented reason, {stricter} valid but refused)")


if __name__ == "__main__":
    main()
