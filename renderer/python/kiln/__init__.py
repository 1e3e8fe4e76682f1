"""kiln: renders glTF 2.0 assets with Embree and Whitted shading; AOVs as NumPy arrays.

kiln.render(asset, **options) renders once; kiln.load(asset, **options) reads an asset once into a
kiln.Scene that renders many times, from a file or from glTF in memory (a dict, or .gltf JSON or
.glb bytes, with its buffers and images). kiln.options() lists the options (those of
`kiln render`). `python -m kiln render ...` runs the command line installed with the package.
"""
import json
import os
import struct

from ._kiln import *  # noqa: F401,F403 (the module's functions, Scene, Result and the error classes)
from ._kiln import __version__  # noqa: F401
from ._kiln import InputError, _load

_MEMORY = "<memory>"  # how errors name an asset in memory


def load(asset, *, buffers=None, images=None, **options):
    """load(asset, *, buffers=None, images=None, **options) -> Scene

    Reads asset once and returns a kiln.Scene whose render(**options) renders it as often as wanted.
    asset is a path (str or pathlib.Path), or glTF in memory: a dict of the glTF JSON, or the bytes
    of a .gltf (JSON) or a .glb. buffers= and images= give the files its URIs name, as a list (by
    buffer or image index) or a dict (by index or by the URI as the JSON writes it), each bytes or
    a NumPy array (its bytes as they lie in memory); images are encoded PNG, JPEG or WebP bytes. A
    buffer or image of a dict that has no "uri" is given one. Nothing is read from files for an
    asset in memory: a URI that is not given is a kiln.InputError naming its JSON pointer, and the
    loader's limits and checks apply as to a file.

    options are those of kiln.render; the ones that change what is loaded (scene, variant,
    animation, working_space, ocio_config, the max_* limits, max_memory, allow_outside_files) decide
    the load, and all of them are every render's defaults, which render()'s own options override.
    """
    if isinstance(asset, (str, os.PathLike)):
        if buffers is not None or images is not None:
            raise TypeError("load(): buffers= and images= go with glTF in memory (a dict or bytes), "
                            "not a path, whose files are read beside it")
        return _load(asset, **options)
    document, files = _memory_asset(asset, buffers, images)
    return _load(None, document=document, files=files, **options)


def _input_error(location, reason):
    error = InputError(f"{_MEMORY}: {location}: {reason}")
    error.file, error.location, error.reason = _MEMORY, location, reason
    return error


def _json_default(value):
    # NumPy numbers and arrays (an accessor's min and max) as JSON numbers and lists.
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not a JSON value")


def _glb_json(data):
    """The JSON chunk of GLB bytes, parsed; None when the container is not readable (the loader
    names what is wrong with it)."""
    if len(data) < 20:
        return None
    length, kind = struct.unpack_from("<II", data, 12)
    if kind != 0x4E4F534A:  # "JSON"
        return None
    try:
        return json.loads(data[20:20 + length])
    except ValueError:
        return None


def _file_bytes(value, where):
    if isinstance(value, (str, os.PathLike)):
        raise TypeError(f"load(): {where} is a path; give its bytes (load a path to read files)")
    try:
        return memoryview(value).tobytes()  # a NumPy array's bytes in C order
    except TypeError:
        raise TypeError(f"load(): {where} must be bytes or a NumPy array, "
                        f"not {type(value).__name__}") from None


def _image_suffix(data):
    if data[:8] == b"\x89PNG\r\n\x1a\n":
        return ".png"
    if data[:2] == b"\xff\xd8":
        return ".jpg"
    if data[:4] == b"RIFF" and data[8:12] == b"WEBP":
        return ".webp"
    return ""


def _named_files(kind, given, entries, editable, files):
    """Adds to files (URI -> bytes) what given holds for doc[kind], by index or URI. Entries without
    a URI get one when editable (a dict's copy)."""
    if given is None:
        return
    if isinstance(given, dict):
        items = given.items()
    elif isinstance(given, (list, tuple)):
        items = enumerate(given)
    else:
        raise TypeError(f"load(): {kind}= must be a list or a dict, not {type(given).__name__}")
    for key, value in items:
        where = f"{kind}[{key!r}]"
        data = _file_bytes(value, where)
        if isinstance(key, str):
            files[key] = data
            continue
        if not isinstance(key, int) or isinstance(key, bool):
            raise TypeError(f"load(): the keys of {kind}= are indices or URIs, not {type(key).__name__}")
        if entries is None or not 0 <= key < len(entries) or not isinstance(entries[key], dict):
            count = len(entries) if isinstance(entries, list) else 0
            raise _input_error(f"/{kind}/{key}", f"no such entry to give bytes for (the asset has {count} {kind})")
        uri = entries[key].get("uri")
        if not isinstance(uri, str):
            if not editable:
                raise _input_error(f"/{kind}/{key}", "has no uri to give bytes for: give it one, or the "
                                   "glTF as a dict, whose entries without one get one")
            suffix = _image_suffix(data) if kind == "images" else ".bin"
            uri = entries[key]["uri"] = f"{kind}-{key}{suffix}"
        files[uri] = data


def _memory_asset(asset, buffers, images):
    """The document bytes and the files by URI of glTF in memory."""
    if isinstance(asset, dict):
        doc = dict(asset)
        for kind in ("buffers", "images"):  # copied: a missing uri is filled in
            if isinstance(doc.get(kind), list):
                doc[kind] = [dict(e) if isinstance(e, dict) else e for e in doc[kind]]
        editable = True
    elif isinstance(asset, (bytes, bytearray, memoryview)):
        data = bytes(asset)
        if data[:4] == b"glTF":
            doc = _glb_json(data)
        else:
            try:
                doc = json.loads(data)
            except ValueError:
                doc = None  # the loader names the fault
        editable = False
    else:
        raise TypeError("load() takes a path (str or pathlib.Path), a glTF dict, or the bytes of a "
                        f".gltf or .glb, not {type(asset).__name__}")
    files = {}
    entries = doc if isinstance(doc, dict) else {}
    _named_files("buffers", buffers, entries.get("buffers"), editable, files)
    _named_files("images", images, entries.get("images"), editable, files)
    if editable:
        data = json.dumps(doc, default=_json_default).encode()
    return data, files
