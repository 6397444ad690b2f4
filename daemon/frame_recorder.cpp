#include "daemon/frame_recorder.hpp"

#include <pthread.h>

namespace depthkey {

int FrameRecorder::start(const std::string &dir, int pngCompression, std::string &error, int colourWidth,
			 int colourHeight)
{
	stop();
	writer_.setCompression(pngCompression);
	int ret = writer_.open(dir, colourWidth, colourHeight);
	if (ret < 0) {
		error = writer_.describeError();
		return ret;
	}
	dir_ = writer_.folder(); // dir, or dir/boot-N after a reboot, or dir/WxH
	stopping_ = false;
	colourBusy_.fill(false);
	depthBusy_.fill(false);
	jobHead_ = jobCount_ = 0;
	worker_ = std::thread([this] { run(); });
	return 0;
}

void FrameRecorder::stop()
{
	if (!worker_.joinable())
		return;
	{
		std::lock_guard<std::mutex> lock(mutex_);
		stopping_ = true;
	}
	wake_.notify_one();
	worker_.join();
	writer_.close();
}

template<typename Frame, size_t N>
void FrameRecorder::enqueue(const Frame &frame, std::array<Frame, N> &slots, std::array<bool, N> &busy, bool colour)
{
	if (!worker_.joinable())
		return;
	std::unique_lock<std::mutex> lock(mutex_);
	int slot = -1;
	for (size_t i = 0; i < N; ++i)
		if (!busy[i]) {
			slot = static_cast<int>(i);
			break;
		}
	if (slot < 0) {
		dropped_++;
		return;
	}
	busy[slot] = true;
	lock.unlock();
	// The worker never touches a slot marked busy before its job is queued.
	slots[slot] = frame; // same size as last time: no allocation
	lock.lock();
	jobs_[(jobHead_ + jobCount_) % kJobs] = { colour, slot };
	jobCount_++;
	lock.unlock();
	wake_.notify_one();
}

void FrameRecorder::recordColour(const ColourFrame &frame)
{
	enqueue(frame, colour_, colourBusy_, true);
}

void FrameRecorder::recordDepth(const DepthFrame &frame)
{
	enqueue(frame, depth_, depthBusy_, false);
}

std::string FrameRecorder::takeError()
{
	std::lock_guard<std::mutex> lock(mutex_);
	std::string e;
	e.swap(error_);
	return e;
}

void FrameRecorder::run()
{
	pthread_setname_np(pthread_self(), "dk-record"); // for top -H and make bench-process
	for (;;) {
		Job job;
		{
			std::unique_lock<std::mutex> lock(mutex_);
			wake_.wait(lock, [this] { return jobCount_ > 0 || stopping_; });
			if (jobCount_ == 0)
				return; // stopping, and everything queued is written
			job = jobs_[jobHead_];
			jobHead_ = (jobHead_ + 1) % kJobs;
			jobCount_--;
		}
		int ret = job.colour ? writer_.writeColour(colour_[job.slot]) : writer_.writeDepth(depth_[job.slot]);
		std::lock_guard<std::mutex> lock(mutex_);
		(job.colour ? colourBusy_[job.slot] : depthBusy_[job.slot]) = false;
		if (ret < 0)
			error_ = writer_.describeError();
		else
			written_++;
	}
}

} // namespace depthkey
