// depthkey-calibrate --live: one camera's search for the pattern, run on a
// thread of its own so that the loop reading the cameras (and the view's
// timeout) goes on while it runs (issue 31 point 12: a search ran for
// minutes on a frame full of blobs, and with it on the loop the per-view
// timeout never came). One search at a time: frames that come meanwhile
// are not searched, the newest is when the search is done.
#pragma once

#include "algo/circle_grid_detector.hpp"

#include <cstdint>
#include <functional>
#include <future>
#include <vector>

namespace depthkey {

class BackgroundGridSearch
{
public:
	// Fills the centres and returns 0, or a negative errno (not found).
	using Search = std::function<int(std::vector<ImagePoint> &)>;

	// Waits for a search still running (bounded: circle_grid_detector.hpp).
	~BackgroundGridSearch();

	bool busy() const { return result_.valid(); }
	// Starts search on a worker for the frame taken at timeNs; does nothing
	// while one runs. The search must own what it reads (a copy of the frame).
	void start(Search search, uint64_t timeNs);
	// True once a search is done, with what it found: found, the centres
	// (when found) and the frame's time.
	bool done(bool &found, std::vector<ImagePoint> &centres, uint64_t &timeNs);

private:
	std::future<int> result_;
	std::vector<ImagePoint> centres_; // the worker's until result_ is ready
	uint64_t timeNs_ = 0;
};

} // namespace depthkey
