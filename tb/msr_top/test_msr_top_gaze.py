"""msr_top: the gaze point (GAZE, docs/spec/contracts.md "Gaze"): a gaze outside the frame is
refused at START with STATUS.ERROR GAZE (nothing started, nothing written) and the next good
frame runs; frames foveated around random gaze points bit-exact with the golden model; GAZE.EN
0 is the frame centre whatever X and Y hold."""
from __future__ import annotations

import cocotb

from msr_flow import regs as R
from msr_top_env import MEM, FILL, ERR_GAZE, ERR_LEVELS, make_image, setup, expect_refused


@cocotb.test()
async def test_gaze(dut):
    env, rng = await setup(dut, 21)
    env.set_pauses(0.1)
    good = dict(W=37, H=21, tile=8, levels=2, metric=0, thr=[6, 14], gain=120)
    env.ram.write(0, bytes([FILL]) * MEM)
    for what, gaze, over, code in (
            ("gaze X = W", (37, 0), {}, ERR_GAZE), ("gaze Y = H", (0, 21), {}, ERR_GAZE),
            ("gaze far outside", (8191, 8191), {}, ERR_GAZE),
            ("gaze X = W at T 32", (37, 20), dict(tile=32), ERR_GAZE),
            # the first failing check in the order of the codes: the gaze's comes last
            ("gaze outside and levels 0", (40, 0), dict(levels=0), ERR_LEVELS)):
        c = {**good, **over}
        env.render.requests = []
        await env.program(c["W"], c["H"], c["tile"], c["levels"], c["metric"], c["thr"], c["gain"], gaze=gaze)
        await expect_refused(dut, env, code, what)
    # the next good frame runs, with its gaze at the last pixel
    await env.frame(**good, gaze=(36, 20))
    # GAZE.EN 0: X and Y are not read (the centre), even when outside the frame
    f = dict(img=make_image(rng, 37, 21), **good, src_en=1, rule=0, gaze=None)
    env.render.image, env.render.requests = f["img"], []
    env.ram.write(0, bytes([FILL]) * MEM)
    f["fb_stride"], f["src_stride"] = await env.program(37, 21, 8, 2, 0, good["thr"], good["gain"])
    await env.wr(R.GAZE, (4000 << R.GAZE_X_LSB) | (4000 << R.GAZE_Y_LSB))
    await env.wr(R.CTRL, R.CTRL_START_MASK)
    st = await env.wait_idle()
    assert st & R.STATUS_DONE_MASK and not st & R.STATUS_ERROR_MASK, f"STATUS {st:#x}"
    env.check_memory(f)
    # random frames and gaze points (corners, edges, inside), and the default between them
    for _ in range(6):
        W, H, T = rng.randint(1, 48), rng.randint(1, 40), rng.choice((8, 16, 32))
        L = rng.randint(1, 3)
        gaze = rng.choice(((0, 0), (W - 1, H - 1), (W - 1, 0), (rng.randrange(W), rng.randrange(H))))
        thr = [rng.choice((0, 4, 8, 16, 40)) for _ in range(L)]
        await env.frame(W, H, T, L, rng.randint(0, 1), thr, rng.choice((30, 120, 255)), gaze=gaze)
        await env.frame(W, H, T, L, 0, thr, 255)
