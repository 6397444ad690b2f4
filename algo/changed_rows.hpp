// Where a picture changed: the first and the last row in which two
// same-size pictures differ. The board's picture comes 10 times a second and
// is mostly the one before with a stroke more; what samples it (the board
// picture prior) then does again only the rows that changed. Pure.
#pragma once

#include "algo/image.hpp"

namespace depthkey {

struct RowRange {
	int first = 1, last = 0; // first > last: no row
	bool empty() const { return first > last; }
};

// Rows first..last of `now` differ from `before` (the rows outside hold the
// same bytes); every row when the sizes differ; no row when all are equal.
RowRange changedRows(const RgbImage &before, const RgbImage &now);

} // namespace depthkey
