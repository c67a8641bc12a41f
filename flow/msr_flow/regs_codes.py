"""The encoded fields of the SystemRDL register map (today STATUS.ERROR, `encode =
status_error_e`) as SystemVerilog and Python, so the codes are written once, in the .rdl:

    python -m msr_flow.regs_codes rtl/regs/msr_regs.rdl OUT.svh [--md docs/regs.md]

writes the SystemVerilog enum `err_e` (ERR_<NAME> = code) that msr_sys_pkg includes;
`python_lines` gives the constants flow/msr_flow/regs.py carries (<REG>_<FIELD>_<NAME>)."""
from __future__ import annotations

import sys
import textwrap
from dataclasses import dataclass

from systemrdl import RDLCompiler
from systemrdl.node import FieldNode

# SystemVerilog type and literal prefix of each encoded field, by "<REG>.<FIELD>".
SV_NAMES = {"STATUS.ERROR": ("err_e", "ERR_")}


@dataclass(frozen=True)
class Code:
    name: str
    value: int
    desc: str


@dataclass(frozen=True)
class EncodedField:
    reg: str
    field: str
    width: int
    codes: tuple[Code, ...]


def encoded_fields(src: str) -> list[EncodedField]:
    rdlc = RDLCompiler()
    rdlc.compile_file(src)
    out = []
    for node in rdlc.elaborate().top.descendants(unroll=False):
        if isinstance(node, FieldNode) and node.get_property("encode") is not None:
            enum = node.get_property("encode")
            codes = tuple(Code(m.name, m.value, " ".join((m.rdl_desc or "").split())) for m in enum)
            out.append(EncodedField(node.parent.inst_name, node.inst_name, node.width, codes))
    return out


def sv_text(src: str) -> str:
    lines = [f"// Generated from {src} by `make regs` (msr_flow.regs_codes); do not edit.",
             "// Included inside msr_sys_pkg: the encoded register fields as enums."]
    for f in encoded_fields(src):
        typ, prefix = SV_NAMES[f"{f.reg}.{f.field}"]
        width = max(len(prefix + c.name) for c in f.codes)
        lines += ["", f"// {f.reg}.{f.field}", f"typedef enum logic [{f.width - 1}:0] {{"]
        for i, c in enumerate(f.codes):
            sep = "," if i < len(f.codes) - 1 else ""
            lines += [f"  // {ln}" for ln in textwrap.wrap(c.desc, 93)]
            lines.append(f"  {(prefix + c.name).ljust(width)} = {f.width}'d{c.value}{sep}")
        lines.append(f"}} {typ};")
    return "\n".join(lines) + "\n"


def python_lines(src: str) -> list[str]:
    return [f"{f.reg}_{f.field}_{c.name} = {c.value}" for f in encoded_fields(src) for c in f.codes]


def markdown_text(src: str) -> str:
    """A section for the register map page: each encoded field's codes as a table."""
    out = []
    for f in encoded_fields(src):
        out += ["", f"## {f.reg}.{f.field} codes", "", "| code | name | meaning |", "|---|---|---|"]
        out += [f"| {c.value} | {c.name} | {c.desc} |" for c in f.codes]
    return "\n".join(out) + "\n"


def main(argv: list[str] | None = None) -> int:
    """SRC OUT.svh [--md PAGE.md]: the SystemVerilog enums; with --md, the codes' tables are
    appended to the register map page that peakrdl-markdown wrote."""
    args = argv if argv is not None else sys.argv[1:]
    src, out = args[:2]
    with open(out, "w") as fh:
        fh.write(sv_text(src))
    if args[2:3] == ["--md"]:
        with open(args[3], "a") as fh:
            fh.write(markdown_text(src))
    return 0


if __name__ == "__main__":
    sys.exit(main())
