#include "hal/preview/preview_server.hpp"

#include "hal/preview/preview_page.hpp"
#include "hal/unique_fd.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <microhttpd.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace depthkey {

namespace {

constexpr const char *kBoundary = "boundarydonotcross"; // uStreamer's
constexpr auto kStreamWait = std::chrono::milliseconds(500);
constexpr auto kSnapshotWait = std::chrono::milliseconds(3000);
constexpr unsigned kIdleTimeoutS = 10;
constexpr int kExtraConnections = 4; // page, status and metrics beside the streams
constexpr size_t kMaxVerified = 16;
constexpr const char *kSecurityPolicy =
	"default-src 'self'; script-src 'self' 'unsafe-inline'; style-src 'unsafe-inline'; img-src 'self'";

// One MJPEG stream: the frame being sent and how far.
struct Stream {
	PreviewEncoder *encoder = nullptr;
	std::atomic<int> *streams = nullptr;
	PreviewStage stage = PreviewStage::Composite;
	uint64_t lastSequence = 0;
	std::shared_ptr<const EncodedFrame> frame;
	std::string head; // part headers before the JPEG
	size_t offset = 0; // into head + jpeg + "\r\n"
};

ssize_t readStream(void *cls, uint64_t, char *buf, size_t max)
{
	auto *s = static_cast<Stream *>(cls);
	const size_t total = s->frame ? s->head.size() + s->frame->jpeg.size() + 2 : 0;
	if (!s->frame || s->offset >= total) {
		// The newest frame when the socket takes more: a slow client skips.
		auto next = s->encoder->waitNewer(s->stage, s->lastSequence, kStreamWait);
		if (!next)
			return s->encoder->running() ? 0 : MHD_CONTENT_READER_END_OF_STREAM;
		s->frame = std::move(next);
		s->lastSequence = s->frame->sequence;
		s->head = std::string("--") + kBoundary + "\r\nContent-Type: image/jpeg\r\nContent-Length: " +
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

void freeStream(void *cls)
{
	auto *s = static_cast<Stream *>(cls);
	s->encoder->unwatch(s->stage);
	(*s->streams)--;
	delete s;
}

MHD_Result queue(MHD_Connection *connection, unsigned status, const std::string &body, const char *type)
{
	MHD_Response *response =
		MHD_create_response_from_buffer(body.size(), const_cast<char *>(body.data()), MHD_RESPMEM_MUST_COPY);
	if (!response)
		return MHD_NO;
	MHD_add_response_header(response, "Content-Type", type);
	MHD_add_response_header(response, "Cache-Control", "no-store");
	MHD_add_response_header(response, "X-Content-Type-Options", "nosniff");
	MHD_Result ret = MHD_queue_response(connection, status, response);
	MHD_destroy_response(response);
	return ret;
}

MHD_Result queueText(MHD_Connection *connection, unsigned status, const std::string &text)
{
	return queue(connection, status, text + "\n", "text/plain; charset=utf-8");
}

MHD_Result onRequest(void *cls, MHD_Connection *connection, const char *url, const char *method,
		     const char *, const char *, size_t *uploadSize, void **state)
{
	static int marker;
	if (*state == nullptr) { // headers only: answer on the next call
		*state = &marker;
		return MHD_YES;
	}
	if (*uploadSize != 0) // no request bodies here
		return MHD_NO;
	return static_cast<PreviewServer *>(cls)->handle(connection, url, method) ? MHD_YES : MHD_NO;
}

// Strips prefix and suffix from url into name; false when it does not fit.
bool stageUrl(std::string_view url, std::string_view prefix, std::string_view suffix, PreviewStage &stage)
{
	if (url.size() <= prefix.size() + suffix.size() || url.substr(0, prefix.size()) != prefix ||
	    url.substr(url.size() - suffix.size()) != suffix)
		return false;
	return previewStageFromName(url.substr(prefix.size(), url.size() - prefix.size() - suffix.size()), stage);
}

// The listening socket is ours, so that a bind failure has its own errno.
int listenOn(const ListenAddress &address, UniqueFd &fd, std::string &error)
{
	sockaddr_storage storage{};
	socklen_t length;
	if (address.ipv6) {
		auto *a = reinterpret_cast<sockaddr_in6 *>(&storage);
		a->sin6_family = AF_INET6;
		a->sin6_port = htons(static_cast<uint16_t>(address.port));
		inet_pton(AF_INET6, address.ip.c_str(), &a->sin6_addr);
		length = sizeof(*a);
	} else {
		auto *a = reinterpret_cast<sockaddr_in *>(&storage);
		a->sin_family = AF_INET;
		a->sin_port = htons(static_cast<uint16_t>(address.port));
		inet_pton(AF_INET, address.ip.c_str(), &a->sin_addr);
		length = sizeof(*a);
	}
	const std::string where = (address.ipv6 ? "[" + address.ip + "]" : address.ip) + ":" +
				  std::to_string(address.port);
	fd = UniqueFd(socket(storage.ss_family, SOCK_STREAM | SOCK_CLOEXEC, 0));
	int one = 1;
	const char *step = nullptr;
	if (!fd.isValid())
		step = "socket";
	else if (setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one)) < 0)
		step = "SO_REUSEADDR";
	else if (address.ipv6 && setsockopt(fd.get(), IPPROTO_IPV6, IPV6_V6ONLY, &one, sizeof(one)) < 0)
		step = "IPV6_V6ONLY";
	else if (bind(fd.get(), reinterpret_cast<sockaddr *>(&storage), length) < 0)
		step = "bind";
	else if (listen(fd.get(), 16) < 0)
		step = "listen";
	if (!step)
		return 0;
	int ret = -errno;
	error = "cannot listen on " + where + ": " + step + ": " + std::strerror(errno);
	fd.reset();
	return ret;
}

int boundPort(int fd)
{
	sockaddr_storage storage{};
	socklen_t length = sizeof(storage);
	if (getsockname(fd, reinterpret_cast<sockaddr *>(&storage), &length) < 0)
		return 0;
	if (storage.ss_family == AF_INET6)
		return ntohs(reinterpret_cast<sockaddr_in6 *>(&storage)->sin6_port);
	return ntohs(reinterpret_cast<sockaddr_in *>(&storage)->sin_port);
}

} // namespace

