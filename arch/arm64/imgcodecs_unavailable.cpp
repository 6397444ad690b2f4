// The arm64 build's OpenCV imgcodecs: every call fails, as imgcodecs does
// for a format it cannot read or write (an empty Mat, false).
//
// Why: Debian 12's libopencv-imgcodecs406:arm64 links libgdal32, which is
// not Multi-Arch: same, so it cannot be installed beside the amd64 one that
// the native build needs (apt would remove it). Image file I/O moves to
// libpng/TurboJPEG (issue 15, the lean half); when it has, this file and
// its lines in the Makefile's ARCH block go. Until then the arm64 daemon
// and tools report "cannot decode" for image files (a value, as for a
// corrupt file), and the tests that need a codec skip on
// DEPTHKEY_NO_IMGCODECS. Built only for ARCH=arm64, into the archive that
// -lopencv_imgcodecs finds there.
#include <opencv2/imgcodecs.hpp>

namespace cv {

Mat imread(const String &, int) { return Mat(); }

bool imwrite(const String &, InputArray, const std::vector<int> &) { return false; }

Mat imdecode(InputArray, int) { return Mat(); }

bool imencode(const String &, InputArray, std::vector<uchar> &buf, const std::vector<int> &)
{
	buf.clear();
	return false;
}

bool haveImageReader(const String &) { return false; }

bool haveImageWriter(const String &) { return false; }

} // namespace cv
