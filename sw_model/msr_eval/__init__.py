"""msr_eval: the evaluation on top of msr_model's public API (research code, not the contract).

- rules:    decision rules compared by the evaluation (functions of msr_model.PassView)
- methods:  rendering methods compared (full, grid, checkerboard, single level, multi level)
- metrics:  PSNR, SSIM, FLIP, Pareto fronts, summaries
- sweep:    the sweep of scenes x modes x methods x settings, serial or on Dask distributed
- report:   plots, example strips and docs/results.md
"""
