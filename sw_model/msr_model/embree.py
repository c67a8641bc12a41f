"""The Embree rendering unit from Python: ctypes on build/renderer/libmsr_render.so.

The same shared library paints pixels for the RTL simulation through DPI-C, so Python and
the hardware flow see bit-identical colours. Build it with `make renderer`.

    with open_renderer("cornell", 320, 240) as r:
        rgb = r.render(xs, ys)      # (N, 3) uint8, any pixel order, any batch split
        img = r.render_full()       # (H, W, 3) uint8

A view: open_renderer(scene, w, h, camera="EX,EY,EZ,TX,TY,TZ,FOV") (eye, target in model
units, vertical field of view in degrees, up +y); the same string gives the same pixels in
every flow (the RTL simulation passes it to the library unchanged).
"""
from __future__ import annotations

import ctypes
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from . import spec

QUALITIES = {"fast": 0, "heavy": 1}
HEAVY_GRID = 4          # heavy mode: 4 x 4 samples per pixel (msr::Renderer::kHeavyGrid)
MAX_GRID = 64           # msr_render_create_spp: grid 1..64
DEFAULT_SEED = 0x4D5352  # MSR_RENDER_DEFAULT_SEED, the seed of the two quality modes
_BATCH = 8192  # pixels per C call: big enough to hide call overhead, small for a smooth progress bar

class RendererUnavailable(spec.SpecError):
    """The shared library is not built (or MSR_RENDER_LIB points nowhere)."""


_lib = None
_lib_lock = threading.Lock()


def library_path() -> Path:
    """The shared library: $MSR_RENDER_LIB, else <repo>/build/renderer/libmsr_render.so."""
    env = os.environ.get("MSR_RENDER_LIB")
    if env:
        return Path(env)
    return Path(__file__).resolve().parents[2] / "build" / "renderer" / "libmsr_render.so"


def _load():
    global _lib
    with _lib_lock:
        if _lib is not None:
            return _lib
        path = library_path()
        if not path.is_file():
            raise RendererUnavailable(f"rendering library {path} not found: run `make renderer` in the repository root"
                               + (" (or fix MSR_RENDER_LIB)" if os.environ.get("MSR_RENDER_LIB") else ""))
        lib = ctypes.CDLL(str(path))  # CDLL releases the GIL during every call
        lib.msr_render_create.restype = ctypes.c_void_p
        lib.msr_render_create.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_int, ctypes.c_int,
                                          ctypes.c_char_p, ctypes.c_size_t]
        lib.msr_render_create_view.restype = ctypes.c_void_p
        lib.msr_render_create_view.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_int,
                                               ctypes.c_int, ctypes.c_char_p, ctypes.c_size_t]
        if hasattr(lib, "msr_render_create_spp"):
            lib.msr_render_create_spp.restype = ctypes.c_void_p
            lib.msr_render_create_spp.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_int,
                                                  ctypes.c_int, ctypes.c_int, ctypes.c_uint32, ctypes.c_char_p,
                                                  ctypes.c_size_t]
        lib.msr_render_pixel.restype = None
        lib.msr_render_pixel.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.POINTER(ctypes.c_uint8)]
        lib.msr_render_pixels.restype = None
        lib.msr_render_pixels.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p,
                                          ctypes.c_void_p]
        lib.msr_render_destroy.restype = None
        lib.msr_render_destroy.argtypes = [ctypes.c_void_p]
        lib.msr_render_scene_names.restype = ctypes.c_char_p
        lib.msr_render_scene_names.argtypes = []
        lib.msr_render_gbuffer.restype = None
        lib.msr_render_gbuffer.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p,
                                           ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
        lib.msr_render_rays.restype = ctypes.c_uint64
        lib.msr_render_rays.argtypes = [ctypes.c_void_p]
        lib.msr_render_view.restype = ctypes.c_int
        lib.msr_render_view.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)]
        if hasattr(lib, "msr_render_pixels_invz"):     # reuse across frames (docs/spec/reuse.md)
            lib.msr_render_pixels_invz.restype = None
            lib.msr_render_pixels_invz.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p,
                                                   ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int]
            lib.msr_render_model_scale.restype = ctypes.c_double
            lib.msr_render_model_scale.argtypes = [ctypes.c_void_p]
        if hasattr(lib, "msr_render_framing"):
            lib.msr_render_framing.restype = ctypes.c_int
            lib.msr_render_framing.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)]
        _lib = lib
        return lib


def scene_names() -> list[str]:
    """The built-in scene names, default scene first."""
    return _load().msr_render_scene_names().decode().split(",")


