#!/usr/bin/env bash
# The Cycles check of path_trace on a scene with an emissive surface (docs/reference.md):
# the courtyard of courtyard.py (a sun and one emissive lamp) at 0 and 1 bounces, under a
# uniform sky, and scaled to 2 km through a 5 cm near plane; both renderers sample the pixel
# area (Cycles' box filter, path_trace jitter=true).
#
#   bash run_courtyard.sh OUT_DIR [BUILD_DIR [SPP]]
#
# BUILD_DIR: the Meson build (default: build/ of this checkout), for bin conegraph and for
# core's library, which pt_sky_render.c (the path tracer under a sky, until `render --sky`
# exists) is compiled against. Needs Blender 3.4 (Debian's `blender`, with python3-numpy for
# its glTF importer) and oiiotool. Writes the renders, the `compare --json` figures and the
# figures' PNGs to OUT_DIR.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../../.." && pwd)
out=$1
build=$(cd "${2:-$repo/build}" && pwd)
spp=${3:-1024}
conegraph=$build/apps/conegraph
export CONEGRAPH_SHADER_DIR=$repo/shaders CONEGRAPH_GRAPH_DIR=$repo/graphs
size=(320 180)
sky=0.12,0.14,0.18
mkdir -p "$out"
cd "$out"
cc -O2 -std=c11 -D_DEFAULT_SOURCE -I"$repo/core/include" -o pt_sky_render "$here/pt_sky_render.c" \
  "$build/core/libcgcore.a" -lembree3 -lOpenImageIO -lOpenImageIO_Util -ltinygltf -ljansson -lstdc++ -lm \
  -lpthread -ldl

python3 "$here/courtyard.py" courtyard-src.gltf
python3 "$here/courtyard.py" courtyard-km-src.gltf 100 0.05
"$conegraph" export courtyard-src.gltf courtyard.gltf
"$conegraph" export courtyard-km-src.gltf courtyard-km.gltf

# name scene bounces sky
runs=(
  "b0 courtyard.gltf 0 none"
  "b1 courtyard.gltf 1 none"
  "sky-b1 courtyard.gltf 1 $sky"
  "km-b1 courtyard-km.gltf 1 none"
)
for run in "${runs[@]}"; do
  read -r name scene bounces s <<<"$run"
  blender -b --factory-startup -P "$here/render_cycles.py" -- "$scene" "cycles-$name.exr" \
    "${size[0]}" "${size[1]}" "$spp" "$bounces" "$s" area >"cycles-$name.log" 2>&1
  if [ "$s" != none ]; then
    ./pt_sky_render "$scene" "pt-$name.exr" "${size[0]}" "${size[1]}" "$spp" "$bounces" "$s"
  else
    "$conegraph" render "$scene" --graph reference.json --size "${size[0]}x${size[1]}" \
      --set trace.spp="$spp" --set trace.bounces="$bounces" --set trace.jitter=true \
      --set trace.progress=false -o "pt-$name.exr" >/dev/null
  fi
  "$conegraph" compare "cycles-$name.exr" "pt-$name.exr" --json --heatmap "heat-$name.png" \
    --heatmap-max 0.3 >"courtyard-$name.json"
  cat "courtyard-$name.json"
  for who in cycles pt; do
    oiiotool "$who-$name.exr" --ch R,G,B --colorconvert linear sRGB -d uint8 -o "$who-$name.png"
  done
  oiiotool "cycles-$name.png" "pt-$name.png" "heat-$name.png" --ch R,G,B --mosaic 1x3 \
    -o "courtyard-$name-cycles-pt-error.png"
done
