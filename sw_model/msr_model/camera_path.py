"""Camera paths (docs/spec/contracts.md, third round): a sequence's view per frame.

A path file is JSON, {"keys": [{"frame": 0, "eye": [x, y, z], "target": [x, y, z], "fov": 40},
...]}: frame numbers ascending, eye and target in model units, the vertical field of view in
degrees; between two keys each value is interpolated linearly in the frame number, before the
first key the first key holds, after the last the last. Up is +Y (as for --camera). A key may
also carry `"gaze": [x, y]` (pixels): the gaze point is interpolated the same way between the
keys that carry one and rounded half up (`gaze(k)`; None when no key carries one). Fields
other than these may be present and are ignored.

`CameraPath.camera(k)` is frame k's view as the renderer's camera string
"EX,EY,EZ,TX,TY,TZ,FOV" (msr_model.embree.check_camera), written with 17 significant digits so
the renderer reads back exactly the interpolated doubles: a path at a given frame renders the
same pixels on every run.

`"space": "framed"` in a path file puts eye and target in framed units: the scene's subject on
the ground plane y = 0 inside a bounding sphere of radius 1, its bounding-box centre above the
origin (where the renderer places a model file; for the built-in scenes the renderer's
`framing` of their subject, e.g. the Cornell box). `camera(k, framing)` converts them to model
units with the scene's `Framing` (EmbreeRenderer.framing()), so one path serves every model
and every flow hands the renderer the same model-unit string. Without "space", or with
"model", the units are the model's.

`default_orbit` is the view of a sequence without a path: the scene's own view turned about
the vertical axis through its framed centre, ORBIT_DEGREES over ORBIT_FRAMES frames.
`sequence_cameras` gives the camera strings of frames 0 .. N-1 for `make sim FRAMES=N` and
`msr_model sequence` alike.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

from . import spec

SPACES = ("model", "framed")
ORBIT_DEGREES = 360.0       # the default orbit: one full turn ...
ORBIT_FRAMES = 96           # ... in 96 frames (3.75 degrees a frame: FRAMES=4 already moves)


@dataclass(frozen=True)
class Framing:
    """Model units -> framed units: p' = R_yaw (p - pivot) * scale + offset, with
    R_yaw (x, z) = (c x + s z, -s x + c z) (the renderer's Placement, msr_render_framing)."""
    pivot: tuple[float, float, float]
    scale: float
    cos_yaw: float = 1.0
    sin_yaw: float = 0.0
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def to_framed(self, p) -> tuple[float, float, float]:
        x, y, z = (p[i] - self.pivot[i] for i in range(3))
        c, s = self.cos_yaw, self.sin_yaw
        return ((c * x + s * z) * self.scale + self.offset[0], y * self.scale + self.offset[1],
                (-s * x + c * z) * self.scale + self.offset[2])

    def to_model(self, p) -> tuple[float, float, float]:
        x, y, z = ((p[i] - self.offset[i]) / self.scale for i in range(3))
        c, s = self.cos_yaw, self.sin_yaw
        return (c * x - s * z + self.pivot[0], y + self.pivot[1], s * x + c * z + self.pivot[2])


@dataclass(frozen=True)
class Key:
    frame: int
    eye: tuple[float, float, float]
    target: tuple[float, float, float]
    fov: float
    gaze: tuple[float, float] | None = None


def _gaze(v, where: str) -> tuple[float, float]:
    if (not isinstance(v, (list, tuple)) or len(v) != 2 or any(isinstance(x, bool) for x in v)
            or not all(isinstance(x, (int, float)) and math.isfinite(x) and x >= 0 for x in v)):
        raise spec.SpecError(f"{where}: must be [x, y], two numbers >= 0 (pixels), got {v!r}")
    return float(v[0]), float(v[1])


def _vec3(v, where: str) -> tuple[float, float, float]:
    if not isinstance(v, (list, tuple)) or len(v) != 3:
        raise spec.SpecError(f"{where}: must be a list of 3 numbers, got {v!r}")
    try:
        out = tuple(float(x) for x in v)
    except (TypeError, ValueError):
        raise spec.SpecError(f"{where}: must be a list of 3 numbers, got {v!r}") from None
    if any(isinstance(x, bool) for x in v) or not all(math.isfinite(x) for x in out):
        raise spec.SpecError(f"{where}: must be 3 finite numbers, got {v!r}")
    return out


class CameraPath:
    """The keys of a path file, checked; camera(k) interpolates frame k."""

    def __init__(self, keys: list[Key], source: str = "camera path", space: str = "model"):
        if not keys:
            raise spec.SpecError(f"{source}: no keys")
        self.keys, self.source, self.space = keys, source, space

    @classmethod
    def from_dict(cls, data, source: str = "camera path") -> "CameraPath":
        if not isinstance(data, dict) or not isinstance(data.get("keys"), list):
            raise spec.SpecError(f'{source}: expected {{"keys": [...]}}')
        space = data.get("space", "model")
        if space not in SPACES:
            raise spec.SpecError(f'{source}: "space" must be one of {", ".join(SPACES)}, got {space!r}')
        keys = []
        for i, k in enumerate(data["keys"]):
            where = f"{source}: keys[{i}]"
            if not isinstance(k, dict):
                raise spec.SpecError(f"{where}: must be an object with frame, eye, target, fov")
            missing = [f for f in ("frame", "eye", "target", "fov") if f not in k]
            if missing:
                raise spec.SpecError(f"{where}: missing {', '.join(missing)}")
            frame = k["frame"]
            if isinstance(frame, bool) or not isinstance(frame, int) or frame < 0:
                raise spec.SpecError(f"{where}: frame must be an integer >= 0, got {frame!r}")
            if keys and frame <= keys[-1].frame:
                raise spec.SpecError(f"{where}: frame {frame} not after the previous key's {keys[-1].frame}")
            fov = k["fov"]
            if isinstance(fov, bool) or not isinstance(fov, (int, float)) or not 0 < fov < 180:
                raise spec.SpecError(f"{where}: fov must be a number of degrees in (0, 180), got {fov!r}")
            eye, target = _vec3(k["eye"], f"{where}.eye"), _vec3(k["target"], f"{where}.target")
            if eye == target:
                raise spec.SpecError(f"{where}: eye and target are the same point")
            gaze = _gaze(k["gaze"], f"{where}.gaze") if "gaze" in k else None
            keys.append(Key(frame, eye, target, float(fov), gaze))
        return cls(keys, source, space)

    def at(self, frame: int) -> tuple[tuple, tuple, float]:
        """(eye, target, fov) of a frame number >= 0."""
        if isinstance(frame, bool) or not isinstance(frame, int) or frame < 0:
            raise spec.SpecError(f"{self.source}: frame must be an integer >= 0, got {frame!r}")
        ks = self.keys
        if frame <= ks[0].frame:
            k = ks[0]
            return k.eye, k.target, k.fov
        if frame >= ks[-1].frame:
            k = ks[-1]
            return k.eye, k.target, k.fov
        j = next(i for i in range(1, len(ks)) if ks[i].frame >= frame)
        a, b = ks[j - 1], ks[j]
        t = (frame - a.frame) / (b.frame - a.frame)
        lerp = lambda p, q: tuple(x + (y - x) * t for x, y in zip(p, q))   # noqa: E731
        return lerp(a.eye, b.eye), lerp(a.target, b.target), a.fov + (b.fov - a.fov) * t

    def camera(self, frame: int, framing: Framing | None = None) -> str:
        """Frame `frame`'s view as the renderer's camera string (model units, exact doubles); a
        framed path needs the scene's framing."""
        eye, target, fov = self.at(frame)
        if eye == target:
            raise spec.SpecError(f"{self.source}: at frame {frame} eye and target are the same point")
        if self.space == "framed":
            if framing is None:
                raise spec.SpecError(f"{self.source}: a framed path needs the scene's framing")
            eye, target = framing.to_model(eye), framing.to_model(target)
        return camera_string(eye, target, fov)

    def gaze(self, frame: int) -> tuple[int, int] | None:
        """Frame `frame`'s gaze point in pixels, interpolated between the keys that carry one and
        rounded half up; None when no key does (the frame's gaze is then the run's)."""
        gs = [k for k in self.keys if k.gaze is not None]
        if not gs:
            return None
        if frame <= gs[0].frame or frame >= gs[-1].frame:
            g = gs[0].gaze if frame <= gs[0].frame else gs[-1].gaze
        else:
            j = next(i for i in range(1, len(gs)) if gs[i].frame >= frame)
            a, b = gs[j - 1], gs[j]
            t = (frame - a.frame) / (b.frame - a.frame)
            g = tuple(p + (q - p) * t for p, q in zip(a.gaze, b.gaze))
        return int(math.floor(g[0] + 0.5)), int(math.floor(g[1] + 0.5))

    @property
    def has_gaze(self) -> bool:
        return any(k.gaze is not None for k in self.keys)

    @property
    def last_key_frame(self) -> int:
        return self.keys[-1].frame


def load_path(path) -> CameraPath:
    """A path file, read and checked; spec.SpecError with a one-line reason otherwise."""
    p = Path(path)
    try:
        text = p.read_text()
    except OSError as e:
        raise spec.SpecError(f"cannot read camera path {path}: {e.strerror or e}") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise spec.SpecError(f"camera path {path}: not JSON ({e.msg}, line {e.lineno})") from None
    return CameraPath.from_dict(data, source=f"camera path {path}")


def camera_string(eye, target, fov) -> str:
    """The renderer's camera string, 17 significant digits: it reads back the exact doubles."""
    return ",".join(format(float(v), ".17g") for v in (*eye, *target, fov))


class Orbit:
    """The default orbit: `view` (eye, target, fov in model units, the scene's own) turned about
    the vertical axis through the framed centre by ORBIT_DEGREES / ORBIT_FRAMES a frame. Eye and
    target turn together, so the camera keeps its heading relative to the subject."""

    def __init__(self, view, framing: Framing, source: str = "default orbit"):
        self.eye, self.target, self.fov = tuple(view[0]), tuple(view[1]), float(view[2])
        self.axis = framing.to_model((0.0, 0.0, 0.0))      # R_yaw keeps y: the axis is vertical
        self.source = source

    def _turn(self, p, c: float, s: float):
        dx, dz = p[0] - self.axis[0], p[2] - self.axis[2]
        return (self.axis[0] + c * dx + s * dz, p[1], self.axis[2] - s * dx + c * dz)

    def at(self, frame: int) -> tuple[tuple, tuple, float]:
        if isinstance(frame, bool) or not isinstance(frame, int) or frame < 0:
            raise spec.SpecError(f"{self.source}: frame must be an integer >= 0, got {frame!r}")
        k = frame % ORBIT_FRAMES
        if k == 0:                                        # exactly the scene's view
            return self.eye, self.target, self.fov
        a = math.radians(ORBIT_DEGREES * k / ORBIT_FRAMES)
        c, s = math.cos(a), math.sin(a)
        return self._turn(self.eye, c, s), self._turn(self.target, c, s), self.fov

    def camera(self, frame: int, framing: Framing | None = None) -> str:
        return camera_string(*self.at(frame))

    def gaze(self, frame: int) -> None:
        return None                                       # the orbit carries no gaze point

    has_gaze = False


def default_orbit(renderer) -> Orbit:
    """The default orbit of the scene an EmbreeRenderer is open on (with its own view)."""
    return Orbit(renderer.view(), renderer.framing(),
                 source=f"default orbit ({ORBIT_DEGREES:g} degrees in {ORBIT_FRAMES} frames)")


@dataclass(frozen=True)
class SceneViews:
    """A scene's views along a path file or the default orbit: camera(k) is frame k's string."""
    path: object                # CameraPath or Orbit
    framing: Framing
    source: str                 # the path file, or the default orbit's description

    @property
    def space(self) -> str:
        return getattr(self.path, "space", "model")

    def camera(self, frame: int) -> str:
        return self.path.camera(frame, self.framing)

    def cameras(self, frames: int) -> list[str]:
        return [self.camera(k) for k in range(frames)]

    @property
    def has_gaze(self) -> bool:
        return self.path.has_gaze

    def gazes(self, frames: int, width: int, height: int) -> list[tuple[int, int] | None]:
        """The path's gaze point of frames 0 .. N-1 (None throughout without one), each checked
        inside the width x height frame (SpecError with the frame number otherwise)."""
        out = []
        for k in range(frames):
            g = self.path.gaze(k)
            if g is not None:
                try:
                    spec.check_gaze(g, width, height)
                except spec.SpecError as e:
                    raise spec.SpecError(f"{self.source}: frame {k}: {e}") from None
            out.append(g)
        return out


def scene_views(scene: str, width: int, height: int, path=None, quality: str = "fast") -> SceneViews:
    """The views of `scene` along the path file `path`, else its default orbit. The scene opens
    once with its own view, for that view and its framing (the automatic framing's fov depends
    on the frame's aspect); SpecError with one line for a bad path or scene."""
    from .embree import open_renderer
    cp = load_path(path) if path is not None else None
    r = open_renderer(scene, width, height, quality=quality)
    try:
        framing = r.framing()
        if cp is None:
            cp = default_orbit(r)
    finally:
        r.close()
    return SceneViews(cp, framing, str(path) if path is not None else cp.source)
