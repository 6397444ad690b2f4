// A borrowed image: rows of width pixels, strideBytes apart, in memory owned
// by someone else (a shared-memory ring slot, hal/shm_ring_writer.hpp), so
// that a frame can be made where it goes instead of in an Image copied there.
#pragma once

#include "algo/image.hpp"

#include <cstddef>
#include <cstdint>

namespace depthkey {

template<typename T>
struct ImageView {
	T *pixels = nullptr;
	int width = 0;
	int height = 0;
	size_t strideBytes = 0;

	T *row(int y) const
	{
		return reinterpret_cast<T *>(reinterpret_cast<uint8_t *>(pixels) + static_cast<size_t>(y) * strideBytes);
	}
};

template<typename T>
ImageView<T> viewOf(Image<T> &image)
{
	return { image.data(), image.width(), image.height(), static_cast<size_t>(image.width()) * sizeof(T) };
}

} // namespace depthkey
