#include "daemon/preview_feed.hpp"

#include "daemon/log.hpp"

#include "algo/composite.hpp"

#include <algorithm>
#include <cerrno>

namespace depthkey {

namespace {

// The page's JPEGs are taken at most this often per stage: enough to aim a
// camera by, at a fraction of the encoding cost of every frame.
constexpr int kPreviewMaxFps = 15;

} // namespace

int PreviewFeed::apply(const PreviewSettings &settings, std::string *portInUse)
{
	// The same settings: a server that runs re-reads its password file; one
	// that did not start (a bad password file, a port in use) tries again.
	if (applied_ && settings == settings_ && (server_.running() || settings.listen.empty())) {
		rereadPasswords();
		return 0;
	}
	stop();
	settings_ = settings;
	applied_ = true;
	if (settings.listen.empty()) {
		logger().clearError("preview", "preview server off (preview.listen = \"\")", { { "DEVICE", "preview" } });
		logger().info("preview server off (preview.listen = \"\")", { { "DEVICE", "preview" } });
		return 0;
	}
	PreviewServerOptions options;
	std::string error = parseListenAddress(settings.listen, options.address);
	options.passwordFile = settings.passwordFile;
	options.maxClients = settings.maxClients;
	int ret = error.empty() ? 0 : -EINVAL;
	if (ret == 0) {
		encoder_.start(settings.jpegQuality, kPreviewMaxFps);
		ret = server_.start(options, encoder_, error);
	}
	if (ret < 0) {
		encoder_.stop();
		if (ret == -EADDRINUSE && portInUse) {
			*portInUse = "preview.listen " + settings.listen +
				     ": the port is in use (another depthkeyd, or another program on it)";
			return ret;
		}
		logger().errorOnce("preview", "preview server not started: " + error,
				   { { "DEVICE", "preview" }, { "ERROR", errnoText(ret) } });
		return ret;
	}
	const ListenAddress &a = options.address;
	std::string url = "http://" + (a.ipv6 ? "[" + a.ip + "]" : a.ip) + ":" + std::to_string(server_.port()) + "/";
	const std::string text = "preview page at " + url + (options.passwordFile.empty() ? "" : " (basic authentication)");
	logger().clearError("preview", "preview server started", { { "DEVICE", "preview" } });
	logger().info(text, { { "DEVICE", "preview" }, { "PREVIEW_URL", url } });
	return 0;
}

// A reload that keeps [preview] as it was still re-reads the password file:
// the path is the same, the accounts in it may not be (issue 31).
void PreviewFeed::rereadPasswords()
{
	if (!server_.running() || settings_.passwordFile.empty())
		return;
	std::string error;
	if (int ret = server_.reloadPasswords(error); ret < 0) {
		logger().errorOnce("preview-passwords", "preview closed until the password file is fixed: " + error,
				   { { "DEVICE", "preview" }, { "ERROR", errnoText(ret) } });
		return;
	}
	logger().clearError("preview-passwords", "preview password file accepted again", { { "DEVICE", "preview" } });
	logger().info("preview password file read again: " + settings_.passwordFile, { { "DEVICE", "preview" } });
}

// The encoder first: its waiters (streams, snapshots) return at once, so
// the server's connection threads end without their timeouts.
void PreviewFeed::stop()
{
	encoder_.stop();
	server_.stop();
}

void PreviewFeed::offer(const ColourFrame *colour, const DepthFrame *depth, const Gray8Image *seeds,
			const PipelineOutput &output, const RecordedPictures &recorded, uint64_t captureNs,
			uint64_t nowNs)
{
	if (!encoder_.running())
		return;
	auto give = [&](PreviewStage stage, const StageImage &image) {
		encoder_.made(stage, nowNs);
		if (encoder_.wanted(stage, nowNs))
			encoder_.offer(stage, image, captureNs, nowNs);
	};
	if (colour && !colour->rgb.empty())
		give(PreviewStage::Colour, { "", StageKind::Colour, &colour->rgb });
	if (depth && !depth->depthMm.empty())
		give(PreviewStage::Depth, { "", StageKind::Depth, nullptr, &depth->depthMm });
	if (seeds && !seeds->empty())
		give(PreviewStage::Seeds, { "", StageKind::Seeds, nullptr, nullptr, seeds });
	if (!output.alpha.empty())
		give(PreviewStage::Alpha, { "", StageKind::Mask, nullptr, nullptr, &output.alpha });
	if (recorded.composite && !recorded.composite->empty())
		give(PreviewStage::Composite, { "", StageKind::Colour, recorded.composite });
	else if (recorded.compositeInSharedMemory)
		encoder_.made(PreviewStage::Composite, nowNs);
	if (recorded.board && !recorded.board->empty())
		give(PreviewStage::Board, { "", StageKind::Colour, recorded.board });
	const bool boardLayer = recorded.boardLayer && !recorded.boardLayer->empty();
	const bool cameraLayer = colour && colour->rgb.width() == output.alpha.width() &&
				 colour->rgb.height() == output.alpha.height() && !output.alpha.empty();
	const bool noSignalLayer = !colour && !output.alpha.empty();
	if (!(boardLayer || cameraLayer || noSignalLayer))
		return;
	encoder_.made(PreviewStage::Lecturer, nowNs);
	if (!encoder_.wanted(PreviewStage::Lecturer, nowNs))
		return;
	if (boardLayer) {
		encoder_.offer(PreviewStage::Lecturer, *recorded.boardLayer, captureNs, nowNs);
	} else if (cameraLayer) {
		lecturerLayer(colour->rgb, output.alpha, layer_);
		encoder_.offer(PreviewStage::Lecturer, layer_, captureNs, nowNs);
	} else {
		// NO SIGNAL: the shared memory's layer is transparent black.
		layer_.resize(output.alpha.width(), output.alpha.height());
		std::fill(layer_.data(), layer_.data() + layer_.size(), Rgba8{ 0, 0, 0, 0 });
		encoder_.offer(PreviewStage::Lecturer, layer_, captureNs, nowNs);
	}
}

void PreviewFeed::setStatus(const PreviewStatus &status)
{
	if (!server_.running())
		return;
	server_.setStatus(status);
	// A client the server had to refuse (libmicrohttpd missing or not
	// starting): its threads do not log, so the journal hears it here.
	if (std::string error = server_.takeError(); !error.empty())
		logger().errorOnce("preview", error, { { "DEVICE", "preview" } });
	else if (server_.serving())
		logger().clearError("preview", "preview server serving", { { "DEVICE", "preview" } });
}

} // namespace depthkey
