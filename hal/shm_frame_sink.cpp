#include "hal/shm_frame_sink.hpp"

#include "algo/composite.hpp"
#include "hal/depthkey_shm.h"

#include <algorithm>
#include <cerrno>

namespace depthkey {

int ShmFrameSink::open(const OutputSettings &settings, int width, int height, int boardWidth,
		       int boardHeight)
{
	failed_ = nullptr;
	sizeMismatch_ = nullptr;

	const bool board = boardWidth > 0 && boardHeight > 0;
	int ret = composite_.open(settings.compositeName, board ? boardWidth : width, board ? boardHeight : height,
				  DK_SHM_FORMAT_RGB24, settings.slots, settings.group);
	if (ret) {
		failed_ = &composite_;
		lecturer_.close(); // no half-configured pair from an earlier open
		return ret;
	}
	ret = lecturer_.open(settings.lecturerName, width, height, DK_SHM_FORMAT_RGBA32,
			     settings.slots, settings.group);
	if (ret) {
		failed_ = &lecturer_;
		composite_.close();
		return ret;
	}
	// In camera geometry the board layer's stream is marked offline: a
	// reader sees it is not being fed rather than a frozen old frame.
	if (!board) {
		// Renamed meanwhile: the old name would never be opened again.
		if (boardLecturer_.name() != settings.boardLecturerName)
			boardLecturer_.remove();
		else
			boardLecturer_.close();
		return 0;
	}
	ret = boardLecturer_.open(settings.boardLecturerName, boardWidth, boardHeight, DK_SHM_FORMAT_RGBA32,
				  settings.slots, settings.group);
	if (ret) {
		failed_ = &boardLecturer_;
		composite_.close();
		lecturer_.close();
		return ret;
	}
	return 0;
}

// Rgb8/Rgba8 are packed byte triples/quads, i.e. exactly RGB24/RGBA32 rows.
template<typename Image>
int ShmFrameSink::publish(ShmRingWriter &writer, const Image &image, uint64_t captureNs,
			  uint32_t flags)
{
	static_assert(sizeof(*image.data()) == 3 || sizeof(*image.data()) == 4);

	if (int ret = checkSize(writer, image.width(), image.height()); ret < 0)
		return ret;
	const int stride = image.width() * static_cast<int>(sizeof(*image.data()));
	int ret = writer.write(reinterpret_cast<const uint8_t *>(image.data()), stride, captureNs,
			       flags);
	return noteWrite(writer, ret);
}

int ShmFrameSink::publishComposite(const RgbImage &image, uint64_t captureNs, uint32_t flags)
{
	return publish(composite_, image, captureNs, flags);
}

int ShmFrameSink::noteWrite(const ShmRingWriter &writer, int ret)
{
	if (ret) {
		failed_ = &writer;
		sizeMismatch_ = nullptr;
	}
	return ret;
}

int ShmFrameSink::repeatLast(uint64_t captureNs, uint32_t flags)
{
	// -EUCLEAN (a stream repaired, the frame still written) goes on to
	// the other streams and is returned last, for FrameOutputs to log.
	int repaired = 0;
	for (ShmRingWriter *writer : { &composite_, &lecturer_, &boardLecturer_ }) {
		if (!writer->isOpen())
			continue;
		const int ret = noteWrite(*writer, writer->repeatLast(captureNs, flags));
		if (ret == -EUCLEAN)
			repaired = ret;
		else if (ret < 0)
			return ret;
	}
	return repaired;
}

int ShmFrameSink::checkSize(const ShmRingWriter &writer, int width, int height)
{
	if (!writer.isOpen() || (width == writer.width() && height == writer.height()))
		return 0;
	sizeMismatch_ = &writer;
	failed_ = nullptr;
	mismatchWidth_ = width;
	mismatchHeight_ = height;
	return -EINVAL;
}

int ShmFrameSink::publishComposite(const CompositeInputs &in, uint64_t captureNs, uint32_t flags)
{
	const int width = in.width(), height = in.height();
	if (int ret = checkSize(composite_, width, height); ret < 0)
		return ret;
	// Parts of other sizes than the colour frame would be read past.
	const bool boardFits = in.board->width() == width && (in.board->height() == height || in.board->height() == 1);
	if (in.alpha->width() != width || in.alpha->height() != height || !boardFits) {
		const int ret = checkSize(composite_, boardFits ? in.alpha->width() : in.board->width(),
					  boardFits ? in.alpha->height() : in.board->height());
		return ret < 0 ? ret : -EBADF; // not open: nothing to write to
	}
	int ret = composite_.writeRows([&](int y, uint8_t *row) { compositeRoiRow(in, y, reinterpret_cast<Rgb8 *>(row)); },
				       captureNs, flags);
	return noteWrite(composite_, ret);
}

int ShmFrameSink::publishLecturer(const RgbImage *colour, const Gray8Image &alpha, uint64_t captureNs,
				  uint32_t flags)
{
	if (int ret = checkSize(lecturer_, alpha.width(), alpha.height()); ret < 0)
		return ret;
	if (colour && (colour->width() != alpha.width() || colour->height() != alpha.height())) {
		const int ret = checkSize(lecturer_, colour->width(), colour->height());
		return ret < 0 ? ret : -EBADF; // not open: nothing to write to
	}
	const int width = alpha.width();
	int ret = lecturer_.writeRows(
		[&](int y, uint8_t *row) {
			Rgba8 *out = reinterpret_cast<Rgba8 *>(row);
			if (colour)
				lecturerLayerRow(path_, colour->row(y), alpha.row(y), out, width);
			else
				std::fill(out, out + width, Rgba8{ 0, 0, 0, 0 });
		},
		captureNs, flags);
	return noteWrite(lecturer_, ret);
}

int ShmFrameSink::publishBoardLecturer(const RgbaImage &image, uint64_t captureNs, uint32_t flags)
{
	return publish(boardLecturer_, image, captureNs, flags);
}

// Both slots lent, made, then committed: the composite and the layer
// published within a few stores of each other, each whole, the one never
// without the other (the composite's slot is abandoned when the layer's
// cannot be lent).
int ShmFrameSink::publishBoard(BoardFrameMaker &maker, uint64_t captureNs, uint32_t flags)
{
	if (!boardLecturer_.isOpen())
		return noteWrite(boardLecturer_, -EBADF);
	ShmRingWriter::LentSlot composite, layer;
	const int compositeRet = composite_.lend(composite, captureNs, flags);
	if (compositeRet < 0 && compositeRet != -EUCLEAN)
		return noteWrite(composite_, compositeRet);
	const int layerRet = boardLecturer_.lend(layer, captureNs, flags);
	if (layerRet < 0 && layerRet != -EUCLEAN) {
		composite_.abandon();
		return noteWrite(boardLecturer_, layerRet);
	}
	const BoardTarget target{
		{ reinterpret_cast<Rgb8 *>(composite.pixels), composite_.width(), composite_.height(),
		  static_cast<size_t>(composite.stride) },
		{ reinterpret_cast<Rgba8 *>(layer.pixels), boardLecturer_.width(), boardLecturer_.height(),
		  static_cast<size_t>(layer.stride) },
		composite.holds == layer.holds ? composite.holds : 0 // one frame's pair, or unknown
	};
	const uint64_t holds = maker.make(target);
	composite_.commit(holds);
	boardLecturer_.commit(holds);
	// -EUCLEAN: a stream repaired, the frame published all the same.
	return compositeRet ? noteWrite(composite_, compositeRet) : noteWrite(boardLecturer_, layerRet);
}

ReaderCounts ShmFrameSink::countReaders(uint64_t nowNs)
{
	return { composite_.countReaders(nowNs), lecturer_.countReaders(nowNs), boardLecturer_.countReaders(nowNs) };
}

void ShmFrameSink::close()
{
	composite_.close();
	lecturer_.close();
	boardLecturer_.close();
}

void ShmFrameSink::remove()
{
	composite_.remove();
	lecturer_.remove();
	boardLecturer_.remove();
}

std::string ShmFrameSink::describeError() const
{
	if (sizeMismatch_)
		return sizeMismatch_->name() + ": image " + std::to_string(mismatchWidth_) + "x" +
		       std::to_string(mismatchHeight_) + " does not match the stream's " +
		       std::to_string(sizeMismatch_->width()) + "x" +
		       std::to_string(sizeMismatch_->height());
	if (failed_)
		return failed_->describeError();
	return {};
}

} // namespace depthkey
