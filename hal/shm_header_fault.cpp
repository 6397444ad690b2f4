#include "hal/shm_header_fault.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>

namespace depthkey {

namespace {

std::string outOfRange(const char *field, uint64_t value, const std::string &expected)
{
	return std::string(field) + " = " + std::to_string(value) + " (expected " + expected + ")";
}

} // namespace

// The same rules as dk_shm_check_layout, one field at a time, in the order a
// reader depends on them: each bound makes the next product safe.
std::string shmHeaderFault(const dk_shm_header &h, uint64_t objectSize)
{
	if (h.magic != DK_SHM_MAGIC)
		return outOfRange("magic", h.magic, std::to_string(DK_SHM_MAGIC));
	if (h.version != DK_SHM_VERSION)
		return outOfRange("version", h.version, std::to_string(DK_SHM_VERSION));
	if (h.header_size != sizeof(dk_shm_header))
		return outOfRange("header_size", h.header_size, std::to_string(sizeof(dk_shm_header)));
	const uint32_t bpp = dk_shm_bytes_per_pixel(h.fourcc);
	if (bpp == 0)
		return outOfRange("fourcc", h.fourcc, "RGB3 or AB24");
	const std::string dimensions = "1.." + std::to_string(DK_SHM_MAX_DIMENSION);
	if (h.width == 0 || h.width > DK_SHM_MAX_DIMENSION)
		return outOfRange("width", h.width, dimensions);
	if (h.height == 0 || h.height > DK_SHM_MAX_DIMENSION)
		return outOfRange("height", h.height, dimensions);
	const uint64_t minStride = static_cast<uint64_t>(h.width) * bpp;
	if (h.stride < minStride || h.stride > 4 * DK_SHM_MAX_DIMENSION)
		return outOfRange("stride", h.stride, std::to_string(minStride) + ".." +
					   std::to_string(4 * DK_SHM_MAX_DIMENSION));
	if (h.slot_count < DK_SHM_MIN_SLOTS || h.slot_count > DK_SHM_MAX_SLOTS)
		return outOfRange("slot_count", h.slot_count, std::to_string(DK_SHM_MIN_SLOTS) + ".." +
					      std::to_string(DK_SHM_MAX_SLOTS));
	const uint64_t frameBytes = static_cast<uint64_t>(h.stride) * h.height;
	if (h.slot_size < frameBytes || h.slot_size > (uint64_t{ 1 } << 32))
		return outOfRange("slot_size", h.slot_size, std::to_string(frameBytes) + "..2^32");
	if (h.data_offset < sizeof(dk_shm_header) || h.data_offset > objectSize)
		return outOfRange("data_offset", h.data_offset, std::to_string(sizeof(dk_shm_header)) +
					       ".." + std::to_string(objectSize));
	if ((objectSize - h.data_offset) / h.slot_count < h.slot_size)
		return "object size " + std::to_string(objectSize) + " too small for " +
		       std::to_string(h.slot_count) + " slots of " + std::to_string(h.slot_size) +
		       " bytes from data_offset " + std::to_string(h.data_offset);
	if (h.reader_slots == 0 || h.reader_slots > DK_SHM_MAX_READERS)
		return outOfRange("reader_slots", h.reader_slots,
				  "1.." + std::to_string(DK_SHM_MAX_READERS));
	if (h.reader_offset % DK_SHM_DATA_ALIGN || h.reader_offset > DK_SHM_MAX_PRESENCE_OFFSET)
		return outOfRange("reader_offset", h.reader_offset,
				  "a page boundary in the presence object, at most 2^32");
	return "";
}

std::string shmObjectFault(const char *name)
{
	const int fd = shm_open(name, O_RDONLY | O_CLOEXEC, 0);
	if (fd < 0)
		return std::string("cannot open: ") + std::strerror(errno);
	struct stat st {};
	if (fstat(fd, &st) < 0 || st.st_size < static_cast<off_t>(sizeof(dk_shm_header))) {
		close(fd);
		return "object size " + std::to_string(st.st_size) + " smaller than the header (" +
		       std::to_string(sizeof(dk_shm_header)) + " bytes)";
	}
	void *map = mmap(nullptr, sizeof(dk_shm_header), PROT_READ, MAP_SHARED, fd, 0);
	close(fd);
	if (map == MAP_FAILED)
		return std::string("cannot map the header: ") + std::strerror(errno);
	// A copy: the writer may change the fields while they are checked.
	dk_shm_header copy;
	std::memcpy(&copy, map, sizeof(copy));
	munmap(map, sizeof(dk_shm_header));
	return shmHeaderFault(copy, static_cast<uint64_t>(st.st_size));
}

} // namespace depthkey
