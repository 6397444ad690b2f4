// Ray casting of the board in both cameras, with sub-pixel samples so that
// circle edges are anti-aliased as a real sensor integrates them.
#include "hal/sim/calibration_pattern.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

namespace depthkey::sim {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
constexpr int kColourSamples = 2;       // per pixel and axis
constexpr int kTofSamples = 4;
constexpr double kPaper = 0.85, kInk = 0.05, kWall = 0.35;     // reflectances
constexpr double kWallDistanceM = 3.5;
constexpr double kReferenceDistanceM = 2.2;     // where tofAmplitude is given
constexpr double kTofRangeM = 7.5;              // 20 MHz modulation

std::vector<Eigen::Vector2f> lensRays(const LensModel &lens, int samples)
{
	std::vector<Eigen::Vector2f> rays;
	rays.reserve(static_cast<size_t>(lens.width) * lens.height * samples * samples);
	for (int y = 0; y < lens.height; y++)
		for (int x = 0; x < lens.width; x++)
			for (int sy = 0; sy < samples; sy++)
				for (int sx = 0; sx < samples; sx++) {
					double xn, yn;
					lens.undistort(x + (sx + 0.5) / samples - 0.5,
						       y + (sy + 0.5) / samples - 0.5, xn, yn);
					rays.emplace_back(static_cast<float>(xn), static_cast<float>(yn));
				}
	return rays;
}

Eigen::Matrix3d boardRotation(const PatternPose &pose)
{
	return (Eigen::AngleAxisd(pose.yawDeg * kDegree, Eigen::Vector3d::UnitY()) *
		Eigen::AngleAxisd(pose.pitchDeg * kDegree, Eigen::Vector3d::UnitX()) *
		Eigen::AngleAxisd(pose.rollDeg * kDegree, Eigen::Vector3d::UnitZ()))
		.toRotationMatrix();
}

uint16_t clampU16(double v)
{
	return static_cast<uint16_t>(std::clamp(std::lround(v), 0L, 65535L));
}

} // namespace

CalibrationTarget calibrationTarget(const PatternPose &pose, const PatternBoard &board)
{
	CalibrationTarget target;
	target.rotation = boardRotation(pose);
	target.centre = pose.centre;
	target.columns = board.grid.cols;
	target.rows = board.grid.rows;
	target.spacingM = board.spacingM;
	target.diameterM = board.diameterM;
	target.marginM = board.marginM;
	return target;
}

void PatternRenderer::configure(const CameraRig &rig, const PatternBoard &board,
				const PatternConditions &conditions)
{
	rig_ = rig;
	board_ = board;
	conditions_ = conditions;
	colourRays_ = lensRays(rig.colour(), kColourSamples);
	tofRays_ = lensRays(rig.tof(), kTofSamples);
}

PatternPose PatternRenderer::poseFor(const PatternStep &step, int index) const
{
	// How far the board's centre may move off the axis with its edge still
	// 8 % inside the image, at this depth.
	double xEdge, yEdge;
	rig_.colour().undistort(0, 0, xEdge, yEdge);
	double halfW = (board_.grid.cols - 1) * board_.spacingM / 2 + board_.diameterM / 2 + board_.marginM;
	double halfH = (board_.grid.rows - 1) * board_.spacingM / 2 + board_.diameterM / 2 + board_.marginM;
	double roomX = std::max(0.0, step.depthM * std::abs(xEdge) * 0.92 - halfW);
	double roomY = std::max(0.0, step.depthM * std::abs(yEdge) * 0.92 - halfH);

	PatternPose pose;
	pose.centre = { step.across * roomX, step.down * roomY, step.depthM };
	// A hand never holds the board square on: a few degrees each way.
	pose.yawDeg = ((index * 7) % 5 - 2) * 4.0;
	pose.pitchDeg = ((index * 3) % 5 - 2) * 3.0;
	pose.rollDeg = ((index * 11) % 5 - 2) * 1.5;
	return pose;
}

