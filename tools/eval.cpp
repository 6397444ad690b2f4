// depthkey-eval: scores a segmentation method against ground truth, on the
// simulated lecture or a recorded sequence with masks, as fast as it can.
//
//   depthkey-eval [--config FILE] (--sequence DIR | --sim SEED --frames N)
//                 [--method depth-only|pipeline] [--csv FILE] [--preview DIR]
//                 [--save-sequence DIR]
//
// Its last line is, for scripts:
//   summary method=pipeline frames=300 iou=0.973 bf=0.912 fnr=0.012 fpr=0.004 fps=850 bf_scaled=0.912 bf_scaled_px=2
// bf_scaled: boundary F at a tolerance of 2 px per 640 of width (bf_scaled_px).
// fps counts the segmentation alone (not rendering or reading PNGs).
#include "algo/latency_estimator.hpp"
#include "algo/pipeline.hpp"
#include "algo/pipeline_stages.hpp"
#include "algo/segmentation_metrics.hpp"
#include "algo/trimap_attribution.hpp"
#include "config/config_loader.hpp"
#include "wiring/pipeline_setup.hpp"
#include "hal/preview/snapshot_writer.hpp"
#include "config/board_calibration_file.hpp"
#include "hal/recording/sequence_reader.hpp"
#include "hal/recording/sequence_writer.hpp"
#include "hal/sim/board_display.hpp"
#include "hal/sim/sim_sequence.hpp"

#include <chrono>
#include <optional>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <deque>
#include <functional>
#include <memory>
#include <string>

using namespace depthkey;

