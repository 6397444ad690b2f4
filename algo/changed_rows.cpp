#include "algo/changed_rows.hpp"

#include <cstring>

namespace depthkey {

RowRange changedRows(const RgbImage &before, const RgbImage &now)
{
	const int h = now.height();
	if (before.width() != now.width() || before.height() != h)
		return { 0, h - 1 };
	const size_t bytes = size_t(now.width()) * sizeof(Rgb8);
	auto same = [&](int y) { return std::memcmp(before.row(y), now.row(y), bytes) == 0; };
	// From the top to the first difference, then from the bottom: an
	// unchanged picture is read once, a changed one at most once.
	int first = 0;
	while (first < h && same(first))
		first++;
	if (first == h)
		return {};
	int last = h - 1;
	while (last > first && same(last))
		last--;
	return { first, last };
}

} // namespace depthkey
