#!/usr/bin/env bash
# Installs what goalagent needs on a bare Debian machine (as root or with sudo): SWI-Prolog
# (when swipl is missing), EGL/Mesa, a virtualenv in .venv and the package in it.
#   bash scripts/setup.sh          for the tests (`make test`): also Chromium and its driver
#                                  (the inspector's browser test), and the dev (with docs),
#                                  bench, cluster (Ray) and gym (Gymnasium) extras
#   bash scripts/setup.sh --demo   for `make demo`: the package with its robot extra only
# Without root, see "Install" in docs/getting-started.md: pip in a virtualenv against the
# SWI-Prolog your system (or Homebrew, or conda) has.
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
FOR_TESTS=1
[ "${1:-}" = "--demo" ] && FOR_TESTS=0
missing=()
command -v swipl >/dev/null 2>&1 || missing+=(swi-prolog-nox)
# Headless MuJoCo rendering (MUJOCO_GL=egl) needs EGL and Mesa's software drivers.
libraries=$(ldconfig -p)  # (grep -q on a pipe would SIGPIPE ldconfig under pipefail)
grep -q 'libEGL.so.1 ' <<<"$libraries" || missing+=(libegl1)
grep -q 'libOpenGL.so.0 ' <<<"$libraries" || missing+=(libopengl0)
[ -e /usr/share/glvnd/egl_vendor.d/50_mesa.json ] || missing+=(libegl-mesa0 libgl1-mesa-dri)
# The mind inspector's end-to-end test drives Debian's headless Chromium through chromedriver.
if [ "$FOR_TESTS" -eq 1 ]; then
    command -v chromium >/dev/null 2>&1 || missing+=(chromium)
    command -v chromedriver >/dev/null 2>&1 || missing+=(chromium-driver)
fi
if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: installing ${missing[*]} with apt-get"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
        "${missing[@]}" >/dev/null
fi
if [ ! -x .venv/bin/python ]; then
    echo "setup: creating .venv"
    python3 -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip
if [ "$FOR_TESTS" -eq 1 ]; then
    .venv/bin/python -m pip install -q -e ".[dev,bench,cluster,gym]"
else
    .venv/bin/python -m pip install -q -e ".[robot]"
fi
# An editable install leaves our own modules uncompiled, and where PYTHONDONTWRITEBYTECODE is
# set (as in many CI images) every Python process compiles them again when it starts: compile
# them once here, as pip does for what it installs (a file changed since is recompiled).
.venv/bin/python -m compileall -q goalagent behaviours robot sim ondisk >/dev/null
# Likewise the GOAL parser's LALR tables (0.2 s of every goalagent process's start), kept
# beside the bytecode (goalagent/parser/grammar.py).
.venv/bin/python -c "from goalagent.parser.grammar import keep_parser; keep_parser()"
echo "setup: done (.venv ready, swipl $(swipl --version | awk '{print $3}'))"