int PreviewServer::start(const PreviewServerOptions &options, PreviewEncoder &encoder, std::string &error)
{
	stop();
	needAuth_ = !options.passwordFile.empty();
	if (!options.address.loopback && !needAuth_) {
		error = "'" + options.address.ip + "' is reachable from the network: a password_file is required";
		return -EPERM;
	}
	if (needAuth_) {
		int ret = passwords_.load(options.passwordFile, error);
		if (ret < 0)
			return ret;
	}
	{
		std::lock_guard lock(authMutex_);
		verified_.clear();
	}
	UniqueFd fd;
	int ret = listenOn(options.address, fd, error);
	if (ret < 0)
		return ret;
	encoder_ = &encoder;
	maxClients_ = options.maxClients;
	const unsigned flags = MHD_USE_THREAD_PER_CONNECTION | MHD_USE_INTERNAL_POLLING_THREAD |
			       (options.address.ipv6 ? MHD_USE_IPv6 : 0);
	daemon_ = MHD_start_daemon(flags, 0, nullptr, nullptr, &onRequest, this, MHD_OPTION_LISTEN_SOCKET, fd.get(),
				   MHD_OPTION_CONNECTION_LIMIT,
				   static_cast<unsigned>(options.maxClients + kExtraConnections),
				   MHD_OPTION_CONNECTION_TIMEOUT, kIdleTimeoutS, MHD_OPTION_END);
	if (!daemon_) {
		ret = errno ? -errno : -EIO;
		error = "libmicrohttpd did not start";
		return ret; // fd closes here
	}
	port_ = boundPort(fd.get());
	fd.release(); // MHD owns it now: MHD_stop_daemon closes it
	return 0;
}

void PreviewServer::stop()
{
	if (!daemon_)
		return;
	// Closes the listening socket too (MHD owns it now); waits for the
	// connection threads, each back within kStreamWait.
	MHD_stop_daemon(daemon_);
	daemon_ = nullptr;
}

void PreviewServer::setStatus(const PreviewStatus &status)
{
	std::lock_guard lock(statusMutex_);
	status_ = status;
}

PreviewStatus PreviewServer::status()
{
	PreviewStatus s;
	{
		std::lock_guard lock(statusMutex_);
		s = status_;
	}
	PreviewEncoderStats e = encoder_->stats();
	s.previewClients = streams_.load();
	s.previewEncoded = e.encoded;
	s.previewSkipped = e.skipped;
	s.previewEncodeMs = e.encoded ? e.encodeNs / 1e6 / e.encoded : 0;
	return s;
}

