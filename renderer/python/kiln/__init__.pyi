# Type stubs of the kiln package, for IDEs and type checkers. The block between the BEGIN and END
# lines is generated from the option table by tools/make_python_stub.py (a test fails when it is
# out of date); the rest is written by hand.
import os
from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Sequence, Union

import numpy
from typing_extensions import TypedDict, Unpack

__version__: str

# A text option also takes a number, a list or tuple joined with commas (aovs=["beauty", "Z"],
# look_from=(0, 1, 3.5)), or a path (environment=pathlib.Path("sky.exr")).
_Text = Union[str, int, float, Sequence[Union[str, int, float]], "os.PathLike[str]"]
_Progress = Optional[Callable[[int, int], Any]]
_Path = Union[str, "os.PathLike[str]"]
# A buffer's or an image's bytes: bytes, or a NumPy array (its bytes as they lie in memory).
_Bytes = Union[bytes, bytearray, memoryview, numpy.ndarray]
_Files = Union[Sequence[_Bytes], Mapping[Union[int, str], _Bytes]]

class Error(RuntimeError):
    file: str
    location: str  # a JSON pointer (/meshes/0/primitives/0) or an option (--spp)
    reason: str

class InputError(Error, ValueError): ...
class TimeLimitError(Error, TimeoutError): ...

class KilnWarning(UserWarning):
    """What kiln render prints as a warning or note (also in Result.warnings)."""

class Result:
    aovs: Dict[str, numpy.ndarray]  # AOV name -> float32 array (height, width, channels)
    channels: Dict[str, List[str]]  # AOV name -> its EXR channel names
    metadata: Dict[str, Any]  # the EXR header's attributes
    stats: Dict[str, Any]  # sizes, timings and ray counts
    warnings: List[str]
    def write(self, path: _Path, preview: Optional[_Path] = None) -> None: ...
    def __getitem__(self, name: str) -> numpy.ndarray: ...

