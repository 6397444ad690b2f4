#include "hal/shm_ring_writer.hpp"

#include "hal/depthkey_shm.h"
#include "hal/shm_name.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <grp.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace depthkey {

static_assert(DK_SHM_MAX_SLOTS <= 8, "ShmRingWriter::holds_ has a tag per slot");

namespace {

// Group read-only: a reader that could write the object could shrink it
// under our mapping (SIGBUS) or scribble on the header (issue 31). Others
// get nothing.
constexpr mode_t kMode = 0640;

uint64_t roundUp(uint64_t value, uint64_t align)
{
	return (value + align - 1) / align * align;
}

// Pixels start on a page of their own (DMA, mapping slots alone).
uint64_t pageAlign()
{
	long page = sysconf(_SC_PAGESIZE);
	return page > static_cast<long>(DK_SHM_DATA_ALIGN) ? static_cast<uint64_t>(page) : DK_SHM_DATA_ALIGN;
}

// Wall-clock time differs across restarts, even of a process that gets the
// same pid back; the pid separates two writers started in the same ns.
uint64_t newGeneration(uint64_t previous)
{
	timespec ts{};
	clock_gettime(CLOCK_REALTIME, &ts);
	uint64_t gen = (static_cast<uint64_t>(ts.tv_sec) * 1000000000u +
			static_cast<uint64_t>(ts.tv_nsec)) ^ static_cast<uint64_t>(getpid());
	while (gen == 0 || gen == previous)
		gen++;
	return gen;
}

} // namespace

ShmRingWriter::~ShmRingWriter()
{
	close();
}

int ShmRingWriter::fail(int error, const char *step, const char *reason)
{
	error_ = error;
	failedStep_ = step;
	reason_ = reason;
	return error;
}

std::string ShmRingWriter::describeError() const
{
	if (error_ == 0)
		return {};
	std::string text = name_.empty() ? std::string("shm ring") : name_;
	text += ": ";
	text += failedStep_;
	if (!detail_.empty())
		text += " '" + detail_ + "'";
	text += ": ";
	text += reason_ ? reason_ : std::strerror(-error_);
	return text;
}

// Accepts a group name or a numeric gid.
int ShmRingWriter::resolveGroup(const std::string &group, unsigned int *gid)
{
	char *end = nullptr;
	unsigned long number = std::strtoul(group.c_str(), &end, 10);
	if (!group.empty() && *end == '\0') {
		*gid = static_cast<unsigned int>(number);
		return 0;
	}

	long hint = sysconf(_SC_GETGR_R_SIZE_MAX);
	std::vector<char> buffer(hint > 0 ? static_cast<size_t>(hint) : 1024);
	struct group entry{};
	struct group *result = nullptr;
	int ret;
	while ((ret = getgrnam_r(group.c_str(), &entry, buffer.data(), buffer.size(),
				 &result)) == ERANGE)
		buffer.resize(buffer.size() * 2);

	detail_ = group;
	if (ret)
		return fail(-ret, "look up group");
	if (!result)
		return fail(-ENOENT, "chgrp to", "no such group");
	*gid = result->gr_gid;
	detail_.clear();
	return 0;
}

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
		return removePresence(name); // a crash between the two unlinks
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
	return ret ? fail(ret, "unlink the stale object") : removePresence(name);
}

