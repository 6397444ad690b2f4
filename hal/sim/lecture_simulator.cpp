#include "hal/sim/lecture_simulator.hpp"

#include "hal/sim/board_display.hpp"
#include "hal/sim/hash_noise.hpp"

#include <algorithm>
#include <cmath>

namespace depthkey {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kReferenceDistanceM = 2.0; // tofAmplitude is the board's amplitude there
constexpr float kBoardReflectivity = 0.8f;
constexpr int kTofSamplesPerPixel = 2;      // 2x2: edge pixels mix depths like the SR-2's big pixels
constexpr int kMotionBlurSamples = 3;       // time samples over the exposure

// Inverse of the standard normal CDF by bisection (configure time only).
double normalQuantile(double p)
{
	double lo = -6, hi = 6;
	for (int i = 0; i < 60; ++i) {
		double mid = (lo + hi) / 2;
		(0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
	}
	return (lo + hi) / 2;
}

uint64_t timeKey(uint64_t seed, uint64_t stream, double timeS)
{
	return sim::hashKey(seed, stream, static_cast<uint64_t>(std::llround(timeS * 1e6)));
}

uint8_t clampU8(int v)
{
	return static_cast<uint8_t>(v < 0 ? 0 : v > 255 ? 255 : v);
}

} // namespace

void LectureSimulator::configure(const SimSettings &settings, int colourWidth, int colourHeight)
{
	settings_ = settings;
	colourWidth_ = colourWidth;
	colourHeight_ = colourHeight;
	rig_.configure(colourWidth, colourHeight, settings.distortion, settings.baselineMm);
	script_.configure(settings.seed, settings.boardDistanceMm / 1000.0, settings.walkSpeedMps,
			  settings.boardChanges);
	look_ = sim::LecturerLook::fromSeed(settings.seed);
	// 256 equiprobable normal quantiles: one hash byte picks a noise value.
	for (int i = 0; i < 256; ++i)
		colourNoise_[i] = static_cast<int8_t>(
			std::clamp(std::lround(settings.colourNoise * normalQuantile((i + 0.5) / 256.0)), -127L, 127L));
	colourReady_ = depthReady_ = false;
	boardCycle_ = ~0ull;
}

void LectureSimulator::setCalibrationTarget(const std::optional<sim::CalibrationTarget> &target)
{
	if (target == target_)
		return;
	target_ = target;
	colourReady_ = depthReady_ = false;
}

void LectureSimulator::renderCalibrationPattern(const sim::CalibrationTarget &target, double timeS,
						ColourFrame &colour, DepthFrame &depth)
{
	setCalibrationTarget(target);
	renderColour(timeS, colour);
	renderDepth(timeS, depth);
}

void LectureSimulator::showOnBoard(const RgbImage &picture)
{
	shownPicture_ = picture;
	shown_.clear();
	colourReady_ = false;
}

void LectureSimulator::poseLecturer(double timeS, std::vector<sim::Capsule> &out) const
{
	if (target_ || !lecturerVisible_)
		out.clear();
	else
		sim::poseLecturer(script_, look_, timeS, out);
}

void LectureSimulator::ensureColourGrid()
{
	if (colourReady_)
		return;
	sim::StaticScene scene = sim::StaticScene::build(settings_.boardDistanceMm / 1000.0, settings_.table,
							 target_ ? &*target_ : nullptr);
	colourGrid_.configure(rig_.colour(), 1, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), scene,
			      sim::RayGrid::Channels::Colour);
	colourReady_ = true;
	// One colour table (issue 15): a pixel off the board display keeps its
	// static colour where a board pixel keeps its texel's.
	backdrop_.build(colourWidth_, colourGrid_.takeBoardTexel(), colourGrid_.takeStaticColour());
	boardCycle_ = ~0ull; // the backdrop holds no texels of this grid's board pixels yet
	if (shownPicture_.empty())
		return;
	// The picture on the display, per colour pixel where the display is seen.
	constexpr int kSub = 4;
	const int pw = shownPicture_.width(), ph = shownPicture_.height();
	const double d = settings_.boardDistanceMm / 1000.0;
	auto sample = [&](double u, double v, int ch) {
		u = std::clamp(u, 0.0, pw - 1.0);
		v = std::clamp(v, 0.0, ph - 1.0);
		int x0 = std::min(int(u), pw - 2 < 0 ? 0 : pw - 2), y0 = std::min(int(v), ph - 2 < 0 ? 0 : ph - 2);
		int x1 = std::min(x0 + 1, pw - 1), y1 = std::min(y0 + 1, ph - 1);
		double fx = u - x0, fy = v - y0;
		auto at = [&](int x, int y) { const Rgb8 &p = shownPicture_.at(x, y); return double(ch == 0 ? p.r : ch == 1 ? p.g : p.b); };
		return (at(x0, y0) * (1 - fx) + at(x1, y0) * fx) * (1 - fy) + (at(x0, y1) * (1 - fx) + at(x1, y1) * fx) * fy;
	};
	shown_.assign(size_t(colourWidth_) * colourHeight_, Rgb8{});
	for (int y = 0; y < colourHeight_; ++y) {
		const uint32_t *backdrop = backdrop_.row(y);
		for (int x = 0; x < colourWidth_; ++x) {
			size_t k = size_t(y) * colourWidth_ + x;
			if (!sim::ColourBackdrop::onBoard(backdrop[x]))
				continue;
			double sum[3] = { 0, 0, 0 };
			for (int j = 0; j < kSub; ++j)
				for (int i = 0; i < kSub; ++i) {
					double u, v;
					simColourToBoard(rig_, d, pw, ph, x + (i + 0.5) / kSub - 0.5, y + (j + 0.5) / kSub - 0.5, u, v);
					for (int ch = 0; ch < 3; ++ch)
						sum[ch] += sample(u, v, ch);
				}
			shown_[k] = { clampU8(int(std::lround(sum[0] / (kSub * kSub)))), clampU8(int(std::lround(sum[1] / (kSub * kSub)))),
				      clampU8(int(std::lround(sum[2] / (kSub * kSub)))) };
		}
	}
}

