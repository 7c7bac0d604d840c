# Thin wrapper: deps + build + run + test. The real build is CMake (CMakeLists.txt).
BUILD      ?= build
BUILD_TYPE ?= RelWithDebInfo
JOBS       ?= 2
CONFIG     ?= config/server.pbtxt
SANITIZE   ?= OFF
# the project's version, as CMakeLists.txt declares it
VERSION    := $(shell grep -m1 -o 'contactsim VERSION [0-9.]*' CMakeLists.txt | cut -d' ' -f3)
FUZZ       ?= OFF
# Unity build: CMake compiles each layer's sources eight to a unit, so Eigen
# and gtest are parsed once a unit instead of once a file (four test files:
# 36 s of CPU one by one, 20 s as one unit). UNITY=OFF compiles one file a
# unit (quicker rebuilds after editing one file).
UNITY      ?= ON
FUZZ_RUNS  ?= 20000
FUZZ_CI_SECONDS ?= 30
FUZZ_SECONDS ?= 600
# ccache (installed by make deps) keeps objects across build folders and
# clones: paths below the clone are hashed relative to it, and the working
# folder that -g records is left out of the hash (the debug info may then
# name another clone's folder)
export CCACHE_BASEDIR := $(CURDIR)
export CCACHE_NOHASHDIR := 1
# clang for the fuzz build (libFuzzer); the default compiler otherwise
CMAKE_CXX  = $(if $(filter ON,$(FUZZ)),-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang,)

.PHONY: all deps build run viewer wheel sdist spy package package-check docker docker-check test test-cpp test-py test-asan fuzz fuzz-build fuzz-ci bench bench-micro bench-lockstep soak flood clean

all: build

# Idempotent: checks what is installed and installs only what is missing.
deps:
	@bash scripts/install_deps.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DCONTACTSIM_SANITIZE=$(SANITIZE) \
	  -DCONTACTSIM_FUZZ=$(FUZZ) -DCMAKE_UNITY_BUILD=$(UNITY) $(CMAKE_CXX) $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache,)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j$(JOBS)

# The viewer runs beside the server and prints its URL (docs/viewer.md).
VIEWER_PORT ?= 8765
VIEWER = CONTACTSIM_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/contactsim-viewer --port $(VIEWER_PORT)

run: build
	@$(VIEWER) & trap "kill $$! 2>/dev/null" EXIT INT TERM; $(BUILD)/bin/contactsim-server --config $(CONFIG)

# The viewer alone, for a server started elsewhere (it needs only the generated LCM types).
viewer: deps $(BUILD)/CMakeCache.txt
	@cmake --build $(BUILD) --target contactsim_lcmtypes_gen >/dev/null
	$(VIEWER)

# The Python client as a wheel with its generated LCM types, in $(BUILD)/dist
# (docs/packaging.md); offline, from the .venv's setuptools, wheel and lcm-gen.
wheel: deps
	.venv/bin/pip wheel -q --no-deps --no-build-isolation -w $(BUILD)/dist clients/python
	@ls $(BUILD)/dist/contactsim-*.whl

# lcm-spy with the jar of the message classes, so every channel decodes
# (LCM_URL=... for another URL than the default).
spy: deps $(BUILD)/CMakeCache.txt
	@cmake --build $(BUILD) --target contactsim_lcmtypes_jar >/dev/null
	bash scripts/spy.sh $(BUILD) $(if $(LCM_URL),--lcm-url=$(LCM_URL),)

# The client's sdist in $(BUILD)/dist, with the .lcm files in it, so that a
# wheel builds from it alone (docs/packaging.md, "Python sdist").
sdist: deps
	cd clients/python && ../../.venv/bin/python -c "import setuptools.build_meta as b; b.build_sdist('$(abspath $(BUILD))/dist')"
	@ls $(BUILD)/dist/contactsim-*.tar.gz

# contactsim_<version>_amd64.deb in $(BUILD): programs, C++ client, config,
# systemd unit (docs/packaging.md)
package: build
	cd $(BUILD) && cpack -G DEB

# The .deb installed, upgraded, removed and purged for real in a throwaway
# Debian root (a container); needs root and a Docker engine, so not in
# `make test`, which checks the package without them (tests/python/test_deb.py).
package-check: package
	bash scripts/package_check.sh $(BUILD)/contactsim_$(VERSION)_amd64.deb

# The server image, built from the package (docker/Dockerfile; docs/packaging.md,
# "Docker"): a debootstrap base once, then the build and runtime stages.
# Minutes, so not in `make test`; `make docker-check` drives the built image.
DOCKER_IMAGE ?= contactsim:$(VERSION)
docker:
	bash scripts/docker_base.sh
	docker build -f docker/Dockerfile -t $(DOCKER_IMAGE) .
	@docker image inspect -f '{{.Size}}' $(DOCKER_IMAGE) | awk '{printf "$(DOCKER_IMAGE): %.0f MB\n", $$1/1e6}'

docker-check: deps
	.venv/bin/python scripts/docker_check.py --image $(DOCKER_IMAGE)

test: build
	@$(MAKE) --no-print-directory test-cpp test-py

# RANDOM_SCENES: the seeded random scenes of each set per method
# (tests/contact/random_scenes_test.cpp; the sanitizer suite runs 1)
test-cpp:
	cd $(BUILD) && RANDOM_SCENES=10 ctest --output-on-failure -j$(JOBS)

test-py:
	CONTACTSIM_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python -m pytest -q tests/python $(PYTEST_ARGS)

