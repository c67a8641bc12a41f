"""The evaluation sweep: scenes x renderer modes x methods x settings, as independent tasks.

For every scene and mode the reference is the full render (cached as PNG under the cache
folder). The renderer is deterministic (same pixel, same colour), so every setting then runs
against the cached reference as the rendering unit: each method still asks the unit only for
the pixels it traces, and the traced count is what the unit was asked for.

Tasks run on an executor (msr_eval.executors: in this process, in order, or on Dask
distributed). Each task is a pure function of its inputs, so both give the same records; only
the wall-time fields (`decide_s`, `full_render_s`) differ between runs. References and records
are cached per scene and mode (`Cache`), keyed by the renderer library and the code that
computes them, so an interrupted run resumes.
"""
from __future__ import annotations

import hashlib
import json
import time
from dataclasses import dataclass
from pathlib import Path

from msr_model import ImageRenderer, load_rgb, save_png
from msr_model.testimage import test_image

from . import conv_store as CS
from . import fingerprint as FP
from . import gbuffer_rule as G
from . import methods as M
from . import reference as REF
from .metrics import TARGETS_DB, pick_near, psnr, ssim, flip
from .scenes import scene_id
from .sweep_space import (  # noqa: F401  (msr_eval.sweep.X stays the name callers use)
    CONV_FAMILIES, DACS_THR, DACS_THR_QUICK, DACS_VARIANTS, FLIP_FAMILIES_FULL, FULL_SCALES, KEY_FAMILIES,
    MAIN_FAMILIES, QUICK_SCALES, SPARSE_SCALES, VRS_THR, VRS_THR_QUICK, Setting, find_setting, fov_gain_for,
    level_thr, settings)

REPO = Path(__file__).resolve().parents[2]

# A record's validity rests on its family's behaviour on a probe frame (msr_eval.fingerprint),
# not on the source of the code. Bump RECORD_VERSION when this file changes what a record holds
# or how it is computed (task_record is not on the probe), or when a method changes in a way
# the probe cannot show.
RECORD_VERSION = 2


# --- scenes and renderers ------------------------------------------------------------------

def _embree():
    from msr_model import embree  # noqa: PLC0415 - needs the built renderer library
    return embree


class Backend:
    """The rendering unit: the Embree binding if it is built, else the built-in test picture."""

    def __init__(self, want: str):
        self.name = "image"
        self.lib_hash = "testimage"
        if want in ("auto", "embree"):
            try:
                embree = _embree()
                _close(embree.open_renderer(embree.scene_names()[0], 8, 8, quality="fast"))  # built?
                self.name = "embree"
                self.lib_hash = _lib_hash(embree.library_path())
            except Exception as e:  # noqa: BLE001 - any failure to load means "not built"
                if want == "embree":
                    raise SystemExit(f"eval: Embree renderer not available: {e}")

    @property
    def embree(self) -> bool:
        return self.name == "embree"

    def builtin_scenes(self) -> list[str]:
        return _embree().scene_names() if self.embree else ["testimage"]

    def open(self, scene: str, width: int, height: int, mode: str):
        return open_unit(self.name, scene, width, height, mode)


def open_unit(backend: str, scene: str, width: int, height: int, mode: str):
    """A rendering unit by backend name (what a task on a worker gets: names, not objects)."""
    if backend == "image":
        return ImageRenderer(test_image(width, height))
    return _embree().open_renderer(scene, width, height, quality=mode)


def _lib_hash(path) -> str:
    """Content hash of the renderer library (so a rebuilt renderer invalidates the cache)."""
    p = Path(path)
    return hashlib.sha1(p.read_bytes()).hexdigest()[:10] if p.is_file() else "nolib"


def _rel(p: Path) -> str:
    """A path relative to the repository when it is inside it (for logs)."""
    try:
        return str(Path(p).resolve().relative_to(REPO))
    except ValueError:
        return str(p)