void LectureSimulator::ensureDepthGrid()
{
	if (depthReady_)
		return;
	sim::StaticScene scene = sim::StaticScene::build(settings_.boardDistanceMm / 1000.0, settings_.table,
							 target_ ? &*target_ : nullptr);
	depthGrid_.configure(rig_.tof(), kTofSamplesPerPixel, rig_.tofRotation(), rig_.tofOrigin(), scene,
			     sim::RayGrid::Channels::Reflectivity);

	// Vignetting: amplitude falls off as 1 / (1 + a r^2)^2 with r = 1 at the
	// corner, where it is tofCornerAmplitude of the centre's.
	const double a = 1.0 / std::sqrt(settings_.tofCornerAmplitude) - 1.0;
	const LensModel &lens = rig_.tof();
	vignette_.resize(static_cast<size_t>(kTofWidth) * kTofHeight);
	for (int v = 0; v < kTofHeight; ++v)
		for (int u = 0; u < kTofWidth; ++u) {
			double dx = (u - lens.cx) / (lens.width / 2.0), dy = (v - lens.cy) / (lens.height / 2.0);
			double r2 = (dx * dx + dy * dy) / 2.0;
			vignette_[static_cast<size_t>(v) * kTofWidth + u] = static_cast<float>(1.0 / ((1 + a * r2) * (1 + a * r2)));
		}
	const int w = depthGrid_.width();
	// The reflectivities are only read here: the grid keeps none.
	const std::vector<float> reflectivity = depthGrid_.takeStaticReflectivity();
	staticAmplitude_.resize(depthGrid_.size());
	for (int j = 0; j < depthGrid_.height(); ++j) {
		const float *staticZ = depthGrid_.staticZRow(j);
		for (int i = 0; i < w; ++i) {
			size_t k = static_cast<size_t>(j) * w + i;
			int u = i / kTofSamplesPerPixel, v = j / kTofSamplesPerPixel;
			float d = static_cast<float>(kReferenceDistanceM) / staticZ[i];
			staticAmplitude_[k] = static_cast<float>(settings_.tofAmplitude) / kBoardReflectivity *
					      reflectivity[k] * d * d *
					      vignette_[static_cast<size_t>(v) * kTofWidth + u];
		}
	}
	depthReady_ = true;
}