def check_camera(text: str) -> str:
    """The view string EX,EY,EZ,TX,TY,TZ,FOV, checked (the library checks it again); returns it
    unchanged, so that every flow hands the library the same string. SpecError when malformed."""
    form = "want EX,EY,EZ,TX,TY,TZ,FOV: eye, target, vertical field of view in degrees"
    if not isinstance(text, str):
        raise spec.SpecError(f"camera must be a string ({form}), got {text!r}")
    parts = text.split(",")
    if len(parts) != 7:
        raise spec.SpecError(f"camera {text!r} has {len(parts)} values, not 7 ({form})")
    try:
        vals = [float(p) for p in parts]
    except ValueError:
        raise spec.SpecError(f"camera {text!r}: not 7 numbers ({form})") from None
    if not all(np.isfinite(vals)):
        raise spec.SpecError(f"camera {text!r}: values must be finite ({form})")
    if not 0 < vals[6] < 180:
        raise spec.SpecError(f"camera {text!r}: field of view must be in (0, 180) degrees")
    if vals[0:3] == vals[3:6]:
        raise spec.SpecError(f"camera {text!r}: eye and target are the same point")
    return text


def _threads() -> int:
    try:
        n = len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        n = os.cpu_count() or 1
    return max(1, n)


class EmbreeRenderer:
    """A renderer object for the golden model: `.render(xs, ys) -> (N, 3) uint8`."""

    def __init__(self, scene: str, width: int, height: int, quality: str | int = "fast",
                 threads: int | None = None, camera: str | None = None, grid: int | None = None,
                 seed: int | None = None):
        spec.check_frame_size(width, height)
        if isinstance(quality, str):
            if quality not in QUALITIES:
                raise spec.SpecError(f"quality must be one of {', '.join(QUALITIES)}, got {quality!r}")
            q = QUALITIES[quality]
        elif quality in (0, 1):
            q = int(quality)
        else:
            raise spec.SpecError(f"quality must be 'fast' or 'heavy', got {quality!r}")
        if not isinstance(scene, (str, os.PathLike)) or not str(scene):
            raise spec.SpecError(f"scene must be a built-in name or a model file path, got {scene!r}")
        if camera is not None and camera != "":
            check_camera(camera)
        if grid is not None and not (isinstance(grid, (int, np.integer)) and 1 <= grid <= MAX_GRID):
            raise spec.SpecError(f"grid must be an integer in 1..{MAX_GRID}, got {grid!r}")
        if seed is not None and not (isinstance(seed, (int, np.integer)) and 0 <= seed < 2 ** 32):
            raise spec.SpecError(f"seed must be an integer in 0..2^32-1, got {seed!r}")
        self._lib = _load()
        err = ctypes.create_string_buffer(512)
        cam = camera.encode() if camera else None
        if grid is None and seed is None:     # the two quality modes, through the DPI's call
            handle = self._lib.msr_render_create_view(os.fsencode(str(scene)), cam, int(width), int(height), q,
                                                      err, len(err))
        else:
            if not hasattr(self._lib, "msr_render_create_spp"):
                raise RendererUnavailable("the rendering library has no msr_render_create_spp: run `make renderer`")
            handle = self._lib.msr_render_create_spp(os.fsencode(str(scene)), cam, int(width), int(height), q,
                                                     int(grid or 0), int(DEFAULT_SEED if seed is None else seed),
                                                     err, len(err))
        if not handle:
            msg = err.value.decode(errors="replace") or f"cannot open scene {scene}"
            raise spec.SpecError(msg)
        self._ctx = handle
        self.scene = str(scene)
        self.camera = camera or None
        self.width = int(width)
        self.height = int(height)
        self.quality = [k for k, v in QUALITIES.items() if v == q][0]
        self.grid = int(grid) if grid is not None else (HEAVY_GRID if q == 1 else 1)
        self.seed = int(DEFAULT_SEED if seed is None else seed)
        self.samples_per_pixel = self.grid * self.grid
        self.threads = max(1, int(threads)) if threads else _threads()
        self.calls = 0
        self.pixels_traced = 0
        self._pool = None  # worker threads, started on the first multi-batch call

    # -- pixels -------------------------------------------------------------------------------
    def _check_open(self):
        if not self._ctx:
            raise spec.SpecError("renderer is closed")

    def _render_into(self, xs: np.ndarray, ys: np.ndarray, out: np.ndarray, progress=None) -> None:
        """Colours of (xs[i], ys[i]) into out[i]; batches spread over self.threads threads."""
        n = xs.size
        starts = list(range(0, n, _BATCH))

        def run(start: int) -> None:
            stop = min(n, start + _BATCH)
            self._lib.msr_render_pixels(self._ctx, stop - start, xs[start:].ctypes.data, ys[start:].ctypes.data,
                                        out[start:].ctypes.data)
            if progress is not None:
                progress.update(stop - start)

        if self.threads == 1 or len(starts) == 1:
            for s in starts:
                run(s)
        else:
            if self._pool is None:
                self._pool = ThreadPoolExecutor(max_workers=self.threads, thread_name_prefix="msr_render")
            list(self._pool.map(run, starts))

    def render(self, xs, ys) -> np.ndarray:
        """Colours of the pixels (xs[i], ys[i]) as an (N, 3) uint8 array."""
        self._check_open()
        xs, ys = np.asarray(xs).reshape(-1), np.asarray(ys).reshape(-1)
        if xs.shape != ys.shape:
            raise spec.SpecError(f"xs and ys differ in length ({xs.size} vs {ys.size})")
        if xs.size and not (np.issubdtype(xs.dtype, np.integer) and np.issubdtype(ys.dtype, np.integer)):
            raise spec.SpecError(f"pixel coordinates must be integers, got {xs.dtype} and {ys.dtype}")
        # Checked before the cast to int32, so a huge coordinate cannot wrap into the frame.
        if xs.size and (xs.min() < 0 or xs.max() >= self.width or ys.min() < 0 or ys.max() >= self.height):
            raise spec.SpecError(f"pixel outside the {self.width}x{self.height} frame")
        xs = np.ascontiguousarray(xs, dtype=np.int32)
        ys = np.ascontiguousarray(ys, dtype=np.int32)
        out = np.empty((xs.size, 3), dtype=np.uint8)
        self.calls += 1
        self.pixels_traced += xs.size
        self._render_into(xs, ys, out)
        return out

    def render_pixel(self, x: int, y: int) -> tuple[int, int, int]:
        """One pixel through msr_render_pixel (the call the DPI bridge makes)."""
        self._check_open()
        rgb = (ctypes.c_uint8 * 3)()
        self._lib.msr_render_pixel(self._ctx, int(x), int(y), rgb)
        return rgb[0], rgb[1], rgb[2]

    def render_full(self, progress: bool = True) -> np.ndarray:
        """Every pixel, as an (H, W, 3) uint8 image; a progress bar when it takes over a second."""
        self._check_open()
        h, w = self.height, self.width
        ys, xs = np.divmod(np.arange(h * w, dtype=np.int32), np.int32(w))
        out = np.empty((h * w, 3), dtype=np.uint8)
        bar = None
        if progress:
            from tqdm import tqdm
            # disable=None: no bar unless stderr is a terminal (logs and CI stay clean)
            bar = tqdm(total=h * w, unit="px", unit_scale=True, delay=1.0, leave=False, disable=None,
                       desc=f"render {Path(self.scene).name} {w}x{h} {self.quality}")
        try:
            self._render_into(xs, ys, out, bar)
        finally:
            if bar is not None:
                bar.close()
        return out.reshape(h, w, 3)

    def gbuffer(self, xs, ys) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """What the primary ray through each pixel centre hits: (prim, material, depth), N each.

        prim: uint32 triangle index + 1 over the scene, material: uint32 material index + 1 (both 0
        for the sky), depth: float32 distance along the camera's viewing axis (inf for the sky).
        Deterministic like the colours; not part of the ray count."""
        self._check_open()
        xs, ys = np.asarray(xs).reshape(-1), np.asarray(ys).reshape(-1)
        if xs.shape != ys.shape:
            raise spec.SpecError(f"xs and ys differ in length ({xs.size} vs {ys.size})")
        if xs.size and (xs.min() < 0 or xs.max() >= self.width or ys.min() < 0 or ys.max() >= self.height):
            raise spec.SpecError(f"pixel outside the {self.width}x{self.height} frame")
        xs = np.ascontiguousarray(xs, dtype=np.int32)
        ys = np.ascontiguousarray(ys, dtype=np.int32)
        prim = np.empty(xs.size, np.uint32)
        mat = np.empty(xs.size, np.uint32)
        depth = np.empty(xs.size, np.float32)
        for start in range(0, xs.size, _BATCH):
            stop = min(xs.size, start + _BATCH)
            self._lib.msr_render_gbuffer(self._ctx, stop - start, xs[start:].ctypes.data, ys[start:].ctypes.data,
                                         prim[start:].ctypes.data, mat[start:].ctypes.data,
                                         depth[start:].ctypes.data)
        return prim, mat, depth

    def gbuffer_full(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """gbuffer() of every pixel, each as an (H, W) array."""
        h, w = self.height, self.width
        ys, xs = np.divmod(np.arange(h * w, dtype=np.int32), np.int32(w))
        return tuple(a.reshape(h, w) for a in self.gbuffer(xs, ys))

    def render_invz(self, xs, ys, invz_exp: int) -> tuple[np.ndarray, np.ndarray]:
        """Colours (render()) and the primary hit's inverse depth in model units, 16-bit fixed
        point: min(65535, max(1, round(2^invz_exp / depth))), 0 for the sky (docs/spec/reuse.md;
        msr_render_pixels_invz). The inverse depth comes from the G-buffer's ray: not a ray count."""
        if not hasattr(self._lib, "msr_render_pixels_invz"):
            raise RendererUnavailable("the rendering library has no msr_render_pixels_invz: run `make renderer`")
        if not 0 <= int(invz_exp) <= 40:
            raise spec.SpecError(f"invz_exp must be in 0..40, got {invz_exp}")
        rgb = self.render(xs, ys)
        xs = np.ascontiguousarray(np.asarray(xs).reshape(-1), dtype=np.int32)
        ys = np.ascontiguousarray(np.asarray(ys).reshape(-1), dtype=np.int32)
        invz = np.empty(xs.size, np.uint16)
        for start in range(0, xs.size, _BATCH):
            stop = min(xs.size, start + _BATCH)
            self._lib.msr_render_pixels_invz(self._ctx, stop - start, xs[start:].ctypes.data, ys[start:].ctypes.data,
                                             None, invz[start:].ctypes.data, int(invz_exp))
        return rgb, invz

    def model_scale(self) -> float:
        """World (renderer depth) units per model unit: the model's placement scale, 1 for the
        built-in scenes (msr_render_model_scale)."""
        self._check_open()
        if not hasattr(self._lib, "msr_render_model_scale"):
            raise RendererUnavailable("the rendering library has no msr_render_model_scale: run `make renderer`")
        return float(self._lib.msr_render_model_scale(self._ctx))

    def view(self) -> tuple[tuple, tuple, float]:
        """(eye, target, vertical field of view in degrees) of this renderer, in model units: the
        scene's own framing or the camera it was opened with (a camera path starts from it)."""
        out = (ctypes.c_double * 7)()
        if not self._ctx or not self._lib.msr_render_view(self._ctx, out):
            raise spec.SpecError("the renderer is closed")
        v = list(out)
        return tuple(v[0:3]), tuple(v[3:6]), v[6]

    def framing(self):
        """The scene's framing (msr_model.camera_path.Framing): model units -> the framed units
        of a "framed" camera path (the subject on the ground plane y = 0 in the unit bounding
        sphere, its bounding-box centre above the origin)."""
        from .camera_path import Framing
        if not hasattr(self._lib, "msr_render_framing"):
            raise RendererUnavailable("the rendering library has no msr_render_framing: run `make renderer`")
        out = (ctypes.c_double * 9)()
        if not self._ctx or not self._lib.msr_render_framing(self._ctx, out):
            raise spec.SpecError("the renderer is closed")
        v = list(out)
        return Framing(pivot=tuple(v[0:3]), scale=v[3], cos_yaw=v[4], sin_yaw=v[5], offset=tuple(v[6:9]))

    @property
    def rays(self) -> int:
        """Rays cast so far by this renderer (primary, shadow, secondary, occlusion)."""
        return int(self._lib.msr_render_rays(self._ctx)) if self._ctx else 0

    # -- lifetime -----------------------------------------------------------------------------
    def close(self) -> None:
        pool = getattr(self, "_pool", None)
        if pool is not None:
            pool.shutdown(wait=True)  # no call may still be running when the context goes
            self._pool = None
        if getattr(self, "_ctx", None):
            self._lib.msr_render_destroy(self._ctx)
            self._ctx = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown
            pass


def open_renderer(scene: str, width: int, height: int, quality: str | int = "fast",
                  threads: int | None = None, camera: str | None = None, grid: int | None = None,
                  seed: int | None = None) -> EmbreeRenderer:
    """Open the Embree rendering unit on a built-in scene name or a model file path, seen from
    the scene's own view or from `camera` ("EX,EY,EZ,TX,TY,TZ,FOV", model units, degrees).

    Raises spec.SpecError with a one-line message for an unknown scene, an unreadable file,
    a file without triangles, a malformed camera or a bad frame size.

    grid, seed (the evaluation's converged references): grid x grid stratified samples per
    pixel and the seed of the pixel hashes (msr_render_create_spp); left out, the quality
    mode's own sampling, bit for bit.
    """
    return EmbreeRenderer(scene, width, height, quality, threads, camera, grid, seed)
