#!/usr/bin/env python3
"""The cost of one pass of two graphs, frame by frame in one process (a benchmark: it prints
figures, it tests nothing).

On a shared machine the load moves between processes by 20% and more (docs/hybrid.md), within one
process far less: so this runs both graphs as one. It writes a graph holding GRAPH_A's passes and
GRAPH_B's, those of B that differ from A's renamed with the prefix `b_` (passes defined alike, the
shadow map and the G-buffer, are shared), both graphs' outputs kept, and renders it with
`conegraph render --frames N --pass-costs`. Per frame, A's PASS against B's PASS; it prints the
median of those ratios over the frames after the first (the first compiles the shaders) and the
ratio of the two passes' fastest frames.

usage: gather_pair.py CONEGRAPH GRAPH_A GRAPH_B [--pass gather] [--scene builtin:openworld]
                      [--size 320x180] [--frames 10] [--runs 1] [--set PASS.PARAM=V]...

--set applies to the pair graph (B's renamed passes by their b_ names). Graph files without a
'/' are looked up in the source tree's graphs/.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

GRAPH_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "graphs")


def refuse(message):
    """Bad input: the message on stderr, exit 2 (as conegraph's own commands)."""
    sys.stderr.write("gather_pair.py: %s\n" % message)
    sys.exit(2)


def load(name):
    path = name if "/" in name else os.path.join(GRAPH_DIR, name)
    try:
        with open(path) as f:
            graph = json.load(f)
    except (OSError, ValueError) as e:
        refuse("%s: %s" % (path, e))
    if not isinstance(graph.get("passes"), dict) or not isinstance(graph.get("outputs"), list):
        refuse("%s: a graph file needs \"passes\" (an object) and \"outputs\" (a list)" % path)
    return graph


def pair_graph(a, b):
    """A's graph with B's passes added, those that differ from A's under b_ names."""
    passes = dict(a["passes"])
    renamed = {n for n, p in b["passes"].items() if passes.get(n) != p}
    # A pass that reads a renamed pass must be renamed too, or it would read A's.
    changed = True
    while changed:
        changed = False
        for n, p in b["passes"].items():
            if n not in renamed and any(v.split(".")[0] in renamed for v in p.get("inputs", {}).values()):
                renamed.add(n)
                changed = True

    def rename(ref):
        head, _, tail = ref.partition(".")
        return "b_" + head + ("." + tail if tail else "") if head in renamed else ref

    for n in renamed:
        p = json.loads(json.dumps(b["passes"][n]))
        if "inputs" in p:
            p["inputs"] = {k: rename(v) for k, v in p["inputs"].items()}
        passes["b_" + n] = p
    graph = dict(a)
    graph["passes"] = passes
    graph["outputs"] = list(a["outputs"]) + [rename(o) for o in b["outputs"] if rename(o) != o]
    return graph


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("conegraph")
    ap.add_argument("graph_a")
    ap.add_argument("graph_b")
    ap.add_argument("--pass", dest="pass_name", default="gather")
    ap.add_argument("--scene", default="builtin:openworld")
    ap.add_argument("--size", default="320x180")
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--set", action="append", default=[])
    args = ap.parse_args()
    if args.frames < 2:
        refuse("--frames must be at least 2 (the first compiles the shaders)")
    graph = pair_graph(load(args.graph_a), load(args.graph_b))
    name_b = "b_" + args.pass_name
    if args.pass_name not in graph["passes"] or name_b not in graph["passes"]:
        refuse("pass '%s' is not in both graphs, or is the same in both" % args.pass_name)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "pair.json")
        with open(path, "w") as f:
            json.dump(graph, f, indent=1)
        for run in range(args.runs):
            costs = os.path.join(tmp, "costs.csv")
            cmd = [args.conegraph, "render", args.scene, "--graph", path, "--size", args.size,
                   "--frames", str(args.frames), "-o", os.path.join(tmp, "out.exr"), "--pass-costs", costs]
            for s in args.set:
                cmd += ["--set", s]
            done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            if done.returncode != 0:
                sys.stderr.write(done.stderr)
                sys.exit(done.returncode)
            ms = {}
            with open(costs) as f:
                for row in csv.DictReader(f):
                    ms.setdefault(int(row["frame"]), {})[row["pass"]] = float(row["ms"])
            frames = [k for k in sorted(ms) if k >= 1]
            a = [ms[k][args.pass_name] for k in frames]
            b = [ms[k][name_b] for k in frames]
            print("run %d: %s %s %.1f ms, %s %s %.1f ms (medians of %d frames); per-frame ratio median %.3f,"
                  " fastest frames' ratio %.3f" % (run + 1, args.graph_a, args.pass_name, statistics.median(a),
                                                   args.graph_b, args.pass_name, statistics.median(b), len(frames),
                                                   statistics.median([x / y for x, y in zip(a, b)]), min(a) / min(b)))


if __name__ == "__main__":
    main()