// O_EXCL: the object is ours from its first byte. Created 0600, then group
// and mode are applied through the fd, so nobody outside the group can open
// it in between, and the umask cannot narrow the mode.
int ShmRingWriter::createFresh(const std::string &name, unsigned int gid, const std::string &group, mode_t mode,
				UniqueFd &out)
{
	UniqueFd fd(shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600));
	if (!fd.isValid())
		return fail(-errno, "create",
			    errno == EEXIST ? "created by someone else meanwhile: try again" : nullptr);
	static constexpr const char *kChgrp = "chgrp to";
	const char *step = nullptr;
	struct stat st{};
	// fchown only when the new object is not in the group yet: the packaged
	// service's seccomp filter (~@privileged) refuses fchown even to our own
	// group, and a fresh object already has our egid.
	if (flock(fd.get(), LOCK_EX | LOCK_NB) < 0)
		step = "lock";
	else if (fstat(fd.get(), &st) < 0)
		step = "fstat";
	else if (st.st_gid != gid && fchown(fd.get(), static_cast<uid_t>(-1), gid) < 0)
		step = kChgrp;
	else if (fchmod(fd.get(), mode) < 0)
		step = "chmod";
	if (step) {
		int err = -errno; // before anything else may change errno
		if (step == kChgrp)
			detail_ = group.empty() ? std::to_string(gid) : group;
		fd.reset();
		shm_unlink(name.c_str());
		return fail(err, step);
	}
	out = std::move(fd);
	return 0;
}

int ShmRingWriter::open(const std::string &name, int width, int height, uint32_t fourcc,
			int slots, const std::string &group)
{
	// Renamed: the old object would stay in /dev/shm (RAM) for good.
	const std::string renamedFrom = created_ != name ? created_ : std::string();
	close();
	name_ = name;
	error_ = 0;
	detail_.clear();

	const uint32_t bpp = dk_shm_bytes_per_pixel(fourcc);
	if (const char *problem = shmNameProblem(name); *problem)
		return fail(-EINVAL, "invalid object name", problem);
	if (width < 1 || height < 1 || width > static_cast<int>(DK_SHM_MAX_DIMENSION) ||
	    height > static_cast<int>(DK_SHM_MAX_DIMENSION))
		return fail(-EINVAL, "invalid frame size");
	if (bpp == 0)
		return fail(-EINVAL, "unsupported pixel format");
	if (slots < static_cast<int>(DK_SHM_MIN_SLOTS) || slots > static_cast<int>(DK_SHM_MAX_SLOTS))
		return fail(-EINVAL, "slot count outside 2..8");

	unsigned int gid = 0;
	if (!group.empty()) {
		int ret = resolveGroup(group, &gid);
		if (ret)
			return ret;
	}

	const int stride = width * static_cast<int>(bpp);
	const uint64_t slotSize = roundUp(static_cast<uint64_t>(stride) * height, DK_SHM_DATA_ALIGN);
	const uint64_t dataOffset = roundUp(sizeof(dk_shm_header), pageAlign());
	const uint64_t needed = dataOffset + slotSize * slots;

	int ret = retireStale(name);
	if (ret)
		return ret;
	const unsigned int ownerGid = group.empty() ? getegid() : gid;
	UniqueFd fd;
	ret = createFresh(name, ownerGid, group, kMode, fd);
	if (ret)
		return ret;
	// On a failure from here the object is unlinked and fd closes itself.
	if (ftruncate(fd.get(), static_cast<off_t>(needed)) < 0) {
		int err = -errno;
		shm_unlink(name.c_str());
		return fail(err, "size");
	}

	void *map = mmap(nullptr, needed, PROT_READ | PROT_WRITE, MAP_SHARED, fd.get(), 0);
	if (map == MAP_FAILED) {
		int err = -errno;
		shm_unlink(name.c_str());
		return fail(err, "mmap");
	}
	// Before the header is written: a reader that finds the header finds
	// the presence object too.
	ret = createPresence(name, ownerGid, group);
	if (ret) {
		munmap(map, needed);
		shm_unlink(name.c_str());
		return ret;
	}

	fd_ = std::move(fd);
	created_ = name;
	header_ = static_cast<dk_shm_header *>(map);
	data_ = static_cast<uint8_t *>(map) + dataOffset;
	readerOffset_ = 0;
	dataOffset_ = dataOffset;
	readerSeen_ = {};
	presenceShrunkTo_ = -1;
	mapSize_ = needed;
	width_ = width;
	height_ = height;
	fourcc_ = fourcc;
	stride_ = stride;
	slots_ = slots;
	slotSize_ = slotSize;
	frame_ = 0;
	writeHeader();
	if (!renamedFrom.empty())
		retireName(renamedFrom);
	return 0;
}

