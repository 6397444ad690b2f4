#include "hal/sim/lecture_script.hpp"

#include "hal/sim/hash_noise.hpp"

#include <algorithm>
#include <cmath>

namespace depthkey::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Handwriting: two lines of 40 cm, cursive loops 2.8 cm apart, letters 4.5 cm.
constexpr int kLines = 2;
constexpr int kMaxWords = 4;
constexpr double kLineWidthM = 0.40;
constexpr double kLineGapM = 0.16;
constexpr double kLetterM = 0.045;
constexpr double kLoopPitchM = 0.028;
constexpr double kLineWriteS = 2.4;
constexpr double kLineReturnS = 0.35;  // pen lifted, back to the next line
constexpr double kStrokeRadiusM = 0.005; // 1 cm wide chalk line

// Where the lecturer stands: talking a step from the desk line, writing an
// arm's length from the board, the pelvis this far left of the writing hand.
constexpr double kTalkFromBoardM = 0.70;
constexpr double kWriteFromBoardM = 0.45;
constexpr double kReachLeftM = 0.28;
constexpr double kTalkS = 1.6, kEraseS = 1.6;

const Rgb8 kInk[4] = { { 0, 0, 0 }, { 236, 236, 226 }, { 236, 214, 92 }, { 120, 200, 232 } };

double jitter(uint64_t seed, uint64_t what, double amplitude)
{
	return (uniformFromHash(hashKey(seed, what)) * 2.0 - 1.0) * amplitude;
}

Rgb8 slideColour(uint64_t slide, double x, double y)
{
	const Rgb8 board{ 28, 33, 31 };
	switch (slide % 3) {
	case 1: // a title bar and a picture on the right
		if (y < -0.66)
			return { 52, 62, 104 };
		if (x > 0.55 && x < 1.25 && y > -0.30 && y < 0.25)
			return { static_cast<uint8_t>(70 + 40 * (y + 0.3)), 92, 80 };
		return board;
	case 2: // a framed diagram area in the middle
		if (std::fabs(x + 0.1) < 0.5 && y > 0.02 && y < 0.40)
			return (std::fabs(x + 0.1) > 0.49 || y < 0.03 || y > 0.39) ? Rgb8{ 150, 150, 150 }
										  : Rgb8{ 36, 44, 52 };
		return board;
	default:
		return board;
	}
}

} // namespace

const Rgb8 *LectureScript::inkColours()
{
	return kInk;
}

void LectureScript::addPhase(LecturerAction action, double duration, double x1, double z1,
			     double yaw, int session)
{
	ScriptPhase p;
	p.action = action;
	p.start = phases_.empty() ? 0.0 : phases_.back().end;
	p.end = p.start + duration;
	p.x0 = phases_.empty() ? x1 : phases_.back().x1;
	p.z0 = phases_.empty() ? z1 : phases_.back().z1;
	p.x1 = x1;
	p.z1 = z1;
	p.yaw = yaw;
	p.session = session;
	phases_.push_back(p);
}

void LectureScript::walkTo(double x, double z)
{
	const ScriptPhase &last = phases_.back();
	double distance = std::hypot(x - last.x1, z - last.z1);
	// Facing the way they walk: yaw -pi/2 walks towards +x.
	double yaw = x >= last.x1 ? -kPi / 2 : kPi / 2;
	addPhase(LecturerAction::Walk, std::max(0.8, distance / walkSpeed_), x, z, yaw, -1);
}

double LectureScript::writeDuration() const
{
	return kLines * kLineWriteS + (kLines - 1) * kLineReturnS;
}

