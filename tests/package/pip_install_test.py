"""pip install of the repository into a fresh venv of a second Python (the newest pyenv version
>= 3.9 other than /usr/bin/python3's, or KILN_TEST_PYTHON; /usr/bin/python3 itself when there is
none), linking the installed C++ package (KILN_PREBUILT_DIR) so that only the module compiles.
In the venv: import kiln from its site-packages (type stubs included), render the Cornell box to
an EXR whose pixel the returned array matches, with a working space (the colour module and config
must come from the package), and the same render through `python -m kiln render` and the `kiln`
script. The sdist holds every tracked file a build from source needs. Exits 77 (skipped) when
pip cannot reach its index.
Usage: pip_install_test.py SOURCE_DIR PREFIX WORK_DIR"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile

import numpy as np
import OpenImageIO as oiio

SKIPPED = 77
SIZE = ["--width", "64", "--height", "48", "--spp", "2", "--working-space", "ACEScg"]


def second_interpreter():
    """The newest pyenv interpreter >= 3.9 whose version differs from this one's, or None."""
    if os.environ.get("KILN_TEST_PYTHON"):
        return os.environ["KILN_TEST_PYTHON"]
    found = []
    for root in {os.environ.get("PYENV_ROOT", ""), os.path.expanduser("~/.pyenv")} - {""}:
        for path in glob.glob(os.path.join(root, "versions", "*", "bin", "python3")):
            match = re.fullmatch(r"(\d+)\.(\d+)\.(\d+)", os.path.basename(os.path.dirname(os.path.dirname(path))))
            if match:
                version = tuple(int(part) for part in match.groups())
                if version[:2] >= (3, 9) and version[:2] != sys.version_info[:2]:
                    found.append((version, path))
    return max(found)[1] if found else None


def run(args, **kwargs):
    print("+", " ".join(args), flush=True)
    return subprocess.run(args, text=True, **kwargs)


def exr_pixels(path):
    """Every channel of the EXR's first part, float32 (height, width, channels), and their names."""
    image = oiio.ImageBuf(path)
    assert not image.has_error, image.geterror()
    return image.get_pixels(oiio.FLOAT), list(image.spec().channelnames)


def check_sdist(python, source, work, env):
    """The sdist (scikit-build-core's, as `python -m build --sdist` makes it) against git's list."""
    tracked = run(["git", "-C", source, "ls-files", "CMakeLists.txt", "pyproject.toml", "renderer", "share",
                   "third_party_cmake"], capture_output=True)
    if tracked.returncode != 0:
        print("sdist contents not checked: the source is not a git checkout")
        return
    assert run([python, "-m", "pip", "install", "-q", "scikit-build-core"], env=env).returncode == 0
    built = run([python, "-c", "import sys, scikit_build_core.build as b; print(b.build_sdist(sys.argv[1]))", work],
                cwd=source, env=env, capture_output=True)
    assert built.returncode == 0, built.stderr
    with tarfile.open(os.path.join(work, built.stdout.split()[-1])) as sdist:
        names = {name.split("/", 1)[1] for name in sdist.getnames() if "/" in name}
    missing = [path for path in tracked.stdout.split() if path not in names]
    assert not missing, f"the sdist lacks {missing[:10]}"
    assert not [name for name in names if name.startswith(("build/", "tests/"))], "the sdist holds build or test files"
    print(f"sdist: {len(names)} entries, every tracked build file among them")


def main():
    source, prefix, work = (os.path.abspath(arg) for arg in sys.argv[1:4])
    interpreter = second_interpreter()
    if interpreter is None:
        interpreter = sys.executable
        print(f"no second interpreter (no pyenv version >= 3.9 but {sys.version.split()[0]}): "
              f"testing {interpreter} in a fresh venv")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    venv = os.path.join(work, "venv")
    assert run([interpreter, "-m", "venv", venv]).returncode == 0
    python = os.path.join(venv, "bin", "python")
    env = {key: value for key, value in os.environ.items() if key not in ("PYTHONPATH", "PYTHONHOME")}
    env["CMAKE_BUILD_PARALLEL_LEVEL"] = "2"

    reach = run([python, "-m", "pip", "download", "-q", "--no-deps", "-d", os.path.join(work, "probe"),
                 "scikit-build-core"], env=env, capture_output=True)
    if reach.returncode != 0:
        print("SKIPPED: pip cannot download the build backend from its index:", reach.stderr.strip()[-300:])
        return SKIPPED

    install = run([python, "-m", "pip", "install", f"--config-settings=cmake.define.KILN_PREBUILT_DIR={prefix}",
                   f"--config-settings=build-dir={os.path.join(work, 'build')}", source], env=env)
    assert install.returncode == 0, "pip install failed"

    scene = os.path.join(source, "scenes", "cornell_box.gltf")
    first = os.path.join(work, "module.exr")
    probe = f"""
import json, sys, sysconfig
import kiln
r = kiln.render({scene!r}, output={first!r}, width=64, height=48, spp=2, working_space="ACEScg")
mapped = sorted({{line.split()[-1] for line in open("/proc/self/maps") if "kiln_colour" in line}})
print(json.dumps({{"file": kiln.__file__, "site": sysconfig.get_paths()["purelib"], "mapped": mapped,
                  "config": r.metadata["kiln/ocio_config_file"], "pixel": r["beauty"][24, 32].tolist(),
                  "version": list(sys.version_info[:2])}}))
"""
    result = run([python, "-c", probe], env=env, cwd=work, capture_output=True)
    assert result.returncode == 0, result.stderr
    seen = json.loads(result.stdout.splitlines()[-1])
    package = os.path.join(seen["site"], "kiln")
    print(f"Python {seen['version']}: kiln from {seen['file']}")
    assert seen["file"] == os.path.join(package, "__init__.py"), seen["file"]
    assert seen["mapped"] == [os.path.join(package, "lib", "kiln", "kiln_colour.so")], seen["mapped"]
    assert seen["config"] == os.path.join(package, "share", "kiln", "ocio", "kiln.ocio"), seen["config"]
    for typing in ("__init__.pyi", "py.typed"):
        assert os.path.isfile(os.path.join(package, typing)), f"the package lacks {typing}"
    pixels, names = exr_pixels(first)
    assert pixels.shape[:2] == (48, 64), pixels.shape
    rgba = pixels[24, 32, [names.index(channel) for channel in "RGBA"]]
    assert np.array_equal(rgba, np.float32(seen["pixel"])), (rgba, seen["pixel"])
    assert min(seen["pixel"][:3]) > 0.0 and seen["pixel"][3] == 1.0, seen["pixel"]

    second = os.path.join(work, "cli.exr")
    assert run([python, "-m", "kiln", "render", scene, "-o", second, "-q"] + SIZE, env=env).returncode == 0
    assert np.array_equal(exr_pixels(second)[0], pixels), "python -m kiln render differs from kiln.render"
    third = os.path.join(work, "script.exr")
    assert run([os.path.join(venv, "bin", "kiln"), "render", scene, "-o", third, "-q"] + SIZE, env=env).returncode == 0
    assert np.array_equal(exr_pixels(third)[0], pixels), "the kiln script differs from kiln.render"
    refused = run([python, "-m", "kiln", "render", os.path.join(work, "missing.gltf"), "-o", second], env=env,
                  capture_output=True)
    assert refused.returncode == 2 and "missing.gltf" in refused.stderr, (refused.returncode, refused.stderr)

    check_sdist(python, source, work, env)
    return 0


if __name__ == "__main__":
    sys.exit(main())
