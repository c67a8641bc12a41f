"""A literal, slow, pure-Python reading of algorithm.md, written apart from msr_model.

It shares no code with the package under test: sets, dicts and ints only, one pixel at a
time, so a misreading of the spec in the vectorised model does not hide behind itself.
"""


def oracle_select(img, tile, levels, thr, metric="max", fov_gain=0):
    """img: list of rows of (r, g, b). Returns (frame dict, code dict, traced list)."""
    H, W = len(img), len(img[0])
    S = 2 ** levels
    ntx, nty = -(-W // tile), -(-H // tile)
    out, code, traced = {}, {}, []

    def trace(x, y, c):
        traced.append((x, y))
        out[(x, y)] = tuple(img[y][x])
        code[(x, y)] = c

    for ty in range(nty):
        for tx in range(ntx):
            x0, y0 = tx * tile, ty * tile
            w, h = min(tile, W - x0), min(tile, H - y0)
            r2 = max(abs(2 * tx - (ntx - 1)), abs(2 * ty - (nty - 1)))
            t = [min(255, thr[k] + ((fov_gain * r2) >> 4)) for k in range(levels)]

            def g0(n):
                s = set(range(0, n, S))
                s.add(n - 1)
                return s
            gx, gy = g0(w), g0(h)
            for y in gy:
                for x in gx:
                    trace(x0 + x, y0 + y, 0)
            for k in range(1, levels + 1):
                nk = S >> (k - 1)

                def new(gs):
                    s = sorted(gs)
                    return [(a + (b - a) // 2, a, b) for a, b in zip(s, s[1:]) if b - a >= 2]

                def decide(pos, pa, pb, a, b, m):
                    A, B = out[pa], out[pb]
                    diffs = [abs(A[c] - B[c]) for c in range(3)]
                    d = max(diffs) if metric == "max" else sum(diffs)
                    g = b - a
                    if d * nk < t[k - 1] * g:
                        return tuple(((b - m) * A[c] + (m - a) * B[c] + g // 2) // g for c in range(3))
                    return None

                def finish(results):
                    """Write a pass's results only after all its decisions (final before the pass)."""
                    for p, v in results:
                        if v is None:
                            trace(*p, k)
                        else:
                            out[p], code[p] = v, 16 + k

                finish([((x0 + m, y0 + y), decide(None, (x0 + a, y0 + y), (x0 + b, y0 + y), a, b, m))
                        for y in sorted(gy) for m, a, b in new(gx)])                       # H pass
                gx = gx | {m for m, _, _ in new(gx)}
                finish([((x0 + x, y0 + m), decide(None, (x0 + x, y0 + a), (x0 + x, y0 + b), a, b, m))
                        for x in sorted(gx) for m, a, b in new(gy)])                       # V pass
                gy = gy | {m for m, _, _ in new(gy)}
    return out, code, traced
