"""The id a scene goes by in file names, records, caches and tables."""
from __future__ import annotations

from pathlib import Path


def scene_id(scene: str) -> str:
    """A built-in scene's name as it is; a model file's stem, spaces as underscores (a path is
    anything with a folder or a suffix: built-in names have neither)."""
    scene = str(scene)
    return Path(scene).stem.replace(" ", "_") if ("/" in scene or "." in scene) else scene
