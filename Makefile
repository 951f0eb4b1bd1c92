# The README's two commands: `make demo` (set up + main demo) and `make test` (set up + suite).
export MUJOCO_GL ?= egl
PY := .venv/bin/python

.PHONY: setup demo test lint bench
setup:
	bash scripts/setup.sh

demo: setup
	.venv/bin/goalagent run agents/examples/hello_world.goal --max-cycles 50

test: setup
	$(PY) -m pytest -q -p no:cacheprovider

lint:
	.venv/bin/ruff check .

bench:
	$(PY) bench/cycles.py
