#!/usr/bin/env bash
# Installs everything goalagent needs on a bare Debian machine: SWI-Prolog (when swipl is
# missing), a virtualenv in .venv, and the package with its dev and bench extras.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v swipl >/dev/null 2>&1; then
    echo "setup: installing SWI-Prolog (swi-prolog-nox)"
    SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends swi-prolog-nox >/dev/null
fi
if [ ! -x .venv/bin/python ]; then
    echo "setup: creating .venv"
    python3 -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e ".[dev,bench]"
echo "setup: done (.venv ready, swipl $(swipl --version | awk '{print $3}'))"
