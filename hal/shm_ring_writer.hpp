// The writing side of a depthkey shared-memory frame ring (layout and reader
// in hal/depthkey_shm.h). One writer per object; any number of readers.
//
// write() never blocks and never waits for readers: it fills the next slot
// under that slot's seqlock and moves on, so a stalled or crashed consumer
// cannot hold up the daemon. Each open() stamps a new generation so that
// readers notice a restart (or a new geometry) and re-open.
//
// Readers cannot harm it (issue 31): the frames and header are mode 0640, so
// the output group maps them read-only; the readers' heartbeats live in a
// separate object (NAME.readers, 0660) that the writer only reads and writes
// with pread/pwrite, never through a mapping, so shrinking it cannot fault
// the writer. Before each frame the writer checks its own object's size and
// header too (guard(), hal/shm_ring_guard.cpp), so that even the owner or
// root shrinking or scribbling on it is repaired and reported, not a SIGBUS
// or a stream every reader silently refuses.
#pragma once

#include "hal/unique_fd.hpp"

#include <array>
#include <cerrno>
#include <cstdint>
#include <string>
#include <sys/types.h>

struct dk_shm_header;
struct dk_shm_reader_table;

namespace depthkey {

class ShmRingWriter
{
public:
	ShmRingWriter() = default;
	~ShmRingWriter();

	ShmRingWriter(const ShmRingWriter &) = delete;
	ShmRingWriter &operator=(const ShmRingWriter &) = delete;

	// Creates the object `name` ("/depthkey.composite") afresh and
	// exclusively (O_EXCL), with mode 0640 (the group reads), and its
	// presence object `name` + ".readers" with mode 0660 (the group writes
	// its heartbeats there), group `group` ("" = our own egid) set through
	// their fds. A stale object of ours is retired first (readers mapping it get
	// -ESTALE; their mapping stays valid); one owned by another user is
	// refused with -EPERM, one held by a running writer with -EBUSY.
	// fourcc is DK_SHM_FORMAT_RGB24 or DK_SHM_FORMAT_RGBA32, slots 2..8.
	// Re-opening an open writer closes it first. Returns 0 or a negative
	// errno; describeError() then says what failed.
	int open(const std::string &name, int width, int height, uint32_t fourcc, int slots,
		 const std::string &group);

	// Publishes one frame: height rows of width * bytesPerPixel bytes, rows
	// srcStride bytes apart. No allocation, no waiting; one fstat (guard()).
	// Returns 0, -EBADF when not open, -EINVAL for a bad buffer, or
	// -EUCLEAN when the object had been tampered with and was repaired (the
	// frame is published; describeError() names what had changed).
	int write(const uint8_t *pixels, int srcStride, uint64_t captureNs, uint32_t flags);

	// Publishes the newest frame's pixels again as the next frame, stamped
	// captureNs with flags (issue 29 point 5: a capture slot whose own frame
	// was shed or late keeps the stream at its rate). A copy from slot to
	// slot: no buffer, no allocation. -ENODATA before the first frame.
	int repeatLast(uint64_t captureNs, uint32_t flags);

	// Publishes one frame made in place: makeRow(y, row) writes row y
	// (width * bytesPerPixel bytes) straight into the slot, so the frame
	// needs no buffer of its own beside the ring (issue 15: the lecturer
	// layer, 1.2 MB at 640x480). Readers see the slot busy until the last
	// row is made. Returns as write(), without -EINVAL.
	template<typename MakeRow>
	int writeRows(MakeRow &&makeRow, uint64_t captureNs, uint32_t flags)
	{
		LentSlot slot;
		const int guarded = lend(slot, captureNs, flags);
		if (guarded < 0 && guarded != -EUCLEAN)
			return guarded;
		for (int y = 0; y < height_; y++)
			makeRow(y, slot.pixels + static_cast<size_t>(y) * static_cast<size_t>(slot.stride));
		commit(0);
		return guarded;
	}

	// The next slot's pixels, lent to be written in place (issue 29 §2: a
	// frame written once, where it goes). holds: the tag the last commit()
	// of this slot gave, if the slot still holds what was written then (0:
	// unknown, write it whole); the slots' tags go with their pixels
	// (repeatLast() copies them along).
	struct LentSlot {
		uint8_t *pixels = nullptr;
		int stride = 0; // bytes between rows
		uint64_t holds = 0;
	};
	// Marks the next slot busy (readers skip it) and lends it. Returns as
	// write(), without -EINVAL; on failure nothing is lent. Then exactly
	// one of commit() (the frame is published: the newest, whole) or
	// abandon() (a failure mid-way: never seen, the newest frame stays the
	// last committed one), with no other write in between.
	int lend(LentSlot &slot, uint64_t captureNs, uint32_t flags);
	// holds: a tag for what was written (0 for none), given back by lend().
	void commit(uint64_t holds);
	void abandon();

