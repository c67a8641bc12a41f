"""The GTKWave view of make sim WAVES=1 (msr_flow.waves): the save file opens zoomed on the recorded window with marker A
at the tile's start and B at its end (GTKWave's `*zoom marker a b ...` line)."""

from msr_flow import waves as gen_gtkw


class FakeDump:
    def __init__(self, first, last, done):
        self.first, self.last, self.done = first, last, done


def parse(lines):
    star = next(ln for ln in lines if ln.startswith("*")).split()
    start = int(next(ln for ln in lines if ln.startswith("[timestart]")).split()[1])
    return start, float(star[0][1:]), [int(v) for v in star[2:]]


def test_window_fills_the_pane_with_markers_at_start_and_end():
    # a tile's life from cycle 1000 to 1300 plus 20 cycles of tail, 10 ns = 10000 ps a cycle
    d = FakeDump(first=1000 * 10000, last=1320 * 10000, done=1300 * 10000)
    start, zoom, markers = parse(gen_gtkw.view_lines(d))
    assert len(markers) == 26 and markers[:2] == [d.first, d.done] and set(markers[2:]) == {-1}
    per_px = 2.0 ** -zoom / gen_gtkw.PIXELS_PER_FRAME
    assert start <= d.first and start + gen_gtkw.WAVE_PANE * per_px >= d.last   # all of it in view
    assert (d.last - d.first) / per_px > 0.9 * gen_gtkw.WAVE_PANE                # and no more than that


def test_cycle_window_has_markers_at_its_ends():
    d = FakeDump(first=500, last=900, done=None)
    _, _, markers = parse(gen_gtkw.view_lines(d))
    assert markers[:2] == [500, 900]
