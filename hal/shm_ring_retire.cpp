// Retiring objects, ShmRingWriter's side of an object's end: a stale one
// found at open(), the old one after a rename, and the one we created on a
// clean stop. Retired is generation 0 and offline, which every reader
// already takes as "re-open by name" (hal/depthkey_shm.h), before the name
// goes; docs/shared-memory.md, "When the daemon stops, renames or meets
// another writer".
#include "hal/shm_ring_writer.hpp"

#include "hal/depthkey_shm.h"

#include <cerrno>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace depthkey {

// An object left by an earlier writer (this process before a reload, a
// crashed daemon, or anyone who created the name first) is never reused: its
// owner, mode or group could be anybody's. Ours and unlocked, it is marked
// retired (generation 0, offline) and unlinked. Readers still mapping it get
// -ESTALE and re-open by name; a reader that opens it by name between the
// mark and the unlink gets -EAGAIN and retries, so none can settle on an
// object that will never change again. Another user's is refused.
int ShmRingWriter::retireStale(const std::string &name)
{
	UniqueFd fd(shm_open(name.c_str(), O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0));
	if (!fd.isValid() && errno == ENOENT)
		return 0;
	if (!fd.isValid() && errno == EACCES)
		return fail(-EPERM, "refusing an object created by another user",
			    "it is not ours and we may not even open it: remove it from /dev/shm");
	if (!fd.isValid())
		return fail(-errno, "open the existing object");

	struct stat st{};
	if (fstat(fd.get(), &st) < 0)
		return fail(-errno, "fstat the existing object");
	if (st.st_uid != geteuid()) {
		detail_ = "uid " + std::to_string(st.st_uid);
		return fail(-EPERM, "refusing an object owned by",
			    "another user could read and change the frames: remove it from /dev/shm");
	}
	// A running writer (another depthkeyd) holds the lock; a crash frees it.
	if (flock(fd.get(), LOCK_EX | LOCK_NB) < 0) {
		int err = errno == EWOULDBLOCK ? -EBUSY : -errno;
		return fail(err, "lock",
			    err == -EBUSY ? "another writer has it open (a second depthkeyd with the same [output] names?)"
					  : nullptr);
	}
	if (static_cast<uint64_t>(st.st_size) >= sizeof(dk_shm_header)) {
		void *map = mmap(nullptr, sizeof(dk_shm_header), PROT_READ | PROT_WRITE, MAP_SHARED, fd.get(), 0);
		if (map != MAP_FAILED) {
			auto *h = static_cast<dk_shm_header *>(map);
			__atomic_store_n(&h->online, 0, __ATOMIC_RELAXED);
			__atomic_store_n(&h->generation, 0, __ATOMIC_RELEASE);
			munmap(map, sizeof(dk_shm_header));
		}
	}
	int ret = shm_unlink(name.c_str()) < 0 && errno != ENOENT ? -errno : 0;
	return ret ? fail(ret, "unlink the stale object") : 0;
}

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
