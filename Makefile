# Whitted: every command a developer or a newcomer needs. All targets are idempotent.
#   make render [SCENE=path/to.blend]   set everything up, render headless (the report's final
#                                       scene by default), print the PNG path
#   make render SCENE=path/to.lua       render a CS488 Lua scene script to the PNG it names
#   make test                           set everything up, lint, run the whole test suite, and
#                                       the Blender tests in every bpy version
#   make test-python                    the kernel tests as plain Python (NUMBA_DISABLE_JIT=1)
#   make bench                          run the benchmarks in tests/benchmarks/
#   make fuzz [FUZZ_EXAMPLES=5000]      the fuzz tests' properties with thousands of examples
SHELL := /bin/bash
PYTHON ?= python3
VENV := .venv
BUILD := .build
SITE := $(VENV)/lib/python3.11/site-packages
SCENE ?= sample_blends/final_scene.blend
RENDERS := $(CURDIR)/build/renders

# One numba kernel cache shared by tests, benchmarks and Blender subprocesses.
export WHITTED_CACHE_DIR ?= $(CURDIR)/.cache/kernels
# Blender finds the add-on (a link to blender_addon/) here, and numpy/numba in the venv.
export BLENDER_USER_SCRIPTS := $(CURDIR)/$(BUILD)/blender_scripts
BLENDER_RUN := PYTHONPATH=$(CURDIR):$(CURDIR)/$(SITE) blender -b --python-use-system-env

.PHONY: setup render test test-python bench fuzz samples addon lint format clean

# The Blenders tested as the bpy module besides the .venv's 5.0, each in .venvs/bpy-<version>
# (tests/blender/versions.py, which holds their pins; a test checks the two lists agree)
BPY_VERSIONS := 4.2 4.5 5.2
BPY_VENVS := $(foreach v,$(BPY_VERSIONS),.venvs/bpy-$(v)/.installed)

setup: $(VENV)/.installed $(BUILD)/blender.ok $(BUILD)/xvfb.ok $(BLENDER_USER_SCRIPTS)/addons/whitted

.venvs/bpy-%/.installed: tests/blender/versions.py pyproject.toml | $(VENV)/.installed
	$(VENV)/bin/python -m tests.blender.versions venv $*
	touch $@

$(VENV)/.installed: pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))' || \
	  { echo "Whitted needs Python 3.11 (Blender's Python); set PYTHON=python3.11"; exit 1; }
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/pip install --quiet --upgrade pip
	$(VENV)/bin/pip install --quiet -e ".[test,bench,farm]"
	touch $@

# $(call debian_package,COMMAND,PACKAGE,MESSAGE): install Debian's PACKAGE when COMMAND is
# not on PATH and we may (root, apt-get); otherwise print MESSAGE (no commas) and fail
define debian_package
	@if ! command -v $(1) >/dev/null; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "Installing Debian's $(2) package (no $(1) on PATH)"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(2) >/dev/null; \
	  else \
	    echo "$(3)"; \
	    exit 1; \
	  fi; \
	fi
endef

$(BUILD)/blender.ok:
	$(call debian_package,blender,blender,Whitted needs Blender 3.4 or newer as 'blender' on PATH: \
	  install it (Debian/Ubuntu: sudo apt-get install blender) and run make again)
	@mkdir -p $(BUILD) && blender --version | head -n 1 && touch $@

# An X server without a screen, for the tests of Blender's window (tests/blender/test_window_*)
$(BUILD)/xvfb.ok:
	$(call debian_package,Xvfb,xvfb,The window tests need Xvfb on PATH: install it \
	  (Debian/Ubuntu: sudo apt-get install xvfb) and run make again)
	@mkdir -p $(BUILD) && touch $@

$(BLENDER_USER_SCRIPTS)/addons/whitted:
	mkdir -p $(BLENDER_USER_SCRIPTS)/addons
	ln -sfn ../../../blender_addon $@

# Blender exits 1 when the engine reports an error, but 0 (with a blank picture written) when
# the engine raises: the log decides too
render: setup
ifeq ($(suffix $(SCENE)),.lua)
	$(VENV)/bin/python -m core render "$(SCENE)"
else
	@mkdir -p $(RENDERS)
	set -o pipefail; $(BLENDER_RUN) --addons whitted "$(SCENE)" -E WHITTED \
	  -o "$(RENDERS)/$(basename $(notdir $(SCENE)))_####" -F PNG -f 1 \
	  2>&1 | tee $(RENDERS)/render.log
	@if grep -qE '^Error|Traceback' $(RENDERS)/render.log; then \
	  echo "The render failed: see the errors above"; exit 1; fi
	@echo "Rendered: $(RENDERS)/$(basename $(notdir $(SCENE)))_0001.png"
endif

# The zips a Blender 4.2+ user installs (Preferences > Get Extensions > Install from Disk), one
# per platform; the Linux one with kernels compiled by both Pythons Blender runs (3.11, 3.13)
addon: $(VENV)/.installed .venvs/bpy-5.2/.installed
	$(VENV)/bin/python blender_addon/packaging/build_extension.py dist \
	  $(VENV)/bin/python .venvs/bpy-5.2/bin/python

samples: setup
	$(BLENDER_RUN) --factory-startup --addons whitted --python sample_blends/build_samples.py

lint: $(VENV)/.installed
	$(VENV)/bin/ruff check .
	$(VENV)/bin/ruff format --check .

format: $(VENV)/.installed
	$(VENV)/bin/ruff format .
	$(VENV)/bin/ruff check --fix .

