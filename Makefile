# The README's two commands: `make demo` (set up the package with its robot extra, then the
# main demo) and `make test` (set up everything the tests use, the import-layer contract of
# pyproject.toml, then the suite, which builds the documentation site with --strict: in two
# worker processes (pytest-xdist), each test file whole in one, handed out in the order
# tests/conftest.py gives (the heavy files first), its slowest tests listed).
export MUJOCO_GL ?= egl
PY := .venv/bin/python

.PHONY: setup demo test lint bench docs
setup:
	bash scripts/setup.sh

demo:
	bash scripts/setup.sh --demo
	.venv/bin/goalagent run agents/garbage_disposal.mas2g \
		--save-beliefs out/exp1.pl --plot out/exp1-reliability.png
	.venv/bin/goalagent run agents/garbage_disposal.mas2g --env-param can=o2 \
		--load-beliefs out/exp1.pl --save-beliefs out/exp2.pl --plot out/exp2-reliability.png

test: setup
	.venv/bin/lint-imports --no-cache
	$(PY) -m pytest -q -p no:cacheprovider -n 2 --dist loadfile --no-loadscope-reorder --durations=25

lint:
	.venv/bin/ruff check .

bench:
	$(PY) bench/cycles.py

docs: setup
	.venv/bin/mkdocs build --strict
