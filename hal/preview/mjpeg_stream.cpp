#include "hal/preview/mjpeg_stream.hpp"

#include <cstring>
#include <microhttpd.h>

namespace depthkey {

ssize_t readMjpegStream(void *cls, uint64_t, char *buf, size_t max)
{
	auto *s = static_cast<MjpegStream *>(cls);
	const size_t total = s->frame ? s->head.size() + s->frame->jpeg.size() + 2 : 0;
	if (!s->frame || s->offset >= total) {
		// The newest frame when the socket takes more: a slow client skips.
		auto next = s->encoder->waitNewer(s->stage, s->lastSequence, kMjpegStreamWait);
		if (!next)
			return s->encoder->running() ? 0 : MHD_CONTENT_READER_END_OF_STREAM;
		s->frame = std::move(next);
		s->lastSequence = s->frame->sequence;
		s->head = std::string("--") + kMjpegBoundary + "\r\nContent-Type: image/jpeg\r\nContent-Length: " +
			  std::to_string(s->frame->jpeg.size()) + "\r\nX-Timestamp: " +
			  std::to_string(s->frame->captureNs / 1000) + "\r\n\r\n";
		s->offset = 0;
	}
	const std::vector<uint8_t> &jpeg = s->frame->jpeg;
	size_t done = 0;
	while (done < max) {
		size_t at = s->offset;
		if (at < s->head.size()) {
			size_t n = std::min(max - done, s->head.size() - at);
			std::memcpy(buf + done, s->head.data() + at, n);
			done += n, s->offset += n;
		} else if (at < s->head.size() + jpeg.size()) {
			size_t from = at - s->head.size(), n = std::min(max - done, jpeg.size() - from);
			std::memcpy(buf + done, jpeg.data() + from, n);
			done += n, s->offset += n;
		} else if (at < s->head.size() + jpeg.size() + 2) {
			buf[done++] = "\r\n"[at - s->head.size() - jpeg.size()];
			s->offset++;
		} else {
			break;
		}
	}
	return static_cast<ssize_t>(done);
}

void freeMjpegStream(void *cls)
{
	auto *s = static_cast<MjpegStream *>(cls);
	s->encoder->unwatch(s->stage);
	(*s->streams)--;
	delete s;
}

} // namespace depthkey
