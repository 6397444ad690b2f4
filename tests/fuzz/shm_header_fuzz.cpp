// libFuzzer harness: the shared-memory reader's validation of a header a
// hostile or broken writer left (hal/depthkey_shm.h). The input is the
// whole object; once dk_shm_check_layout() accepts it, reading the newest
// frame must stay inside the object (ASan checks every byte copied).
#include "hal/depthkey_shm.h"

#include <cstdlib>
#include <cstring>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (size < sizeof(dk_shm_header))
		return 0;
	// An exactly sized heap copy: one byte past it is an ASan report.
	std::vector<uint8_t> object(data, data + size);
	const auto *h = reinterpret_cast<const dk_shm_header *>(object.data());
	dk_shm_reader r{};
	if (dk_shm_check_layout(h, size, &r) != 0)
		return 0;
	r.header = h;
	r.base = object.data();
	r.map_size = size;
	r.generation = h->generation;
	if (r.frame_bytes > (16u << 20))
		return 0; // a valid but huge frame: nothing new to learn, slow to copy
	std::vector<uint8_t> frame(r.frame_bytes);
	dk_shm_frame_info info{};
	uint64_t latest;
	(void)dk_shm_latest(&r, &latest);
	int ret = dk_shm_read_latest(&r, frame.data(), frame.size(), &info);
	if (ret == 0 && info.bytes != r.frame_bytes)
		std::abort();
	return 0;
}