# Both suites again on a clang Debug build (-O1) with AddressSanitizer,
# UndefinedBehaviorSanitizer and libFuzzer's coverage instrumentation (the
# Python tests drive the instrumented server and tools), then the libFuzzer
# targets of the same build (fuzz-ci): one sanitizer build instead of two.
# Its scene tests also check that clang ends every method on the hashes g++
# pinned (docs/snapshots.md, "Determinism across builds"). The long
# scenario cases listed in tests/sanitizer_exclusions.txt, with their
# times, are left to `make test`; the random scenes run one scene a set
# (RANDOM_SCENES=1). CI runs this after `make test`.
ASAN_BUILD = build-asan
ASAN_CTEST_EXCLUDE = $(shell sed -e 's/\#.*//' -e 's/[[:space:]]*$$//' tests/sanitizer_exclusions.txt | grep -v '^$$' | paste -sd'|')
FUZZ_BUILD = $(ASAN_BUILD)
# Python suites the sanitizer run leaves to `make test`: they pace a server
# in real time against another process (Drake's iiwa, Panda and WSG drivers),
# track a trajectory at 1 kHz for seconds of simulated time, or render
# robots and megabyte surfaces in a browser, or follow pinocchio's passive
# iiwa for seconds at 1 kHz (soft's 42 s under the sanitizers); what they
# exercise in the server runs under the sanitizers in the other suites. The
# soak runs 1,000 steps there (3,000 steps took 253 s).
ASAN_PYTEST_SKIP = --ignore=tests/python/test_iiwa_driver.py --ignore=tests/python/test_panda_driver.py \
	--ignore=tests/python/test_wsg_driver.py --ignore=tests/python/test_driver_replay.py \
	--ignore=tests/python/test_viewer_models.py --ignore=tests/python/test_viewer_surfaces.py \
	--deselect=tests/python/test_joint_channels.py::test_iiwa_tracks_a_joint_trajectory_at_1khz_in_lockstep \
	--deselect=tests/python/test_models.py::test_passive_iiwa_follows_pinocchio
test-asan: fuzz-build
	cd $(ASAN_BUILD) && RANDOM_SCENES=1 ctest --output-on-failure -j$(JOBS) -E '$(ASAN_CTEST_EXCLUDE)'
	@CONTACTSIM_SOAK_STEPS=1000 $(MAKE) --no-print-directory test-py BUILD=$(ASAN_BUILD) PYTEST_ARGS='$(ASAN_PYTEST_SKIP)'
	@$(MAKE) --no-print-directory fuzz-ci

# The sanitizer build (clang, ASan, UBSan, libFuzzer coverage) with the fuzz
# targets. A folder configured otherwise (g++, or without FUZZ) is
# reconfigured from scratch.
fuzz-build: deps
	@grep -qs 'CONTACTSIM_FUZZ:BOOL=ON' $(FUZZ_BUILD)/CMakeCache.txt || { rm -rf $(FUZZ_BUILD); \
	  $(MAKE) --no-print-directory $(FUZZ_BUILD)/CMakeCache.txt BUILD=$(FUZZ_BUILD) BUILD_TYPE=Debug SANITIZE=ON FUZZ=ON; }
	cmake --build $(FUZZ_BUILD) -j$(JOBS)

# each target stops at FUZZ_RUNS executions or FUZZ_CI_SECONDS, whichever
# comes first (the apply target runs ~30 inputs a second under the sanitizers)
fuzz-ci: fuzz-build
	scripts/fuzz.sh $(FUZZ_BUILD) -runs=$(FUZZ_RUNS) -max_total_time=$(FUZZ_CI_SECONDS)

# The fuzz targets for FUZZ_SECONDS each (the corpus in build-asan/fuzz grows
# across runs; a crash input is left there as crash-*).
fuzz: fuzz-build
	scripts/fuzz.sh $(FUZZ_BUILD) -max_total_time=$(FUZZ_SECONDS)

# The standard scenes in contactsim (every contact method), Bullet, ODE and
# MuJoCo, side by side; rewrites the generated tables in BENCHMARKS.md
# (takes tens of minutes; prints progress).
bench: build
	.venv/bin/python bench/scripts/bench_scenes.py --build-dir $(BUILD)

# The Google Benchmark micro benchmarks (broadphase, narrowphase, penalty).
bench-micro: build
	$(BUILD)/bin/contactsim-bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

# Lockstep cycles per second (one controller, 1 and 100 bodies) beside a raw
# LCM ping-pong between two processes, measured in the same run (BENCHMARKS.md).
bench-lockstep: build
	$(BUILD)/bin/contactsim-bench-lockstep --config $(CONFIG)

# A real server under random valid and invalid commands from several
# clients for STEPS steps (default 100,000), recorded with lcm-logger: no
# crash, no NaN, RSS growth after warm-up < 5%, an identical --replay
# (docs/reliability.md). `make test` runs a 3,000-step version.
STEPS ?= 100000
soak: build
	CONTACTSIM_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python scripts/soak.py --steps $(STEPS)

# One client publishes ADDS ADD commands (default 100,000) without waiting
# while another measures its reply latency every 20 ms; prints latencies and
# the server's RSS (docs/reliability.md). `make test` runs 20,000.
ADDS ?= 100000
flood: build
	CONTACTSIM_BUILD_DIR=$(abspath $(BUILD)) .venv/bin/python scripts/flood.py --adds $(ADDS)

clean:
	rm -rf $(BUILD)
