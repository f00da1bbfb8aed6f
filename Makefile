# rownav: the two set-up commands are `make demo` and `make test`.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 600
TEST_FUZZ ?= 1

.PHONY: deps configure build build-demo demo test test-asan test-fuzz fuzz-build fuzz bench bench-suite format clean

deps:
	scripts/install-deps

configure: deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS) >/dev/null

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Only the command line: the demo needs no test or benchmark executable.
build-demo: configure
	cmake --build $(BUILD) -j $(JOBS) --target rownav

## demo: install what is missing, build the command line, run the main job (writes out/demo/)
demo: build-demo
	$(BUILD)/rownav demo --out out/demo --overwrite

## test: install what is missing, build, run every test, then the quick closed-loop benchmark
## (fails when a tracked metric regresses beyond bench/quick_baseline.json's tolerances), then
## every fuzz target for 30 s (`make test-fuzz`: its own clang + ASan tree, build-fuzz/).
## `make test TEST_FUZZ=0` leaves the fuzz runs out.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 600
	rm -rf $(BUILD)/bench-quick
	$(BUILD)/rownav bench --quick --out $(BUILD)/bench-quick --jobs $(JOBS)
ifneq ($(TEST_FUZZ),0)
	$(MAKE) --no-print-directory test-fuzz JOBS=$(JOBS)
endif

## test-fuzz: every fuzz target for 30 s, seed 1 (fails on a crash, an input over 1 s or over
## 512 MB)
test-fuzz: fuzz-build
	FUZZ_BUILD=$(FUZZ_BUILD) FUZZ_JOBS=$(JOBS) FUZZ_SEED=1 scripts/fuzz 30

## fuzz-build: the libFuzzer targets of fuzz/ with clang, ASan + UBSan (own build tree)
fuzz-build: deps
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DROWNAV_FUZZ=ON -DROWNAV_BUILD_TESTS=OFF -DROWNAV_BUILD_BENCH=OFF \
	  -DROWNAV_BUILD_ROS=OFF >/dev/null
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target rownav_fuzzers

## fuzz: every fuzz target for FUZZ_SECONDS (600) s, two at a time (BENCHMARK.md, issue 13)
fuzz: fuzz-build
	FUZZ_BUILD=$(FUZZ_BUILD) FUZZ_JOBS=$(JOBS) scripts/fuzz $(FUZZ_SECONDS)

## test-asan: every CTest test under AddressSanitizer + UBSan (own build tree: build-asan/)
test-asan: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROWNAV_BUILD_BENCH=OFF \
	  -DROWNAV_SANITIZE=address,undefined >/dev/null
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/scripts/lsan.supp:print_suppressions=0 \
	  ctest --output-on-failure -j $(JOBS) --timeout 1800

## bench: run the micro-benchmarks (figures are recorded in BENCHMARK.md)
bench: build
	@for b in $(BUILD)/*_bench; do echo "== $$b"; $$b --benchmark_min_time=0.5; done

## bench-suite: the papers' tables, every method side by side (resumable; out/bench/tables.md)
bench-suite: build
	$(BUILD)/rownav bench --out out/bench --jobs $(JOBS)

format:
	clang-format -i $$(git ls-files '*.hpp' '*.cpp')

clean:
	rm -rf $(BUILD) build-asan $(FUZZ_BUILD) out
