// FrameSink backend for the recorder: one shared-memory ring per stream,
// settings.compositeName as RGB24, settings.lecturerName as RGBA32 and, in
// board geometry, settings.boardLecturerName as RGBA32.
#pragma once

#include "hal/frame_sink.hpp"
#include "hal/kernel_path_env.hpp"
#include "hal/shm_ring_writer.hpp"

namespace depthkey {

class ShmFrameSink : public FrameSink
{
public:
	int open(const OutputSettings &settings, int width, int height, int boardWidth = 0,
		 int boardHeight = 0) override;
	int publishComposite(const RgbImage &image, uint64_t captureNs, uint32_t flags) override;
	int publishComposite(const CompositeInputs &inputs, uint64_t captureNs, uint32_t flags) override;
	int publishLecturer(const RgbImage *colour, const Gray8Image &alpha, uint64_t captureNs,
			    uint32_t flags) override;
	int publishBoardLecturer(const RgbaImage &image, uint64_t captureNs, uint32_t flags) override;
	int publishBoard(BoardFrameMaker &maker, uint64_t captureNs, uint32_t flags) override;
	int repeatLast(uint64_t captureNs, uint32_t flags) override;
	ReaderCounts countReaders(uint64_t nowNs) override;
	void close() override;
	void remove() override;
	std::string describeError() const override;

	// For tests and status reports.
	const ShmRingWriter &composite() const { return composite_; }
	const ShmRingWriter &lecturer() const { return lecturer_; }
	const ShmRingWriter &boardLecturer() const { return boardLecturer_; }

private:
	template<typename Image>
	int publish(ShmRingWriter &writer, const Image &image, uint64_t captureNs, uint32_t flags);
	// -EINVAL and the mismatch noted when width x height is not the writer's.
	int checkSize(const ShmRingWriter &writer, int width, int height);
	// A writer's result, its failure noted for describeError(); returns ret.
	int noteWrite(const ShmRingWriter &writer, int ret);

	ShmRingWriter composite_;
	ShmRingWriter lecturer_;
	ShmRingWriter boardLecturer_;   // open only in board geometry
	KernelPath path_ = kernelPathFromEnvironment(); // the lecturer layer's rows
	// The writer that failed last, or null when the failure was our own
	// (sizeMismatch_) or there was none.
	const ShmRingWriter *failed_ = nullptr;
	const ShmRingWriter *sizeMismatch_ = nullptr;
	int mismatchWidth_ = 0;
	int mismatchHeight_ = 0;
};

} // namespace depthkey
