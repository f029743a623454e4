#!/usr/bin/env bash
# Installs everything the tests need (the package and test tools in .venv, Debian's Chromium for the
# browser tests, pdflatex with TikZ for the figures' test) and runs the whole suite, then the quick suite
# again on the lowest versions pyproject.toml allows (scripts/test_lowest.sh). `.ci/run` calls exactly
# this. `--quick`: all but the browser tests and the slow ones, current versions only; other arguments
# go to pytest (and leave the lowest versions out).
set -euo pipefail
cd "$(dirname "$0")/.."
as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }
if ! command -v chromium >/dev/null 2>&1; then
  as_root apt-get update -qq && as_root apt-get install -y -qq chromium >/dev/null
fi
if ! command -v pdflatex >/dev/null 2>&1 || ! kpsewhich tikz.sty >/dev/null 2>&1; then
  as_root apt-get update -qq && as_root apt-get install -y -qq texlive-latex-base texlive-pictures >/dev/null
fi
# A virtual environment, so that it works where the system Python refuses pip (PEP 668). Like the
# README's quick start, it sees no system packages: the tests run on exactly what pyproject.toml asks for.
if [ ! -x .venv/bin/python ]; then
  if ! python3 -m venv .venv 2>/dev/null; then  # Debian: venv is its own package
    rm -rf .venv
    as_root apt-get update -qq && as_root apt-get install -y -qq python3-venv >/dev/null
    python3 -m venv .venv
  fi
fi
.venv/bin/python -m pip install -q -e '.[test,notebook,fast]'
.venv/bin/python -m ruff check .
.venv/bin/python -m mypy  # the package, as configured in pyproject.toml
# The core, the workbench and the API under --strict (their imports checked, not reported: the rest of
# the package keeps the basic strictness above).
.venv/bin/python -m mypy --strict --follow-imports=silent apf_viz/core apf_viz/workbench apf_viz/api
whole=$([ "$#" = 0 ] && echo yes || echo no)  # no arguments: the whole suite, then the lowest versions
if [ "${1:-}" = "--quick" ]; then  # lint, types, and every test but the browser's and the slow ones
  shift
  set -- -m "not browser and not slow" "$@"
fi
# Four workers on two cores: a browser test mostly waits (on Chromium, on the server's frames), so two
# more workers fill the waits (docs/PERFORMANCE.md, "The suite"). APF_VIZ_TEST_WORKERS=0: one process.
if [ "$whole" = yes ]; then
  # The lowest version of every direct dependency (scripts/lowest.txt), in a fresh virtual environment,
  # installed while the suite runs (pip waits on the network and the disk, the suite on the CPU: 2.5 of
  # the command's minutes, docs/PERFORMANCE.md); its tests after the suite.
  bash scripts/test_lowest.sh --prepare > .lowest-prepare.log 2>&1 &
  preparing=$!
  trap 'kill "$preparing" 2>/dev/null || true' EXIT
fi
.venv/bin/python -m pytest -n "${APF_VIZ_TEST_WORKERS:-4}" --dist load --durations=15 "$@"
if [ "$whole" = yes ]; then
  if ! wait "$preparing"; then
    cat .lowest-prepare.log
    echo "the lowest versions' environment could not be made (above)" >&2
    exit 1
  fi
  trap - EXIT
  cat .lowest-prepare.log
  bash scripts/test_lowest.sh --prepared  # installed, `apf-viz serve` answering a page, their tests
fi
