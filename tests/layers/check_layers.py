#!/usr/bin/env python3
"""Checks that the renderer's libraries include only the layers below them.

Data flows one way (docs/architecture.md): loader -> Scene -> accelerator -> shading -> film ->
EXR. Each unit below is a folder of renderer/; a unit may include itself and the units listed for
it, nothing else. Tests (*_test.cpp) may reach across layers and are not checked.

usage: check_layers.py REPO_ROOT [--graph]   (--graph prints the include graph as found)
"""
import pathlib
import re
import sys

# unit -> units it may include. Keep in step with docs/architecture.md's layering list.
ALLOWED = {
    "core": set(),
    "scene": {"core"},
    "geometry": {"core", "scene"},
    "accel": {"core", "scene", "geometry"},
    "shade": {"core", "scene", "geometry", "accel"},
    "render": {"core", "scene", "geometry", "accel", "shade"},
    "io/file": {"core"},
    "io/plugin": {"core", "io/file"},
    "io/colour": {"core", "io/file", "io/plugin"},
    "io/image_codecs": {"core", "scene", "io/file", "io/exr", "io/plugin", "io/colour"},
    "io/gltf": {"core", "scene", "geometry", "io/file", "io/image_codecs"},
    "io/exr": {"core", "scene", "render", "io/file", "io/image_codecs", "io/colour"},
    "job": {"core", "scene", "geometry", "accel", "shade", "render", "io/file", "io/image_codecs",
            "io/gltf", "io/exr", "io/colour"},
    "ray_replay": {"core", "scene", "geometry", "accel", "shade", "render"},
    "python": {"core", "scene", "render", "io/exr", "job"},
    "app": {"core", "scene", "geometry", "accel", "shade", "render", "io/file", "io/image_codecs",
            "io/gltf", "io/exr", "job", "ray_replay"},
    "package": set(),  # the CMake package's configuration: no sources
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def unit_of(path: str):
    """The unit a renderer-relative path belongs to: the longest matching prefix."""
    best = None
    for unit in ALLOWED:
        if path == unit or path.startswith(unit + "/"):
            if best is None or len(unit) > len(best):
                best = unit
    return best


def include_graph(root: pathlib.Path):
    """{(from_unit, to_unit): [file, ...]} over the renderer's non-test sources."""
    renderer = root / "renderer"
    graph = {}
    for source in sorted(renderer.rglob("*")):
        if source.suffix not in (".h", ".cpp") or source.name.endswith("_test.cpp"):
            continue
        rel = source.relative_to(renderer).as_posix()
        here = unit_of(rel)
        if here is None:
            continue
        for target in INCLUDE.findall(source.read_text(encoding="utf-8")):
            there = unit_of(target)
            if there is not None and there != here:
                graph.setdefault((here, there), []).append(rel)
    return graph


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    graph = include_graph(root)
    if "--graph" in sys.argv:
        for (a, b), files in sorted(graph.items()):
            print(f"{a} -> {b} ({len(files)} files)")
        return 0
    bad = [(a, b, files) for (a, b), files in sorted(graph.items()) if b not in ALLOWED[a]]
    for a, b, files in bad:
        print(f"layering: {a} must not include {b}: {', '.join(files)}")
    unknown = [p.relative_to(root / "renderer").as_posix() for p in (root / "renderer").iterdir()
               if p.is_dir() and p.name != "io" and unit_of(p.name) is None]
    for name in unknown:
        print(f"layering: renderer/{name} is in no layer; add it to ALLOWED")
    if not graph:
        print("layering: no includes found; wrong root?")
        return 1
    return 1 if bad or unknown else 0


if __name__ == "__main__":
    sys.exit(main())
