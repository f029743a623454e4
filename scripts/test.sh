#!/usr/bin/env bash
# Installs everything the tests need (the package, test tools, Debian's Chromium for the browser tests)
# and runs the whole suite. `.ci/run` calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v chromium >/dev/null 2>&1; then
  if [ "$(id -u)" = 0 ]; then apt-get update -qq && apt-get install -y -qq chromium >/dev/null;
  else sudo apt-get update -qq && sudo apt-get install -y -qq chromium >/dev/null; fi
fi
python3 -m pip install -q -e '.[test]'
python3 -m ruff check .
python3 -m pytest "$@"
