"""Benchmarks: engine (cocotb on the tile engine), hw (the frame harness), golden (the model),
renderer (Embree)."""
