"""Ray budget: the closed-loop rate controller of docs/budget.md, in integers, bit for bit.

A budget B (traced pixels per frame; 0 = off) makes the tile generator scale every tile's
per-level thresholds by one factor per tile row. The controller's scale u is unsigned fixed
point, 1.0 = 256, in [U_MIN, U_MAX] = [45, 1448] (a first frame's rows down to U_MIN_FIRST = 32);
the thresholds take its square,

    m = (u * u + 128) >> 8                               # once per tile row, 8..8190
    thr_k'' = min(255, (thr_k' * m + d) >> 8)            # per tile; thr_k' the foveated threshold

because a tile row's traced pixels above its initial grid fall about as 1 / sqrt(threshold):
in u they fall as 1 / u, which the law below assumes. d = thr_dither(tx, ty), the bit-reversed
(tx + ty) mod 256, in place of the rounding's 128: a row's mean threshold follows thr' * m / 256
instead of stepping between integers (small thresholds made a row's count jump at one u).

A budget frame dispatches its tile rows interleaved (row_order): rows 0, S, 2S, .., then 1,
1 + S, .. (S = 2^(msb(nty) - 2), at least 1), so the rows the law has seen are spread over the
frame. The law runs over positions j in that order: positions 0 and 1 take the seed u_0
(register SCALE_INIT, 0 read as 1.0); position j >= 2 takes the scale the controller computed
when position j - 2 was finished, and is handed out only after that (so nothing depends on
which engine was faster). After each finished position j:

    a_j = max(c_j - g_j, p_j >> FLOOR_SHIFT) * u_j    # the row's activity: traced above its
                                       # initial grid (at least a floor), times u
    N  += a_j;  C += c_j;  P += p_j    # activity, traced and pixels of the finished rows
    X   = B - C - G_rem                # budget left above the initial grid of the rows to come
    q   = ((N + N0) * Q) // ((P + P0) * X)           # first frame: the rows seen so far, extrapolated
    q   = (A_prev - A_done) // (u_0 * X)               # seeded: the previous frame's row activities
    u_{j+2} = clamp(min(max(q, fall(u_{j+1})), 2 u_{j+1}))  # X <= 0: U_MAX + 1; at most 2x a row
    fall(u) = u >> 1 (first frame), u - (u >> 2) (seeded)     # at most 1/2 or 1/4 down a row

A seeded frame's scale falls by at most a quarter per row: it starts near where the previous
frame settled, so a large step down is the model's error more than the content's (below about
u = 55 some scenes' rows trace far more than 1 / u^2 predicts, and one step too far at the
frame's end overshoots the budget with no row left to make up for it; docs/budget.md, "The
seeded fall limit").

clamp(v) = min(U_MAX, max(lo, v)) with lo = U_MIN (45), except in a first frame once row j + 1
already runs at U_MIN or below: then lo = U_MIN_FIRST (32). A first frame knows nothing of the
rows below it, and the bottom rows of an object-centred scene (floor, background) cannot trace
20 % even at 45; below 45 the level thresholds fall by a whole step (thr'' rounds to 0), which
the 1 / u model does not see, so the scale takes that step only from a row already at the bound.
Seeded frames, u_0 and SCALE_OUT keep [45, 1448], where the activity model that seeds the next
frame holds (docs/budget.md, "The first frame's range").

with Q the pixels and G_rem the initial grid of the rows not finished, N0 = ((B - G) * u_0) >>
PRIOR_SHIFT and P0 = (W * H) >> PRIOR_SHIFT (the seed's guess "u_0 traces B", weighted as that
part of a frame). Seeded, from the previous frame's activity a'_k and scale u'_k of every
position (the activity memory; profiles outside the controller are per tile row, top to
bottom): A_prev = sum of a'_k * w(u'_k, u_0), w = min(u'_k, u_0) (seed_weight), and A_done its
part over positions <= j; a row that ran below the seed is counted as if its excess fell as
1 / u^2 between its own scale and the seed (docs/budget.md, "The seeded law"). After the last
row SCALE_OUT = clamp(N // (B - G)):
the one scale that, on this frame's activity, traces B; it and the activity memory seed the next
frame.

The floor (p_j >> FLOOR_SHIFT, 1/128 of the row's pixels): a row that traced only its grid at a
large scale would otherwise read as a row that never traces at any scale; with the floor the law
keeps some budget for it and a sequence of frames at a small budget settles instead of swinging
(docs/budget.md, "The activity floor").

A budget below the frame's initial grid (`grid_count`) cannot be met: START refuses it
(`BudgetRefused`; STATUS.ERROR ERR_BUDGET in the hardware).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import spec
from .golden import FrameResult, frame_stats, select, select_region, threshold_maps
from .rules import DEFAULT_RULE, get_rule
from .spec import Params

SCALE_FRAC = 8                     # fraction bits of u and m: 1.0 = 256
SCALE_ONE = 1 << SCALE_FRAC
U_MIN = 45                         # m = 8: thresholds x 1/32 (u_0 and every seeded frame)
U_MIN_FIRST = 32                   # m = 4: thresholds x 1/64 (a first frame's rows, from a row at U_MIN)
U_MAX = 1448                       # m = 8190: thresholds x 32 (u: 11 bits)
PRIOR_SHIFT = 6                    # default weight of the seed's guess: 1/64 of a frame
PRIOR_SHIFT_MAX = 7
AUTO_PRIOR_SHIFT = 3               # the driver's PRIOR_SHIFT beside a seed from budget_seed (1/8 frame)
FLOOR_SHIFT = 7                    # activity floor of a row: its pixels >> 7 (docs/budget.md)
BUDGET_MAX = (1 << 24) - 1         # BUDGET register: 24 bits (W * H <= 2^24)
ERR_BUDGET = 14                    # STATUS.ERROR: budget below the frame's initial grid
ERR_PROFILE = 15                   # STATUS.ERROR: seeded from a profile of another tile-row count


def parse_budget(text) -> tuple[str, object]:
    """A budget as a user writes it: `N` (pixels) or `P%` (of the frame, P a decimal number
    0..100): ('px', N) or ('pct', P as a Fraction). ValueError with the reason otherwise."""
    from fractions import Fraction
    t = str(text).strip()
    try:
        if t.endswith("%"):
            pct = Fraction(t[:-1].strip())
            if not 0 <= pct <= 100:
                raise ValueError(f"budget {text}: a percentage must be 0..100")
            return ("pct", pct)
        n = int(t, 10)
    except ZeroDivisionError:
        raise ValueError(f"budget must be a pixel count or a percentage like 10%, got {text!r}") from None
    except ValueError as e:
        if "percentage must" in str(e):
            raise
        raise ValueError(f"budget must be a pixel count or a percentage like 10%, got {text!r}") from None
    if not 0 <= n <= BUDGET_MAX:
        raise ValueError(f"budget {n} outside 0..{BUDGET_MAX}")
    return ("px", n)


def budget_pixels(parsed, width: int, height: int) -> int:
    """The BUDGET register value of a parsed budget for a W x H frame (a percentage rounds
    down); ValueError when a pixel count is more than the frame."""
    kind, v = parsed
    pixels = int(v * width * height // 100) if kind == "pct" else int(v)
    if kind == "px" and pixels > width * height:
        raise ValueError(f"budget {pixels} is more than the frame's {width * height} pixels")
    return pixels


class BudgetRefused(spec.SpecError):
    """START refuses a budget below the frame's initial grid (it cannot be met)."""


