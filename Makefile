# depthkey: build, run, test, benchmark and install.
#
#   make            build everything into build/bin/
#   make run        install missing packages, build, calibrate for and start depthkeyd on
#                   simulated devices (config build/run.toml)
#   make test       install missing packages, build, run every test, then the HIL suite
#   make check      the unit tests alone (tests/*.cpp), in seconds, in-process
#   make process-check  the tests that start processes (tests/process/*.cpp): the
#                   daemon, the tools, curl, chromium, a C compiler
#   make hil        the hardware-in-the-loop suite alone (QEMU VM, tests/hil/)
#   make hil-campaign [CAMPAIGN_FAULTS=N] [CAMPAIGN_SEED=S]
#                   the HIL VM through N faults (default 1000) in a seeded random order
#   make bench      run the Google Benchmark suite (medians)
#   make offset-trials  20 live starts of depthkeyd on the simulator under a CPU quota:
#                   the depth offset applied against the simulator's truth (issue 29)
#   make soak       a million frames through depthkeyd on a replayed sequence, as
#                   fast as it goes, VmRSS, fds and keying time sampled (tests/soak/)
#   make bench-process  whole-process figures: libraries mapped, depthkeyd's RSS and
#                   time to READY=1 on the simulator, depthkey-siox's start
#   make frame-instructions  instructions of one pipeline frame (callgrind)
#   make deps       install missing Debian 12 packages (idempotent, quiet when all there)
#   make deb        build the Debian package into build/deb/ (see debian/)
#   make boot-test  boot the package with systemd in the QEMU VM (in `make test` too)
#   make install DESTDIR=... PREFIX=...
#   make clean
#   make ARCH=arm64 ...  cross-build for arm64 (Debian's aarch64-linux-gnu
#                   toolchain, arm64 libraries through multiarch) into build/arm64/;
#                   `make ARCH=arm64 deps` installs them, `make ARCH=arm64 check` runs
#                   the unit tests under qemu-user (docs/arm64.md)
#   make SAN=1 ... build with AddressSanitizer + UndefinedBehaviorSanitizer (in build/san/)
#   make SAN=thread ... build with ThreadSanitizer (in build/tsan/)
#   make fuzz [FUZZ_SECONDS=N | FUZZ_RUNS=N] [FUZZ_TARGETS="config image ..."] [FUZZ_ASAN=0]
#                   build the libFuzzer harnesses (tests/fuzz/) with clang, ASan and
#                   UBSan into build/fuzz/ and run each N seconds (default 30)
#
# Sources are found by wildcard, so adding a file needs no edit here:
#   algo/ hal/ config/ wiring/ daemon/ -> build/libdepthkey.a (daemon/main.cpp is depthkeyd's main)
#   (settings/ holds headers only: the config's plain structs)
#   tools/NAME.cpp              -> build/bin/depthkey-NAME
#   tests/*.cpp                 -> build/bin/depthkey-unit-tests (GoogleTest)
#   tests/process/*.cpp         -> build/bin/depthkey-process-tests (GoogleTest, + tests/main.cpp)
#   tests/bench/*.cpp           -> build/bin/depthkey-bench (Google Benchmark)

PREFIX ?= /usr/local
DESTDIR ?=
SAN ?= 0

