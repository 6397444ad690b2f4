#include "algo/no_signal_frame.hpp"

#include "algo/bitmap_font.hpp"

#include <algorithm>
#include <vector>

namespace depthkey {

namespace {

void fillRect(RgbImage &out, int x0, int y0, int x1, int y1, Rgb8 colour)
{
	x0 = std::max(x0, 0);
	y0 = std::max(y0, 0);
	x1 = std::min(x1, out.width());
	y1 = std::min(y1, out.height());
	for (int y = y0; y < y1; ++y)
		std::fill(out.row(y) + x0, out.row(y) + std::max(x0, x1), colour);
}

constexpr int kMargin = 8; // of the black box around the text

int lineWidth(const std::string &line, int zoom)
{
	int width = 0;
	for (char c : line)
		width += glyphOf(c).advance * zoom;
	return width;
}

// Words on lines no wider than maxWidth where it can (a word wider than
// that stands alone on its line, cut off by the picture's edge).
std::vector<std::string> wrapText(const std::string &text, int zoom, int maxWidth)
{
	std::vector<std::string> lines(1);
	size_t start = 0;
	while (start <= text.size()) {
		size_t end = text.find(' ', start);
		if (end == std::string::npos)
			end = text.size();
		const std::string word = text.substr(start, end - start);
		std::string joined = lines.back().empty() ? word : lines.back() + " " + word;
		if (lines.back().empty() || lineWidth(joined, zoom) <= maxWidth)
			lines.back() = joined;
		else
			lines.push_back(word);
		start = end + 1;
	}
	return lines;
}

void drawGlyph(RgbImage &out, const Glyph &g, int x, int top, int zoom)
{
	for (int row = 0; row < kGlyphHeight; ++row)
		for (int col = 0; col < kGlyphWidth; ++col)
			if (g.rows[row] & (0x8000u >> col))
				fillRect(out, x + col * zoom, top + row * zoom, x + (col + 1) * zoom, top + (row + 1) * zoom,
					 Rgb8{ 255, 255, 255 });
}

} // namespace

void renderNoSignalFrame(const std::string &text, RgbImage &out)
{
	const int w = out.width(), h = out.height();
	if (w <= 0 || h <= 0)
		return;
	// Seven dim colour bars, the look every technician recognises.
	static const Rgb8 bars[] = { { 96, 96, 96 }, { 96, 96, 0 }, { 0, 96, 96 }, { 0, 96, 0 },
				     { 96, 0, 96 }, { 96, 0, 0 }, { 0, 0, 96 } };
	for (int i = 0; i < 7; ++i)
		fillRect(out, i * w / 7, 0, (i + 1) * w / 7 + 1, h, bars[i]);
	// The glyphs enlarged to about the size OpenCV drew them at (its scale
	// w / 640, twice the font's), whole pixels so that they stay crisp.
	const int zoom = std::max(1, (2 * w + 320) / 640);
	const std::vector<std::string> lines = wrapText(text, zoom, w - 2 * kMargin);
	int textWidth = 0;
	for (const std::string &line : lines)
		textWidth = std::max(textWidth, lineWidth(line, zoom));
	const int lineHeight = kGlyphHeight * zoom, capHeight = (kGlyphBaseline - 2) * zoom;
	const int descent = (kGlyphHeight - kGlyphBaseline) * zoom;
	const int blockHeight = capHeight + descent + (int(lines.size()) - 1) * lineHeight;
	const int top = (h - blockHeight) / 2, left = (w - textWidth) / 2;
	fillRect(out, left - kMargin, top - kMargin, left + textWidth + kMargin, top + blockHeight + kMargin,
		 Rgb8{ 0, 0, 0 });
	for (size_t i = 0; i < lines.size(); ++i) {
		const int baseline = top + capHeight + int(i) * lineHeight;
		int x = (w - lineWidth(lines[i], zoom)) / 2;
		for (char c : lines[i]) {
			drawGlyph(out, glyphOf(c), x, baseline - kGlyphBaseline * zoom, zoom);
			x += glyphOf(c).advance * zoom;
		}
	}
}

} // namespace depthkey
