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
  circles    inside a core module folder (those in NO_CIRCLES), each apps/ folder and the SDK
             (passes/sdk) no file leans on another that leans back on it, directly or around a
             longer circle: a file leans on a header of the folder
             it includes and on the file that defines a function or variable it names (read as
             text: non-static definitions at the start of a line, C++ ones only when extern "C").
             A circle means neither file can be read, tested or replaced without the other.

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
# core/image is left out: image.c hands the OIIO module (oiio_module.c) a table of its own
# allocators, a circle by design of the module's loading.
NO_CIRCLES = ["base", "metrics", "scene", "trace", "gl", "fg"]
NO_CIRCLES_OUTSIDE_CORE = ["apps/common", "apps/conegraph", "apps/demo", "passes/sdk"]
COMMENT_OR_STRING = re.compile(r'/\*.*?\*/|//[^\n]*|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'', re.S)
IDENTIFIER = re.compile(r"[A-Za-z_]\w*")
# A name at the start of a line followed by "(", the return type on the same line or the one above.
DEFINITION = re.compile(r"^(?:([A-Za-z_][\w \*]*?)\s*\**\s*)?\b([A-Za-z_]\w*)\s*\(")
# A file-scope variable defined with an initialiser ("const fg_format_info fg_formats[] = {").
VARIABLE = re.compile(r"^([A-Za-z_][\w \*]*?)\s*\**\s*\b([A-Za-z_]\w*)\s*(?:\[[^\]]*\])*\s*=")
KEYWORDS = {"if", "for", "while", "switch", "return", "sizeof", "defined"}


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


def code_text(path):
    """The file without comments; strings and characters emptied, keeping 'extern "C"' readable."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    return COMMENT_OR_STRING.sub(lambda m: " " if m.group(0)[0] == "/" else m.group(0)[0] * 2, text)


def definitions(text, cpp):
    """Names a file defines for other files: functions and initialised variables, not static."""
    lines = text.split("\n")
    names = set()
    for i, line in enumerate(lines):
        if not line or line[0].isspace() or line.startswith("#"):
            continue
        variable = VARIABLE.match(line)
        m = DEFINITION.match(line)
        if variable and not (m and m.end() <= variable.end() and "(" in line[:variable.end()]):
            words = variable.group(1).split()
            if not cpp and words and not {"static", "typedef", "extern"} & set(words) and words[0] != "return":
                names.add(variable.group(2))
            continue
        if not m or m.group(2) in KEYWORDS:
            continue
        kind = (m.group(1) or "") + " " + (lines[i - 1] if i and not m.group(1) else "")
        if "static" in kind.split() or "typedef" in kind.split() or (cpp and "extern" not in kind):
            continue
        rest = "\n".join(lines[i:i + 60])
        depth, k = 0, rest.index("(")
        for k in range(k, len(rest)):
            depth += {"(": 1, ")": -1}.get(rest[k], 0)
            if depth == 0:
                break
        if rest[k + 1:].lstrip().startswith("{"):
            names.add(m.group(2))
    return names


def circles(root, folder):
    """Each circle of files inside `folder` that lean on each other, as text."""
    files = sorted(sources(root, folder))
    text = {path: code_text(path) for path in files}
    owner = {}
    for path in files:
        if path.endswith((".c", ".cpp")):
            for name in definitions(text[path], path.endswith(".cpp")):
                owner.setdefault(name, path)
    edges = {path: {} for path in files}
    for path in files:
        for _, inc in includes(path):
            target = os.path.normpath(os.path.join(os.path.dirname(path), inc))
            if target in edges and target != path:
                edges[path][target] = "#include"
        # A header only declares: it leans on the headers it includes, not on the definitions.
        for word in set(IDENTIFIER.findall(text[path])) if not path.endswith(".h") else ():
            target = owner.get(word)
            if target and target != path and edges[path].get(target) != "#include":
                edges[path].setdefault(target, [])
                edges[path][target].append(word)
    # Strongly connected components (Tarjan); each one of more than a file holds a circle.
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in files:
        if v not in index:
            visit(v)
    texts = []
    for component in found:
        # One circle through the component's first file: a shortest way back to it.
        start = component[0]
        paths = {start: [start]}
        queue = [start]
        circle = None
        while queue and not circle:
            v = queue.pop(0)
            for w in edges[v]:
                if w == start:
                    circle = paths[v] + [start]
                    break
                if w in component and w not in paths:
                    paths[w] = paths[v] + [w]
                    queue.append(w)
        steps = [os.path.relpath(circle[0], root)]
        for a, b in zip(circle, circle[1:]):
            why = edges[a][b]
            why = why if isinstance(why, str) else ", ".join(sorted(why)[:3])
            steps.append(f"-> {os.path.relpath(b, root)} ({why})")
        others = len(component) - (len(circle) - 1)
        texts.append(" ".join(steps) + (f"; {others} more file(s) in the same knot" if others > 0 else ""))
    return texts


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

    for folder in [os.path.join("core", m) for m in NO_CIRCLES] + NO_CIRCLES_OUTSIDE_CORE:
        for circle in circles(root, folder):
            problems.append(f"{folder}: a circle: {circle}")

    for p in problems:
        print(p)
    print(f"check_layers: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")))
