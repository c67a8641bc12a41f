# make sim: interim flow until the RTL system and the Embree unit land (issues 3 and 5):
# the golden model on the built-in procedural test picture.
SIM_OUT = $(if $(OUT),$(OUT),out/sim/testimage)

sim: setup
	@echo "make sim: RTL flow not built yet; running the golden model on the built-in test picture"
	$(ENV) python scripts/sim_golden.py --width $(WIDTH) --height $(HEIGHT) --tile $(TILE) \
	    --levels $(LEVELS) --thr $(THR) --metric $(METRIC) --fov-gain $(FOV_GAIN) --out $(SIM_OUT)
