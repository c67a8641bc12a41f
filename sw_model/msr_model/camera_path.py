"""Camera paths (docs/spec/contracts.md, third round): a sequence's view per frame.

A path file is JSON, {"keys": [{"frame": 0, "eye": [x, y, z], "target": [x, y, z], "fov": 40},
...]}: frame numbers ascending, eye and target in model units, the vertical field of view in
degrees; between two keys each value is interpolated linearly in the frame number, before the
first key the first key holds, after the last the last. Up is +Y (as for --camera). Fields
other than these may be present and are ignored.

`CameraPath.camera(k)` is frame k's view as the renderer's camera string
"EX,EY,EZ,TX,TY,TZ,FOV" (msr_model.embree.check_camera), written with 17 significant digits so
the renderer reads back exactly the interpolated doubles: a path at a given frame renders the
same pixels on every run.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

from . import spec


@dataclass(frozen=True)
class Key:
    frame: int
    eye: tuple[float, float, float]
    target: tuple[float, float, float]
    fov: float


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

    def __init__(self, keys: list[Key], source: str = "camera path"):
        if not keys:
            raise spec.SpecError(f"{source}: no keys")
        self.keys, self.source = keys, source

    @classmethod
    def from_dict(cls, data, source: str = "camera path") -> "CameraPath":
        if not isinstance(data, dict) or not isinstance(data.get("keys"), list):
            raise spec.SpecError(f'{source}: expected {{"keys": [...]}}')
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
            keys.append(Key(frame, eye, target, float(fov)))
        return cls(keys, source)

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

    def camera(self, frame: int) -> str:
        """Frame `frame`'s view as the renderer's camera string (exact doubles)."""
        eye, target, fov = self.at(frame)
        if eye == target:
            raise spec.SpecError(f"{self.source}: at frame {frame} eye and target are the same point")
        return ",".join(format(v, ".17g") for v in (*eye, *target, fov))

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
