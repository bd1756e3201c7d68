# centaur: the two commands a user needs.
#   make demo   installs missing Debian packages, builds, runs the main job with embedded defaults
#   make test   installs missing Debian packages, builds, runs the whole test suite (ctest)
BUILD  ?= build
JOBS   ?= $(shell nproc)
OUT    ?= out
# Instruction set of a new build directory, e.g. ARCH=x86-64-v3 (AVX2, faster planner; CMakeLists.txt CENTAUR_ARCH).
ARCH   ?=
CENTAUR = $(BUILD)/src/cli/centaur

# Every Debian package the project needs (build, run, render, plot).
DEBS = cmake make g++ pkg-config libeigen3-dev coinor-libipopt-dev libopenblas0-pthread \
       libmujoco-dev libqhull-dev libyaml-cpp-dev libgtest-dev libgmock-dev libbenchmark-dev \
       libhdf5-dev libcli11-dev nlohmann-json3-dev libosmesa6-dev libstb-dev ffmpeg gnuplot-nox \
       libopenmpi-dev openmpi-bin python3-h5py cyclonedds-dev cyclonedds-tools libtinyxml2-dev
# The HTML report (docs/report.md): chromium for its browser tests; Node.js + npm bundle its viewer at build time
# (a node and npm already on PATH will do, e.g. a newer Node.js; otherwise Debian's).
DEBS += chromium $(if $(shell command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1 && echo y),,nodejs npm)

# Only for `make fuzz` (coverage-guided fuzzing with libFuzzer, fuzz/README.md).
FUZZ_DEBS = clang-14 libclang-rt-14-dev llvm-14
FUZZ_BUILD ?= build-fuzz
FUZZ_TIME ?= 60
FUZZ_TARGETS ?= yaml planner_config sim_config stack primitive arm_trajectory sim_log cli
SANITIZE_BUILD ?= build-sanitize

.PHONY: all deps fuzz-deps configure build demo test bench clean fuzz test-sanitize

all: build

# $(call install_missing,<packages>): install the missing ones as root, else print the apt-get line and stop.
install_missing = missing=""; for p in $(1); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = "0" ]; then \
	    echo "Installing missing Debian packages:$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing >/dev/null || exit 1; \
	  else \
	    echo "Missing Debian packages. Run:"; echo "  sudo apt-get install -y$$missing"; exit 1; \
	  fi; \
	fi

deps:
	@$(call install_missing,$(DEBS))

fuzz-deps:
	@$(call install_missing,$(DEBS) $(FUZZ_DEBS))

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(if $(ARCH),-DCENTAUR_ARCH=$(ARCH))

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(CENTAUR) bench planner

demo: build
	@mkdir -p $(OUT)
	$(CENTAUR) plan squat-jump --out $(OUT)/primitives.h5
	$(CENTAUR) plan half-squat-jump --out $(OUT)/primitives.h5 --append
	$(CENTAUR) inspect $(OUT)/primitives.h5
	$(CENTAUR) plot $(OUT)/primitives.h5 --out $(OUT)/primitives.png
	$(CENTAUR) simulate stand --duration 5 --out $(OUT)/stand.h5 --snapshot $(OUT)/stand.png --at 2 --json
	$(CENTAUR) simulate squat-jump --primitive $(OUT)/primitives.h5 --stabilizer raibert --video $(OUT)/squat-jump-raibert.mp4
	$(CENTAUR) simulate half-squat-jump --primitive $(OUT)/primitives.h5 --stabilizer raibert --video $(OUT)/half-squat-jump-raibert.mp4
	$(CENTAUR) compare --out $(OUT)/compare --primitives $(OUT)/primitives.h5
	@echo
	@echo "Demo outputs in $(OUT)/:"
	@echo "  primitives.h5                      both planned jumps (docs/primitive-format.md)"
	@echo "  primitives-squat-jump.png          forces, feet and waist of the squat jump (like the paper's Fig. 3)"
	@echo "  primitives-half-squat-jump.png     the same for the half-squat jump (rear wheels onto a wall)"
	@echo "  primitives.*.yaml                  the effective planner configurations"
	@echo "  stand.h5, stand.png                CENTAURO standing in MuJoCo: log and snapshot (docs/sim.md)"
	@echo "  squat-jump-raibert.mp4             the squat jump with the Raibert-like stabilizer (docs/jumps.md)"
	@echo "  half-squat-jump-raibert.mp4        the half-squat jump onto the wall, same stabilizer"
	@echo "  compare/compare.md                 both jumps x four stabilizer modes: outcome, pitch, torque (docs/validation.md)"
	@echo "  compare/compare-pitch.png          IMU pitch over time, one panel per jump (like the paper's Fig. 4)"
	@echo "  compare/compare.json, compare-pitch.csv, <jump>-<mode>.h5   the same table, the plotted data, the logs"
	@echo "  compare/report.html                every run replayed in 3D with its plan, synced plots (docs/report.md)"
	@echo
	@echo "Open in a browser (works offline, no server): $(abspath $(OUT))/compare/report.html"

# libFuzzer targets in their own build directory (clang-14, -fsanitize=fuzzer,address,undefined), each run for
# FUZZ_TIME seconds from the committed corpus (fuzz/corpus/<target>); findings go to $(FUZZ_BUILD)/findings/.
fuzz: fuzz-deps
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang-14 \
	  -DCMAKE_CXX_COMPILER=clang++-14 -DCENTAUR_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_targets
	tools/run_fuzz.sh $(FUZZ_BUILD) $(FUZZ_TIME) $(FUZZ_TARGETS)

# The whole test suite built with AddressSanitizer + UndefinedBehaviorSanitizer (g++), in its own build directory.
# -O1 -g1 (line tables: reports name file and line) compiles 1.6x faster than -O2 -g with the same checks.
# Processes started by mpirun run without leak detection: Open MPI's plugins leak at MPI_Finalize and are unloaded
# before LeakSanitizer looks, so their stacks cannot be suppressed by library name (the same sweep code runs with
# leak detection in its threaded tests). Address and UB checks stay on in those processes.
test-sanitize: deps
	cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
	  -DCENTAUR_SANITIZE=ON
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  OMPI_MCA_mca_base_env_list="ASAN_OPTIONS=detect_leaks=0:abort_on_error=1" \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tools/lsan.supp UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD) $(FUZZ_BUILD) $(SANITIZE_BUILD)
