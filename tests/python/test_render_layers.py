"""Render layers from Python as from the command line: two flat layers of the Cornell box's objects
and room (mattes by default) add to the full render; with others="invisible" the room's layer has
no hole where the objects stand and names none of them in its ids; a deep render's layer defaults
to invisible others. Run by CTest with PYTHONPATH at the build's module."""
import os

import numpy as np

import kiln

SOURCE = os.environ.get("KILN_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CORNELL = os.path.join(SOURCE, "scenes", "cornell_box.gltf")
SMALL = {"width": 40, "height": 30, "spp": 4, "threads": 2, "aovs": ["beauty", "id"]}
OBJECT_NODES = {11, 12, 13, 17}  # the children of the node "objects"


def beauty(result):
    return np.asarray(result.aovs["beauty"], dtype=np.float64)


def test_flat_layers_add_with_plus():
    full = kiln.render(CORNELL, **SMALL)
    objects = kiln.render(CORNELL, only="objects", **SMALL)
    room = kiln.render(CORNELL, holdout="objects", **SMALL)
    assert room.metadata["kiln/others"] == "matte"
    assert np.abs(beauty(objects) + beauty(room) - beauty(full)).max() < 1e-3
    assert (beauty(room)[:, :, 3] == 0).sum() > 20  # the objects are mattes in the room's layer


def test_invisible_others_leave_no_hole_and_no_ids():
    room = kiln.render(CORNELL, holdout="objects", others="invisible", **SMALL)
    assert room.metadata["kiln/others"] == "invisible"
    assert beauty(room)[:, :, 3].min() == 1.0
    ids = np.asarray(room.aovs["id"])[:, :, 0].astype(int)  # id.object
    assert not OBJECT_NODES & set(np.unique(ids).tolist())


def test_others_refused_with_invisible_holdouts():
    try:
        kiln.render(CORNELL, holdout="objects", others="invisible", holdout_invisible=True, **SMALL)
    except kiln.InputError as e:
        assert "--holdout-invisible" in str(e)
    else:
        raise AssertionError("contradictory options rendered")
