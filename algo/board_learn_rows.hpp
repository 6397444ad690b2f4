// The board model's learning (BoardModel::learn and learnDecided,
// algo/board_model.hpp), a row at a time (issue 28 section 2: at 1920x1080
// the two per-pixel loops were 47 M of a frame's 260 M instructions). A
// plain C reference (_C) and SSE2 and NEON rows (board_learn_rows_sse2.cpp,
// _neon.cpp) that give its bytes and sums exactly
// (tests/board_learn_rows_test.cpp). The SSE2 and NEON rows are built only
// where their instructions are: boardLearnRows() gives the C rows for a
// path elsewhere, so any path can be named anywhere.
//
// Learn row: for each pixel whose trimap byte is kTrimapBoard, if the model
// has seen it (a != 0) its colour and model RGB are summed (the light's
// gain), and BoardModel::update(model, colour). That is the teach row
// (algo/board_teach_rows.hpp) at unit gain, so the sums are its type, the
// colour in .predicted.
//
// learnDecided's row is two more: the alpha rows y - margin, y, y + margin
// ORed (alphaOr), then a select row that says, in trimap bytes for the
// learn row, which pixels are learned: kTrimapBoard where the trimap is
// neither board nor lecturer and the OR is 0 at x - margin, x and x + margin
// (no lecturer pixel among the 9), kTrimapLecturer elsewhere.
#pragma once

#include "algo/board_teach_rows.hpp"
#include "algo/image.hpp"
#include "algo/kernel_path.hpp"

#include <cstdint>

namespace depthkey {

void boardLearnRow_C(const Rgb8 *colour, const uint8_t *trimap, Rgba8 *model, int n, BoardTeachSums &sums);
void boardLearnRow_SSE2(const Rgb8 *colour, const uint8_t *trimap, Rgba8 *model, int n, BoardTeachSums &sums);
void boardLearnRow_NEON(const Rgb8 *colour, const uint8_t *trimap, Rgba8 *model, int n, BoardTeachSums &sums);

// out[x] = a[x] | b[x] | c[x].
void boardAlphaOrRow_C(const uint8_t *a, const uint8_t *b, const uint8_t *c, uint8_t *out, int n);
void boardAlphaOrRow_SSE2(const uint8_t *a, const uint8_t *b, const uint8_t *c, uint8_t *out, int n);
void boardAlphaOrRow_NEON(const uint8_t *a, const uint8_t *b, const uint8_t *c, uint8_t *out, int n);

// select[x] = kTrimapBoard where trimap[x] is neither kTrimapBoard nor
// kTrimapLecturer and near[x - margin], near[x], near[x + margin] are all
// 0, else kTrimapLecturer; x in [0, n). near must be readable from -margin
// to n + margin (0 where outside the image: out-of-image neighbours are
// ignored).
void boardDecidedSelectRow_C(const uint8_t *near, const uint8_t *trimap, int margin, uint8_t *select, int n);
void boardDecidedSelectRow_SSE2(const uint8_t *near, const uint8_t *trimap, int margin, uint8_t *select, int n);
void boardDecidedSelectRow_NEON(const uint8_t *near, const uint8_t *trimap, int margin, uint8_t *select, int n);

struct BoardLearnRows {
	void (*learn)(const Rgb8 *, const uint8_t *, Rgba8 *, int, BoardTeachSums &);
	void (*alphaOr)(const uint8_t *, const uint8_t *, const uint8_t *, uint8_t *, int);
	void (*decidedSelect)(const uint8_t *, const uint8_t *, int, uint8_t *, int);
};
// The rows for path (the C rows where the path has none of its own, or
// none on this architecture).
BoardLearnRows boardLearnRows(KernelPath path);

} // namespace depthkey
