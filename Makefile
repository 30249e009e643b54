# The two commands of the README:
#   make run   set up a fresh Debian 12 machine, build, install the workbench,
#              then find the contacts of the bundled motor
#   make test  build if needed, then every test: GoogleTest, pytest, GUI (Xvfb)
SHELL := /bin/bash
.DEFAULT_GOAL := run

BUILD_DIR    ?= build
PYTHON       := /usr/bin/python3
JOBS         ?= $(shell nproc)
SUDO         := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
# FreeCAD 0.20 loads user workbenches from $HOME/.local/share/FreeCAD/Mod/<name>/.
FREECAD_MOD  ?= $(HOME)/.local/share/FreeCAD/Mod
INSTALL_DIR  := $(FREECAD_MOD)/Contacts
BIN_DIR      ?= $(HOME)/.local/bin
SAMPLE       ?= Resources/samples/motor.step

# What `make run` needs, in two lists: what the build of the extension needs
# (a compiler, CMake, Ninja, the libraries it links), installed first, and
# what only the installed workbench and later rebuilds need (FreeCAD, Qt's SVG
# module, Graphviz, ccache), installed while the extension compiles (`run`).
# The compiler is clang-14: it compiles the extension with less CPU than g++ 12
# (idle, a cold `make run` from a clone: 197 s against 285 s) from smaller
# packages; g++ (`make run CONTACTS_CXX=g++`, with the test packages) gives the
# same results (docs/benchmarks.md, issue 23). libfontconfig-dev: OCCT's
# visualization toolkit (TKService, which the STEP reader's XDE links) names
# -lfontconfig, and libocct-visualization-dev does not pull it in (a fresh
# Debian 12's `make run` failed at the extension's link without it, 27 Nov).
DEB_BUILD_PACKAGES := libocct-foundation-dev libocct-modeling-data-dev \
  libocct-modeling-algorithms-dev libocct-data-exchange-dev libocct-ocaf-dev \
  libocct-visualization-dev libhidapi-dev pybind11-dev python3-pybind11 \
  python3-dev cmake make clang-14 libtbb-dev libeigen3-dev libfcl-dev pkg-config ninja-build \
  libfontconfig-dev
DEB_APP_PACKAGES := freecad python3-pyside2.qtsvg graphviz ccache
DEB_PACKAGES := $(DEB_BUILD_PACKAGES) $(DEB_APP_PACKAGES)
# What `make test`, `make bench`, `make sanitize` and `make fuzz` add (g++ for a
# g++ build folder and the sanitizer build).
DEB_TEST_PACKAGES := $(DEB_PACKAGES) g++ libcoin-dev python3-pytest googletest libgtest-dev \
  libbenchmark-dev python3-pil xvfb xauth clang libclang-rt-14-dev liburdfdom-tools libmujoco-dev

.PHONY: run test deps deps-test build build-extension install uninstall samples bench test-cpp test-python test-gui clean fuzz sanitize

# The packages of $(1) that dpkg does not have ("install ok installed"), as a
# shell command substitution.
missing = $$(for p in $(1); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | \
  grep -q '^install ok installed' || echo $$p; done)
# sudo drops the environment: DEBIAN_FRONTEND goes through env. dpkg's
# --force-unsafe-io skips its fsync before each file's rename (what Debian's
# own container images set): the files installed are the same; a power cut
# during the install can leave some of them empty (docs/benchmarks.md).
APT_INSTALL = env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
  -o Dpkg::Options::=--force-unsafe-io

# Installs only the packages that are missing.
define install_missing
	@missing="$(call missing,$(1))"; \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages:" $$missing; \
	  $(SUDO) apt-get update -q && $(SUDO) $(APT_INSTALL) $$missing; \
	else echo "All Debian packages present."; fi
endef

deps:
	$(call install_missing,$(DEB_PACKAGES))

deps-test:
	$(call install_missing,$(DEB_TEST_PACKAGES))

# ccache, when the machine has it, makes rebuilds in several checkouts cheap.
LAUNCHER     := $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

# The compiler of a new build folder (CMake reads CXX on a folder's first
# configure only: an existing folder keeps the compiler it was made with).
CONTACTS_CXX ?= clang++-14

CONFIGURE    := CXX=$(CONTACTS_CXX) cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=$(PYTHON) $(LAUNCHER)

# A first configure for `make run` asks for neither GoogleTest nor Google
# Benchmark (a fresh machine has only the run packages). With Ninja (looked
# for when the recipe runs: `make deps` may just have installed it) the three
# targets of the extension compile side by side: Make's generator builds
# target after target, a core, then haptics, then bindings, each ending with
# one core idle. A build folder keeps its generator: later configures
# (`make build`) give none.
$(BUILD_DIR)/CMakeCache.txt:
	$(CONFIGURE) $$(command -v ninja >/dev/null && echo -G Ninja) -DCONTACTS_BUILD_TESTS=OFF -DCONTACTS_BUILD_BENCH=OFF

# Everything: the extension, the GoogleTest suites, benchmarks and fuzz replays.
build:
	$(CONFIGURE) -DCONTACTS_BUILD_TESTS=ON -DCONTACTS_BUILD_BENCH=ON
	cmake --build $(BUILD_DIR) -j $(JOBS)

# What `make run` needs and nothing more: the Python extension (the CLI and
# the workbench are Python around it).
build-extension: $(BUILD_DIR)/CMakeCache.txt
	cmake --build $(BUILD_DIR) -j $(JOBS) --target contactcore_py

# Copies the workbench (and the built extension) where FreeCAD reads it, and
# a `contacts` command-line wrapper into $(BIN_DIR).
install: build-extension
	$(PYTHON) tools/install_workbench.py --build-dir $(BUILD_DIR) --mod-dir $(INSTALL_DIR) --bin-dir $(BIN_DIR)

