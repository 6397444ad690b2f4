// Plain images for the pipeline: owning, row-major, tightly packed (stride ==
// width). algo/ works on these and nothing else, so kernels never see device
// formats. Buffers are allocated once (resize) and reused frame after frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace depthkey {

struct Rgb8 {
	uint8_t r, g, b;
	bool operator==(const Rgb8 &) const = default;
};

struct Rgba8 {
	uint8_t r, g, b, a;
	bool operator==(const Rgba8 &) const = default;
};

template<typename T>
class Image
{
public:
	Image() = default;
	Image(int width, int height, T fill = T{})
		: width_(width), height_(height),
		  pixels_(static_cast<size_t>(width) * height, fill)
	{
	}

	// Reallocates only when the size grows, so a steady stream of equally
	// sized frames costs no allocation.
	void resize(int width, int height)
	{
		width_ = width;
		height_ = height;
		pixels_.resize(static_cast<size_t>(width) * height);
	}

	int width() const { return width_; }
	int height() const { return height_; }
	size_t size() const { return pixels_.size(); }
	bool empty() const { return pixels_.empty(); }

	T *data() { return pixels_.data(); }
	const T *data() const { return pixels_.data(); }
	T *row(int y) { return pixels_.data() + static_cast<size_t>(y) * width_; }
	const T *row(int y) const { return pixels_.data() + static_cast<size_t>(y) * width_; }
	T &at(int x, int y) { return row(y)[x]; }
	const T &at(int x, int y) const { return row(y)[x]; }

	bool operator==(const Image &) const = default;

private:
	int width_ = 0;
	int height_ = 0;
	std::vector<T> pixels_;
};

using RgbImage = Image<Rgb8>;
using RgbaImage = Image<Rgba8>;
using Gray8Image = Image<uint8_t>;
using Gray16Image = Image<uint16_t>;

} // namespace depthkey
