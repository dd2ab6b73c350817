# The two set-up commands: `make demo` and `make test`. Both install missing
# dependencies first (scripts/install-deps.sh), then build with CMake.
JOBS ?= $(shell nproc)
BUILD ?= build/release
TYPE ?= Release

.PHONY: all deps build demo test bench asan clean

all: build

deps:
	@bash scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(TYPE) -DPROXIMA_BUILD_TESTS=ON -DPROXIMA_BUILD_BENCH=ON $(CMAKE_EXTRA) >/dev/null
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	$(BUILD)/proxima demo --out out/demo

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD)/proxima bench trace --out out/bench-trace

# Debug build with AddressSanitizer + UndefinedBehaviorSanitizer, whole test suite.
asan:
	$(MAKE) test BUILD=build/asan TYPE=Debug CMAKE_EXTRA=-DPROXIMA_SANITIZE=ON

clean:
	rm -rf build out