def thr_multiplier(u: int) -> int:
    """m = (u * u + 128) >> 8: the row's threshold multiplier (1.0 = 256)."""
    return (int(u) * int(u) + (SCALE_ONE >> 1)) >> SCALE_FRAC


def scale_threshold(thr, m: int, dither=SCALE_ONE >> 1):
    """thr'' = min(255, (thr * m + d) >> 8): one 8 x 13-bit product at the descriptor stage. d is
    the tile's dither (`thr_dither`) in a budget frame, 128 (rounding) elsewhere; with m = 256
    thr'' = thr for any d in 0..255."""
    out = np.minimum(255, (np.asarray(thr, dtype=np.int64) * int(m) + np.asarray(dither, dtype=np.int64))
                     >> SCALE_FRAC)
    return int(out) if np.ndim(out) == 0 else out.astype(np.int32)


def thr_dither(tx: int, ty: int) -> int:
    """The threshold dither of tile (tx, ty): (tx + ty) mod 256 with its 8 bits reversed. Its mean
    over 256 neighbouring tiles is 127.5, the rounding's 128 less a half: a row's mean threshold
    then follows thr * m / 256 smoothly instead of stepping between integers (docs/budget.md
    section 1)."""
    v = (int(tx) + int(ty)) & 0xFF
    return int(f"{v:08b}"[::-1], 2)


