// Removing what a ShmRingWriter created: the old object after a rename, and
// the one it created on a clean stop. Both go through retireStale() (in
// shm_ring_writer.cpp, which retires a stale object found at open()):
// generation 0 and offline, which every reader already takes as "re-open by
// name" (hal/depthkey_shm.h), before the name goes; docs/shared-memory.md,
// "When the daemon stops, renames or meets another writer".
#include "hal/shm_ring_writer.hpp"

namespace depthkey {

// Through retireStale(): it checks, under the writer lock, that the object
// under the name is still one nobody writes, so a name another daemon took
// over after our close() is left alone.
void ShmRingWriter::retireName(const std::string &name)
{
	const int error = error_;
	const char *step = failedStep_, *reason = reason_;
	const std::string detail = detail_;
	retireStale(name);
	// Best effort: a failure here must not read as the open's or the
	// stream's (an object another writer took over is theirs to remove).
	error_ = error;
	failedStep_ = step;
	reason_ = reason;
	detail_ = detail;
}

void ShmRingWriter::remove()
{
	close();
	if (created_.empty())
		return;
	retireName(created_);
	created_.clear();
}

} // namespace depthkey
