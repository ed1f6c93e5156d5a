#!/bin/bash
# tests/tools/gi_measure.sh: the GI figures of docs/vct.md (indirect light against the path tracer,
# the white furnace, volume reads per pixel), one line per render. Run from the source tree with a
# build in ./build (BUILD= to choose another).
#
#   gi_measure.sh indirect SCENE GRAPH LABEL [--set PASS.PARAM=VALUE ...]
#       `conegraph compare --direct --ref-direct` (core/metrics' cg_metrics_part): the estimate is
#       GRAPH's image minus its own direct light and emission (direct.radiance + gbuf.emissive of
#       the same frame), the truth the path tracer's image minus its parts emitted and
#       direct_punctual (reference.json, trace.bounces=$BOUNCES, $SPP spp, cached in $CACHE), as
#       bench's GI columns; prints the energy and nrmse of the indirect part and both means.
#   gi_measure.sh suite GRAPH TAG [--set ...]      `indirect` over $SCENES
#   gi_measure.sh furnace GRAPH TAG [--set ...]    builtin:furnace?albedo=0.5&radiance=2 at 64x64,
#                                                  scales $SCALES: mean and worst pixel against
#                                                  path_trace at $FURNACE_BOUNCES (gi-metric furnace)
#   gi_measure.sh reads SCENE GRAPH LABEL [--set ...]  volume reads per covered pixel of the diffuse
#                                                  cones (gather.count_reads): a deterministic cost;
#                                                  mean, median, 99th percentile and maximum
# Environment: SIZE (160x90), SPP (1024), BOUNCES (1), CACHE (build/gi-cache), SCENES, SCALES.
set -e
BUILD=${BUILD:-build}
C=$BUILD/apps/conegraph
M=$BUILD/tests/gi-metric
CACHE=${CACHE:-$BUILD/gi-cache}
SIZE=${SIZE:-160x90}
SPP=${SPP:-1024}
BOUNCES=${BOUNCES:-1}
export CONEGRAPH_LOG=${CONEGRAPH_LOG:-warn}
OUT=${OUT:-$BUILD/gi-out}
mkdir -p "$CACHE" "$OUT"

# The truth of SCENE at $SIZE, $SPP, $BOUNCES: its directory ($CACHE/KEY: ref.exr and the parts
# emitted.exr, punctual.exr), rendered once.
truth() {
  local scene=$1 key d
  key=$(echo "$scene|$SIZE|$SPP|$BOUNCES|v3" | md5sum | cut -c1-12)
  d=$CACHE/$key
  mkdir -p "$d"
  echo "$scene $SIZE spp $SPP bounces $BOUNCES" > "$d/what"
  if [ ! -f "$d/ref.exr" ]; then
    $C render "$scene" --graph reference.json --size "$SIZE" --set trace.spp="$SPP" --set trace.bounces="$BOUNCES" \
      --set trace.parts=true --set trace.progress=false --dump trace.emitted="$d/emitted.exr" \
      --dump trace.direct_punctual="$d/punctual.exr" -o "$d/ref.tmp.exr" > /dev/null 2>> "$OUT/render.log"
    mv "$d/ref.tmp.exr" "$d/ref.exr"
  fi
  echo "$d"
}

name() { echo -n "$1" | tr -c 'A-Za-z0-9_.=-' '_'; }

indirect() {
  local scene=$1 graph=$2 label=$3 d img
  shift 3
  d=$(truth "$scene")
  img=$OUT/$(name "$label")
  $C render "$scene" --graph "$graph" --size "$SIZE" "$@" --dump direct.radiance="$img.direct.exr" \
    --dump gbuf.emissive="$img.emissive.exr" -o "$img.exr" > /dev/null 2>> "$OUT/render.log"
  $C compare "$img.exr" "$d/ref.exr" --direct "$img.direct.exr" --direct "$img.emissive.exr" \
    --ref-direct "$d/emitted.exr" --ref-direct "$d/punctual.exr" --json |
    python3 -c 'import json, sys; i = json.load(sys.stdin)["indirect"]
f = lambda x: "inf" if x is None else "%.4f" % x
print(sys.argv[1], "energy", f(i["energy"]), "nrmse", f(i["nrmse"]), "meanY_est %.6g meanY_truth %.6g" % (i["mean_luminance_test"], i["mean_luminance_ref"]))' "$label"
}

cmd=$1
shift
case "$cmd" in
indirect) indirect "$@" ;;
suite)
  graph=$1 tag=$2
  shift 2
  SCENES=${SCENES:-"cornell openworld plates plates?h=0.5 plates?h=0.25 plates?h=2 wallfloor thinwall thinwall?view=1 boxplane terrain terrain?A=0"}
  for s in $SCENES; do indirect "builtin:$s" "$graph" "$tag:$s" "$@"; done ;;
furnace)
  graph=$1 tag=$2
  shift 2
  for sc in ${SCALES:-1e-3 1 1e4}; do
    img=$OUT/furnace_$(name "$tag")_$sc.exr
    $C render "builtin:furnace?scale=$sc&albedo=0.5&radiance=2" --graph "$graph" --size 64x64 "$@" -o "$img" > /dev/null 2>> "$OUT/render.log"
    echo "$tag scale $sc: $($M furnace "$img" 0.5 2 "${FURNACE_BOUNCES:-0}")"
  done ;;
reads)
  scene=$1 graph=$2 label=$3
  shift 3
  img=$OUT/reads_$(name "$label").exr
  $C render "$scene" --graph "$graph" --size "$SIZE" "$@" --set gather.count_reads=true \
    --dump gather.reads="$img" -o "$OUT/reads_image.exr" > /dev/null 2>> "$OUT/render.log"
  echo "$label reads per pixel: $($M mean "$img")" ;;
*)
  echo "usage: gi_measure.sh indirect|suite|furnace|reads ... (see the file's head)" >&2
  exit 2 ;;
esac
