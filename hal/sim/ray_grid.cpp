#include "hal/sim/ray_grid.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace depthkey::sim {

namespace {

constexpr float kFar = std::numeric_limits<float>::max();

} // namespace

void RayGrid::configure(const LensModel &lens, int samplesPerPixel, const Eigen::Matrix3d &cameraRotation,
			const Eigen::Vector3d &cameraOrigin, const StaticScene &scene, Channels channels)
{
	lens_ = lens;
	colour_ = channels == Channels::Colour;
	samples_ = samplesPerPixel;
	width_ = lens.width * samples_;
	height_ = lens.height * samples_;
	footprint_ = static_cast<float>(1.0 / (std::sqrt(lens.fx * lens.fy) * samples_));
	toCamera_ = cameraRotation.transpose().cast<float>();
	origin_ = cameraOrigin.cast<float>();
	size_t n = static_cast<size_t>(width_) * height_;
	rays_.begin(lens, samples_);
	std::vector<float> staticZ(n, kFar); // kept compactly once complete
	// The channels not kept give their memory back.
	const size_t colourSamples = colour_ ? n : 0, reflectivitySamples = colour_ ? 0 : n;
	staticReflectivity_.assign(reflectivitySamples, 0.0f);
	boardTexel_.assign(colourSamples, -1);
	staticColour_.assign(colourSamples, Rgb8{ 0, 0, 0 });
	staticReflectivity_.shrink_to_fit();
	boardTexel_.shrink_to_fit();
	staticColour_.shrink_to_fit();
	rowZ_.assign(width_, kFar);
	rowAlpha_.assign(width_, 0.0f);
	rowColour_.assign(colour_ ? width_ : 0, Rgb8{ 0, 0, 0 });
	rowReflectivity_.assign(colour_ ? 0 : width_, 0.0f);
	rowX0_ = rowX1_ = 0;
	posed_.clear();
	dirtyX0_ = dirtyY0_ = dirtyX1_ = dirtyY1_ = 0;

	const int columns = BoardGeometry::texelColumns(), rows = BoardGeometry::texelRows();
	struct Prepared {
		Eigen::Vector3d normal, toOrigin, u, v; // u, v: edges over their squared length
	};
	std::vector<Prepared> prepared;
	for (const Quad &q : scene.quads)
		prepared.push_back({ q.edgeU.cross(q.edgeV), q.origin - cameraOrigin, q.edgeU / q.edgeU.squaredNorm(),
				     q.edgeV / q.edgeV.squaredNorm() });
	for (int j = 0; j < height_; ++j)
		for (int i = 0; i < width_; ++i) {
			size_t k = static_cast<size_t>(j) * width_ + i;
			Eigen::Vector3d ray = SampleRays::exactRay(lens, samples_, i, j);
			rays_.put(i, j, ray);
			Eigen::Vector3d dir = cameraRotation * ray;
			double best = std::numeric_limits<double>::max();
			for (size_t qi = 0; qi < scene.quads.size(); ++qi) {
				const Quad &q = scene.quads[qi];
				const Prepared &p = prepared[qi];
				double denom = p.normal.dot(dir);
				if (std::fabs(denom) < 1e-12)
					continue;
				double t = p.normal.dot(p.toOrigin) / denom;
				if (t <= 0 || t >= best)
					continue;
				Eigen::Vector3d rel = dir * t - p.toOrigin;
				double s = rel.dot(p.u);
				double u = rel.dot(p.v);
				if (s < 0 || s > 1 || u < 0 || u > 1)
					continue;
				best = t;
				Eigen::Vector3d hit = cameraOrigin + dir * t;
				staticZ[k] = static_cast<float>(t * ray.z());
				Rgb8 colour = q.colour;
				float reflectivity = q.reflectivity;
				int32_t texel = -1;
				if (q.surface == QuadSurface::Board) {
					int c = static_cast<int>((hit.x() - BoardGeometry::kLeft) / BoardGeometry::kTexelM);
					int r = static_cast<int>((hit.y() - BoardGeometry::kTop) / BoardGeometry::kTexelM);
					if (hit.x() >= BoardGeometry::kLeft && hit.y() >= BoardGeometry::kTop &&
					    c < columns && r < rows)
						texel = r * columns + c;
				} else if (q.surface == QuadSurface::CalibrationTarget && scene.target) {
					calibrationTargetSurface(*scene.target, s, u, t * footprint_, colour, reflectivity);
				}
				if (colour_) {
					staticColour_[k] = colour;
					boardTexel_[k] = texel;
				} else {
					staticReflectivity_[k] = reflectivity;
				}
			}
		}
	staticZ_.assign(width_, height_, staticZ);
	// Never seen: a lens whose mirrored samples round differently keeps
	// every ray.
	if (!rays_.exact()) {
		rays_.begin(lens, samples_, false);
		for (int j = 0; j < height_; ++j)
			for (int i = 0; i < width_; ++i)
				rays_.put(i, j, SampleRays::exactRay(lens, samples_, i, j));
	}
}

void RayGrid::setCapsules(const std::vector<Capsule> &sceneCapsules)
{
	posed_.clear(); // keeps its capacity: no allocation once the lecturer has been posed
	dirtyX0_ = width_;
	dirtyY0_ = height_;
	dirtyX1_ = dirtyY1_ = 0;
	for (const Capsule &c : sceneCapsules) {
		PosedCapsule p;
		if (!pose(c, p))
			continue;
		posed_.push_back(p);
		dirtyX0_ = std::min(dirtyX0_, p.x0);
		dirtyX1_ = std::max(dirtyX1_, p.x1);
		dirtyY0_ = std::min(dirtyY0_, p.y0);
		dirtyY1_ = std::max(dirtyY1_, p.y1);
	}
	if (posed_.empty())
		dirtyX0_ = dirtyY0_ = dirtyX1_ = dirtyY1_ = 0;
}