void LectureSimulator::ensureBoard(double timeS)
{
	uint64_t cycle = settings_.boardChanges ? script_.cycleOf(timeS) : 0;
	if (cycle == boardCycle_)
		return;
	// The whole board's raster (2.5 mm texels, 5.2 MB) only while the
	// texels the colour pixels show are picked from it (issue 15).
	std::vector<sim::BoardTexel> raster;
	script_.rasterise(cycle, raster);
	backdrop_.pick(raster);
	boardCycle_ = cycle;
}

// Room light: brightness swings slowly, warmer when brighter (daylight
// through a window and the projector's lamp), as Q8 gains per channel.
void LectureSimulator::lightingGains(double timeS, int gains[3]) const
{
	double swing = settings_.lightingChange
			       ? std::sin(2 * kPi * timeS / settings_.lightingPeriodS + (settings_.seed % 13))
			       : 0.0;
	double g = 1.0 + settings_.lightingAmplitude * swing;
	gains[0] = static_cast<int>(std::lround(256 * g * (1 + 0.04 * swing)));
	gains[1] = static_cast<int>(std::lround(256 * g));
	gains[2] = static_cast<int>(std::lround(256 * g * (1 - 0.04 * swing)));
}

void LectureSimulator::renderColour(double timeS, ColourFrame &out, GroundTruth *truth)
{
	ensureColourGrid();
	ensureBoard(timeS);
	poseLecturer(timeS, capsules_);
	colourGrid_.setCapsules(capsules_);

	const int w = colourWidth_, h = colourHeight_;
	out.rgb.resize(w, h);
	out.timestampNs = static_cast<uint64_t>(std::llround(timeS * 1e9));
	if (truth) {
		truth->mask.resize(w, h);
		truth->alpha.resize(w, h);
		truth->depthMm.resize(w, h);
		truth->timeS = timeS;
	}
	int gain[3];
	lightingGains(timeS, gain);
	const uint16_t tick = static_cast<uint16_t>(
		std::min(65534.0, script_.cycleTime(timeS) / sim::LectureScript::kTickS));
	const uint64_t noiseKey = timeKey(settings_.seed, 3, timeS);
	const bool noise = settings_.colourNoise > 0;
	const bool showing = !shown_.empty();
	size_t inked = 0; // the backdrop's running count, every pixel asked in row-major order
	const int dx0 = colourGrid_.dirtyX0(), dx1 = colourGrid_.dirtyX1();
	const int dy0 = colourGrid_.dirtyY0(), dy1 = colourGrid_.dirtyY1();

	for (int y = 0; y < h; ++y) {
		Rgb8 *row = out.rgb.row(y);
		const size_t base = static_cast<size_t>(y) * w;
		const bool lecturerRow = y >= dy0 && y < dy1;
		const sim::RayGrid::Row lecturer = lecturerRow ? colourGrid_.drawRow(y) : sim::RayGrid::Row{};
		const float *staticZ = truth ? colourGrid_.staticZRow(y) : nullptr;
		const uint32_t *backdrop = backdrop_.row(y);
		for (int x = 0; x < w; ++x) {
			const size_t k = base + x;
			Rgb8 c = backdrop_.colourAt(backdrop[x], tick, inked);
			if (showing && sim::ColourBackdrop::onBoard(backdrop[x]))
				c = shown_[k];
			int alpha256 = 0;
			if (lecturerRow && x >= dx0 && x < dx1 && lecturer.alpha[x] > 0) {
				alpha256 = static_cast<int>(lecturer.alpha[x] * 256.0f + 0.5f);
				const Rgb8 l = lecturer.colour[x];
				c = { static_cast<uint8_t>(c.r + (((l.r - c.r) * alpha256) >> 8)),
				      static_cast<uint8_t>(c.g + (((l.g - c.g) * alpha256) >> 8)),
				      static_cast<uint8_t>(c.b + (((l.b - c.b) * alpha256) >> 8)) };
			}
			int r = (c.r * gain[0]) >> 8, g = (c.g * gain[1]) >> 8, b = (c.b * gain[2]) >> 8;
			if (noise) {
				uint64_t hsh = sim::mixHash(noiseKey + k);
				r += colourNoise_[hsh & 0xFF];
				g += colourNoise_[(hsh >> 8) & 0xFF];
				b += colourNoise_[(hsh >> 16) & 0xFF];
			}
			row[x] = { clampU8(r), clampU8(g), clampU8(b) };
			if (truth) {
				uint8_t a8 = static_cast<uint8_t>(std::min(255, alpha256 - (alpha256 >> 8)));
				truth->alpha.row(y)[x] = a8;
				bool covered = alpha256 >= 128;
				truth->mask.row(y)[x] = covered ? 255 : 0;
				float z = covered ? lecturer.z[x] : staticZ[x];
				truth->depthMm.row(y)[x] = static_cast<uint16_t>(std::min(65535.0f, z * 1000.0f + 0.5f));
			}
		}
	}
}

