"""Python constants from the SystemRDL register map (peakrdl has no plain-constants exporter).

    python scripts/gen_reg_consts.py rtl/regs/msr_regs.rdl OUT.py

Emits, for every register, `<REG>` = byte offset (arrays: `<REG>_<i>`), and for every field
`<REG>_<FIELD>_LSB` / `_WIDTH` / `_MASK`. Used by the cocotb tests (flow/msr_flow/regs.py).
"""
import argparse
import sys

from systemrdl import RDLCompiler
from systemrdl.node import FieldNode, RegNode

from .regs_codes import python_lines


def generate(src: str, out: str) -> int:
    """Write the constants of the register map `src` into the Python module `out`."""
    rdlc = RDLCompiler()
    rdlc.compile_file(src)
    root = rdlc.elaborate()
    top = root.top
    lines = [f'"""Register map of {top.inst_name}: generated from {src} by scripts/gen_reg_consts.py; do not edit."""', ""]
    for node in top.descendants(unroll=True):
        if isinstance(node, RegNode):
            name = node.inst_name + ("".join(f"_{i}" for i in node.current_idx) if node.is_array else "")
            lines.append(f"{name} = 0x{node.absolute_address:02X}")
        elif isinstance(node, FieldNode):
            reg = node.parent
            if reg.is_array and any(reg.current_idx):
                continue  # array entries share the field layout of entry 0
            prefix = f"{reg.inst_name}_{node.inst_name}"
            lines.append(f"{prefix}_LSB = {node.lsb}")
            lines.append(f"{prefix}_WIDTH = {node.width}")
            lines.append(f"{prefix}_MASK = 0x{((1 << node.width) - 1) << node.lsb:08X}")
    lines += ["", "# Encoded fields' codes (SystemRDL `encode`)", *python_lines(src)]
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    return 0


PARSER = argparse.ArgumentParser(description=__doc__.splitlines()[0])
PARSER.add_argument("src", help="the SystemRDL source")
PARSER.add_argument("out", help="the Python module to write")


def main(argv: list[str] | None = None) -> int:
    return generate(**vars(PARSER.parse_args(argv)))


if __name__ == "__main__":
    sys.exit(main())
