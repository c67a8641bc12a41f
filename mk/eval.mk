# make eval: image quality against traced pixels (issue 7, scripts/eval.py).
#   make eval          quick run: small frames, every scene, both renderer modes -> out/eval/
#   make eval FULL=1   1920x1080, every scene, both modes; also writes docs/results.md, docs/img/
# EVAL_ARGS passes more flags (for example EVAL_ARGS="--max-scenes 4").
FULL ?= 0
EVAL_ARGS ?=
EVAL_DEPS := $(if $(wildcard mk/renderer.mk),renderer,)

eval: setup $(EVAL_DEPS)
	$(ENV) python scripts/eval.py $(if $(filter 1,$(FULL)),--full --docs,) $(EVAL_ARGS)
