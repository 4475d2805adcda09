# gibench — thin wrapper over CMake and ctest. Two commands set everything up on a fresh Debian 12:
#   make reproduce   install missing packages, build, run the quick profile, draw the plots, write the report
#   make test        install missing packages, build (normal + ASan/UBSan), run every test
BUILD      ?= build
ASAN_BUILD ?= build-asan
# The report's Python is one package, harness/reporting, run as modules.
PY         = PYTHONPATH=harness python3 -m
PROFILE    ?= quick
RESULTS    ?= results
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=

# Debian 12 packages gibench builds and runs with (ARCHITECTURE.md, "Toolchain facts"); parallel,
# slurm-wlm and munge are for spreading matrices over machines (harness/cluster/, tests/cluster/);
# chromium opens the report in its test (tests/report/); ffmpeg makes the sequences' animations
# (harness/reporting/temporal_tables.py).
PACKAGES = build-essential cmake pkg-config python3 python3-glad \
  libegl-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev \
  libembree-dev libopenexr-dev libopenimageio-dev openimageio-tools libassimp-dev \
  libinih-dev zlib1g-dev gnuplot-nox python3-numpy python3-skimage git clang \
  parallel slurm-wlm munge \
  libsqlite3-dev \
  chromium ffmpeg
# The self-contained bundle (make bundle) reads images with libstb instead of OpenImageIO.
BUNDLE_PACKAGES = libstb-dev
# The reference renderer against Blender Cycles (make bench-cycles): Debian's blender, only there.
BENCH_PACKAGES = blender
BUNDLE ?= build-bundle