namespace {

struct Options {
	std::string config, sequence, csv, preview, saveSequence;
	std::string method = "pipeline";
	long simSeed = -1;
	long frames = 0;
	long previewEvery = 0; // 0 = the four spread frames
};

void usage(FILE *out)
{
	std::fprintf(out, "usage: depthkey-eval [--config FILE] (--sequence DIR | --sim SEED --frames N)\n"
			  "                     [--method depth-only|pipeline] [--csv FILE] [--preview DIR]\n"
			  "                     [--preview-every N] [--save-sequence DIR]\n");
}

bool parseNumber(const char *text, long min, long &out)
{
	char *end = nullptr;
	errno = 0;
	long v = std::strtol(text, &end, 10);
	if (errno || !end || *end || end == text || v < min)
		return false;
	out = v;
	return true;
}

// 0 = parsed, else the exit status.
int parseOptions(int argc, char **argv, Options &o)
{
	for (int i = 1; i < argc; ++i) {
		std::string arg = argv[i];
		bool hasValue = i + 1 < argc;
		if (arg == "--help" || arg == "-h") {
			usage(stdout);
			return -1;
		} else if (arg == "--config" && hasValue) {
			o.config = argv[++i];
		} else if (arg == "--sequence" && hasValue) {
			o.sequence = argv[++i];
		} else if (arg == "--sim" && hasValue) {
			if (!parseNumber(argv[++i], 0, o.simSeed)) {
				std::fprintf(stderr, "depthkey-eval: --sim needs a seed >= 0, not '%s'\n", argv[i]);
				return 2;
			}
		} else if (arg == "--frames" && hasValue) {
			if (!parseNumber(argv[++i], 1, o.frames)) {
				std::fprintf(stderr, "depthkey-eval: --frames needs a count >= 1, not '%s'\n", argv[i]);
				return 2;
			}
		} else if (arg == "--method" && hasValue) {
			o.method = argv[++i];
			if (o.method != "depth-only" && o.method != "pipeline") {
				std::fprintf(stderr, "depthkey-eval: --method must be depth-only or pipeline, not '%s'\n",
					     o.method.c_str());
				return 2;
			}
		} else if (arg == "--csv" && hasValue) {
			o.csv = argv[++i];
		} else if (arg == "--preview" && hasValue) {
			o.preview = argv[++i];
		} else if (arg == "--preview-every" && hasValue) {
			if (!parseNumber(argv[++i], 1, o.previewEvery)) {
				std::fprintf(stderr, "depthkey-eval: --preview-every needs a whole number >= 1, not '%s'\n",
					     argv[i]);
				return 2;
			}
		} else if (arg == "--save-sequence" && hasValue) {
			o.saveSequence = argv[++i];
		} else {
			std::fprintf(stderr, "depthkey-eval: unknown or incomplete argument '%s'\n", arg.c_str());
			usage(stderr);
			return 2;
		}
	}
	if (o.sequence.empty() == (o.simSeed < 0)) {
		std::fprintf(stderr, "depthkey-eval: give either --sequence DIR or --sim SEED --frames N\n");
		return 2;
	}
	if (o.simSeed >= 0 && o.frames == 0) {
		std::fprintf(stderr, "depthkey-eval: --sim needs --frames N\n");
		return 2;
	}
	return 0;
}

// Where scored frames come from: the stream the daemon would receive, each
// colour frame with its truth, preceded by the depth frames that have
// arrived by then.
class FrameSource
{
public:
	using DepthHandler = std::function<void(const DepthFrame &)>;
	virtual ~FrameSource() = default;
	// 1 = a frame, 0 = the end, negative = error (printed).
	virtual int next(ColourFrame &colour, Gray8Image &truth, const DepthHandler &onDepth) = 0;
};

class SimSource : public FrameSource
{
public:
	explicit SimSource(const Settings &s)
	{
		sequence_.configure(s.sim, s.colour.width, s.colour.height, s.colour.fps, s.depth.fps);
	}
	int next(ColourFrame &colour, Gray8Image &truth, const DepthHandler &onDepth) override
	{
		sequence_.frame(n_++, colour, truth_, onDepth);
		truth = truth_.alpha;
		return 1;
	}

private:
	SimSequence sequence_;
	GroundTruth truth_;
	uint64_t n_ = 0;
};

class RecordedSource : public FrameSource
{
public:
	int open(const std::string &dir)
	{
		int ret = reader_.open(dir);
		if (ret < 0) {
			std::fprintf(stderr, "depthkey-eval: %s\n", reader_.describeError().c_str());
			return ret;
		}
		if (!reader_.hasMask() || reader_.depth().empty()) {
			std::fprintf(stderr, "depthkey-eval: %s: needs rgb, depth and mask (ground truth) to score\n",
				     dir.c_str());
			return -EINVAL;
		}
		return 0;
	}
	int next(ColourFrame &colour, Gray8Image &truth, const DepthHandler &onDepth) override
	{
		const auto &rgb = reader_.colour(), &dep = reader_.depth();
		if (i_ >= rgb.size())
			return 0;
		int ret = 0;
		for (; d_ < dep.size() && dep[d_].timestampNs <= rgb[i_].timestampNs && ret >= 0; ++d_)
			if ((ret = reader_.readDepth(d_, depth_)) >= 0 &&
			    (ret = sameSize(depthSize_, depth_.depthMm, dep[d_].file)) >= 0)
				onDepth(depth_);
		if (ret >= 0 && (ret = reader_.readColour(i_, colour)) >= 0 &&
		    (ret = sameSize(colourSize_, colour.rgb, rgb[i_].file)) >= 0 &&
		    (ret = reader_.readMask(i_, truth)) >= 0)
			ret = sameSize(colourSize_, truth, "the mask of " + rgb[i_].file);
		if (ret < 0) {
			if (ret != -EDOM)
				std::fprintf(stderr, "depthkey-eval: %s\n", reader_.describeError().c_str());
			return ret;
		}
		++i_;
		return 1;
	}

private:
	// Every frame of a stream, and every mask, must have the first frame's
	// size: a mis-sized one would be scored 0 (or keyed wrongly) unnoticed.
	template<typename Image>
	int sameSize(std::pair<int, int> &size, const Image &image, const std::string &what)
	{
		if (size.first == 0)
			size = { image.width(), image.height() };
		if (size == std::pair(image.width(), image.height()))
			return 0;
		std::fprintf(stderr, "depthkey-eval: %s: %s is %dx%d, but the sequence's frames are %dx%d\n",
			     reader_.dir().c_str(), what.c_str(), image.width(), image.height(), size.first,
			     size.second);
		return -EDOM;
	}
	std::pair<int, int> colourSize_{ 0, 0 }, depthSize_{ 0, 0 };
	SequenceReader reader_;
	DepthFrame depth_;
	size_t i_ = 0, d_ = 0;
};

// The method under test, timed alone.
class Method
{
public:
	Method(const Settings &settings, bool depthOnly) : settings_(settings), depthOnly_(depthOnly)
	{
		// The files the daemon would read, read the same way.
		PipelineFiles files = loadPipelineFiles(settings);
		if (!files.calibrationError.empty())
			std::fprintf(stderr, "depthkey-eval: calibration refused, mapping by plain scaling: %s\n",
				     files.calibrationError.c_str());
		if (!files.boardError.empty())
			std::fprintf(stderr, "depthkey-eval: board image unusable: %s\n", files.boardError.c_str());
		mapping_ = files.mapping;
		calibrated_ = files.calibrated;
		calibrationFileBoard_ = files.boardCalibration;
		configurePipeline(pipeline_, settings, mapping_, files.board);
	}

