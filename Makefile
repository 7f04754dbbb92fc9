# Talus top-level commands. `make test` is what CI runs (.ci/run).
#
#   make test      install deps, build, run every test (plain + ASan/UBSan)
#   make test-tsan the engine's threaded tests under ThreadSanitizer in build-tsan/
#   make test-tsan-full  the same plus the runner's jobs (needs the harness: long)
#   make build     configure and build the release tree in build/
#   make format    reformat the sources with clang-format
#   make report    run the default scenarios through Talus, Bullet and ODE
#                  and write the comparison report to reports/latest/
#   make report-full   the same page with every analysis added: the time
#                  step x iterations sweep, the stress envelope and the
#                  large scenes' scaling series and speed against
#                  accuracy (long: about an hour on 2 cores), in
#                  reports/full/
#
#   make fuzz      build the libFuzzer targets (clang, ASan + UBSan) in
#                  build-fuzz/ and run each for FUZZ_SECONDS (default 600)
#   make fuzz-ci   the same, a fixed number of inputs per target from a
#                  fixed seed (the bounded form .ci/run runs after `make test`)
#   make test-avx2 the engine's dynamics and world suites linked against
#                  the AVX2 variant of the engine, in build/ (.ci/run runs it too)
#   make soak      the full soak suite (tests/soak: 1e5 steps of every
#                  scenario and the abuse cases on every backend; minutes)
#
# JOBS sets build and test parallelism (default: all cores).

JOBS ?= $(shell nproc)
BUILD_DIR ?= build
ASAN_DIR ?= build-asan
TSAN_DIR ?= build-tsan
CMAKE ?= cmake
GENERATOR ?= Ninja
CTEST_FLAGS ?= --output-on-failure --no-tests=error -j $(JOBS)
SOURCES = $(shell git ls-files '*.cpp' '*.h' 2>/dev/null)
REPORT_DIR ?= reports/latest
TESTBED = $(BUILD_DIR)/apps/testbed/talus-testbed
REPLAY ?= free_fall_15,box_pyramid_4,hull_rest,box_toss
SAT_CHECK = $(BUILD_DIR)/apps/sat_check/talus-sat-check
SAT_PAIRS ?= 1000
FULL_DIR ?= reports/full
SCENES = $(BUILD_DIR)/apps/scenes/talus-scenes
# The scaling series runs the engines compared by the speed goal (Talus
# variants are compared on the small scenarios), each peer in its fastest
# configuration (docs/bench-scenes.md: Bullet's single-precision build, both
# margins, the faster of which each ratio divides by; ODE's hash space);
# about an hour. MuJoCo 2.2.2 is listed so the section says why it cannot
# run the series sizes (its skip costs no time; docs/testbed-backends.md).
SCENES_ENGINES ?= talus,bullet-f32,bullet-f32-tuned,ode-quickstep-tuned,ode-step-tuned,mujoco,mujoco-tuned
# The Talus engines run the series at each of these thread counts, back to
# back, for the report's thread-scaling and where-the-time-goes tables
# (docs/bench-scenes.md); each count adds Talus's share of the series again.
SCENES_THREADS ?= 1,2
# Speed against accuracy (docs/bench-scenes.md, "Iterations and
# substeps"): pyramid H = 10 and hull_pile L = 10 again at these solver
# iteration counts, one run each, on the engines of the series that have
# the knob; their defaults are the series' own runs. A few minutes.
SCENES_TRADEOFF_ENGINES ?= talus,bullet-f32,bullet-f32-tuned,ode-quickstep-tuned
SCENES_ITERATIONS ?= 2,4,8,20

FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 600
# libFuzzer's -seed: 0 draws one per run; fuzz-ci fixes it so a CI finding
# replays with the same command.
FUZZ_SEED ?= 0
FUZZ_TARGETS ?= hull_builder point_file pair_sat scenario_loader shard_merge

.PHONY: deps configure build test test-release test-asan test-tsan test-tsan-full format format-check clean report report-full \
  fuzz-build fuzz fuzz-ci soak test-avx2

deps:
	@scripts/install-deps.sh

configure: deps
	@$(CMAKE) -S . -B $(BUILD_DIR) -G $(GENERATOR) -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@$(CMAKE) --build $(BUILD_DIR) -j $(JOBS)

