// The writer checks, before each frame, that its object still has its size
// and its header the fields it wrote (issue 31). The output group can no
// longer write either (mode 0640), but the owner or root still can, and
// without this check a shrunk object killed the writer with SIGBUS at its
// next frame, and a header with generation 0 or slot_count 9 made every
// reader refuse the stream while the daemon reported frames and no errors.
// A repair is a new generation, so readers that opened meanwhile (and may
// have copied a changed geometry) re-open. One fstat and a few loads per
// frame; a message (allocation) only when something changed.
#include "hal/shm_ring_writer.hpp"

#include "hal/depthkey_shm.h"
#include "hal/shm_name.hpp"

#include <sys/stat.h>
#include <unistd.h>

namespace depthkey {

std::string ShmRingWriter::headerChange() const
{
	const dk_shm_header &h = *header_;
	auto load = [](const auto &field) { return static_cast<uint64_t>(__atomic_load_n(&field, __ATOMIC_RELAXED)); };
	const struct {
		const char *name;
		uint64_t seen, expected;
	} fields[] = {
		{ "magic", load(h.magic), DK_SHM_MAGIC },
		{ "version", load(h.version), DK_SHM_VERSION },
		{ "header_size", load(h.header_size), sizeof(dk_shm_header) },
		{ "slot_count", load(h.slot_count), static_cast<uint64_t>(slots_) },
		{ "generation", load(h.generation), generation_ },
		{ "width", load(h.width), static_cast<uint64_t>(width_) },
		{ "height", load(h.height), static_cast<uint64_t>(height_) },
		{ "stride", load(h.stride), static_cast<uint64_t>(stride_) },
		{ "fourcc", load(h.fourcc), fourcc_ },
		{ "slot_size", load(h.slot_size), slotSize_ },
		{ "data_offset", load(h.data_offset), dataOffset_ },
		{ "latest_frame", load(h.latest_frame), frame_ },
		{ "online", load(h.online), 1 },
		{ "reader_slots", load(h.reader_slots), DK_SHM_MAX_READERS },
		{ "reader_offset", load(h.reader_offset), readerOffset_ },
	};
	for (const auto &field : fields) {
		// The generation is not named: it changes with every repair, and
		// the journal line would then never repeat (logged once).
		if (field.seen != field.expected)
			return std::string(field.name) + " = " + std::to_string(field.seen) +
			       (field.name == std::string_view("generation") ? std::string(" (not ours)")
									     : " (expected " + std::to_string(field.expected) + ")");
	}
	// Between frames every slot is complete: an odd sequence would make
	// readers drop that slot's copies as torn.
	for (uint32_t i = 0; i < DK_SHM_MAX_SLOTS; i++)
		if (load(h.slots[i].sequence) & 1)
			return "slots[" + std::to_string(i) + "].sequence odd between frames";
	return "";
}

int ShmRingWriter::guard()
{
	struct stat st {};
	if (fstat(fd_.get(), &st) < 0)
		return fail(-errno, "fstat before a frame");
	if (static_cast<uint64_t>(st.st_size) < mapSize_) {
		// Writing now would fault (SIGBUS) past the new end.
		detail_ = std::to_string(st.st_size) + " bytes, expected " + std::to_string(mapSize_);
		if (ftruncate(fd_.get(), static_cast<off_t>(mapSize_)) < 0)
			return fail(-errno, "restore the size of the shrunk object");
		writeHeader();
		return fail(-EUCLEAN, "restored the size of the object",
			    "someone truncated it; header rewritten, readers re-open");
	}
	if (std::string change = headerChange(); !change.empty()) {
		detail_ = std::move(change);
		writeHeader();
		return fail(-EUCLEAN, "rewrote the header, field",
			    "someone else wrote to it; readers re-open");
	}
	if (presenceShrunkTo_ >= 0) {
		detail_ = shmPresenceName(name_) + ": " + std::to_string(presenceShrunkTo_) + " bytes";
		presenceShrunkTo_ = -1;
		return fail(-EUCLEAN, "restored the size of the readers' object",
			    "someone truncated it; readers claim their slots again");
	}
	return 0;
}

} // namespace depthkey
