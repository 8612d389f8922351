#!/usr/bin/env bash
# On the GPU machine: the Python package built for the image's python3 (the one with PyTorch and
# CuPy; pybind11 from its pip packages), then the whole Python suite with the GPU required.
# Usage: bash bench/gpu/device_python.sh  (writes $OUT/pytest.log)
export CMAKE_ARGS="-DPython_EXECUTABLE=$(command -v python3) -Dpybind11_DIR=$(python3 -m pybind11 --cmakedir)"
source bench/gpu/device_build.sh
HORIZON_CLI="$BUILD/bin/horizon" PYTHONPATH="$BUILD/python" python3 -m pytest -q -rs -p no:cacheprovider tests/python \
  2>&1 | tee "$OUT/pytest.log" | tail -15
