# The two set-up commands: `make demo` and `make test`. Both install missing
# dependencies first (scripts/install-deps.sh), then build with CMake: `make demo` only the
# command line, `make test` and `make bench` everything (tests, benchmarks). docs/build.md.
JOBS ?= $(shell nproc)
BUILD ?= build/release
TYPE ?= Release

.PHONY: all deps configure cli build demo test example test-real bench asan fuzz clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(TYPE) -DPROXIMA_BUILD_TESTS=ON -DPROXIMA_BUILD_BENCH=ON $(CMAKE_EXTRA) >/dev/null

# The command line alone (and the library it links).
cli: configure
	cmake --build $(BUILD) -j $(JOBS) --target proxima

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: cli
	$(BUILD)/proxima demo --out out/demo

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The library as another project uses it (examples/cpp, docs/build.md): installs it into
# EXAMPLE_DIR/prefix, then configures, builds and runs the example against that prefix.
EXAMPLE_DIR ?= $(BUILD)/example
example: configure
	cmake --build $(BUILD) -j $(JOBS) --target proxima_lib
	rm -rf $(EXAMPLE_DIR)/prefix $(EXAMPLE_DIR)/build
	cmake --install $(BUILD) --prefix $(abspath $(EXAMPLE_DIR))/prefix --component library >/dev/null
	cmake -S examples/cpp -B $(EXAMPLE_DIR)/build -DCMAKE_BUILD_TYPE=Release \
	  -DCMAKE_PREFIX_PATH=$(abspath $(EXAMPLE_DIR))/prefix >/dev/null
	cmake --build $(EXAMPLE_DIR)/build -j $(JOBS)
	$(EXAMPLE_DIR)/build/envmap_error

# The real-content tier (docs/real-content.md): scripts/real-content.sh installs the Debian
# packages that ship real models and builds the corpus in REAL_CONTENT, then every technique
# runs on it with the built-in scenes' bounds (tests/real/). The script exits 3 when the
# packages cannot be installed here (.ci/run runs it first and skips the tier then).
REAL_CONTENT ?= build/real-content
test-real: build
	@bash scripts/real-content.sh --out $(REAL_CONTENT)
	PROXIMA_REAL_CONTENT=$(abspath $(REAL_CONTENT)) $(BUILD)/proxima_tests --gtest_filter='RealContent.*'

bench: build
	$(BUILD)/proxima bench trace --out out/bench-trace

# Debug build with AddressSanitizer + UndefinedBehaviorSanitizer (+ float-cast-overflow),
# whole test suite. Every report is fatal (-fno-sanitize-recover), leaks included.
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1 \
	LSAN_OPTIONS=suppressions=$(CURDIR)/fuzz/lsan.supp UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
asan:
	$(SANITIZER_ENV) $(MAKE) test BUILD=build/asan TYPE=Debug \
	  CMAKE_EXTRA="-DPROXIMA_SANITIZE=ON -DPROXIMA_BUILD_BENCH=OFF"

# Each libFuzzer target in FUZZ_TARGETS (default: all of fuzz/) for FUZZ_SECONDS on its
# corpus (clang; scripts/fuzz.sh). Runs them all, then fails if any found something.
FUZZ_SECONDS ?= 30
FUZZ_TARGETS ?= $(patsubst fuzz/%_fuzz.cpp,%,$(wildcard fuzz/*_fuzz.cpp))
fuzz:
	@bash scripts/install-deps.sh --fuzz
	@status=0; for t in $(FUZZ_TARGETS); do \
	  $(SANITIZER_ENV) JOBS=$(JOBS) bash scripts/fuzz.sh $$t $(FUZZ_SECONDS) || status=1; \
	done; exit $$status

clean:
	rm -rf build out
