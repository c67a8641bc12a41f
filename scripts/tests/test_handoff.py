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


def test_core_and_sdc_reference_existing_files():
    core = (ROOT / "msr.core").read_text()
    for f in re.findall(r"^      - ([\w/.]+)", core, re.M):
        assert (ROOT / f).exists(), f
    sdc = (ROOT / "syn/msr_top.sdc").read_text()
    assert "create_clock" in sdc and "clk_i" in sdc
