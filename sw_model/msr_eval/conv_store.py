"""Committed converged references and records (data/converged/WxH/): what lets a long
converged run resume on a new machine from the repository instead of from out/.

A heavy 1080p converged reference takes minutes (1024 samples per pixel: about 8 minutes on
the two cores), so each finished one is written here as a PNG with a small JSON beside it, and
each finished scene's records as a compact table. Both are taken back only when they are
provably the same computation:

- a reference, when the scene's 16-spp full render of this run hashes to the one recorded with
  it (the same renderer, scene, view and size: the renderer is deterministic) and its sample
  count and seed are the ones asked for;
- a record, when also its family's signature (msr_eval.sweep.SweepConfig.family_signatures:
  the family's settings, what its code computes on a probe frame (msr_eval.fingerprint) and
  the scoring set-up) is the same, so a new family (a new rule) or a changed one is computed
  alone, and a refactor that changes no output keeps everything.

Anything else is rendered or computed again and overwritten.
"""
from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
STORE = REPO / "data" / "converged"
LADDER = STORE / "ladder.json"

_FLOAT_DIGITS = 5            # significant digits of the floats in the committed tables


def frame_sha(frame: np.ndarray) -> str:
    """The hash that ties a stored item to the renderer's output (shape and pixels)."""
    h = hashlib.sha1(repr(frame.shape).encode())
    h.update(np.ascontiguousarray(frame, dtype=np.uint8).tobytes())
    return h.hexdigest()[:16]


def ladder() -> dict:
    """Per scene id, the heavy converged sample count the quick-size ladder chose (data/converged/ladder.json)."""
    if not LADDER.is_file():
        return {}
    return json.loads(LADDER.read_text()).get("scenes", {})


def ladder_grid(scene_id: str) -> int | None:
    """The antialiasing grid (sqrt of the sample count) for a scene, or None if the ladder does not know it."""
    e = ladder().get(scene_id)
    if not e:
        return None
    g = int(round(e["spp"] ** 0.5))
    if g * g != e["spp"]:
        raise ValueError(f"ladder.json: {scene_id}: spp {e['spp']} is not a square")
    return g


class Store:
    """One frame size's folder of committed references and records."""

    def __init__(self, width: int, height: int, root: Path = STORE):
        self.dir = Path(root) / f"{width}x{height}"

    def _ref(self, sid: str, mode: str):
        return self.dir / f"{sid}_{mode}_conv.png", self.dir / f"{sid}_{mode}_conv.json"

    def load_ref(self, sid: str, mode: str, full_sha: str, grid: int, seed: int):
        """(frame, info) of a committed reference of the same renderer output, grid and seed; else None."""
        from msr_model import load_rgb
        png, meta = self._ref(sid, mode)
        if not (png.is_file() and meta.is_file()):
            return None
        info = json.loads(meta.read_text())
        if info.get("full_render_sha") != full_sha or info.get("grid") != grid or \
                info.get("seeds", [None])[0] != seed:
            return None
        frame = load_rgb(png)
        if frame_sha(frame) != info.get("sha"):
            return None
        return frame, info

    def save_ref(self, sid: str, mode: str, frame: np.ndarray, info: dict, full_sha: str):
        from msr_model import save_png
        self.dir.mkdir(parents=True, exist_ok=True)
        png, meta = self._ref(sid, mode)
        save_png(png, frame)
        meta.write_text(json.dumps({**info, "full_render_sha": full_sha, "sha": frame_sha(frame)}, indent=1))

    def _records(self, sid: str, mode: str):
        return self.dir / f"{sid}_{mode}_records.json"

    def load_records(self, sid: str, mode: str, family_sigs: dict, full_sha: str) -> list:
        """The committed records of a scene and mode whose family's signature is unchanged
        (msr_eval.sweep.SweepConfig.family_signatures), for the same full render; [] if none."""
        f = self._records(sid, mode)
        if not f.is_file():
            return []
        d = json.loads(f.read_text())
        if d.get("full_render_sha") != full_sha:
            return []
        ok = {fam for fam, sig in d.get("families", {}).items() if family_sigs.get(fam) == sig}
        return [r for r in unpack(d) if r.get("family") in ok]

    def save_records(self, sid: str, mode: str, records: list, family_sigs: dict, full_sha: str, extra=None):
        self.dir.mkdir(parents=True, exist_ok=True)
        fams = {r["family"] for r in records}
        d = {"full_render_sha": full_sha, "families": {f: family_sigs[f] for f in sorted(fams)},
             **(extra or {}), **pack(records)}
        # one row a line: small diffs, readable
        rows = d.pop("rows")
        head = json.dumps(d)[:-1]
        body = ",\n".join(json.dumps(r, separators=(",", ":")) for r in rows)
        self._records(sid, mode).write_text(f'{head}, "rows": [\n{body}\n]}}\n')


def _round(v):
    if isinstance(v, float):
        return float(f"{v:.{_FLOAT_DIGITS}g}") if np.isfinite(v) else v
    if isinstance(v, dict):
        return {k: _round(x) for k, x in v.items()}
    return v


def pack(records: list) -> dict:
    """Records as a column list and rows (floats to _FLOAT_DIGITS significant digits; a
    field a record lacks is stored as "__absent__", so unpack gives back the same keys)."""
    cols = sorted({k for r in records for k in r})
    return {"columns": cols, "rows": [[_round(r.get(k)) if k in r else "__absent__" for k in cols]
                                      for r in records]}


def unpack(d: dict) -> list:
    cols = d["columns"]
    return [{k: v for k, v in zip(cols, row) if not (isinstance(v, str) and v == "__absent__")}
            for row in d["rows"]]