test-release: build
	cd $(BUILD_DIR) && ctest $(CTEST_FLAGS) -LE '^(soak|avx2)$$'

# The sanitizer tree is a debug-assert build (-O1, asserts on), so programmer
# errors trip assertions as well as ASan/UBSan, with the validation pass on
# (TALUS_VALIDATE: every step's contact graph, islands, broad phase and
# colours checked; engine/src/world/world_validate.h). Benchmarks are left out.
# -g1 (line tables only) keeps file:line in every sanitizer stack trace and
# compiles about 25% faster than -g (scenario_loader.cpp before its split:
# 29 s against 39 s of CPU), which is most of what keeps `make test` inside CI's budget.
test-asan: deps
	@$(CMAKE) -S . -B $(ASAN_DIR) -G $(GENERATOR) -DCMAKE_BUILD_TYPE=Debug \
	  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" -DTALUS_SANITIZE=ON -DTALUS_VALIDATE=ON -DTALUS_BUILD_BENCH=OFF \
	  -DTALUS_BUILD_AVX2_VARIANT=OFF >/dev/null
	@$(CMAKE) --build $(ASAN_DIR) -j $(JOBS)
	cd $(ASAN_DIR) && ctest $(CTEST_FLAGS) -LE 'slow|^soak$$|^avx2$$'

# The ThreadSanitizer tree: Debug at -O1 (asserts on) with TSan. `test-tsan`
# (part of `make test`) builds only the engine's threaded tests
# (talus_threads_tests: the job pool, worlds stepped at 1, 2, 3 and 8
# threads) and runs the tests labelled `threads`; `test-tsan-full` adds the
# testbed's runner at 1, 2 and 8 jobs (talus_runner_threads_tests), which
# needs the whole harness library and costs minutes CI does not have.
# TSAN_OPTIONS makes any report fail the test (halt_on_error) rather than
# only print.
TSAN_CONFIGURE = $(CMAKE) -S . -B $(TSAN_DIR) -G $(GENERATOR) -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" -DTALUS_SANITIZE_THREAD=ON -DTALUS_BUILD_BENCH=OFF \
  -DTALUS_BUILD_TESTBED=OFF -DTALUS_BUILD_AVX2_VARIANT=OFF >/dev/null
TSAN_RUN = cd $(TSAN_DIR) && TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" ctest $(CTEST_FLAGS)

test-tsan: deps
	@$(TSAN_CONFIGURE)
	@$(CMAKE) --build $(TSAN_DIR) -j $(JOBS) --target talus_threads_tests
	$(TSAN_RUN) -L '^threads$$'

test-tsan-full: deps
	@$(TSAN_CONFIGURE)
	@$(CMAKE) --build $(TSAN_DIR) -j $(JOBS) --target talus_threads_tests talus_runner_threads_tests
	$(TSAN_RUN) -L '^(threads|runner_threads)$$'

test: format-check test-release test-asan test-tsan

# The AVX2 suites: the engine's dynamics and world tests linked again
# against talus_engine_avx2, the library whose wide kernels are compiled
# with -mavx2 (engine/CMakeLists.txt). They share the Release tree: the
# variant differs from the default library in that one object, and the
# suites' objects are the same ones (tests/CMakeLists.txt), so this costs
# one file's compile and two links, not a tree. Built anywhere; run only on
# a CPU with AVX2 (the binary would stop on an illegal instruction), which
# it says when it skips.
test-avx2: configure
	@$(CMAKE) --build $(BUILD_DIR) -j $(JOBS) --target talus_dynamics_avx2_tests talus_world_avx2_tests
	@if grep -qw avx2 /proc/cpuinfo; then \
	  cd $(BUILD_DIR) && ctest $(CTEST_FLAGS) -L '^avx2$$'; \
	else echo "test-avx2: this CPU has no AVX2; built, not run"; fi

# The full soak suite (tests/soak, ctest label soak): every scenario for 1e5
# steps and the abuse cases on every backend, in the Release tree. Minutes;
# not part of `make test`, which runs its shortened form (label slow).
soak: build
	cd $(BUILD_DIR) && ctest $(CTEST_FLAGS) -L '^soak$$'

