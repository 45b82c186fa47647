# crowdlab: the two set-up commands are `make demo` and `make test` (see README.md).
BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc)
DEMO_OUT   ?= demo-out
CMAKE_GEN  := $(shell command -v ninja >/dev/null 2>&1 && echo "-G Ninja")

.PHONY: all deps test-deps web-deps build demo test test-asan bench format clean

all: build

deps:
	@scripts/install-deps.sh
	@$(MAKE) --no-print-directory web-deps

test-deps:
	@scripts/install-deps.sh --test
	@$(MAKE) --no-print-directory web-deps

# jsPsych 8 and its plugins (for `crowdlab export-web`) and puppeteer-core (for the browser test), pinned
# in study_ui/web/package-lock.json, installed with `npm ci` into the build tree ($(BUILD)/web), never
# into the source tree. Re-run only when the lock file changes. Without npm the web study is skipped.
WEB_DEPS := $(BUILD)/web/node_modules/.crowdlab-lock
web-deps: $(WEB_DEPS)
$(WEB_DEPS): study_ui/web/package.json study_ui/web/package-lock.json
	@if command -v npm >/dev/null; then \
	  mkdir -p $(BUILD)/web && cp study_ui/web/package.json study_ui/web/package-lock.json $(BUILD)/web/ && \
	  echo "crowdlab: npm ci (jsPsych, puppeteer-core) into $(BUILD)/web" && \
	  (cd $(BUILD)/web && npm ci --silent --no-audit --no-fund) && cp study_ui/web/package-lock.json $@; \
	else echo "crowdlab: warning: no npm; export-web and the browser test need jsPsych (make web-deps)"; fi

build: deps
	@cmake -S . -B $(BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

# The demo needs the binary alone: the test executables (about a third of a cold build) are left to
# `make test` (issue 31).
demo: deps
	@cmake -S . -B $(BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS) --target crowdlab
	@$(BUILD)/crowdlab demo --out $(DEMO_OUT)

test: test-deps
	@cmake -S . -B $(BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The whole suite again under AddressSanitizer + UndefinedBehaviorSanitizer (CI runs both).
# -Og for every object, libraries and tests (issue 31, session 22; docs/building.md): on a quiet 2-core machine
# its build took 405 s of wall instead of -O1's 647 s (compile CPU 776 s instead of 1256 s: ASan and UBSan
# together make each object about four times larger than either alone, and -Og runs fewer passes over it),
# and its ctest 324 s instead of 270 s. The sanitizers instrument the same accesses and operations at both
# levels (-Og keeps more values in memory, so ASan sees more of them, not fewer). Leak detection is off
# because Mesa's llvmpipe keeps process-lifetime allocations that LeakSanitizer would report.
# ASAN_SKIP: the slowest tests under the sanitizers (each 2-8 min of a loaded two-core machine) check numbers,
# hashes and job engines, not memory: a Monte Carlo body volume, the bookkeeping of shards, GNU parallel /
# make / Slurm running the shards, the gomez2024 and hoyet2016 reproductions' tolerances, the pinned output
# hash (its stages run under the sanitizers in the pipeline tests), the whole-spec run-and-reuse test, the
# simulated observers' statistics and the manifold model comparison. The Release run performs them; the code
# they drive (volumes, the run pipeline, correction, figures, simulated studies, reports, surface crowds)
# runs under the sanitizers in the other tests. A test that checks numbers on a large input but drives code
# no other test reaches runs here on a smaller input instead (test::kSanitized in tests/support/test_paths.hpp:
# e.g. the MPFB2-body corridor tests of tests/correction on a 3 m corridor instead of 6 m); the Release run
# keeps the full size. ctest starts the slowest first by their sanitizer-build costs (tests/test_costs_sanitized.cmake).
ASAN_SKIP  ?= capsule union is 65-80 litres|shards are disjoint|plan writes Slurm|real single-node Slurm|reproduce gomez2024 --quick|reproduce hoyet2016 --quick|pinned output hash|run makes every condition|simulated observers analysed|experiment manifold-compare
test-asan: test-deps
	@cmake -S . -B $(ASAN_BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-Og -DNDEBUG" \
	  -DCROWDLAB_SANITIZE=ON -DCROWDLAB_TEST_OPTIMIZE=-Og >/dev/null
	@cmake --build $(ASAN_BUILD) -j $(JOBS)
	@cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=0:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) -E '$(ASAN_SKIP)'

bench: build
	@$(BUILD)/crowdlab bench --help

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
