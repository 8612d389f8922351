#!/usr/bin/env bash
# pip install --no-build-isolation . into a fresh venv made as Debian wants (--system-site-packages),
# then import the installed package from elsewhere and search. Usage: pip_install_test.sh SOURCE WORK
set -euo pipefail
source_dir=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
# Unoptimised (-O0, CMAKE_BUILD_TYPE None) and for this CPU's SIMD level only: this tests how the
# package builds and installs, and compiles in a fraction of the portable Release build's time.
HORIZON_CMAKE_ARGS="-DHORIZON_CUDA=off -DCMAKE_BUILD_TYPE=None -DHORIZON_NATIVE=ON" "$work/venv/bin/pip" install --no-build-isolation --no-deps -q "$source_dir"
cd "$work"
"$work/venv/bin/python" - <<'PY'
import horizon
assert "site-packages" in horizon.__file__, horizon.__file__
nl = horizon.search(horizon.lattice(30), 0.5)
assert nl.total == 459360, nl.total  # 6 face neighbours x 29*30*30 + 12 edge neighbours x 29*29*30
i, S = horizon.primitive_neighbor_list("iS", [True] * 3, [[1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0.2, 0.3, 0.4]], 1.5)
assert len(i) == 18, len(i)  # the atomistic module is installed: 6 images at 1, 12 at sqrt(2)
print("installed:", horizon.__file__, nl)
PY
