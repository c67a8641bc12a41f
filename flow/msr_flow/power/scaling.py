"""Energy per operation at other nodes, labelled estimates: the polynomial energy factors of
Stillmaker and Baas (2017) below 130 nm, and classical scaling from 180 to 130 nm."""
from __future__ import annotations

PAPER = ("A. Stillmaker, B. Baas, \"Scaling equations for the accurate prediction of CMOS device performance "
         "from 180 nm to 7 nm\", Integration, the VLSI Journal 58 (2017) 74-81")
# Energy factor a V^2 + b V + c per node (the paper's fitted coefficients as transcribed in open-source
# accelerator models that cite it), evaluated at the node's nominal supply.
COEFFS = {130: (7.171, -6.709, 2.904), 32: (0.9559, -0.7823, 0.471), 20: (0.373, -0.1582, 0.04104),
          7: (0.1776, -0.09097, 0.02447)}
VDD = {130: 1.3, 28: 0.9, 7: 0.7}
# 180 -> 130 nm: classical scaling of C V^2 (C with the feature size, 1.8 V -> 1.3 V), as the table used
# starts at 130 nm.
BRIDGE_180_130 = (130 / 180) * (1.3 / 1.8) ** 2


def factor(node: int, vdd: float) -> float:
    if node == 28:             # between the 32 and 20 nm rows, linear in the node
        w = (32 - 28) / (32 - 20)
        return (1 - w) * factor(32, vdd) + w * factor(20, vdd)
    a, b, c = COEFFS[node]
    return a * vdd * vdd + b * vdd + c


def from_180(node: int) -> float:
    """Energy at `node` over energy at 180 nm (1.8 V)."""
    return BRIDGE_180_130 * factor(node, VDD[node]) / factor(130, VDD[130])


def source(node: int) -> str:
    return (f"ESTIMATE: {PAPER}: energy factor a V^2 + b V + c at {node} nm and {VDD[node]} V over that of 130 nm "
            f"at 1.3 V ({factor(node, VDD[node]):.4g} / {factor(130, 1.3):.4g}), times classical C V^2 scaling "
            f"180 -> 130 nm ({BRIDGE_180_130:.4f}); factor {from_180(node):.5f}")
