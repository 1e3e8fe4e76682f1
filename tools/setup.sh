#!/usr/bin/env bash
# The README's first command: installs missing Debian packages, builds kiln and its Python module
# (incrementally), installs the module into Debian's site-packages for /usr/bin/python3 (when
# that folder is writable) and renders the demo scene to out/cornell_box.exr (plus a PNG preview).
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install_dependencies.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target kiln kiln_python
# `python3 -c "import kiln"` from anywhere: the package kiln/ (the module, the kiln binary, its plugin
# modules and shipped files), as pip would install it; the single-file module of earlier versions goes.
site=$(/usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_paths()["platlib"])')
if mkdir -p "$site" 2>/dev/null && [ -w "$site" ]; then
  rm -f "$site"/kiln.cpython-*.so "$site"/kiln_image_codecs.so "$site"/kiln_colour.so
  cmake --install build --component python --prefix "$site" >/dev/null
  echo "kiln: Python package installed in $site/kiln"
else
  echo "kiln: $site is not writable; use the module with PYTHONPATH=$PWD/build/python"
fi
mkdir -p out
# A second run renders again only when the binary or the scene changed since the last render.
if [[ out/cornell_box.png -nt out/cornell_box.exr && out/cornell_box.exr -nt build/renderer/app/kiln &&
      out/cornell_box.exr -nt scenes/cornell_box.gltf ]]; then
  echo "kiln: out/cornell_box.exr is up to date (preview: out/cornell_box.png)"
  exit 0
fi
build/renderer/app/kiln render scenes/cornell_box.gltf -o out/cornell_box.exr --spp 4
python3 tools/exr_to_png.py out/cornell_box.exr out/cornell_box.png
echo "kiln: wrote out/cornell_box.exr (preview: out/cornell_box.png)"
