#include "hal/preview/preview_auth.hpp"

#include "hal/preview/constant_time.hpp"

#include <arpa/inet.h>
#include <cstring>
#include <netinet/in.h>
#include <sys/socket.h>

namespace depthkey {

namespace {

constexpr size_t kMaxVerified = 16;

} // namespace

PreviewAuth::PreviewAuth(const PreviewAuthLimits &limits)
	: limits_(limits), limiter_(limits.perAddress), hashTokens_(limits.hashesPerSecond)
{
}

int PreviewAuth::load(const std::string &path, std::string &error)
{
	auto file = std::make_shared<PasswordFile>();
	const int ret = file->load(path, error);
	std::lock_guard lock(mutex_);
	generation_++;
	verified_.clear();
	passwords_ = ret < 0 ? nullptr : std::move(file);
	return ret;
}

bool PreviewAuth::cached(const std::string &key) const
{
	bool found = false;
	// All of them, each in constant time: the time says nothing of how much
	// of a remembered password a guess has right.
	for (const std::string &v : verified_)
		found |= equalConstantTime(v, key);
	return found;
}

// A bucket of hashesPerSecond tokens, refilled continuously.
bool PreviewAuth::takeHash(uint64_t nowNs)
{
	if (nowNs > lastRefillNs_) {
		hashTokens_ = std::min(limits_.hashesPerSecond,
				       hashTokens_ + limits_.hashesPerSecond * double(nowNs - lastRefillNs_) / 1e9);
		lastRefillNs_ = nowNs;
	}
	if (hashTokens_ < 1)
		return false;
	hashTokens_ -= 1;
	return true;
}

AuthVerdict PreviewAuth::check(const std::string &address, const char *user, const char *password, uint64_t nowNs)
{
	std::string key;
	if (user && password)
		key = std::string(user) + '\0' + password;
	// Twice at most: a check that a load overtook is made again with the
	// new accounts, so that nothing verified by the old ones is let in.
	for (int attempt = 0; attempt < 2; attempt++) {
		std::shared_ptr<const PasswordFile> passwords;
		uint64_t generation;
		{
			std::lock_guard lock(mutex_);
			if (!passwords_)
				return AuthVerdict::Closed;
			if (!user || !password)
				return AuthVerdict::Refused; // a browser's first request: no cost, not a failure
			// Before the limiter: a technician whose password is known
			// gets in even while somebody at the same address guesses.
			if (cached(key))
				return AuthVerdict::Allowed;
			if (limiter_.blocked(address, nowNs) || !takeHash(nowNs)) {
				limited_++;
				return AuthVerdict::Limited;
			}
			passwords = passwords_;
			generation = generation_;
		}
		const bool right = passwords->verify(user, password); // the hash, unlocked
		std::lock_guard lock(mutex_);
		if (generation != generation_)
			continue;
		if (right) {
			if (verified_.size() >= kMaxVerified)
				verified_.erase(verified_.begin());
			verified_.push_back(key);
			limiter_.succeeded(address);
			return AuthVerdict::Allowed;
		}
		failures_++;
		if (limiter_.failed(address, nowNs))
			blocks_++;
		return AuthVerdict::Refused;
	}
	return AuthVerdict::Refused; // reloaded twice meanwhile: the client asks again
}

PreviewAuthStats PreviewAuth::stats() const
{
	return { failures_.load(), limited_.load(), blocks_.load() };
}

std::string clientAddressKey(const sockaddr *address)
{
	char text[INET6_ADDRSTRLEN] = "";
	if (!address)
		return "";
	if (address->sa_family == AF_INET) {
		const auto *a = reinterpret_cast<const sockaddr_in *>(address);
		inet_ntop(AF_INET, &a->sin_addr, text, sizeof(text));
		return text;
	}
	if (address->sa_family == AF_INET6) {
		in6_addr prefix = reinterpret_cast<const sockaddr_in6 *>(address)->sin6_addr;
		std::memset(prefix.s6_addr + 8, 0, 8);
		inet_ntop(AF_INET6, &prefix, text, sizeof(text));
		return std::string(text) + "/64";
	}
	return "";
}

} // namespace depthkey
