// Helpers for the shared-memory tests: object names that no other test (or
// concurrent test run) uses, removed again when the test ends.
#pragma once

#include "hal/depthkey_shm.h"

#include <atomic>
#include <string>
#include <sys/mman.h>
#include <unistd.h>

namespace depthkey::test {

class ShmName
{
public:
	ShmName()
	{
		static std::atomic<int> counter{ 0 };
		name_ = "/depthkey-test-" + std::to_string(getpid()) + "-" +
			std::to_string(counter++);
		shm_unlink(name_.c_str());
		shm_unlink(presence().c_str());
	}
	~ShmName()
	{
		shm_unlink(name_.c_str());
		shm_unlink(presence().c_str());
	}

	ShmName(const ShmName &) = delete;
	ShmName &operator=(const ShmName &) = delete;

	const std::string &str() const { return name_; }
	const char *c_str() const { return name_.c_str(); }
	// The readers' heartbeat object (hal/depthkey_shm.h).
	std::string presence() const { return name_ + DK_SHM_PRESENCE_SUFFIX; }

private:
	std::string name_;
};

// Removes a daemon's two streams PREFIX.composite and PREFIX.lecturer and
// their readers' objects, for a test whose daemon may not have stopped
// cleanly (a clean stop removes them itself).
inline void unlinkStreams(const std::string &prefix)
{
	for (const char *stream : { ".composite", ".lecturer" }) {
		shm_unlink((prefix + stream).c_str());
		shm_unlink((prefix + stream + DK_SHM_PRESENCE_SUFFIX).c_str());
	}
}

// What a reader gets when it opens the object: 0 or a negative errno.
inline int openStatus(const char *name)
{
	dk_shm_reader r;
	int ret = dk_shm_open(name, &r);
	dk_shm_close(&r);
	return ret;
}

} // namespace depthkey::test
