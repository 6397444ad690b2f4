// One client's multipart MJPEG stream (/stream/STAGE.mjpg), as uStreamer
// serves it: libmicrohttpd asks readMjpegStream() for more whenever the
// client's socket takes more, and it sends the newest JPEG of the stage then,
// so a slow client skips frames and nobody waits for it.
#pragma once

#include "hal/preview/preview_encoder.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <sys/types.h>

namespace depthkey {

inline constexpr const char *kMjpegBoundary = "boundarydonotcross"; // uStreamer's
// How long a stream waits for a frame before telling libmicrohttpd "nothing
// yet": also how soon its thread notices the server stopping.
inline constexpr auto kMjpegStreamWait = std::chrono::milliseconds(500);

// The frame being sent and how far. Owned by libmicrohttpd's response from
// its creation on: freeMjpegStream() deletes it.
struct MjpegStream {
	PreviewEncoder *encoder = nullptr;
	std::atomic<int> *streams = nullptr; // the server's count, taken down at the end
	PreviewStage stage = PreviewStage::Composite;
	uint64_t lastSequence = 0;
	std::shared_ptr<const EncodedFrame> frame;
	std::string head; // part headers before the JPEG
	size_t offset = 0; // into head + jpeg + "\r\n"
};

// libmicrohttpd's content reader callback and its free callback; cls is an
// MjpegStream.
ssize_t readMjpegStream(void *cls, uint64_t position, char *buf, size_t max);
void freeMjpegStream(void *cls);

} // namespace depthkey
