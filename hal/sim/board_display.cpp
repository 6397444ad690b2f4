#include "hal/sim/board_display.hpp"

#include "hal/sim/scene_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace depthkey {

namespace {

using sim::BoardGeometry;

constexpr double kDisplayWidthM = BoardGeometry::kRight - BoardGeometry::kLeft;
constexpr double kDisplayHeightM = BoardGeometry::kBottom - BoardGeometry::kTop;

} // namespace

int simBoardHeight(int width)
{
	return std::max(16, int(std::lround(width * kDisplayHeightM / kDisplayWidthM)));
}

void SimBoardDisplay::configure(const SimSettings &settings, int width)
{
	script_.configure(settings.seed, settings.boardDistanceMm / 1000.0, settings.walkSpeedMps,
			  settings.boardChanges);
	boardChanges_ = settings.boardChanges;
	width_ = width;
	height_ = simBoardHeight(width);
	// Each board pixel shows the texel (2.5 mm) under its centre: strokes
	// 1 cm wide stay crisp at 1920 px (1.7 mm a pixel).
	const int columns = BoardGeometry::texelColumns(), rows = BoardGeometry::texelRows();
	texelOf_.resize(size_t(width_) * height_);
	for (int y = 0; y < height_; ++y)
		for (int x = 0; x < width_; ++x) {
			int c = std::min(columns - 1, int((x + 0.5) * columns / width_));
			int r = std::min(rows - 1, int((y + 0.5) * rows / height_));
			texelOf_[size_t(y) * width_ + x] = r * columns + c;
		}
	cycle_ = ~0ull;
}

void SimBoardDisplay::render(double timeS, RgbImage &out)
{
	uint64_t cycle = boardChanges_ ? script_.cycleOf(timeS) : 0;
	if (cycle != cycle_) {
		script_.rasterise(cycle, texels_);
		cycle_ = cycle;
	}
	const uint16_t tick =
		uint16_t(std::min(65534.0, script_.cycleTime(timeS) / sim::LectureScript::kTickS));
	const Rgb8 *ink = sim::LectureScript::inkColours();
	out.resize(width_, height_);
	Rgb8 *dst = out.data();
	for (size_t k = 0; k < out.size(); ++k) {
		const sim::BoardTexel &t = texels_[size_t(texelOf_[k])];
		bool inked = t.ink && tick >= t.writeTick && tick < t.eraseTick;
		dst[k] = inked ? ink[t.ink] : t.background;
	}
}

bool simColourToBoard(const CameraRig &rig, double boardDistanceM, int width, int height, double x, double y,
		      double &u, double &v)
{
	double xn, yn;
	rig.colour().undistort(x, y, xn, yn);
	// The colour camera sits at the origin looking along z at the plane.
	double bx = xn * boardDistanceM, by = yn * boardDistanceM;
	u = (bx - BoardGeometry::kLeft) / kDisplayWidthM * width - 0.5;
	v = (by - BoardGeometry::kTop) / kDisplayHeightM * height - 0.5;
	return std::isfinite(u) && std::isfinite(v);
}

Homography simTrueHomography(const CameraRig &rig, double boardDistanceM, int width, int height)
{
	const LensModel &lens = rig.colour();
	const double su = boardDistanceM / lens.fx * width / kDisplayWidthM;
	const double sv = boardDistanceM / lens.fy * height / kDisplayHeightM;
	Homography h;
	h.h = { su, 0, -lens.cx * su - BoardGeometry::kLeft / kDisplayWidthM * width - 0.5,
		0, sv, -lens.cy * sv - BoardGeometry::kTop / kDisplayHeightM * height - 0.5,
		0, 0, 1 };
	return h;
}

} // namespace depthkey