def _close(r):
    close = getattr(r, "close", None)
    if close:
        close()



_SIGNATURES: dict = {}     # family signatures per sweep set-up (the probe runs once a process)


@dataclass(frozen=True)
class SweepConfig:
    width: int
    height: int
    scales: tuple
    quick: bool
    all_metrics: bool
    cache: Path
    conv: bool = True                 # score against the converged reference too (msr_eval.reference)
    conv_grid: int | None = None      # its antialiasing grid (None: reference.CONV_GRID per mode)
    conv_check: bool = True           # and a second seed's render, for the two-seed PSNR
    conv_modes: tuple | None = None   # the modes with a converged reference (None: every mode)
    conv_ladder: bool = False         # heavy grid per scene from data/converged/ladder.json (full size)
    store: Path | None = None         # committed references and records (msr_eval.conv_store), or None
    refs_only: bool = False           # stop after the references (run_sweep returns no records)

    @property
    def sweep(self) -> list[Setting]:
        return settings(self.width, self.height, self.scales, self.quick)

    def conv_signature(self) -> bytes:
        """What the converged scores of a record depend on besides its family's code."""
        if not self.conv:
            return b""
        out = repr(("conv", self.conv_grid, self.conv_check, REF.CONV_GRIDS, REF.CONV_TARGET_DB,
                    REF.CONV_SEEDS, self.conv_modes, self.conv_ladder)).encode()
        if self.conv_ladder:
            out += CS.LADDER.read_bytes() if CS.LADDER.is_file() else b""
        return out

    def family_signatures(self) -> dict:
        """Per family: a hash of its settings' outputs on the probe frame (msr_eval.fingerprint),
        the scoring code's outputs there and the scoring set-up. A record whose family's
        signature is unchanged is still valid."""
        key = (self.width, self.height, tuple(self.scales), self.quick, self.all_metrics,
               self.conv_signature())
        if key not in _SIGNATURES:
            sweep = self.sweep
            common = hashlib.sha1(FP.scoring_fingerprint())
            common.update(repr((RECORD_VERSION, self.all_metrics, KEY_FAMILIES, FLIP_FAMILIES_FULL,
                                TARGETS_DB)).encode())
            common.update(key[-1])
            sigs = {}
            for fam, probe in FP.family_fingerprints(sweep).items():
                h = sigs[fam] = common.copy()
                h.update(probe)
            for st in sweep:
                sigs[st.family].update(f"{st.label}|{sorted(st.setting.items())}".encode())
            _SIGNATURES[key] = {f: h.hexdigest()[:10] for f, h in sigs.items()}
        return dict(_SIGNATURES[key])

    def signature(self) -> str:
        """Changes whenever the sweep or the code that computes a record changes."""
        h = hashlib.sha1(repr(sorted(self.family_signatures().items())).encode())
        return h.hexdigest()[:10]

    def conv_wanted(self, mode: str) -> bool:
        return self.conv and (self.conv_modes is None or mode in self.conv_modes)

    def ladder_grid(self, sid: str) -> int | None:
        return CS.ladder_grid(sid) if self.conv_ladder and not self.conv_grid else None


# --- tasks (pure functions of their arguments) -----------------------------------------------

def gbuffer_of(backend: Backend, scene: str, cfg: SweepConfig):
    """The scene's G-buffer at the sweep's size (msr_eval.gbuffer_rule), cached beside the references."""
    return G.scene_gbuffer(backend.name, scene, cfg.width, cfg.height, cfg.cache,
                           f"{scene_id(scene)}_{cfg.width}x{cfg.height}_{backend.lib_hash}")


def _timed(renderer, run):
    """run(renderer) and its wall time in seconds; the renderer is closed afterwards."""
    try:
        t0 = time.perf_counter()
        res = run(renderer)
        return res, time.perf_counter() - t0
    finally:
        _close(renderer)


