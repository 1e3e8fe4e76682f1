#!/usr/bin/env bash
# The installed CMake package from outside the build: examples/render_gltf configured against
# PREFIX alone (find_package(kiln), kiln::kiln), built and run on the Cornell box. Its EXR must
# hold the pixels `kiln render` writes with the same options, lit ones among them; a misspelt
# option must give the option table's one-line error and exit 2.
# Usage: cmake_package_test.sh SOURCE_DIR PREFIX WORK_DIR KILN_BINARY PYTHON (with NumPy and OpenImageIO)
set -euo pipefail
source_dir=$1 prefix=$2 work=$3 kiln=$4 python=$5
scene="$source_dir/scenes/cornell_box.gltf"
rm -rf "$work"
mkdir -p "$work"

cmake -S "$source_dir/examples/render_gltf" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" >"$work/configure.log"
cmake --build "$work/build" >"$work/build.log"
"$work/build/render_gltf" "$scene" "$work/example.exr" width=64 height=48 spp=2
"$kiln" render "$scene" -o "$work/cli.exr" --width 64 --height 48 --spp 2 -q

status=0
"$work/build/render_gltf" "$scene" "$work/refused.exr" sp=2 2>"$work/refused.txt" || status=$?
if [[ $status -ne 2 ]] || ! grep -q -- "--sp: is not a render option" "$work/refused.txt"; then
  echo "a misspelt option: exit $status, $(cat "$work/refused.txt")" >&2
  exit 1
fi

"$python" - "$work/example.exr" "$work/cli.exr" <<'PYTHON'
import sys

import numpy as np
import OpenImageIO as oiio

example, cli = (oiio.ImageBuf(path) for path in sys.argv[1:3])
assert example.spec().channelnames == cli.spec().channelnames, (example.spec().channelnames, cli.spec().channelnames)
a, b = example.get_pixels(oiio.FLOAT), cli.get_pixels(oiio.FLOAT)
assert a.shape == (48, 64, len(example.spec().channelnames)), a.shape
assert np.array_equal(a, b), f"{np.count_nonzero(a != b)} values differ from kiln render's"
rgb = [example.spec().channelnames.index(channel) for channel in "RGB"]
lit = a[:, :, rgb].max(axis=2) > 0.01
assert lit.sum() > 0.5 * lit.size, f"only {lit.sum()} of {lit.size} pixels lit"
print(f"example EXR: {a.shape[1]}x{a.shape[0]}, equal to kiln render's, {lit.sum()} lit pixels")
PYTHON
