#include "hal/preview/preview_server.hpp"

#include "hal/preview/mjpeg_stream.hpp"
#include "hal/preview/preview_listener.hpp"
#include "hal/preview/preview_page.hpp"
#include "hal/unique_fd.hpp"

#include <algorithm>
#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <utility>
#include <microhttpd.h>
#include <netinet/in.h>
#include <time.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

namespace depthkey {

namespace {

constexpr auto kSnapshotWait = std::chrono::milliseconds(3000);
// The loop writes a snapshot between frames: well within this.
constexpr auto kSnapshotAnswerWait = std::chrono::milliseconds(5000);
constexpr unsigned kIdleTimeoutS = 10;
// Connections beyond the streams (the page, status, metrics, snapshots, and
// closed ones whose threads have not yet been reaped): libmicrohttpd closes
// any connection over its limit without a word. The connections waiting in
// the backlog when the library is loaded all arrive at once and finish at
// once, so the limit leaves room for a backlog of them (with 4, ten clients
// reconnecting together lost one reply in seven runs of the unit test).
constexpr int kExtraConnections = kListenBacklog;
// All connections, as many as kClientAddresses addresses may hold each: a
// client trickling requests from one address holds at most its own share
// (40 such connections took every slot of 24 before, issue 31).
constexpr int kClientAddresses = 4;
// The server's threads' nice value above the daemon's (at most 19):
// libmicrohttpd's threads inherit it from the thread that starts the
// library. Weight 110 against the keyer's 1024: a flood of requests takes
// the keyer's core only when the keyer leaves it. Relative, because the
// daemon may itself run niced (a unit's Nice=, `nice make test`): an
// absolute 10 put the server level with a daemon at 10, and above one at 15.
constexpr int kServerNiceAbove = 10;
// What a client backing off is told to wait (FailureLimits::backOffNs).
constexpr const char *kRetryAfterS = "60";
// Why a stage has no picture: the page shows it on the tile.
constexpr std::string_view kNotMade =
	"the daemon makes none now (a camera or the board's source missing or not streaming: see setup and status)";
constexpr const char *kSecurityPolicy =
	"default-src 'self'; script-src 'self' 'unsafe-inline'; style-src 'unsafe-inline'; img-src 'self' blob:";

uint64_t monotonicNs()
{
	timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return static_cast<uint64_t>(ts.tv_sec) * 1000000000u + static_cast<uint64_t>(ts.tv_nsec);
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
		static_cast<PreviewServer *>(cls)->requestArrived(connection);
		return MHD_YES;
	}
	if (*uploadSize != 0) // no request bodies here
		return MHD_NO;
	return static_cast<PreviewServer *>(cls)->handle(connection, url, method) ? MHD_YES : MHD_NO;
}

void onConnection(void *cls, MHD_Connection *connection, void **, MHD_ConnectionNotificationCode code)
{
	static_cast<PreviewServer *>(cls)->connectionEvent(connection, code == MHD_CONNECTION_NOTIFY_STARTED);
}

// Strips prefix and suffix from url into name; false when it does not fit.
bool stageUrl(std::string_view url, std::string_view prefix, std::string_view suffix, PreviewStage &stage)
{
	if (url.size() <= prefix.size() + suffix.size() || url.substr(0, prefix.size()) != prefix ||
	    url.substr(url.size() - suffix.size()) != suffix)
		return false;
	return previewStageFromName(url.substr(prefix.size(), url.size() - prefix.size() - suffix.size()), stage);
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
	passwordFile_ = options.passwordFile;
	auth_ = std::make_unique<PreviewAuth>(options.authLimits); // no thread uses it: stopped above
	deadlines_.clear();
	if (needAuth_) {
		int ret = auth_->load(passwordFile_, error);
		if (ret < 0)
			return ret;
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
	// This thread only (Linux's nice is per thread), and so the library's.
	const id_t self = static_cast<id_t>(gettid());
	errno = 0;
	const int nice = getpriority(PRIO_PROCESS, self); // -1 is a nice value too
	if (errno == 0 && setpriority(PRIO_PROCESS, self, std::min(19, nice + kServerNiceAbove)) < 0) {
		// not allowed to: the server runs at the daemon's priority
	}
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
			return expireSlowRequests();
		noteError("preview server not serving: " + error);
		refuseWaitingClient(listen_.get(), "preview unavailable: " + error);
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
	const unsigned perClient = static_cast<unsigned>(maxClients_ + kExtraConnections);
	MHD_Daemon *daemon = mhd->startDaemon(flags, 0, nullptr, nullptr, &onRequest, this, MHD_OPTION_LISTEN_SOCKET,
					      listen_.get(), MHD_OPTION_CONNECTION_LIMIT, perClient * kClientAddresses,
					      MHD_OPTION_PER_IP_CONNECTION_LIMIT, perClient,
					      MHD_OPTION_CONNECTION_TIMEOUT, kIdleTimeoutS, MHD_OPTION_NOTIFY_CONNECTION,
					      &onConnection, this, MHD_OPTION_END);
	if (!daemon) {
		int ret = errno ? -errno : -EIO;
		error = std::string(kMicroHttpdSoname) + " did not start" + (errno ? std::string(": ") + std::strerror(errno) : "");
		return ret;
	}
	listen_.release(); // libmicrohttpd owns it now: MHD_stop_daemon closes it
	daemon_ = daemon;
	return 0;
}

// Once serving, this thread cuts the connections whose request head is
// late, once a second, until stop().
void PreviewServer::expireSlowRequests()
{
	pollfd wake = { wake_.get(), POLLIN, 0 };
	for (;;) {
		const int n = poll(&wake, 1, 1000);
		if (n > 0 || (n < 0 && errno != EINTR))
			return;
		deadlines_.expire(monotonicNs());
	}
}

void PreviewServer::connectionEvent(MHD_Connection *connection, bool started)
{
	if (!started) {
		deadlines_.closed(connection);
		return;
	}
	const MHD_ConnectionInfo *info = mhd_->getConnectionInfo(connection, MHD_CONNECTION_INFO_CONNECTION_FD);
	if (info)
		deadlines_.opened(connection, info->connect_fd, monotonicNs());
}

void PreviewServer::requestArrived(MHD_Connection *connection)
{
	deadlines_.arrived(connection);
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
	snapshots_.cancel(); // a page waiting for a snapshot gets 503 now
	// Closes the listening socket too (libmicrohttpd owns it once serving);
	// waits for the connection threads, each back within kMjpegStreamWait.
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
	const PreviewAuthStats a = auth_->stats();
	s.previewAuthFailures = a.failures;
	s.previewAuthLimited = a.limited;
	s.previewAuthBlocks = a.blocks;
	s.previewSlowRequestsCut = deadlines_.expired();
	return s;
}

int PreviewServer::reloadPasswords(std::string &error)
{
	return needAuth_ ? auth_->load(passwordFile_, error) : 0;
}

AuthVerdict PreviewServer::authorise(MHD_Connection *connection)
{
	if (!needAuth_)
		return AuthVerdict::Allowed;
	const MHD_ConnectionInfo *info = mhd_->getConnectionInfo(connection, MHD_CONNECTION_INFO_CLIENT_ADDRESS);
	const std::string address = clientAddressKey(info ? info->client_addr : nullptr);
	char *password = nullptr;
	char *user = mhd_->basicAuthGetUsernamePassword(connection, &password);
	const AuthVerdict verdict = auth_->check(address, user, password, monotonicNs());
	if (user)
		mhd_->free(user);
	if (password)
		mhd_->free(password);
	return verdict;
}

// The answer to a request that may not see the page, none of them hashed.
bool PreviewServer::refuse(MHD_Connection *connection, AuthVerdict verdict)
{
	if (verdict == AuthVerdict::Closed)
		return queueText(*mhd_, connection, MHD_HTTP_SERVICE_UNAVAILABLE,
				 "preview closed: its password file was refused at the last reload (see the journal)") ==
		       MHD_YES;
	if (verdict == AuthVerdict::Limited) {
		const std::string body = "too many wrong passwords from this address; try again in a minute\n";
		MHD_Response *response = mhd_->createResponseFromBuffer(
			body.size(), const_cast<char *>(body.data()), MHD_RESPMEM_MUST_COPY);
		if (!response)
			return false;
		mhd_->addResponseHeader(response, "Content-Type", "text/plain; charset=utf-8");
		mhd_->addResponseHeader(response, "Retry-After", kRetryAfterS);
		MHD_Result ret = mhd_->queueResponse(connection, MHD_HTTP_TOO_MANY_REQUESTS, response);
		mhd_->destroyResponse(response);
		return ret == MHD_YES;
	}
	const std::string body = "authentication required\n";
	MHD_Response *response =
		mhd_->createResponseFromBuffer(body.size(), const_cast<char *>(body.data()), MHD_RESPMEM_MUST_COPY);
	if (!response)
		return false;
	MHD_Result ret = mhd_->queueBasicAuthFailResponse(connection, "depthkey preview", response);
	mhd_->destroyResponse(response);
	return ret == MHD_YES;
}

// Authenticated already. Only POST (a GET that writes files would be
// followed by link prefetchers), and only with the page's own header.
bool PreviewServer::handleSnapshotPost(MHD_Connection *connection, const char *method)
{
	if (std::strcmp(method, "POST") != 0)
		return queueText(*mhd_, connection, MHD_HTTP_METHOD_NOT_ALLOWED, "/snapshot takes POST only") == MHD_YES;
	const char *marker = mhd_->lookupConnectionValue(connection, MHD_HEADER_KIND, "X-Depthkey-Snapshot");
	if (!marker || std::strcmp(marker, "1") != 0)
		return queueText(*mhd_, connection, MHD_HTTP_BAD_REQUEST,
				 "POST /snapshot needs the header X-Depthkey-Snapshot: 1 (the page's button sends it)") ==
		       MHD_YES;
	const SnapshotReply reply = snapshots_.request(monotonicNs(), kSnapshotAnswerWait);
	return queueText(*mhd_, connection, reply.httpStatus, reply.message) == MHD_YES;
}

int PreviewServer::handle(MHD_Connection *connection, const char *urlText, const char *method)
{
	if (const AuthVerdict verdict = authorise(connection); verdict != AuthVerdict::Allowed)
		return refuse(connection, verdict);
	const std::string_view url = urlText;
	if (url == "/snapshot")
		return handleSnapshotPost(connection, method);
	if (std::strcmp(method, "GET") != 0 && std::strcmp(method, "HEAD") != 0)
		return queueText(*mhd_, connection, MHD_HTTP_METHOD_NOT_ALLOWED, "only GET") == MHD_YES;

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
		// A stage the loop makes no picture of (NO SIGNAL's depth, seeds and
		// alpha): said at once, not after a 3 s wait that holds one of the
		// few connections a browser opens to the page (issue 30).
		if (!encoder_->making(stage, monotonicNs()))
			return queueText(*mhd_, connection, MHD_HTTP_SERVICE_UNAVAILABLE,
					 "no " + std::string(previewStageName(stage)) + " frame yet: " + std::string(kNotMade)) ==
			       MHD_YES;
		encoder_->watch(stage);
		auto current = encoder_->waitNewer(stage, 0, std::chrono::milliseconds(0));
		auto frame = encoder_->waitNewer(stage, current ? current->sequence : 0, kSnapshotWait);
		encoder_->unwatch(stage);
		if (!frame)
			return queueText(*mhd_, connection, MHD_HTTP_SERVICE_UNAVAILABLE,
					 "no " + std::string(previewStageName(stage)) + " frame within 3 s") == MHD_YES;
		// The capture time (µs), as each part of a stream has it: the
		// shared memory's timestamp_ns / 1000 of the same frame.
		MHD_Response *response = mhd_->createResponseFromBuffer(
			frame->jpeg.size(), const_cast<uint8_t *>(frame->jpeg.data()), MHD_RESPMEM_MUST_COPY);
		if (!response)
			return false;
		mhd_->addResponseHeader(response, "Content-Type", "image/jpeg");
		mhd_->addResponseHeader(response, "Cache-Control", "no-store");
		mhd_->addResponseHeader(response, "X-Timestamp", std::to_string(frame->captureNs / 1000).c_str());
		const MHD_Result ret = mhd_->queueResponse(connection, MHD_HTTP_OK, response);
		mhd_->destroyResponse(response);
		return ret == MHD_YES;
	}
	if (stageUrl(url, "/stream/", ".mjpg", stage)) {
		if (++streams_ > maxClients_) {
			streams_--;
			return queueText(*mhd_, connection, MHD_HTTP_SERVICE_UNAVAILABLE,
					 "too many preview streams (preview.max_clients = " +
						 std::to_string(maxClients_) + ")") == MHD_YES;
		}
		encoder_->watch(stage);
		auto *s = new MjpegStream;
		s->encoder = encoder_;
		s->streams = &streams_;
		s->stage = stage;
		MHD_Response *response =
			mhd_->createResponseFromCallback(MHD_SIZE_UNKNOWN, 64 * 1024, &readMjpegStream, s, &freeMjpegStream);
		if (!response) {
			freeMjpegStream(s);
			return false;
		}
		const std::string type = std::string("multipart/x-mixed-replace;boundary=") + kMjpegBoundary;
		mhd_->addResponseHeader(response, "Content-Type", type.c_str());
		mhd_->addResponseHeader(response, "Cache-Control", "no-store, no-cache, must-revalidate, max-age=0");
		mhd_->addResponseHeader(response, "Pragma", "no-cache");
		MHD_Result ret = mhd_->queueResponse(connection, MHD_HTTP_OK, response);
		mhd_->destroyResponse(response);
		return ret == MHD_YES;
	}
	return queueText(*mhd_, connection, MHD_HTTP_NOT_FOUND,
			 "no such page; try /, /stream/STAGE.mjpg, /snapshot/STAGE.jpg, /status.json, /metrics, "
			 "POST /snapshot (STAGE: composite, lecturer, board, colour, depth, seeds, alpha)") == MHD_YES;
}

} // namespace depthkey
