// Files that are not what a reader expects, for the regression tests of the
// bounded readers (config/text_file.hpp, hal/image_file_reader.hpp).
#pragma once

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <pthread.h>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

namespace depthkey::test {

// A fresh folder, removed with everything in it when the test ends.
class ScratchDir
{
public:
	ScratchDir()
	{
		char pattern[] = "/tmp/depthkey-hostile-XXXXXX";
		const char *dir = mkdtemp(pattern);
		path_ = dir ? dir : "";
	}
	~ScratchDir()
	{
		if (!path_.empty())
			std::filesystem::remove_all(path_);
	}
	std::string operator/(const std::string &name) const { return path_ + "/" + name; }
	const std::string &path() const { return path_; }

private:
	std::string path_;
};

// A FIFO at path with a writer that keeps offering `text`: a reader that
// opens it blocking would get unblocked (and read the text) instead of
// hanging the test, so a missing O_NONBLOCK/fstat check fails the test's
// assertions rather than stalling the whole suite.
class FifoWithWriter
{
public:
	FifoWithWriter(const std::string &path, std::string text)
		: path_(path), text_(std::move(text))
	{
		ok_ = mkfifo(path.c_str(), 0600) == 0;
		thread_ = std::thread([this] { feed(); });
	}
	~FifoWithWriter()
	{
		stop_ = true;
		thread_.join();
	}
	bool ok() const { return ok_; }
	int fedReaders() const { return fed_; }

private:
	void feed()
	{
		using namespace std::chrono_literals;
		// The reader under test opens the FIFO and closes it at once
		// (refused): a write in between gets EPIPE and a SIGPIPE, which
		// would kill the whole test binary (seen: 1 run in 6). Blocked in
		// this thread only, the signal stays pending here and write()
		// just fails.
		sigset_t pipe;
		sigemptyset(&pipe);
		sigaddset(&pipe, SIGPIPE);
		pthread_sigmask(SIG_BLOCK, &pipe, nullptr);
		while (!stop_) {
			// Non-blocking: fails with ENXIO while no reader has it open.
			int fd = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
			if (fd >= 0) {
				(void)!::write(fd, text_.data(), text_.size());
				::close(fd);
				fed_++;
			}
			std::this_thread::sleep_for(20ms);
		}
	}

	std::string path_, text_;
	bool ok_ = false;
	std::atomic<bool> stop_{ false };
	std::atomic<int> fed_{ 0 };
	std::thread thread_;
};

// A sparse file of `bytes` (no disk space used): st_size is what counts.
inline bool makeSparseFile(const std::string &path, off_t bytes)
{
	int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
	if (fd < 0)
		return false;
	bool ok = ftruncate(fd, bytes) == 0;
	::close(fd);
	return ok;
}

} // namespace depthkey::test