# Every engine (talus and its variants; bullet, bullet-f32, ode-step,
# ode-quickstep, each in its defaults and -tuned configuration) on the
# default suite. REPLAY names the runs the page can replay in 3D (the
# write-up's figures 2-4: free fall of 15 bodies, a small pyramid, a hull
# coming to rest, a tossed box). The SAT validation (talus-sat-check,
# SAT_PAIRS pairs, seed 1) is run into the same folder and added as a
# section.
# It exits 0 once the report is written: a run that failed or stopped (a
# peer that cannot step an arch, say) is a result the report shows, and a
# SAT check that finds a fault is written as its own section's verdict;
# gating is `talus-testbed check`'s and ctest's job. It fails when there is
# no report: bad input to the run (exit 2) or a report that could not be
# written. A failed run or SAT check is still named on stderr.
report: build
	@status=0; $(TESTBED) run scenarios --jobs $(JOBS) --replay $(REPLAY) --out $(REPORT_DIR) >/dev/null || status=$$?; \
	  if [ $$status -gt 1 ]; then echo "report: talus-testbed run exited $$status (bad input): no report" >&2; exit $$status; fi; \
	  if [ $$status -eq 1 ]; then echo "report: some runs failed or stopped; the report shows which" >&2; fi; \
	  satStatus=0; $(SAT_CHECK) --pairs $(SAT_PAIRS) --seed 1 --json $(REPORT_DIR)/sat_check.json \
	    --markdown $(REPORT_DIR)/sat_check.md || satStatus=$$?; \
	  sat="--sat-check $(REPORT_DIR)/sat_check.json"; \
	  if [ $$satStatus -eq 1 ]; then echo "report: the SAT check found a fault; its section shows it" >&2; \
	  elif [ $$satStatus -ne 0 ]; then sat=; echo "report: the SAT check exited $$satStatus and wrote nothing; no SAT section" >&2; fi; \
	  $(TESTBED) report $(REPORT_DIR)/results.json $$sat

format:
	clang-format -i $(SOURCES)

format-check: deps
	@clang-format --dry-run --Werror $(SOURCES)

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR) $(TSAN_DIR) $(FUZZ_DIR)

# The fuzz tree: clang with libFuzzer, ASan and UBSan over the engine and the
# point reader, asserts on (Debug at -O1). TALUS_FUZZ_DEPS=1 adds clang and
# its runtime to the packages install-deps checks; `make test` needs neither.
fuzz-build:
	@TALUS_FUZZ_DEPS=1 scripts/install-deps.sh
	@$(CMAKE) -S . -B $(FUZZ_DIR) -G $(GENERATOR) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=clang++-14 \
	  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer" \
	  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
	  -DTALUS_BUILD_FUZZ=ON -DTALUS_BUILD_TESTS=OFF -DTALUS_BUILD_BENCH=OFF -DTALUS_BUILD_TESTBED=OFF >/dev/null
	@$(CMAKE) --build $(FUZZ_DIR) -j $(JOBS) --target $(addprefix talus_fuzz_,$(FUZZ_TARGETS))

# Each target starts from its seeds in tests/data/fuzz/<target>/ (read only)
# and grows its own corpus in build-fuzz/corpus/<target>/; a crash is saved
# as build-fuzz/artifacts/<target>-crash-... and stops the run. Turn it into
# a file in tests/data/fuzz/<target>/ (the test suites replay those).
fuzz: fuzz-build
	@for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ_DIR)/corpus/$$t $(FUZZ_DIR)/artifacts; \
	  echo "fuzz: $$t for $(FUZZ_SECONDS) s"; \
	  $(FUZZ_DIR)/fuzz/talus_fuzz_$$t $(FUZZ_DIR)/corpus/$$t tests/data/fuzz/$$t \
	    -max_total_time=$(FUZZ_SECONDS) -seed=$(FUZZ_SEED) -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
	    -artifact_prefix=$(FUZZ_DIR)/artifacts/$$t- || exit 1; \
	done