// The header has its own seqlock: generation 0 while the fields change, then
// the new generation. Readers that raced with us see 0 or a new value and
// retry; readers still on the old generation get -ESTALE.
void ShmRingWriter::writeHeader()
{
	dk_shm_header *h = header_;
	const uint64_t previous = __atomic_load_n(&h->generation, __ATOMIC_RELAXED);

	__atomic_store_n(&h->generation, 0, __ATOMIC_RELAXED);
	__atomic_thread_fence(__ATOMIC_RELEASE);

	h->magic = DK_SHM_MAGIC;
	h->version = DK_SHM_VERSION;
	h->header_size = sizeof(dk_shm_header);
	h->slot_count = static_cast<uint32_t>(slots_);
	h->width = static_cast<uint32_t>(width_);
	h->height = static_cast<uint32_t>(height_);
	h->stride = static_cast<uint32_t>(stride_);
	h->fourcc = fourcc_;
	h->slot_size = slotSize_;
	h->data_offset = dataOffset_;
	h->reader_slots = DK_SHM_MAX_READERS;
	h->reader_offset = readerOffset_;
	// header_size, magic, version and the reserved bytes too: the header
	// may be rewritten after someone scribbled on it (guard()).
	std::memset(h->reserved, 0, sizeof(h->reserved));
	__atomic_store_n(&h->latest_frame, 0, __ATOMIC_RELAXED);
	for (dk_shm_slot &slot : h->slots) {
		// Sequence numbers only ever grow; an odd one left by a writer
		// that died mid-frame is closed here.
		uint32_t seq = __atomic_load_n(&slot.sequence, __ATOMIC_RELAXED);
		__atomic_store_n(&slot.sequence, (seq + 1) & ~1u, __ATOMIC_RELAXED);
		__atomic_store_n(&slot.frame, 0, __ATOMIC_RELAXED);
		__atomic_store_n(&slot.timestamp_ns, 0, __ATOMIC_RELAXED);
		__atomic_store_n(&slot.flags, 0, __ATOMIC_RELAXED);
		__atomic_store_n(&slot.payload_bytes, 0, __ATOMIC_RELAXED);
	}
	__atomic_store_n(&h->online, 1, __ATOMIC_RELAXED);
	holds_.fill(0); // a repair may have zeroed the pixels (ftruncate)

	generation_ = newGeneration(previous);
	__atomic_store_n(&h->generation, generation_, __ATOMIC_RELEASE);
}

int ShmRingWriter::write(const uint8_t *pixels, int srcStride, uint64_t captureNs, uint32_t flags)
{
	if (header_ && (!pixels || srcStride < stride_))
		return fail(-EINVAL, "write with a bad source buffer");
	const size_t rowBytes = static_cast<size_t>(stride_);
	LentSlot slot;
	const int guarded = lend(slot, captureNs, flags);
	if (guarded < 0 && guarded != -EUCLEAN)
		return guarded;
	if (static_cast<size_t>(srcStride) == rowBytes) {
		std::memcpy(slot.pixels, pixels, rowBytes * height_);
	} else {
		for (int y = 0; y < height_; y++)
			std::memcpy(slot.pixels + y * rowBytes, pixels + static_cast<size_t>(y) * srcStride, rowBytes);
	}
	commit(0);
	return guarded;
}

int ShmRingWriter::repeatLast(uint64_t captureNs, uint32_t flags)
{
	if (header_ && frame_ == 0)
		return fail(-ENODATA, "repeat before the first frame");
	// The same check as write() (lend()): a shrunk object would SIGBUS the copy.
	LentSlot slot;
	const int guarded = lend(slot, captureNs, flags);
	if (guarded < 0 && guarded != -EUCLEAN)
		return guarded;
	// Slots >= 2: the newest frame's slot is not the one written next.
	const uint64_t last = frame_ % static_cast<uint64_t>(slots_);
	std::memcpy(slot.pixels, data_ + last * slotSize_, static_cast<size_t>(stride_) * height_);
	commit(holds_[last]); // the same pixels, the same tag
	return guarded;
}

