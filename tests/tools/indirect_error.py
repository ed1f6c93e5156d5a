#!/usr/bin/env python3
"""The indirect light of graphs against the path tracer's, as docs/hybrid.md measures it.

    indirect_error.py SCENE [--size WxH] [--spp N] [--frames N] [--out DIR]
                      GRAPH[:PASS.PARAM=V,...] ...

Per scene the reference is path-traced twice (reference.json, 1 bounce and `--set
trace.bounces=0`, cached in OUT by scene and size); truth = the difference. Per graph: the
graph's image minus direct.json's (each side's own direct light taken away); then
  energy = mean luminance(estimate) / mean luminance(truth)
  nrmse  = rmse(estimate - truth) / rmse(truth)      (1: no better than leaving GI out)
and, from the render's --report, the gather pass's time in the last frame, the frame's and the GI
memory (with --rounds R, the smallest of R renders taken in turn). Images: conegraph render, differences: oiiotool, figures: conegraph compare.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def run(args, **kw):
    r = subprocess.run(args, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        sys.exit("failed (%d): %s\n%s%s" % (r.returncode, " ".join(args), r.stdout[-2000:], r.stderr[-2000:]))
    return r


def render(exe, scene, graph, sets, size, frames, out, report=None):
    args = [exe, "render", scene, "--graph", graph, "--size", size, "--frames", str(frames), "-o", out]
    for s in sets:
        args += ["--set", s]
    if report:
        args += ["--report", report]
    run(args)


def compare(exe, test, ref):
    return json.loads(run([exe, "compare", test, ref, "--json"]).stdout)["full"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("graphs", nargs="+", help="GRAPH or GRAPH:PASS.PARAM=V,PASS.PARAM=V")
    ap.add_argument("--size", default="160x90")
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--frames", type=int, default=3)
    ap.add_argument("--out", default="indirect-out")
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "apps", "conegraph"))
    ap.add_argument("--rounds", type=int, default=1,
                    help="render every graph this many times, one after the other in turn, and report the "
                         "smallest gather and frame times (the machine is shared: the least disturbed run)")
    ap.add_argument("--json", help="also write the rows to this file")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    key = hashlib.sha1(("%s|%s|%d" % (a.scene, a.size, a.spp)).encode()).hexdigest()[:12]
    ref1, ref0 = os.path.join(a.out, key + "-ref1.exr"), os.path.join(a.out, key + "-ref0.exr")
    truth, black = os.path.join(a.out, key + "-truth.exr"), os.path.join(a.out, key + "-black.exr")
    direct = os.path.join(a.out, key + "-direct.exr")
    if not os.path.exists(truth):
        render(a.exe, a.scene, "reference.json", ["trace.spp=%d" % a.spp], a.size, 1, ref1)
        render(a.exe, a.scene, "reference.json", ["trace.spp=%d" % a.spp, "trace.bounces=0"], a.size, 1, ref0)
        render(a.exe, a.scene, "direct.json", [], a.size, 1, direct)
        run(["oiiotool", ref1, ref0, "--sub", "-o", truth])
        run(["oiiotool", truth, "--mulc", "0", "-o", black])
    truth_rms = compare(a.exe, black, truth)["rmse"]
    rows = []
    timings = {}
    for rnd in range(a.rounds):
        for g in a.graphs:
            graph, _, set_text = g.partition(":")
            sets = [s for s in set_text.split(",") if s]
            tag = hashlib.sha1(g.encode()).hexdigest()[:8]
            img, rep = (os.path.join(a.out, "%s-%s.%s" % (key, tag, ext)) for ext in ("exr", "json"))
            render(a.exe, a.scene, graph, sets, a.size, a.frames, img if rnd == 0 else img + ".again.exr", rep)
            r = json.load(open(rep))
            gather = [p["ms"] for p in r["passes"] if p["name"] == "gather" and not p["culled"]]
            frame = sum(p["ms"] for p in r["passes"] if not p["culled"])
            t = timings.setdefault(g, [1e30, 1e30, r["memory"]["gi_bytes"] / 2 ** 20])
            t[0] = min(t[0], gather[0] if gather else 0.0)
            t[1] = min(t[1], frame)
    print("| graph | energy | nrmse | gather ms | frame ms | GI MiB |")
    print("|---|---:|---:|---:|---:|---:|")
    for g in a.graphs:
        tag = hashlib.sha1(g.encode()).hexdigest()[:8]
        img, est = (os.path.join(a.out, "%s-%s.%s" % (key, tag, ext)) for ext in ("exr", "est.exr"))
        run(["oiiotool", img, direct, "--sub", "-o", est])
        c = compare(a.exe, est, truth)
        t = timings[g]
        row = {"graph": g, "energy": c["lum_ratio"], "nrmse": c["rmse"] / truth_rms, "gather_ms": t[0],
               "frame_ms": t[1], "gi_mib": t[2]}
        rows.append(row)
        print("| %s | %.3f | %.3f | %.1f | %.1f | %.1f |" % (g, row["energy"], row["nrmse"], row["gather_ms"],
                                                          row["frame_ms"], row["gi_mib"]), flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"scene": a.scene, "size": a.size, "spp": a.spp, "rows": rows}, f, indent=1)


if __name__ == "__main__":
    main()
