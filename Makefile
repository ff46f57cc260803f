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
#   ASAN_DIR      AddressSanitizer + UndefinedBehaviorSanitizer build folder (default: build-asan)
#   ASAN_TESTS    gtest filter of sylva_core_tests run under ASan+UBSan (default: all)
#   FUZZ_DIR      libFuzzer build folder of `make fuzz` (default: build-fuzz; clang-14)
#   FUZZ_SECONDS  seconds of fuzzing per loader target (default: 600)

BUILD_DIR    ?= build
JOBS         ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS   ?=
DEMO_PROJECT ?= projects/demo/demo.sylva
DEMO_OUT     ?= out/demo
SYLVA_BIN     = $(BUILD_DIR)/bin/sylva
TSAN_DIR     ?= build-tsan
TSAN_TESTS   ?= Scheduler.*:TileCache.*:TileEvaluator.*:Clipmap.*:WorkerPool.*:LodSelectorScene.SelectionIs*
ASAN_DIR     ?= build-asan
ASAN_TESTS   ?= *
ASAN_FLAGS    = -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
FUZZ_DIR     ?= build-fuzz
FUZZ_SECONDS ?= 600
FUZZ_TARGETS  = gltf_import obj_import plod manifest sidecar

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
.PHONY: help setup samples build demo test tsan asan fuzz goldens clean

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
	@echo "make asan     build the core and DSL tests with ASan+UBSan in $(ASAN_DIR), run them (halt on error)"
	@echo "make fuzz     build the loaders' libFuzzer targets (clang-14) in $(FUZZ_DIR), fuzz each $(FUZZ_SECONDS) s"
	@echo "make goldens  regenerate tests/render/goldens/*.png (review before committing)"
	@echo "make clean    remove $(BUILD_DIR)/, $(TSAN_DIR)/, $(ASAN_DIR)/ and out/ (data/ is kept)"

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
	$(MAKE) --no-print-directory asan

tsan:
	cmake -S . -B $(TSAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSYLVA_WERROR=OFF \
	  -DCMAKE_CXX_FLAGS=-fsanitize=thread -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread \
	  -DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=thread $(CMAKE_ARGS)
	cmake --build $(TSAN_DIR) -j$(JOBS) --target sylva_core_tests
	TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
	  $(TSAN_DIR)/tests/sylva_core_tests --gtest_filter='$(TSAN_TESTS)'

# AddressSanitizer + UndefinedBehaviorSanitizer over the CPU tests (core and DSL): any
# report aborts (halt_on_error, -fno-sanitize-recover), so `make test` fails on it.
# Leak checking is on; the tests' data files come from data/ as in the main build.
asan:
	cmake -S . -B $(ASAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSYLVA_WERROR=OFF \
	  "-DCMAKE_CXX_FLAGS=$(ASAN_FLAGS)" "-DCMAKE_C_FLAGS=$(ASAN_FLAGS)" \
	  "-DCMAKE_EXE_LINKER_FLAGS=$(ASAN_FLAGS)" "-DCMAKE_SHARED_LINKER_FLAGS=$(ASAN_FLAGS)" $(CMAKE_ARGS)
	cmake --build $(ASAN_DIR) -j$(JOBS) --target sylva_core_tests sylva_dsl_tests
	ASAN_OPTIONS="halt_on_error=1 detect_leaks=1 abort_on_error=0" \
	  LSAN_OPTIONS="suppressions=$(CURDIR)/tests/sanitizers/lsan.supp print_suppressions=0" \
	  UBSAN_OPTIONS="halt_on_error=1 print_stacktrace=1" \
	  $(ASAN_DIR)/tests/sylva_core_tests --gtest_filter='$(ASAN_TESTS)'
	ASAN_OPTIONS="halt_on_error=1 detect_leaks=1" \
	  LSAN_OPTIONS="suppressions=$(CURDIR)/tests/sanitizers/lsan.supp print_suppressions=0" \
	  UBSAN_OPTIONS="halt_on_error=1 print_stacktrace=1" \
	  $(ASAN_DIR)/tests/sylva_dsl_tests

# libFuzzer on the file loaders (tests/fuzz): each target in turn, niced, for FUZZ_SECONDS,
# starting from the committed seeds; new inputs go to $(FUZZ_DIR)/corpus/TARGET and
# crashes to $(FUZZ_DIR)/crash-*. Not part of `make test` (CI replays the seeds instead:
# CTest fuzz.replay.*).
fuzz:
	CC=clang-14 CXX=clang++-14 cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DSYLVA_WERROR=OFF -DSYLVA_FUZZ=ON $(CMAKE_ARGS)
	cmake --build $(FUZZ_DIR) -j$(JOBS) $(addprefix --target sylva_fuzz_,$(FUZZ_TARGETS))
	for target in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ_DIR)/corpus/$$target && \
	  (cd $(FUZZ_DIR) && nice -n 19 tests/fuzz/sylva_fuzz_$$target corpus/$$target \
	    $(CURDIR)/tests/fuzz/corpus/$$target -max_total_time=$(FUZZ_SECONDS) -timeout=20 \
	    -rss_limit_mb=2048 -print_final_stats=1 2>&1 | tail -n 25) || exit 1; \
	done

# Rewrites the golden images from the current renderer; see tests/README.md.
goldens:
	$(call cmake_build,$(WERROR_TEST))
	SYLVA_UPDATE_GOLDENS=1 ctest --test-dir $(BUILD_DIR) -L golden --output-on-failure --no-tests=error
	@echo "goldens rewritten in tests/render/goldens/; review the changed PNGs before committing:"
	@git status --short -- tests/render/goldens 2>/dev/null || true

clean:
	rm -rf $(BUILD_DIR) $(TSAN_DIR) $(ASAN_DIR) $(FUZZ_DIR) out
