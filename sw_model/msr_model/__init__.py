"""msr_model: the contract of multi-level selective rendering (docs/spec/algorithm.md).

- spec:        the spec's rules (thresholds, tiles, grids, decision, interpolation, source codes)
- passview:    one pass as a decision rule sees it (`PassView`)
- rules:       the contract's decision rules, "patent" (default) and "lindilate" (docs/rules.md)
- golden:      vectorised whole-frame model, `select(renderer, W, H, params, rule=...)`
- tile_model:  per-tile step-by-step model in the hardware's order, `tile_schedule`, `run_tile`
- renderer:    the rendering-unit protocol and the one checked render call
- image_renderer: a picture as the rendering unit; embree: the Embree rendering unit
- cli:         `python -m msr_model select|render` (docs/spec/contracts.md)

Research code (other rules, other methods, sweeps) lives in msr_eval, on top of this API.
"""
from .spec import DEFAULT_THR, Params, SpecError, Tile, default_thresholds, frame_tiles  # noqa: F401
from .passview import PassView  # noqa: F401
from .rules import RULES, get_rule  # noqa: F401
from .renderer import Renderer, render_checked  # noqa: F401
from .golden import select, FrameResult  # noqa: F401
from .image_renderer import ImageRenderer, load_rgb, save_png  # noqa: F401
from .tile_model import tile_schedule, run_tile, select_tiled  # noqa: F401

__all__ = ["DEFAULT_THR", "Params", "SpecError", "Tile", "default_thresholds", "frame_tiles", "PassView",
           "RULES", "get_rule", "Renderer", "render_checked", "select", "FrameResult", "ImageRenderer",
           "load_rgb", "save_png", "tile_schedule", "run_tile", "select_tiled"]
