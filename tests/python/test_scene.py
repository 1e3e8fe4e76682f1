"""kiln.load and kiln.Scene: a scene loaded once renders what kiln.render renders from the same
options, bit for bit, whatever was rendered before; options that change the load load anew for
that render alone; two threads may render one Scene; frames and info come from the kept scene; glTF
given in memory (a dict, JSON or GLB bytes, with buffers and images by index or URI) renders as the
file does, reads no file, and is checked as a file is; pathlib.Path is a path everywhere; and the
NumPy example of docs/python.md runs as written. Run by CTest with PYTHONPATH at the build's module."""
import concurrent.futures
import json
import os
import pathlib
import re
import struct
import warnings

import numpy as np
import pytest

import kiln

SOURCE = os.environ.get("KILN_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CORNELL = os.path.join(SOURCE, "scenes", "cornell_box.gltf")
SMALL = {"width": 40, "height": 30, "spp": 2, "threads": 2}


def assert_same_arrays(a, b):
    assert a.aovs.keys() == b.aovs.keys()
    for name in a.aovs:
        assert np.array_equal(a.aovs[name], b.aovs[name], equal_nan=True), name
    assert np.count_nonzero(a.aovs["beauty"][:, :, 3]) > 100  # the scene is in the picture


# Each set of options after the last, on one Scene: every render must equal a fresh kiln.render.
RENDERS = [
    {},
    {"look_from": (0.2, 1.0, 3.5), "look_at": (0, 1, 0), "width": 32, "height": 32},
    {"spp": 4, "aovs": ["beauty", "Z", "albedo"]},
    {"crop": "4,3,30,20"},
    {"lighting": "headlight"},
    {"camera_view": "three-quarter", "background": (0.2, 0.3, 0.4), "show_background": True},
    {"accel": "grid"},
    {},
]


def test_a_scene_renders_what_kiln_render_renders_whatever_came_before():
    scene = kiln.load(CORNELL, **SMALL)
    assert scene.file == CORNELL and scene.options == SMALL
    for options in RENDERS:
        ours = scene.render(**options)
        alone = kiln.render(CORNELL, **{**SMALL, **options})
        assert_same_arrays(ours, alone)
        assert ours.metadata["kiln/settings_hash"] == alone.metadata["kiln/settings_hash"]
        assert ours.metadata["kiln/input_hash"] == alone.metadata["kiln/input_hash"]
        assert ours.stats["camera"] == alone.stats["camera"]


def test_an_option_that_changes_the_load_loads_anew_for_that_render_alone():
    scene = kiln.load(CORNELL, **SMALL)
    assert_same_arrays(scene.render(max_nodes=1000), kiln.render(CORNELL, **SMALL, max_nodes=1000))
    # A limit the file breaks refuses that render as kiln.render refuses it; the Scene renders on.
    with pytest.raises(kiln.InputError) as refused:
        scene.render(max_nodes=1)
    assert refused.value.location == "/nodes" and "--max-nodes" in refused.value.reason
    assert_same_arrays(scene.render(), kiln.render(CORNELL, **SMALL))
    with pytest.raises(kiln.InputError, match="camera index 7 out of range"):
        scene.render(camera=7)
    assert_same_arrays(scene.render(camera=0), kiln.render(CORNELL, **SMALL, camera=0))


def test_bad_load_options_and_keywords_raise_as_kiln_render_does():
    with pytest.raises(TypeError, match="did you mean 'spp'"):
        kiln.load(CORNELL, sp=2)
    with pytest.raises(TypeError, match="did you mean 'spp'"):
        kiln.load(CORNELL).render(sp=2)
    with pytest.raises(kiln.InputError, match="scenes/3 does not exist"):
        kiln.load(CORNELL, scene=3)
    with pytest.raises(kiln.InputError):
        kiln.load(os.path.join(SOURCE, "scenes", "no_such_file.gltf"))


# A Scene keeps its textures' pyramids and its environment's tables between renders; each render
# under another map, turn or strength, and back, must still be kiln.render's.
TEXTURED = os.path.join(SOURCE, "..", "shared", "assets", "BoxTextured", "glTF", "BoxTextured.gltf")
SKY = os.path.join(SOURCE, "scenes", "glass_showcase_sky.hdr")
STUDIO = os.path.join(SOURCE, "share", "environments", "studio.exr")
ENVIRONMENTS = [
    {},
    {"environment": SKY},
    {"environment": SKY, "environment_rotation": 90},
    {"environment": STUDIO, "environment_intensity": 0.5},
    {"environment": SKY},
    {"look_from": (2, 1, 3), "look_at": (0, 0, 0)},
]


@pytest.mark.skipif(not os.path.isfile(TEXTURED), reason="../shared/assets is absent")
def test_kept_pyramids_and_environment_tables_render_what_kiln_render_renders():
    scene = kiln.load(TEXTURED, **SMALL)
    for options in ENVIRONMENTS:
        assert_same_arrays(scene.render(**options), kiln.render(TEXTURED, **{**SMALL, **options}))


def test_two_threads_render_one_scene_and_each_gets_its_own_picture():
    scene = kiln.load(CORNELL, **SMALL)
    views = [{"look_from": (0.2, 1.0, 3.5), "look_at": (0, 1, 0)}, {"spp": 3, "camera_view": "top"}]
    expected = [kiln.render(CORNELL, **{**SMALL, **view}) for view in views]
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        futures = [pool.submit(scene.render, **views[i % 2]) for i in range(6)]
        for i, future in enumerate(futures):
            assert_same_arrays(future.result(timeout=120), expected[i % 2])


def test_frames_and_info_come_from_the_kept_scene(tmp_path):
    scene = kiln.load(CORNELL, **SMALL)
    frames = scene.render_sequence(turntable=3, output=str(tmp_path / "turn.####.exr"))
    alone = kiln.render_sequence(CORNELL, **SMALL, turntable=3)
    assert len(frames) == 3
    for ours, theirs in zip(frames, alone):
        assert_same_arrays(ours, theirs)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["turn.0001.exr", "turn.0002.exr", "turn.0003.exr"]
    ours, theirs = scene.info(camera_view="top"), kiln.info(CORNELL, **SMALL, camera_view="top")
    for document in (ours, theirs):  # the estimate's seconds come from timed probe renders
        for timed in ("load_seconds", "render_seconds_one_thread", "peak_memory_bytes"):
            document["render"].pop(timed)
    assert ours == theirs
    assert ours["render"]["view"].startswith("top view") and ours["cameras"][0]["name"] == "main"


def test_pathlib_paths_are_paths_everywhere(tmp_path):
    path = pathlib.Path(CORNELL)
    result = kiln.render(path, **SMALL, output=tmp_path / "a.exr")
    assert (tmp_path / "a.exr").stat().st_size > 0
    assert_same_arrays(kiln.load(path, **SMALL).render(output=tmp_path / "b.exr"), result)
    assert (tmp_path / "b.exr").stat().st_size > 0
    result.write(tmp_path / "c.exr", preview=tmp_path / "c.png")
    assert (tmp_path / "c.exr").stat().st_size > 0 and (tmp_path / "c.png").stat().st_size > 0
    assert kiln.info(path)["cameras"][0]["name"] == "main"
    assert len(kiln.render_sequence(path, **SMALL, turntable=2)) == 2
    sky = pathlib.Path(SOURCE, "scenes", "glass_showcase_sky.hdr")
    lit, by_text = kiln.render(path, **SMALL, environment=sky), kiln.render(CORNELL, **SMALL, environment=str(sky))
    assert os.path.samefile(lit.metadata["kiln/environment"], sky)
    assert lit.metadata["kiln/settings_hash"] == by_text.metadata["kiln/settings_hash"]
    assert_same_arrays(lit, by_text)
    with pytest.raises(TypeError):
        kiln.render(3.5)


# --- glTF in memory ---------------------------------------------------------------------------

def cornell_in_memory():
    with open(CORNELL, "rb") as f:
        document = json.load(f)
    with open(os.path.join(SOURCE, "scenes", "cornell_box.bin"), "rb") as f:
        buffer = f.read()
    with open(os.path.join(SOURCE, "scenes", "checker.png"), "rb") as f:
        checker = f.read()
    return document, buffer, checker


def glb_of(document, buffer):
    """A .glb of document with buffer 0 as its BIN chunk."""
    document = dict(document, buffers=[{"byteLength": len(buffer)}])
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    buffer += b"\0" * (-len(buffer) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(buffer), 0x004E4942) + buffer
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


def test_gltf_in_memory_renders_as_the_file_does():
    document, buffer, checker = cornell_in_memory()
    expected = kiln.render(CORNELL, **SMALL)
    uri_buffer = document["buffers"][0]["uri"]
    uri_image = document["images"][0]["uri"]
    # A dict with its files by URI; the same as JSON bytes, by index; an array as a buffer; a GLB.
    by_uri = kiln.load(document, buffers={uri_buffer: buffer}, images={uri_image: checker}, **SMALL)
    assert by_uri.file == "<memory>"
    assert_same_arrays(by_uri.render(), expected)
    text = json.dumps(document).encode()
    assert_same_arrays(kiln.load(text, buffers=[np.frombuffer(buffer, np.uint8)], images={0: checker},
                                 **SMALL).render(), expected)
    glb = glb_of(document, buffer)
    assert_same_arrays(kiln.load(glb, images=[checker], **SMALL).render(), expected)
    # A dict's buffer without a uri gets one; the scene renders again with other options.
    document_without = dict(document, buffers=[{"byteLength": len(buffer)}])
    scene = kiln.load(document_without, buffers=[buffer], images=[checker], **SMALL)
    assert_same_arrays(scene.render(spp=3), kiln.render(CORNELL, **{**SMALL, "spp": 3}))
    assert "uri" not in document_without["buffers"][0]  # the caller's dict is left as it was


def test_gltf_in_memory_is_checked_as_a_file_and_reads_no_file(tmp_path, monkeypatch):
    document, buffer, checker = cornell_in_memory()
    monkeypatch.chdir(os.path.join(SOURCE, "scenes"))  # where the URIs' files lie: still not read

    def refused(asset, location, reason, **kwargs):
        with pytest.raises(kiln.InputError) as e:
            kiln.load(asset, **kwargs).render(**SMALL)
        assert e.value.file == "<memory>" and e.value.location == location, str(e.value)
        assert re.search(reason, e.value.reason), e.value.reason
        assert str(e.value) == ": ".join(part for part in ("<memory>", location, e.value.reason) if part)

    refused(document, "/buffers/0/uri", "'cornell_box.bin', which was not given", images=[checker])
    refused(document, "/images/0/uri", "'checker.png', which was not given", buffers=[buffer])
    refused(document, "/buffers/0/byteLength", "but the bytes given for 'cornell_box.bin' are 10",
            buffers=[buffer[:10]], images=[checker])
    refused(document, "/buffers/4", "no such entry", buffers={4: buffer})
    refused(json.dumps(dict(document, buffers=[{"byteLength": len(buffer)}])).encode(), "/buffers/0",
            "has no uri", buffers=[buffer])
    refused(document, "", "over the limit of 100 \\(--max-json-bytes\\)", buffers=[buffer], images=[checker],
            max_json_bytes=100)
    bad_accessor = json.loads(json.dumps(document))
    bad_accessor["accessors"][0]["count"] = 10 ** 9
    refused(bad_accessor, "/accessors/0/count", "larger than any glTF buffer", buffers=[buffer], images=[checker])
    refused(b"{\"asset\": ", "", "JSON|json", buffers=[])
    with pytest.raises(TypeError, match="not int"):
        kiln.load(12)
    with pytest.raises(TypeError, match="is a path; give its bytes"):
        kiln.load(document, buffers=["cornell_box.bin"])
    with pytest.raises(TypeError, match="bytes or a NumPy array, not int"):
        kiln.load(document, buffers=[3])
    with pytest.raises(TypeError, match="glTF in memory"):
        kiln.load(CORNELL, buffers=[buffer])


def readme_example():
    """The NumPy example of docs/python.md, exactly as the page shows it."""
    with open(os.path.join(SOURCE, "docs", "python.md"), encoding="utf-8") as f:
        readme = f.read()
    match = re.search(r"<!-- tests/python/test_scene\.py runs this block -->\n```python\n(.*?)```", readme, re.S)
    assert match, "docs/python.md has no tested NumPy example"
    return match.group(1)


def test_the_readme_numpy_example_renders_a_lit_sphere(tmp_path, monkeypatch):
    code = readme_example()
    assert 15 <= len(code.strip().splitlines()) <= 40
    monkeypatch.chdir(tmp_path)
    namespace = {}
    with warnings.catch_warnings():
        warnings.simplefilter("error", kiln.KilnWarning)  # no headlight, no degenerate triangles
        exec(compile(code, "docs/python.md", "exec"), namespace)
    result = namespace["result"]
    beauty = result.aovs["beauty"]
    height, width, _ = beauty.shape
    centre, corner = beauty[height // 2, width // 2], beauty[2, 2]
    assert centre[3] == 1.0 and corner[3] == 0.0  # the sphere fills the middle, not the corner
    assert centre[0] > centre[1] > centre[2] > 0.0  # lit, and orange as its material says
    lit_side, dark_side = beauty[height // 2, width * 2 // 3, 0], beauty[height // 2, width // 3, 0]
    assert lit_side > dark_side  # the light stands to the right
    assert (tmp_path / "sphere.exr").stat().st_size > 0
    assert result.stats["camera"] != "default"  # the file's own camera
