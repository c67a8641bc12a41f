"""A decision rule that uses what the renderer knows: the G-buffer edge test.

With every traced pixel the rendering unit returns, beside its colour, what the primary ray
through the pixel centre hit: an id (the material's, or the triangle's) and the depth along
the camera's viewing axis (msr_render_gbuffer; `gbuffer(xs, ys)` of the Embree binding). The
tile buffer keeps them next to the colour. A decision between A and B then also looks at
their ids and depths:

    edge(A, B)  iff  id(A) != id(B)  or  |z(A) - z(B)| > depth_tol * min(z(A), z(B))

(two sky pixels, id 0 and depth +inf, are equal; sky against a surface differs by id). An
edge forces a trace: the colour test cannot see a silhouette or a material border whose two
sides happen to have close colours, which is what G-buffer edge tests in checkerboard and
variable-rate renderers catch. Rules (functions of a PassView, built per frame by
`gbuffer_rule`):

- "gbuf":          the patent's test and no edge (the rule alone);
- "gbuflindilate": lindilate with the edge test inside its base decision
                   D' = (P or Q) and not edge, then dilated across lines as lindilate does
                   (docs/rules.md), so an edge on the neighbouring line also traces.

An interpolated pixel needs an id and a depth too (later levels read it as A or B): it is
interpolated only where A and B have the same id and close depths, so it takes that id and
the depth interpolated linearly between z(A) and z(B) at m. Depths are held as IEEE half
floats (16 bits, what the hardware would store); ids as the renderer gives them (material
ids of the evaluated scenes fit in 6 bits, docs/rules.md).

Like every rule it reads only pixels of its own tile that were final before the pass (A and
B), so tiles stay independent and the pass stays order-free.
"""
from __future__ import annotations

import numpy as np

from msr_model import ImageRenderer, Params, PassView, SpecError, render_checked, select
from msr_model.rules import dilate, patent, second_difference_ok

from . import methods as M

ID_KINDS = ("material", "prim")
COMBINE = ("patent", "lindilate")
DEFAULT_DEPTH_TOL = 0.1
DEPTH_DTYPE = np.float16


class GBufferImage(ImageRenderer):
    """A picture and its G-buffer (prim, material, depth: (H, W) each) as the rendering unit:
    `render` as ImageRenderer, `gbuffer(xs, ys)` as the Embree binding's."""

    def __init__(self, image, gbuffer):
        super().__init__(image)
        prim, mat, depth = (np.asarray(a) for a in gbuffer)
        if not (prim.shape == mat.shape == depth.shape == self.image.shape[:2]):
            raise ValueError(f"G-buffer shapes {prim.shape} {mat.shape} {depth.shape} != frame {self.image.shape[:2]}")
        self.prim, self.mat, self.depth = prim, mat, depth

    def gbuffer(self, xs, ys):
        xs, ys = np.asarray(xs), np.asarray(ys)
        return self.prim[ys, xs], self.mat[ys, xs], self.depth[ys, xs]


def flat_gbuffer(height: int, width: int):
    """A G-buffer without edges (one material, one depth): for a rendering unit that has none
    (the built-in test picture); the rules then reduce to their base rule."""
    return (np.ones((height, width), np.uint32), np.ones((height, width), np.uint32),
            np.ones((height, width), np.float32))


class TileGBuffer:
    """The rendering unit seen through a render response that carries (colour, id, depth),
    and the id / depth planes the tile buffers would hold for every final pixel."""

    def __init__(self, unit, gbuffer_of, width: int, height: int, id_kind: str = "material"):
        if id_kind not in ID_KINDS:
            raise SpecError(f"id_kind must be one of {', '.join(ID_KINDS)}, got {id_kind!r}")
        self.unit, self.gbuffer_of, self.id_kind = unit, gbuffer_of, id_kind
        self.ids = np.zeros((height, width), np.uint32)
        self.depth = np.full((height, width), np.nan, DEPTH_DTYPE)     # nan: not final yet

    def render(self, xs, ys):
        xs = np.asarray(xs, dtype=np.int32).ravel()
        ys = np.asarray(ys, dtype=np.int32).ravel()
        cols = render_checked(self.unit, xs, ys)
        if xs.size:
            prim, mat, depth = self.gbuffer_of(xs, ys)
            self.ids[ys, xs] = mat if self.id_kind == "material" else prim
            self.depth[ys, xs] = np.asarray(depth, np.float32).astype(DEPTH_DTYPE)
        return cols

    # -- what a decision reads ------------------------------------------------------------
    def neighbours(self, v: PassView):
        """id and depth (float32) of A and B of every decision of the pass, each (F, M)."""
        out = []
        for pos in (v.a, v.b):
            ys, xs = (v.line, pos) if v.horizontal else (pos, v.line)
            ys, xs = np.broadcast_arrays(ys, xs)
            out += [self.ids[ys, xs], self.depth[ys, xs].astype(np.float32)]
        idA, zA, idB, zB = out
        if np.isnan(zA).any() or np.isnan(zB).any():
            raise RuntimeError("a neighbour's depth was read before the pixel was final")
        return idA, zA, idB, zB

    def store_interpolated(self, v: PassView, interp: np.ndarray, idA, zA, zB):
        """id and depth of the pixels the pass interpolates: A's id, depth linear at m."""
        ys, xs = np.broadcast_arrays(v.ys, v.xs)
        w = np.broadcast_to(((v.m - v.a) / v.gap).astype(np.float32), v.shape)
        with np.errstate(invalid="ignore"):
            z = np.where(zA == zB, zA, zA + (zB - zA) * w)   # equal (sky: inf == inf) stays as is
        self.ids[ys[interp], xs[interp]] = idA[interp]
        self.depth[ys[interp], xs[interp]] = z[interp].astype(DEPTH_DTYPE)


