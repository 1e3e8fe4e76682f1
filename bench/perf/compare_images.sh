#!/bin/bash
# Renders every scene with two kiln builds (default AOVs: RGBA, Z, N) and reports, per scene, the
# pixels that differ at all (idiff -fail 0) and the largest difference.
# usage: bench/perf/compare_images.sh BEFORE_KILN AFTER_KILN   (from the repository root)
set -u
B=$1 A=$2; out=$(mktemp -d); S=../shared/assets
list=(scenes/cornell_box.gltf scenes/glass_showcase.gltf scenes/quadric_showcase.gltf
      $S/ToyCar/glTF/ToyCar.gltf $S/DamagedHelmet/glTF-Binary/DamagedHelmet.glb $S/TransmissionTest/glTF-Binary/TransmissionTest.glb
      $S/AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb $S/2CylinderEngine/glTF-Binary/2CylinderEngine.glb
      $S/NegativeScaleTest/glTF-Binary/NegativeScaleTest.glb $S/SimpleInstancing/glTF-Binary/SimpleInstancing.glb
      $S/Suzanne/glTF/Suzanne.gltf $S/GlassVaseFlowers/glTF-Binary/GlassVaseFlowers.glb)
for f in "${list[@]}"; do
  [ -f "$f" ] || continue
  $B render "$f" -o $out/b.exr --width 480 --height 360 --spp 4 --threads 2 -q --aovs beauty,Z,N,P,id 2>/dev/null
  $A render "$f" -o $out/a.exr --width 480 --height 360 --spp 4 --threads 2 -q --aovs beauty,Z,N,P,id 2>/dev/null
  r=$(idiff -fail 0 -warn 0 $out/b.exr $out/a.exr 2>&1)
  if echo "$r" | grep -q PASS; then echo "$(basename $f): identical"
  else echo "$(basename $f): $(echo "$r" | grep -E 'Max error|pixels' | tr -s ' ' | tr '\n' ';')"; fi
done
rm -rf "$out"
