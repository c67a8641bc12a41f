"""The hand-off package stays consistent: one file list (rtl/msr.f) that every flow reads."""
import re
from pathlib import Path

from msr_flow.filelist import rtl_sources   # the one reader of rtl/msr.f

ROOT = Path(__file__).resolve().parents[2]


def filelist():
    return [str(p.relative_to(ROOT)) for p in rtl_sources()]


def test_filelist_files_exist_one_module_per_file_named_after_it():
    for f in filelist():
        text = (ROOT / f).read_text()
        mods = re.findall(r"^\s*module\s+(\w+)", text, re.M)
        pkgs = re.findall(r"^\s*package\s+(\w+)", text, re.M)
        assert len(mods) + len(pkgs) == 1, f"{f}: one module or package per file"
        assert Path(f).stem == (mods or pkgs)[0], f"{f}: file named after its unit"


def test_fusesoc_core_lists_exactly_msr_f():
    core = (ROOT / "msr.core").read_text()
    assert core.startswith("CAPI=2:")
    block = re.search(r"^  rtl:\n    files:\n((?:      - .*\n)+)", core, re.M).group(1)
    core_files = [ln.strip()[2:] for ln in block.splitlines()]
    assert core_files == filelist()


def test_fusesoc_core_is_generated_from_msr_f():
    """msr.core's rtl fileset is written by `python -m msr_flow.filelist --core`: a stale core
    (a file added to rtl/msr.f and not regenerated) fails here."""
    from msr_flow.filelist import core_text
    assert (ROOT / "msr.core").read_text() == core_text(), "run python -m msr_flow.filelist --core"


def test_rtl_folders_hold_at_most_20_modules_and_subsystems_stay_apart():
    """A folder per subsystem: no folder of rtl/ over 20 modules; the budget's and the
    frame-buffer writer's units each in a folder that holds nothing else."""
    for d in (ROOT / "rtl").iterdir():
        if d.is_dir():
            assert len(list(d.glob("*.sv"))) <= 20, d
    assert all(p.name.startswith("msr_budget") for p in (ROOT / "rtl/budget").iterdir())
    assert all(p.name.startswith(("msr_fbw", "msr_fb_writer")) for p in (ROOT / "rtl/fbw").iterdir())


def test_core_and_sdc_reference_existing_files():
    core = (ROOT / "msr.core").read_text()
    for f in re.findall(r"^      - ([\w/.]+)", core, re.M):
        assert (ROOT / f).exists(), f
    sdc = (ROOT / "syn/msr_top.sdc").read_text()
    assert "create_clock" in sdc and "clk_i" in sdc
