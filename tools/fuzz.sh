#!/usr/bin/env bash
# Fuzzes kiln's loader with libFuzzer (clang-14 from Debian, ASan+UBSan).
#   tools/fuzz.sh [TARGET] [SECONDS]
#     TARGET  gltf_loader (whole .gltf/.glb files), quadric (the KILN_quadric extension),
#             image_header (encoded image headers), image_decode (PNG and JPEG through kiln's own
#             decoding, io/image_codecs/direct_decode.h), transforms (extreme transforms, cameras and
#             coordinates through the whole render job), draco_stream (KHR_draco_mesh_compression
#             streams through the decoder wrapper), resume_check (damaged EXR, deep EXR and preview
#             outputs through `kiln batch --resume`'s check) or all (default: every one in sequence);
#             SECONDS per target, default 300
# Each run's last lines (libFuzzer's final stats) give executions and coverage; the full log is
# fuzz/findings/TARGET.log. Seeds for gltf_loader: scenes/, tests/data/bad_gltf/,
# tests/data/fuzz_regressions/ and, when present, ../shared/assets (files under 1 MiB); for quadric:
# the definitions of scenes/quadric_showcase.gltf, one per seed and all together.
# Findings land in fuzz/findings/; each one becomes a regression input in tests/data/fuzz_regressions/,
# which the normal test suite replays (tests/fuzz_regression_test.cpp).
set -euo pipefail
cd "$(dirname "$0")/.."
target=all
seconds=300
for arg in "$@"; do
  case "$arg" in
    gltf_loader | quadric | image_header | image_decode | transforms | draco_stream | ocio_config_text | resume_check | all) target="$arg" ;;
    *[!0-9]* | "") echo "usage: tools/fuzz.sh [gltf_loader|quadric|image_header|image_decode|transforms|draco_stream|ocio_config_text|resume_check|all] [SECONDS]" >&2 && exit 2 ;;
    *) seconds="$arg" ;;
  esac
done
targets=(gltf_loader quadric image_header image_decode transforms draco_stream ocio_config_text resume_check)
[[ "$target" != all ]] && targets=("$target")

if ! command -v clang++-14 >/dev/null; then
  apt-get update -q && apt-get install -y -q clang-14
fi
tools/install_dependencies.sh
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKILN_FUZZ=ON \
  -DKILN_BUILD_TESTS=OFF -DKILN_BUILD_BENCHMARKS=OFF -DKILN_SANITIZE=address,undefined "${launcher[@]}" >/dev/null
cmake --build build-fuzz --target "${targets[@]/#/fuzz_}"
mkdir -p fuzz/findings
failed=0

seed_gltf_loader() {
  local seeds=(scenes tests/data/bad_gltf tests/data/fuzz_regressions)
  [[ -d ../shared/assets ]] && seeds+=(../shared/assets)
  find "${seeds[@]}" -type f \( -name '*.gltf' -o -name '*.glb' \) -size -1024k -exec cp -n {} "$1/" \; 2>/dev/null || true
}

# Input format of fuzz_quadric: the extension's value, a newline, then the node's placement.
seed_quadric() {
  python3 - "$1" <<'PY'
import json, sys
ext = json.load(open("scenes/quadric_showcase.gltf"))["extensions"]["KILN_quadric"]
defs = ext["primitives"]
for i, d in enumerate(defs):
    with open(f"{sys.argv[1]}/one_{i}", "w") as f:
        f.write(json.dumps({"primitives": [d]}) + "\n" + json.dumps({"primitive": 0, "material": 0}))
    with open(f"{sys.argv[1]}/all_{i}", "w") as f:
        f.write(json.dumps(ext) + "\n" + json.dumps({"primitive": i}))
PY
}

# Seeds for fuzz_image_header: the headers of the images in scenes/ and tests/data (first 4 KiB).
seed_image_header() {
  find scenes tests/data -type f \( -name '*.png' -o -name '*.jpg' -o -name '*.jpeg' -o -name '*.webp' \) \
    -size -4096k | head -200 | while read -r f; do head -c 4096 "$f" >"$1/$(basename "$f")"; done
}

