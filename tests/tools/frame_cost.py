#!/usr/bin/env python3
"""Per-frame cost of dynamic scenes (a benchmark: it prints figures, it tests nothing).

Runs `conegraph render --frames N --pass-costs` on builtin:openworld for each triangle count,
motion (sun: the sun turning; one: one building moving; all: every complex object moving),
graph and cache setting, and prints a Markdown table of the medians over the frames after the
first (the first builds every cache):

  update   the lightmap update: every pass that builds the 3D and 2D lightmaps, their mips and
           tables (voxelize, voxel_light, mip3d, heightmap_raster, mip2d, hsat), and apart its 3D
           part (voxelize, voxel_light, mip3d) and its 2D part (heightmap_raster, mip2d, hsat)
  common   what every renderer pays each frame (shadow_map, gbuffer, direct_light, composite)
  gather   the cone gather (cone_gather, hybrid_gather)
  update / gather   the issue's done-when ratio (at most 0.3 wanted)

then each pass's share of the frame and what the caching passes (heightmap_raster, voxelize)
reported rebuilding in the last frame. `cache=off` sets PASS.cache=false on every heightmap_raster
and voxelize pass of the graph (the papers' rebuild every frame; voxelize caches only with
model=surface, and ignores the setting otherwise); graphs without one run once.
Timings on llvmpipe are noisy and the machine may be shared: compare ratios of one run.

usage: frame_cost.py CONEGRAPH [--triangles 200000,2000000] [--motions sun,one,all]
                     [--graphs vct.json,hybrid.json] [--size 1280x720] [--frames 4]
                     [--period 20] [--exported]

--exported writes each built-in scene (its motion included) to a .glb with `conegraph export` and
renders that file instead: the same scene read back as glTF, animation and all, which the issue
asks to measure beside the built-in.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

UPDATE = {"voxelize", "voxel_light", "mip3d", "heightmap_raster", "mip2d", "hsat"}
UPDATE_3D = {"voxelize", "voxel_light", "mip3d"}
COMMON = {"shadow_map", "gbuffer", "direct_light", "composite"}
GATHER = {"cone_gather", "hybrid_gather"}


CACHING = {"heightmap_raster", "voxelize"}


def caching_passes(conegraph, graph, workdir):
    """Names of the graph's heightmap_raster and voxelize passes, from `conegraph graph --report`."""
    report = os.path.join(workdir, "graph.json")
    done = subprocess.run([conegraph, "graph", graph, "--report", report], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("frame_cost: conegraph graph %s exited %d:\n%s" % (graph, done.returncode, done.stderr))
    with open(report) as f:
        passes = json.load(f)["passes"]
    os.remove(report)
    return [p["name"] for p in passes if p["type"] in CACHING]


def run(conegraph, scene, graph, sets, size, frames, workdir):
    costs = os.path.join(workdir, "costs.csv")
    cmd = [conegraph, "render", scene, "--graph", graph, "--size", size, "--frames", str(frames),
           "--pass-costs", costs, "-o", os.path.join(workdir, "frame.exr")]
    for s in sets:
        cmd += ["--set", s]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("frame_cost: %s exited %d:\n%s" % (" ".join(cmd), done.returncode, done.stderr))
    rows = list(csv.DictReader(open(costs)))
    os.remove(costs)
    return rows


def summarize(rows, frames):
    """Medians over frames 1.. (0-based; frame 0 builds the caches) per pass and per group."""
    later = [r for r in rows if int(r["frame"]) >= 1] if frames > 1 else rows
    per_frame = {}
    per_pass = {}
    types = {}
    for r in later:
        f = int(r["frame"])
        ms = float(r["ms"])
        types[r["pass"]] = r["type"]
        per_pass.setdefault(r["pass"], []).append(ms)
        groups = per_frame.setdefault(f, {"update": 0.0, "3d": 0.0, "2d": 0.0, "common": 0.0, "gather": 0.0,
                                          "other": 0.0, "frame": 0.0})
        t = r["type"]
        group = "update" if t in UPDATE else "common" if t in COMMON else "gather" if t in GATHER else "other"
        groups[group] += ms
        if t in UPDATE:
            groups["3d" if t in UPDATE_3D else "2d"] += ms
        groups["frame"] += ms
    med = {g: statistics.median(v[g] for v in per_frame.values()) for g in
           ("update", "3d", "2d", "common", "gather", "other", "frame")}
    passes = {p: statistics.median(v) for p, v in per_pass.items()}
    last = max(int(r["frame"]) for r in rows)
    rebuilt = {r["pass"]: r["rebuilt"] for r in rows if int(r["frame"]) == last and r["rebuilt"]}
    return med, passes, types, rebuilt


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("conegraph")
    ap.add_argument("--triangles", default="200000,2000000")
    ap.add_argument("--motions", default="sun,one,all")
    ap.add_argument("--graphs", default="vct.json,hybrid.json")
    ap.add_argument("--size", default="1280x720")
    ap.add_argument("--frames", type=int, default=4)
    ap.add_argument("--period", default="20")
    ap.add_argument("--exported", action="store_true",
                    help="render each scene exported to .glb and read back (conegraph export)")
    a = ap.parse_args()
    if a.frames < 2:
        sys.exit("frame_cost: --frames must be at least 2 (the first frame builds the caches)")
    print("frame_cost: %s, %d frames per run (medians of frames 2..%d), ms from `render --timing sync`"
          % (a.size, a.frames, a.frames))
    print()
    if a.exported:
        print("Each scene exported with `conegraph export` and rendered from the .glb.")
        print()
    print("| triangles | motion | graph | cache | frame ms | update ms (3D + 2D) | common ms | gather ms "
          "| update / gather | passes (ms, share of the frame) | caching passes, last frame |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as workdir:
        for tri in a.triangles.split(","):
            for motion in a.motions.split(","):
                scene = "builtin:openworld?triangles=%s&motion=%s&period=%s" % (tri, motion, a.period)
                if a.exported:
                    glb = os.path.join(workdir, "scene.glb")
                    done = subprocess.run([a.conegraph, "export", scene, glb], capture_output=True, text=True)
                    if done.returncode != 0:
                        sys.exit("frame_cost: conegraph export %s exited %d:\n%s"
                                 % (scene, done.returncode, done.stderr))
                    scene = glb
                for graph in a.graphs.split(","):
                    cached = caching_passes(a.conegraph, graph, workdir)
                    settings = [("on", []), ("off", ["%s.cache=false" % h for h in cached])] \
                        if cached else [("-", [])]
                    for label, sets in settings:
                        rows = run(a.conegraph, scene, graph, sets, a.size, a.frames, workdir)
                        med, passes, types, rebuilt = summarize(rows, a.frames)
                        shares = ", ".join("%s %.0f (%.0f%%)" % (p, ms, 100.0 * ms / med["frame"])
                                           for p, ms in passes.items())
                        note = "; ".join("%s: %s" % (h, rebuilt[h]) for h in cached if h in rebuilt) or "-"
                        ratio = med["update"] / med["gather"] if med["gather"] > 0 else float("inf")
                        print("| %s | %s | %s | %s | %.0f | %.0f (%.0f + %.0f) | %.0f | %.0f | %.2f | %s | %s |"
                              % (tri, motion, graph, label, med["frame"], med["update"], med["3d"], med["2d"],
                                 med["common"], med["gather"], ratio, shares, note), flush=True)


if __name__ == "__main__":
    main()
