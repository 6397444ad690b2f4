// The live preview's HTTP server, on libmicrohttpd (a thread per connection,
// its own threads; nothing runs on the daemon's event loop). The library is
// loaded when the first client connects (hal/preview/microhttpd_library.hpp:
// 2.5 MB of resident GnuTLS saved while nobody watches); until then one
// thread waits on the listening socket. It serves:
//
//   /                    the page (hal/preview/preview_page.hpp)
//   /stream/STAGE.mjpg   multipart/x-mixed-replace MJPEG, as uStreamer serves it
//   /snapshot/STAGE.jpg  the next JPEG of the stage
//   /status.json         the status (hal/preview/preview_status.hpp)
//   /metrics             the same in Prometheus' text format
//   POST /snapshot       the stage pictures written as SIGUSR1 writes them
//                        (hal/preview/snapshot_requests.hpp), with the header
//                        X-Depthkey-Snapshot: 1 (a form on another site
//                        cannot send it, nor make a browser send it unasked)
//
// A stream's thread sends the newest JPEG whenever its socket takes more,
// so a slow client skips frames and nobody waits for it. At most maxClients
// streams run at once (more get 503); connections idle for 10 s are closed.
// With a password file every request needs HTTP basic authentication
// (hal/preview/preview_auth.hpp: re-read by reloadPasswords(), failures
// limited per client address).
//
// Slow clients (issue 31): one client address may hold at most
// maxClients + 16 connections, all together four times that, so that a
// client trickling its requests a byte at a time cannot take every slot
// from the technician. The server's threads run at nice 10 (inherited
// from the thread that starts libmicrohttpd): on a busy box the keyer,
// at nice 0 on the event loop, comes first. A request head not whole within
// 5 s is cut (hal/preview/request_deadlines.hpp), so slow clients from the
// technician's own address (127.0.0.1 through ssh -L) free their slots.
#pragma once

#include "config/listen_address.hpp"
#include "hal/preview/microhttpd_library.hpp"
#include "hal/preview/preview_auth.hpp"
#include "hal/preview/request_deadlines.hpp"
#include "hal/unique_fd.hpp"
#include "hal/preview/preview_encoder.hpp"
#include "hal/preview/preview_status.hpp"
#include "hal/preview/snapshot_requests.hpp"

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

struct MHD_Daemon;
struct MHD_Connection;

namespace depthkey {

struct PreviewServerOptions {
	ListenAddress address;
	std::string passwordFile; // "" = no authentication (loopback only)
	int maxClients = 8;
	// What wrong passwords may cost (the fuzz harness lifts them, to reach
	// the hashing on every input).
	PreviewAuthLimits authLimits;
	// What loads libmicrohttpd (tests give one that fails); null: loadMicroHttpd.
	const MicroHttpd *(*load)(std::string &error) = nullptr;
};

class PreviewServer
{
public:
	PreviewServer() = default;
	~PreviewServer() { stop(); }
	PreviewServer(const PreviewServer &) = delete;
	PreviewServer &operator=(const PreviewServer &) = delete;

	// Binds and listens; serves the encoder's stages from the first client
	// on. Refuses an address off loopback without a password file. Returns 0
	// or a negative errno with error saying what and where.
	int start(const PreviewServerOptions &options, PreviewEncoder &encoder, std::string &error);
	void stop();
	// On a reload that keeps the options: reads the password file again
	// (nothing without one). Returns 0, or a negative errno with error
	// naming the file and line; the page is closed then (503) until a
	// good file is read. For the event loop: the file is small, no hashing.
	int reloadPasswords(std::string &error);
	bool running() const { return doorman_.joinable(); } // started, not yet stopped
	// libmicrohttpd loaded and serving (after the first client).
	bool serving() const { return daemon_ != nullptr; }
	// Why the last client was refused (libmicrohttpd not loaded or not
	// started; that client got 503 with it), once, then ""; the next client
	// tries again. For the daemon's journal: the server's threads do not log.
	std::string takeError();
	int port() const { return port_; } // the bound port (options may ask for 0)

	// A copy for the HTTP threads; called once a second by the daemon.
	void setStatus(const PreviewStatus &status);
	int streams() const { return streams_.load(); }
	// The page's snapshot requests, answered by the daemon's loop.
	SnapshotRequests &snapshots() { return snapshots_; }

	// Used by the C callbacks of libmicrohttpd.
	int handle(MHD_Connection *connection, const char *url, const char *method);
	void connectionEvent(MHD_Connection *connection, bool started); // started, or closed
	void requestArrived(MHD_Connection *connection);                  // its head is whole

private:
	AuthVerdict authorise(MHD_Connection *connection);
	bool refuse(MHD_Connection *connection, AuthVerdict verdict);
	PreviewStatus status();
	void waitForFirstClient();
	void expireSlowRequests();
	int startServing(std::string &error);
	void noteError(std::string error);
	bool handleSnapshotPost(MHD_Connection *connection, const char *method);

	UniqueFd listen_;          // ours until libmicrohttpd takes it
	UniqueFd wake_;            // eventfd: stop() wakes the waiting thread
	std::thread doorman_;      // waits for the first client, then cuts late requests; joined by stop()
	const MicroHttpd *(*load_)(std::string &error) = nullptr;
	const MicroHttpd *mhd_ = nullptr;
	std::atomic<MHD_Daemon *> daemon_{ nullptr };
	bool ipv6_ = false;
	std::mutex errorMutex_;
	std::string error_;
	PreviewEncoder *encoder_ = nullptr;
	std::unique_ptr<PreviewAuth> auth_ = std::make_unique<PreviewAuth>(); // replaced by start()
	std::string passwordFile_;
	RequestDeadlines deadlines_{ kRequestHeadDeadlineNs };
	bool needAuth_ = false;
	int port_ = 0;
	int maxClients_ = 8;
	std::atomic<int> streams_{ 0 };
	std::mutex statusMutex_;
	PreviewStatus status_;
	SnapshotRequests snapshots_;
};

} // namespace depthkey
