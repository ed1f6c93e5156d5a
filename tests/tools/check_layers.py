#!/usr/bin/env python3
"""Checks who includes whom, so that the folder tree keeps telling the architecture.

  core/      a module includes core's public headers (include/cg/) of its own module and of
             the modules before it in LAYERS, its own private headers, and nothing of passes/
             or apps/; a public header obeys its module's rule too.
  passes/    a pass folder includes cg/ headers, the SDK's (sdk/) and its own files; the SDK
             includes cg/ and sdk/ headers and the one header C shares with GLSL,
             shaders/common/blocks.h, which passes reach through sdk/blocks.h. No pass includes
             another pass's files.
  apps/      apps include cg/ and sdk/ headers and their own; nothing else under passes/.

Prints each violation as FILE:LINE: what; exits 1 when there is any (meson runs it as a test).
"""
import os
import re
import sys

LAYERS = ["base", "image", "metrics", "scene", "trace", "gl", "fg"]
HEADER_MODULE = {
    "error.h": "base", "progress.h": "base", "log.h": "base", "fs.h": "base",
    "image.h": "image", "metrics.h": "metrics",
    "scene.h": "scene", "camera.h": "scene", "pt_render.h": "trace", "bsdf.h": "trace",
    "gl.h": "gl", "shader.h": "gl", "gpu_scene.h": "gl",
    "fg.h": "fg", "graphfile.h": "fg",
}
# Headers of shaders/ that C includes too (the SDK only, which re-exports them).
SHARED_WITH_GLSL = {"common/blocks.h"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def includes(path):
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE.match(line)
            if m:
                yield number, m.group(1)


def sources(root, folder):
    for dirpath, _, names in os.walk(os.path.join(root, folder)):
        for name in sorted(names):
            if name.endswith((".c", ".h", ".cpp", ".in")):
                yield os.path.join(dirpath, name)


def main(root):
    root = os.path.abspath(root)
    problems = []
    public = os.path.join(root, "core", "include", "cg")
    for name in os.listdir(public):
        if name not in HEADER_MODULE:
            problems.append(f"core/include/cg/{name}: not assigned to a module in {__file__}")

    def check_core(path, module):
        level = LAYERS.index(module)
        for line, inc in includes(path):
            where = f"{os.path.relpath(path, root)}:{line}"
            if inc.startswith("cg/"):
                owner = HEADER_MODULE.get(inc[3:])
                if owner is None:
                    problems.append(f"{where}: includes unknown public header {inc}")
                elif LAYERS.index(owner) > level:
                    problems.append(f"{where}: module {module} includes {inc} of module {owner}, a later layer")
            elif inc.startswith("sdk/") or inc.startswith("passes/") or inc.startswith("apps/"):
                problems.append(f"{where}: core includes {inc}")

    for module in LAYERS:
        for path in sources(root, os.path.join("core", module)):
            check_core(path, module)
    for name, module in HEADER_MODULE.items():
        path = os.path.join(public, name)
        if os.path.exists(path):
            check_core(path, module)

    passes = os.path.join(root, "passes")
    for entry in sorted(os.listdir(passes)):
        folder = os.path.join(passes, entry)
        if not os.path.isdir(folder):
            continue
        for path in sources(root, os.path.join("passes", entry)):
            for line, inc in includes(path):
                where = f"{os.path.relpath(path, root)}:{line}"
                own = os.path.exists(os.path.join(os.path.dirname(path), inc))
                if inc.startswith("cg/") or inc.startswith("sdk/") or (own and "/" not in inc):
                    continue
                if entry == "sdk" and inc in SHARED_WITH_GLSL:
                    continue
                problems.append(f"{where}: a pass includes {inc} (only cg/, sdk/ and its own files)")
    for path in sources(root, "passes"):
        if os.path.dirname(path) == passes:
            for line, inc in includes(path):
                if not (inc.startswith("cg/") or inc.startswith("sdk/")):
                    problems.append(f"{os.path.relpath(path, root)}:{line}: includes {inc}")

    for path in sources(root, "apps"):
        for line, inc in includes(path):
            where = f"{os.path.relpath(path, root)}:{line}"
            if inc.startswith("cg/") or inc.startswith("sdk/"):
                continue
            target = os.path.normpath(os.path.join(os.path.dirname(path), inc))
            inside_apps = target.startswith(os.path.join(root, "apps") + os.sep)
            if os.path.exists(target) and inside_apps:
                continue
            # Headers of another apps folder reached through its include directory.
            if any(os.path.exists(os.path.join(root, "apps", d, inc)) for d in os.listdir(os.path.join(root, "apps"))):
                continue
            problems.append(f"{where}: apps include {inc} (only cg/, sdk/ and apps' own headers)")

    for p in problems:
        print(p)
    print(f"check_layers: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")))