# ARCH: empty = this machine's; arm64 = cross-built with Debian's toolchain
# and run under qemu-user (docs/arm64.md). Everything that differs per
# architecture is in this block; the rules below only use its variables.
ARCH ?=
PKG_CONFIG ?= pkg-config
# How a built binary is started (empty: directly), and the process tests.
RUN :=
PROCESS_RUN :=
ARCH_LIBS :=
ifeq ($(ARCH),arm64)
CROSS := aarch64-linux-gnu-
CXX := $(CROSS)g++
# pkgconf:arm64's wrapper reads the arm64 .pc files (and the
# architecture-independent ones: eigen3).
PKG_CONFIG := $(CROSS)pkg-config
BUILDROOT ?= build/arm64
DEPS_LISTS := packaging/build-deps.txt packaging/build-deps-arm64.txt
# OpenCV's calib3d and features2d -dev packages cannot be installed for
# arm64 beside amd64's (they pull imgcodecs-dev -> libgdcm-dev, which is not
# Multi-Arch: same), so only their runtime libraries are; the headers are the
# amd64 ones (/usr/include/opencv4 is the same for every architecture) and
# the linker finds the libraries through links made by the rules at the end.
ARCH_LINKS = $(BUILDROOT)/opencv-links
LDFLAGS += -L$(ARCH_LINKS)
# imgcodecs cannot be installed for arm64 at all beside amd64's (libgdal32,
# which it links, is not Multi-Arch: same): the arm64 build has no image
# file codecs until they move to libpng/TurboJPEG (issue 15, the lean half).
# Meanwhile -lopencv_imgcodecs finds arch/arm64/imgcodecs_unavailable.cpp,
# which answers every call with a failure, and the tests that need a codec
# skip (DEPTHKEY_NO_IMGCODECS).
CXXFLAGS_ARCH := -DDEPTHKEY_NO_IMGCODECS
ARCH_LIBS = $(ARCH_LINKS)/libopencv_imgcodecs.a $(ARCH_LINKS)/libopencv_calib3d.so $(ARCH_LINKS)/libopencv_features2d.so
# qemu-user, with the multiarch arm64 loader (/lib/ld-linux-aarch64.so.1 of
# libc6:arm64, which the :arm64 -dev packages pull in) and so the libc of
# the same build. No -L /usr/aarch64-linux-gnu: that loader is the cross
# toolchain's (libc6-arm64-cross, glibc 2.36-8), but the libraries it then
# finds through the host's ld.so.cache are the multiarch ones, libc6:arm64
# (2.36-9+deb12uN); a loader and libc of different builds disagree on their
# private _rtld_global, and every pthread_create spun for ever walking the
# "stack cache" at the wrong offset (the unit suite hung at its first
# thread: BackgroundJob, then HostileSequence's FIFO writer).
RUN := qemu-aarch64-static
# The process tests run the daemon and tools with execve(): only where the
# kernel hands arm64 binaries to qemu (binfmt_misc), else reported skipped.
PROCESS_RUN := tests/arm64/process-check.sh $(RUN) --
else ifneq ($(ARCH),)
$(error ARCH=$(ARCH): only arm64 (or empty, this machine) is known)
endif
# The package build (debian/rules) compiles apart, in build/deb/, with
# Debian's hardening flags, and never touches the developer's build/.
BUILDROOT ?= build

ifeq ($(SAN),1)
BUILD := $(BUILDROOT)/san
SANFLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
# fontconfig's process-long cache, reached through cairo (tests/lsan-suppressions.txt).
export LSAN_OPTIONS ?= suppressions=$(CURDIR)/tests/lsan-suppressions.txt
else ifeq ($(SAN),thread)
# ThreadSanitizer: every part with a thread (the recorder's worker, the
# reload worker). halt_on_error: a race fails the test run.
BUILD := $(BUILDROOT)/tsan
# TSan does not model the shm ring's seqlock fences (gcc's -Wtsan says
# so); the copies they guard race by design and are checked afterwards,
# which tests/tsan-suppressions.txt states for exactly those functions.
SANFLAGS := -fsanitize=thread -fno-omit-frame-pointer -Wno-tsan
export TSAN_OPTIONS ?= halt_on_error=1 second_deadlock_stack=1 suppressions=$(CURDIR)/tests/tsan-suppressions.txt
else
BUILD := $(BUILDROOT)
SANFLAGS :=
endif
BIN := $(BUILD)/bin
OBJ := $(BUILD)/obj

PKGS := libsystemd tomlplusplus libusb-1.0 libgpiodcxx libturbojpeg libpng eigen3 libmicrohttpd libxcrypt
# The tools and tests may use OpenCV's core and imgproc; depthkeyd links no
# OpenCV at all (its pictures, NO SIGNAL and the stage previews, are drawn by
# the project: about 4.5 MB of resident libraries less, issue 15), so its
# link line has none and a cv:: call in its objects fails to link. Only
# depthkey-calibrate fits homographies and finds circle grids (calib3d,
# features2d), and only
# depthkey-siox (its still images in the formats image editors use, issue 30)
# and the tests use imgcodecs, the tests as an independent PNG/JPEG codec to check
# hal/png_codec against (Debian's imgcodecs maps GDAL, poppler, HDF5 and
# ~130 more libraries: issue 15). Those go on the link lines that need them,
# below; --as-needed records in each binary only the libraries it calls.
OPENCV_LIBS := -lopencv_imgproc -lopencv_core
OPENCV_CALIB_LIBS := -lopencv_calib3d -lopencv_features2d
OPENCV_CODEC_LIBS := -lopencv_imgcodecs

