// The calibration file's schema, its consistency rules, and its writer.
#include "config/calibration_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <sstream>

#include "config/atomic_file.hpp"
#include "config/file_format.hpp"
#include "config/text_file.hpp"
#include "config/toml_binder.hpp"

namespace depthkey {

namespace {

// Limits that no real calibration reaches: a value outside them means a
// corrupt file or a failed fit, not a camera.
constexpr double kMaxCoefficient = 1e5;     // pixels; the offset term is ~W/2
constexpr double kMinDepthM = 0.3;          // the depth camera's range
constexpr double kMaxDepthM = 7.5;
constexpr size_t kMaxDepths = 64;
constexpr double kMaxResidualPx = 1e4;
constexpr int kMaxPoints = 10'000'000;

constexpr std::string_view kModels[] = { "paper", "parallax" };
constexpr std::string_view kSets[] = { "fit", "heldout" };
constexpr std::string_view kSelections[] = { "heldout", "option" };

// How many coefficients per axis a model has: what basis() fills.
int coefficientCount(MappingKind kind)
{
	MappingModel model;
	model.kind = kind;
	std::array<double, kMappingCoefficients> b;
	return model.basis(0.0, 0.0, 1.0, false, b);
}

std::string checkIdentity(std::string_view name)
{
	if (name.empty())
		return "is empty";
	bool control = std::any_of(name.begin(), name.end(),
				   [](char c) { return static_cast<unsigned char>(c) < 0x20; });
	return control ? "contains a control character" : "";
}

// Every key of the file is required: a partial file must never pass for a
// whole one. A missing key is reported at its section's header.
void requireKeys(TomlSection &sec, std::initializer_list<std::string_view> keys)
{
	for (std::string_view key : keys)
		sec.require(sec.has(key), key, "missing");
}

MappingKind kindOf(const std::string &name)
{
	MappingKind kind = MappingKind::Parallax;
	parseMappingKind(name, kind);
	return kind;
}

void bindStats(TomlSection &sec, ResidualStats &stats, std::string_view prefix)
{
	std::string points = std::string(prefix) + "points";
	std::string rms = std::string(prefix) + "rms_px";
	std::string max = std::string(prefix) + "max_px";
	requireKeys(sec, { points, rms, max });
	sec.integer(points, stats.points, 0, kMaxPoints);
	sec.number(rms, stats.rmsPx, 0.0, kMaxResidualPx);
	sec.number(max, stats.maxPx, 0.0, kMaxResidualPx);
}

void bindMapping(TomlSection &sec, Calibration &c)
{
	requireKeys(sec, { "model", "date", "colour_camera", "tof_camera", "colour_width",
			   "colour_height", "tof_width", "tof_height", "depths_m", "selected_by",
			   "held_out", "x", "y" });
	std::string model;
	bool modelOk = sec.string("model", model, kModels);
	c.mapping.kind = kindOf(model);
	sec.string("date", c.date, checkUtcDate);
	sec.string("colour_camera", c.colourCamera, checkIdentity);
	sec.string("tof_camera", c.tofCamera, checkIdentity);
	sec.integer("colour_width", c.mapping.colourWidth, 16, 1920);
	sec.integer("colour_height", c.mapping.colourHeight, 16, 1080);
	sec.integer("tof_width", c.mapping.tofWidth, 16, 1024);
	sec.integer("tof_height", c.mapping.tofHeight, 16, 1024);
	sec.string("selected_by", c.selectedBy, kSelections);
	sec.string("held_out", c.heldOutViews, checkIdentity);

	if (sec.numbers("depths_m", c.depthsM, 1, kMaxDepths, kMinDepthM, kMaxDepthM) &&
	    !c.depthsM.empty())
		sec.require(std::is_sorted(c.depthsM.begin(), c.depthsM.end()) &&
				    std::adjacent_find(c.depthsM.begin(), c.depthsM.end()) ==
					    c.depthsM.end(),
			    "depths_m", "must be in ascending order without repeats");

	// The coefficient count follows from the model; with an unknown model
	// only the values are checked (that error is reported already).
	size_t n = static_cast<size_t>(coefficientCount(c.mapping.kind));
	bool known = modelOk && sec.has("model");
	for (int axis = 0; axis < 2; axis++) {
		std::vector<double> values;
		const char *key = axis ? "y" : "x";
		if (sec.numbers(key, values, known ? n : 1, known ? n : kMappingCoefficients,
				-kMaxCoefficient, kMaxCoefficient) &&
		    known && values.size() == n)
			std::copy(values.begin(), values.end(), (axis ? c.mapping.y : c.mapping.x).begin());
	}
}

void bindSummaries(TomlSection &sec, Calibration &c)
{
	for (std::string_view name : kModels) {
		if (!sec.has(name))
			continue;
		CalibrationSummary summary;
		summary.model = kindOf(std::string(name));
		sec.table(name, [&](TomlSection &model) {
			bindStats(model, summary.fit, "");
			bindStats(model, summary.heldOut, "heldout_");
		});
		c.summaries.push_back(summary);
	}
}

void bindResidual(TomlSection &sec, CalibrationResidual &r)
{
	requireKeys(sec, { "model", "set", "depth_m" });
	std::string model, set;
	sec.string("model", model, kModels);
	sec.string("set", set, kSets);
	sec.number("depth_m", r.depthM, kMinDepthM, kMaxDepthM);
	bindStats(sec, r.stats, "");
	r.model = kindOf(model);
	r.heldOut = set == "heldout";
}

void bindEnd(TomlSection &sec)
{
	bool complete = false;
	requireKeys(sec, { "complete" });
	if (sec.boolean("complete", complete) && sec.has("complete"))
		sec.require(complete, "complete", "must be true");
}

std::string formatDepth(double depthM)
{
	char buf[32];
	std::snprintf(buf, sizeof(buf), "%g", depthM);
	return buf;
}

// What is missing from the file as a whole: a file cut short loses its end,
// so these are reported at its last line rather than at the top.
struct Missing {
	std::vector<std::pair<std::string, std::string>> items;     // key, message
	void require(bool ok, std::string key, std::string message)
	{
		if (!ok)
			items.emplace_back(std::move(key), std::move(message));
	}
};

// Rules across sections, checked once each section bound cleanly.
void checkConsistency(const Calibration &c, Missing &missing)
{
	auto hasSummary = [&](MappingKind kind) {
		return std::any_of(c.summaries.begin(), c.summaries.end(),
				   [&](const CalibrationSummary &s) { return s.model == kind; });
	};
	missing.require(hasSummary(c.mapping.kind), "summary",
			std::string("has no [summary.") + mappingKindName(c.mapping.kind) +
				"] for the selected model");

	for (const CalibrationSummary &s : c.summaries) {
		for (double depth : c.depthsM) {
			bool found = std::any_of(c.residuals.begin(), c.residuals.end(),
						 [&](const CalibrationResidual &r) {
							 return r.model == s.model && !r.heldOut &&
								r.depthM == depth;
						 });
			missing.require(found, "residuals",
					std::string("has no fit row for model ") +
						mappingKindName(s.model) + " at depth_m " +
						formatDepth(depth));
		}
	}
}

std::string formatNumbers(const double *values, int count)
{
	std::string out = "[";
	for (int i = 0; i < count; i++)
		out += (i ? ", " : "") + formatExact(values[i]);
	return out + "]";
}

std::string formatString(const std::string &value)
{
	// Control characters would make toml++ write a multi-line string; the
	// reader refuses them anyway.
	std::string clean = value;
	std::replace_if(clean.begin(), clean.end(),
			[](char ch) { return static_cast<unsigned char>(ch) < 0x20; }, ' ');
	std::ostringstream out;
	out << toml::value<std::string>(clean);
	return out.str();
}

std::string formatStats(const ResidualStats &stats, const char *prefix)
{
	char buf[160];
	std::snprintf(buf, sizeof(buf), "%spoints = %d\n%srms_px = %.4f\n%smax_px = %.4f\n",
		      prefix, stats.points, prefix, stats.rmsPx, prefix, stats.maxPx);
	return buf;
}

} // namespace

CalibrationResult parseCalibration(std::string_view text, const std::string &sourceName)
{
	CalibrationResult result;
	Calibration &c = result.calibration;
	Missing missing;
	TomlBindResult bound = bindToml(text, sourceName, [&](TomlSection &root) {
		int format = 0;
		missing.require(root.has("format"), "format", "missing");
		if (root.integer("format", format, 0, 1'000'000) && root.has("format"))
			root.require(format == kCalibrationFormat, "format",
				     "format " + std::to_string(format) +
					     " is not supported: this depthkey reads format " +
					     std::to_string(kCalibrationFormat));
		// Without [calibration] every one of its keys would be reported too.
		missing.require(root.has("calibration"), "calibration", "missing section [calibration]");
		bool ok = root.has("calibration") &&
			  root.table("calibration", [&](TomlSection &sec) { bindMapping(sec, c); });
		ok = root.table("summary", [&](TomlSection &sec) { bindSummaries(sec, c); }) && ok;
		ok = root.tables("residuals", [&](TomlSection &sec, size_t) {
			c.residuals.emplace_back();
			bindResidual(sec, c.residuals.back());
		}) && ok;
		if (root.has("board"))
			ok = root.table("board", [&](TomlSection &sec) {
				c.board.emplace();
				bindBoardCalibrationSection(sec, *c.board);
				const MappingModel &m = c.mapping;
				sec.require(m.colourWidth == 0 || (c.board->colourWidth == m.colourWidth &&
								   c.board->colourHeight == m.colourHeight),
					    "colour_width",
					    "the board was fitted in another colour size than the mapping (" +
						    std::to_string(c.board->colourWidth) + "x" +
						    std::to_string(c.board->colourHeight) + " vs " +
						    std::to_string(m.colourWidth) + "x" + std::to_string(m.colourHeight) + ")");
			}) && ok;
		// [end] is written last: a file cut anywhere before it lacks it.
		missing.require(root.has("end"), "end", "missing section [end]: the file is cut short");
		if (root.has("end"))
			ok = root.table("end", bindEnd) && ok;
		if (ok)
			checkConsistency(c, missing);
	});
	result.errors = std::move(bound.errors);
	int end = lastLineOf(text);
	for (auto &[key, message] : missing.items)
		result.errors.push_back({ sourceName, end, 1, key, message });
	capErrors(result.errors, 0, sourceName);
	return result;
}

CalibrationResult loadCalibration(const std::string &path)
{
	std::string text;
	CalibrationResult result;
	ConfigError error;
	if (!readToolFile(path, "calibration", text, error)) {
		result.errors.push_back(error);
		return result;
	}
	return parseCalibration(text, path);
}

std::string formatCalibration(const Calibration &c)
{
	const MappingModel &m = c.mapping;
	int n = coefficientCount(m.kind);
	std::string out =
		"# depthkey calibration: the depth -> colour mapping, written by depthkey-calibrate.\n"
		"# Do not edit; calibrate again instead. Every key is described in\n"
		"# docs/calibration-file.md. Residuals are distances in colour pixels.\n"
		"format = " + std::to_string(kCalibrationFormat) + "\n\n"
		"[calibration]\n"
		"model = \"" + mappingKindName(m.kind) + "\"\n"
		"date = " + formatString(c.date) + "\n"
		"colour_camera = " + formatString(c.colourCamera) + "\n"
		"tof_camera = " + formatString(c.tofCamera) + "\n"
		"colour_width = " + std::to_string(m.colourWidth) + "\n"
		"colour_height = " + std::to_string(m.colourHeight) + "\n"
		"tof_width = " + std::to_string(m.tofWidth) + "\n"
		"tof_height = " + std::to_string(m.tofHeight) + "\n"
		"depths_m = " + formatNumbers(c.depthsM.data(), static_cast<int>(c.depthsM.size())) + "\n"
		"selected_by = " + formatString(c.selectedBy) + "\n"
		"held_out = " + formatString(c.heldOutViews) + "\n"
		"x = " + formatNumbers(m.x.data(), n) + "\n"
		"y = " + formatNumbers(m.y.data(), n) + "\n";

	for (const CalibrationSummary &s : c.summaries) {
		out += std::string("\n[summary.") + mappingKindName(s.model) + "]\n";
		out += formatStats(s.fit, "") + formatStats(s.heldOut, "heldout_");
	}
	for (const CalibrationResidual &r : c.residuals) {
		out += std::string("\n[[residuals]]\nmodel = \"") + mappingKindName(r.model) + "\"\n";
		out += std::string("set = \"") + (r.heldOut ? "heldout" : "fit") + "\"\n";
		out += "depth_m = " + formatExact(r.depthM) + "\n" + formatStats(r.stats, "");
	}
	if (c.board)
		out += "\n# The board: the homography colour px -> board px, fitted in the same\n"
		       "# session (docs/calibration-file.md). board.homography_file overrides it.\n" +
		       formatBoardCalibrationSection(*c.board);
	return out + "\n# Written last, so that a file cut short is refused.\n[end]\ncomplete = true\n";
}

int writeCalibration(const std::string &path, const Calibration &calibration, std::string &error)
{
	std::string text = formatCalibration(calibration);
	CalibrationResult check = parseCalibration(text, path);
	if (!check.ok()) {
		error = "refusing to write a calibration the daemon would not load: " +
			check.errors.front().toString();
		return -EINVAL;
	}
	return writeFileAtomically(path, text, error);
}

} // namespace depthkey
