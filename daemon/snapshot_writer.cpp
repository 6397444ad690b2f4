#include "daemon/snapshot_writer.hpp"

#include "hal/preview/stage_picture.hpp"

#include <cerrno>
#include <opencv2/imgcodecs.hpp>
#include <sys/stat.h>

namespace depthkey {

namespace {

bool writePng(const std::string &path, const cv::Mat &mat, std::string &error)
{
	bool ok = false;
	try {
		ok = cv::imwrite(path, mat);
	} catch (const cv::Exception &e) {
		error = path + ": " + e.what();
		return false;
	}
	if (!ok)
		error = path + ": cannot write";
	return ok;
}

} // namespace

int writeStageImages(const std::string &dir, const std::string &prefix, const StageImages &stages,
		     std::string &error)
{
	if (mkdir(dir.c_str(), 0755) < 0 && errno != EEXIST) {
		int ret = -errno;
		error = dir + ": cannot create folder";
		return ret;
	}
	for (const StageImage &stage : stages.items()) {
		cv::Mat picture = drawStagePicture(stage);
		if (picture.empty())
			continue;
		if (!writePng(dir + "/" + prefix + stage.name + ".png", picture, error))
			return -EIO;
	}
	return 0;
}

} // namespace depthkey
