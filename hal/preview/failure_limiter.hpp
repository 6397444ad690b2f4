// Failed password attempts per client address (issue 31): after
// kMaxFailures failures within kWindow an address is turned away for
// kBackOff without its password being hashed. A hash costs milliseconds of
// a core the keyer shares; a client guessing as fast as it can otherwise
// takes that core from the composite (7,421 guesses in 15 s took it from
// 21 to 1.3 fps). Times are the caller's (CLOCK_MONOTONIC ns), so tests
// need no sleeping.
#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <unordered_map>

namespace depthkey {

struct FailureLimits {
	int maxFailures = 5;
	uint64_t windowNs = 60'000'000'000ull;
	uint64_t backOffNs = 60'000'000'000ull;
	// Addresses remembered at most: a client with many addresses (IPv6)
	// must not grow the table without bound. The oldest go first.
	size_t maxAddresses = 4096;
};

class FailureLimiter
{
public:
	explicit FailureLimiter(const FailureLimits &limits = {}) : limits_(limits) {}

	// Whether address is backing off at nowNs: answer it without a check.
	bool blocked(const std::string &address, uint64_t nowNs);
	// A wrong password from address; returns true when this one starts its
	// back-off.
	bool failed(const std::string &address, uint64_t nowNs);
	// A right password: the address's earlier slips are forgotten.
	void succeeded(const std::string &address);
	size_t addresses() const;

private:
	struct Attempts {
		int failures = 0;
		uint64_t windowStartNs = 0;
		uint64_t blockedUntilNs = 0;
	};
	void makeRoom(uint64_t nowNs);

	FailureLimits limits_;
	mutable std::mutex mutex_;
	std::unordered_map<std::string, Attempts> attempts_;
};

} // namespace depthkey
