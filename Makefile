# depthkey: build, run, test, benchmark and install.
#
#   make            build everything into build/bin/
#   make run        install missing packages, build, start depthkeyd on simulated devices
#   make test       install missing packages, build, run every test, then the HIL suite
#   make hil        the hardware-in-the-loop suite alone (QEMU VM, tests/hil/)
#   make bench      run the Google Benchmark suite (medians)
#   make deps       install missing Debian 12 packages (idempotent, quiet when all there)
#   make install DESTDIR=... PREFIX=...
#   make clean
#   make SAN=1 ... build with AddressSanitizer + UndefinedBehaviorSanitizer (in build/san/)
#
# Sources are found by wildcard, so adding a file needs no edit here:
#   algo/ hal/ config/ daemon/   -> build/libdepthkey.a (daemon/main.cpp is depthkeyd's main)
#   tools/NAME.cpp              -> build/bin/depthkey-NAME
#   tests/*.cpp                 -> build/bin/depthkey-tests (GoogleTest)
#   tests/bench/*.cpp           -> build/bin/depthkey-bench (Google Benchmark)

PREFIX ?= /usr/local
DESTDIR ?=
SAN ?= 0

ifeq ($(SAN),1)
BUILD := build/san
SANFLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
else
BUILD := build
SANFLAGS :=
endif
BIN := $(BUILD)/bin
OBJ := $(BUILD)/obj

PKGS := libsystemd tomlplusplus libusb-1.0 libgpiodcxx libturbojpeg eigen3
OPENCV_LIBS := -lopencv_calib3d -lopencv_features2d -lopencv_imgcodecs -lopencv_imgproc -lopencv_core

# Recursive (=) so pkg-config runs only when a recipe needs it, i.e. after `deps`.
# No -march=native: the binaries must run on any x86-64 CPU (and under QEMU TCG).
CXXFLAGS ?= -O2 -g
CXXFLAGS += -std=c++20 -Wall -Wextra -Werror -MMD -MP -I. -isystem /usr/include/opencv4 $(SANFLAGS)
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS))
LDLIBS = $(shell pkg-config --libs $(PKGS)) $(OPENCV_LIBS) -lpthread -lrt
LDFLAGS += $(SANFLAGS)

LIB_SRCS := $(filter-out daemon/main.cpp,$(wildcard algo/*.cpp hal/*.cpp hal/*/*.cpp config/*.cpp daemon/*.cpp))
TOOL_SRCS := $(wildcard tools/*.cpp)
SR2EMU_SRCS := $(wildcard tools/sr2_emulator/*.cpp)
TEST_SRCS := $(wildcard tests/*.cpp)
BENCH_SRCS := $(wildcard tests/bench/*.cpp)

LIB := $(BUILD)/libdepthkey.a
DAEMON := $(BIN)/depthkeyd
TOOLS := $(patsubst tools/%.cpp,$(BIN)/depthkey-%,$(TOOL_SRCS))
SR2EMU := $(BIN)/depthkey-sr2-emulator
TESTS := $(BIN)/depthkey-tests
BENCH := $(BIN)/depthkey-bench

obj = $(patsubst %.cpp,$(OBJ)/%.o,$(1))
# Builds started by run/test/bench use every core unless told otherwise.
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

# Keep tool objects (intermediates of the pattern rule) so nothing rebuilds twice.
.SECONDARY:

.PHONY: all run test check hil bench deps install clean
.DEFAULT_GOAL := all

# The SR-2 emulator is built (for the HIL tests) but not installed.
all: $(DAEMON) $(TOOLS) $(SR2EMU)

deps:
	@packaging/install-deps.sh

# run/test/bench first install packages, then build in a fresh make so that
# pkg-config sees the newly installed libraries.
run: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all
	@sh daemon/run-sim.sh $(BIN)

# The unit tests, then the hardware-in-the-loop suite: the real daemon in a
# QEMU VM against emulated devices (tests/hil/run.sh; it fails, never skips,
# when the VM cannot start).
test: deps
	@$(MAKE) --no-print-directory -j$(JOBS) check $(HIL_TOOLS)
	@tests/hil/run.sh $(BIN)

hil: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all $(HIL_TOOLS)
	@tests/hil/run.sh $(BIN)

check: all $(TESTS)
	@$(TESTS) --gtest_brief=1

bench: deps
	@$(MAKE) --no-print-directory -j$(JOBS) $(BENCH)
	@$(BENCH) --benchmark_repetitions=9 --benchmark_report_aggregates_only=true \
	    --benchmark_display_aggregates_only=true $(BENCH_ARGS)

$(OBJ)/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS) $(PKG_CFLAGS) -c $< -o $@

$(LIB): $(call obj,$(LIB_SRCS))
	@mkdir -p $(dir $@)
	@rm -f $@
	ar rcs $@ $^

$(DAEMON): $(call obj,daemon/main.cpp) $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(BIN)/depthkey-%: $(OBJ)/tools/%.o $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

# The emulated SR-2 (a USB gadget for the HIL tests) is several files.
$(SR2EMU): $(call obj,$(SR2EMU_SRCS)) $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

# Helpers of the HIL suite (tests/hil/NAME.cpp -> depthkey-hil-NAME, with _
# as -): a bare libusb SR-2 client, a shared-memory flag watcher.
HIL_TOOLS := $(BIN)/depthkey-hil-sr2-probe $(BIN)/depthkey-hil-shm-watch
$(BIN)/depthkey-hil-sr2-probe: $(OBJ)/tests/hil/sr2_probe.o
$(BIN)/depthkey-hil-shm-watch: $(OBJ)/tests/hil/shm_watch.o
$(HIL_TOOLS):
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(TESTS): $(call obj,$(TEST_SRCS)) $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -lgmock -lgtest -o $@

$(BENCH): $(call obj,$(BENCH_SRCS)) $(LIB)
	@mkdir -p $(dir $@)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -lbenchmark -o $@

install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/include/depthkey
	install -m 0755 $(DAEMON) $(TOOLS) $(DESTDIR)$(PREFIX)/bin/
	install -m 0644 hal/depthkey_shm.h $(DESTDIR)$(PREFIX)/include/depthkey/
	install -D -m 0644 config/depthkey.toml $(DESTDIR)/etc/depthkey/depthkey.toml

clean:
	rm -rf build

-include $(shell find $(OBJ) -name '*.d' 2>/dev/null)
