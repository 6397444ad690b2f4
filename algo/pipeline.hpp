// The per-frame segmentation of the paper, stage by stage (one file each):
//   DepthSeeder   depth -> surely lecturer / undecided / surely board, at ToF
//                 resolution ([segmentation]);
//   SeedMapper    the seeds into the colour image through the calibration's
//                 mapping (DepthMapper, [mapping]);
//   ColourLearner lecturer and board colours -> SIOX signatures ([learning]);
//   SioxRefiner   SIOX on the undecided band, post-processing, soft alpha
//                 ([siox]);
//   composite     the lecturer over the board source ([composite]).
// Pure: no I/O, no clock. Buffers are allocated when sizes change, never per
// frame in steady state (tests/pipeline_allocation_test.cpp counts).
#pragma once

#include "algo/board_model.hpp"
#include "algo/board_picture_prior.hpp"
#include "algo/colour_learner.hpp"
#include "algo/composite.hpp"
#include "algo/depth_mapper.hpp"
#include "algo/depth_seeder.hpp"
#include "algo/frame_pairer.hpp"
#include "algo/frames.hpp"
#include "algo/fused_evidence.hpp"
#include "algo/guided_filter.hpp"
#include "algo/boundary_unmixing.hpp"
#include "algo/kernel_path.hpp"
#include "algo/mapping_model.hpp"
#include "algo/morphology.hpp"
#include "algo/pipeline_settings.hpp"
#include "algo/seed_mapper.hpp"
#include "algo/siox_classifier.hpp"
#include "algo/siox_refiner.hpp"
#include "settings/settings.hpp"

#include <array>

namespace depthkey {

struct PipelineOutput {
	Gray8Image alpha;     // 255 = lecturer
	RgbImage composite;   // lecturer over the board source
	// The lecturer layer (straight alpha) is not kept here: it is the colour
	// frame with this alpha, made where it goes (lecturerLayer(),
	// algo/composite.hpp; in the daemon straight into shared memory).
};

// What the daemon reports and the previews show.
struct PipelineStatus {
	bool learning = true;        // still collecting the first colours
	bool mappingFits = true;     // the calibration matches the frame sizes
	int derivations = 0;         // signature derivations so far
	size_t bandPixels = 0;       // undecided pixels SIOX decided in the last frame
	size_t lecturerCentroids = 0, boardCentroids = 0;
	bool boardPictureTaught = false; // the board's picture taught the board model this frame
};

class Pipeline
{
public:
	Pipeline();

	// Takes what may change on reload; cheap when unchanged. A new mapping
	// or new seeding restarts the colour learning.
	void configure(const PipelineSettings &settings, const MappingModel &mapping);
	// Whether process() and passThrough() make PipelineOutput::composite
	// (the default). Off, the composite is left empty (its memory freed)
	// and compositeInputs() says how to make it where it goes: the daemon
	// makes it in the recorder's shared memory unless somebody else (the
	// preview, a virtual webcam, a snapshot) reads it (issue 15: 0.9 MB at
	// 640x480).
	void setMakeComposite(bool make) { makeComposite_ = make; }
	// After process() (not passThrough(), whose composite is the colour
	// frame): the composite's parts, colour being the frame just keyed.
	CompositeInputs compositeInputs(const RgbImage &colour, const Gray8Image &alpha) const
	{
		return { &colour, &alpha, &board_, keyed_.roi, opacityQ8_, kernelPath_ };
	}
	// The board's picture for the camera-geometry composite (scaled to the
	// colour size, nearest neighbour); an empty image = board.colour.
	void setBoardImage(const RgbImage &board);
	// The board's own picture as the electronic board delivers it, and the
	// homography colour px -> its px (the board calibration): the board
	// model is then taught the board the picture predicts
	// (algo/board_picture_prior.hpp). setBoardGeometry once per H (an
	// allocation), setBoardPicture with each new picture (kept by pointer,
	// not copied; null = no picture).
	void setBoardGeometry(const Homography &colourToBoard, const RadialLens &lens, int boardWidth, int boardHeight);
	void clearBoardGeometry();
	// Call it again whenever the picture's pixels change in place: the
	// prior samples a picture once, not every frame.
	void setBoardPicture(const RgbImage *picture)
	{
		boardPicture_ = picture;
		picturePrior_.pictureChanged();
	}
	// The same picture, changed in place in its rows firstRow..lastRow only
	// (first > last: not at all): sampled again there only.
	void boardPictureRowsChanged(int firstRow, int lastRow) { picturePrior_.pictureRowsChanged(firstRow, lastRow); }
	const RgbImage *boardPicture() const { return boardPicture_; }
	// Whether the board's picture and its geometry are both set.
	bool hasBoardPicture() const { return boardPicture_ && boardWidth_ > 0; }
	// The row kernels to use (algo/kernel_path.hpp); the best by default.
	void setKernelPath(KernelPath path)
	{
		kernelPath_ = path;
		seeder_.setKernelPath(path);
		seedMapper_.setKernelPath(path);
		refiner_.setKernelPath(path);
		evidence_.setKernelPath(path);
		guided_.setKernelPath(path);
		unmixing_.setKernelPath(path);
		boardModel_.setKernelPath(path);
	}

