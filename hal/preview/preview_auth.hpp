// Who may see the preview when it has a password file (issue 31): the
// file's accounts, what was verified already, and what a failing client
// may still cost. Called from libmicrohttpd's connection threads, never from
// the daemon's event loop, which keys the frames (hal/preview/preview_server.hpp
// starts those threads at a lower priority too).
//
// - A reload re-reads the file (load()): changed or removed passwords stop
//   working at once, the cache of verified ones is emptied. A file that is
//   refused closes the page (everyone gets Closed) until a good one is
//   loaded: the old accounts may be the very ones being revoked, so falling
//   back to them would keep a revoked password working. The daemon itself
//   runs on; only the page is shut.
// - A right "user:password" is remembered (kMaxVerified of them), so a page
//   that asks every second, or a flood with the right password, is not
//   hashed again: a hash costs milliseconds, a comparison nanoseconds.
// - Wrong passwords are limited per client address (FailureLimiter), and
//   all hashing together by a budget per second, so that many addresses
//   cannot buy what one may not. Both answer Limited without hashing.
#pragma once

#include "hal/preview/failure_limiter.hpp"
#include "hal/preview/password_file.hpp"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <sys/socket.h>
#include <vector>

namespace depthkey {

enum class AuthVerdict {
	Allowed,
	Refused, // no, wrong or unknown credentials: 401
	Limited, // not checked: the address is backing off, or the budget is spent: 429
	Closed,  // the password file was refused at the last reload: 503
};

struct PreviewAuthStats {
	uint64_t failures = 0; // credentials hashed and found wrong (or the user unknown)
	uint64_t limited = 0;  // requests turned away without a check
	uint64_t blocks = 0;   // back-offs begun (an address reached its failure limit)
};

struct PreviewAuthLimits {
	FailureLimits perAddress;
	// Hashes for credentials not yet verified, all clients together: about
	// 2 % of a core with yescrypt's default cost (about 1 ms a hash here).
	double hashesPerSecond = 20;
};

class PreviewAuth
{
public:
	explicit PreviewAuth(const PreviewAuthLimits &limits = {});

	// Reads path (hal/preview/password_file.hpp). Returns 0, or a negative
	// errno with error naming the file and line; then the page is Closed.
	int load(const std::string &path, std::string &error);
	// user and password as the request gave them (null: none); address is
	// the client's (clientAddressKey()); nowNs CLOCK_MONOTONIC.
	AuthVerdict check(const std::string &address, const char *user, const char *password, uint64_t nowNs);
	PreviewAuthStats stats() const;

private:
	bool cached(const std::string &key) const;
	bool takeHash(uint64_t nowNs);

	PreviewAuthLimits limits_;
	FailureLimiter limiter_;
	mutable std::mutex mutex_; // what follows
	std::shared_ptr<const PasswordFile> passwords_; // null: closed
	uint64_t generation_ = 0;  // loads; a check that spans one is not cached
	std::vector<std::string> verified_; // "user\0password", oldest first
	double hashTokens_ = 0;
	uint64_t lastRefillNs_ = 0;
	std::atomic<uint64_t> failures_{ 0 }, limited_{ 0 }, blocks_{ 0 };
};

// The key a client is limited by: its IPv4 address, or its IPv6 /64 (one
// host is commonly given a whole /64). "" for another family.
std::string clientAddressKey(const sockaddr *address);

} // namespace depthkey