void LectureSimulator::renderDepth(double timeS, DepthFrame &out)
{
	ensureDepthGrid();
	const int sw = depthGrid_.width(), ss = kTofSamplesPerPixel;
	tof_.reset(kTofWidth, kTofHeight);
	const int times = settings_.motionBlur && !target_ ? kMotionBlurSamples : 1;
	const double exposure = settings_.tofExposureMs / 1000.0;
	for (int ti = 0; ti < times; ++ti) {
		double t = times == 1 ? timeS : timeS + exposure * (ti / (times - 1.0) - 0.5);
		poseLecturer(t, capsules_);
		depthGrid_.setCapsules(capsules_);
		for (int j = 0; j < depthGrid_.height(); ++j) {
			// Alpha 0 all along a row no capsule reaches.
			const sim::RayGrid::Row lecturer = depthGrid_.drawRow(j);
			const float *staticZ = depthGrid_.staticZRow(j);
			for (int i = 0; i < sw; ++i) {
				size_t k = static_cast<size_t>(j) * sw + i;
				size_t pixel = static_cast<size_t>(j / ss) * kTofWidth + i / ss;
				float a = lecturer.alpha[i];
				tof_.add(pixel, staticAmplitude_[k] * (1.0f - a), staticZ[i]);
				if (a > 0) {
					const float z = lecturer.z[i];
					float d = static_cast<float>(kReferenceDistanceM) / z;
					float amp = static_cast<float>(settings_.tofAmplitude) / kBoardReflectivity *
						    lecturer.reflectivity[i] * d * d * vignette_[pixel];
					tof_.add(pixel, a * amp, z);
					tof_.lecturerAmp[pixel] += a * amp;
					tof_.lecturerAmpZ[pixel] += a * amp * z;
					tof_.lecturerCover[pixel] += a;
				}
			}
		}
	}
	tof_.samples = times * ss * ss;
	sim::finishTofFrame(tof_, settings_, timeKey(settings_.seed, 4, timeS), out);
	out.timestampNs = static_cast<uint64_t>(std::llround(timeS * 1e9));
}

} // namespace depthkey