def task_reference(backend: str, scene: str, mode: str, width: int, height: int):
    """The full render of a scene and its wall time."""
    res, dt = _timed(open_unit(backend, scene, width, height, mode), lambda r: M.full_render(r, width, height))
    return res.frame, {"full_render_s": dt, "traced": res.traced}


def task_record(ref, sid: str, mode: str, setting: Setting, all_metrics: bool, gbuf=None, conv=None) -> dict:
    """One setting on one scene's reference (and its G-buffer, for the G-buffer rule): its record;
    with `conv` (the converged reference) also its scores against that (msr_eval.reference.score)."""
    H, W = ref.shape[:2]
    rr = G.rendering_unit(ref, gbuf)
    t0 = time.perf_counter()
    res = setting.run(rr, W, H)
    dt = time.perf_counter() - t0
    if rr.pixels_traced != res.traced:
        raise RuntimeError(f"{setting.family}: method count {res.traced} != renderer count {rr.pixels_traced}")
    rec = {"scene": sid, "mode": mode, "family": setting.family, "method": res.method,
           "label": setting.label, "setting": setting.setting, "traced": res.traced,
           "traced_fraction": res.traced / (W * H), "psnr": psnr(ref, res.frame),
           "decide_s": dt, "key_setting": False}
    if all_metrics:
        rec["ssim"] = ssim(ref, res.frame)
        rec["flip"] = flip(ref, res.frame)
    if conv is not None:
        rec.update(REF.score(conv, res.frame, all_metrics))
    return rec


def task_key_metrics(ref, setting: Setting, want_flip: bool, gbuf=None, conv=None) -> dict:
    """SSIM (and FLIP) of one setting, run again on the reference (and against `conv`, the
    converged reference, when given)."""
    H, W = ref.shape[:2]
    res = setting.run(G.rendering_unit(ref, gbuf), W, H)
    out = {"ssim": ssim(ref, res.frame)}
    if want_flip:
        out["flip"] = flip(ref, res.frame)
    if conv is not None:
        out["ssim_conv"] = ssim(conv, res.frame)
        if want_flip:
            out["flip_conv"] = flip(conv, res.frame)
    return out


# --- the cache --------------------------------------------------------------------------------

class Cache:
    """The sweep's cache folder. What is cached under a key is KEY.json, and for a frame KEY.png
    beside it (the frame, KEY.json its info); the key names everything the value depends on
    (scene, mode, size, renderer library, settings and code), so a value found is valid."""

    def __init__(self, folder: Path):
        self.dir = Path(folder)
        self.dir.mkdir(parents=True, exist_ok=True)

    def load(self, key: str, frame: bool = True, valid=None):
        """(frame, info) under `key` (with `frame`), else the JSON value; None when it is
        missing, or when `valid(info)` says it does not serve."""
        meta, png = self.dir / f"{key}.json", self.dir / f"{key}.png"
        if not meta.is_file() or (frame and not png.is_file()):
            return None
        info = json.loads(meta.read_text())
        if valid is not None and not valid(info):
            return None
        return (load_rgb(png), info) if frame else info

    def save(self, key: str, value, info=None):
        """`value` under `key`: a frame with its `info`, or (info None) a JSON value."""
        if info is None:
            (self.dir / f"{key}.json").write_text(json.dumps(value))
            return
        save_png(self.dir / f"{key}.png", value)
        (self.dir / f"{key}.json").write_text(json.dumps(info))

    def frames(self, executor, jobs, bar, valid=None, done=None) -> dict:
        """Cache or compute: `jobs` is a list of (item, key, task), task = (fn, *args) giving
        (frame, info). Each item's pair comes from the cache (when there and valid), else from
        its task on the executor, written here as soon as it is in (in list order, so a stopped
        run keeps every finished one). `done(item, frame, info, fresh)` after each item; `bar(n)`
        is the progress bar of the n tasks. Returns {item: (frame, info)}."""
        out, todo = {}, []
        for item, key, task in jobs:
            hit = self.load(key, valid=valid)
            if hit is None:
                todo.append((item, key, task))
                continue
            out[item] = hit
            if done is not None:
                done(item, *hit, False)
        with bar(len(todo)) as b:
            futs = [executor.submit(*task) for _, _, task in todo]
            for (item, key, _), fut in zip(todo, futs):
                frame, info = out[item] = fut.result()
                b.update(1)
                self.save(key, frame, info)
                if done is not None:
                    done(item, frame, info, True)
        return out


