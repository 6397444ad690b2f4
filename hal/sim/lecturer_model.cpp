#include "hal/sim/lecturer_model.hpp"

#include "hal/sim/hash_noise.hpp"

#include <algorithm>
#include <cmath>

namespace depthkey::sim {

namespace {

using Vec = Eigen::Vector3f;
constexpr double kPi = 3.14159265358979323846;

// Body measures (m) of a 1.75 m adult; heights above the floor.
constexpr float kShoulderHeight = 1.44f, kShoulderHalf = 0.19f;
constexpr float kHipHeight = 0.93f, kHipHalf = 0.09f;
constexpr float kHeadHeight = 1.63f, kHeadRadius = 0.10f;
constexpr float kUpperArm = 0.30f, kForearm = 0.30f;
constexpr float kStepM = 0.7f;          // a stride, for the leg swing
constexpr double kTurnS = 0.8;          // how long a turn takes

struct Body {
	Vec floor, right, up, forward;
	Vec at(float lateral, float height, float ahead = 0) const
	{
		return floor + right * lateral + up * height + forward * ahead;
	}
};

double smoothstep(double x)
{
	x = std::clamp(x, 0.0, 1.0);
	return x * x * (3 - 2 * x);
}

double blendAngle(double from, double to, double q)
{
	double d = std::remainder(to - from, 2 * kPi);
	return from + d * q;
}

// Two-bone IK: the elbow bends towards pole. Unreachable targets straighten
// the arm towards them.
void reach(const Vec &shoulder, Vec target, const Vec &pole, Vec &elbow, Vec &hand)
{
	Vec dir = target - shoulder;
	float d = dir.norm();
	dir /= std::max(d, 1e-4f);
	d = std::clamp(d, 0.08f, kUpperArm + kForearm - 1e-3f);
	hand = shoulder + dir * d;
	float a = (kUpperArm * kUpperArm - kForearm * kForearm + d * d) / (2 * d);
	float h = std::sqrt(std::max(0.0f, kUpperArm * kUpperArm - a * a));
	Vec side = pole - dir * pole.dot(dir);
	side = side.norm() > 1e-5f ? Vec(side.normalized()) : Vec(0, 1, 0);
	elbow = shoulder + dir * a + side * h;
}

Capsule capsule(const Vec &a, const Vec &b, float radius, Rgb8 colour, float reflectivity, bool fast = false)
{
	Capsule c;
	c.a = a;
	c.b = b;
	c.radius = radius;
	c.colour = colour;
	c.reflectivity = reflectivity;
	c.fast = fast;
	return c;
}

// Where the hands go in a phase at cycle time t: the right one on the
// board, gesturing to the audience or swinging; the left one resting.
void handTargets(const LectureScript &script, const ScriptPhase &phase, double t, const Body &body, float swing,
		 Vec &right, Vec &left)
{
	const double local = t - phase.start;
	double boardX = 0, boardY = 0;
	bool onBoard = script.handOnBoard(phase, t, boardX, boardY);
	if (phase.action == LecturerAction::Write || phase.action == LecturerAction::Erase) {
		float lift = onBoard ? 0.05f : 0.10f; // hand centre off the board surface
		right = Vec(static_cast<float>(boardX), static_cast<float>(boardY),
			    static_cast<float>(script.boardDistance()) - lift);
	} else if (phase.action == LecturerAction::Talk) {
		// Circles in front of the chest at 0.9 Hz (0.6 m/s): a fast hand.
		double w = 2 * kPi * 0.9 * local;
		right = body.at(0.22f + 0.10f * static_cast<float>(std::cos(w)),
				1.25f + 0.10f * static_cast<float>(std::sin(w)), 0.35f);
	} else {
		right = body.at(0.24f, 0.82f, 0.15f * swing);
	}
	left = phase.action == LecturerAction::Talk ? body.at(-0.26f, 1.02f, 0.20f)
						     : body.at(-0.24f, 0.82f, -0.15f * swing);
}

} // namespace

LecturerLook LecturerLook::fromSeed(uint64_t seed)
{
	// Shirts: chalk-white, board-dark, red, blue; trousers dark like the board.
	static const Rgb8 shirts[] = { { 214, 214, 206 }, { 44, 52, 48 }, { 150, 44, 52 }, { 58, 84, 142 } };
	static const Rgb8 skins[] = { { 222, 176, 146 }, { 176, 128, 96 }, { 120, 84, 62 } };
	uint64_t h = hashKey(seed, 0x100);
	LecturerLook look;
	look.shirt = shirts[(seed + 3) % 4]; // seed 1: chalk-white shirt
	look.sleeves = (h & 1) ? look.shirt : shirts[(seed + 2) % 4];
	look.skin = skins[(h >> 8) % 3];
	look.hair = { 58, 44, 34 };
	look.trousers = { 36, 40, 44 };
	return look;
}

void poseLecturer(const LectureScript &script, const LecturerLook &look, double timeS,
		  std::vector<Capsule> &out)
{
	const double t = script.cycleTime(timeS);
	const ScriptPhase &phase = script.phaseAt(t);
	const ScriptPhase &prev = *script.previousPhase(phase);
	const double local = t - phase.start;
	const double q = (phase.end > phase.start) ? local / (phase.end - phase.start) : 0.0;

	// Where the writing hand goes decides where the body stands.
	double boardX = 0, boardY = 0;
	script.handOnBoard(phase, t, boardX, boardY);
	double x = phase.x0 + (phase.x1 - phase.x0) * q;
	double z = phase.z0 + (phase.z1 - phase.z0) * q;
	if (phase.action == LecturerAction::Write || phase.action == LecturerAction::Erase)
		x = std::clamp(boardX - 0.28, std::min(phase.x0, phase.x1) - 0.05, std::max(phase.x0, phase.x1) + 0.05);
	double yaw = blendAngle(prev.yaw, phase.yaw, smoothstep(local / kTurnS));

	Body body;
	body.floor = Vec(static_cast<float>(x), static_cast<float>(kCameraHeightM), static_cast<float>(z));
	body.up = Vec(0, -1, 0);
	body.right = Vec(static_cast<float>(-std::cos(yaw)), 0, static_cast<float>(std::sin(yaw)));
	body.forward = Vec(static_cast<float>(-std::sin(yaw)), 0, static_cast<float>(-std::cos(yaw)));

	// Walking: legs and arms swing in opposition, the body bobs a little.
	float swing = 0;
	if (phase.action == LecturerAction::Walk) {
		double travelled = std::hypot(phase.x1 - phase.x0, phase.z1 - phase.z0) * q;
		swing = static_cast<float>(std::sin(2 * kPi * travelled / kStepM));
		body.floor += body.up * (0.015f * std::fabs(swing));
	}

	const Vec shoulderL = body.at(-kShoulderHalf, kShoulderHeight);
	const Vec shoulderR = body.at(kShoulderHalf, kShoulderHeight);
	const Vec pole = body.up * -1.0f - body.forward * 0.4f; // elbows down and back

	// Hands: the targets of this phase, blended in from the last phase's
	// over a turn's time, so a hand never jumps.
	const double blend = smoothstep(local / kTurnS);
	Vec handTargetR, handTargetL, prevR, prevL;
	handTargets(script, phase, t, body, swing, handTargetR, handTargetL);
	if (blend < 1.0) {
		handTargets(script, prev, prev.end - 1e-6, body, 0.0f, prevR, prevL);
		float b = static_cast<float>(blend);
		handTargetR = prevR + (handTargetR - prevR) * b;
		handTargetL = prevL + (handTargetL - prevL) * b;
	}

	Vec elbowR, handR, elbowL, handL;
	reach(shoulderR, handTargetR, pole + body.right * 0.5f, elbowR, handR);
	reach(shoulderL, handTargetL, pole - body.right * 0.5f, elbowL, handL);

	const float fabric = 0.55f, skinIr = 0.5f;
	out.clear();
	out.push_back(capsule(body.at(-0.085f, 1.40f), body.at(-0.075f, 0.98f), 0.115f, look.shirt, fabric));
	out.push_back(capsule(body.at(0.085f, 1.40f), body.at(0.075f, 0.98f), 0.115f, look.shirt, fabric));
	out.push_back(capsule(body.at(0, 1.42f), body.at(0, 1.55f, 0.01f), 0.052f, look.skin, skinIr));
	out.push_back(capsule(body.at(0, kHeadHeight, 0.01f), body.at(0, kHeadHeight - 0.03f, 0.02f),
			      kHeadRadius, look.skin, skinIr));
	// Hair: a slightly larger sphere up and back shows above and behind the face.
	Vec hairCentre = body.at(0, kHeadHeight + 0.025f, -0.02f);
	out.push_back(capsule(hairCentre, hairCentre, kHeadRadius + 0.004f, look.hair, 0.3f));
	for (int side = -1; side <= 1; side += 2) {
		float stride = 0.25f * swing * side;
		out.push_back(capsule(body.at(side * kHipHalf, kHipHeight), body.at(side * kHipHalf, 0.08f, stride),
				      0.075f, look.trousers, fabric));
	}
	out.push_back(capsule(shoulderL, elbowL, 0.05f, look.sleeves, fabric));
	out.push_back(capsule(shoulderR, elbowR, 0.05f, look.sleeves, fabric));
	out.push_back(capsule(elbowL, handL, 0.04f, look.sleeves, fabric, true));
	out.push_back(capsule(elbowR, handR, 0.04f, look.sleeves, fabric, true));
	out.push_back(capsule(handL, handL, 0.048f, look.skin, skinIr, true));
	out.push_back(capsule(handR, handR, 0.048f, look.skin, skinIr, true));
	// Trouser waist joins the torso to the legs.
	out.push_back(capsule(body.at(-0.07f, 0.97f), body.at(0.07f, 0.97f), 0.11f, look.trousers, fabric));
}

} // namespace depthkey::sim
