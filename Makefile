# Talus top-level commands. `make test` is what CI runs (.ci/run).
#
#   make test      install deps, build, run every test (plain + ASan/UBSan)
#   make build     configure and build the release tree in build/
#   make format    reformat the sources with clang-format
#   make report    run the default scenarios through Talus, Bullet and ODE
#                  and write the comparison report to reports/latest/
#   make report-full   the same page with every analysis added: the time
#                  step x iterations sweep, the stress envelope and the
#                  large scenes' scaling series (long: about an hour on 2
#                  cores), in reports/full/
#
# JOBS sets build and test parallelism (default: all cores).

JOBS ?= $(shell nproc)
BUILD_DIR ?= build
ASAN_DIR ?= build-asan
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
# about an hour.
SCENES_ENGINES ?= talus,bullet-f32,bullet-f32-tuned,ode-quickstep-tuned,ode-step-tuned

.PHONY: deps configure build test test-release test-asan format format-check clean report report-full

deps:
	@scripts/install-deps.sh

configure: deps
	@$(CMAKE) -S . -B $(BUILD_DIR) -G $(GENERATOR) -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@$(CMAKE) --build $(BUILD_DIR) -j $(JOBS)

test-release: build
	cd $(BUILD_DIR) && ctest $(CTEST_FLAGS)

# The sanitizer tree is a debug-assert build (-O1, asserts on), so programmer
# errors trip assertions as well as ASan/UBSan. Benchmarks are left out.
test-asan: deps
	@$(CMAKE) -S . -B $(ASAN_DIR) -G $(GENERATOR) -DCMAKE_BUILD_TYPE=Debug \
	  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DTALUS_SANITIZE=ON -DTALUS_BUILD_BENCH=OFF >/dev/null
	@$(CMAKE) --build $(ASAN_DIR) -j $(JOBS)
	cd $(ASAN_DIR) && ctest $(CTEST_FLAGS) -LE slow

test: format-check test-release test-asan

# Every engine (talus and its variants; bullet, bullet-f32, ode-step,
# ode-quickstep, each in its defaults and -tuned configuration) on the
# default suite; the report is written even when a run failed, and the
# target then fails. REPLAY names the runs the page can replay in 3D (the
# write-up's figures 2-4: free fall of 15 bodies, a small pyramid, a hull
# coming to rest, a tossed box). The SAT validation (talus-sat-check,
# SAT_PAIRS pairs, seed 1) is run into the same folder and added as a
# section; if it fails, the report is written without it and the target fails.
report: build
	@status=0; $(TESTBED) run scenarios --jobs $(JOBS) --replay $(REPLAY) --out $(REPORT_DIR) >/dev/null || status=$$?; \
	  sat=; if $(SAT_CHECK) --pairs $(SAT_PAIRS) --seed 1 --json $(REPORT_DIR)/sat_check.json \
	    --markdown $(REPORT_DIR)/sat_check.md; then sat="--sat-check $(REPORT_DIR)/sat_check.json"; \
	  else status=1; fi; \
	  $(TESTBED) report $(REPORT_DIR)/results.json $$sat && exit $$status

format:
	clang-format -i $(SOURCES)

format-check: deps
	@clang-format --dry-run --Werror $(SOURCES)

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR)

# One page with every analysis: the default run and SAT validation as in
# `report`, plus the sweep (run time against error), the stress envelope and
# the scaling series of the large scenes, each run into its own subfolder
# and added with the report's --sweep, --stress and --scenes. Each step
# prints its progress on stderr; the page is written even when a step
# failed (without that step's section), and the target then fails.
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
	  if $(SCENES) --series --engines $(SCENES_ENGINES) --format jsonl >$(FULL_DIR)/scenes.jsonl; then \
	    extras="$$extras --scenes $(FULL_DIR)/scenes.jsonl"; else status=1; fi; \
	  $(TESTBED) report $(FULL_DIR)/results.json $$extras && exit $$status
