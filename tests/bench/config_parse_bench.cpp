// How long a reload's parse can hold the event loop: the config reader caps a
// file at kMaxConfigFileBytes (1 MiB), so these are the worst cases a reload
// (SIGHUP) can meet, each exactly 1 MiB. Compare with the frame period (40 ms
// at 25 fps, 33 ms at 30 fps).
#include "config/calibration_file.hpp"
#include "config/config_loader.hpp"
#include "config/text_file.hpp"

#include <benchmark/benchmark.h>

#include <string>

using namespace depthkey;

namespace {

// Lines from `line(i)` until the text is exactly 1 MiB (a comment pads it).
template<typename Line>
std::string oneMebibyte(std::string text, Line line)
{
	for (int i = 0;; i++) {
		std::string next = line(i);
		if (text.size() + next.size() + 2 > kMaxConfigFileBytes)
			break;
		text += next;
	}
	text += '#';
	text.resize(kMaxConfigFileBytes - 1, '#');
	return text + '\n';
}

void parse(benchmark::State &state, const std::string &text, bool calibration)
{
	size_t errors = 0;
	for (auto _ : state) {
		if (calibration)
			errors = countErrors(parseCalibration(text, "bench.toml").errors);
		else
			errors = countErrors(parseConfig(text, "bench.toml").errors);
		benchmark::DoNotOptimize(errors);
	}
	state.counters["errors"] = static_cast<double>(errors);
	state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

// ~80,000 unknown keys: every one an error, with a nearest-key search each.
void BM_ReloadParse1MiB_UnknownKeys(benchmark::State &state)
{
	static const std::string text = oneMebibyte("[segmentation]\n", [](int i) {
		return "key" + std::to_string(i) + " = 1\n";
	});
	parse(state, text, false);
}
BENCHMARK(BM_ReloadParse1MiB_UnknownKeys)->Unit(benchmark::kMillisecond);

// One huge array of integers where a string belongs.
void BM_ReloadParse1MiB_HugeArray(benchmark::State &state)
{
	static const std::string text = oneMebibyte("[daemon]\nlog_level = [", [](int i) {
		return std::to_string(i % 1000) + ",";
	}).replace(kMaxConfigFileBytes - 3, 3, "]\n\n");
	parse(state, text, false);
}
BENCHMARK(BM_ReloadParse1MiB_HugeArray)->Unit(benchmark::kMillisecond);

// Many [[depth.sr2_register]] tables, each bound by the schema.
void BM_ReloadParse1MiB_ManyTables(benchmark::State &state)
{
	static const std::string text = oneMebibyte("", [](int i) {
		return "[[depth.sr2_register]]\naddress = " + std::to_string(i % 256) + "\nvalue = 1\n";
	});
	parse(state, text, false);
}
BENCHMARK(BM_ReloadParse1MiB_ManyTables)->Unit(benchmark::kMillisecond);

// A calibration file padded with residual rows: what a reload re-reads when
// mapping.calibration_file is set.
void BM_ReloadParse1MiB_Calibration(benchmark::State &state)
{
	static const std::string text = oneMebibyte("format = 1\n", [](int i) {
		return "[[residuals]]\nmodel = \"parallax\"\nset = \"fit\"\ndepth_m = " +
		       std::to_string(1 + i % 3) + "\npoints = 30\nrms_px = 0.25\nmax_px = 0.9\n";
	});
	parse(state, text, true);
}
BENCHMARK(BM_ReloadParse1MiB_Calibration)->Unit(benchmark::kMillisecond);

} // namespace