# BEGIN options
class RenderOptions(TypedDict, total=False):
    width: Optional[int]
    """--width: Image width in pixels (default 640, or from --height and the camera's aspect)"""
    height: Optional[int]
    """--height: Image height in pixels (default 480, or from the camera's aspect ratio)"""
    spp: Optional[int]
    """--spp: Samples per pixel, stratified and jittered (default 16; 1 = pixel centre)"""
    sampler: Optional[Literal['stratified', 'random']]
    """--sampler: Sample positions inside a pixel: jittered strata, or independent uniform samples (the baseline stratification is measured against) (default stratified)"""
    filter: Optional[Literal['box', 'tent', 'gaussian', 'blackman-harris']]
    """--filter: Reconstruction filter for the stratified samples (default radius: box 0.5, tent 1, gaussian 1.5 with sigma radius/3, blackman-harris 2)"""
    filter_radius: Optional[float]
    """--filter-radius: Filter radius in pixels, in (0, 16] (default: the filter's own)"""
    adaptive_threshold: Optional[float]
    """--adaptive-threshold: Whitted's adaptive supersampling: split a pixel square while its corners differ by more than T in R, G, B or A, or hit different instances (0 = off; replaces --spp and --filter) (default 0)"""
    adaptive_depth: Optional[int]
    """--adaptive-depth: Adaptive supersampling: most splits per pixel (default 4)"""
    threads: Optional[int]
    """--threads: Render threads (0 = all cores) (default 0)"""
    tile_size: Optional[int]
    """--tile-size: Tile side in pixels (default 32)"""
    camera: Optional[_Text]
    """--camera: glTF camera by name or index (default: the first camera in the file)"""
    look_from: Optional[_Text]
    """--look-from: Look-at camera position X,Y,Z (overrides --camera; needs --look-at)"""
    look_at: Optional[_Text]
    """--look-at: Look-at camera target X,Y,Z"""
    up: Optional[_Text]
    """--up: Look-at camera up vector X,Y,Z (default 0,1,0)"""
    fov: Optional[float]
    """--fov: Vertical field of view in degrees of a look-at camera, --camera-view and --turntable (default 45)"""
    camera_view: Optional[_Text]
    """--camera-view: Frame the asset like the default camera but from another direction: front, three-quarter (azimuth 45, elevation 25), top, or AZIMUTH,ELEVATION in degrees (azimuth from +Z towards +X); --fov sets its lens (default 45)"""
    scene: Optional[int]
    """--scene: glTF scene index (default: the file's default scene)"""
    time: Optional[float]
    """--time: Pose the scene at this time in seconds of its animations (default 0; or --frame)"""
    frame: Optional[int]
    """--frame: Pose the scene at frame N: time (N - frame-start) / fps seconds (instead of --time)"""
    fps: Optional[float]
    """--fps: Frames per second of --frame (default 24)"""
    frame_start: Optional[int]
    """--frame-start: The frame number at time 0 for --frame (default 1)"""
    animation: Optional[_Text]
    """--animation: glTF animations to play: all, or one by name or index (default all)"""
    variant: Optional[_Text]
    """--variant: KHR_materials_variants: render the variant NAME (or its index) of a file with material variants"""
    shutter: Optional[_Text]
    """--shutter: Motion blur: the shutter is open from OPEN to CLOSE, in frames relative to the frame (default: no blur)"""
    motion_steps: Optional[int]
    """--motion-steps: Time steps of --shutter's motion blur (default: as many as the motion needs, up to 33)"""
    background: Optional[_Text]
    """--background: A constant environment R,G,B (linear radiance): lights every surface and is seen by rays that leave the scene (default: none; see --lighting)"""
    environment: Optional[_Text]
    """--environment: Equirectangular environment map (EXR, HDR, ...; linear radiance): lights every surface and is seen by rays that leave the scene"""
    lighting: Optional[Literal['auto', 'studio', 'headlight', 'file']]
    """--lighting: What lights the scene: auto (the file's lights, and --environment or --background when given, else kiln's studio environment), studio (the studio environment alone), headlight (the file's lights, or a light at the camera when it has none) or file (the file's lights and the environment given, nothing added) (default auto)"""
    environment_rotation: Optional[float]
    """--environment-rotation: Turn the environment map about +Y by DEG degrees (counter-clockwise seen from above) (default 0)"""
    environment_intensity: Optional[float]
    """--environment-intensity: Scale of the environment map's radiance (default 1)"""
    environment_samples: Optional[int]
    """--environment-samples: Environment light samples per shading point (each a pair: one drawn from the map, one from the material's lobes, combined by multiple importance sampling) (default 2)"""
    show_background: Optional[bool]
    """--show-background: Camera rays that miss see the environment colour with alpha 1 (default: transparent, alpha 0)"""
    transmission_alpha: Optional[Literal['opaque', 'transparent']]
    """--transmission-alpha: What glass contributes to alpha: opaque (it holds out, what it shows is baked in) or transparent (refraction reaching a background the camera does not show is transparent) (default opaque)"""
    holdout: Optional[_Text]
    """--holdout: Render these nodes and their subtrees (names, /paths or globs, comma-separated) as holdout mattes: they cut alpha to zero and hide what is behind them, but still cast shadows and show in reflections"""
    only: Optional[_Text]
    """--only: Render only these nodes and their subtrees (names, /paths or globs); every other node is outside the layer, as --others says (a render layer: flat layers add with plus, deep ones merge by depth)"""
    holdout_invisible: Optional[bool]
    """--holdout-invisible: Holdouts matte the camera only: they cast no shadows and do not show in reflections or through glass (default false)"""
    others: Optional[Literal['auto', 'invisible', 'matte']]
    """--others: What a render layer (--only, --holdout) does with the nodes outside it: invisible (the layer's camera rays pass them by; they still cast shadows and show in reflections and through glass: deep layers merge by depth), matte (they cut alpha to zero: flat layers add with plus) or auto (invisible with --deep, else matte)"""
    max_depth: Optional[int]
    """--max-depth: Maximum reflection depth (default 8)"""
    min_throughput: Optional[float]
    """--min-throughput: Reflections weighted below this are not traced (default 0.00100000005)"""
    max_rays_per_sample: Optional[int]
    """--max-rays-per-sample: Reflected, refracted and continued rays one camera sample may spawn; past it the sample keeps the light gathered so far (default 4096)"""
    allow_outside_files: Optional[bool]
    """--allow-outside-files: Let buffer and image URIs name files outside the asset's folder ('..' escapes, symlinks that lead out); absolute paths and URLs stay refused (default false)"""
    max_json_bytes: Optional[int]
    """--max-json-bytes: Refuse glTF JSON larger than this (bytes) (default 536870912)"""
    max_json_depth: Optional[int]
    """--max-json-depth: Refuse glTF JSON nested deeper than this (default 512)"""
    max_nodes: Optional[int]
    """--max-nodes: Refuse glTF files with more nodes than this (default 1000000)"""
    max_instances: Optional[int]
    """--max-instances: Refuse glTF files whose EXT_mesh_gpu_instancing takes the scene past this many mesh instances (default 1000000)"""
    max_texels: Optional[int]
    """--max-texels: Refuse glTF images declaring more texels than this (width x height), before decoding (default 268435456)"""
    max_pixels: Optional[int]
    """--max-pixels: Refuse images with more pixels than this (width x height) (default 268435456)"""
    max_memory: Optional[_Text]
    """--max-memory: Memory budget of a job, in bytes or with K, M, G, T (binary): a file whose estimated memory exceeds it is refused (default: 90% of the machine's or the cgroup's memory)"""
    grid_density: Optional[float]
    """--grid-density: Grid backends: aim for density x N cells for N items (the resolution heuristic; default 2)"""
    grid_resolution: Optional[_Text]
    """--grid-resolution: Grid backends: N or X,Y,Z cells per axis for every grid, instead of the heuristic"""
    grid_max_items: Optional[int]
    """--grid-max-items: Adaptive grid: a cell holding more items than this is subdivided (default 8)"""
    grid_max_depth: Optional[int]
    """--grid-max-depth: Adaptive grid: levels of subdivision below the top grid (default 3)"""
    bvh_quality: Optional[Literal['low', 'medium', 'high']]
    """--bvh-quality: Embree BVH build quality: low, medium or high (default medium)"""
    bvh_compact: Optional[bool]
    """--bvh-compact: Embree: compact BVH layout (less memory, slower rays) (default false)"""
    packets: Optional[Union[Literal['on', 'off'], bool]]
    """--packets: Trace each pixel's camera rays together as Embree packets: on or off (default on)"""
    shading: Optional[Literal['wave', 'reference']]
    """--shading: How a tile's samples are shaded: wave (the camera's hits of a run of samples made ready together, grouped by material, then shaded) or reference (each sample from its camera ray to its last bounce, one at a time: the scalar path the wave is held to) (default wave)"""
    time_limit: Optional[float]
    """--time-limit: Stop a job still loading or rendering after this many seconds: nothing is written, exit 124 (0 = no limit) (default 0)"""
    quiet: Optional[bool]
    """--quiet: No progress line or summary (default false)"""
    float: Optional[bool]
    """--float: Write beauty, N, albedo, direct, reflection, refraction, lightgroups, albedo_filtered, N_filtered, diffuse, specular, shadow, emission as 32-bit float instead of half (uv is float unless --channel-format uv=half; Z, P, id and Cryptomatte are always float) (default false)"""
    channel_format: Optional[_Text]
    """--channel-format: Per-AOV sample format after --float, e.g. beauty=float,N=half,uv=half (beauty, N, albedo, uv, direct, reflection, refraction, lightgroups, albedo_filtered, N_filtered, diffuse, specular, shadow, emission; Z, P and id are always float)"""
    compression: Optional[Literal['none', 'rle', 'zips', 'zip', 'piz', 'pxr24', 'b44', 'b44a', 'dwaa', 'dwab']]
    """--compression: EXR codec; pxr24, b44, b44a, dwaa and dwab are lossy and need --multipart when the file holds Z, P or id (which then keep zip) (default zip)"""
    compression_level: Optional[int]
    """--compression-level: zip/zips: zlib level 1-9 (default 4); dwaa/dwab: dwaCompressionLevel (default 45)"""
    tiled: Optional[bool]
    """--tiled: Tiled EXR (64x64 tiles unless --exr-tile-size) instead of scanlines (default false)"""
    exr_tile_size: Optional[int]
    """--exr-tile-size: Tiled EXR with NxN tiles (implies --tiled)"""
    multipart: Optional[bool]
    """--multipart: One EXR part per layer (rgba, depth, N, P, albedo, uv, id, forward, backward, direct, reflection, refraction, albedo_filtered, N_filtered, diffuse, specular, emission, CryptoObject, CryptoMaterial), each with the full header (default false)"""
    frames: Optional[_Text]
    """--frames: Render frames FIRST-LAST[:STEP] in one process, each to -o with its #### (or %04d) replaced by the frame number; the asset loads once and only what moves is updated"""
    turntable: Optional[int]
    """--turntable: Render N frames orbiting the asset about +Y through its bounds' centre, framed like the default camera at every angle, each to -o with its #### replaced (as --frames); an animation plays along"""
    turntable_elevation: Optional[float]
    """--turntable-elevation: Turntable: the camera's elevation above the asset's centre in degrees, -90 to 90 (default 20)"""
    turntable_start: Optional[float]
    """--turntable-start: Turntable: the first frame's azimuth in degrees, from the front (+Z) towards +X (default 0); frame i is at start + 360 i / N"""
    turntable_animation: Optional[Literal['play', 'hold']]
    """--turntable-animation: Turntable of an animated asset: play (default: frame N poses the animation at frame N) or hold (the pose at --time, default 0, while the camera turns)"""
    preview: Optional[_Text]
    """--preview: Also write an 8-bit sRGB preview FILE.png (with alpha) or FILE.jpg of the beauty"""
    ocio_config: Optional[_Text]
    """--ocio-config: OpenColorIO config for --working-space and the preview (default: $OCIO, else kiln's share/ocio/kiln.ocio)"""
    working_space: Optional[_Text]
    """--working-space: Render in this colour space of the config (e.g. ACEScg): glTF's linear Rec.709 colours, textures and lights are converted into it, and the EXR is tagged with it (default: linear Rec.709, unconverted)"""
    display: Optional[_Text]
    """--display: Preview through this display of the OpenColorIO config (default: the config's default)"""
    view: Optional[_Text]
    """--view: Preview through this view of the display (default: the display's default view)"""
    preview_exposure: Optional[float]
    """--preview-exposure: Preview: scale linear colour by 2^EV (default 0)"""
    deep: Optional[bool]
    """--deep: Also write a deep EXR beside -o (NAME.deep.exr for NAME.exr): per pixel its camera paths' surfaces front to back, premultiplied R G B A, Z, ZBack and the ids; whole frame, stratified samples and a filter inside the pixel only (default false)"""
    aovs: Optional[_Text]
    """--aovs: Comma-separated outputs to write: beauty (R G B A, premultiplied colour), Z (ray distance, or planar depth with --depth-mode), N (world shading normal), P (world position), albedo (base colour after textures and vertex colours), uv (TEXCOORD_0), id (glTF node, material and scene instance as integers), motion (screen-space motion to the next and previous frame, in pixels), crypto_object (Cryptomatte of the node names), crypto_material (Cryptomatte of the material names), direct (the beauty's emission, direct light and background seen directly), reflection (the beauty through the first mirror ray), refraction (the beauty through the first refracted ray), lightgroups (the beauty by light: one layer per light, emission and environment), albedo_filtered (denoising albedo filtered like the beauty), N_filtered (shading normal filtered like the beauty), diffuse (direct light by the Lambert lobe), specular (direct light by the glossy lobes), shadow (one shadow matte per light and the environment), emission (emitted light seen directly); cryptomatte for both Cryptomatte layers (default beauty,Z,N)"""
    cryptomatte_depth: Optional[int]
    """--cryptomatte-depth: Cryptomatte ranks (id and coverage pairs) per pixel, two per RGBA channel set (default 6)"""
    depth_mode: Optional[Literal['distance', 'planar']]
    """--depth-mode: What Z holds: distance (along the ray from the camera, the default) or planar (along the view axis)"""
    crop: Optional[_Text]
    """--crop: Render and store only pixels [x0, x1) x [y0, y1) (EXR data window; the display window stays the full frame)"""
    band: Optional[_Text]
    """--band: Render band I (0-based) of N horizontal bands of whole rows, as a crop (band I holds rows [floor(I*H/N), floor((I+1)*H/N)); join the files with kiln stitch)"""
    accel: Optional[Literal['embree', 'grid', 'adaptive-grid']]
    """--accel: Traversal backend (default embree)"""
    progress_interval: Optional[float]
    """--progress-interval: Seconds between progress lines when stderr is not a terminal (a log or a pipe) (default 5)"""
