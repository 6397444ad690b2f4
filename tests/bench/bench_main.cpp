// Google Benchmark entry point for build/bin/depthkey-bench (`make bench`).
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