# Each part timed (tests/support/timed_step), the parts and the whole printed at the end as
# `name: seconds` lines; pytest lists its slowest tests, where the kernels' first compiles show
TEST_TIMES := $(BUILD)/test_times
TIMED := tests/support/timed_step $(TEST_TIMES)
# The parts run in two lanes at once: the suite alone kept 1.2 of the 2 cores busy (compiles,
# Blender's start-ups and Python are one thread each). Lane A is pytest and then the bpy
# versions whose kernel cache folder is the .venv's (the same Python and numba: warm once
# pytest is done); lane B, printed after lane A, the plain-Python kernels and the versions
# with a Python or numba of their own (a cache folder of their own, core.jit.cache_folder).
# The bpy environments are made at once too (downloads mostly), after the rest of the set-up
# (whose apt-get installs must not run together). Lane B runs as a job of its own (set -m):
# a job a shell starts with `&` otherwise ignores Ctrl-C, and so would every test process in
# it (and Ctrl-C of `make test` stops it by the trap).
# Blender 3.4's run of the in-process Blender tests (two minutes of one Blender) and its first
# render from an empty cache (40 s) go last in lane B, which is otherwise that much shorter;
# by then lane A's first test has filled the shared kernel cache they load from.
LANE_A_BPY := 4.2
LANE_B_BPY := $(filter-out $(LANE_A_BPY),$(BPY_VERSIONS))
LANE_B_TESTS := tests/blender/test_blender34_cli.py::test_the_in_process_blender_tests_pass_inside_blender_34_too \
  tests/blender/test_blender34_cli.py::test_a_first_render_on_a_new_machine_compiles_only_its_variant_and_says_each_step
LANE_B_LOG := $(BUILD)/test_lane_b.log
test:
	@mkdir -p $(BUILD) && rm -f $(TEST_TIMES) && date +%s >$(TEST_TIMES).start
	@$(TIMED) setup sh -c '$(MAKE) --no-print-directory setup && $(MAKE) --no-print-directory -j3 $(BPY_VENVS)'
	@$(TIMED) lint $(MAKE) --no-print-directory lint
	@echo "Lane B (plain Python; bpy $(LANE_B_BPY); Blender 3.4 in-process) runs beside lane A; its output follows it"
	@set -m; $(MAKE) --no-print-directory test-lane-b >$(LANE_B_LOG) 2>&1 & lane_b=$$!; \
	  trap 'kill -- -$$lane_b 2>/dev/null' INT TERM; \
	  $(MAKE) --no-print-directory test-lane-a; a=$$?; \
	  wait $$lane_b; b=$$?; \
	  echo "== Lane B's output (exit $$b)"; cat $(LANE_B_LOG); \
	  echo "The test run's parts:"; cat $(TEST_TIMES); \
	  echo "test_run_s: $$(( $$(date +%s) - $$(cat $(TEST_TIMES).start) ))"; \
	  [ $$a = 0 ] && [ $$b = 0 ]

# $(call bpy_tests,VERSIONS): each version's tests in its own environment, timed
bpy_tests = for v in $(1); do \
	  $(TIMED) bpy_$$v $(VENV)/bin/python -m tests.blender.versions test $$v || exit 1; done

.PHONY: test-lane-a test-lane-b
test-lane-a:
	@$(TIMED) pytest $(VENV)/bin/python -m pytest --durations=12 $(addprefix --deselect=,$(LANE_B_TESTS))
	@$(call bpy_tests,$(LANE_A_BPY))

test-lane-b:
	@$(TIMED) plain_python $(MAKE) --no-print-directory test-python
	@$(call bpy_tests,$(LANE_B_BPY))
	@$(TIMED) blender34 $(VENV)/bin/python -m pytest -q -p no:cacheprovider --durations=2 $(LANE_B_TESTS)

# The kernel and render tests with numba's JIT off: the kernels run as plain Python, so a
# failure inside one comes with a Python traceback (and pdb works). Small scenes only: the
# tests whose brute-force references or large meshes would take hours in Python stay out.
PYTHON_KERNEL_TESTS := tests/core/kernels/test_shapes.py tests/core/kernels/test_sphere_intersection.py \
  tests/core/kernels/test_slabs.py tests/core/kernels/test_csg.py \
  tests/core/kernels/test_shadow_culling.py tests/core/kernels/test_stability.py \
  tests/core/test_render_accuracy.py tests/core/test_lighting.py \
  tests/core/test_driver.py tests/core/model/test_validation.py
test-python: setup
	NUMBA_DISABLE_JIT=1 $(VENV)/bin/python -m pytest -q -p no:cacheprovider \
	  -W ignore::RuntimeWarning $(PYTHON_KERNEL_TESTS)

FUZZ_EXAMPLES ?= 5000
fuzz: setup
	WHITTED_FUZZ_EXAMPLES=$(FUZZ_EXAMPLES) $(VENV)/bin/python -m pytest -q tests/core/test_fuzz.py \
	  tests/core/cs488/test_fuzz_scripts.py tests/core/test_fuzz_files.py \
	  tests/blender/test_numeric_settings.py

bench: setup $(VENV)/.embree $(BUILD)/povray.ok
	$(VENV)/bin/python -m tests.benchmarks

# POV-Ray 3.7, the classic tracer the final scene is timed against (Debian's povray package)
$(BUILD)/povray.ok:
	$(call debian_package,povray,povray,make bench times POV-Ray 3.7 as 'povray': \
	  install it (sudo apt-get install povray))
	@mkdir -p $(BUILD) && touch $@

$(VENV)/.embree: pyproject.toml | $(VENV)/.installed
	$(VENV)/bin/pip install --quiet -e ".[embree]"
	touch $@

clean:
	rm -rf $(VENV) .venvs $(BUILD) .cache build