void LectureScript::configure(uint64_t seed, double boardDistanceM, double walkSpeedMps, bool boardChanges)
{
	seed_ = seed;
	boardDistance_ = boardDistanceM;
	walkSpeed_ = walkSpeedMps;
	boardChanges_ = boardChanges;

	sessions_.clear();
	const double centres[3] = { -0.72, 0.02, 0.62 };
	for (int s = 0; s < 3; ++s) {
		Session session;
		session.left = centres[s] + jitter(seed, 10 + s, 0.08) - kLineWidthM / 2;
		session.top = -0.54 + jitter(seed, 20 + s, 0.05);
		session.colour = 1 + (s == 1 ? 1 : 0) + (s == 2 && seed % 2 ? 2 : 0);
		double at = 0.02;
		for (int w = 0; w < kMaxWords && at < 0.95; ++w) {
			double length = 0.18 + 0.14 * uniformFromHash(hashKey(seed, 30 + s, w));
			session.wordStart[w] = at;
			session.wordEnd[w] = std::min(0.98, at + length);
			at = session.wordEnd[w] + 0.07;
			session.words = w + 1;
		}
		sessions_.push_back(session);
	}

	const double zTalk = boardDistanceM - kTalkFromBoardM;
	const double zWrite = boardDistanceM - kWriteFromBoardM;
	const double xTalk = -0.35 + jitter(seed, 40, 0.1);
	auto startX = [&](int s) { return sessions_[s].left - kReachLeftM; };
	auto endX = [&](int s) { return sessions_[s].left + kLineWidthM - kReachLeftM; };

	phases_.clear();
	addPhase(LecturerAction::Talk, kTalkS, xTalk, zTalk, 0.0, -1);
	walkTo(startX(0), zWrite);
	addPhase(LecturerAction::Write, writeDuration(), endX(0), zWrite, kPi, 0);
	walkTo((sessions_[0].left + sessions_[1].left) / 2, zTalk);
	addPhase(LecturerAction::Talk, kTalkS, phases_.back().x1, zTalk, 0.0, -1);
	walkTo(startX(1), zWrite);
	addPhase(LecturerAction::Write, writeDuration(), endX(1), zWrite, kPi, 1);
	eraseLeft_ = sessions_[0].left - 0.03;
	eraseRight_ = sessions_[0].left + kLineWidthM + 0.03;
	walkTo(eraseLeft_ - kReachLeftM, zWrite);
	addPhase(LecturerAction::Erase, kEraseS, eraseRight_ - kReachLeftM, zWrite, kPi, 0);
	eraseStart_ = phases_.back().start;
	eraseEnd_ = phases_.back().end;
	walkTo(startX(2), zWrite);
	addPhase(LecturerAction::Write, writeDuration(), endX(2), zWrite, kPi, 2);
	walkTo(xTalk, zTalk);
	addPhase(LecturerAction::Talk, kTalkS + 0.4, xTalk, zTalk, 0.0, -1);
	cycleLength_ = phases_.back().end;
}

uint64_t LectureScript::cycleOf(double timeS) const
{
	return timeS <= 0 ? 0 : static_cast<uint64_t>(timeS / cycleLength_);
}

double LectureScript::cycleTime(double timeS) const
{
	double t = std::fmod(timeS, cycleLength_);
	return t < 0 ? t + cycleLength_ : t;
}

const ScriptPhase &LectureScript::phaseAt(double cycleTime) const
{
	auto it = std::upper_bound(phases_.begin(), phases_.end(), cycleTime,
				   [](double t, const ScriptPhase &p) { return t < p.end; });
	return it == phases_.end() ? phases_.back() : *it;
}

const ScriptPhase *LectureScript::previousPhase(const ScriptPhase &phase) const
{
	size_t index = static_cast<size_t>(&phase - phases_.data());
	return index == 0 ? &phases_.back() : &phases_[index - 1];
}

bool LectureScript::penPosition(int s, double localTime, double &x, double &y, double &lineX) const
{
	const Session &session = sessions_[s];
	const double linePeriod = kLineWriteS + kLineReturnS;
	int line = std::min(kLines - 1, static_cast<int>(localTime / linePeriod));
	double within = localTime - line * linePeriod;
	double baseline = session.top + line * kLineGapM + kLetterM;
	if (within > kLineWriteS) { // lifted, travelling back to the next line
		double q = (within - kLineWriteS) / kLineReturnS;
		lineX = session.left + kLineWidthM * (1.0 - q);
		x = lineX;
		y = baseline + q * kLineGapM - kLetterM;
		return false;
	}
	double p = std::clamp(within / kLineWriteS, 0.0, 1.0);
	lineX = session.left + p * kLineWidthM;
	double phase = 2.0 * kPi * p * kLineWidthM / kLoopPitchM + line * 1.3;
	double height = kLetterM * (0.65 + 0.35 * std::sin(p * 23.0 + s + line));
	x = lineX + 0.007 * std::cos(phase);
	y = baseline - height * (0.5 + 0.5 * std::sin(phase));
	for (int w = 0; w < session.words; ++w)
		if (p >= session.wordStart[w] && p <= session.wordEnd[w])
			return true;
	return false;
}