def edges(idA, zA, idB, zB, depth_tol: float) -> np.ndarray:
    """True where A and B lie on different surfaces: other id, or depths apart by more than
    depth_tol of the nearer one (depth_tol = inf: ids only)."""
    with np.errstate(invalid="ignore"):
        dz = np.where(zA == zB, 0.0, np.abs(zA - zB))          # inf - inf would be nan
        far = dz > depth_tol * np.minimum(zA, zB)
    return (idA != idB) | far


def gbuffer_rule(gb: TileGBuffer, combine: str = "patent", depth_tol: float = DEFAULT_DEPTH_TOL):
    """The rule "gbuf" (combine="patent") or "gbuflindilate" (combine="lindilate") over the
    tile G-buffer `gb`, as a function of a PassView for msr_model.select."""
    if combine not in COMBINE:
        raise SpecError(f"combine must be one of {', '.join(COMBINE)}, got {combine!r}")
    if not depth_tol > 0:
        raise SpecError(f"depth_tol must be > 0, got {depth_tol}")

    def rule(v: PassView) -> np.ndarray:
        idA, zA, idB, zB = gb.neighbours(v)
        edge = edges(idA, zA, idB, zB, depth_tol)
        if combine == "patent":
            ok = patent(v) & ~edge
        else:
            ok = dilate(v, (patent(v) | second_difference_ok(v)) & ~edge)
        gb.store_interpolated(v, ok, idA, zA, zB)
        return ok

    rule.__name__ = "gbuf" if combine == "patent" else "gbuflindilate"
    return rule


def multi_level_gbuffer(renderer, width: int, height: int, params: Params, combine: str = "patent",
                        id_kind: str = "material", depth_tol: float = DEFAULT_DEPTH_TOL) -> M.MethodResult:
    """The patent's multi-level method with the G-buffer rule. `renderer` must answer
    `gbuffer(xs, ys)` too (the Embree binding, or GBufferImage)."""
    if not callable(getattr(renderer, "gbuffer", None)):
        raise SpecError("the G-buffer rule needs a rendering unit with gbuffer(xs, ys)")
    c = M.CountingRenderer(renderer, width, height)
    gb = TileGBuffer(c, renderer.gbuffer, width, height, id_kind)
    rule = gbuffer_rule(gb, combine, depth_tol)
    r = select(gb, width, height, params, rule=rule)
    settings = {**params.as_dict(), "rule": rule.__name__, "id": id_kind, "depth_tol": depth_tol}
    return M.MethodResult(r.frame, r.source, c.requests, f"multi_{rule.__name__}", settings)


# --- in the evaluation sweep (msr_eval.sweep) ----------------------------------------------

METHOD = "msr_eval.gbuffer_rule:multi_level_gbuffer"      # a Setting's method name
# family -> the rule it combines with; T=16, L=3 like the families it is compared with
SWEEP_FAMILIES = {"multi_L3_T16_gbuf": "patent", "multi_L3_T16_gbuflindilate": "lindilate"}


def needs_gbuffer(setting) -> bool:
    return getattr(setting, "method", None) == METHOD


def rendering_unit(ref, gbuffer=None):
    """The cached reference as the rendering unit, with its G-buffer when there is one."""
    return ImageRenderer(ref) if gbuffer is None else GBufferImage(ref, gbuffer)


def scene_gbuffer(backend: str, scene: str, width: int, height: int, cache=None, key: str = ""):
    """(prim, material, depth) of every pixel of a scene (the primary ray's hit, the same in
    both renderer modes), cached as .npz under `cache` with `key` in its name; a flat
    G-buffer for the test-picture backend."""
    if backend == "image":
        return flat_gbuffer(height, width)
    from pathlib import Path
    path = Path(cache) / f"gbuffer_{key}.npz" if cache else None
    if path is not None and path.is_file():
        with np.load(path) as z:
            return z["prim"], z["mat"], z["depth"]
    from msr_model import embree
    with embree.open_renderer(scene, width, height, quality="fast") as r:
        prim, mat, depth = r.gbuffer_full()
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        np.savez_compressed(path, prim=prim, mat=mat, depth=depth)
    return prim, mat, depth
