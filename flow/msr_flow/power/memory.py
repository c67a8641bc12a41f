"""Energy of the tile-buffer macros per access, from the cited SRAM macro's own liberty: the
internal energy of its CLK pin under the read and the write conditions (one rising and one
falling CLK transition per access), for the two published sizes of syn/asic/sram_macro.json."""
from __future__ import annotations

import math
from dataclasses import dataclass

SOURCE = ("GlobalFoundries GF180MCU single-port SRAM macros gf180mcu_fd_ip_sram (180 nm), typical corner "
          "tt_025C_1v80: internal_power of pin CLK, when \"!CEN & GWEN\" (read) and \"!CEN & !GWEN & ...\" "
          "(write), rise_power = fall_power, in pJ per transition (capacitive_load_unit pf x voltage_unit V^2); "
          "https://github.com/google/globalfoundries-pdk-ip-gf180mcu_fd_ip_sram, cells/*/"
          "*__tt_025C_1v80.lib")
# (words, bits per word) -> pJ per CLK transition, read and write
POINTS = {
    64: {"read": 84.3399, "write": 92.043},     # gf180mcu_fd_ip_sram__sram64x8m8wm1
    512: {"read": 103.176, "write": 112.563},   # gf180mcu_fd_ip_sram__sram512x8m8wm1
}
POINT_BITS = 8
RULE = ("energy per access = rise + fall CLK energy of the macro; between and beyond the two published depths "
        "linear in log2(depth) (the access-time rule of sram_macro.json); a word of W bits costs W / 8 of the "
        "8-bit macro (one 8-bit macro per byte, side by side); a 1R1W tile buffer is priced as one single-port "
        "access per read and per write of each macro")


@dataclass(frozen=True)
class MacroEnergy:
    read_pj: float
    write_pj: float


def per_access(depth: int, width: int) -> MacroEnergy:
    lo, hi = POINTS[64], POINTS[512]
    t = (math.log2(depth) - 6) / 3          # 0 at 64 words, 1 at 512
    e = {k: 2 * (lo[k] + t * (hi[k] - lo[k])) * width / POINT_BITS for k in ("read", "write")}
    return MacroEnergy(e["read"], e["write"])
