"""msr_eval: the evaluation on top of msr_model's public API (research code, not the contract).

- rules:    decision rules compared by the evaluation (functions of msr_model.PassView)
- gbuffer_rule: the G-buffer edge rules (gbuf, gbuflindilate): the renderer's material id and
            depth with each traced pixel force traces across surfaces
- methods:  rendering methods compared (full, grid, checkerboard, single level, multi level)
- metrics:  PSNR, SSIM, FLIP, Pareto fronts, summaries
- scenes:   the scene set (model files, textured scenes) and scene ids
- sweep:    the sweep of scenes x modes x methods x settings, as tasks on an executor, cached
- executors: where the tasks run: in this process, in order, or on Dask distributed
- dacs:     Deferred Adaptive Compute Shading (Mallett and Yuksel 2018), a peer method
- vrs:      a VRS-like baseline (one shading rate per 8x8 or 16x16 tile)
- reference: the converged reference per scene and mode and the scores against it
- conv_report: the comparison against it (tables, plots, the section leading docs/results.md)
- report:   plots, example strips and docs/results.md
- present:  what the pages and plots share (family names, number formats, figures, scene grids)
- textured: docs/results.md sections on the textured scenes and the G-buffer rule
"""