def row_dither(ty: int, ntx: int) -> np.ndarray:
    """thr_dither of the tiles of tile row ty, as a (1, ntx) array."""
    return np.array([thr_dither(tx, ty) for tx in range(ntx)], dtype=np.int64)[None, :]


def clamp_scale(u: int, lo: int = U_MIN) -> int:
    """clamp(v) of the law: [lo, U_MAX]; lo = U_MIN, or U_MIN_FIRST (Controller.scale_floor)."""
    return min(U_MAX, max(lo, int(u)))


def seed_weight(u_prev: int, u0: int) -> int:
    """The seed pass's factor w of a row that ran at u_prev, for a frame seeded at u0 (b = a' * w):
    min(u_prev, u0). Below u0 the row's excess is taken to fall as 1 / u^2 up to u0, above it
    as 1 / u (with the rows interleaved, a first frame's scales do not stray far above the seed,
    and a heavier weight above it measures the same; docs/budget.md section 4)."""
    return min(int(u_prev), int(u0))


def grid_axis(n: int, stride: int) -> int:
    """|G0(n)|: ceil(n / S) positions, plus the far corner n - 1 when (n - 1) mod S != 0."""
    return (n + stride - 1) // stride + (1 if (n - 1) % stride else 0)


def grid_line(n_total: int, tile: int, stride: int) -> int:
    """Sum of |G0(extent)| over the tiles of one axis: full tiles and the last, shorter one."""
    full, rest = divmod(n_total, tile)
    return full * grid_axis(tile, stride) + (grid_axis(rest, stride) if rest else 0)


def row_grid(width: int, h: int, params: Params) -> int:
    """g_r: the initial samples of a tile row of height h (closed form of spec section 2)."""
    return grid_line(width, params.tile, params.stride) * grid_axis(h, params.stride)


def grid_count(width: int, height: int, params: Params) -> int:
    """G: the frame's initial samples, the least any budget can trace."""
    return grid_line(width, params.tile, params.stride) * grid_line(height, params.tile, params.stride)


def row_stride_log2(nty: int) -> int:
    """log2 of the dispatch stride S of a budget frame: the largest power of two with 4 * S <= nty
    (at least 1): msb(nty) - 2, floored at 0. Every phase then holds at least four tile rows."""
    return max(int(nty).bit_length() - 3, 0)


def next_row(r: int, lgs: int, nty: int) -> int:
    """The tile row dispatched after row r in a budget frame: r + S within its phase (r mod S),
    else the first row of the next phase, (r mod S) + 1 (docs/budget.md section 2)."""
    s = 1 << lgs
    return r + s if r + s < nty else (r & (s - 1)) + 1


def row_order(nty: int) -> list[int]:
    """The tile rows of a budget frame in dispatch order: rows 0, S, 2S, .., then 1, 1 + S, ..
    up to phase S - 1 (S = 2 ** row_stride_log2(nty); S = 1, raster order, below 8 rows)."""
    lgs, out, r = row_stride_log2(nty), [], 0
    for _ in range(nty):
        out.append(r)
        r = next_row(r, lgs, nty)
    return out


SEED_C = 33.4                      # budget_seed's constant (fitted at 960x540 and 640x480)
SEED_PIXELS_REF = 1920 * 1080      # budget_seed's reference frame size
SEED_THR_REF = 16.0                # budget_seed's reference threshold (geometric mean of 8, 16, 32)


def budget_seed(width: int, height: int, budget: int, params: Params, c: float = SEED_C) -> int:
    """A first frame's SCALE_INIT for a driver with no previous frame, from the frame's size, the
    budget and the thresholds (docs/budget.md section 7, "The first frame's seed"):

        u_0 = clamp(round(c * sqrt(W * H / (B' - G)) * (W0 * H0 / (W * H)) ** (1/4)
                            * sqrt(thr_ref / thr_g)))

    B' = min(B, W * H); W0 * H0 = 1920 * 1080; thr_g the geometric mean of the levels' thresholds,
    thr_ref = 16 (that of 8, 16, 32). The square root of the budget's share above the grid is the
    shape of the scales the evaluation's sequences settle at; a smaller frame of the same view has
    more colour change per pixel (the fourth root of the pixel count, measured: the settled scales
    of 960x540 and 640x480 need 1.41 and 1.61 times the constant of 1080p without it); thresholds
    k times larger settle at a scale sqrt(k) smaller (m = u^2 multiplies them). c = 33.4 is
    fitted on the settled scales of 960x540 and 640x480 (1080p alone gives 34.8). A driver's
    choice: the hardware reads SCALE_INIT as written."""
    spare = min(int(budget), width * height) - grid_count(width, height, params)
    if spare <= 0:
        return U_MAX
    thr_g = float(np.exp(np.mean(np.log(np.maximum(np.asarray(params.thr, dtype=np.float64), 1.0)))))
    u = c * (width * height / spare) ** 0.5 * (SEED_PIXELS_REF / (width * height)) ** 0.25 \
        * (SEED_THR_REF / thr_g) ** 0.5
    return clamp_scale(int(u + 0.5))