	// The simulated lecture's board picture (board.backend "sim"), as the
	// daemon's board source delivers it, with the board calibration the
	// daemon would use (board.homography_file, else the calibration file's
	// [board]): the board model is taught what the picture predicts
	// (algo/board_picture_prior.hpp). Without one, nothing (said once).
	void useSimBoard()
	{
		if (settings_.board.backend != "sim")
			return;
		BoardCalibrationResult board;
		if (!settings_.board.homographyFile.empty()) {
			board = loadBoardCalibration(settings_.board.homographyFile);
		} else if (calibrationFileBoard_) {
			board.calibration = *calibrationFileBoard_;
		} else {
			std::fprintf(stderr, "depthkey-eval: no board calibration (board.homography_file is empty and the "
					     "calibration file has no [board]): the board model learns without the board's picture\n");
			return;
		}
		if (!board.ok()) {
			std::fprintf(stderr, "depthkey-eval: board calibration refused: %s\n",
				     board.errors.front().toString().c_str());
			return;
		}
		display_.configure(settings_.sim, settings_.board.width);
		const BoardCalibration &c = board.calibration;
		if (c.colourWidth != settings_.colour.width || c.colourHeight != settings_.colour.height ||
		    c.boardWidth != display_.width() || c.boardHeight != display_.height()) {
			std::fprintf(stderr, "depthkey-eval: board calibration for colour %dx%d and board %dx%d, "
					     "but the simulator gives %dx%d and %dx%d\n", c.colourWidth, c.colourHeight,
				     c.boardWidth, c.boardHeight, settings_.colour.width, settings_.colour.height,
				     display_.width(), display_.height());
			return;
		}
		pipeline_.setBoardGeometry(c.colourToBoard, c.lens(), c.boardWidth, c.boardHeight);
		simBoard_ = true;
	}

	// depth == nullptr: nothing paired, the daemon publishes the colour
	// picture unkeyed (everything lecturer) and so is it scored.
	const Gray8Image &run(const ColourFrame &colour, const FramePairer::Bracket &bracket)
	{
		const DepthFrame *depth = bracket.before ? bracket.before : bracket.after;
		if (simBoard_) { // the board source's work in the daemon: not timed
			// Its latest picture, delivered board.fps times a second:
			// up to one board period older than the colour frame.
			const double fps = settings_.board.fps;
			const int64_t tick = int64_t(std::floor(double(colour.timestampNs) / 1e9 * fps));
			if (tick != boardTick_) {
				display_.render(double(tick) / fps, picture_);
				pipeline_.setBoardPicture(&picture_);
				boardTick_ = tick;
			}
		}
		auto start = std::chrono::steady_clock::now();
		const Gray8Image *alpha;
		if (!depth) {
			pipeline_.passThrough(colour, output_);
			alpha = &output_.alpha;
		} else if (depthOnly_) {
			// The paper's baseline (Figure 7): depth mapped into the colour
			// image (the calibration's mapping, plain scaling without one),
			// lecturer where it lies in [near_mm, far_mm].
			const int w = colour.rgb.width(), h = colour.rgb.height();
			mapDepthToColour(depth->depthMm, mapping_, w, h, mapped_);
			alpha_.resize(w, h);
			const unsigned nearMm = static_cast<unsigned>(settings_.segmentation.nearMm);
			const unsigned span = static_cast<unsigned>(settings_.segmentation.farMm) - nearMm;
			for (size_t i = 0; i < mapped_.size(); ++i)
				alpha_.data()[i] = (mapped_.data()[i] - nearMm <= span) ? 255 : 0;
			alpha = &alpha_;
		} else {
			pipeline_.process(colour, bracket, output_);
			alpha = &output_.alpha;
		}
		seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
		return *alpha;
	}