# END options

def render(
    asset: _Path, *, output: Optional[_Path] = None, progress: _Progress = None, **options: Unpack[RenderOptions]
) -> Result:
    """Renders asset with the options of `kiln render`; help(kiln.render) lists them. output= also
    writes the EXR; progress(pixels_done, pixels_total) is called with a total above 0, the last
    time at 100%. Raises kiln.InputError for bad input, TypeError for an unknown keyword."""

def render_sequence(
    asset: _Path, *, output: Optional[_Path] = None, progress: _Progress = None, **options: Unpack[RenderOptions]
) -> List[Result]:
    """Renders the frames of frames="FIRST-LAST[:STEP]" (or turntable=N), loading the asset once;
    output= with #### or %04d writes each frame as it finishes."""

def info(asset: _Path, **options: Unpack[RenderOptions]) -> Dict[str, Any]:
    """What `kiln info ASSET --json` prints (its keys: docs/info.md)."""

class Scene:
    """An asset loaded once (kiln.load), rendered and described as often as wanted."""

    file: str  # the asset's path, or '<memory>'
    options: Dict[str, Any]  # load()'s options: every render's defaults
    def render(
        self, *, output: Optional[_Path] = None, progress: _Progress = None, **options: Unpack[RenderOptions]
    ) -> Result:
        """Renders as kiln.render(asset, **load_options, **options) would, without reading the asset
        again. An option that changes what is loaded loads anew for this render alone."""
    def render_sequence(
        self, *, output: Optional[_Path] = None, progress: _Progress = None, **options: Unpack[RenderOptions]
    ) -> List[Result]:
        """The frames of frames= (or turntable=), posed from the loaded scene."""
    def info(self, **options: Unpack[RenderOptions]) -> Dict[str, Any]:
        """kiln.info's document for the loaded scene."""

def load(
    asset: Union[_Path, Dict[str, Any], bytes, bytearray, memoryview],
    *,
    buffers: Optional[_Files] = None,
    images: Optional[_Files] = None,
    **options: Unpack[RenderOptions],
) -> Scene:
    """Reads asset once (a path, a glTF dict, or .gltf or .glb bytes with its buffers and images by
    index or URI) and returns a Scene. options are every render's defaults."""

def options() -> List[Dict[str, Any]]:
    """Every render option: name, option, type, help, choices, default."""
