# SPDX-License-Identifier: LGPL-2.1-or-later
# Facet's front door. Every target installs the Debian packages it is missing.
#
#   make          build libcore and facet._core in place (workbench/facet/)
#   make demo     planarize the bundled facade: OBJ, JSON report, FreeCAD document, PNG
#   make test     every test: C (ctest), Python (pytest), FreeCAD headless, FreeCAD GUI (Xvfb),
#                 and the C tests again built with AddressSanitizer + UBSan (test-sanitize)
#   make check-memory  the C tests under valgrind memcheck (normal build)
#   make bench    solver benchmarks (ns per face per iteration, 1 and 2 threads)
#   make install  the workbench into FreeCAD's user Mod folders and a `facet` command
#   make fuzz     libFuzzer on the C API and the Python readers (FUZZ_SECONDS per target)
#   make screenshots  the tutorial's screenshots (taken by the GUI test) into docs/images
#   make translations resources/translations/Facet.ts from the sources and .ui forms

# FreeCAD's interpreter: Debian's, not whatever python3 is first on PATH.
PYTHON ?= /usr/bin/python3
BUILD ?= build
OUT ?= out
DRAG_SCREEN ?= 1600x1000x24
PREFIX ?= $(HOME)/.local
JOBS ?= 2

PKGS_BUILD = gcc make cmake pkg-config libsuitesparse-dev liblapack-dev python3-dev python3-numpy
PKGS_PYTHON = python3-pytest python3-numpy python3-scipy python3-shapely python3-ezdxf \
              python3-matplotlib python3-pynest2d fonts-dejavu-core
PKGS_FREECAD = freecad xvfb xauth
PKGS_MEMCHECK = valgrind
PKGS_FUZZ = clang libclang-rt-14-dev libomp-14-dev python3.11-dev
PKGS_TRANSLATE = pyqt5-dev-tools
ENSURE = sh tools/ensure-packages.sh

CORE = $(BUILD)/libcore/.built
FC_ENV = sh tests/fc_env.sh

.PHONY: all build deps deps-build deps-test test test-c test-python test-freecad test-gui \
        demo examples bench bench-panels bench-drag install uninstall clean build-sanitize \
        test-sanitize check-memory fuzz fuzz-build screenshots translations

all: build

deps-build:
	@$(ENSURE) $(PKGS_BUILD)

deps-test: deps-build
	@$(ENSURE) $(PKGS_PYTHON) $(PKGS_FREECAD)

deps: deps-test

build: deps-build
	cmake -S libcore -B $(BUILD)/libcore -DCMAKE_BUILD_TYPE=Release \
	    -DPython3_EXECUTABLE=$(PYTHON) -DFACET_PYTHON_OUTPUT_DIR=$(CURDIR)/workbench/facet
	cmake --build $(BUILD)/libcore -j $(JOBS)

test: deps-test build
	$(MAKE) --no-print-directory test-c test-sanitize test-python test-freecad test-gui

test-c: build
	cd $(BUILD)/libcore && ctest --output-on-failure

# The C library and tests with AddressSanitizer and UndefinedBehaviorSanitizer
# (every report fatal), run with the default thread count, 1 thread (the
# *_1thread tests) and 2 threads. OMP_WAIT_POLICY=passive: libgomp's spinning
# workers are slowed so much by ASan on a shared machine that a run took 10x
# longer; waiting passively changes no result. No suppressions: libgomp,
# CHOLMOD, SPQR and OpenBLAS gave no report (leak checking included).
SAN_BUILD = $(BUILD)/sanitize
SAN_ENV = ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1 \
          UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
          OMP_WAIT_POLICY=passive

