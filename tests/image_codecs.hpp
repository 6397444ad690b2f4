// Tests that read or write image files (PNG, JPEG) need OpenCV's imgcodecs.
// The arm64 cross build has none (DEPTHKEY_NO_IMGCODECS, docs/arm64.md:
// Debian 12's libopencv-imgcodecs406:arm64 cannot be installed beside the
// amd64 one), so there those tests skip, saying why, rather than fail on a
// codec that is not there. Everywhere else the macro does nothing.
#pragma once

#include <gtest/gtest.h>

#if defined(DEPTHKEY_NO_IMGCODECS)
#define SKIP_WITHOUT_IMAGE_CODECS()                                                                      \
	GTEST_SKIP() << "this build has no image codecs: libopencv-imgcodecs406:arm64 cannot be installed " \
			"beside amd64's (libgdal32 is not Multi-Arch: same); docs/arm64.md"
#else
#define SKIP_WITHOUT_IMAGE_CODECS() static_cast<void>(0)
#endif