# The papers' figures and tables (make reproduce, ~20 min on 2 cores) and our own parameter studies
# beyond them (make reproduce-studies, ~10 min): the report reads the committed CSVs of both.
MATRICES = $(wildcard harness/matrices/*.matrix)
STUDIES  = $(wildcard harness/matrices/studies/*.matrix)

.PHONY: all deps build build-asan install test tsan tsan-build reproduce reproduce-studies cone-study cone-study-sponza cone-study-rooms cone-study-sponza-spot cone-controls-sponza-spot vct-floor-control energy-controls plots report baselines fuzz bench bench-cycles bench-references bench-timing bundle clean help

all: build

help:
	@echo "make install PREFIX=DIR | make reproduce | make reproduce-studies | make cone-study | make energy-controls | make test | make deps | make build | make plots | make report | make baselines | make fuzz | make bench | make bench-cycles | make bench-references | make bench-timing | make bundle | make clean"

# Installs only what is missing, with sudo when not root, without recommended packages.
deps:
	@missing=""; for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing$$missing"; \
	  if [ "$$(id -u)" = 0 ]; then SUDO=; else SUDO=sudo; fi; \
	  $$SUDO apt-get update -q && \
	  DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -q --no-install-recommends $$missing; \
	else echo "make deps: all Debian packages present"; fi

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_ARGS)
	cmake --build $(BUILD) -j$(JOBS)

# gibench, the technique contract's headers and a CMake / pkg-config package for techniques built
# as plugins in their own repositories (docs/adding-a-technique.md, "As a plugin").
PREFIX ?= /usr/local
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# Unit tests run again under AddressSanitizer and UndefinedBehaviorSanitizer.
build-asan: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DGIB_SANITIZE=ON $(CMAKE_ARGS)
	cmake --build $(ASAN_BUILD) -j$(JOBS)

# Every test in two builds: the sanitizer build (ASan+UBSan at -O1, LeakSanitizer with Mesa's and
# the driver's own leaks suppressed by tests/lsan_mesa.supp, never ours) and the release build; then
# ThreadSanitizer over the reference's threads and the runner. Tests labelled release_only run in
# the release build alone (shader output, which the sanitizers do not instrument, and scripts over
# files no build enters), sanitizer_only in the sanitizer build alone (the harness's own logic and
# hostile inputs, whose checks read the same in both); tests/CMakeLists.txt and each test say why.
# The three builds are made at once, then the three runs go at once (tests/run_suites.sh, lines
# prefixed [asan], [release], [tsan]): on 2 cores one's idle moments are another's work.
test: deps
	@$(MAKE) --no-print-directory -j3 build build-asan tsan-build
	sh tests/run_suites.sh $(ASAN_BUILD) $(BUILD) $(TSAN_BUILD) $(JOBS)

TSAN_BUILD ?= build-tsan
tsan-build: deps
	cmake -S . -B $(TSAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGIB_TSAN=ON -DGIB_WERROR=OFF $(CMAKE_ARGS)
	cmake --build $(TSAN_BUILD) -j$(JOBS) --target gibench

tsan: tsan-build
	sh tests/tsan/run_tsan.sh $(TSAN_BUILD) $(TSAN_BUILD)/tsan-work

# The matrices (the three papers' results), then plots, the papers' tables beside ours and the report.
# PROFILE=quick (the default) is a smoke reproduction at reduced settings (~20 min on 2 cores); the
# committed verdicts come from PROFILE=paper, the papers' parameters at images at most 4x smaller
# per side (hours on llvmpipe: shard it, docs/scale-out.md). Afresh: `gibench run` skips the runs
# its CSV already holds, so the rows of $(PROFILE) from the last run (the committed ones, in a
# clone) move to $(RESULTS)/previous/ first, and the other profiles' rows stay; RESUME=1 continues
# an interrupted run instead.
reproduce: build
	@if [ "$(PROFILE)" = quick ]; then echo "make reproduce: the quick profile, a smoke" \
	  "reproduction at reduced settings; the committed verdicts are the paper profile's" \
	  "(make reproduce PROFILE=paper)"; fi
	@if [ -z "$(RESUME)" ]; then $(PY) reporting.set_aside $(RESULTS) $(PROFILE) $(MATRICES); fi
	$(BUILD)/gibench run $(MATRICES) --profile $(PROFILE) --out $(RESULTS); \
	  rc=$$?; \
	  $(MAKE) --no-print-directory report || rc=1; exit $$rc

reproduce-studies:
	$(MAKE) --no-print-directory reproduce MATRICES="$(STUDIES)"

# The voxel techniques' diffuse gather split into its six cones, each against the reference's cone
# (gibench reference --cone), and the best any six-cone gather scores (harness/reporting/cone_study.py,
# ~4 min): results/cone_study.csv.
cone-study: build
	GIBENCH_SCHEMA=build/schema.json $(PY) reporting.cone_study --gibench build/gibench \
	  --out results/cone_study.csv --cache results/cache

# The same on the LRSM paper's sun-lit Sponza at its 512^3 (160x90, 256-spp cone references; needs the
# shared scenes, ~10 min): results/cone_study_sponza.csv, the energy audit's control for the voxel
# techniques' indirect light there.
# The same on the thesis' rooms, where the voxel techniques' indirect light is 0.7-0.84 of the
# reference's (the energy audit): water_room and ring at 128x128, 256^3 (~2 min):
# results/cone_study_rooms.csv.
cone-study-rooms: build
	GIBENCH_SCHEMA=build/schema.json $(PY) reporting.cone_study --gibench build/gibench \
	  --out results/cone_study_rooms.csv --cache results/cache --size 128x128 --spp 256 \
	  --full-spp 1024 --scenes water_room,ring --voxel-res 256

# The same on the LDM paper's Sponza under its spot light (thesis_indirect's and lrsm_sweeps' view),
# vct at 256^3, 200x200 (~4 min): results/cone_study_sponza_spot.csv, the energy audit's control
# for vct's indirect light there.
cone-study-sponza-spot: build
	GIBENCH_SCHEMA=build/schema.json $(PY) reporting.cone_study --gibench build/gibench \
	  --out results/cone_study_sponza_spot.csv --cache results/cache --size 200x200 --spp 256 \
	  --full-spp 1024 --scenes sponza --voxel-res 256 --techniques vct

# vct's cones on that view with one of its departures or its fill turned off each (front_faces=0,
# sample_level=0, clearance=0, fill=0; ~20 min): results/cone_controls_sponza_spot.csv, the energy
# audit's evidence that none of them is why its cones 4-5 read 0.65 of their caps.
cone-controls-sponza-spot: build
	rm -f results/cone_controls_sponza_spot.csv
	for p in front_faces=0 sample_level=0 clearance=0 fill=0; do \
	  GIBENCH_SCHEMA=build/schema.json $(PY) reporting.cone_study --gibench build/gibench \
	    --out results/cone_controls_sponza_spot.csv --cache results/cache --size 200x200 \
	    --spp 256 --full-spp 1024 --scenes sponza --voxel-res 256 --techniques vct \
	    --param $$p --append || exit 1; done

# What a vct cone reads of a lit floor that fills its cap (synthetic volume, 256^3; 60- and
# 10-degree cones at several heights and tilts; seconds): results/vct_floor_control.csv, the energy
# audit's control for vct's cones over Sponza's floor. The same program is the ctest
# vct_test_vct_oblique_floor, which asserts what must hold whatever the sampling.
vct-floor-control: build
	$(BUILD)/tests/vct/test_vct_oblique_floor --csv results/vct_floor_control.csv

# The energy audit's measured controls (harness/energy_controls/run.py): each cell of
# harness/energy_controls/cells.csv rendered as committed and with one suspected cause removed (a
# patch built into build-control from a copy of the sources, or another parameter), against the
# same cached references; needs the shared scenes (its time: PERFORMANCE.md): results/energy_controls.csv.
energy-controls: build
	GIBENCH_SCHEMA=build/schema.json python3 harness/energy_controls/run.py --gibench build/gibench \
	  --out results/energy_controls.csv --cache results/cache

cone-study-sponza: build
	for t in lrsm vct; do extra=""; [ $$t = lrsm ] && extra="--param rsm_res=1024"; \
	  GIBENCH_SCHEMA=build/schema.json $(PY) reporting.cone_study --gibench build/gibench \
	    --out $(BUILD)/cone_study_sponza_$$t.csv --cache results/cache --size 160x90 --spp 256 \
	    --full-spp 1024 --scenes sponza_glossy --voxel-res 512 --techniques $$t $$extra || exit 1; done
	(cat $(BUILD)/cone_study_sponza_lrsm.csv; tail -n +2 $(BUILD)/cone_study_sponza_vct.csv | \
	  grep -v '^sponza_glossy,ideal') > results/cone_study_sponza.csv

# The project's own benchmarks, apart from the papers' results (their CSVs are committed and the
# report reads them): the reference's ray throughput against Embree alone (~10 min on 2 cores with
# all scenes) and the timing method's (bench-timing, ~10 min). Run them on an otherwise idle machine.
bench: build
	$(BUILD)/gibench bench reference --scene cornell,sibenik,sponza --repeat 9 \
	  --out $(RESULTS)/bench_reference.csv
	$(BUILD)/gibench bench scoring --repeat 9 --out $(RESULTS)/bench_scoring.csv
	$(MAKE) --no-print-directory bench-cycles
	$(MAKE) --no-print-directory bench-references
	$(MAKE) --no-print-directory bench-timing

# The quick profile's references rendered one request at a time and each scene's together at one
# instant (gibench bench references; reference/PERFORMANCE.md, "One world, every component"):
# seconds and noise each way, whether every image came out the same bits; ~3 min on 2 cores.
bench-references: build
	$(BUILD)/gibench bench references harness/matrices/*.matrix --profile quick --repeat 3 \
	  --out $(RESULTS)/bench_references.csv

# The reference's `full` against Blender Cycles (CPU, no denoising) on one closed room, 128x128 at
# 256 spp, 8 seeds each: time, noise and efficiency (reference/PERFORMANCE.md, "Against Blender
# Cycles"); rows appended to $(RESULTS)/bench_cycles.csv.
bench-cycles: build
	@$(MAKE) --no-print-directory deps PACKAGES="$(BENCH_PACKAGES)"
	python3 harness/bench_cycles/bench_cycles.py --gibench $(BUILD)/gibench --threads $(JOBS) \
	  --out $(RESULTS)/bench_cycles.csv

# The scripts read the results schema the build exports ($(BUILD)/schema.json, harness/reporting/schema.py).
plots: build
	GIBENCH_SCHEMA=$(BUILD)/schema.json $(PY) reporting.plot $(RESULTS) --out $(RESULTS)/plots
	GIBENCH_SCHEMA=$(BUILD)/schema.json $(PY) reporting.paper_tables $(RESULTS)
	GIBENCH_SCHEMA=$(BUILD)/schema.json $(PY) reporting.claims $(RESULTS)

# The reproduction report from the CSVs: $(RESULTS)/REPORT.md and $(RESULTS)/report/index.html
# (opens offline from the file system); for the committed results also the README's picture of its
# first screen, docs/report.png.
report: plots
	GIBENCH_SCHEMA=$(BUILD)/schema.json $(PY) reporting.report $(RESULTS)
	@if [ "$(RESULTS)" = results ]; then \
	  $(PY) reporting.report_screenshot results/report/index.html docs/report.png; fi

# libFuzzer over every parser of outside input (tests/fuzz/README.md): FUZZ_SECONDS and FUZZ_RUNS
# per target (the first reached stops it; -1: no count), a summary in $(FUZZ_BUILD)/fuzz.csv;
# FUZZ_TARGETS picks targets.
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 120
FUZZ_RUNS    ?= -1
FUZZ_TARGETS ?= fuzz_scene fuzz_matrix fuzz_values fuzz_exr fuzz_mesh fuzz_merge fuzz_history fuzz_resume
fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGIB_FUZZ=ON \
	  -DGIB_WERROR=OFF -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ $(CMAKE_ARGS)
	cmake --build $(FUZZ_BUILD) -j$(JOBS) --target $(FUZZ_TARGETS)
	tests/fuzz/run_fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_RUNS) $(FUZZ_BUILD)/fuzz.csv $(FUZZ_TARGETS)

# The timing method's own benchmark (PERFORMANCE.md): the same matrices twice and once with a longer
# warm-up; writes $(RESULTS)/bench_timing.csv and $(RESULTS)/timing_resolution.csv, the resolution the
# report and the claims call ties by. About 10 minutes on 2 cores; run it on an otherwise idle machine.
bench-timing: build
	$(PY) reporting.bench_timing $(BUILD)/gibench $(RESULTS) --work $(BUILD)/bench_timing

# Accepts the current quality numbers as the new baselines: a deliberate step, never automatic.
baselines: build
	python3 tests/quality/check_quality.py --gibench $(BUILD)/gibench --work $(BUILD)/quality \
	  --update tests/quality/baselines.csv

# gibench for a machine without our Debian libraries (a bare one with an NVIDIA driver, reached by
# harness/device/run_on_nvidia.sh): $(BUNDLE)/gibench-bundle.tar.xz, Release, without OpenImageIO
# and -march=native, with the libraries the machine lacks (harness/device/make_bundle.sh).
bundle:
	@$(MAKE) --no-print-directory deps PACKAGES="$(PACKAGES) $(BUNDLE_PACKAGES)"
	sh harness/device/make_bundle.sh $(BUNDLE)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD) $(TSAN_BUILD) $(BUNDLE)
