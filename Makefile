# Quick start on a fresh Debian 12 machine (as root):
#   make run    installs missing packages, builds, searches the 10^6-point lattice at m = 3.015
#   make test   builds and runs every test and the docs' snippets, builds the docs, then the CPU
#               suite again under ASan + UBSan
# Also: make docs (build/docs/html), make package (build/horizon_VERSION_amd64.deb),
#       make wheel (build/wheel/), make bench, make fuzz, make device-deps.
BUILD ?= build
JOBS ?= $(shell nproc)
PYTHON ?= /usr/bin/python3  # Debian's, with Debian's Sphinx, pybind11 and NumPy
PACKAGES = build-essential cmake libgtest-dev libbenchmark-dev libcli11-dev libfmt-dev \
           nlohmann-json3-dev libnanoflann-dev libhwy-dev libopenmpi-dev openmpi-bin \
           python3-dev python3-pybind11 pybind11-dev python3-numpy python3-scipy python3-pytest \
           python3-venv python3-pip python3-matplotlib python3-meshio python3-ase \
           doxygen python3-sphinx furo python3-myst-parser python3-breathe gfortran pkg-config

.PHONY: deps build run test test-sanitize docs package wheel device-deps fuzz bench clean

deps:
	@missing=$$(for p in $(PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "installing:" $$missing; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	fi

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

# The default problem: lattice n = 100 (10^6 points), horizon 3.015 h (h = 0.1).
run: build
	$(BUILD)/bin/horizon search lattice:100 --horizon 0.3015 --out $(BUILD)/lattice100
	$(BUILD)/bin/horizon verify lattice:100 $(BUILD)/lattice100 --horizon 0.3015 --sample 2000

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)
	$(MAKE) docs
	$(MAKE) test-sanitize

# The documentation site: Doxygen XML of the public headers, then Sphinx (MyST pages, Breathe,
# autodoc of the built Python package), warnings as errors and every internal reference checked.
docs: build
	rm -rf $(BUILD)/docs
	mkdir -p $(BUILD)/docs
	sed 's|build/|$(BUILD)/|g' docs/Doxyfile | doxygen -
	HORIZON_DOXYGEN_XML=$(abspath $(BUILD))/docs/doxygen/xml PYTHONPATH=$(BUILD)/python \
	  $(PYTHON) -m sphinx -W -n --keep-going -q -b html docs $(BUILD)/docs/html
	@echo "docs: $(BUILD)/docs/html/index.html"

# Debian package of the library, headers, CMake package and CLI.
package: build
	cd $(BUILD) && cpack -G DEB
	@ls $(BUILD)/horizon_*.deb

# A Python wheel built with Debian's pybind11 and NumPy (no download), the CUDA module included
# when nvcc is found.
wheel: deps
	$(PYTHON) -m pip wheel --no-build-isolation --no-deps -w $(BUILD)/wheel .
	@ls $(BUILD)/wheel/horizon-*.whl

# Debian packages the GPU machine's image lacks, for bench/device/build.sh (carry .deps).
device-deps:
	mkdir -p .deps && cd .deps && apt-get download libhwy-dev libhwy1 libnanoflann-dev

# The CPU suite (and the MPI tests at 1-3 ranks and the C API) built with AddressSanitizer and
# UndefinedBehaviorSanitizer (not the installed-package consumer, the examples and the packaging
# tests, which test how things link and install, not memory), for the SSE4 and AVX2 kernels:
# the Release suite runs every target the CPU has. The MPI tests run without leak
# detection: OpenMPI's plugins, unloaded at exit, keep allocations LeakSanitizer cannot attribute.
# -O1 -g1 (line tables): the SIMD kernels compile 3x faster than at -O2 -g (2-core VM: 50 s vs 147 s).
SANITIZE = -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
test-sanitize: deps
	cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
	  -DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_FORTRAN=off -DHORIZON_EXAMPLES=OFF \
	  -DHORIZON_BENCH=OFF "-DHORIZON_SIMD_DISABLED=(HWY_SSSE3|HWY_AVX3|HWY_AVX3_DL)" "-DCMAKE_CXX_FLAGS=$(SANITIZE)" "-DCMAKE_EXE_LINKER_FLAGS=$(SANITIZE)" \
	  "-DCMAKE_SHARED_LINKER_FLAGS=$(SANITIZE)"
	cmake --build build-sanitize -j $(JOBS)
	cd build-sanitize && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  HORIZON_DIFFERENTIAL_PROBLEMS=60 ctest --output-on-failure -j $(JOBS) -E "mpi|find_package_consumer"
	cd build-sanitize && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  HORIZON_DIFFERENTIAL_PROBLEMS=40 ctest --output-on-failure -j $(JOBS) -R "mpi_np[123]|mpi_cli"

# libFuzzer (Debian's clang) over every reader of user files, FUZZ_SECONDS per target, JOBS
# targets at a time; inputs that reach new code are merged into the committed corpus, which
# `make test` replays (under the sanitizers too).
FUZZ_TARGETS = npy_points text_points extxyz lammps_data bond_filters neighbor_list
FUZZ_SECONDS ?= 600
FUZZ_FLAGS = -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
fuzz:
	@dpkg -s clang libomp-dev >/dev/null 2>&1 || (apt-get update -qq && apt-get install -y -qq clang libomp-dev)
	cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHORIZON_FUZZ=ON \
	  -DHORIZON_TESTS=OFF -DHORIZON_BENCH=OFF -DHORIZON_CUDA=off -DHORIZON_PYTHON=off -DHORIZON_MPI=OFF \
	  "-DCMAKE_CXX_FLAGS=$(FUZZ_FLAGS)" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined"
	cmake --build build-fuzz -j $(JOBS)
	printf '%s\n' $(FUZZ_TARGETS) | xargs -P $(JOBS) -I{} sh -c 'mkdir -p build-fuzz/found/{} && \
	  build-fuzz/bin/fuzz_{} -max_total_time=$(FUZZ_SECONDS) -timeout=10 -rss_limit_mb=4096 \
	    -artifact_prefix=build-fuzz/crash-{}- build-fuzz/found/{} tests/fuzz/corpus/{} > build-fuzz/fuzz_{}.log 2>&1; \
	  status=$$?; echo "fuzz_{}: exit $$status"; tail -n 2 build-fuzz/fuzz_{}.log; exit $$status'
	for t in $(FUZZ_TARGETS); do build-fuzz/bin/fuzz_$$t -merge=1 tests/fuzz/corpus/$$t build-fuzz/found/$$t 2>&1 | tail -n 1; done

bench: build
	$(BUILD)/bin/horizon_bench

clean:
	rm -rf $(BUILD)