bool PreviewServer::authorised(MHD_Connection *connection)
{
	if (!needAuth_)
		return true;
	char *password = nullptr;
	char *user = MHD_basic_auth_get_username_password(connection, &password);
	bool ok = false;
	if (user && password) {
		std::string key = std::string(user) + '\0' + password;
		{
			std::lock_guard lock(authMutex_);
			ok = verified_.count(key) > 0;
		}
		if (!ok && passwords_.verify(user, password)) {
			ok = true;
			std::lock_guard lock(authMutex_);
			if (verified_.size() >= kMaxVerified)
				verified_.clear();
			verified_.insert(std::move(key));
		}
	}
	if (user)
		MHD_free(user);
	if (password)
		MHD_free(password);
	return ok;
}

int PreviewServer::handle(MHD_Connection *connection, const char *urlText, const char *method)
{
	if (!authorised(connection)) {
		const std::string body = "authentication required\n";
		MHD_Response *response = MHD_create_response_from_buffer(
			body.size(), const_cast<char *>(body.data()), MHD_RESPMEM_MUST_COPY);
		MHD_Result ret = MHD_queue_basic_auth_fail_response(connection, "depthkey preview", response);
		MHD_destroy_response(response);
		return ret == MHD_YES;
	}
	if (std::strcmp(method, "GET") != 0 && std::strcmp(method, "HEAD") != 0)
		return queueText(connection, MHD_HTTP_METHOD_NOT_ALLOWED, "only GET") == MHD_YES;

	const std::string_view url = urlText;
	PreviewStage stage;
	if (url == "/" || url == "/index.html") {
		MHD_Response *response = MHD_create_response_from_buffer(
			previewPageHtml().size(), const_cast<char *>(previewPageHtml().data()), MHD_RESPMEM_PERSISTENT);
		MHD_add_response_header(response, "Content-Type", "text/html; charset=utf-8");
		MHD_add_response_header(response, "Content-Security-Policy", kSecurityPolicy);
		MHD_add_response_header(response, "Cache-Control", "no-store");
		MHD_Result ret = MHD_queue_response(connection, MHD_HTTP_OK, response);
		MHD_destroy_response(response);
		return ret == MHD_YES;
	}
	if (url == "/status.json")
		return queue(connection, MHD_HTTP_OK, previewStatusJson(status()), "application/json") == MHD_YES;
	if (url == "/metrics")
		return queue(connection, MHD_HTTP_OK, previewStatusMetrics(status()),
			     "text/plain; version=0.0.4; charset=utf-8") == MHD_YES;
	if (stageUrl(url, "/snapshot/", ".jpg", stage)) {
		encoder_->watch(stage);
		auto current = encoder_->waitNewer(stage, 0, std::chrono::milliseconds(0));
		auto frame = encoder_->waitNewer(stage, current ? current->sequence : 0, kSnapshotWait);
		encoder_->unwatch(stage);
		if (!frame)
			return queueText(connection, MHD_HTTP_SERVICE_UNAVAILABLE,
					 "no " + std::string(previewStageName(stage)) + " frame within 3 s") == MHD_YES;
		return queue(connection, MHD_HTTP_OK,
			     std::string(frame->jpeg.begin(), frame->jpeg.end()), "image/jpeg") == MHD_YES;
	}
	if (stageUrl(url, "/stream/", ".mjpg", stage)) {
		if (++streams_ > maxClients_) {
			streams_--;
			return queueText(connection, MHD_HTTP_SERVICE_UNAVAILABLE,
					 "too many preview streams (preview.max_clients = " +
						 std::to_string(maxClients_) + ")") == MHD_YES;
		}
		encoder_->watch(stage);
		auto *s = new Stream;
		s->encoder = encoder_;
		s->streams = &streams_;
		s->stage = stage;
		MHD_Response *response =
			MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 64 * 1024, &readStream, s, &freeStream);
		if (!response) {
			freeStream(s);
			return false;
		}
		const std::string type = std::string("multipart/x-mixed-replace;boundary=") + kBoundary;
		MHD_add_response_header(response, "Content-Type", type.c_str());
		MHD_add_response_header(response, "Cache-Control", "no-store, no-cache, must-revalidate, max-age=0");
		MHD_add_response_header(response, "Pragma", "no-cache");
		MHD_Result ret = MHD_queue_response(connection, MHD_HTTP_OK, response);
		MHD_destroy_response(response);
		return ret == MHD_YES;
	}
	return queueText(connection, MHD_HTTP_NOT_FOUND,
			 "no such page; try /, /stream/STAGE.mjpg, /snapshot/STAGE.jpg, /status.json, /metrics "
			 "(STAGE: colour, depth, seeds, alpha, composite)") == MHD_YES;
}

} // namespace depthkey