PatternRenderer::Hit PatternRenderer::trace(const Eigen::Vector3d &origin, const Eigen::Vector3d &dir,
					    const PatternPose &pose, const Eigen::Matrix3d &rotation) const
{
	Eigen::Vector3d normal = rotation.col(2);
	double denom = normal.dot(dir);
	if (std::abs(denom) > 1e-9) {
		double t = normal.dot(pose.centre - origin) / denom;
		Eigen::Vector3d local = rotation.transpose() * (origin + t * dir - pose.centre);
		const GridSize &g = board_.grid;
		double halfCols = (g.cols - 1) / 2.0, halfRows = (g.rows - 1) / 2.0;
		double halfW = halfCols * board_.spacingM + board_.diameterM / 2 + board_.marginM;
		double halfH = halfRows * board_.spacingM + board_.diameterM / 2 + board_.marginM;
		if (t > 0 && std::abs(local.x()) <= halfW && std::abs(local.y()) <= halfH) {
			double col = std::clamp(std::round(local.x() / board_.spacingM + halfCols), 0.0, g.cols - 1.0);
			double row = std::clamp(std::round(local.y() / board_.spacingM + halfRows), 0.0, g.rows - 1.0);
			double dx = local.x() - (col - halfCols) * board_.spacingM;
			double dy = local.y() - (row - halfRows) * board_.spacingM;
			double r = board_.diameterM / 2;
			return { t, dx * dx + dy * dy <= r * r ? kInk : kPaper };
		}
	}
	return { (kWallDistanceM - origin.z()) / dir.z(), kWall };
}

void PatternRenderer::render(const PatternPose &pose, uint64_t frame, ColourFrame &colour,
			     DepthFrame &depth) const
{
	std::mt19937_64 rng(conditions_.seed * 0x9e3779b97f4a7c15ULL + frame);
	std::normal_distribution<double> gauss(0.0, 1.0);
	Eigen::Matrix3d rotation = boardRotation(pose);

	const LensModel &cl = rig_.colour();
	colour.rgb.resize(cl.width, cl.height);
	const Eigen::Vector2f *ray = colourRays_.data();
	for (int y = 0; y < cl.height; y++) {
		for (int x = 0; x < cl.width; x++) {
			double sum = 0;
			for (int s = 0; s < kColourSamples * kColourSamples; s++, ray++)
				sum += trace(Eigen::Vector3d::Zero(), { (*ray).x(), (*ray).y(), 1.0 }, pose, rotation)
					       .reflectance;
			double level = 255.0 * 0.95 * sum / (kColourSamples * kColourSamples) +
				       conditions_.colourNoise * gauss(rng);
			uint8_t v = static_cast<uint8_t>(std::clamp(std::lround(level), 0L, 255L));
			colour.rgb.at(x, y) = { v, v, v };
		}
	}

	const LensModel &tl = rig_.tof();
	depth.depthMm.resize(tl.width, tl.height);
	depth.amplitude.resize(tl.width, tl.height);
	depth.intensity.resize(tl.width, tl.height);
	const Eigen::Vector3d &origin = rig_.tofOrigin();
	ray = tofRays_.data();
	for (int v = 0; v < tl.height; v++) {
		for (int u = 0; u < tl.width; u++) {
			// Vignetting: the amplitude falls to tofCornerAmplitude at the corner.
			double ru = (u - tl.cx) / tl.cx, rv = (v - tl.cy) / tl.cy;
			double vignette = std::pow(conditions_.tofCornerAmplitude, (ru * ru + rv * rv) / 2);
			double sumA = 0, sumAz = 0;
			for (int s = 0; s < kTofSamples * kTofSamples; s++, ray++) {
				Eigen::Vector3d dir = rig_.tofRotation() * Eigen::Vector3d((*ray).x(), (*ray).y(), 1.0);
				Hit hit = trace(origin, dir, pose, rotation);
				double range = hit.t * dir.norm();
				double a = conditions_.tofAmplitude * hit.reflectance / kPaper * vignette *
					   std::pow(kReferenceDistanceM / range, 2);
				// Samples mix by amplitude, as phases do in one pixel.
				sumA += a;
				sumAz += a * hit.t;
			}
			double a = sumA / (kTofSamples * kTofSamples);
			double z = sumAz / sumA;
			double intensity = conditions_.tofAmbient + 1.5 * a;
			if (conditions_.depthNoise) {
				double sigma = kTofRangeM / std::sqrt(8.0) * std::sqrt(intensity) / (2 * a);
				z += sigma * gauss(rng);
				a += std::sqrt(intensity) * gauss(rng);
			}
			depth.depthMm.at(u, v) = z > 0 ? clampU16(z * 1000.0) : 0;
			depth.amplitude.at(u, v) = clampU16(std::max(a, 1.0));
			depth.intensity.at(u, v) = clampU16(intensity);
		}
	}
	depth.sequence = colour.sequence = frame;
}

} // namespace depthkey::sim
