#include "hal/preview/preview_server.hpp"

#include "hal/preview/preview_page.hpp"
#include "hal/unique_fd.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <utility>
#include <microhttpd.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

namespace depthkey {

namespace {

constexpr const char *kBoundary = "boundarydonotcross"; // uStreamer's
constexpr auto kStreamWait = std::chrono::milliseconds(500);
constexpr auto kSnapshotWait = std::chrono::milliseconds(3000);
constexpr unsigned kIdleTimeoutS = 10;
constexpr int kListenBacklog = 16;
// Connections beyond the streams (the page, status, metrics, snapshots, and
// closed ones whose threads have not yet been reaped): libmicrohttpd closes
// any connection over its limit without a word. The connections waiting in
// the backlog when the library is loaded all arrive at once and finish at
// once, so the limit leaves room for a backlog of them (with 4, ten clients
// reconnecting together lost one reply in seven runs of the unit test).
constexpr int kExtraConnections = kListenBacklog;
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

MHD_Result queue(const MicroHttpd &mhd, MHD_Connection *connection, unsigned status, const std::string &body,
		 const char *type)
{
	MHD_Response *response =
		mhd.createResponseFromBuffer(body.size(), const_cast<char *>(body.data()), MHD_RESPMEM_MUST_COPY);
	if (!response)
		return MHD_NO;
	mhd.addResponseHeader(response, "Content-Type", type);
	mhd.addResponseHeader(response, "Cache-Control", "no-store");
	mhd.addResponseHeader(response, "X-Content-Type-Options", "nosniff");
	MHD_Result ret = mhd.queueResponse(connection, status, response);
	mhd.destroyResponse(response);
	return ret;
}

MHD_Result queueText(const MicroHttpd &mhd, MHD_Connection *connection, unsigned status, const std::string &text)
{
	return queue(mhd, connection, status, text + "\n", "text/plain; charset=utf-8");
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
	else if (listen(fd.get(), kListenBacklog) < 0)
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

// Answers the connection waiting on listenFd with 503 and why, then closes
// it: the server could not be started for it, and a client must not hang
// on a connection nobody will read.
void refuse(int listenFd, const std::string &why)
{
	UniqueFd client(accept4(listenFd, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK));
	if (!client.isValid())
		return;
	const std::string body = why + "\n";
	const std::string reply = "HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain; charset=utf-8\r\n"
				  "Connection: close\r\nContent-Length: " +
				  std::to_string(body.size()) + "\r\n\r\n" + body;
	if (send(client.get(), reply.data(), reply.size(), MSG_NOSIGNAL | MSG_DONTWAIT) < 0) {
		// the client left already: nothing to tell it
	}
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
	int ret = listenOn(options.address, listen_, error);
	if (ret < 0)
		return ret;
	wake_ = UniqueFd(eventfd(0, EFD_CLOEXEC));
	if (!wake_.isValid()) {
		ret = -errno;
		error = std::string("cannot create the preview's eventfd: ") + std::strerror(errno);
		listen_.reset();
		return ret;
	}
	encoder_ = &encoder;
	maxClients_ = options.maxClients;
	load_ = options.load ? options.load : &loadMicroHttpd;
	ipv6_ = options.address.ipv6;
	port_ = boundPort(listen_.get());
	doorman_ = std::thread(&PreviewServer::waitForFirstClient, this);
	return 0;
}

// Until the first client knocks only this thread (a poll() on the socket,
// a few kB of stack) stands for the server: libmicrohttpd and GnuTLS are
// loaded then, and the connection waiting in the backlog is its first.
void PreviewServer::waitForFirstClient()
{
	pollfd fds[2] = { { listen_.get(), POLLIN, 0 }, { wake_.get(), POLLIN, 0 } };
	for (;;) {
		if (poll(fds, 2, -1) < 0) {
			if (errno == EINTR)
				continue;
			noteError(std::string("preview server: poll: ") + std::strerror(errno));
			return;
		}
		if (fds[1].revents)
			return; // stop()
		if (!(fds[0].revents & (POLLIN | POLLERR | POLLHUP)))
			continue;
		std::string error;
		if (startServing(error) == 0)
			return;
		noteError("preview server not serving: " + error);
		refuse(listen_.get(), "preview unavailable: " + error);
		// A client that cannot even be accepted (no fds left) keeps the
		// socket readable: wait a little before trying again, awake for stop().
		if (poll(&fds[1], 1, 100) > 0)
			return;
	}
}

int PreviewServer::startServing(std::string &error)
{
	const MicroHttpd *mhd = load_(error);
	if (!mhd)
		return -ENOENT;
	mhd_ = mhd; // before the first request can reach handle()
	const unsigned flags =
		MHD_USE_THREAD_PER_CONNECTION | MHD_USE_INTERNAL_POLLING_THREAD | (ipv6_ ? MHD_USE_IPv6 : 0);
	MHD_Daemon *daemon = mhd->startDaemon(flags, 0, nullptr, nullptr, &onRequest, this, MHD_OPTION_LISTEN_SOCKET,
					      listen_.get(), MHD_OPTION_CONNECTION_LIMIT,
					      static_cast<unsigned>(maxClients_ + kExtraConnections),
					      MHD_OPTION_CONNECTION_TIMEOUT, kIdleTimeoutS, MHD_OPTION_END);
	if (!daemon) {
		int ret = errno ? -errno : -EIO;
		error = std::string(kMicroHttpdSoname) + " did not start" + (errno ? std::string(": ") + std::strerror(errno) : "");
		return ret;
	}
	listen_.release(); // libmicrohttpd owns it now: MHD_stop_daemon closes it
	daemon_ = daemon;
	return 0;
}

void PreviewServer::noteError(std::string error)
{
	std::lock_guard lock(errorMutex_);
	error_ = std::move(error);
}

std::string PreviewServer::takeError()
{
	std::lock_guard lock(errorMutex_);
	return std::exchange(error_, std::string());
}

void PreviewServer::stop()
{
	if (!doorman_.joinable())
		return;
	uint64_t one = 1;
	if (write(wake_.get(), &one, sizeof(one)) < 0) {
		// an eventfd write fails only when its counter is full: it is readable then anyway
	}
	doorman_.join();
	// Closes the listening socket too (libmicrohttpd owns it once serving);
	// waits for the connection threads, each back within kStreamWait.
	if (MHD_Daemon *daemon = daemon_.exchange(nullptr))
		mhd_->stopDaemon(daemon);
	listen_.reset();
	wake_.reset();
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
	char *user = mhd_->basicAuthGetUsernamePassword(connection, &password);
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
		mhd_->free(user);
	if (password)
		mhd_->free(password);
	return ok;
}

int PreviewServer::handle(MHD_Connection *connection, const char *urlText, const char *method)
{
	if (!authorised(connection)) {
		const std::string body = "authentication required\n";
		MHD_Response *response = mhd_->createResponseFromBuffer(
			body.size(), const_cast<char *>(body.data()), MHD_RESPMEM_MUST_COPY);
		MHD_Result ret = mhd_->queueBasicAuthFailResponse(connection, "depthkey preview", response);
		mhd_->destroyResponse(response);
		return ret == MHD_YES;
	}
	if (std::strcmp(method, "GET") != 0 && std::strcmp(method, "HEAD") != 0)
		return queueText(*mhd_, connection, MHD_HTTP_METHOD_NOT_ALLOWED, "only GET") == MHD_YES;

	const std::string_view url = urlText;
	PreviewStage stage;
	if (url == "/" || url == "/index.html") {
		MHD_Response *response = mhd_->createResponseFromBuffer(
			previewPageHtml().size(), const_cast<char *>(previewPageHtml().data()), MHD_RESPMEM_PERSISTENT);
		mhd_->addResponseHeader(response, "Content-Type", "text/html; charset=utf-8");
		mhd_->addResponseHeader(response, "Content-Security-Policy", kSecurityPolicy);
		mhd_->addResponseHeader(response, "Cache-Control", "no-store");
		MHD_Result ret = mhd_->queueResponse(connection, MHD_HTTP_OK, response);
		mhd_->destroyResponse(response);
		return ret == MHD_YES;
	}
	if (url == "/status.json")
		return queue(*mhd_, connection, MHD_HTTP_OK, previewStatusJson(status()), "application/json") == MHD_YES;
	if (url == "/metrics")
		return queue(*mhd_, connection, MHD_HTTP_OK, previewStatusMetrics(status()),
			     "text/plain; version=0.0.4; charset=utf-8") == MHD_YES;
	if (stageUrl(url, "/snapshot/", ".jpg", stage)) {
		encoder_->watch(stage);
		auto current = encoder_->waitNewer(stage, 0, std::chrono::milliseconds(0));
		auto frame = encoder_->waitNewer(stage, current ? current->sequence : 0, kSnapshotWait);
		encoder_->unwatch(stage);
		if (!frame)
			return queueText(*mhd_, connection, MHD_HTTP_SERVICE_UNAVAILABLE,
					 "no " + std::string(previewStageName(stage)) + " frame within 3 s") == MHD_YES;
		return queue(*mhd_, connection, MHD_HTTP_OK,
			     std::string(frame->jpeg.begin(), frame->jpeg.end()), "image/jpeg") == MHD_YES;
	}
	if (stageUrl(url, "/stream/", ".mjpg", stage)) {
		if (++streams_ > maxClients_) {
			streams_--;
			return queueText(*mhd_, connection, MHD_HTTP_SERVICE_UNAVAILABLE,
					 "too many preview streams (preview.max_clients = " +
						 std::to_string(maxClients_) + ")") == MHD_YES;
		}
		encoder_->watch(stage);
		auto *s = new Stream;
		s->encoder = encoder_;
		s->streams = &streams_;
		s->stage = stage;
		MHD_Response *response =
			mhd_->createResponseFromCallback(MHD_SIZE_UNKNOWN, 64 * 1024, &readStream, s, &freeStream);
		if (!response) {
			freeStream(s);
			return false;
		}
		const std::string type = std::string("multipart/x-mixed-replace;boundary=") + kBoundary;
		mhd_->addResponseHeader(response, "Content-Type", type.c_str());
		mhd_->addResponseHeader(response, "Cache-Control", "no-store, no-cache, must-revalidate, max-age=0");
		mhd_->addResponseHeader(response, "Pragma", "no-cache");
		MHD_Result ret = mhd_->queueResponse(connection, MHD_HTTP_OK, response);
		mhd_->destroyResponse(response);
		return ret == MHD_YES;
	}
	return queueText(*mhd_, connection, MHD_HTTP_NOT_FOUND,
			 "no such page; try /, /stream/STAGE.mjpg, /snapshot/STAGE.jpg, /status.json, /metrics "
			 "(STAGE: colour, depth, seeds, alpha, composite)") == MHD_YES;
}

} // namespace depthkey
