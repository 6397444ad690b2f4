#include "tools/calibrate_print/print_command.hpp"

#include "algo/printed_pattern.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>

namespace depthkey {

namespace {

constexpr double kPointsPerMm = 72.0 / 25.4;

struct PrintOptions {
	std::string file;
	std::string paper = "a1"; // the default plan reaches 2.5 m: man depthkey-calibrate
	GridSize grid;
};

int parse(int argc, char **argv, PrintOptions &o)
{
	for (int i = 1; i < argc; i++) {
		std::string a = argv[i];
		const char *v = i + 1 < argc ? argv[i + 1] : nullptr;
		bool ok = v != nullptr;
		if (a == "-h" || a == "--help") {
			std::printf("usage (depthkey-calibrate --help has every form):\n");
			printPatternUsage(stdout);
			std::exit(0);
		} else if (a == "--print-pattern" && ok)
			o.file = v;
		else if (a == "--paper" && ok)
			ok = findPaperSize(o.paper = v) != nullptr;
		else if (a == "--grid" && ok)
			ok = std::sscanf(v, "%dx%d", &o.grid.cols, &o.grid.rows) == 2 && o.grid.cols >= 5 &&
			     o.grid.rows >= 5 && o.grid.cols != o.grid.rows && o.grid.cols * o.grid.rows <= 400;
		else
			ok = false;
		if (!ok) {
			std::fprintf(stderr, "depthkey-calibrate: bad or unknown option with --print-pattern: %s%s%s\n",
				     a.c_str(), v ? " " : "", v ? v : "");
			std::fprintf(stderr, "usage:\n");
			printPatternUsage(stderr);
			return 2;
		}
		i++;
	}
	return 0;
}

bool endsWith(const std::string &s, const char *suffix)
{
	size_t n = std::strlen(suffix);
	return s.size() >= n && strcasecmp(s.c_str() + s.size() - n, suffix) == 0;
}

// cairo writes through this, so that a full disk or a bad folder is an
// errno with the file named, not only cairo's "error while writing".
struct Sink {
	FILE *file = nullptr;
	int error = 0;
};

cairo_status_t writeTo(void *closure, const unsigned char *data, unsigned int length)
{
	Sink *sink = static_cast<Sink *>(closure);
	if (std::fwrite(data, 1, length, sink->file) != length) {
		sink->error = errno ? errno : EIO;
		return CAIRO_STATUS_WRITE_ERROR;
	}
	return CAIRO_STATUS_SUCCESS;
}

void draw(cairo_t *cr, const PrintedPattern &p)
{
	cairo_set_source_rgb(cr, 1, 1, 1);
	cairo_paint(cr);
	cairo_set_source_rgb(cr, 0, 0, 0);
	for (int row = 0; row < p.grid.rows; row++)
		for (int col = 0; col < p.grid.cols; col++) {
			cairo_new_sub_path(cr);
			cairo_arc(cr, p.centreXMm(col), p.centreYMm(row), p.diameterMm / 2, 0, 2 * M_PI);
		}
	cairo_fill(cr);

	char text[256];
	std::snprintf(text, sizeof(text),
		      "depthkey depth calibration pattern, %dx%d circles: spacing %.0f mm centre to centre, "
		      "diameter %.1f mm, %s. Print at 100 %% (actual size); check: %d spacings = %.0f mm.",
		      p.grid.cols, p.grid.rows, p.spacingMm, p.diameterMm, p.paper.name, p.grid.cols - 1,
		      (p.grid.cols - 1) * p.spacingMm);
	cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
	cairo_set_font_size(cr, 3.5); // mm: about 10 pt
	cairo_text_extents_t extents;
	cairo_text_extents(cr, text, &extents);
	double size = std::min(3.5, 3.5 * (p.paper.widthMm - 2 * kPrinterBorderMm) / extents.x_advance);
	cairo_set_font_size(cr, size);
	cairo_text_extents(cr, text, &extents);
	cairo_move_to(cr, (p.paper.widthMm - extents.x_advance) / 2, p.textBaselineMm);
	cairo_show_text(cr, text);
}

// PDF in points, SVG in millimetres (its width and height attributes then
// say "mm"): either way the drawing is in mm.
int writePattern(const std::string &path, const PrintedPattern &p, std::string &error)
{
	bool svg = endsWith(path, ".svg");
	if (!svg && !endsWith(path, ".pdf")) {
		error = path + ": the file's name must end in .pdf or .svg (that is the format written)";
		return -EINVAL;
	}
	Sink sink;
	sink.file = std::fopen(path.c_str(), "wb");
	if (!sink.file) {
		int err = errno;
		error = path + ": " + std::strerror(err);
		return -err;
	}
	cairo_surface_t *surface;
	double scale = 1;
	if (svg) {
		surface = cairo_svg_surface_create_for_stream(writeTo, &sink, p.paper.widthMm, p.paper.heightMm);
		cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_MM);
	} else {
		surface = cairo_pdf_surface_create_for_stream(writeTo, &sink, p.paper.widthMm * kPointsPerMm,
							       p.paper.heightMm * kPointsPerMm);
		cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, "depthkey depth calibration pattern");
		scale = kPointsPerMm;
	}
	cairo_t *cr = cairo_create(surface);
	cairo_scale(cr, scale, scale);
	draw(cr, p);
	cairo_status_t status = cairo_status(cr);
	cairo_destroy(cr);
	cairo_surface_finish(surface);
	if (status == CAIRO_STATUS_SUCCESS)
		status = cairo_surface_status(surface);
	cairo_surface_destroy(surface);
	if (std::fclose(sink.file) != 0 && !sink.error)
		sink.error = errno;
	if (status != CAIRO_STATUS_SUCCESS || sink.error) {
		error = path + ": " + (sink.error ? std::strerror(sink.error) : cairo_status_to_string(status));
		::unlink(path.c_str());
		return -(sink.error ? sink.error : EIO);
	}
	return 0;
}

} // namespace

bool wantsPatternPrint(int argc, char **argv)
{
	for (int i = 1; i < argc; i++)
		if (std::strcmp(argv[i], "--print-pattern") == 0)
			return true;
	return false;
}

void printPatternUsage(FILE *out)
{
	std::fprintf(out, "       depthkey-calibrate --print-pattern FILE.pdf|FILE.svg [--paper %s] [--grid COLSxROWS]\n",
		     paperSizeNames().c_str());
}

int runPatternPrint(int argc, char **argv)
{
	PrintOptions o;
	if (int ret = parse(argc, argv, o))
		return ret;
	PrintedPattern pattern;
	if (layoutPrintedPattern(*findPaperSize(o.paper), o.grid, pattern) < 0) {
		std::fprintf(stderr, "depthkey-calibrate: a %dx%d grid does not fit %s with circles 10 mm apart\n",
			     o.grid.cols, o.grid.rows, o.paper.c_str());
		return 1;
	}
	std::string error;
	if (writePattern(o.file, pattern, error) < 0) {
		std::fprintf(stderr, "depthkey-calibrate: cannot write the pattern: %s\n", error.c_str());
		return 1;
	}
	std::printf("wrote the depth calibration pattern %s: %s landscape (%.0f x %.0f mm), %dx%d circles "
		    "%.0f mm apart, %.1f mm across; print at 100 %% (actual size) on matt paper and fix it "
		    "flat on a stiff board\n",
		    o.file.c_str(), pattern.paper.name, pattern.paper.widthMm, pattern.paper.heightMm, o.grid.cols,
		    o.grid.rows, pattern.spacingMm, pattern.diameterMm);
	return 0;
}

} // namespace depthkey
