# The README's two commands. Each installs missing Debian packages, then builds with CMake.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: deps build demo test test-sanitize clean

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS) -- --no-print-directory

# The main job: the live demo with a display, a headless recording without one.
demo: build
	@$(BUILD_DIR)/fogpipe demo

# The whole test suite (what CI runs).
test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) --timeout 900

# The suite again, built with AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer
# (float-cast-overflow included): CI runs it after `make test`. Mesa's and LLVM's own
# allocations kept until exit are suppressed by name (tests/sanitizers/lsan.supp), not by
# switching leak checks off.
SANITIZE_DIR ?= build-sanitize
# A report exits 86, a code no command uses: the bad-input corpus expects exit 1 of most
# cases, which a sanitizer's default exit code (1) met.
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1:abort_on_error=0:exitcode=86 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers/lsan.supp:print_suppressions=0:exitcode=86 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:exitcode=86
test-sanitize: deps
	@cmake -S . -B $(SANITIZE_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFOGPIPE_SANITIZE=ON >/dev/null
	@cmake --build $(SANITIZE_DIR) -j $(JOBS) -- --no-print-directory
	@cd $(SANITIZE_DIR) && $(SANITIZER_ENV) ctest --output-on-failure -j $(JOBS) --timeout 1800

clean:
	rm -rf $(BUILD_DIR) $(SANITIZE_DIR)

# libFuzzer harnesses (tests/fuzz/, docs/reliability.md): each target for FUZZ_SECONDS.
FUZZ_SECONDS ?= 60
.PHONY: fuzz fuzz-regressions
fuzz: deps
	@bash tests/fuzz/run.sh all $(FUZZ_SECONDS)

# Every harness built and run once over its seeds and regression inputs (no fuzzing; CI
# runs it, so the harnesses keep building against the libraries they test).
fuzz-regressions: deps
	@bash tests/fuzz/run.sh regressions
