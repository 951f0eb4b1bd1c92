# The README's two commands: `make demo` (set up + main demo) and `make test` (set up, the
# import-layer contract of pyproject.toml, then the suite).
export MUJOCO_GL ?= egl
PY := .venv/bin/python

.PHONY: setup demo test lint bench
setup:
	bash scripts/setup.sh

demo: setup
	.venv/bin/goalagent run agents/garbage_disposal.mas2g \
		--save-beliefs out/exp1.pl --plot out/exp1-reliability.png
	.venv/bin/goalagent run agents/garbage_disposal.mas2g --env-param can=o2 \
		--load-beliefs out/exp1.pl --save-beliefs out/exp2.pl --plot out/exp2-reliability.png

test: setup
	.venv/bin/lint-imports --no-cache
	$(PY) -m pytest -q -p no:cacheprovider

lint:
	.venv/bin/ruff check .

bench:
	$(PY) bench/cycles.py
