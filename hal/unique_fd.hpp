// An owned file descriptor (as libcamera's UniqueFD): closed when it goes
// out of scope or is reset, so an error path cannot forget it or close it
// twice. Move-only; release() hands the number over without closing.
#pragma once

#include <cerrno>
#include <unistd.h>
#include <utility>

namespace depthkey {

class UniqueFd
{
public:
	UniqueFd() = default;
	explicit UniqueFd(int fd) : fd_(fd) {}
	UniqueFd(UniqueFd &&other) noexcept : fd_(other.release()) {}
	UniqueFd &operator=(UniqueFd &&other) noexcept
	{
		reset(other.release());
		return *this;
	}
	UniqueFd(const UniqueFd &) = delete;
	UniqueFd &operator=(const UniqueFd &) = delete;
	~UniqueFd() { reset(); }

	int get() const { return fd_; }
	bool isValid() const { return fd_ >= 0; }
	int release() { return std::exchange(fd_, -1); }
	// Closes the one held (errno kept: callers report the error that led here).
	void reset(int fd = -1)
	{
		if (fd_ >= 0 && fd_ != fd) {
			const int saved = errno;
			::close(fd_);
			errno = saved;
		}
		fd_ = fd;
	}

private:
	int fd_ = -1;
};

} // namespace depthkey