	// Where the pipeline's wrong pixels lie in its trimap (a wrong seed is
	// depth's fault, a wrong band pixel SIOX's), and the bound of the seeds.
	void attribute(const Gray8Image &alpha, const Gray8Image &truth, SegmentationScorer &scorer)
	{
		if (depthOnly_)
			return;
		attribution_.add(alpha, truth, pipeline_.trimap(), scorer);
		// The alpha's error against the truth's fractional coverage, over
		// the frame and inside the band (superset minus core).
		const Gray8Image &trimap = pipeline_.trimap();
		if (trimap.size() != alpha.size() || truth.size() != alpha.size())
			return;
		for (size_t i = 0; i < alpha.size(); ++i) {
			const unsigned e = unsigned(std::abs(int(alpha.data()[i]) - int(truth.data()[i])));
			alphaError_ += e;
			const uint8_t t = trimap.data()[i];
			if (t != kTrimapBoard && t != kTrimapLecturer) {
				bandAlphaError_ += e;
				bandPixels_++;
			}
		}
		alphaPixels_ += alpha.size();
	}
	void printAlphaError() const
	{
		if (alphaPixels_)
			std::printf("  alpha mean absolute error (of 255): whole frame %.2f, band %.2f\n",
				    double(alphaError_) / double(alphaPixels_),
				    bandPixels_ ? double(bandAlphaError_) / double(bandPixels_) : 0.0);
	}
	void printAttribution() const
	{
		const TrimapAttribution &a = attribution_;
		using R = TrimapAttribution::Region;
		const uint64_t all = a.pixels(R::SurelyLecturer) + a.pixels(R::Band) + a.pixels(R::SurelyBoard);
		if (depthOnly_ || !all)
			return;
		static const char *const names[] = { "surely lecturer", "band (SIOX)", "surely board" };
		std::printf("  wrong pixels:");
		for (int k = 0; k < R::Regions; ++k) {
			const R r = R(k);
			std::printf(" %s %.4f of the image (%.3f of its pixels)%s", names[k], double(a.wrong(r)) / double(all),
				    a.pixels(r) ? double(a.wrong(r)) / double(a.pixels(r)) : 0.0, k + 1 < R::Regions ? "," : "\n");
		}
		std::printf("  band: %.3f of its wrong pixels are board taken for lecturer\n",
			    a.wrong(R::Band) ? double(a.bandTaken()) / double(a.wrong(R::Band)) : 0.0);
		SegmentationScore o = a.bound();
		std::printf("  bound of the depth seeds (every band pixel right): IoU %.3f  boundary F %.3f\n", o.iou,
			    o.boundaryF);
	}

	void stages(const ColourFrame &colour, const DepthFrame &depth, const Gray8Image &truth, StageImages &out)
	{
		if (depthOnly_) {
			out.add("colour", colour.rgb);
			out.addDepth("depth", depth.depthMm);
			out.addDepth("depth-mapped", mapped_);
			out.add("segmentation", StageKind::Mask, alpha_);
		} else {
			collectPipelineStages(colour, depth, pipeline_, output_, mapping_, out);
		}
		out.add("truth", StageKind::Mask, truth);
	}

	double seconds() const { return seconds_; }
	bool calibrated() const { return calibrated_; }

private:
	Settings settings_;
	bool depthOnly_;
	MappingModel mapping_;
	bool calibrated_ = false;
	Pipeline pipeline_;
	std::optional<BoardCalibration> calibrationFileBoard_;
	SimBoardDisplay display_;
	RgbImage picture_;
	bool simBoard_ = false;
	int64_t boardTick_ = -1;
	PipelineOutput output_;
	Gray16Image mapped_;
	Gray8Image alpha_;
	double seconds_ = 0;
	TrimapAttribution attribution_;
	uint64_t alphaError_ = 0, bandAlphaError_ = 0, alphaPixels_ = 0, bandPixels_ = 0;
};

// Four frames spread over the run (at 1/8, 3/8, 5/8, 7/8 of it), or of an
// open-ended sequence frames 50, 150, 250, 350.
bool isPreviewFrame(long frame, long frames)
{
	for (long k = 1; k < 8; k += 2)
		if (frames > 0 ? frame == k * frames / 8 : frame == (k / 2) * 100 + 50)
			return true;
	return false;
}

} // namespace