bool LectureScript::handOnBoard(const ScriptPhase &phase, double cycleTime, double &x, double &y) const
{
	double local = cycleTime - phase.start;
	if (phase.action == LecturerAction::Write) {
		double lineX;
		penPosition(phase.session, local, x, y, lineX);
		return std::fmod(local, kLineWriteS + kLineReturnS) <= kLineWriteS;
	}
	if (phase.action == LecturerAction::Erase) {
		double q = std::clamp(local / (phase.end - phase.start), 0.0, 1.0);
		const Session &session = sessions_[phase.session];
		x = eraseLeft_ + q * (eraseRight_ - eraseLeft_);
		// Wiping up and down over both lines, 2.5 strokes a second.
		y = session.top + (kLineGapM + kLetterM) * (0.5 + 0.5 * std::sin(2 * kPi * 2.5 * local));
		return true;
	}
	return false;
}

void LectureScript::rasterise(uint64_t cycle, std::vector<BoardTexel> &texels) const
{
	const int columns = BoardGeometry::texelColumns(), rows = BoardGeometry::texelRows();
	texels.assign(static_cast<size_t>(columns) * rows, BoardTexel{});
	uint64_t slide = boardChanges_ ? cycle : 0;
	for (int r = 0; r < rows; ++r)
		for (int c = 0; c < columns; ++c) {
			double x = BoardGeometry::kLeft + (c + 0.5) * BoardGeometry::kTexelM;
			double y = BoardGeometry::kTop + (r + 0.5) * BoardGeometry::kTexelM;
			texels[static_cast<size_t>(r) * columns + c].background = slideColour(slide, x, y);
		}

	const uint16_t cycleEnd = static_cast<uint16_t>(std::min(65535.0, cycleLength_ / kTickS));
	const int radius = static_cast<int>(std::ceil(kStrokeRadiusM / BoardGeometry::kTexelM));
	for (const ScriptPhase &phase : phases_) {
		if (phase.action != LecturerAction::Write)
			continue;
		const Session &session = sessions_[phase.session];
		// Small steps: the pen never skips a texel.
		for (double local = 0; local <= writeDuration(); local += 0.002) {
			double x, y, lineX;
			if (!penPosition(phase.session, local, x, y, lineX))
				continue;
			int cx = static_cast<int>((x - BoardGeometry::kLeft) / BoardGeometry::kTexelM);
			int cy = static_cast<int>((y - BoardGeometry::kTop) / BoardGeometry::kTexelM);
			uint16_t write = boardChanges_ ? static_cast<uint16_t>((phase.start + local) / kTickS) : 0;
			for (int dy = -radius; dy <= radius; ++dy)
				for (int dx = -radius; dx <= radius; ++dx) {
					int tx = cx + dx, ty = cy + dy;
					if (dx * dx + dy * dy > radius * radius || tx < 0 || ty < 0 ||
					    tx >= columns || ty >= rows)
						continue;
					BoardTexel &t = texels[static_cast<size_t>(ty) * columns + tx];
					if (t.ink && t.writeTick <= write)
						continue;
					t.ink = static_cast<uint8_t>(session.colour);
					t.writeTick = write;
					double wipe = eraseStart_ + (tx * BoardGeometry::kTexelM + BoardGeometry::kLeft -
								     eraseLeft_) / (eraseRight_ - eraseLeft_) *
								    (eraseEnd_ - eraseStart_);
					bool wiped = boardChanges_ && phase.session == 0;
					t.eraseTick = !boardChanges_ ? 65535
						      : wiped ? static_cast<uint16_t>(wipe / kTickS)
							      : cycleEnd;
				}
		}
	}
}

} // namespace depthkey::sim
