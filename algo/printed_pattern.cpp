#include "algo/printed_pattern.hpp"

#include <cerrno>
#include <cmath>

namespace depthkey {

namespace {

// ISO 216, landscape (the grid is wider than tall).
constexpr PaperSize kPapers[] = {
	{ "a4", 297, 210 },
	{ "a3", 420, 297 },
	{ "a2", 594, 420 },
	{ "a1", 841, 594 },
};

} // namespace

const PaperSize *findPaperSize(const std::string &name)
{
	for (const PaperSize &p : kPapers)
		if (name == p.name)
			return &p;
	return nullptr;
}

std::string paperSizeNames()
{
	std::string names;
	for (const PaperSize &p : kPapers)
		names += (names.empty() ? "" : "|") + std::string(p.name);
	return names;
}

int layoutPrintedPattern(const PaperSize &paper, GridSize grid, PrintedPattern &out)
{
	// Extent of the grid with its white surround, in spacings.
	double across = (grid.cols - 1) + kDiameterPerSpacing + 2 * kPaperPerSpacing;
	double down = (grid.rows - 1) + kDiameterPerSpacing + 2 * kPaperPerSpacing;
	double usableW = paper.widthMm - 2 * kPrinterBorderMm;
	double usableH = paper.heightMm - 2 * kPrinterBorderMm - kTextLineMm;
	double spacing = std::floor(std::min(usableW / across, usableH / down));
	if (spacing < 10)
		return -EINVAL;

	out.paper = paper;
	out.grid = grid;
	out.spacingMm = spacing;
	out.diameterMm = std::round(kDiameterPerSpacing * spacing * 10) / 10;
	double gridW = (grid.cols - 1) * spacing, gridH = (grid.rows - 1) * spacing;
	double blockH = gridH + (kDiameterPerSpacing + 2 * kPaperPerSpacing) * spacing + kTextLineMm;
	out.originXMm = (paper.widthMm - gridW) / 2;
	out.originYMm = (paper.heightMm - blockH) / 2 + (kDiameterPerSpacing / 2 + kPaperPerSpacing) * spacing;
	out.textBaselineMm = out.originYMm + gridH + (kDiameterPerSpacing / 2 + kPaperPerSpacing) * spacing + 0.6 * kTextLineMm;
	return 0;
}

} // namespace depthkey