	// Keys a colour frame with the depth frames captured just before and
	// just after it (either may be missing, not both: FramePairer::bracket).
	// A stale bracket (depth.staleNs > 0, no depth within pairing.max_skew_ms)
	// is keyed with its superset grown by staleMarginPx() (issue 29 point 4).
	void process(const ColourFrame &colour, const FramePairer::Bracket &depth, PipelineOutput &out);
	// With one depth frame (pairing.delay_ms = 0, tests).
	void process(const ColourFrame &colour, const DepthFrame &depth, PipelineOutput &out);

	// What is published when the depth camera is missing: the colour frame as
	// it is (lecturer layer opaque), since a plain picture beats a black one.
	void passThrough(const ColourFrame &colour, PipelineOutput &out);

	// How far the lecturer may have walked in gapNs, in colour pixels at
	// width: the superset of a stale frame is grown by this. A brisk walk
	// crosses the camera's view in kCrossingNs; capped at width / kMaxGrowthDivisor
	// (the dilation's cost grows with it, and beyond it depth says little).
	static constexpr int64_t kCrossingNs = 2'000'000'000;
	static constexpr int kMaxGrowthDivisor = 4;
	static int staleMarginPx(int width, int64_t gapNs);

	const PipelineStatus &status() const { return status_; }
	// Stage images of the last frame, for snapshots and previews.
	const Gray8Image &trimap() const { return keyed_.trimap; }
	// What depth says at each pixel of the last frame (128 neither, 255
	// lecturer, 0 board or outside the superset: DepthSeeder::evidence).
	const Gray8Image &depthEvidence() const { return keyed_.evidence; }
	// The seeds of the newest depth frame the last colour frame was keyed with.
	const DepthSeeds &seeds() const { return seeded_[newest_].seeds; }
	// Where the last frame's alpha may be non-zero (0 outside): what the
	// board-geometry composite (algo/board_compositor.hpp) warps.
	const Roi &roi() const { return keyed_.roi; }
	// SIOX's confidence (algo/siox_classifier.hpp) for every pixel of an
	// image, not only the band: shows which colours the signatures confuse.
	// For previews; allocates.
	void confidence(const RgbImage &colour, Gray8Image &out) const;

private:
	void teachBoardFromPicture(const RgbImage &colour);
	void ensureSizes(int colourWidth, int colourHeight, int depthWidth, int depthHeight);
	void renderBoard(int width, int height);
	void restartLearning();
	// One depth frame seeded and mapped, once (colour frames sharing it,
	// and the next colour frame keyed with it from the other side, reuse it).
	struct SeededDepth {
		DepthSeeds seeds;
		MappedSeeds mapped;
		uint64_t ns = 0, sequence = 0;
		bool valid = false;
		bool holds(const DepthFrame &d) const
		{
			return valid && d.timestampNs == ns && d.sequence == sequence && (ns != 0 || sequence != 0);
		}
	};
	// The seeds of depth, seeding it unless held; never evicts `keep`.
	const SeededDepth &seededFor(const DepthFrame &depth, const SeededDepth *keep);
	void compose(const RgbImage &colour, PipelineOutput &out) const;
	// A stale frame's superset: grown by marginPx, depth's say in it dropped.
	void growSuperset(int marginPx);
	// Keeps this frame's alpha and colour inside its ROI for the next
	// frame's temporal evidence.
	void rememberFrame(const RgbImage &colour, const Gray8Image &alpha);
	// The edge-aware alpha: the guided filter of the hard decision.
	void guideAlpha(const RgbImage &colour, Gray8Image &alpha);

	PipelineSettings settings_;
	MappingModel mapping_;
	int opacityQ8_ = 128;
	bool makeComposite_ = true;
	KernelPath kernelPath_ = bestKernelPath();

	QuantisedLab lab_;
	SioxClassifier classifier_;
	ColourLearner learner_;
	DepthMapper mapper_;
	DepthSeeder seeder_;
	SeedMapper seedMapper_;
	SioxRefiner refiner_;
	BoardModel boardModel_;
	BoardPicturePrior picturePrior_;
	const RgbImage *boardPicture_ = nullptr;
	Homography colourToBoard_;
	RadialLens boardLens_;
	int boardWidth_ = 0, boardHeight_ = 0;
	FusedEvidence evidence_;
	GuidedFilter guided_;
	BoundaryUnmixing unmixing_;
	Gray8Image matte_;               // the hard decision, the guided filter's input
	Gray8Image grown_;               // a stale frame's grown superset (growSuperset)
	MorphologyScratch morphology_;
	Gray8Image previousAlpha_;
	RgbImage previousColour_;
	Roi previousRoi_;
	bool havePrevious_ = false;

	std::array<SeededDepth, 2> seeded_;
	size_t newest_ = 0;              // seeded_ slot seeded last
	MappedSeeds keyed_;              // the trimap the colour frame is keyed with
	RgbImage boardSource_, board_;
	PipelineStatus status_;
	int colourWidth_ = 0, colourHeight_ = 0, depthWidth_ = 0, depthHeight_ = 0;
	bool mappingDirty_ = true;
	bool boardDirty_ = true;
};

} // namespace depthkey
