"""The Python module against the CLI: the arrays of kiln.render equal the EXR `kiln render` writes
for the same options, bit for bit; output= writes that EXR; bad options and bad assets raise
kiln.InputError with the CLI's one-line message; Ctrl-C (SIGINT) and a progress callback that
raises stop a render early; threads writing one path each leave a complete file. Run by CTest with
PYTHONPATH at the build's module."""
import ast
import base64
import importlib.util
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
import warnings

import numpy as np
import OpenImageIO as oiio
import pytest

import kiln

SOURCE = os.environ.get("KILN_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
KILN = os.environ.get("KILN_BINARY", os.path.join(SOURCE, "build", "renderer", "app", "kiln"))
CORNELL = os.path.join(SOURCE, "scenes", "cornell_box.gltf")
GLASS = os.path.join(SOURCE, "scenes", "glass_showcase.gltf")
LOBES = os.path.join(SOURCE, "scenes", "lobe_showcase.gltf")


def cli(args):
    return subprocess.run([KILN] + args, capture_output=True, text=True)


def read_channels(path):
    """Every channel of every part of an EXR as float32 (height, width) arrays, by full name."""
    channels = {}
    image = oiio.ImageInput.open(path)
    part = 0
    while image.seek_subimage(part, 0):
        spec = image.spec()
        pixels = image.read_image(part, 0, 0, spec.nchannels, oiio.FLOAT)
        for c, name in enumerate(spec.channelnames):
            channels[name] = pixels[:, :, c]
        part += 1
    image.close()
    return channels


def assert_arrays_match_exr(result, path):
    stored = read_channels(path)
    compared = 0
    for aov, array in result.aovs.items():
        assert array.dtype == np.float32
        assert array.shape[:2] == (result.stats["height"], result.stats["width"])
        for c, name in enumerate(result.channels[aov]):
            assert name in stored, name
            # Bit for bit: the same float32 values, NaN-free by construction.
            assert np.array_equal(array[:, :, c].view(np.uint32), stored[name].view(np.uint32)), (aov, name)
            compared += 1
    assert compared == len(stored)


OPTIONS = {"width": 40, "height": 30, "spp": 2, "threads": 2,
           "aovs": ["beauty", "Z", "N", "P", "albedo", "uv", "id", "direct", "reflection", "refraction",
                    "cryptomatte", "lightgroups", "albedo_filtered", "N_filtered", "diffuse", "specular",
                    "shadow", "emission"]}
ARGUMENTS = ["--width", "40", "--height", "30", "--spp", "2", "--threads", "2", "--aovs",
             "beauty,Z,N,P,albedo,uv,id,direct,reflection,refraction,cryptomatte,lightgroups,"
             "albedo_filtered,N_filtered,diffuse,specular,shadow,emission"]


@pytest.mark.parametrize("extra,arguments", [({}, []), ({"float": True}, ["--float"]),
                                             ({"multipart": True, "filter": "gaussian"},
                                              ["--multipart", "--filter", "gaussian"])])
def test_arrays_equal_the_cli_exr_bit_for_bit(tmp_path, extra, arguments):
    out = str(tmp_path / "cli.exr")
    done = cli(["render", GLASS, "-o", out, "-q"] + ARGUMENTS + arguments)
    assert done.returncode == 0, done.stderr
    result = kiln.render(GLASS, **OPTIONS, **extra)
    assert result.aovs["beauty"].shape == (30, 40, 4)
    assert result.aovs["Z"].shape == (30, 40, 1)
    assert np.count_nonzero(result.aovs["beauty"][:, :, 3]) > 100  # the scene is in the picture
    assert_arrays_match_exr(result, out)
    assert result.metadata["kiln/samples_per_pixel"] == 2  # numbers as numbers, as the EXR holds them
    assert result.metadata["kiln/fps"] == 24.0 and result.metadata["kiln/frame_start"] == 1
    assert result.metadata["kiln/settings_hash"] == oiio.ImageInput.open(out).spec().get_string_attribute(
        "kiln/settings_hash")
    assert result.stats["camera_rays"] == 40 * 30 * 2


def test_material_extension_lobes_render_from_python_as_from_the_cli(tmp_path):
    # Clearcoat, sheen, iridescence, anisotropy, dispersion, specular and diffuse transmission.
    out = str(tmp_path / "cli.exr")
    done = cli(["render", LOBES, "-o", out, "-q"] + ARGUMENTS)
    assert done.returncode == 0, done.stderr
    result = kiln.render(LOBES, **OPTIONS)
    assert np.count_nonzero(result.aovs["beauty"][:, :, 3]) > 600  # the spheres and the ground
    assert_arrays_match_exr(result, out)


def test_light_groups_are_arrays_that_sum_to_the_beauty():
    result = kiln.render(CORNELL, width=32, height=24, spp=2, float=True, aovs="beauty,lightgroups")
    groups = sorted(name for name in result.aovs if name.startswith("lightgroup_"))
    assert groups == ["lightgroup_ceiling_light", "lightgroup_emission", "lightgroup_environment",
                      "lightgroup_fill_light"]
    total = sum(result.aovs[name] for name in groups)
    beauty = result.aovs["beauty"][:, :, :3]
    assert beauty.max() > 0.1
    assert np.abs(total - beauty).max() <= 1e-5 * max(1.0, beauty.max())


def test_render_layers_from_python_match_the_cli(tmp_path):
    out = str(tmp_path / "layer.exr")
    done = cli(["render", CORNELL, "-o", out, "-q", "--width", "32", "--height", "24", "--only", "*wall*"])
    assert done.returncode == 0, done.stderr
    result = kiln.render(CORNELL, width=32, height=24, only="*wall*")
    assert_arrays_match_exr(result, out)
    alpha = result.aovs["beauty"][:, :, 3]
    assert np.count_nonzero(alpha == 0) > 50 and np.count_nonzero(alpha == 1) > 50  # floor held out, walls kept
    with pytest.raises(kiln.InputError, match="--holdout"):
        kiln.render(CORNELL, width=8, height=6, holdout="no_such_node")


def test_a_render_layer_selects_a_node_and_its_subtree():
    group = kiln.render(CORNELL, width=32, height=24, spp=1, only="objects")
    listed = kiln.render(CORNELL, width=32, height=24, spp=1,
                         only=["glass_column", "blue_ball", "yellow_ring", "orange_cone"])
    assert np.array_equal(group.aovs["beauty"], listed.aovs["beauty"])
    assert np.count_nonzero(group.aovs["beauty"][:, :, 3]) > 50
    with pytest.raises(kiln.InputError, match="did you mean 'objects'"):
        kiln.render(CORNELL, width=8, height=6, only="objets")


def test_denoiser_and_relighting_passes_are_arrays():
    result = kiln.render(CORNELL, width=32, height=24, spp=2, float=True, filter="blackman-harris",
                         aovs="beauty,direct,albedo_filtered,N_filtered,diffuse,specular,shadow")
    for name in ("albedo_filtered", "N_filtered", "diffuse", "specular"):
        assert result.aovs[name].shape == (24, 32, 3), name
    assert result.channels["N_filtered"] == ["N_filtered.X", "N_filtered.Y", "N_filtered.Z"]
    mattes = sorted(name for name in result.aovs if name.startswith("shadow_"))
    assert mattes == ["shadow_ceiling_light", "shadow_environment", "shadow_fill_light"]
    for name in mattes:
        matte = result.aovs[name]
        assert matte.shape == (24, 32, 1) and result.channels[name] == [name + ".A"]
        assert matte.min() >= 0.0 and matte.max() <= 1.0
    # The box's walls shadow parts of the room from the fill light, never all of it.
    assert 0.0 < result.aovs["shadow_fill_light"].mean() < 1.0
    albedo = result.aovs["albedo_filtered"]
    assert albedo.min() >= 0.0 and albedo.max() <= 1.0 and albedo.max() > 0.5
    # The room is closed and nothing in it glows: the direct term is the two lobes.
    lobes = result.aovs["diffuse"] + result.aovs["specular"]
    direct = result.aovs["direct"]
    assert direct.max() > 0.1
    assert np.abs(lobes - direct).max() <= 1e-5 * max(1.0, direct.max())


def test_output_writes_the_exr_the_cli_writes(tmp_path):
    out = str(tmp_path / "python.exr")
    result = kiln.render(CORNELL, output=out, width=32, height=24, look_from=(0.0, 1.0, 3.5),
                         look_at=[0, 1, 0], background="0.1,0.2,0.3", show_background=True)
    assert_arrays_match_exr(result, out)
    again = str(tmp_path / "again.exr")
    result.write(again)
    assert_arrays_match_exr(result, again)
    spec = oiio.ImageInput.open(out).spec()
    assert spec.get_string_attribute("kiln/camera") == "look-at"
    assert spec.get_string_attribute("kiln/command_line").startswith("kiln.render(")
    matrix = spec.getattribute("worldToCamera")
    assert list(np.array(matrix, dtype=np.float32).ravel()) == result.metadata["worldToCamera"]


def cli_message(args):
    done = cli(args)
    assert done.returncode == 2, done.stderr
    line = done.stderr.strip()
    assert line.startswith("kiln: ")
    return line[len("kiln: "):]


def test_bad_options_raise_with_the_cli_message(tmp_path):
    out = str(tmp_path / "x.exr")
    for keywords, arguments in [({"spp": 0}, ["--spp", "0"]), ({"accel": "octree"}, ["--accel", "octree"]),
                                ({"fov": float("nan")}, ["--look-from", "0,0,1", "--look-at", "0,0,0",
                                                         "--fov", "nan"])]:
        expected = cli_message(["render", CORNELL, "-o", out] + arguments).split(" (run 'kiln")[0]
        with pytest.raises(kiln.InputError) as caught:
            kiln.render(CORNELL, **keywords)
        assert str(caught.value) == expected
        assert isinstance(caught.value, ValueError)
    with pytest.raises(TypeError, match=r"^render\(\) got an unexpected keyword argument 'no_such_option' "
                                        r"\(kiln.options\(\) lists the options\)$"):
        kiln.render(CORNELL, no_such_option=1)
    assert not os.path.exists(out)


def test_a_misspelled_keyword_is_a_type_error_with_the_clis_suggestion(tmp_path):
    out = str(tmp_path / "x.exr")
    for typo, meant in [("sp", "spp"), ("widht", "width"), ("look_form", "look_from"), ("thread", "threads")]:
        dashed = "--" + typo.replace("_", "-")
        line = cli_message(["render", CORNELL, "-o", out, dashed, "1"])
        assert line.startswith("unknown option %s; did you mean --%s?" % (dashed, meant.replace("_", "-"))), line
        for call in (kiln.render, kiln.render_sequence, kiln.info):
            with pytest.raises(TypeError) as caught:
                call(CORNELL, **{typo: 1})
            assert str(caught.value) == "%s() got an unexpected keyword argument '%s'; did you mean '%s'?" % (
                call.__name__, typo, meant)
    assert not os.path.exists(out)


def test_bad_assets_raise_with_the_file_and_json_pointer(tmp_path):
    bad = tmp_path / "bad.gltf"
    bad.write_text('{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 7}}]}],'
                   ' "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}')
    expected = cli_message(["render", str(bad), "-o", str(tmp_path / "x.exr")])
    with pytest.raises(kiln.InputError) as caught:
        kiln.render(str(bad))
    assert str(caught.value) == expected
    assert caught.value.file == str(bad)
    assert caught.value.location == "/meshes/0/primitives/0/attributes/POSITION"
    assert "/accessors/7 does not exist" in caught.value.reason
    with pytest.raises(kiln.InputError):
        kiln.render(str(tmp_path / "missing.gltf"))


def test_ctrl_c_cancels_a_render():
    started = time.monotonic()
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        # Minutes of work when left to finish.
        kiln.render(GLASS, width=1600, height=1200, spp=64, threads=2)
    assert time.monotonic() - started < 30


def test_a_time_limit_stops_a_render(tmp_path):
    out = str(tmp_path / "x.exr")
    started = time.monotonic()
    with pytest.raises(kiln.TimeLimitError, match="time limit of 0.5 s reached, nothing written"):
        kiln.render(GLASS, output=out, width=1600, height=1200, spp=64, threads=2, time_limit=0.5)
    assert time.monotonic() - started < 30
    assert not os.path.exists(out)


def test_a_progress_callback_that_raises_cancels_the_render():
    calls = []

    # Calls come every 50 ms once the render has begun (none while the scene loads).
    def progress(done, total):
        calls.append((done, total))
        if sum(1 for _, t in calls if t > 0) >= 3:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        kiln.render(GLASS, width=1600, height=1200, spp=64, threads=2, progress=progress)
    assert calls[-1][1] == 1600 * 1200
    assert all(total == 1600 * 1200 for _, total in calls)


def readme_script():
    """The README's first Python script, exactly as the README shows it."""
    with open(os.path.join(SOURCE, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    match = re.search(r"<!-- tests/python/test_kiln_module\.py runs this block -->\n```python\n(.*?)```", readme, re.S)
    assert match, "README.md has no tested first Python script"
    return match.group(1)


def test_the_readmes_first_script_runs_as_written(tmp_path, monkeypatch, capsys):
    code = readme_script()
    assert len(code.strip().splitlines()) <= 12  # a first script, not a program
    os.symlink(os.path.join(os.path.abspath(SOURCE), "scenes"), tmp_path / "scenes")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(code, "README.md", "exec"), namespace)
    assert namespace["r"].aovs["beauty"].shape == (240, 320, 4)
    assert (tmp_path / "out.exr").is_file() and (tmp_path / "out.png").is_file()
    moves = sorted(p.name for p in tmp_path.glob("move.*.exr"))
    assert moves == ["move.%04d.exr" % i for i in range(8)]
    printed = [float(line) for line in capsys.readouterr().out.split()]
    assert printed and printed[-1] == 1.0 and printed == sorted(printed)


def test_the_readmes_progress_callback_works_and_ends_at_100_percent(capsys):
    # The README's own callback, exactly: no (0, 0) call while the scene loads.
    assert "progress=lambda done, total: print(done / total)" in readme_script()
    kiln.render(GLASS, width=400, height=300, spp=4, threads=2, progress=lambda done, total: print(done / total))
    printed = [float(line) for line in capsys.readouterr().out.split()]
    assert printed and printed[-1] == 1.0
    assert all(0.0 <= f <= 1.0 for f in printed) and printed == sorted(printed)
    calls = []
    kiln.render(CORNELL, width=8, height=6, spp=1, progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (48, 48) and all(total == 48 for _, total in calls)
    frames = []
    kiln.render_sequence(CORNELL, turntable=2, width=8, height=6, spp=1,
                         progress=lambda done, total: frames.append((done, total)))
    assert frames and frames[-1] == (48, 48) and all(total == 48 for _, total in frames)


def triangle_gltf(path, extensions_used=()):
    """One triangle and no lights (a data-URI buffer); extensions_used are listed as optional."""
    positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)
    uri = "data:application/octet-stream;base64," + base64.b64encode(positions.tobytes()).decode()
    document = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "scene": 0,
                "nodes": [{"mesh": 0, "name": "tri"}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
                "buffers": [{"byteLength": 36, "uri": uri}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
                "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                               "min": [0, 0, 0], "max": [1, 1, 0]}]}
    if extensions_used:
        document["extensionsUsed"] = list(extensions_used)
    path.write_text(json.dumps(document))
    return str(path)


def test_warnings_are_kiln_warnings_and_result_warnings_as_the_cli_prints_them(tmp_path):
    asset = triangle_gltf(tmp_path / "tri.gltf", ["EXT_made_up"])
    view = dict(width=8, height=8, spp=1, lighting="headlight")
    done = cli(["render", asset, "-o", str(tmp_path / "x.exr"), "--width", "8", "--height", "8",
                "--lighting", "headlight", "--tile", "0/1"])
    assert done.returncode == 0, done.stderr
    printed = [line[len("kiln: "):].replace("warning: ", "", 1) for line in done.stderr.splitlines()
               if not line.startswith("kiln: 8x8")]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = kiln.render(asset, tile="0/1", **view)
    assert [w.category for w in caught] == [kiln.KilnWarning] * len(caught)
    assert [str(w.message) for w in caught] == result.warnings
    # The CLI's lines, the deprecated name's in Python's words.
    assert result.warnings == [line.replace("--tile is deprecated; use --band", "tile= is deprecated; use band=")
                               for line in printed]
    assert "extension EXT_made_up is not supported; it is ignored" in result.warnings
    assert "the file has no lights; using a headlight at the camera" in result.warnings
    assert issubclass(kiln.KilnWarning, UserWarning)
    with warnings.catch_warnings():
        warnings.simplefilter("error", kiln.KilnWarning)
        with pytest.raises(kiln.KilnWarning, match="EXT_made_up"):
            kiln.render(asset, **view)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert kiln.render(CORNELL, width=8, height=6, spp=1).warnings == []
    assert caught == []


def test_texture_cache_mb_is_accepted_with_a_deprecation_warning():
    assert "texture_cache_mb" not in [option["name"] for option in kiln.options()]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = kiln.render(CORNELL, width=8, height=6, spp=1, texture_cache_mb=64)
    assert result.warnings == ["texture_cache_mb= does nothing (kiln keeps every texture's mip pyramid in memory) "
                               "and will be removed; drop it"]
    assert [w.category for w in caught] == [kiln.KilnWarning]


def test_view_without_a_preview_is_a_kiln_warning(tmp_path):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = kiln.render(CORNELL, width=8, height=6, spp=1, view="Raw")
    assert result.warnings == ["--view does nothing without --preview"]
    assert [(w.category, str(w.message)) for w in caught] == [(kiln.KilnWarning, result.warnings[0])]
    preview = tmp_path / "p.png"
    assert kiln.render(CORNELL, output=str(tmp_path / "p.exr"), width=8, height=6, spp=1, view="Raw",
                       preview=str(preview)).warnings == []
    assert preview.exists()
    # A preview is written beside the EXR: without output= there is neither, and it says so.
    with pytest.warns(kiln.KilnWarning, match="--preview does nothing without an output"):
        result = kiln.render(CORNELL, width=8, height=6, spp=1, preview=str(tmp_path / "q.png"))
    assert result.warnings == ["--preview does nothing without an output (output=; Result.write writes both)"]
    assert not (tmp_path / "q.png").exists()


def test_info_is_the_clis_json_document(tmp_path):
    done = subprocess.run([KILN, "info", "--json", CORNELL, "--width", "40", "-q"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    expected = json.loads(done.stdout)
    info = kiln.info(CORNELL, width=40)
    for timing in ("load_seconds", "render_seconds_one_thread"):
        assert info["render"].pop(timing) > 0
        expected["render"].pop(timing)
    assert info == expected
    assert [light["name"] for light in info["lights"]] == ["ceiling_light", "fill_light"]
    assert info["render"]["width"] == 40
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        made_up = kiln.info(triangle_gltf(tmp_path / "tri.gltf", ["EXT_made_up"]))
    assert made_up["extensions"] == [{"name": "EXT_made_up", "required": False, "support": "ignored"}]
    assert made_up["geometry"]["triangles"] == 1 and made_up["nodes"][0]["name"] == "tri"
    assert "extension EXT_made_up is not supported; it is ignored" in [str(w.message) for w in caught]
    with pytest.raises(kiln.InputError, match="cannot open file"):
        kiln.info(str(tmp_path / "missing.gltf"))


def load_stub_tool():
    spec = importlib.util.spec_from_file_location("make_python_stub",
                                                  os.path.join(SOURCE, "tools", "make_python_stub.py"))
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    return tool


def test_help_and_the_type_stub_list_every_option_with_its_type_and_help():
    options = kiln.options()
    for option in options:
        assert "\n    %s: " % option["name"] in kiln.render.__doc__, option["name"]
        assert option["help"] in kiln.render.__doc__, option["name"]
    tool = load_stub_tool()
    with open(tool.DEFAULT_STUB) as f:
        committed = f.read()
    # The committed stub's options are what the tool makes of this module: it cannot drift from the table.
    assert committed == tool.updated(committed, kiln), "run tools/make_python_stub.py"
    tree = ast.parse(committed)
    classes = {node.name: node for node in tree.body if isinstance(node, ast.ClassDef)}
    body = classes["RenderOptions"].body
    fields = {node.target.id: (ast.unparse(node.annotation), body[i + 1].value.value)
              for i, node in enumerate(body) if isinstance(node, ast.AnnAssign)}
    assert list(fields) == [o["name"] for o in options]
    expected_types = {"int": "Optional[int]", "float": "Optional[float]", "bool": "Optional[bool]"}
    for option in options:
        annotation, doc = fields[option["name"]]
        assert doc.startswith("%s: %s" % (option["option"], option["help"])), option["name"]
        if option["choices"]:
            assert all(repr(choice) in annotation for choice in option["choices"]), annotation
        else:
            assert annotation == expected_types.get(option["type"], "Optional[_Text]"), option["name"]
    functions = {node.name: node for node in tree.body if isinstance(node, ast.FunctionDef)}
    for name in ("render", "render_sequence", "info"):
        assert ast.unparse(functions[name].args.kwarg.annotation) == "Unpack[RenderOptions]", name


def test_options_are_the_clis():
    names = {o["option"] for o in kiln.options()}
    help_text = cli(["render", "--help"]).stdout
    for name in names:
        if name != "--quiet":
            assert name in help_text, name
    assert {"--spp", "--aovs", "--band", "--look-from"} <= names
    spp = next(o for o in kiln.options() if o["name"] == "spp")
    assert spp["type"] == "int" and spp["default"] == "16"


CESIUM_MAN = os.path.join(SOURCE, "..", "shared", "assets", "CesiumMan", "glTF-Binary", "CesiumMan.glb")


@pytest.mark.skipif(not os.path.exists(CESIUM_MAN), reason="no shared sample assets")
def test_time_keywords_pose_the_scene_as_the_cli_does(tmp_path):
    view = dict(width=24, height=24, quiet=True)
    walk = kiln.render(CESIUM_MAN, time=0.5, **view)
    # Frame 13 at 24 fps from frame 1 is t = 0.5 s: the same image, bit for bit.
    frame = kiln.render(CESIUM_MAN, frame=13, fps=24, frame_start=1, animation="0", **view)
    rest = kiln.render(CESIUM_MAN, animation="none", **view)
    assert np.array_equal(walk.aovs["beauty"], frame.aovs["beauty"])
    assert not np.array_equal(walk.aovs["beauty"], rest.aovs["beauty"])
    out = str(tmp_path / "walk.exr")
    args = ["render", CESIUM_MAN, "-o", out, "--time", "0.5", "--width", "24", "--height", "24", "-q"]
    assert cli(args).returncode == 0
    assert np.array_equal(read_channels(out)["R"], walk.aovs["beauty"][:, :, 0])
    with pytest.raises(kiln.InputError, match="no animation 'walk'"):
        kiln.render(CESIUM_MAN, animation="walk", **view)


@pytest.mark.skipif(not os.path.exists(CESIUM_MAN), reason="no shared sample assets")
def test_render_sequence_returns_and_writes_each_frame_as_the_cli_does(tmp_path):
    view = dict(width=24, height=24, quiet=True)
    pattern = str(tmp_path / "walk.####.exr")
    frames = kiln.render_sequence(CESIUM_MAN, frames="1-13:6", output=pattern, **view)
    assert [f.metadata["kiln/frame"] for f in frames] == [1, 7, 13]
    assert [f.metadata["timeCode"] for f in frames] == ["00:00:00:00", "00:00:00:06", "00:00:00:12"]
    # Frame 13 of the sequence is kiln.render(frame=13), and the file it wrote holds it.
    alone = kiln.render(CESIUM_MAN, frame=13, **view)
    assert np.array_equal(frames[2].aovs["beauty"], alone.aovs["beauty"])
    assert not np.array_equal(frames[0].aovs["beauty"], frames[2].aovs["beauty"])
    assert np.array_equal(read_channels(str(tmp_path / "walk.0013.exr"))["R"], alone.aovs["beauty"][:, :, 0])
    with pytest.raises(kiln.InputError, match="frames"):
        kiln.render(CESIUM_MAN, frames="1-3", **view)
    with pytest.raises(kiln.InputError, match="no frame placeholder"):
        kiln.render_sequence(CESIUM_MAN, frames="1-3", output=str(tmp_path / "plain.exr"), **view)


def test_a_turntable_is_a_sequence_whose_frames_render_alone_as_the_cli_does(tmp_path):
    view = dict(width=16, height=12, spp=1, quiet=True)
    frames = kiln.render_sequence(CORNELL, turntable=3, turntable_elevation=30,
                                  output=str(tmp_path / "tt.####.exr"), **view)
    assert [f.metadata["kiln/frame"] for f in frames] == [1, 2, 3]
    assert frames[2].metadata["framesPerSecond"] == (24, 1) and frames[2].metadata["timeCode"] == "00:00:00:02"
    assert frames[1].metadata["kiln/camera"] == "turntable frame 2 of 3 (azimuth 120, elevation 30)"
    alone = kiln.render(CORNELL, turntable=3, turntable_elevation=30, frame=2, **view)
    assert np.array_equal(frames[1].aovs["beauty"], alone.aovs["beauty"])
    out = tmp_path / "cli.exr"
    assert cli(["render", CORNELL, "-o", str(out), "--turntable", "3", "--turntable-elevation", "30",
                "--frame", "2", "--width", "16", "--height", "12", "--spp", "1", "-q"]).returncode == 0
    assert np.array_equal(read_channels(str(out))["R"], alone.aovs["beauty"][:, :, 0])
    with pytest.raises(kiln.InputError, match="turntable"):
        kiln.render(CORNELL, turntable=3, **view)
    view_three_quarter = kiln.render(CORNELL, camera_view="three-quarter", **view)
    assert view_three_quarter.metadata["kiln/camera"] == "three-quarter view (azimuth 45, elevation 25)"


SHOE = os.path.join(SOURCE, "..", "shared", "assets", "MaterialsVariantsShoe", "glTF", "MaterialsVariantsShoe.gltf")


@pytest.mark.skipif(not os.path.exists(SHOE), reason="no shared sample assets")
def test_variant_keyword_recolours_as_the_cli_does(tmp_path):
    view = dict(width=24, height=24, quiet=True)
    beach = kiln.render(SHOE, variant="beach", **view)
    street = kiln.render(SHOE, variant=2, **view)
    assert beach.metadata["kiln/variant"] == "beach"
    assert np.array_equal(beach.aovs["beauty"][:, :, 3], street.aovs["beauty"][:, :, 3])  # one shape
    assert not np.array_equal(beach.aovs["beauty"], street.aovs["beauty"])  # two colourways
    out = str(tmp_path / "beach.exr")
    assert cli(["render", SHOE, "-o", out, "--variant", "beach", "--width", "24", "--height", "24", "-q"]).returncode == 0
    assert np.array_equal(read_channels(out)["R"], beach.aovs["beauty"][:, :, 0])
    with pytest.raises(kiln.InputError, match="no variant 'forest'"):
        kiln.render(SHOE, variant="forest", **view)


@pytest.mark.skipif(not os.path.exists(CESIUM_MAN), reason="no shared sample assets")
def test_motion_vectors_arrive_as_forward_and_backward_arrays_equal_to_the_exr(tmp_path):
    view = dict(width=32, height=32, quiet=True, frame=10, aovs=["beauty", "motion"])
    walk = kiln.render(CESIUM_MAN, **view)
    assert walk.channels["forward"] == ["forward.u", "forward.v"]
    assert walk.channels["backward"] == ["backward.u", "backward.v"]
    out = str(tmp_path / "walk.exr")
    assert cli(["render", CESIUM_MAN, "-o", out, "--frame", "10", "--aovs", "beauty,motion",
                "--width", "32", "--height", "32", "-q"]).returncode == 0
    assert_arrays_match_exr(walk, out)
    moving = walk.aovs["beauty"][:, :, 3] > 0
    assert np.abs(walk.aovs["forward"][moving]).max() > 0.1  # the figure walks
    assert not walk.aovs["forward"][~moving].any()  # background is 0


@pytest.mark.skipif(not os.path.exists(CESIUM_MAN), reason="no shared sample assets")
def test_motion_blur_takes_the_shutter_and_equals_the_cli(tmp_path):
    view = dict(width=32, height=32, quiet=True, frame=10, spp=4)
    sharp = kiln.render(CESIUM_MAN, **view)
    blurred = kiln.render(CESIUM_MAN, shutter="-0.5,0.5", **view)
    out = str(tmp_path / "blurred.exr")
    assert cli(["render", CESIUM_MAN, "-o", out, "--frame", "10", "--spp", "4", "--shutter", "-0.5,0.5",
                "--width", "32", "--height", "32", "-q"]).returncode == 0
    assert_arrays_match_exr(blurred, out)
    # The walking figure blurs.
    assert not np.array_equal(sharp.aovs["beauty"], blurred.aovs["beauty"])
    with pytest.raises(kiln.InputError, match="must open before it closes"):
        kiln.render(CESIUM_MAN, shutter="0.5,-0.5", **view)


def test_deep_writes_a_deep_file_beside_the_output(tmp_path):
    out = str(tmp_path / "python.exr")
    kiln.render(CORNELL, output=out, width=32, height=24, deep=True)
    spec = oiio.ImageInput.open(str(tmp_path / "python.deep.exr")).spec()
    assert spec.deep
    assert oiio.ImageInput.open(out).spec().get_string_attribute("kiln/deep") == "on"


def test_a_working_space_converts_like_the_cli_and_tags_the_exr(tmp_path):
    view = dict(width=32, height=24, spp=2, quiet=True)
    aces = kiln.render(CORNELL, working_space="ACEScg", **view)
    out = str(tmp_path / "aces.exr")
    assert cli(["render", CORNELL, "-o", out, "--width", "32", "--height", "24", "--spp", "2", "-q",
                "--working-space", "ACEScg"]).returncode == 0
    assert_arrays_match_exr(aces, out)
    assert oiio.ImageInput.open(out).spec().get_string_attribute("colorspace") == "ACEScg"
    # The Cornell box's coloured walls are other numbers in ACEScg.
    assert not np.array_equal(aces.aovs["beauty"], kiln.render(CORNELL, **view).aovs["beauty"])
    with pytest.raises(kiln.InputError, match="no-such-space"):
        kiln.render(CORNELL, working_space="no-such-space", **view)


def without_capture_date(data):
    """An EXR's bytes with its capDate value (the second it was written) blanked."""
    return re.sub(rb"(capDate\x00string\x00\x13\x00\x00\x00).{19}", rb"\1" + b"?" * 19, data, flags=re.DOTALL)


def test_threads_writing_one_path_each_succeed_and_leave_one_complete_result(tmp_path):
    """Each write has a temporary file of its own: four threads writing one path all succeed, and
    the file left is always exactly one of the complete results, byte for byte but for the date."""
    view = dict(width=160, height=120, quiet=True)
    results = [kiln.render(CORNELL, spp=1, **view), kiln.render(CORNELL, spp=2, **view)]
    expected = []
    for i, result in enumerate(results):
        result.write(str(tmp_path / f"alone{i}.exr"))
        expected.append(without_capture_date((tmp_path / f"alone{i}.exr").read_bytes()))
    assert expected[0] != expected[1]
    out = str(tmp_path / "shared.exr")
    for trial in range(10):
        errors = []

        def write(result):
            try:
                result.write(out)
            except Exception as e:  # noqa: BLE001 (collected for the assertion below)
                errors.append(str(e))

        threads = [threading.Thread(target=write, args=(results[t % 2],)) for t in range(4)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        assert errors == [], trial
        assert without_capture_date((tmp_path / "shared.exr").read_bytes()) in expected, trial
    assert sorted(os.listdir(tmp_path)) == ["alone0.exr", "alone1.exr", "shared.exr"]


def run_child(script, timeout=120):
    """Runs script in a fresh interpreter (kiln's first calls, a crash that would take pytest down)
    and returns its result; a hang fails the test at the deadline instead of stalling the suite."""
    try:
        return subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        pytest.fail(f"still running after {timeout} s (deadlocked?)")


FIRST_RENDERS = """
import sys, threading
import kiln
assert "numpy" not in sys.modules  # the first render imports it, under this test's threads
barrier = threading.Barrier(8)
results, errors = [None] * 8, []
def render(i):
    try:
        barrier.wait()
        results[i] = kiln.render(sys.argv[1], width=24, height=16, spp=2, threads=1).aovs["beauty"]
    except BaseException as e:
        errors.append(repr(e))
threads = [threading.Thread(target=render, args=(i,)) for i in range(8)]
for t in threads: t.start()
for t in threads: t.join()
assert not errors, errors
assert all((r == results[0]).all() for r in results)
print("rendered", len(results))
"""


def test_first_renders_from_many_threads_at_once_do_not_deadlock():
    # Eight threads reach kiln's first NumPy arrays together: each run used to hang (one thread
    # in pybind11's NumPy initialiser, holding the GIL the other's numpy import waited for).
    for _ in range(3):
        done = run_child(FIRST_RENDERS.replace("sys.argv[1]", repr(CORNELL)), timeout=60)
        assert done.returncode == 0, done.stderr
        assert done.stdout.strip() == "rendered 8"


def test_concurrent_renders_equal_renders_one_at_a_time():
    jobs = [(CORNELL, dict(width=24, height=16, spp=2)), (GLASS, dict(width=20, height=20, spp=1)),
            (CORNELL, dict(width=16, height=16, spp=1, aovs=["beauty", "Z", "N"])),
            (GLASS, dict(width=24, height=12, spp=2, working_space="ACEScg"))] * 3
    alone = [kiln.render(asset, threads=1, **options) for asset, options in jobs]
    together = [None] * len(jobs)

    def render(i):
        asset, options = jobs[i]
        together[i] = kiln.render(asset, threads=2, **options)

    threads = [threading.Thread(target=render, args=(i,)) for i in range(len(jobs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
        assert not t.is_alive()
    for a, b in zip(alone, together):
        assert a.aovs.keys() == b.aovs.keys()
        for name in a.aovs:
            assert np.array_equal(a.aovs[name], b.aovs[name]), name


def test_a_looping_ocio_config_raises_input_error_not_a_crash(tmp_path):
    # ACEScg converted to the reference through itself: OpenColorIO would recurse until the
    # interpreter died (SIGSEGV), so the call runs in a child.
    with open(os.path.join(SOURCE, "share", "ocio", "kiln.ocio")) as f:
        config = f.read()
    looping = re.sub(r"to_scene_reference: !<MatrixTransform> \{matrix: \[0\.6954.*\]\}",
                     "to_scene_reference: !<ColorSpaceTransform> {src: ACEScg, dst: ACES2065-1}", config)
    assert looping != config
    path = tmp_path / "loop.ocio"
    path.write_text(looping)
    done = run_child(f"""
import kiln
try:
    kiln.render({CORNELL!r}, width=8, height=8, ocio_config={str(path)!r}, working_space="ACEScg")
except kiln.InputError as e:
    print(e.file, e.location, sep="\\n")
    print(e.reason)
""")
    assert done.returncode == 0, f"exit {done.returncode}: {done.stderr}"
    file, location, reason = done.stdout.splitlines()
    assert (file, location) == (str(path), "colour space 'ACEScg'")
    assert reason.startswith("its references loop back to it")


def test_a_nul_in_a_path_raises_input_error_instead_of_naming_another_file(tmp_path):
    # The system reads a path up to its first NUL: the asset rendered the Cornell box, and the
    # output went to x.exr.
    out = tmp_path / "x.exr"
    with pytest.raises(kiln.InputError) as caught:
        kiln.render(CORNELL + "\0.other", width=8, height=8, spp=1)
    assert caught.value.location == "asset"
    assert caught.value.reason == "'" + CORNELL + "\\x00.other' holds a NUL character, which no file name can"
    for keywords, location in [({"output": str(out) + "\0.tmp"}, "-o"),
                               ({"output": str(out), "preview": str(tmp_path / "x.png") + "\0"}, "--preview"),
                               ({"environment": os.path.join(SOURCE, "scenes", "glass_showcase_sky.hdr") + "\0"},
                                "--environment")]:
        with pytest.raises(kiln.InputError) as caught:
            kiln.render(CORNELL, width=8, height=8, spp=1, **keywords)
        assert caught.value.location == location
        assert "\\x00" in caught.value.reason
        assert caught.value.reason.endswith("' holds a NUL character, which no file name can")
    result = kiln.render(CORNELL, width=8, height=8, spp=1)
    with pytest.raises(kiln.InputError, match="NUL"):
        result.write(str(out) + "\0.tmp")
    assert os.listdir(tmp_path) == []
