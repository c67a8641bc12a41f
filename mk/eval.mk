# make eval: image quality against traced pixels (scripts/eval.py, package msr_eval).
#   make eval          quick run: small frames, every scene, both renderer modes -> out/eval/
#   make eval FULL=1   1920x1080, every scene, both modes; also writes data/results.json, the
#                      pages docs/results.md and docs/results/*.md, and the figures in docs/img/
#   make eval-pages    only the pages, from the committed data/results.json (no rendering)
# The sweep runs as tasks on Dask distributed: a LocalCluster with one worker per CPU, or the
# scheduler named by DASK_SCHEDULER=tcp://host:port (or the environment variable
# MSR_DASK_SCHEDULER); DASK_SCHEDULER=serial runs it in one process.
# EVAL_ARGS passes more flags (for example EVAL_ARGS="--max-scenes 4").
FULL ?= 0
EVAL_ARGS ?=
DASK_SCHEDULER ?=
EVAL_DEPS := $(if $(wildcard mk/renderer.mk),renderer,)

eval: setup $(EVAL_DEPS)
	$(ENV) python scripts/eval.py $(if $(filter 1,$(FULL)),--full --docs,) \
	    $(if $(DASK_SCHEDULER),--scheduler "$(DASK_SCHEDULER)") $(EVAL_ARGS)

eval-pages: setup
	$(ENV) python -m msr_eval.report --from-records data/results.json
