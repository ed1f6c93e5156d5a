#!/usr/bin/env bash
# The plugin walk-through of docs/architecture.md, run as it is written there: builds
# tests/plugin/example_plugin.c outside meson, against the source tree and a build directory,
# and loads it into conegraph. Arguments: source root, build root, the conegraph executable.
# Prints TAP.
set -u
source_root=$1 build_root=$2 conegraph=$3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cd "$source_root" || exit 1
echo "1..2"
if ${CC:-cc} -std=c11 -Wall -Wextra -shared -fPIC -I core/include -I passes -I shaders -I "$build_root/core" \
    tests/plugin/example_plugin.c -o "$out/example_plugin.so"; then
    echo "ok 1 - example_plugin.c builds outside meson"
else
    echo "not ok 1 - example_plugin.c builds outside meson"
    exit 1
fi
if "$conegraph" passes --plugin "$out/example_plugin.so" | grep -q '^example_fill$'; then
    echo "ok 2 - conegraph passes --plugin lists example_fill"
else
    echo "not ok 2 - conegraph passes --plugin lists example_fill"
    exit 1
fi