# --- the sweep -------------------------------------------------------------------------------

def run_sweep(backend: Backend, scenes: list[str], modes: list[str], cfg: SweepConfig, executor,
              log=print, show_progress: bool = True):
    """Every setting on every scene and mode. Returns (records, refs, infos), refs and infos
    keyed by (scene, mode); records in the order scene, mode, setting."""
    from tqdm import tqdm

    cache = Cache(cfg.cache)
    W, H = cfg.width, cfg.height
    sweep = cfg.sweep
    sig = cfg.signature()
    pairs = [(scene, mode) for scene in scenes for mode in modes]

    def bar(total, desc):
        return tqdm(total=total, desc=desc, unit="task", disable=True if not show_progress or total == 0 else None,
                    leave=False, mininterval=1.0)

    # References: from the cache, else rendered as tasks (each cached as soon as it is done).
    got = cache.frames(executor, [(pair, f"{scene_id(pair[0])}_{pair[1]}_{W}x{H}_{backend.lib_hash}",
                                   (task_reference, backend.name, *pair, W, H)) for pair in pairs],
                       lambda n: bar(n, "eval: references"))
    refs = {pair: got[pair][0] for pair in pairs}
    infos = {pair: got[pair][1] for pair in pairs}

    # Converged references (msr_eval.reference): from the committed store (msr_eval.conv_store,
    # when cfg.store), else the cache, else rendered as tasks; each saved as soon as it is done.
    convs = {}
    store = CS.Store(W, H, cfg.store) if cfg.store else None
    full_sha = {pair: CS.frame_sha(refs[pair]) for pair in pairs} if store is not None else {}
    if cfg.conv:
        jobs, grids = [], {}
        for scene, mode in pairs:
            if not cfg.conv_wanted(mode):
                continue
            sid = scene_id(scene)
            lg = cfg.ladder_grid(sid)
            g = grids[(scene, mode)] = REF.conv_grids_for(mode, cfg.conv_grid, lg)
            if store is not None and len(g) == 1:
                hit = store.load_ref(sid, mode, full_sha[(scene, mode)], g[0], REF.CONV_SEEDS[0])
                if hit is not None and (not cfg.conv_check or "psnr_two_seeds" in hit[1]):
                    convs[(scene, mode)], infos[(scene, mode)]["converged"] = hit[0], {**hit[1], "from": "store"}
                    log(f"  {sid}/{mode}: converged reference from {_rel(store.dir)} ({hit[1]['spp']} spp)")
                    continue
            key = f"conv_{sid}_{mode}_{W}x{H}_{backend.lib_hash}_{REF.conv_key(mode, cfg.conv_grid, cfg.conv_check, lg)}"
            jobs.append(((scene, mode), key, (REF.task_converged, backend.name, scene, mode, W, H, g, cfg.conv_check)))
        # the largest first, so the run's length is known early and the small ones fill the end
        jobs.sort(key=lambda j: -max(grids[j[0]]))

        def conv_done(pair, frame, info, fresh):
            convs[pair] = frame
            infos[pair]["converged"] = info
            sid, mode = scene_id(pair[0]), pair[1]
            if store is not None and (fresh or len(grids[pair]) == 1):
                store.save_ref(sid, mode, frame, info, full_sha[pair])
            if fresh:                     # (hours at 1080p)
                log(f"  {sid}/{mode}: converged reference, {info['spp']} samples per pixel in "
                    f"{info['render_s']:.0f} s" +
                    (f", two seeds {info['psnr_two_seeds']:.2f} dB" if info.get("psnr_two_seeds") else ""))
        cache.frames(executor, jobs, lambda n: bar(n, "eval: converged references"),
                     valid=lambda info: not cfg.conv_check or "psnr_two_seeds" in info, done=conv_done)
    if cfg.refs_only:
        return [], refs, infos

    # G-buffers (one primary ray a pixel), for the settings that read them: cached per scene.
    gbufs = {}
    if any(G.needs_gbuffer(s) for s in sweep):
        gbufs = {scene: gbuffer_of(backend, scene, cfg) for scene in scenes}

    # Records: from the committed store (the families whose signature is unchanged; cfg.store),
    # else the per-scene cache, else one task per setting still missing.
    fsig = cfg.family_signatures()
    order = {(st.family, st.label): i for i, st in enumerate(sweep)}
    records, pending = {}, []
    for scene, mode in pairs:
        sid = scene_id(scene)
        rkey = f"records_{sid}_{mode}_{W}x{H}_{backend.lib_hash}_{sig}"
        kept = []
        if store is not None:
            kept = [r for r in store.load_records(sid, mode, fsig, full_sha[(scene, mode)])
                    if (r["family"], r["label"]) in order]
        elif (hit := cache.load(rkey, frame=False)) is not None:
            records[(scene, mode)] = hit
            log(f"  {sid}/{mode}: {len(records[(scene, mode)])} settings (cached)")
            continue
        have = {(r["family"], r["label"]) for r in kept}
        todo = [st for st in sweep if (st.family, st.label) not in have]
        if not todo:
            records[(scene, mode)] = sorted(kept, key=lambda r: order[(r["family"], r["label"])])
            log(f"  {sid}/{mode}: {len(kept)} settings (from {_rel(store.dir)})")
            continue
        if kept:
            log(f"  {sid}/{mode}: {len(kept)} settings from {_rel(store.dir)}, {len(todo)} to compute")
        pending.append((scene, mode, rkey, todo, kept))
    t0 = time.perf_counter()
    shared = {(scene, mode): executor.scatter(refs[(scene, mode)]) for scene, mode, *_ in pending}
    # (a G-buffer is a tuple of three arrays: scattered inside a list, so as one object)
    gshared = {scene: executor.scatter([gbufs[scene]])[0] for scene in {p[0] for p in pending} if scene in gbufs}

    cshared = {(scene, mode): executor.scatter(convs[(scene, mode)]) for scene, mode, *_ in pending
               if (scene, mode) in convs}

    def gb(scene, s):       # the G-buffer (for the settings that read it), then the converged reference
        return (gshared[scene] if G.needs_gbuffer(s) else None,)

    def cv(scene, mode):
        return (cshared.get((scene, mode)),)

    futs = [[executor.submit(task_record, shared[(scene, mode)], scene_id(scene), mode, st, cfg.all_metrics,
                             *gb(scene, st), *cv(scene, mode)) for st in todo]
            for scene, mode, _, todo, _ in pending]

    def key_jobs(scene, mode):
        """Key settings: the cheapest of each key family reaching the targets on this scene and
        mode; their SSIM/FLIP (and against the converged reference) as tasks."""
        jobs = []
        recs = records[(scene, mode)]

        def add(r, done_key, want_flip=None):
            if done_key not in r and not any(r is j[0] for j in jobs):
                if want_flip is None:
                    want_flip = cfg.quick or r["family"] in FLIP_FAMILIES_FULL
                st = find_setting(sweep, r)
                jobs.append((r, executor.submit(task_key_metrics, shared[(scene, mode)], st, want_flip,
                                                *gb(scene, st), *cv(scene, mode), priority=1)))
        for fam in KEY_FAMILIES:
            for t in (TARGETS_DB if cfg.quick else (40.0,)):
                r = pick_near(recs, scene_id(scene), mode, fam, t)
                if r is not None:
                    r["key_setting"] = True
                    add(r, "ssim")
        if (scene, mode) in convs:      # ... and against the converged reference (the full render too)
            if cfg.quick:
                for fam in (*KEY_FAMILIES, "full"):
                    for t in TARGETS_DB:
                        r = REF.pick_near_conv(recs, scene_id(scene), mode, fam, t)
                        if r is not None:
                            r["key_setting_conv"] = True
                            add(r, "ssim_conv")
            else:   # full size: at the equal-quality point (the full render's own PSNR), with FLIP
                eq = [r["psnr_conv"] for r in recs if r["family"] == "full"]
                for fam in CONV_FAMILIES:
                    r = REF.pick_near_conv(recs, scene_id(scene), mode, fam, eq[0]) if eq else None
                    if r is not None:
                        r["key_setting_conv"] = True
                        add(r, "ssim_conv", want_flip=True)
        return jobs

    def finish(scene, mode, rkey, jobs):
        for (r, _), extra in zip(jobs, executor.results([f for _, f in jobs])):
            r.update(extra)
        cache.save(rkey, records[(scene, mode)])
        if store is not None:
            store.save_records(scene_id(scene), mode, records[(scene, mode)], fsig, full_sha[(scene, mode)],
                               {"converged": infos[(scene, mode)].get("converged")})
        log(f"  {scene_id(scene)}/{mode}: {len(sweep)} settings, full render "
            f"{infos[(scene, mode)]['full_render_s']:.2f} s")

    # Pair by pair, in submission order: its settings, then its key metrics; a pair's records
    # are written to the cache (and the store) as soon as they are complete (a long run that is
    # stopped keeps every finished pair), while the later pairs' tasks keep the workers busy.
    last = None
    with bar(sum(map(len, futs)), "eval: settings") as b:
        for (scene, mode, rkey, todo, kept), pf in zip(pending, futs):
            recs = kept + executor.results(pf, b)
            records[(scene, mode)] = sorted(recs, key=lambda r: order[(r["family"], r["label"])])
            jobs = key_jobs(scene, mode)
            if last is not None:
                finish(*last)
            last = (scene, mode, rkey, jobs)
    if last is not None:
        finish(*last)
    if pending:
        log(f"  sweep of {sum(map(len, futs))} settings on {executor.name}: {time.perf_counter() - t0:.1f} s")
    return [r for pair in pairs for r in records[pair]], refs, infos


def rerun(ref, rec: dict, sweep: list[Setting], gbuf=None) -> M.MethodResult:
    """Run one recorded setting again on the reference (for images and late metrics); the
    G-buffer rule's settings need the scene's G-buffer (G.scene_gbuffer)."""
    H, W = ref.shape[:2]
    return find_setting(sweep, rec).run(G.rendering_unit(ref, gbuf), W, H)


def speedup(backend: Backend, scene, mode, rec, ref, info, sweep: list[Setting]) -> dict:
    """Wall time of the selective render on the live renderer against the full render (run here,
    alone, so no other task disturbs the timing)."""
    H, W = ref.shape[:2]
    setting = find_setting(sweep, rec)
    res, dt = _timed(backend.open(scene, W, H, mode), lambda r: setting.run(r, W, H))
    cached = rerun(ref, rec, sweep)
    return {"scene": scene_id(scene), "mode": mode, "family": rec["family"], "label": rec["label"],
            "traced_fraction": res.traced / (W * H), "psnr": rec["psnr"],
            "full_render_s": info["full_render_s"], "selective_s": dt,
            "speedup": info["full_render_s"] / dt if dt > 0 else None,
            "bit_equal_to_cached_run": bool((res.frame == cached.frame).all())}
