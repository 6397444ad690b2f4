// FrameSink for tests of the daemon: keeps the last frame of each stream and
// counts them, and can be told to fail.
#pragma once

#include "algo/composite.hpp"
#include "hal/depthkey_shm.h"
#include "hal/frame_sink.hpp"

#include <algorithm>
#include <cerrno>
#include <unistd.h>

namespace depthkey {

class FakeFrameSink : public FrameSink
{
public:
	int open(const OutputSettings &settings, int width, int height, int boardWidth = 0,
		 int boardHeight = 0) override
	{
		if (failOpen_)
			return failOpen_;
		settings_ = settings;
		width_ = width;
		height_ = height;
		boardWidth_ = boardWidth;
		boardHeight_ = boardHeight;
		open_ = true;
		opens_++;
		return 0;
	}

	int publishComposite(const RgbImage &image, uint64_t captureNs, uint32_t flags) override
	{
		int ret = boardWidth_ ? check(image.width(), image.height(), boardWidth_, boardHeight_)
				      : check(image.width(), image.height());
		if (ret)
			return ret;
		if (publishDelayUs_)
			usleep(publishDelayUs_); // a slow box: keying takes this much longer
		composite_ = image;
		boardHolds_ = 0;
		compositeCount_++;
		noColourCount_ += (flags & DK_SHM_FLAG_COLOUR_OK) == 0;
		captureNs_ = captureNs;
		flags_ = flags;
		return 0;
	}

	int publishComposite(const CompositeInputs &inputs, uint64_t captureNs, uint32_t flags) override
	{
		compositeRoi(*inputs.lecturer, *inputs.alpha, *inputs.board, inputs.roi, inputs.opacityQ8, made_,
			     KernelPath::C);
		return publishComposite(made_, captureNs, flags);
	}

	int publishLecturer(const RgbImage *colour, const Gray8Image &alpha, uint64_t captureNs,
			    uint32_t flags) override
	{
		int ret = check(alpha.width(), alpha.height());
		if (ret)
			return ret;
		if (colour) {
			if (colour->width() != alpha.width() || colour->height() != alpha.height())
				return -EINVAL;
			lecturerLayer(*colour, alpha, lecturer_, KernelPath::C);
		} else {
			lecturer_.resize(alpha.width(), alpha.height());
			std::fill(lecturer_.data(), lecturer_.data() + lecturer_.size(), Rgba8{ 0, 0, 0, 0 });
		}
		lecturerCount_++;
		captureNs_ = captureNs;
		flags_ = flags;
		return 0;
	}

	int publishBoardLecturer(const RgbaImage &image, uint64_t captureNs, uint32_t flags) override
	{
		if (!boardWidth_)
			return -EBADF;
		int ret = check(image.width(), image.height(), boardWidth_, boardHeight_);
		if (ret)
			return ret;
		boardLecturer_ = image;
		boardHolds_ = 0;
		boardLecturerCount_++;
		captureNs_ = captureNs;
		flags_ = flags;
		return 0;
	}

	// Made in place into the images composite() and boardLecturer() show,
	// which hold what the last frame left, as a ring slot does.
	int publishBoard(BoardFrameMaker &maker, uint64_t captureNs, uint32_t flags) override
	{
		if (!boardWidth_)
			return -EBADF;
		if (!open_)
			return -EBADF;
		const bool sized = composite_.width() == boardWidth_ && composite_.height() == boardHeight_ &&
				   boardLecturer_.width() == boardWidth_ && boardLecturer_.height() == boardHeight_;
		if (!sized) {
			composite_.resize(boardWidth_, boardHeight_);
			boardLecturer_.resize(boardWidth_, boardHeight_);
			boardHolds_ = 0;
		}
		boardHolds_ = maker.make({ viewOf(composite_), viewOf(boardLecturer_), boardHolds_ });
		compositeCount_++;
		boardLecturerCount_++;
		boardInPlaceCount_++;
		noColourCount_ += (flags & DK_SHM_FLAG_COLOUR_OK) == 0;
		captureNs_ = captureNs;
		flags_ = flags;
		return 0;
	}

	int repeatLast(uint64_t captureNs, uint32_t flags) override
	{
		if (!compositeCount_)
			return -ENODATA;
		compositeCount_++;
		lecturerCount_++;
		repeatedCount_++;
		captureNs_ = captureNs;
		flags_ = flags;
		return 0;
	}

	ReaderCounts countReaders(uint64_t) override { return readers_; }
	void close() override { open_ = false; }
	void setReaders(ReaderCounts readers) { readers_ = readers; }

	std::string describeError() const override
	{
		return failOpen_ ? "fake sink: told to fail" : std::string();
	}

	void failOpenWith(int error) { failOpen_ = error; }
	void setPublishDelayUs(unsigned us) { publishDelayUs_ = us; }

	bool isOpen() const { return open_; }
	int opens() const { return opens_; }
	int width() const { return width_; }
	int height() const { return height_; }
	int boardWidth() const { return boardWidth_; }
	int boardHeight() const { return boardHeight_; }
	const RgbaImage &boardLecturer() const { return boardLecturer_; }
	uint64_t boardLecturerCount() const { return boardLecturerCount_; }
	// Board-geometry frames made in place (publishBoard()).
	uint64_t boardInPlaceCount() const { return boardInPlaceCount_; }
	const OutputSettings &settings() const { return settings_; }
	const RgbImage &composite() const { return composite_; }
	const RgbaImage &lecturer() const { return lecturer_; }
	uint64_t compositeCount() const { return compositeCount_; }
	// Composites published without the colour camera (NO SIGNAL frames).
	uint64_t noColourCount() const { return noColourCount_; }
	uint64_t lecturerCount() const { return lecturerCount_; }
	uint64_t repeatedCount() const { return repeatedCount_; }
	uint64_t lastCaptureNs() const { return captureNs_; }
	uint32_t lastFlags() const { return flags_; }

private:
	RgbImage made_; // the composite made from its parts, reused
	int check(int width, int height) const { return check(width, height, width_, height_); }
	int check(int width, int height, int wantWidth, int wantHeight) const
	{
		if (!open_)
			return -EBADF;
		return width == wantWidth && height == wantHeight ? 0 : -EINVAL;
	}

	OutputSettings settings_;
	bool open_ = false;
	int failOpen_ = 0;
	unsigned publishDelayUs_ = 0;
	int opens_ = 0;
	int width_ = 0;
	int height_ = 0;
	int boardWidth_ = 0, boardHeight_ = 0;
	RgbImage composite_;
	RgbaImage boardLecturer_;
	uint64_t boardLecturerCount_ = 0;
	uint64_t boardInPlaceCount_ = 0;
	uint64_t boardHolds_ = 0; // what publishBoard()'s maker left in the images
	RgbaImage lecturer_;
	uint64_t compositeCount_ = 0;
	uint64_t noColourCount_ = 0;
	uint64_t lecturerCount_ = 0;
	uint64_t repeatedCount_ = 0;
	uint64_t captureNs_ = 0;
	uint32_t flags_ = 0;
	ReaderCounts readers_;
};

} // namespace depthkey