build-sanitize: deps-build
	cmake -S libcore -B $(SAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	    -DFACET_SANITIZE=address,undefined -DFACET_PYTHON=OFF -DFACET_BENCH=OFF
	cmake --build $(SAN_BUILD) -j $(JOBS)

test-sanitize: build-sanitize
	cd $(SAN_BUILD) && $(SAN_ENV) ctest -j $(JOBS) --output-on-failure
	cd $(SAN_BUILD) && $(SAN_ENV) OMP_NUM_THREADS=2 ctest -j $(JOBS) --output-on-failure -E _1thread

# Every C test under valgrind memcheck, on the normal (optimised) build:
# any error or definite leak fails (tools/sanitizer/check-memory.sh).
check-memory: build
	@$(ENSURE) $(PKGS_MEMCHECK)
	sh tools/sanitizer/check-memory.sh $(BUILD)/libcore/tests

test-python: deps-test build
	PYTHONPATH=$(CURDIR)/workbench $(PYTHON) -m pytest -q tests/python

test-freecad: deps-test build
	$(FC_ENV) headless

test-gui: deps-test build
	$(FC_ENV) gui $(OUT)/gui

# the tutorial's screenshots, taken by the GUI test (tests/gui), into docs/images
SCREENSHOTS = facade_surface taskpanel_surface_mesh facade_control_mesh taskpanel_planarize \
              facade_planarized taskpanel_panels facade_panels taskpanel_cutsheets \
              facade_cutsheets lifting lifting_mix taskpanel_lift_pins lift_pins
screenshots: deps-test build
	$(FC_ENV) gui $(OUT)/gui
	mkdir -p docs/images
	for name in $(SCREENSHOTS); do cp $(OUT)/gui/$$name.png docs/images/; done

# resources/translations/Facet.ts from the Python sources and the .ui forms (pylupdate5)
translations:
	@$(ENSURE) $(PKGS_TRANSLATE)
	pylupdate5 workbench/InitGui.py workbench/facetwb/*.py workbench/facetwb/*/*.py \
	    resources/ui/*.ui -ts resources/translations/Facet.ts

demo: deps-test build
	sh tools/demo.sh $(OUT)/demo

# examples/facade.FCStd, roof.FCStd, roof_plan.dxf and roof_heights.csv (commit them after
# a change)
examples: deps-test build
	$(PYTHON) tools/make_example_plan.py
	$(FC_ENV) freecadcmd tools/make_examples.py

# BENCH_ARGS: options of tools/bench/run_bench.py; BENCH_ARGS=--quick is a smoke run (< 1 min)
# bench_planarize and bench_surface call no BLAS; OPENBLAS_NUM_THREADS=1 keeps OpenBLAS's
# worker threads, which may spin for about 0.1 s after the library loads, off the cores
# that the first two-thread solves measure (docs/benchmarks.md, "OpenBLAS's start-up spin").
bench: deps-test build
	mkdir -p $(OUT)/bench
	OPENBLAS_NUM_THREADS=1 $(BUILD)/libcore/bench/bench_planarize $(if $(findstring --quick,$(BENCH_ARGS)),--max-faces 10000 --runs 3,--runs 5) \
	    --json $(OUT)/bench/bench_c.json
	OPENBLAS_NUM_THREADS=1 $(BUILD)/libcore/bench/bench_surface --runs 5 --json $(OUT)/bench/bench_surface.json
	$(BUILD)/libcore/bench/bench_lift --runs 5 --json $(OUT)/bench/bench_lift.json
	PYTHONPATH=$(CURDIR)/workbench $(PYTHON) tools/bench/run_bench.py --out $(OUT)/bench $(BENCH_ARGS)
	$(PYTHON) tools/bench/interactive.py --live --mesh quad_grid --mesh hex_torus --mesh level6 \
	    --json $(OUT)/bench/interactive.json

# the 10,000-panel fabrication pipeline, each stage timed
bench-panels: deps-test build
	$(PYTHON) tools/bench_panels.py --panels 10000 --out $(OUT)/bench_panels

# FUZZ_SECONDS per target, 7 targets: the default is 12 minutes in all.
# Findings go to $(BUILD)/fuzz/findings/ and make the target fail; keep each
# as a regression input in libcore/fuzz/regressions/<target>/ (see libcore/fuzz/README.md).
FUZZ_SECONDS ?= 105
FUZZ_TARGETS ?= mesh planarize lift panel cleanup surface python
fuzz-build: deps-build
	@$(ENSURE) $(PKGS_FUZZ)
	CC=clang cmake -S libcore -B $(BUILD)/fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFACET_FUZZ=ON \
	    -DFACET_SANITIZE=address,undefined -DFACET_BENCH=OFF -DFACET_TESTS=OFF \
	    -DPython3_EXECUTABLE=$(PYTHON) -DFACET_PYTHON_OUTPUT_DIR=$(CURDIR)/$(BUILD)/fuzz/pyext
	cmake --build $(BUILD)/fuzz -j $(JOBS)

fuzz: fuzz-build
	sh tools/fuzz/run_fuzz.sh $(BUILD)/fuzz $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# dragging a control vertex of a 10k-face facade in FreeCAD under Xvfb: frames per second
bench-drag: deps-test build
	mkdir -p $(OUT)/bench
	FACET_DRAG_JSON=$(abspath $(OUT))/bench/drag_fps.json $(FC_ENV) xvfb-run -a -s "-screen 0 $(DRAG_SCREEN)" \
	    freecad tools/bench/drag_fps.py

install: build
	sh tools/install.sh "$(PREFIX)" "$(PYTHON)"

uninstall:
	sh tools/install.sh --uninstall "$(PREFIX)"

clean:
	rm -rf $(BUILD) $(OUT) workbench/facet/_core*.so