def first_frame_config(width: int, height: int, budget: int, params: Params) -> "BudgetConfig":
    """The driver's registers for a first budget frame, with no previous frame to seed it:
    SCALE_INIT = budget_seed(...) and PRIOR_SHIFT = AUTO_PRIOR_SHIFT (3: a seed fitted to the
    budget is worth more than the reset value 1.0, so the law counts its guess as an eighth of a
    frame instead of a 64th). What the CLI (`select --budget` without --scale-init or
    --budget-prev), `make sim BUDGET=` and eval_budget.py write; measured in docs/budget.md
    section 7, "The first frame's seed"."""
    return BudgetConfig(int(budget), scale_init=budget_seed(width, height, budget, params),
                        prior_shift=AUTO_PRIOR_SHIFT)


@dataclass(frozen=True)
class BudgetConfig:
    """The budget registers: BUDGET (pixels, 0 = off), SCALE_INIT (seed u_0, 1.0 = 256, 0 read
    as 1.0), PRIOR_SHIFT (weight of the seed's guess: a frame >> PRIOR_SHIFT) and, for a seeded
    frame, the previous frame's activity and scale per tile row (the activity memory; None =
    first frame)."""

    budget: int = 0
    scale_init: int = SCALE_ONE
    prior_shift: int = PRIOR_SHIFT
    profile: tuple[int, ...] | None = None
    profile_scales: tuple[int, ...] | None = None

    def __post_init__(self):
        if not 0 <= int(self.budget) <= BUDGET_MAX:
            raise spec.SpecError(f"budget {self.budget} outside 0..{BUDGET_MAX}")
        if not 0 <= int(self.scale_init) <= U_MAX:
            raise spec.SpecError(f"scale_init {self.scale_init} outside 0..{U_MAX}")
        if not 0 <= int(self.prior_shift) <= PRIOR_SHIFT_MAX:
            raise spec.SpecError(f"prior_shift {self.prior_shift} outside 0..{PRIOR_SHIFT_MAX}")
        if (self.profile is None) != (self.profile_scales is None):
            raise spec.SpecError("a seeded frame needs the previous frame's activity and scale per row")
        if self.profile is not None:
            if len(self.profile) != len(self.profile_scales):
                raise spec.SpecError(f"activity profile of {len(self.profile)} rows, scales of "
                                     f"{len(self.profile_scales)}")
            if any(not U_MIN_FIRST <= int(u) <= U_MAX for u in self.profile_scales):
                raise spec.SpecError(f"profile scales must lie in {U_MIN_FIRST}..{U_MAX}")
            if any(int(a) < 0 or int(a) % int(u) or int(a) // int(u) >= 1 << 18
                   for a, u in zip(self.profile, self.profile_scales)):
                raise spec.SpecError("a profile activity is its row's excess (< 2^18) times its "
                                     "scale: max(c - g, p >> 7) * u")

    @property
    def seed(self) -> int:
        """u_0, the scale of rows 0 and 1: SCALE_INIT clamped to [U_MIN, U_MAX], 0 read as 1.0."""
        return clamp_scale(self.scale_init or SCALE_ONE)


