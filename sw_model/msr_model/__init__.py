"""msr_model: golden model of multi-level selective rendering (../shared/spec/algorithm.md).

- spec:        the spec's rules (thresholds, grids, decision, interpolation, source codes)
- golden:      vectorised whole-frame model, `select(renderer, W, H, params)`
- tile_model:  per-tile step-by-step model in the hardware's order, `tile_schedule`, `run_tile`
- image_renderer: a picture as the rendering unit
"""
from .spec import Params, SpecError  # noqa: F401
from .golden import select, FrameResult  # noqa: F401
from .image_renderer import ImageRenderer, load_rgb, save_png  # noqa: F401
from .tile_model import tile_schedule, run_tile, select_tiled  # noqa: F401

__all__ = ["Params", "SpecError", "select", "FrameResult", "ImageRenderer", "load_rgb",
           "save_png", "tile_schedule", "run_tile", "select_tiled"]