	// Marks the stream offline and unmaps. The object stays, holding the last
	// frames, until the next open() (this process or a restarted one)
	// replaces it, or remove() or an open() under another name retires it.
	void close();

	// Closes, then retires the object this writer created (generation 0,
	// offline: readers mapping it get -ESTALE, and -ENOENT when they open
	// the name again) and removes its name, unless another writer has taken
	// the name over meanwhile. open() under a new name does this to the old
	// one once the new one is there (a failed open keeps the old one, for
	// the daemon to go back to), so a rename leaves nothing behind in
	// /dev/shm; the daemon does it on a clean stop. Nothing to do when this
	// writer created none.
	void remove();

	// Closes, then removes the object's name (clean shutdown, tests).
	// Returns 0 or a negative errno (-ENOENT if already gone).
	int unlink();

	// Samples the readers' heartbeats (hal/depthkey_shm.h) at nowNs
	// (CLOCK_MONOTONIC) and returns how many are present: their beat
	// counter moved within DK_SHM_READER_TIMEOUT_MS. A slot that stopped
	// beating is freed. Call it at least every 250 ms so that a dead reader
	// is counted gone within 2 s. One pread (a pwrite per slot freed):
	// never waits, never faults (hal/shm_ring_presence.cpp). A shrunk
	// presence object is resized; the next write() reports it.
	int countReaders(uint64_t nowNs);

	bool isOpen() const { return header_ != nullptr; }
	const std::string &name() const { return name_; }
	int width() const { return width_; }
	int height() const { return height_; }
	uint32_t fourcc() const { return fourcc_; }
	int stride() const { return stride_; }
	int slots() const { return slots_; }
	uint64_t generation() const { return generation_; }
	uint64_t frameCount() const { return frame_; }

	// The last failure: 0 or a negative errno, and a sentence naming the
	// object ("/depthkey.composite: chgrp to 'video': no such group").
	int error() const { return error_; }
	std::string describeError() const;

private:
	int fail(int error, const char *step, const char *reason = nullptr);
	int resolveGroup(const std::string &group, unsigned int *gid);
	int retireStale(const std::string &name);
	// retireStale() on an object we created, leaving error() as it was.
	void retireName(const std::string &name);
	// 0 with out holding the new object, or a negative errno.
	int createFresh(const std::string &name, unsigned int gid, const std::string &group, mode_t mode,
			UniqueFd &out);
	// The presence object: a stale one removed (retireStale), a fresh one
	// created and sized.
	int removePresence(const std::string &name);
	int createPresence(const std::string &name, unsigned int gid, const std::string &group);
	void writeHeader();
	// Before each frame: 0 when the object still has its size and the
	// header its fields; else repairs them (size restored, header
	// rewritten under a new generation) and returns -EUCLEAN, or another
	// negative errno (and nothing may be written) when it could not.
	int guard();
	// The first header field not as writeHeader() left it, "" for none.
	std::string headerChange() const;
	// The seqlock's two halves around a frame's payload: the slot of frame
	// frame_ + 1 marked busy and its fields set (returns its pixels), then
	// marked done and made the latest.
	uint8_t *beginFrame(uint64_t captureNs, uint32_t flags);
	// The slot the next frame goes to (lent until committed or abandoned).
	size_t nextSlot() const { return size_t((frame_ + 1) % static_cast<uint64_t>(slots_)); }
	void endFrame();

	std::string name_;
	std::string created_; // the object we created and have not removed, "" none
	UniqueFd fd_; // held for the writer lock
	UniqueFd presenceFd_; // the readers' object: pread/pwrite only
	dk_shm_header *header_ = nullptr;
	uint8_t *data_ = nullptr;
	uint64_t readerOffset_ = 0; // the table's offset in the presence object
	uint64_t dataOffset_ = 0;
	// Bytes pread() found in a shrunk presence object (resized since),
	// reported by the next write(); -1 = nothing to report.
	int64_t presenceShrunkTo_ = -1;
	// What countReaders() saw of each slot last, and since when.
	struct ReaderSeen {
		uint64_t owner = 0;
		uint64_t beats = 0;
		uint64_t sinceNs = 0;
	};
	std::array<ReaderSeen, 16> readerSeen_{};
	size_t mapSize_ = 0;
	size_t presenceSize_ = 0;
	// Per slot: the tag of what commit() wrote there (LentSlot::holds), 0
	// when unknown (a fresh or repaired object, a frame from write()).
	std::array<uint64_t, 8> holds_{};
	bool lent_ = false;

	int width_ = 0;
	int height_ = 0;
	uint32_t fourcc_ = 0;
	int stride_ = 0;
	int slots_ = 0;
	uint64_t slotSize_ = 0;
	uint64_t generation_ = 0;
	uint64_t frame_ = 0;

	// Static strings, so that failing in write() needs no allocation.
	int error_ = 0;
	const char *failedStep_ = "";
	const char *reason_ = nullptr; // replaces strerror() when set
	std::string detail_;           // e.g. the group name
};

} // namespace depthkey
