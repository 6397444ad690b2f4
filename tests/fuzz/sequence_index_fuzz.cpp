// libFuzzer harness: a recorded sequence's index file (rgb.txt, depth.txt...).
// Invariants: timestamps never go backwards in an accepted index, and a
// refused one says where (path:line).
#include "hal/recording/sequence_reader.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	using namespace depthkey;
	std::string_view text(reinterpret_cast<const char *>(data), size);
	std::vector<SequenceEntry> index;
	std::string error;
	int ret = parseSequenceIndex(text, "rgb.txt", index, error);
	if (ret < 0 && error.rfind("rgb.txt:", 0) != 0)
		std::abort();
	for (size_t i = 1; ret == 0 && i < index.size(); i++)
		if (index[i].timestampNs < index[i - 1].timestampNs)
			std::abort();
	return 0;
}
