// The writer's side of reader presence (hal/depthkey_shm.h): the readers'
// heartbeats live in an object of their own, NAME.readers, mode 0660, the
// only thing the output group may write (issue 31: a reader with write
// access to the frames' object could shrink it and kill the writer with
// SIGBUS, or scribble on the header). Even so a reader can shrink this one,
// so the writer never maps it: it reads the table with one pread, frees a
// dead reader's slot with a pwrite, and restores the size when a pread
// comes back short. A pread of a shrunk file is short, never a fault.
#include "hal/shm_ring_writer.hpp"

#include "hal/depthkey_shm.h"
#include "hal/shm_name.hpp"

#include <cerrno>
#include <cstddef>
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace depthkey {

static_assert(DK_SHM_MAX_READERS == 16, "readerSeen_ has one entry per reader slot");

int ShmRingWriter::removePresence(const std::string &name)
{
	const std::string presence = shmPresenceName(name);
	if (shm_unlink(presence.c_str()) == 0 || errno == ENOENT)
		return 0;
	const int err = errno == EACCES ? -EPERM : -errno;
	detail_ = presence;
	return fail(err, "refusing the readers' object",
		    err == -EPERM ? "another user created it: remove it from /dev/shm" : nullptr);
}

// A fresh, zeroed table: readers of an earlier writer keep the old, unlinked
// object, so their slots never count here; they re-open on the new
// generation and claim new ones.
int ShmRingWriter::createPresence(const std::string &name, unsigned int gid, const std::string &group)
{
	const std::string presence = shmPresenceName(name);
	UniqueFd fd;
	if (int ret = createFresh(presence, gid, group, 0660, fd); ret)
		return ret;
	const long page = sysconf(_SC_PAGESIZE);
	const size_t size = static_cast<size_t>(page > 0 ? page : DK_SHM_DATA_ALIGN);
	static_assert(sizeof(dk_shm_reader_table) <= DK_SHM_DATA_ALIGN);
	if (ftruncate(fd.get(), static_cast<off_t>(size)) < 0) {
		const int err = -errno;
		shm_unlink(presence.c_str());
		detail_ = presence;
		return fail(err, "size the readers' object");
	}
	presenceFd_ = std::move(fd);
	presenceSize_ = size;
	return 0;
}

int ShmRingWriter::countReaders(uint64_t nowNs)
{
	if (!presenceFd_.isValid())
		return 0;
	dk_shm_reader_table table;
	const ssize_t got = pread(presenceFd_.get(), &table, sizeof(table), static_cast<off_t>(readerOffset_));
	if (got != static_cast<ssize_t>(sizeof(table))) {
		// Shrunk by a reader: back to its size (zeroes: the readers
		// claim slots again on their next beat), reported by write().
		if (got >= 0 && ftruncate(presenceFd_.get(), static_cast<off_t>(presenceSize_)) == 0)
			presenceShrunkTo_ = got;
		readerSeen_ = {};
		return 0;
	}
	constexpr uint64_t kTimeoutNs = uint64_t{ DK_SHM_READER_TIMEOUT_MS } * 1000000u;
	int present = 0;
	for (size_t i = 0; i < readerSeen_.size(); i++) {
		const dk_shm_reader_slot &slot = table.readers[i];
		ReaderSeen &seen = readerSeen_[i];
		if (slot.owner == 0) {
			seen = {};
			continue;
		}
		if (slot.owner != seen.owner || slot.beats != seen.beats) {
			seen = { slot.owner, slot.beats, nowNs };
			present++;
		} else if (nowNs - seen.sinceNs <= kTimeoutNs) {
			present++;
		} else {
			// Gone: free the slot unless its reader beat or a new one
			// claimed it since the table was read. Without a mapping
			// there is no compare-and-swap; the window is a pread to a
			// pwrite, and a live reader freed in it only claims a slot
			// again on its next beat.
			const off_t at = static_cast<off_t>(readerOffset_ + offsetof(dk_shm_reader_table, readers) +
							    i * sizeof(dk_shm_reader_slot));
			uint64_t now[2] = { 0, 0 }; // owner, beats
			const uint64_t free = 0;
			if (pread(presenceFd_.get(), now, sizeof(now), at) == static_cast<ssize_t>(sizeof(now)) &&
			    now[0] == slot.owner && now[1] == slot.beats &&
			    pwrite(presenceFd_.get(), &free, sizeof(free), at) == static_cast<ssize_t>(sizeof(free)))
				seen = {};
		}
	}
	return present;
}

} // namespace depthkey
