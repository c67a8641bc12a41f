"""Decision rules beyond the patent, behind a mode flag (issue 7). golden.select stays the
bit-exact contract with the RTL; `select_rule(..., rule="patent")` gives exactly its pixels.

Same passes, same positions, same tile independence (a rule reads only pixels of its own
tile that were final before the pass began), only the interpolate-or-trace test changes:

- "patent": d * n_k < thr_k' * g, d the colour difference of the two neighbours A, B.
- "dilate": the patent's test, and a gap is also traced when the same gap on the previous
  or the next fixed line of the pass fails it (same tile; the neighbouring row of G_y(k-1) in the H
  pass, the neighbouring column of G_x(k) in the V pass). Edges are
  continuous, so a detection next door says a feature may have slipped between this pair's
  two samples (a thin line, a corner). In hardware: the decision of the next line is known
  one line ahead (its two samples are final before the pass), so it costs two more
  tile-buffer reads and one line of decision bits per decision.
- "linear": also interpolate when the four samples A', A, B, B' on the line (A' at a - g,
  B' at b + g, both final, inside the tile) lie on a straight line within the threshold:
  max(|A' - 2A + B|, |A - 2B + B'|) * n_k < thr_k' * g. Linear interpolation is exact on a
  linear ramp, so a smooth gradient steeper than the threshold no longer forces traces,
  while an edge between A and B still gives a second difference of about |B - A|. Costs two
  more tile-buffer reads per decision.
- "lindilate": the "linear" test, then "dilate" applied to its failures.
- "diag": the patent's test, and for a centre pixel (new on both axes; decided in the V pass
  from two H-pass results) also the four diagonal corners (a_x, a_y), (b_x, a_y), (a_x, b_y),
  (b_x, b_y) that claim 8 lets it read: their colour range must pass the same test.
"""
from __future__ import annotations

import numpy as np

from . import spec
from .golden import FrameResult, frame_axis, threshold_maps
from .spec import Params

RULES = ("patent", "dilate", "linear", "lindilate", "diag")


def _range_diff(cols, metric):
    """Colour range of a stack of colours (first axis = the samples), as the spec metric."""
    cols = np.asarray(cols, dtype=np.int32)
    rng = cols.max(axis=0) - cols.min(axis=0)
    return rng.max(axis=-1) if metric == "max" else rng.sum(axis=-1)