// The capsule in camera coordinates and its samples: the screen bounding box
// of the corners of its 3D box; a sample or two of margin covers the lens
// bending the box's edges.
bool RayGrid::pose(const Capsule &scene, PosedCapsule &out) const
{
	const Eigen::Vector3f a = toCamera_ * (scene.a - origin_), b = toCamera_ * (scene.b - origin_);
	const float r = scene.radius;
	Eigen::Vector3f lo = a.cwiseMin(b).array() - r, hi = a.cwiseMax(b).array() + r;
	if (hi.z() < 0.05f)
		return false;
	lo.z() = std::max(lo.z(), 0.05f);
	double minX = 1e9, minY = 1e9, maxX = -1e9, maxY = -1e9;
	for (int corner = 0; corner < 8; ++corner) {
		Eigen::Vector3d p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
				  (corner & 4) ? hi.z() : lo.z());
		double x, y;
		lens_.project(p, x, y);
		minX = std::min(minX, x);
		maxX = std::max(maxX, x);
		minY = std::min(minY, y);
		maxY = std::max(maxY, y);
	}
	auto toSample = [this](double pixel) { return (pixel + 0.5) * samples_ - 0.5; };
	out.x0 = std::max(0, static_cast<int>(std::floor(toSample(minX))) - 2 * samples_);
	out.x1 = std::min(width_, static_cast<int>(std::ceil(toSample(maxX))) + 2 * samples_ + 1);
	out.y0 = std::max(0, static_cast<int>(std::floor(toSample(minY))) - 2 * samples_);
	out.y1 = std::min(height_, static_cast<int>(std::ceil(toSample(maxY))) + 2 * samples_ + 1);
	if (out.x0 >= out.x1 || out.y0 >= out.y1)
		return false;
	out.a = a;
	out.ba = b - a;
	out.r = r;
	out.C = out.ba.squaredNorm();
	out.aa = a.squaredNorm();
	out.aba = a.dot(out.ba);
	out.colour = scene.colour;
	out.reflectivity = scene.reflectivity;
	return true;
}

RayGrid::Row RayGrid::drawRow(int j)
{
	std::fill(rowZ_.begin() + rowX0_, rowZ_.begin() + rowX1_, kFar);
	std::fill(rowAlpha_.begin() + rowX0_, rowAlpha_.begin() + rowX1_, 0.0f);
	rowX0_ = width_;
	rowX1_ = 0;
	const float *staticZ = posed_.empty() ? nullptr : staticZ_.row(j);
	// Capsule by capsule in their order, as each sample's result depends on.
	for (const PosedCapsule &c : posed_)
		if (j >= c.y0 && j < c.y1) {
			drawSpan(c, j, c.x0, c.x1, staticZ);
			rowX0_ = std::min(rowX0_, c.x0);
			rowX1_ = std::max(rowX1_, c.x1);
		}
	rowX1_ = std::max(rowX1_, rowX0_);
	return { rowZ_.data(), rowAlpha_.data(), rowColour_.data(), rowReflectivity_.data() };
}

// Closest approach of the ray t*d (|d| = 1) to the segment a + s*(b - a):
//   s = (B (d.a) - ba.a) / (C - B^2),  B = d.ba, C = ba.ba, clamped to [0, 1]
//   t = d.a + s B
//   dist^2 = t^2 - 2 t (d.a) - 2 t s B + a.a + 2 s (a.ba) + s^2 C
// all from per-capsule constants and two dot products per sample.
void RayGrid::drawSpan(const PosedCapsule &c, int j, int x0, int x1, const float *staticZ)
{
	const Eigen::Vector3f a = c.a, ba = c.ba;
	const float r = c.r, C = c.C, aa = c.aa, aba = c.aba;
	for (int i = x0; i < x1; ++i) {
		const SampleRays::Ray ray = rays_.at(i, j);
		float dx = ray.x, dy = ray.y, dz = ray.z;
		float da = dx * a.x() + dy * a.y() + dz * a.z();
		float B = dx * ba.x() + dy * ba.y() + dz * ba.z();
		float denom = C - B * B;
		float s = denom > 1e-9f ? (B * da - aba) / denom : 0.0f;
		s = std::clamp(s, 0.0f, 1.0f);
		float t = da + s * B;
		if (t <= 0.05f)
			continue;
		float dist2 = t * t - 2 * t * da - 2 * t * s * B + aa + 2 * s * aba + s * s * C;
		float dist = std::sqrt(std::max(dist2, 0.0f));
		float fp = t * footprint_;
		float alpha = std::clamp((r - dist) / fp + 0.5f, 0.0f, 1.0f);
		if (alpha <= 0.0f)
			continue;
		float inside = std::max(0.0f, r * r - dist2);
		float z = (t - std::sqrt(inside)) * dz;
		if (z >= staticZ[i])
			continue; // behind the desk or the board
		if (z < rowZ_[i] && (alpha >= 0.5f || rowAlpha_[i] < 0.5f)) {
			rowZ_[i] = z;
			// Rounder towards the middle: light falls off to the rim.
			if (colour_) {
				float shade = 0.62f + 0.38f * std::sqrt(inside) / r;
				rowColour_[i] = { static_cast<uint8_t>(c.colour.r * shade),
						  static_cast<uint8_t>(c.colour.g * shade),
						  static_cast<uint8_t>(c.colour.b * shade) };
			} else {
				rowReflectivity_[i] = c.reflectivity;
			}
		}
		rowAlpha_[i] = std::max(rowAlpha_[i], alpha);
	}
}

} // namespace depthkey::sim
