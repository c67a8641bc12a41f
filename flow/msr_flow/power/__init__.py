"""make power: switching activity from a simulated frame, priced with the OSU 0.18 um liberty
on the mapped netlists of make asic (msr_flow.asic), the tile buffers priced with the cited
SRAM macro's own read and write energies; energy per decision and per pixel, scaled to 28 nm
and 7 nm, and the balance against the rays the decisions save (docs/asic.md, "Power")."""
