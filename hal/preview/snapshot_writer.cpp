#include "hal/preview/snapshot_writer.hpp"

#include "hal/preview/stage_picture.hpp"

#include <cerrno>
#include <sys/stat.h>

namespace depthkey {

int writeStageImages(const std::string &dir, const std::string &prefix, const StageImages &stages,
		     std::string &error)
{
	if (mkdir(dir.c_str(), 0755) < 0 && errno != EEXIST) {
		int ret = -errno;
		error = dir + ": cannot create folder";
		return ret;
	}
	for (const StageImage &stage : stages.items()) {
		StagePicture picture = drawStagePicture(stage);
		if (picture.empty())
			continue;
		if (int ret = writeStagePicturePng(dir + "/" + prefix + stage.name + ".png", picture, error); ret < 0)
			return ret;
	}
	return 0;
}

} // namespace depthkey
