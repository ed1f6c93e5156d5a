#!/bin/bash
# gather_reads.sh: the gathers' time and counted texture reads (render --pass-costs) for
# downsample 1, 2 and 4, on Cornell, the open world and a DEM with a village, vct.json and
# hybrid.json at 640x360: the gather's median ms of frames 2 and 3, the reads of the last frame,
# the pixels that traced, reads per pixel and ns per read (docs/results/gi-resolution.md).
# Run from the source tree with a build in build-me (BUILD=dir to change); OUT=dir for scratch.
set -u
BUILD=${BUILD:-build-me}
OUT=${OUT:-/tmp/gather_reads}
mkdir -p "$OUT"
export CONEGRAPH_SHADER_DIR=$PWD/shaders CONEGRAPH_GRAPH_DIR=$PWD/graphs
DEM='dem:tests/data/dem/valley.png?spacing=15.625&scale=0.002&meshes=tests/data/dem/village.gltf&place=instances'
for scene in builtin:cornell builtin:openworld "$DEM"; do
 for g in vct hybrid; do
  for d in 1 2 4; do
   f=$OUT/costs.csv
   nice -n 5 "$BUILD/apps/conegraph" render "$scene" --graph graphs/$g.json --size 640x360 --frames 3 \
     --set gather.downsample=$d -o "$OUT/o.exr" --pass-costs $f 2>/dev/null >/dev/null || { echo "fail $scene $g $d"; continue; }
   python3 - "$scene" $g $d $f <<'PY'
import csv,sys,statistics
scene,g,d,f=sys.argv[1:]
rows=[r for r in csv.DictReader(open(f)) if r['pass']=='gather']
ms=statistics.median(float(r['ms']) for r in rows[1:])
r=rows[-1]
reads=float(r['reads']); items=float(r['items'])
print(f"{scene[:20]:20s} {g:7s} d={d} gather {ms:8.1f} ms  reads {reads/1e6:8.3f} M  items {items:7.0f}  per item {reads/items:7.1f}  ns/read {ms*1e6/reads:6.1f}")
PY
  done
 done
done
