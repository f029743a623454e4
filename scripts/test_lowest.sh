#!/usr/bin/env bash
# The lowest versions pyproject.toml allows (scripts/lowest.txt), in a fresh virtual environment that
# sees no system packages: apf-viz installed on them, the tests that reach each dependency run (LOWEST_TESTS),
# and `apf-viz serve` answering a page. Other arguments go to pytest instead of that list.
set -euo pipefail
cd "$(dirname "$0")/.."
prepare() {
  rm -rf .venv-lowest
  python3 -m venv .venv-lowest
  .venv-lowest/bin/python -m pip install -q -r scripts/lowest.txt
  .venv-lowest/bin/python -m pip install -q --no-deps -e .
  .venv-lowest/bin/python - <<'PY'
import importlib.metadata as m
import re
from pathlib import Path
for line in Path("scripts/lowest.txt").read_text().splitlines():
    if line and not line.startswith("#"):
        name, version = re.split(r"==", re.sub(r"\[.*\]", "", line))
        assert m.version(name) == version, (name, m.version(name), version)
print("apf-viz on the lowest versions:", ", ".join(l.split("==")[0] + " " + l.split("==")[1]
      for l in Path("scripts/lowest.txt").read_text().splitlines() if l and not l.startswith("#")))
PY
}
# --prepare: only the environment (scripts/test.sh makes it while the suite runs: it waits on the network
# and the disk, the suite on the CPU); --prepared: the environment is made, run the tests on it.
case "${1:-}" in
  --prepare) prepare; exit 0 ;;
  --prepared) shift ;;
  *) prepare ;;
esac
port=$(.venv-lowest/bin/python -c "from apf_viz.ui.network import free_port; print(free_port())")
.venv-lowest/bin/apf-viz serve --port "$port" > /tmp/apf-viz-lowest-serve.log 2>&1 &
server=$!
trap 'kill -INT $server 2>/dev/null || true' EXIT
for _ in $(seq 1 120); do
  if .venv-lowest/bin/python -c "import urllib.request,sys; urllib.request.urlopen('http://127.0.0.1:$port/', timeout=1)" 2>/dev/null; then
    echo "apf-viz serve answered a page on the lowest versions"; break
  fi
  sleep 0.5
done
.venv-lowest/bin/python -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/', timeout=5)"
if grep -q "lacks" /tmp/apf-viz-lowest-serve.log; then cat /tmp/apf-viz-lowest-serve.log; exit 1; fi
# The tests that reach each dependency's API (the rest run on the newest versions only: running the whole
# quick suite again here took six minutes of the README's test command for no dependency it does not
# reach below). viser, msgspec, zstandard: the scene, the shared producer, the server; numpy, numba,
# hypothesis: the geometry and the compiled view kernel; pydantic: every file format and lectures;
# imageio, pillow: images, figures, recordings; dask, pyarrow, matplotlib, pandas, tqdm: the sweep, the
# hunt and the API. tests/test_house.py holds every dependency of scripts/lowest.txt to a file here.
LOWEST_TESTS=(
  tests/test_viser_compat.py tests/test_broadcast.py tests/test_scene.py tests/test_portrayal.py
  tests/test_serve.py tests/test_coordinates.py tests/test_grid.py tests/test_shapes.py
  tests/test_visibility.py tests/test_view_kernel.py tests/test_lecture.py tests/test_security.py
  tests/test_image.py tests/test_figure.py tests/test_recorder.py tests/test_sweep.py tests/test_hunt.py
  tests/test_api.py tests/test_api_workflow.py tests/test_join.py
)
if [ "$#" = 0 ]; then set -- "${LOWEST_TESTS[@]}"; fi
.venv-lowest/bin/python -m pytest -p no:cacheprovider -n "${APF_VIZ_TEST_WORKERS:-4}" --dist load -m "not browser and not slow" "$@"