# Recursive (=) so pkg-config runs only when a recipe needs it, i.e. after `deps`.
# No -march=native: the binaries must run on any x86-64 CPU (and under QEMU TCG).
# -g1: line tables and function names (backtraces, sanitizer reports, perf
# and callgrind by line), without the types and locals of -g, which cost
# 20-40 % of each compile (measured on daemon.cpp, board_output_test.cpp,
# coarse_to_fine_cut.cpp: 18.0 s -> 12.9 s of CPU). CI builds the project
# five times (native, package, SAN, fuzz, arm64), so this is minutes of its
# 70. For a debugger's view of locals: make CXXFLAGS="-O2 -g". The package
# keeps Debian's -g (dpkg-buildflags), for its -dbgsym.
CXXFLAGS ?= -O2 -g1
CXXFLAGS += -std=c++20 -Wall -Wextra -Werror -MMD -MP -I. -isystem /usr/include/opencv4 $(SANFLAGS) $(CXXFLAGS_ARCH)
PKG_CFLAGS = $(shell $(PKG_CONFIG) --cflags $(PKGS))
DAEMON_LDLIBS = $(shell $(PKG_CONFIG) --libs $(PKGS)) -lpthread -lrt
LDLIBS = $(DAEMON_LDLIBS) $(OPENCV_LIBS)
LDFLAGS += -Wl,--as-needed $(SANFLAGS)