# The CI form is bounded by input count, not by time: with libFuzzer's seed
# fixed, -runs=N makes the same N inputs from run to run on a machine that
# lets the fuzzer run without address-space randomisation (setarch -R), so
# a slow or fast machine cannot reach a different stretch of the mutation
# sequence. It starts from the seeds alone (a fresh corpus folder each time)
# for the same reason, and the corpus is not re-read while it runs
# (-reload=0). libFuzzer's comparison tracing records pointer values, so
# where setarch -R is refused (as on the CI machine of 2026-11-24) the
# inputs differ from run to run: CI then fuzzes a new stretch each time,
# and a finding there may need a few seeds here to reproduce
# (docs/fuzzing.md). Counts: what each target ran in 30 s at seed 1 on the
# shared 2-core machine; an idle machine gets through them in less.
FUZZ_CI_RUNS ?= hull_builder:20000 point_file:450000 pair_sat:14000 scenario_loader:39000 shard_merge:13500
FUZZ_NO_ASLR := $(shell setarch $$(uname -m) -R true >/dev/null 2>&1 && echo setarch $$(uname -m) -R)

fuzz-ci: fuzz-build
	@for tr in $(FUZZ_CI_RUNS); do \
	  t=$${tr%%:*}; n=$${tr##*:}; \
	  rm -rf $(FUZZ_DIR)/corpus-ci/$$t; mkdir -p $(FUZZ_DIR)/corpus-ci/$$t $(FUZZ_DIR)/artifacts; \
	  echo "fuzz-ci: $$t, $$n inputs from seed 1"; \
	  $(FUZZ_NO_ASLR) $(FUZZ_DIR)/fuzz/talus_fuzz_$$t $(FUZZ_DIR)/corpus-ci/$$t tests/data/fuzz/$$t \
	    -runs=$$n -seed=1 -reload=0 -max_total_time=600 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
	    -artifact_prefix=$(FUZZ_DIR)/artifacts/$$t- || exit 1; \
	done

# One page with every analysis: the default run and SAT validation as in
# `report`, plus the sweep (run time against error), the stress envelope and
# the scaling series of the large scenes, each run into its own subfolder
# and added with the report's --sweep, --stress and --scenes. Each step
# prints its progress on stderr; the page is written even when a step
# failed (without that step's section), and the target then fails. The
# sweep runs with its default noise floor (2 perturbed copies per point),
# three times the runs of a sweep without one (docs/testbed-sweeps.md).
report-full: build
	@mkdir -p $(FULL_DIR); status=0; extras=; \
	  $(TESTBED) run scenarios --jobs $(JOBS) --replay $(REPLAY) --out $(FULL_DIR) >/dev/null || status=$$?; \
	  if $(SAT_CHECK) --pairs $(SAT_PAIRS) --seed 1 --json $(FULL_DIR)/sat_check.json \
	    --markdown $(FULL_DIR)/sat_check.md; then extras="$$extras --sat-check $(FULL_DIR)/sat_check.json"; \
	  else status=1; fi; \
	  if $(TESTBED) sweep scenarios --jobs $(JOBS) -o $(FULL_DIR)/sweep >/dev/null; then \
	    extras="$$extras --sweep $(FULL_DIR)/sweep/results.json"; else status=1; fi; \
	  if $(TESTBED) stress -b talus,talus-split,bullet,ode-step,ode-quickstep -o $(FULL_DIR)/stress >/dev/null; \
	    then extras="$$extras --stress $(FULL_DIR)/stress/stress.json"; else status=1; fi; \
	  if $(SCENES) --series --engines $(SCENES_ENGINES) --threads $(SCENES_THREADS) --format jsonl >$(FULL_DIR)/scenes.jsonl \
	    && $(SCENES) --scene pyramid --param 10 --engines $(SCENES_TRADEOFF_ENGINES) \
	      --iterations $(SCENES_ITERATIONS) --format jsonl >>$(FULL_DIR)/scenes.jsonl \
	    && $(SCENES) --scene hull_pile --param 10 --engines $(SCENES_TRADEOFF_ENGINES) \
	      --iterations $(SCENES_ITERATIONS) --format jsonl >>$(FULL_DIR)/scenes.jsonl; then \
	    extras="$$extras --scenes $(FULL_DIR)/scenes.jsonl"; else status=1; fi; \
	  $(TESTBED) report $(FULL_DIR)/results.json $$extras && exit $$status
