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
	rayX_.resize(n);
	rayY_.resize(n);
	rayZ_.resize(n);
	staticZ_.assign(n, kFar);
	lecZ_.assign(n, kFar);
	lecAlpha_.assign(n, 0.0f);
	// The channels not kept give their memory back.
	const size_t colourSamples = colour_ ? n : 0, reflectivitySamples = colour_ ? 0 : n;
	staticReflectivity_.assign(reflectivitySamples, 0.0f);
	lecReflectivity_.assign(reflectivitySamples, 0.0f);
	boardTexel_.assign(colourSamples, -1);
	staticColour_.assign(colourSamples, Rgb8{ 0, 0, 0 });
	lecColour_.assign(colourSamples, Rgb8{ 0, 0, 0 });
	for (auto *v : { &staticReflectivity_, &lecReflectivity_ })
		v->shrink_to_fit();
	boardTexel_.shrink_to_fit();
	staticColour_.shrink_to_fit();
	lecColour_.shrink_to_fit();
	dirtyX0_ = dirtyY0_ = 0;
	dirtyX1_ = width_;
	dirtyY1_ = height_;

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
			double xn, yn;
			lens.undistort((i + 0.5) / samples_ - 0.5, (j + 0.5) / samples_ - 0.5, xn, yn);
			Eigen::Vector3d ray = Eigen::Vector3d(xn, yn, 1.0).normalized();
			rayX_[k] = static_cast<float>(ray.x());
			rayY_[k] = static_cast<float>(ray.y());
			rayZ_[k] = static_cast<float>(ray.z());
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
				staticZ_[k] = static_cast<float>(t * ray.z());
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
}

void RayGrid::clearDirty()
{
	for (int j = dirtyY0_; j < dirtyY1_; ++j) {
		size_t row = static_cast<size_t>(j) * width_;
		std::fill(lecZ_.begin() + row + dirtyX0_, lecZ_.begin() + row + dirtyX1_, kFar);
		std::fill(lecAlpha_.begin() + row + dirtyX0_, lecAlpha_.begin() + row + dirtyX1_, 0.0f);
	}
	dirtyX0_ = width_;
	dirtyY0_ = height_;
	dirtyX1_ = dirtyY1_ = 0;
}

void RayGrid::drawCapsules(const std::vector<Capsule> &sceneCapsules)
{
	clearDirty();
	for (const Capsule &c : sceneCapsules) {
		Capsule local = c;
		local.a = toCamera_ * (c.a - origin_);
		local.b = toCamera_ * (c.b - origin_);
		drawCapsule(local);
	}
}

// Closest approach of the ray t*d (|d| = 1) to the segment a + s*(b - a):
//   s = (B (d.a) - ba.a) / (C - B^2),  B = d.ba, C = ba.ba, clamped to [0, 1]
//   t = d.a + s B
//   dist^2 = t^2 - 2 t (d.a) - 2 t s B + a.a + 2 s (a.ba) + s^2 C
// all from per-capsule constants and two dot products per sample.
void RayGrid::drawCapsule(const Capsule &c)
{
	const Eigen::Vector3f a = c.a, ba = c.b - c.a;
	const float r = c.radius;
	// Screen bounding box from the corners of the capsule's 3D box; a sample
	// or two of margin covers the lens bending the box's edges.
	Eigen::Vector3f lo = a.cwiseMin(c.b).array() - r, hi = a.cwiseMax(c.b).array() + r;
	if (hi.z() < 0.05f)
		return;
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
	int x0 = std::max(0, static_cast<int>(std::floor(toSample(minX))) - 2 * samples_);
	int x1 = std::min(width_, static_cast<int>(std::ceil(toSample(maxX))) + 2 * samples_ + 1);
	int y0 = std::max(0, static_cast<int>(std::floor(toSample(minY))) - 2 * samples_);
	int y1 = std::min(height_, static_cast<int>(std::ceil(toSample(maxY))) + 2 * samples_ + 1);
	if (x0 >= x1 || y0 >= y1)
		return;
	dirtyX0_ = std::min(dirtyX0_, x0);
	dirtyX1_ = std::max(dirtyX1_, x1);
	dirtyY0_ = std::min(dirtyY0_, y0);
	dirtyY1_ = std::max(dirtyY1_, y1);

	const float C = ba.squaredNorm(), aa = a.squaredNorm(), aba = a.dot(ba);
	for (int j = y0; j < y1; ++j) {
		size_t row = static_cast<size_t>(j) * width_;
		for (int i = x0; i < x1; ++i) {
			size_t k = row + i;
			float dx = rayX_[k], dy = rayY_[k], dz = rayZ_[k];
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
			if (z >= staticZ_[k])
				continue; // behind the desk or the board
			if (z < lecZ_[k] && (alpha >= 0.5f || lecAlpha_[k] < 0.5f)) {
				lecZ_[k] = z;
				// Rounder towards the middle: light falls off to the rim.
				if (colour_) {
					float shade = 0.62f + 0.38f * std::sqrt(inside) / r;
					lecColour_[k] = { static_cast<uint8_t>(c.colour.r * shade),
							  static_cast<uint8_t>(c.colour.g * shade),
							  static_cast<uint8_t>(c.colour.b * shade) };
				} else {
					lecReflectivity_[k] = c.reflectivity;
				}
			}
			lecAlpha_[k] = std::max(lecAlpha_[k], alpha);
		}
	}
}

} // namespace depthkey::sim
