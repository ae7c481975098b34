# brdfit — top-level entry points. `make demo` and `make test` install missing Debian
# packages (scripts/setup-deps.sh), configure, build and run.
BUILD      ?= build
BUILD_ASAN ?= build-asan
JOBS       ?= $(shell nproc)
CMAKE_ARGS ?=
DEMO_OUT   ?= demo-out

.PHONY: all deps configure build demo test test-asan fuzz-smoke bench format clean

all: build

deps:
	@./scripts/setup-deps.sh

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

configure: $(BUILD)/build.ninja

build: deps configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	./$(BUILD)/brdfit demo -o $(DEMO_OUT)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer.
# clang (installed with BRDFIT_WITH_CLANG=1, as for fuzz-smoke): instrumented with ASan + UBSan
# it compiles this project in about half of GCC's time (cli/cmd_info.cc: 46 s against 97 s);
# -g1: line tables for the sanitizers' stack traces without full debug info; no benchmarks
# (never run under the sanitizers). docs/reliability.md, "Continuous integration".
test-asan:
	BRDFIT_WITH_CLANG=1 ./scripts/setup-deps.sh
	CC=clang CXX=clang++ cmake -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DBRDFIT_SANITIZE=ON -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
	  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DBRDFIT_BUILD_BENCH=OFF $(CMAKE_ARGS)
	cmake --build $(BUILD_ASAN) -j $(JOBS)
	cd $(BUILD_ASAN) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ctest --output-on-failure -j $(JOBS)

# libFuzzer smoke run (about a minute in all, after replaying every committed fuzz input):
# clang + libclang-rt are installed by setup-deps.sh with BRDFIT_WITH_CLANG=1. docs/reliability.md.
BUILD_FUZZ ?= build-fuzz
fuzz-smoke:
	BRDFIT_WITH_CLANG=1 ./scripts/setup-deps.sh
	BUILD_FUZZ=$(BUILD_FUZZ) JOBS=$(JOBS) ./scripts/fuzz.sh smoke

bench: build
	for b in $(BUILD)/bench/bench_*; do $$b; done

format:
	find models core io fit factor report preview pipeline cli tests bench -name '*.h' -o -name '*.cc' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(BUILD_ASAN)
