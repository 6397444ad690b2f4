#include "config/board_calibration_file.hpp"

#include "config/atomic_file.hpp"
#include "config/file_format.hpp"
#include "config/toml_binder.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

namespace depthkey {

namespace {

constexpr double kMaxCoefficient = 1e7;    // a corrupt file, not a camera
constexpr double kMaxResidualPx = 1e4;
// A webcam's radial terms at a focal length of one image width are a few
// hundredths; beyond 1 it is a fisheye or a corrupt file.
constexpr double kMaxLensTerm = 1.0;

} // namespace

void bindBoardCalibrationSection(TomlSection &sec, BoardCalibration &c)
{
	for (std::string_view key : { "date", "colour_width", "colour_height", "board_width", "board_height",
				      "homography", "points", "rms_px", "max_px" })
		sec.require(sec.has(key), key, "missing");
	sec.string("date", c.date, checkUtcDate);
	sec.integer("colour_width", c.colourWidth, 16, 1920);
	sec.integer("colour_height", c.colourHeight, 16, 1080);
	sec.integer("board_width", c.boardWidth, 16, 3840);
	sec.integer("board_height", c.boardHeight, 16, 2160);
	sec.integer("points", c.points, 4, 10000);
	sec.number("rms_px", c.rmsPx, 0.0, kMaxResidualPx);
	sec.number("max_px", c.maxPx, 0.0, kMaxResidualPx);
	bool lensOk = sec.number("lens_k1", c.lensK1, -kMaxLensTerm, kMaxLensTerm);
	lensOk = sec.number("lens_k2", c.lensK2, -kMaxLensTerm, kMaxLensTerm) && lensOk;
	if (lensOk && c.colourWidth > 1 && c.colourHeight > 1) {
		// Every pixel of the colour image must undistort: the lens may
		// not fold back inside the picture. Its centre is the image's, so
		// the corners are the farthest pixels, all at the same radius.
		double ix, iy;
		sec.require(c.lens().undistort(0, 0, ix, iy), "lens_k1",
			    "the lens terms fold the image's corners back (not a camera's lens)");
	}
	std::vector<double> h;
	if (!sec.numbers("homography", h, 9, 9, -kMaxCoefficient, kMaxCoefficient) || h.size() != 9)
		return;
	std::copy(h.begin(), h.end(), c.colourToBoard.h.begin());
	// A singular H, or one that sends the colour image's middle to
	// infinity, cannot be a camera's view of a board.
	Homography inverse;
	double u, v;
	bool usable = c.colourToBoard.inverse(inverse) &&
		      c.colourToBoard.apply((c.colourWidth - 1) / 2.0, (c.colourHeight - 1) / 2.0, u, v) &&
		      std::isfinite(u) && std::isfinite(v);
	sec.require(usable, "homography", "is singular or maps the colour image's middle to infinity");
}

BoardCalibrationResult parseBoardCalibration(std::string_view text, const std::string &sourceName)
{
	BoardCalibrationResult result;
	std::vector<std::pair<std::string, std::string>> missing;
	TomlBindResult bound = bindToml(text, sourceName, [&](TomlSection &root) {
		int format = 0;
		if (!root.has("format"))
			missing.emplace_back("format", "missing");
		if (root.integer("format", format, 0, 1'000'000) && root.has("format"))
			root.require(format == kBoardCalibrationFormat, "format",
				     "format " + std::to_string(format) + " is not supported: this depthkey reads format " +
					     std::to_string(kBoardCalibrationFormat));
		if (!root.has("board"))
			missing.emplace_back("board", "missing section [board]");
		else
			root.table("board", [&](TomlSection &sec) { bindBoardCalibrationSection(sec, result.calibration); });
		// [end] is written last: a file cut anywhere before it lacks it.
		if (!root.has("end"))
			missing.emplace_back("end", "missing section [end]: the file is cut short");
		else
			root.table("end", [&](TomlSection &sec) {
				bool complete = false;
				sec.require(sec.has("complete"), "complete", "missing");
				if (sec.boolean("complete", complete) && sec.has("complete"))
					sec.require(complete, "complete", "must be true");
			});
	});
	result.errors = std::move(bound.errors);
	// What is missing is reported at the last line, where a cut file stops.
	for (auto &[key, message] : missing)
		result.errors.push_back({ sourceName, lastLineOf(text), 1, key, message });
	return result;
}

BoardCalibrationResult loadBoardCalibration(const std::string &path)
{
	std::string text;
	BoardCalibrationResult result;
	ConfigError error;
	if (!readToolFile(path, "board calibration", text, error)) {
		result.errors.push_back(error);
		return result;
	}
	return parseBoardCalibration(text, path);
}

std::string formatBoardCalibrationSection(const BoardCalibration &c)
{
	std::string h = "[";
	for (int i = 0; i < 9; ++i)
		h += (i ? ", " : "") + formatExact(c.colourToBoard.h[i]);
	h += "]";
	char stats[128];
	std::snprintf(stats, sizeof(stats), "points = %d\nrms_px = %.4f\nmax_px = %.4f\n", c.points, c.rmsPx, c.maxPx);
	const std::string lens = "# The colour lens's radial terms, about the image centre at a focal length\n"
				 "# of one image width; the homography maps the undistorted pixels.\n"
				 "lens_k1 = " + formatExact(c.lensK1) + "\nlens_k2 = " + formatExact(c.lensK2) + "\n";
	return "[board]\n"
	       "date = \"" + c.date + "\"\n"
	       "colour_width = " + std::to_string(c.colourWidth) + "\n"
	       "colour_height = " + std::to_string(c.colourHeight) + "\n"
	       "board_width = " + std::to_string(c.boardWidth) + "\n"
	       "board_height = " + std::to_string(c.boardHeight) + "\n"
	       "homography = " + h + "\n" + lens + stats;
}

std::string formatBoardCalibration(const BoardCalibration &c)
{
	return "# depthkey board calibration, written by depthkey-calibrate --board: the\n"
	       "# homography from colour-camera pixels to board pixels (row-major 3x3).\n"
	       "# Do not edit; calibrate again instead. Residuals are in board pixels.\n"
	       "format = " + std::to_string(kBoardCalibrationFormat) + "\n\n" +
	       formatBoardCalibrationSection(c) +
	       "\n# Written last, so that a file cut short is refused.\n[end]\ncomplete = true\n";
}

int writeBoardCalibration(const std::string &path, const BoardCalibration &calibration, std::string &error)
{
	std::string text = formatBoardCalibration(calibration);
	BoardCalibrationResult check = parseBoardCalibration(text, path);
	if (!check.ok()) {
		error = "refusing to write a board calibration the daemon would not load: " + check.errors.front().toString();
		return -EINVAL;
	}
	return writeFileAtomically(path, text, error);
}

} // namespace depthkey
