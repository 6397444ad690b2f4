#include "tools/calibrate_live/background_grid_search.hpp"

#include <chrono>
#include <utility>

namespace depthkey {

BackgroundGridSearch::~BackgroundGridSearch()
{
	if (result_.valid())
		result_.wait();
}

void BackgroundGridSearch::start(Search search, uint64_t timeNs)
{
	if (busy())
		return;
	timeNs_ = timeNs;
	result_ = std::async(std::launch::async,
			     [this, search = std::move(search)] { return search(centres_); });
}

bool BackgroundGridSearch::done(bool &found, std::vector<ImagePoint> &centres, uint64_t &timeNs)
{
	if (!busy() || result_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
		return false;
	found = result_.get() == 0; // get() leaves result_ invalid: not busy
	if (found)
		centres = centres_;
	timeNs = timeNs_;
	return true;
}

} // namespace depthkey