# Seeds for fuzz_image_decode: whole PNG and JPEG images of scenes/, tests/data and the sample assets
# (the small ones: libFuzzer mutates within -max_len).
seed_image_decode() {
  local seeds=(scenes tests/data)
  [[ -d ../shared/assets ]] && seeds+=(../shared/assets)
  find "${seeds[@]}" -type f \( -name '*.png' -o -name '*.jpg' -o -name '*.jpeg' \) -size -256k -not -path '*/invalid/*' |
    head -100 | while read -r f; do cp -n "$f" "$1/$(echo "$f" | tr '/' '_')"; done || true  # head ends find early
}

# Seeds for fuzz_transforms: the flag byte alone (every number at its default), one per flag set.
seed_transforms() {
  for flags in 0 1 2 3 4 6 12 15; do printf "\\x$(printf %02x $flags)" >"$1/flags_$flags"; done
}

# Seeds for fuzz_draco_stream: the sample assets' Draco buffers (Box.bin is one whole stream), each
# behind a first byte (36) asking for attributes 0 and 1 as three floats each.
seed_draco_stream() {
  [[ -d ../shared/assets ]] || return 0
  find ../shared/assets -path '*glTF-Draco*' -name '*.bin' -size -1024k | while read -r f; do
    { printf '\x24'; cat "$f"; } >"$1/$(basename "$(dirname "$(dirname "$f")")")_$(basename "$f")"
  done
}

# Seeds for fuzz_ocio_config_text: kiln's own OpenColorIO config.
seed_ocio_config_text() {
  cp share/ocio/kiln.ocio "$1/kiln.ocio"
}

# Seeds for fuzz_resume_check: a tiny render's outputs in several codecs, with its deep file and
# previews, each behind the byte naming its kind (0 flat, 1 deep, 2 PNG, 3 JPEG). Needs a kiln
# binary (the release tree's, or KILN=...); without one the corpus starts from the studio map.
seed_resume_check() {
  local kiln="${KILN:-build/renderer/app/kiln}" work
  work="$(mktemp -d)"
  { printf '\x00'; cat share/environments/studio.exr; } >"$1/studio.exr"
  if [[ -x "$kiln" ]]; then
    for codec in zip piz b44 dwaa; do
      "$kiln" render scenes/cornell_box.gltf -o "$work/$codec.exr" --width 8 --height 6 --spp 1 -q \
        --compression "$codec" --multipart --deep --preview "$work/$codec.png" &&
        { printf '\x00'; cat "$work/$codec.exr"; } >"$1/$codec.exr" &&
        { printf '\x01'; cat "$work/$codec.deep.exr"; } >"$1/$codec.deep.exr" &&
        { printf '\x02'; cat "$work/$codec.png"; } >"$1/$codec.png"
    done
    "$kiln" render scenes/cornell_box.gltf -o "$work/j.exr" --width 8 --height 6 --spp 1 -q --preview "$work/j.jpg" &&
      { printf '\x03'; cat "$work/j.jpg"; } >"$1/j.jpg"
  fi
  rm -rf "$work"
}

for t in "${targets[@]}"; do
  corpus="fuzz/corpus/$t"
  mkdir -p "$corpus"
  "seed_$t" "$corpus"
  dict=(-dict=fuzz/gltf.dict)
  [[ "$t" == quadric ]] && dict=(-dict=fuzz/quadric.dict)
  [[ "$t" == image_header || "$t" == image_decode || "$t" == transforms || "$t" == draco_stream ||
     "$t" == ocio_config_text || "$t" == resume_check ]] && dict=()
  echo "kiln: fuzzing $t for $seconds s" >&2
  set +e
  ASAN_OPTIONS=detect_leaks=1:fast_unwind_on_malloc=0 LSAN_OPTIONS=suppressions=fuzz/lsan.supp \
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "build-fuzz/fuzz/fuzz_$t" "$corpus" "${dict[@]}" -max_total_time="$seconds" \
    -max_len=262144 -rss_limit_mb=4096 -timeout=10 -artifact_prefix="fuzz/findings/$t-" -print_final_stats=1 \
    2>&1 | tee "fuzz/findings/$t.log" | grep -E '^(#[0-9]+ +(INITED|DONE)|stat::|==[0-9]+==|SUMMARY|artifact_prefix)'
  status=${PIPESTATUS[0]}
  set -e
  if [[ $status -ne 0 ]]; then
    echo "kiln: fuzz_$t stopped with status $status: see fuzz/findings/$t.log" >&2
    failed=1
  fi
done
exit "$failed"
