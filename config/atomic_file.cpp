// write, fsync, rename, fsync(dir): the sequence POSIX needs for a durable replace.
#include "config/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace depthkey {

namespace {

std::string directoryOf(const std::string &path)
{
	size_t slash = path.rfind('/');
	if (slash == std::string::npos)
		return ".";
	return slash == 0 ? "/" : path.substr(0, slash);
}

int writeAll(int fd, std::string_view text)
{
	while (!text.empty()) {
		ssize_t n = ::write(fd, text.data(), text.size());
		if (n < 0 && errno == EINTR)
			continue;
		if (n < 0)
			return -errno;
		text.remove_prefix(static_cast<size_t>(n));
	}
	return 0;
}

int fsyncDirectory(const std::string &dir)
{
	int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (fd < 0)
		return -errno;
	int ret = ::fsync(fd) < 0 ? -errno : 0;
	::close(fd);
	return ret;
}

} // namespace

int writeFileAtomically(const std::string &path, std::string_view text, std::string &error)
{
	// The temporary lives beside path: rename() is only atomic within one
	// file system.
	std::string temp = path + ".XXXXXX";
	int fd = ::mkostemp(temp.data(), O_CLOEXEC);
	if (fd < 0) {
		int ret = -errno;
		error = "cannot create a temporary file in " + directoryOf(path) + ": " +
			std::strerror(-ret);
		return ret;
	}

	auto fail = [&](const char *step, int ret) {
		::close(fd);
		::unlink(temp.c_str());
		error = std::string("cannot ") + step + ' ' + temp + ": " + std::strerror(-ret);
		return ret;
	};

	// mkostemp creates 0600; a calibration is not a secret and the daemon
	// may run as another user.
	if (::fchmod(fd, 0644) < 0)
		return fail("chmod", -errno);
	if (int ret = writeAll(fd, text); ret < 0)
		return fail("write", ret);
	if (::fsync(fd) < 0)
		return fail("fsync", -errno);
	if (::close(fd) < 0) {
		int ret = -errno;
		::unlink(temp.c_str());
		error = "cannot close " + temp + ": " + std::strerror(-ret);
		return ret;
	}
	if (::rename(temp.c_str(), path.c_str()) < 0) {
		int ret = -errno;
		::unlink(temp.c_str());
		error = "cannot rename " + temp + " to " + path + ": " + std::strerror(-ret);
		return ret;
	}
	// Without this the rename itself may not survive a power cut.
	if (int ret = fsyncDirectory(directoryOf(path)); ret < 0) {
		error = "cannot fsync directory " + directoryOf(path) + ": " + std::strerror(-ret);
		return ret;
	}
	return 0;
}

} // namespace depthkey
