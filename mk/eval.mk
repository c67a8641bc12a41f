# make eval: image quality against traced pixels (scripts/eval.py, package msr_eval).
#   make eval          quick run: small frames, every scene, both renderer modes -> out/eval/
#   make eval FULL=1   1920x1080, every scene, both modes; also writes docs/results.md, docs/img/
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
