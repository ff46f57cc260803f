# Sylva: entry points for people and CI.
#   make demo     set up, fetch samples, build, render the demo project, list the images
#   make test     set up, fetch samples, build (warnings are errors), run the whole test suite
# Both do all set-up on a fresh Debian 12 machine (scripts/setup needs root or sudo).
#
# Variables (override on the command line, e.g. `make test BUILD_DIR=build-asan`):
#   BUILD_DIR     CMake build folder (default: build)
#   SYLVA_WERROR  ON/OFF (default ON everywhere, so demo and test share one build)
#   JOBS          parallel build jobs (default: nproc)
#   CMAKE_ARGS    extra arguments for the CMake configure step
#   TSAN_DIR      ThreadSanitizer build folder of `make test` (default: build-tsan)
#   TSAN_TESTS    gtest filter run under ThreadSanitizer (the threaded tile code, WorkerPool)

BUILD_DIR    ?= build
JOBS         ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS   ?=
DEMO_PROJECT ?= projects/demo/demo.sylva
DEMO_OUT     ?= out/demo
SYLVA_BIN     = $(BUILD_DIR)/bin/sylva
TSAN_DIR     ?= build-tsan
TSAN_TESTS   ?= Scheduler.*:TileCache.*:TileEvaluator.*:Clipmap.*:WorkerPool.*:LodSelectorScene.SelectionIs*

# An explicit SYLVA_WERROR (command line or environment) wins everywhere.
ifdef SYLVA_WERROR
  WERROR_TEST  := $(SYLVA_WERROR)
  WERROR_BUILD := $(SYLVA_WERROR)
else
  WERROR_TEST  := ON
  WERROR_BUILD := ON
endif

# Recipes run in bash with pipefail, so a piped ctest keeps its exit status.
SHELL        := /bin/bash
.SHELLFLAGS  := -o pipefail -c

# ctest prints its timing summaries after "N% tests passed, N tests failed out
# of N"; this filter holds that line back (everything else streams through
# unchanged) and prints it last.
CTEST_SUMMARY_LAST = awk '/^[0-9]+% tests passed, [0-9]+ tests failed out of [0-9]+/ { s = $$0; next } \
  s == "" { print; fflush(); next } \
  NF || t != "" { t = t $$0 "\n" } \
  END { printf "%s", t; if (s != "") { if (t != "") print ""; print s } }'

# Steps run in the order written, even under make -j.
.NOTPARALLEL:
.DEFAULT_GOAL := help
.PHONY: help setup samples build demo test tsan goldens clean

# $(call cmake_build,WERROR): Release configure + build into $(BUILD_DIR) with Ninja.
define cmake_build
	@if [ -f "$(BUILD_DIR)/CMakeCache.txt" ] && ! grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' "$(BUILD_DIR)/CMakeCache.txt"; then \
	  echo "make: $(BUILD_DIR) was configured with another CMake generator; run 'make clean' first" >&2; exit 1; fi
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSYLVA_WERROR=$(1) $(CMAKE_ARGS)
	cmake --build $(BUILD_DIR) -j$(JOBS)
endef

help:
	@echo "make demo     set up, fetch samples, build, render $(DEMO_PROJECT) into $(DEMO_OUT)"
	@echo "make test     set up, fetch samples, build with SYLVA_WERROR=$(WERROR_TEST), run all tests (ctest)"
	@echo "make setup    install the Debian packages (scripts/setup)"
	@echo "make samples  fetch the sample data into data/ (scripts/fetch-samples)"
	@echo "make build    Release build into $(BUILD_DIR)/ (SYLVA_WERROR=$(WERROR_BUILD))"
	@echo "make tsan     build sylva_core_tests with ThreadSanitizer in $(TSAN_DIR), run the threaded tile tests"
	@echo "make goldens  regenerate tests/render/goldens/*.png (review before committing)"
	@echo "make clean    remove $(BUILD_DIR)/, $(TSAN_DIR)/ and out/ (data/ is kept)"

setup:
	scripts/setup

samples:
	scripts/fetch-samples

build:
	$(call cmake_build,$(WERROR_BUILD))

demo:
	scripts/setup
	scripts/fetch-samples
	$(call cmake_build,$(WERROR_BUILD))
	rm -rf $(DEMO_OUT)
	$(SYLVA_BIN) render $(DEMO_PROJECT) --out $(DEMO_OUT)
	@echo "demo images:"
	@ls -1 $(DEMO_OUT)/*.png 2>/dev/null || { echo "make: no PNG was written to $(DEMO_OUT)" >&2; exit 1; }

# ctest's summary line is the last thing printed; --no-tests=error makes an
# empty suite fail instead of passing silently. Then the scheduler and cache tests
# (with the 10 s stress test) run again under ThreadSanitizer: only sylva_core_tests
# is built in $(TSAN_DIR); any report fails the build (halt_on_error).
test:
	scripts/setup
	scripts/fetch-samples
	$(call cmake_build,$(WERROR_TEST))
	ctest --test-dir $(BUILD_DIR) --output-on-failure --no-tests=error -j2 2>&1 | $(CTEST_SUMMARY_LAST)
	$(MAKE) --no-print-directory tsan

tsan:
	cmake -S . -B $(TSAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSYLVA_WERROR=OFF \
	  -DCMAKE_CXX_FLAGS=-fsanitize=thread -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread \
	  -DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=thread $(CMAKE_ARGS)
	cmake --build $(TSAN_DIR) -j$(JOBS) --target sylva_core_tests
	TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
	  $(TSAN_DIR)/tests/sylva_core_tests --gtest_filter='$(TSAN_TESTS)'

# Rewrites the golden images from the current renderer; see tests/README.md.
goldens:
	$(call cmake_build,$(WERROR_TEST))
	SYLVA_UPDATE_GOLDENS=1 ctest --test-dir $(BUILD_DIR) -L golden --output-on-failure --no-tests=error
	@echo "goldens rewritten in tests/render/goldens/; review the changed PNGs before committing:"
	@git status --short -- tests/render/goldens 2>/dev/null || true

clean:
	rm -rf $(BUILD_DIR) $(TSAN_DIR) out