int ShmRingWriter::lend(LentSlot &slot, uint64_t captureNs, uint32_t flags)
{
	if (!header_)
		return fail(-EBADF, "write to a closed ring");
	if (lent_)
		abandon(); // a caller that neither committed nor abandoned
	const int guarded = guard();
	if (guarded < 0 && guarded != -EUCLEAN)
		return guarded;
	slot.pixels = beginFrame(captureNs, flags);
	slot.stride = stride_;
	slot.holds = holds_[nextSlot()];
	lent_ = true;
	return guarded;
}

void ShmRingWriter::commit(uint64_t holds)
{
	if (!lent_)
		return;
	lent_ = false;
	holds_[nextSlot()] = holds;
	endFrame();
}

// The slot's frame number 0 and its sequence even again: a reader never
// picks it (latest_frame still names the last committed frame, in
// another slot), and one that raced with us drops its copy; the frame
// number is not used up.
void ShmRingWriter::abandon()
{
	if (!lent_)
		return;
	lent_ = false;
	dk_shm_slot &slot = header_->slots[nextSlot()];
	holds_[nextSlot()] = 0;
	__atomic_store_n(&slot.frame, 0, __ATOMIC_RELAXED);
	const uint32_t seq = __atomic_load_n(&slot.sequence, __ATOMIC_RELAXED);
	__atomic_store_n(&slot.sequence, seq + 1, __ATOMIC_RELEASE);
}

uint8_t *ShmRingWriter::beginFrame(uint64_t captureNs, uint32_t flags)
{
	const uint64_t frame = frame_ + 1;
	const uint32_t index = static_cast<uint32_t>(frame % static_cast<uint64_t>(slots_));
	dk_shm_slot &slot = header_->slots[index];

	// Seqlock writer side: odd sequence, release fence, payload, even
	// sequence with release (endFrame). A reader that copied any byte of
	// this payload then sees the sequence change and drops its copy.
	const uint32_t seq = __atomic_load_n(&slot.sequence, __ATOMIC_RELAXED);
	__atomic_store_n(&slot.sequence, seq + 1, __ATOMIC_RELAXED);
	__atomic_thread_fence(__ATOMIC_RELEASE);

	__atomic_store_n(&slot.frame, frame, __ATOMIC_RELAXED);
	__atomic_store_n(&slot.timestamp_ns, captureNs, __ATOMIC_RELAXED);
	__atomic_store_n(&slot.flags, flags, __ATOMIC_RELAXED);
	__atomic_store_n(&slot.payload_bytes, static_cast<uint64_t>(stride_) * height_, __ATOMIC_RELAXED);
	return data_ + index * slotSize_;
}

void ShmRingWriter::endFrame()
{
	const uint64_t frame = frame_ + 1;
	dk_shm_slot &slot = header_->slots[frame % static_cast<uint64_t>(slots_)];
	const uint32_t seq = __atomic_load_n(&slot.sequence, __ATOMIC_RELAXED);
	__atomic_store_n(&slot.sequence, seq + 1, __ATOMIC_RELEASE);
	__atomic_store_n(&header_->latest_frame, frame, __ATOMIC_RELEASE);
	frame_ = frame;
}

void ShmRingWriter::close()
{
	if (!header_)
		return;
	abandon();
	__atomic_store_n(&header_->online, 0, __ATOMIC_RELEASE);
	munmap(header_, mapSize_);
	fd_.reset(); // releases the writer lock
	presenceFd_.reset();
	header_ = nullptr;
	data_ = nullptr;
	mapSize_ = 0;
}

int ShmRingWriter::unlink()
{
	close();
	if (created_ == name_)
		created_.clear();
	if (name_.empty())
		return fail(-EINVAL, "unlink an unnamed ring");
	const int ret = shm_unlink(name_.c_str()) < 0 ? -errno : 0;
	shm_unlink(shmPresenceName(name_).c_str()); // ours, or gone already
	return ret ? fail(ret, "shm_unlink") : 0;
}

} // namespace depthkey