int main(int argc, char **argv)
{
	Options o;
	if (int ret = parseOptions(argc, argv, o))
		return ret < 0 ? 0 : ret;

	std::string configPath = o.config.empty() ? findDefaultConfig() : o.config;
	ConfigResult config = loadConfig(configPath);
	if (!config.ok()) {
		for (const ConfigError &e : config.errors)
			std::fprintf(stderr, "%s\n", e.toString().c_str());
		return 1;
	}
	Settings settings = config.settings;

	std::unique_ptr<FrameSource> source;
	std::string what;
	if (o.simSeed >= 0) {
		settings.sim.seed = static_cast<uint64_t>(o.simSeed);
		source = std::make_unique<SimSource>(settings);
		what = "sim seed " + std::to_string(o.simSeed);
	} else {
		auto recorded = std::make_unique<RecordedSource>();
		if (recorded->open(o.sequence) < 0)
			return 1;
		source = std::move(recorded);
		what = o.sequence;
	}

	std::FILE *csv = nullptr;
	if (!o.csv.empty()) {
		csv = std::fopen(o.csv.c_str(), "w");
		if (!csv) {
			std::fprintf(stderr, "depthkey-eval: %s: cannot write: %s\n", o.csv.c_str(), std::strerror(errno));
			return 1;
		}
		std::fprintf(csv, "frame,colour_timestamp_ns,depth_timestamp_ns,iou,bf,boundary_precision,"
				  "boundary_recall,fnr,fpr\n");
	}
	SequenceWriter saver(settings.daemon.recordCompression); // the recorder's level, from the config
	if (!o.saveSequence.empty() && saver.open(o.saveSequence) < 0) {
		std::fprintf(stderr, "depthkey-eval: %s\n", saver.describeError().c_str());
		return 1;
	}

	Method method(settings, o.method == "depth-only");
	if (o.simSeed >= 0)
		method.useSimBoard();
	SegmentationScorer scorer(2);
	ScoreAverage average;
	// Boundary F again at a tolerance scaled with the width (2 px per 640,
	// issue 28): 2 px at 1920x1080 is a third of what it is at 640x480.
	std::optional<SegmentationScorer> scaledScorer;
	int scaledTolerancePx = 2;
	ScoreAverage scaledAverage;
	// Paired as the daemon pairs: colour frames wait for depth from both
	// sides in time (pairing.delay_ms), "now" being the newest frame's time.
	PairingQueue queue;
	configurePairingQueue(queue, settings, settings.pairing.offsetAuto ? 0 : int64_t{ settings.pairing.offsetMs } * 1'000'000);
	std::deque<Gray8Image> heldTruths; // beside the queue's held colour frames, in order
	// The depth latency, measured as the daemon measures it (applied when
	// pairing.offset_ms is "auto"), re-estimated once a second of frames.
	LatencyEstimator latency;
	latency.configure(settings.segmentation.nearMm, settings.segmentation.farMm);
	LatencyEstimator::Estimate latencyEstimate;
	long colourSeen = 0;
	ColourFrame colour;
	Gray8Image truth;
	bool depthSeen = false;
	int saveError = 0;
	auto onDepth = [&](const DepthFrame &depth) {
		queue.addDepth(depth);
		latency.addDepth(depth, depth.timestampNs);
		depthSeen = true;
		if (!o.saveSequence.empty() && saveError >= 0)
			saveError = saver.writeDepth(depth);
	};
	// Scores every held frame due at nowNs (makeRoom: and a full ring's
	// oldest, a frame is about to come); false on a write error.
	auto scoreDue = [&](uint64_t nowNs, bool makeRoom) {
		PairingQueue::Keying k;
		while ((o.frames == 0 || average.frames() < o.frames) && queue.next(nowNs, k, makeRoom)) {
			makeRoom = false;
			const ColourFrame &keyed = *k.colour;
			const Gray8Image &truthOf = heldTruths.front();
			const DepthFrame *depth = k.depth.before ? k.depth.before : k.depth.after;
			const Gray8Image &alpha = method.run(keyed, k.depth);
			SegmentationScore s = scorer.score(alpha, truthOf);
			if (!scaledScorer) {
				scaledTolerancePx = std::max(2, int((2 * keyed.rgb.width() + 320) / 640));
				scaledScorer.emplace(scaledTolerancePx);
			}
			scaledAverage.add(scaledTolerancePx == 2 ? s : scaledScorer->score(alpha, truthOf));
			if (depth)
				method.attribute(alpha, truthOf, scorer);
			long frame = average.frames();
			average.add(s);
			if (csv)
				std::fprintf(csv, "%ld,%llu,%llu,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f\n", frame,
					     static_cast<unsigned long long>(keyed.timestampNs),
					     static_cast<unsigned long long>(depth ? depth->timestampNs : 0), s.iou, s.boundaryF,
					     s.boundaryPrecision, s.boundaryRecall, s.fnr, s.fpr);
			if (!o.saveSequence.empty()) {
				int w = saveError;
				if (w >= 0)
					w = saver.writeColour(keyed);
				if (w >= 0)
					w = saver.writeMask(truthOf, keyed.timestampNs, keyed.sequence);
				if (w < 0) {
					std::fprintf(stderr, "depthkey-eval: %s\n", saver.describeError().c_str());
					return false;
				}
			}
			if (!o.preview.empty() && depth &&
			    (o.previewEvery ? frame % o.previewEvery == 0 : isPreviewFrame(frame, o.frames))) {
				StageImages stages;
				method.stages(keyed, *depth, truthOf, stages);
				char prefix[32];
				std::snprintf(prefix, sizeof(prefix), "frame%06ld-", frame);
				std::string error;
				if (writeStageImages(o.preview, prefix, stages, error) < 0) {
					std::fprintf(stderr, "depthkey-eval: %s\n", error.c_str());
					return false;
				}
			}
			queue.pop();
			heldTruths.pop_front();
		}
		return true;
	};
	int ret = 0;
	while ((o.frames == 0 || average.frames() < o.frames) && (ret = source->next(colour, truth, onDepth)) > 0) {
		latency.addColour(colour.rgb, colour.timestampNs);
		if (++colourSeen % std::max(1, settings.colour.fps) == 0) {
			latencyEstimate = latency.estimate();
			if (latencyEstimate.valid && settings.pairing.offsetAuto)
				queue.setOffset(int64_t(std::lround(latencyEstimate.offsetMs * 1e6)));
		}
		if (!depthSeen)
			continue; // starting up: no depth camera has delivered yet
		if (!scoreDue(colour.timestampNs, true))
			return 1;
		queue.addColour(colour, colour.timestampNs);
		heldTruths.push_back(truth);
		if (!scoreDue(colour.timestampNs, false))
			return 1;
	}
	// A finished sequence: what is still held is keyed with what came.
	if (ret == 0 && !scoreDue(UINT64_MAX, false))
		return 1;
	if (csv)
		std::fclose(csv);
	if (ret < 0)
		return 1;

	SegmentationScore m = average.mean();
	long frames = average.frames();
	double fps = method.seconds() > 0 ? frames / method.seconds() : 0.0;
	std::printf("depthkey-eval: %s, method %s, %ld frames, mapping %s\n", what.c_str(), o.method.c_str(), frames,
		    method.calibrated() ? "from the calibration" : "by plain scaling (no calibration)");
	std::printf("  IoU %.3f  boundary F (2 px) %.3f (precision %.3f, recall %.3f); at %d px (2 px per 640) %.3f\n",
		    m.iou, m.boundaryF, m.boundaryPrecision, m.boundaryRecall, scaledTolerancePx,
		    scaledAverage.mean().boundaryF);
	std::printf("  lecturer pixels lost (FNR) %.3f  board pixels taken (FPR) %.3f  %.0f frames/s\n", m.fnr,
		    m.fpr, fps);
	method.printAttribution();
	method.printAlphaError();
	const PairingStats &ps = queue.pairer().stats();
	std::printf("  pairing: %llu paired, %llu colour frames without depth (scored unkeyed)\n",
		    static_cast<unsigned long long>(ps.paired), static_cast<unsigned long long>(ps.unpaired));
	if (latencyEstimate.valid)
		std::printf("  depth offset measured: %+.1f ms (correlation %.2f over %zu depth frames)%s%s\n",
			    latencyEstimate.offsetMs, latencyEstimate.correlation, latencyEstimate.depthFrames,
			    settings.pairing.offsetAuto ? ", applied" : ", not applied (offset_ms is set)",
			    o.simSeed >= 0 ? ("; the simulator's truth: " +
					      std::to_string(-int(std::lround(settings.sim.depthLatencyMs))) + " ms")
							 .c_str()
					   : "");
	else
		std::printf("  depth offset: not measured (too little motion seen in both cameras)\n");
	std::printf("summary method=%s frames=%ld iou=%.3f bf=%.3f fnr=%.3f fpr=%.3f fps=%.0f bf_scaled=%.3f "
		    "bf_scaled_px=%d\n",
		    o.method.c_str(), frames, m.iou, m.boundaryF, m.fnr, m.fpr, fps, scaledAverage.mean().boundaryF,
		    scaledTolerancePx);
	return 0;
}