LIB_SRCS := $(filter-out daemon/main.cpp,$(wildcard algo/*.cpp hal/*.cpp hal/*/*.cpp config/*.cpp wiring/*.cpp daemon/*.cpp))
TOOL_SRCS := $(wildcard tools/*.cpp)
SR2EMU_SRCS := $(wildcard tools/sr2_emulator/*.cpp)
UNIT_TEST_SRCS := $(wildcard tests/*.cpp)
PROCESS_TEST_SRCS := $(wildcard tests/process/*.cpp) tests/main.cpp
BENCH_SRCS := $(wildcard tests/bench/*.cpp)

LIB := $(BUILD)/libdepthkey.a
DAEMON := $(BIN)/depthkeyd
TOOLS := $(patsubst tools/%.cpp,$(BIN)/depthkey-%,$(TOOL_SRCS))
SR2EMU := $(BIN)/depthkey-sr2-emulator
UNIT_TESTS := $(BIN)/depthkey-unit-tests
PROCESS_TESTS := $(BIN)/depthkey-process-tests
BENCH := $(BIN)/depthkey-bench

obj = $(patsubst %.cpp,$(OBJ)/%.o,$(1))
# Builds started by run/test/bench use every core unless told otherwise.
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

# Keep tool objects (intermediates of the pattern rule) so nothing rebuilds twice.
.SECONDARY:

.PHONY: all run test check process-check accuracy-sizes recording-minute offset-trials live-share live-table hil hil-campaign bench bench-process soak frame-instructions deps deb deb-deps package-test boot-test install clean fuzz fuzz-build
.DEFAULT_GOAL := all

# The SR-2 emulator is built (for the HIL tests) but not installed.
all: $(DAEMON) $(TOOLS) $(SR2EMU)

deps:
	@packaging/install-deps.sh $(DEPS_LISTS)

# run/test/bench first install packages, then build in a fresh make so that
# pkg-config sees the newly installed libraries.
run: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(SIM_CALIBRATION) $(SIM_BOARD_CALIBRATION)
	@sh daemon/run-sim.sh $(BIN) $(BUILD)

# The calibration `make run` uses: fitted to the simulated cameras (about
# 1.5 s), again whenever depthkey-calibrate changes. The tool's report goes
# to sim-calibration.log beside it; make shows its summary line (model,
# residuals in colour pixels), or all of it when the fit fails.
SIM_CALIBRATION := $(BUILD)/sim-calibration.toml
$(SIM_CALIBRATION): $(BIN)/depthkey-calibrate
	@$< --sim --output $@ > $(@:.toml=.log) 2>&1 || { cat $(@:.toml=.log); exit 1; }
	@echo "$@: `tail -n 1 $(@:.toml=.log)`"

# The board calibration `make run` uses: the simulated board showing the
# pattern, fitted with depthkey-calibrate --board --sim (well under a second).
SIM_BOARD_CALIBRATION := $(BUILD)/sim-board.toml
$(SIM_BOARD_CALIBRATION): $(BIN)/depthkey-calibrate
	@$< --board --sim --output $@ > $(@:.toml=.log) 2>&1 || { cat $(@:.toml=.log); exit 1; }
	@echo "$@: `tail -n 1 $(@:.toml=.log)`"

# The unit tests, the process tests, then the hardware-in-the-loop suite: the
# real daemon in a QEMU VM against emulated devices (tests/hil/run.sh; it
# fails, never skips, when the VM cannot start).
test: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(UNIT_TESTS) $(PROCESS_TESTS) $(HIL_TOOLS)
	@$(MAKE) --no-print-directory check
	@$(MAKE) --no-print-directory process-check
ifeq ($(SAN),0)
	@$(MAKE) --no-print-directory package-test
endif
	@tests/hil/run.sh $(BIN)

hil: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(HIL_TOOLS)
	@tests/hil/run.sh $(BIN)

# The fault campaign (not part of `make test`): the HIL VM through
# CAMPAIGN_FAULTS faults drawn in an order fixed by CAMPAIGN_SEED (docs/hil.md).
CAMPAIGN_FAULTS ?= 1000
CAMPAIGN_SEED ?= 14
hil-campaign: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(HIL_TOOLS)
	@HIL_CAMPAIGN_FAULTS=$(CAMPAIGN_FAULTS) HIL_CAMPAIGN_SEED=$(CAMPAIGN_SEED) tests/hil/run.sh $(BIN)

# The unit tests need no other binary; the process tests run the daemon and
# the tools, so they build everything first. Both build on every core, as
# `make test` does: CI calls `make SAN=1 check` and `make SAN=1
# process-check` directly, and their sanitizer builds ran one compile at a
# time (24 of CI's minutes on 8 December, most of it that build).
# CHECK_ARGS: more GoogleTest flags (e.g. --gtest_filter=...).
check:
	@$(MAKE) --no-print-directory -j$(JOBS) $(UNIT_TESTS)
	@$(RUN) $(UNIT_TESTS) --gtest_brief=1 $(CHECK_ARGS)

process-check:
	@$(MAKE) --no-print-directory -j$(JOBS) all $(PROCESS_TESTS)
	@$(PROCESS_RUN) $(PROCESS_TESTS) --gtest_brief=1

# Not in `make test`: issue 28's accuracy rows at 1280x720 and 1920x1080
# (tests/process/accuracy_sizes_test.cpp), several minutes.
accuracy-sizes: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(PROCESS_TESTS)
	@DEPTHKEY_ACCURACY_SIZES=1 $(PROCESS_RUN) $(PROCESS_TESTS) --gtest_filter='AccuracySizes.*'

# Not in `make test`: issue 29 point 5's minute-long recording through the
# printed command on a slowed daemon (make test records 15 s).
recording-minute: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(PROCESS_TESTS)
	@DEPTHKEY_RECORDING_SECONDS=60 $(PROCESS_RUN) $(PROCESS_TESTS) \
	    --gtest_filter='ShmCatRateTest.PrintedRecordingKeepsWallTimeOnASlowBox'

# Issue 29: the daemon on 35 % of one core (a cgroup CPU quota) for 60 s,
# its live score against depthkey-eval's; and the note's table (seeds 1-3
# at 100/50/35 %, 640x480 25 fps and 1280x720 30 fps; LIVE_SECONDS a run).
live-share: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(PROCESS_TESTS)
	@DEPTHKEY_LIVE_SHARE=1 $(PROCESS_RUN) $(PROCESS_TESTS) --gtest_filter='LiveScoreDaemon.UnderACpuShareLiveIsOffline'

LIVE_SECONDS ?= 60
live-table: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all
	@sh tests/process/live_vs_offline.sh --table $(BIN) $(LIVE_SECONDS)

bench: deps
	@$(MAKE) --no-print-directory -j$(JOBS) $(BENCH)
	@$(RUN) $(BENCH) --benchmark_repetitions=9 --benchmark_report_aggregates_only=true \
	    --benchmark_display_aggregates_only=true $(BENCH_ARGS)

# Not in `make test`: issue 29 §3's live starts (tests/offset/offset-trials.sh),
# OFFSET_TRIALS starts of OFFSET_SECONDS each (default 20 x 30 s, ~11 minutes),
# the applied depth offset against the simulator's truth, under a CPU quota.
OFFSET_TRIALS ?= 20
OFFSET_SECONDS ?= 30
offset-trials: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(SIM_CALIBRATION) $(SIM_BOARD_CALIBRATION)
	@sh tests/offset/offset-trials.sh $(BIN) $(BUILD) $(OFFSET_TRIALS) $(OFFSET_SECONDS)

# Not in `make test`: it takes half an hour to an hour (SOAK_FRAMES=N for fewer).
soak: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all
	@tests/soak/run.sh $(BIN) $(BUILD)
# Whole-process figures (issue 15): ldd lines per binary, depthkeyd's time to
# READY=1 and its VmRSS (anonymous / file-backed / shared memory) on the
# simulated cameras, depthkey-siox's process start; medians, no verdict.
#   make bench-process [BENCH_PROCESS_ARGS="--seconds 10 --runs 3 --siox IMAGE TRIMAP --breakdown --blocks"]
# Then (issue 28) the keying worker's share of one core live, apart from the
# loop and the simulator's rendering, the keying time and the frames shed, at
# 640x480 25 fps and 1280x720 30 fps (tests/bench/keying_share.py):
#   [KEYING_SHARE_ARGS="--seconds 10 --runs 3"]
bench-process: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(SIM_CALIBRATION) $(SIM_BOARD_CALIBRATION)
	@python3 tests/bench/process_bench.py $(BIN) $(BUILD) $(BENCH_PROCESS_ARGS)
	@python3 tests/bench/keying_share.py $(BIN) $(BUILD) $(KEYING_SHARE_ARGS)

# The instructions of one whole pipeline frame (640x480), callgrind on the
# native build: the stand-in for `make bench` where its times mean nothing
# (ARCH=arm64 under qemu-user, docs/arm64.md). Needs valgrind (build-deps.txt).
frame-instructions: $(BENCH)
	@test -z "$(ARCH)" || { echo "make frame-instructions: counts on the native build (no ARCH=)" >&2; exit 1; }
	@tests/bench/frame_instructions.sh $(BENCH)
	@tests/bench/frame_instructions.sh $(BENCH) 640 480 BM_PipelineFrameLecture
	@tests/bench/frame_instructions.sh $(BENCH) 1920 1080 BM_PipelineFrameLecture

$(OBJ)/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(CXXFLAGS) $(PKG_CFLAGS) -c $< -o $@

# The tests' own code at -O1: what they test (algo/, hal/, daemon/) keeps
# -O2, and the test files are two thirds of a build's compile time, which CI
# pays three times (native, SAN, arm64). Measured under SAN=1 (CPU seconds,
# -O2 -> -O1): board_output_test 25.1 -> 16.5, live_score_test 14.0 -> 6.5.
# The benchmarks time their own loops too: they keep -O2.
TEST_OPT ?= -O1
$(OBJ)/tests/%.o: CXXFLAGS += $(TEST_OPT)
$(OBJ)/tests/bench/%.o: TEST_OPT :=

$(LIB): $(call obj,$(LIB_SRCS))
	@mkdir -p $(dir $@)
	@rm -f $@
	ar rcs $@ $^

$(DAEMON): $(call obj,daemon/main.cpp) $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(DAEMON_LDLIBS) -o $@

$(BIN)/depthkey-%: $(OBJ)/tools/%.o $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

# The emulated SR-2 (a USB gadget for the HIL tests) is several files.
$(SR2EMU): $(call obj,$(SR2EMU_SRCS)) $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

# depthkey-siox reads what image editors read (PNG, JPEG, BMP, TIFF, PNM,
# WebP) through imgcodecs: the one installed binary that links it (issue 30).
SIOX_SRCS := $(wildcard tools/siox/*.cpp)
$(BIN)/depthkey-siox: $(OBJ)/tools/siox.o $(call obj,$(SIOX_SRCS)) $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(OPENCV_CODEC_LIBS) $(LDLIBS) -o $@

# depthkey-calibrate --board, --live and --print-pattern live in their own
# folders. --print-pattern draws the depth pattern as PDF or SVG with cairo,
# which only this tool links (issue 30).
CALIBRATE_BOARD_SRCS := $(wildcard tools/calibrate_board/*.cpp) $(wildcard tools/calibrate_live/*.cpp) \
	$(wildcard tools/calibrate_print/*.cpp)
$(call obj,$(wildcard tools/calibrate_print/*.cpp)): PKG_CFLAGS += $(shell $(PKG_CONFIG) --cflags cairo)
$(BIN)/depthkey-calibrate: $(OBJ)/tools/calibrate.o $(call obj,$(CALIBRATE_BOARD_SRCS)) $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(OPENCV_CALIB_LIBS) $(shell $(PKG_CONFIG) --libs cairo) $(LDLIBS) -o $@

# Helpers of the HIL suite (tests/hil/NAME.cpp -> depthkey-hil-NAME, with _
# as -): a bare libusb SR-2 client, a shared-memory flag watcher.
HIL_TOOLS := $(BIN)/depthkey-hil-sr2-probe $(BIN)/depthkey-hil-shm-watch
$(BIN)/depthkey-hil-sr2-probe: $(OBJ)/tests/hil/sr2_probe.o
$(BIN)/depthkey-hil-shm-watch: $(OBJ)/tests/hil/shm_watch.o
$(HIL_TOOLS):
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

# The two GoogleTest binaries share tests/main.cpp and one link rule.
$(UNIT_TESTS): $(call obj,$(UNIT_TEST_SRCS)) $(LIB)
$(PROCESS_TESTS): $(call obj,$(PROCESS_TEST_SRCS)) $(LIB)
$(UNIT_TESTS) $(PROCESS_TESTS):
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(OPENCV_CALIB_LIBS) $(OPENCV_CODEC_LIBS) $(LDLIBS) -lgmock -lgtest -o $@

$(BENCH): $(call obj,$(BENCH_SRCS)) $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(OPENCV_CALIB_LIBS) $(OPENCV_CODEC_LIBS) $(LDLIBS) -lbenchmark -o $@

# Where the system files go; the defaults are Debian 12's (pkg-config's
# systemd.pc and udev.pc say the same). The unit names $(PREFIX)/sbin/depthkeyd.
UNITDIR ?= /lib/systemd/system
UDEVRULESDIR ?= /lib/udev/rules.d
SYSUSERSDIR ?= /usr/lib/sysusers.d
TMPFILESDIR ?= /usr/lib/tmpfiles.d
MANDIR ?= $(PREFIX)/share/man
# A tool's page is installed with the tool: man/depthkey-NAME.1 for tools/NAME.cpp.
TOOL_MANS := $(patsubst tools/%.cpp,man/depthkey-%.1,$(TOOL_SRCS))
# depthkey.toml(5) is generated from the commented config/depthkey.toml.
CONFIG_MAN := $(BUILD)/man/depthkey.toml.5
VERSION = $(shell sed -n 's/^\#define DEPTHKEY_VERSION "\(.*\)"/\1/p' daemon/version.hpp)

$(CONFIG_MAN): config/depthkey.toml man/depthkey.toml.5.awk daemon/version.hpp
	@mkdir -p $(dir $@)
	awk -v version=$(VERSION) -f man/depthkey.toml.5.awk config/depthkey.toml > $@

install: all $(CONFIG_MAN)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/sbin $(DESTDIR)$(PREFIX)/include/depthkey
	install -m 0755 $(DAEMON) $(DESTDIR)$(PREFIX)/sbin/
	install -m 0755 $(TOOLS) $(DESTDIR)$(PREFIX)/bin/
	install -m 0644 hal/depthkey_shm.h $(DESTDIR)$(PREFIX)/include/depthkey/
	# The box's config: the cameras, not the simulator (packaging/box-config.sed).
	install -d $(DESTDIR)/etc/depthkey
	sed -f packaging/box-config.sed config/depthkey.toml > $(DESTDIR)/etc/depthkey/depthkey.toml
	chmod 0644 $(DESTDIR)/etc/depthkey/depthkey.toml
	install -d $(DESTDIR)$(UNITDIR)
	sed 's|/usr/sbin/depthkeyd|$(PREFIX)/sbin/depthkeyd|' packaging/depthkeyd.service \
	    > $(DESTDIR)$(UNITDIR)/depthkeyd.service
	install -D -m 0644 packaging/60-depthkey.rules $(DESTDIR)$(UDEVRULESDIR)/60-depthkey.rules
	install -D -m 0644 packaging/depthkey.sysusers $(DESTDIR)$(SYSUSERSDIR)/depthkey.conf
	install -D -m 0644 packaging/depthkey.metainfo.xml $(DESTDIR)$(PREFIX)/share/metainfo/depthkey.metainfo.xml
	install -D -m 0644 packaging/depthkey.tmpfiles $(DESTDIR)$(TMPFILESDIR)/depthkey.conf
	install -D -m 0644 packaging/depthkey-v4l2loopback.conf \
	    $(DESTDIR)$(PREFIX)/share/doc/depthkey/examples/depthkey-v4l2loopback.conf
	# The documentation the man pages and the config point to (issue 30), in
	# the tree's layout so that README's links hold; its pictures stay in
	# the source (docs/accuracy/ is 6 MB of figures).
	install -d $(DESTDIR)$(PREFIX)/share/doc/depthkey/docs
	install -m 0644 README.md $(DESTDIR)$(PREFIX)/share/doc/depthkey/
	install -m 0644 docs/*.md $(DESTDIR)$(PREFIX)/share/doc/depthkey/docs/
	install -d $(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(MANDIR)/man5 $(DESTDIR)$(MANDIR)/man8
	install -m 0644 $(CONFIG_MAN) $(DESTDIR)$(MANDIR)/man5/
	for page in man/depthkeyd.8 $(TOOL_MANS); do \
	    sed 's/@VERSION@/$(VERSION)/' $$page > $(DESTDIR)$(MANDIR)/man$${page##*.}/$${page#man/}; \
	done

# The Debian package (debhelper; debian/ must sit at the top of the source
# tree, where dpkg-buildpackage looks). Output: build/deb/*.deb.
deb: deb-deps
	@packaging/build-deb.sh $(ARCH)

deb-deps:
	@packaging/install-deps.sh packaging/deb-deps.txt $(DEPS_LISTS)

# The package's tests (in `make test`, not repeated by SAN=1): offline checks
# of the unit and lintian on the host, then the boot test in the QEMU VM.
DEB_FILE = build/deb/depthkey_$(VERSION)_$(or $(ARCH),$(shell dpkg --print-architecture)).deb

package-test: deb
	@tests/package/offline_checks.sh $(DEB_FILE)
	@tests/boot/boot_test.sh $(DEB_FILE)

boot-test: deb
	@tests/boot/boot_test.sh $(DEB_FILE)

clean:
	rm -rf build

# Fuzzing (tests/fuzz/README.md): clang from Debian (clang, libclang-rt-dev
# for libFuzzer), the harnesses and the few library sources they reach,
# built apart in build/fuzz/ with coverage for libFuzzer, ASan and UBSan.
FUZZ_SECONDS ?= 30
FUZZ_RUNS ?=
FUZZ_CXX ?= clang++
# FUZZ_ASAN=0: UBSan alone, built apart in build/fuzz-ubsan/. For the
# preview server's long run: its harness starts a server thread an input, and
# ASan's per-thread set-up made that 6.6 times dearer (2.58 against 0.39 ms
# an input); the corpus such a run finds is then replayed under ASan
# (tests/fuzz/README.md, "Long runs").
FUZZ_ASAN ?= 1
FUZZ_DIR := $(BUILDROOT)/fuzz$(if $(filter 0,$(FUZZ_ASAN)),-ubsan)
FUZZ_ALL := $(patsubst tests/fuzz/%_fuzz.cpp,%,$(wildcard tests/fuzz/*_fuzz.cpp))
FUZZ_TARGETS ?= $(FUZZ_ALL)
# The library sources the harnesses reach, linked as objects. Folders whose
# files call one another (config/, hal/preview/) are taken whole, so that a
# file added there cannot be missing at link time (stop 26's CI failure).
FUZZ_LIB_SRCS := $(wildcard config/*.cpp) algo/frame_pairer.cpp algo/mapping_model.cpp algo/homography.cpp algo/radial_lens.cpp hal/sr2/sr2_frame_parser.cpp \
	hal/recording/sequence_reader.cpp hal/recording/sequence_format.cpp hal/image_file.cpp hal/image_file_reader.cpp hal/png_codec.cpp \
	hal/v4l2/yuv_to_rgb.cpp hal/v4l2/mjpeg_decoder.cpp hal/v4l2/depth16_to_frame.cpp \
	$(wildcard hal/preview/*.cpp)
# toml++ 3.3.0 reaches __builtin_unreachable() in its own inline code, a
# UBSan "unreachable" report that is the library's (tomlplusplus#190, fixed
# upstream by PR #305, not in Debian 12): exactly that check is switched
# off for exactly its headers (tests/fuzz/ubsan-ignorelist.txt).
FUZZ_SAN := -fsanitize=$(if $(filter 0,$(FUZZ_ASAN)),,address,)undefined -fno-sanitize-recover=undefined \
	-fno-omit-frame-pointer -fsanitize-ignorelist=tests/fuzz/ubsan-ignorelist.txt
FUZZ_CXXFLAGS := -O1 -g1 -std=c++20 -I. -isystem /usr/include/opencv4 $(FUZZ_SAN) -MMD -MP
FUZZ_OBJS := $(patsubst %.cpp,$(FUZZ_DIR)/obj/%.o,$(FUZZ_LIB_SRCS))
FUZZ_BINS := $(patsubst %,$(FUZZ_DIR)/bin/%_fuzz,$(FUZZ_TARGETS))

fuzz: deps
	@$(MAKE) --no-print-directory -j$(JOBS) fuzz-build
	@FUZZ_RUNS=$(FUZZ_RUNS) tests/fuzz/run.sh $(FUZZ_DIR) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

fuzz-build: $(FUZZ_BINS)

$(FUZZ_DIR)/obj/%.o: %.cpp tests/fuzz/ubsan-ignorelist.txt
	@mkdir -p $(dir $@)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -fsanitize=fuzzer-no-link $(FUZZ_COV) $(PKG_CFLAGS) -c $< -o $@

# The SR-2 parser's loops compare each of 19,840 pixels a frame; traced, those
# comparisons were most of the harness's time (320 executions a second) and
# tell the fuzzer nothing (no magic values there). Edges stay instrumented.
$(FUZZ_DIR)/obj/hal/sr2/sr2_frame_parser.o: FUZZ_COV := -fno-sanitize-coverage=trace-cmp

$(FUZZ_DIR)/bin/%_fuzz: $(FUZZ_DIR)/obj/tests/fuzz/%_fuzz.o $(FUZZ_OBJS)
	@mkdir -p $(dir $@)
	$(FUZZ_CXX) $(FUZZ_SAN) -fsanitize=fuzzer $^ $(LDLIBS) -o $@

# ARCH=arm64: the OpenCV libraries the linker finds in $(ARCH_LINKS) (see
# the ARCH block), made before anything links.
$(LIB): | $(ARCH_LIBS)
$(ARCH_LINKS)/libopencv_%.so:
	@mkdir -p $(dir $@)
	ln -sf /usr/lib/aarch64-linux-gnu/libopencv_$*.so.406 $@
$(ARCH_LINKS)/libopencv_imgcodecs.a: $(OBJ)/arch/arm64/imgcodecs_unavailable.o
	@mkdir -p $(dir $@)
	@rm -f $@
	$(CROSS)ar rcs $@ $^

-include $(shell find $(OBJ) -name '*.d' 2>/dev/null)
ifneq ($(filter fuzz fuzz-build,$(MAKECMDGOALS)),)
-include $(shell find $(FUZZ_DIR)/obj -name '*.d' 2>/dev/null)
endif
