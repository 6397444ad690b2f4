// libFuzzer harness: the SR-2 frame parser on any USB transfer. The first
// four bytes choose the distance window, the rest is the transfer.
#include "hal/sr2/sr2_frame_parser.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	using namespace depthkey;
	if (size < 4)
		return 0;
	int minMm = data[0] | data[1] << 8, maxMm = data[2] | data[3] << 8;
	static DepthFrame frame; // reused like the backend does: allocation-free after the first
	Sr2FrameStats stats;
	Sr2FrameCheck check = parseSr2Frame(data + 4, size - 4, minMm, maxMm, frame, stats);
	if (check == Sr2FrameCheck::Ok &&
	    (frame.depthMm.empty() || frame.amplitude.width() != frame.depthMm.width()))
		std::abort();
	(void)sr2FrameCheckName(check);
	return 0;
}