uninstall:
	rm -rf $(INSTALL_DIR) $(BIN_DIR)/contacts

# The build's packages first; then the extension compiles while the
# workbench's packages (FreeCAD and what only it pulls in: about half of the
# download) install beside it. dpkg keeps about one core busy, the compile
# two, and neither needs the other until `install` copies the workbench into
# FreeCAD's folder, which waits for both. apt's output of that second step
# goes to $(BESIDE_LOG), shown if it fails. sudo is asked for in the
# foreground (apt-get update) before apt-get runs in the background, which
# therefore never prompts (sudo -n). LAUNCHER is passed down as this make
# found it: ccache, installed beside the build, is not used by a build that
# started before it was there.
BESIDE_LOG   := $(BUILD_DIR)/packages-beside-build.log
SUDO_BESIDE  := $(if $(SUDO),sudo -n)
run:
	@missing="$(call missing,$(DEB_PACKAGES))"; \
	if [ -n "$$missing" ]; then $(SUDO) apt-get update -q; fi
	@missing="$(call missing,$(DEB_BUILD_PACKAGES))"; \
	if [ -n "$$missing" ]; then echo "Installing the build's Debian packages:" $$missing; \
	  $(SUDO) $(APT_INSTALL) $$missing; else echo "The build's Debian packages are present."; fi
	@beside="$(call missing,$(DEB_APP_PACKAGES))"; \
	if [ -n "$$beside" ]; then mkdir -p $(BUILD_DIR); \
	  echo "Installing beside the build (output in $(BESIDE_LOG)):" $$beside; \
	  $(SUDO_BESIDE) $(APT_INSTALL) $$beside < /dev/null > $(BESIDE_LOG) 2>&1 & pid=$$!; fi; \
	$(MAKE) --no-print-directory build-extension LAUNCHER="$(LAUNCHER)"; built=$$?; \
	if [ -n "$$beside" ]; then \
	  if wait $$pid; then echo "Installed beside the build:" $$beside; \
	  else tail -n 20 $(BESIDE_LOG); echo "Installing $$beside failed: see $(BESIDE_LOG)"; exit 1; fi; fi; \
	exit $$built
	@$(MAKE) --no-print-directory install LAUNCHER="$(LAUNCHER)"
	$(BIN_DIR)/contacts $(SAMPLE)

samples:
	$(PYTHON) tools/make_samples.py --out Resources/samples

bench: deps-test build
	$(PYTHON) bench/run_benchmarks.py --build-dir $(BUILD_DIR) --plot docs/read_scaling.png
	$(PYTHON) bench/bench_bad_inputs.py --build-dir $(BUILD_DIR)
	$(PYTHON) bench/bench_gui.py --build-dir $(BUILD_DIR)

test: deps-test build
	@bash tests/run_all.sh $(BUILD_DIR)

test-cpp: deps-test build
	cd $(BUILD_DIR) && ctest --output-on-failure

test-python: deps-test build
	CONTACTS_BUILD_DIR=$(abspath $(BUILD_DIR)) CONTACTS_PYTHON_DIR=$(abspath $(BUILD_DIR))/python $(PYTHON) -m pytest -q tests --ignore=tests/gui

test-gui: deps-test build
	CONTACTS_BUILD_DIR=$(abspath $(BUILD_DIR)) $(PYTHON) -m pytest -q tests/gui

# Reliability builds (docs/reliability.md), separate from `make test`: the core
# and its tests or fuzz targets only (no Python extension), with -O1 -g.
SANITIZE_DIR ?= build-sanitize
FUZZ_DIR     ?= build-fuzz
FUZZ_SECONDS ?= 60
# fuzz_step's own time (a child process per job, fuzz/run_fuzzers.sh); 600 s is a run that matters.
FUZZ_STEP_SECONDS ?= $(FUZZ_SECONDS)
CHECK_FLAGS  := -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCONTACTS_BUILD_PYTHON=OFF -DCONTACTS_BUILD_BENCH=OFF $(LAUNCHER)

# AddressSanitizer + UBSan build of the core and its GoogleTest suites, run by
# ctest (and by the build's test discovery); suppressions, for Debian's
# uninstrumented libraries only, in fuzz/*.supp.
SANITIZER_ENV := ASAN_OPTIONS=detect_leaks=1 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/fuzz/lsan.supp:print_suppressions=0 \
  UBSAN_OPTIONS=suppressions=$(CURDIR)/fuzz/ubsan.supp:print_stacktrace=1:halt_on_error=1
sanitize: deps-test
	cmake -S . -B $(SANITIZE_DIR) -DCONTACTS_SANITIZE=ON $(CHECK_FLAGS)
	$(SANITIZER_ENV) cmake --build $(SANITIZE_DIR) -j $(JOBS) --target contactcore_tests fuzz_replay_tests
	cd $(SANITIZE_DIR) && $(SANITIZER_ENV) ctest --output-on-failure -j $(JOBS)

# libFuzzer targets (clang 14) run $(FUZZ_SECONDS) s each on a copy of the
# seed corpus in fuzz/corpus/; fails on any crash, leak, timeout or OOM.
fuzz: deps-test
	CC=clang-14 CXX=clang++-14 cmake -S . -B $(FUZZ_DIR) -DCONTACTS_FUZZ=ON -DCONTACTS_BUILD_TESTS=OFF $(CHECK_FLAGS)
	cmake --build $(FUZZ_DIR) -j $(JOBS) --target fuzz_step fuzz_brep fuzz_hid
	FUZZ_STEP_SECONDS=$(FUZZ_STEP_SECONDS) bash fuzz/run_fuzzers.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

clean:
	rm -rf $(BUILD_DIR)