@dataclass
class Controller:
    """The controller over one frame (docs/budget.md, "State"): feed it every finished row's
    traced count in dispatch order (`finish_row`; `order[j]` is the tile row at position j);
    `scales[j]` is position j's u once it is known. Profiles (cfg.profile, `activity`) are per
    tile row, top to bottom; the law and the activity memory run over positions."""

    width: int
    height: int
    params: Params
    cfg: BudgetConfig
    n_act: int = 0                 # N: activity of the finished rows
    traced: int = 0                # C
    pixels: int = 0                # P
    grid_done: int = 0             # initial grid of the finished rows
    prof_done: int = 0             # A_done: the previous frame's activity over the finished rows
    rows_done: int = 0
    scales: list[int] = field(default_factory=list)      # u of every position, as handed out
    act_pos: list[int] = field(default_factory=list)     # a_j of every finished position
    scale_out: int | None = None

    def __post_init__(self):
        self.total = self.width * self.height
        self.grid = grid_count(self.width, self.height, self.params)
        self.budget = min(int(self.cfg.budget), self.total)     # BUDGET saturates at W * H
        if self.budget < self.grid:
            raise BudgetRefused(f"budget {self.budget} below the {self.grid} pixels of the initial grid "
                                f"(W {self.width}, H {self.height}, T {self.params.tile}, "
                                f"L {self.params.levels}): status error {ERR_BUDGET}")
        self.nty = spec.tile_counts(self.width, self.height, self.params.tile)[1]
        self.order = row_order(self.nty)
        self.profile = None if self.cfg.profile is None else [int(a) for a in self.cfg.profile]
        if self.profile is not None and len(self.profile) != self.nty:
            raise BudgetRefused(f"activity profile of {len(self.profile)} tile rows, the frame has "
                                f"{self.nty}: status error {ERR_PROFILE}")
        u0 = self.cfg.seed
        # The seeded law's words by position: a' * w(u', u0), i.e. e' * u' * w(u', u0) with e'
        # the row's excess (floored) of the previous frame: what the START pass writes into the
        # memory (which the hardware holds by position).
        self.prof_words = None if self.profile is None else [
            self.profile[r] * seed_weight(int(self.cfg.profile_scales[r]), u0) for r in self.order]
        self.prof_total = sum(self.prof_words) if self.profile is not None else 0
        self.prior_n = ((self.budget - self.grid) * u0) >> self.cfg.prior_shift
        self.prior_p = self.total >> self.cfg.prior_shift
        self.scales = [u0] * min(2, self.nty)

    def row_height(self, j: int) -> int:
        """The pixel height of the tile row at position j."""
        return min(self.params.tile, self.height - self.order[j] * self.params.tile)

    def row_floor(self, j: int) -> int:
        """Position j's activity floor in pixels: p_j >> FLOOR_SHIFT."""
        return (self.width * self.row_height(j)) >> FLOOR_SHIFT

    @property
    def activity(self) -> list[int]:
        """a_j of every finished tile row, top to bottom (the profile of the next frame)."""
        out = [0] * len(self.act_pos)
        for j, a in enumerate(self.act_pos):
            out[self.order[j]] = a
        return out

    def scale_of_rows(self) -> list[int]:
        """u of every tile row, top to bottom (every position's scale must be known)."""
        out = [0] * self.nty
        for j, u in enumerate(self.scales):
            out[self.order[j]] = u
        return out

    def finish_row(self, traced: int) -> None:
        """Position `rows_done` (tile row order[rows_done]) is finished with `traced` pixels of
        source code < 16: update, and set the scale of position rows_done + 2, or SCALE_OUT after
        the last."""
        j = self.rows_done
        h = self.row_height(j)
        g, p = row_grid(self.width, h, self.params), self.width * h
        if not g <= traced <= p:
            raise ValueError(f"row {j}: traced {traced} outside {g}..{p}")
        a = max(traced - g, self.row_floor(j)) * self.scales[j]
        self.act_pos.append(a)
        self.n_act += a
        self.traced += traced
        self.pixels += p
        self.grid_done += g
        if self.profile is not None:
            self.prof_done += self.prof_words[j]
        self.rows_done += 1
        if self.rows_done == self.nty:
            spare = self.budget - self.grid
            self.scale_out = U_MAX if spare <= 0 else clamp_scale(self.n_act // spare)
        elif j + 2 < self.nty:
            u1 = self.scales[j + 1]
            self.scales.append(clamp_scale(min(max(self.quotient(), self.scale_fall(u1)), u1 << 1),
                                           self.scale_floor(j)))

    def scale_fall(self, u1: int) -> int:
        """The least u_{j+2} before the clamp: u_{j+1} >> 1 in a first frame (a scale at most halves
        per row), u_{j+1} - (u_{j+1} >> 2) in a seeded frame (at most a quarter down)."""
        return u1 - (u1 >> 2) if self.profile is not None else u1 >> 1

    def scale_floor(self, j: int) -> int:
        """lo of the clamp of u_{j+2}: U_MIN_FIRST in a first frame once u_{j+1} <= U_MIN."""
        first = self.profile is None
        return U_MIN_FIRST if first and self.scales[j + 1] <= U_MIN else U_MIN

    def quotient(self) -> int:
        """q of the law: the scale at which the rows to come are expected to trace the budget left
        above their grid; U_MAX + 1 when nothing is left."""
        x = self.budget - self.traced - (self.grid - self.grid_done)
        if x <= 0:
            return U_MAX + 1
        if self.profile is not None:
            return max(self.prof_total - self.prof_done, 0) // (self.cfg.seed * x)
        q = self.total - self.pixels
        return ((self.n_act + self.prior_n) * q) // ((self.pixels + self.prior_p) * x)


def select_budget(renderer, width: int, height: int, params: Params, cfg: BudgetConfig,
                  rule=DEFAULT_RULE, fixed_scale: int | None = None, fixed_dither: bool = False) -> FrameResult:
    """The selective render with a ray budget: tile rows in dispatch order, each with its scale
    and every tile's thresholds dithered. With cfg.budget == 0 this is golden.select(), bit for
    bit. `fixed_scale` (a u, for the evaluation) runs every row at that one scale without the
    controller: fixed thresholds, rounded as a user's (or dithered as a budget frame's, with
    `fixed_dither`)."""
    spec.check_frame_size(width, height)
    spec.check_gaze(params.gaze, width, height)
    if cfg.budget == 0 and fixed_scale is None:
        return select(renderer, width, height, params, rule=rule)
    rule_name, decide = get_rule(rule)
    T = params.tile
    ntx, nty = spec.tile_counts(width, height, T)
    thr_maps = threshold_maps(params, ntx, nty)
    ctl = Controller(width, height, params, cfg) if fixed_scale is None else None
    frame = np.zeros((height, width, 3), dtype=np.uint8)
    source = np.full((height, width), spec.SRC_UNSET, dtype=np.uint8)
    per_level: dict = {}
    row_traced = [0] * nty
    # A budget frame dispatches its tile rows interleaved (row_order); fixed thresholds do not
    # depend on the order (every row at one scale) and take raster order.
    for j, r in enumerate(range(nty) if ctl is None else ctl.order):
        y0, h = r * T, min(T, height - r * T)
        m = thr_multiplier(fixed_scale if ctl is None else ctl.scales[j])
        d = row_dither(r, ntx) if ctl is not None or fixed_dither else SCALE_ONE >> 1
        band_thr = [scale_threshold(t[r:r + 1], m, d) for t in thr_maps]
        f, s, counts = select_region(_Band(renderer, width, y0, h), width, h, params, decide, band_thr)
        frame[y0:y0 + h], source[y0:y0 + h] = f, s
        for key, v in counts.items():
            per_level[key] = per_level.get(key, 0) + v
        row_traced[r] = int((s < spec.SRC_INTERP_BASE).sum())
        if ctl is not None:
            ctl.finish_row(row_traced[r])
    stats = frame_stats(source, params, per_level, rule_name)
    stats["budget"] = 0 if ctl is None else ctl.budget
    scales = [fixed_scale] * nty if ctl is None else ctl.scale_of_rows()
    stats["budget_control"] = {
        "scale_init": None if ctl is None else cfg.seed,
        "prior_shift": None if ctl is None else cfg.prior_shift,
        "seeded": ctl is not None and ctl.profile is not None,
        "fixed_scale": fixed_scale,
        "grid": grid_count(width, height, params),
        "scale_per_row": scales,
        "thr_multiplier_per_row": [thr_multiplier(u) for u in scales],
        "traced_per_row": row_traced,
        "activity_per_row": None if ctl is None else ctl.activity,
        "scale_out": None if ctl is None else ctl.scale_out,
        "budget_error": None if ctl is None else (stats["traced"] - ctl.budget) / ctl.budget,
    }
    return FrameResult(frame, source, params, stats)


class _Band:
    """One tile row of the rendering unit as a frame of its own (tiles never read each other)."""

    def __init__(self, renderer, width: int, y0: int, h: int):
        self.renderer, self.width, self.height, self.y0 = renderer, width, h, y0

    def render(self, xs, ys):
        return self.renderer.render(np.asarray(xs), np.asarray(ys) + self.y0)