def _linear_ok(at, a, b, shape, known_line, n_line, T, A, B, thr_pos, g, n, metric):
    """The second-difference test of rule "linear" (False where no outer sample exists)."""
    pa, pb = a - (b - a), b + (b - a)              # outer samples a - g and b + g
    va = (pa >= 0) & (pa // T == a // T) & known_line[np.clip(pa, 0, n_line - 1)]
    vb = (pb < n_line) & (pb // T == b // T) & known_line[np.clip(pb, 0, n_line - 1)]
    Ai, Bi = A.astype(np.int32), B.astype(np.int32)
    c2 = np.zeros(shape, np.int32)
    for valid, outer, near, far in ((va, pa, Ai, Bi), (vb, pb, Bi, Ai)):
        if valid.any():
            P = at(np.clip(outer, 0, n_line - 1)[None, :]).astype(np.int32)
            c = np.abs(P - 2 * near + far)
            c = c.max(-1) if metric == "max" else c.sum(-1)
            c2 = np.where(valid[None, :], np.maximum(c2, c), c2)
    return (va | vb)[None, :] & spec.interpolate_ok(c2, thr_pos, g, n)


def select_rule(renderer, width: int, height: int, params: Params, rule: str = "patent") -> FrameResult:
    """golden.select with a choice of decision rule; rule="patent" is golden.select."""
    if rule not in RULES:
        raise spec.SpecError(f"rule must be one of {RULES}, got {rule!r}")
    spec.check_frame_size(width, height)
    T, L = params.tile, params.levels
    ntx, nty = spec.tile_counts(width, height, T)
    ax, ay = frame_axis(width, T, L), frame_axis(height, T, L)
    thr_maps = threshold_maps(params, ntx, nty)
    # known[k][p]: position p (global) is in G(k) of its tile on that axis
    kx = [np.isin(np.arange(width), g) for g in ax.known]
    ky = [np.isin(np.arange(height), g) for g in ay.known]

    frame = np.zeros((height, width, 3), dtype=np.uint8)
    source = np.full((height, width), spec.SRC_UNSET, dtype=np.uint8)
    counts = {"initial": 0}

    def trace(xs, ys):
        cols = np.asarray(renderer.render(xs.astype(np.int32), ys.astype(np.int32)), dtype=np.uint8)
        if cols.shape != (len(xs), 3):
            raise RuntimeError(f"renderer returned shape {cols.shape} for {len(xs)} pixels")
        return cols

    yy, xx = np.meshgrid(ay.known[0], ax.known[0], indexing="ij")
    frame[yy, xx] = trace(xx.ravel(), yy.ravel()).reshape(yy.shape + (3,))
    source[yy, xx] = spec.SRC_INITIAL
    counts["initial"] = yy.size

    use_lin = rule in ("linear", "lindilate")
    use_dilate = rule in ("dilate", "lindilate")
    use_diag = rule == "diag"
    for k in range(1, L + 1):
        n = params.nominal_gap(k)
        thr = thr_maps[k - 1]
        for horizontal in (True, False):
            if horizontal:
                fixed, ftile = ay.known[k - 1], ay.known_tile[k - 1]
                m, a, b, mtile = ax.new_m[k - 1], ax.new_a[k - 1], ax.new_b[k - 1], ax.new_tile[k - 1]
                known_line, n_line = kx[k - 1], width
            else:
                fixed, ftile = ax.known[k], ax.known_tile[k]
                m, a, b, mtile = ay.new_m[k - 1], ay.new_a[k - 1], ay.new_b[k - 1], ay.new_tile[k - 1]
                known_line, n_line = ky[k - 1], height
            if len(m) == 0 or len(fixed) == 0:
                continue
            F = fixed[:, None]                     # decisions shaped (fixed lines, new positions)
            Mm, Aa, Bb = m[None, :], a[None, :], b[None, :]

            def at(line_pos, fixed_pos=F):
                """Colours at (line position, fixed line) for this pass's orientation."""
                return frame[fixed_pos, line_pos] if horizontal else frame[line_pos, fixed_pos]

            A, B = at(Aa), at(Bb)
            g = Bb - Aa
            if horizontal:
                thr_pos = thr[ftile[:, None], mtile[None, :]]
            else:
                thr_pos = thr[mtile[None, :], ftile[:, None]]
            d = spec.color_diff(A, B, params.metric)
            ok = spec.interpolate_ok(d, thr_pos, g, n)
            if use_lin:
                ok |= _linear_ok(at, a, b, d.shape, known_line, n_line, T, A, B, thr_pos, g, n, params.metric)
            if use_dilate:
                # trace a gap if the test fails on the previous or next fixed line of the
                # same tile (computed from samples final before the pass)
                bad = ~ok
                same = (ftile[1:] == ftile[:-1])[:, None]
                ok[1:] &= ~(bad[:-1] & same)
                ok[:-1] &= ~(bad[1:] & same)
            if use_diag and not horizontal:
                # centre pixels: x new at level k (not in G_x(k-1)); corners from G_x(k-1)
                x = fixed
                centre = ~kx[k - 1][x]
                if centre.any():
                    # the x neighbours of a level-k column: the split that created it
                    lut_a = np.full(width, -1, np.int64)
                    lut_b = np.full(width, -1, np.int64)
                    lut_a[ax.new_m[k - 1]] = ax.new_a[k - 1]
                    lut_b[ax.new_m[k - 1]] = ax.new_b[k - 1]
                    xc = x[centre]
                    xa, xb = lut_a[xc][:, None], lut_b[xc][:, None]   # (centre cols, 1)
                    corners = np.stack([frame[Aa, xa], frame[Aa, xb], frame[Bb, xa], frame[Bb, xb]])
                    rd = _range_diff(corners, params.metric)           # (centre cols, new rows)
                    ok[centre] &= spec.interpolate_ok(rd, thr_pos[centre], g, n)
            values = spec.interpolate(A, B, Aa, Bb, Mm)
            if horizontal:
                ty, tx = np.broadcast_to(F, ok.shape), np.broadcast_to(Mm, ok.shape)
            else:
                ty, tx = np.broadcast_to(Mm, ok.shape), np.broadcast_to(F, ok.shape)
            if (~ok).any():
                values[~ok] = trace(tx[~ok], ty[~ok])
            frame[ty, tx] = values
            source[ty, tx] = np.where(ok, spec.source_code_interp(k), spec.source_code_traced(k))
            counts[f"t{k}"] = counts.get(f"t{k}", 0) + int((~ok).sum())
            counts[f"i{k}"] = counts.get(f"i{k}", 0) + int(ok.sum())

    assert not (source == spec.SRC_UNSET).any(), "every pixel is final after level L"
    traced = int((source < spec.SRC_INTERP_BASE).sum())
    total = width * height
    stats = {"width": width, "height": height, "pixels": total, "traced": traced,
             "interpolated": total - traced, "traced_fraction": traced / total,
             "traced_initial": counts["initial"], "rule": rule, "params": params.as_dict()}
    return FrameResult(frame, source, params, stats)
