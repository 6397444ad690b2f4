// Everything the config file can set, with the defaults that apply when a key
// is absent. The loader (config/config_loader.hpp) fills this from TOML and
// refuses anything it does not know; config/depthkey.toml documents each key.
//
// Plain structs with no code and no includes of the project: every layer
// reads them (algo/ its sections, hal/ the devices', daemon/ all), so they
// sit apart from config/, whose file readers use algo/'s types (the mapping,
// the homography). Dependencies then point one way: config/ -> algo/ ->
// settings/.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace depthkey {

struct DaemonSettings {
	std::string logLevel = "info";      // error | warning | info | debug
	std::string snapshotDir = "";       // where SIGUSR1 stage snapshots go; "" = off
	std::string recordDir = "";         // record the camera inputs here; "" = off
	int recordCompression = 1;          // PNG zlib level 0..9 of the recording
	bool operator==(const DaemonSettings &) const = default;
};

struct ColourCameraSettings {
	std::string backend = "sim";        // sim | v4l2 | replay
	std::string device = "/dev/video0";
	int width = 640;                    // 16..1920
	int height = 480;                   // 16..1080
	int fps = 25;                       // 1..60
	std::string pixelFormat = "auto";   // auto | yuyv | nv12 | mjpeg
	int timeoutMs = 1000;               // no frame this long: device lost
	bool operator==(const ColourCameraSettings &) const = default;
};

// A raw SR-2 register write from the config, applied after the built-in ones.
struct Sr2RegisterWrite {
	int address = 0;                    // 0..255
	int value = 0;                      // 0..255
	bool operator==(const Sr2RegisterWrite &) const = default;
};

struct DepthCameraSettings {
	std::string backend = "sim";        // sim | sr2 | v4l2 | replay
	int fps = 10;                       // 1..60
	int timeoutMs = 1000;               // transfer / frame timeout
	int minMm = 300;                    // valid depth range; outside = no measurement
	int maxMm = 7500;
	// sr2
	std::string usbPath = "";           // "" = first 0852:0071, else "BUS-PORT[.PORT...]"
	int integrationTime = 40;           // register 0x09, 0..255
	bool autoIntegration = false;
	int intensityLow = 14000;           // auto integration window (mean intensity)
	int intensityHigh = 18000;
	std::vector<Sr2RegisterWrite> sr2Registers;
	// v4l2
	std::string device = "/dev/video1";
	int width = 640;
	int height = 480;
	std::string pixelFormat = "z16";    // z16 | y16
	double scaleMm = 1.0;               // millimetres per count
	bool operator==(const DepthCameraSettings &) const = default;
};

// Soft synchronisation of the two free-running cameras (Friedland et al.):
// depth frames are matched to colour frames by capture time.
struct PairingSettings {
	int offsetMs = 0;                   // added to depth timestamps (depth latency)
	bool offsetAuto = true;             // offset_ms = "auto": the measured latency (algo/latency_estimator.hpp)
	int maxSkewMs = 150;                // farther apart: colour goes out unkeyed
	int delayMs = 150;                  // 0..1000: colour waits this long for depth captured after it
	bool operator==(const PairingSettings &) const = default;
};

// Depth seeding (paper 6.1), at the depth camera's resolution.
struct SegmentationSettings {
	int nearMm = 500;                   // lecturer depth interval [near, far]
	int farMm = 1850;                   // 150 mm in front of the simulated board (2000 mm)
	int minAmplitude = 100;             // 0..65535: weaker echoes are not trusted
	int maxAmplitude = 65535;           // 1..65535: at or above = saturated, not trusted
	int erodePx = 2;                    // 0..20 ToF px: in-range mask -> surely lecturer
	int dilatePx = 7;                   // 1..40 ToF px: surely lecturer -> superset
	int surfacePx = 8;                  // 1..40 ToF px: his depth averaged to map the seeds
	int corePx = 3;                     // 0..20 ToF px eroded beyond erode_px: the fixed core
	int haloPx = 4;                     // 0..20 ToF px: the scattered-light halo's reach, 0 = none
	double haloShare = 0.5;             // 0..0.9: its share where he covers half the box
	bool operator==(const SegmentationSettings &) const = default;
};

// Where the depth -> colour mapping comes from (paper section 5).
struct MappingSettings {
	std::string calibrationFile = "";   // "" = none: identity scaling, reported
	bool operator==(const MappingSettings &) const = default;
};

// Colour learning (paper 6.1-6.2): decaying colour histograms per class.
struct LearningSettings {
	int initialFrames = 20;             // 1..1000 frames before SIOX starts
	double boardRate = 0.2;             // 0..1 weight of each frame's board colours
	double lecturerRate = 0.01;         // 0..1 weight of each frame's lecturer colours
	int samples = 4096;                 // 256..65536 samples per class and frame
	int marginPx = 1;                   // 0..40 ToF px kept free beyond the superset
	double relearnMisfit = 0.05;        // 0..1 rise of misclassified samples that re-derives
	bool operator==(const LearningSettings &) const = default;
};

// SIOX on the undecided band (paper section 6).
struct SioxSettings {
	int smoothing = 1;                  // 0..8 passes of 3x3 confidence smoothing
	bool softAlpha = true;              // fractional alpha on the boundary
	int guidedRadius = 5;               // 0..7: guided filter of the matte (edge-aware alpha); 0 = off
	int guidedEps = 10;                 // 1..65025: its smoothing, in squared 8-bit levels
	bool operator==(const SioxSettings &) const = default;
};

// How the evidence decides the undecided pixels inside the superset
// (algo/fused_evidence.hpp). Weights are in units of SIOX's colour
// confidence, which counts 1.
struct DecisionSettings {
	int depthWeight = 64;               // 0..255: the depth evidence (DepthSeeder::depthEvidence)
	int depthPivot = 144;               // 1..254: the depth evidence value that is neutral
	int boardWeight = 240;              // 0..255: a match with the board model
	int boardMatch = 10;                // 1..255: L1 RGB distance below which the board model matches
	int temporalWeight = 64;            // 0..255: the previous frame's alpha where colour did not change
	int stillColour = 24;               // 1..255: L1 RGB change below which a pixel did not change
	int cutSmoothness = 1000;           // 0..10000: the band's minimum cut (algo/band_graph_cut.hpp); 0 = off
	int cutEdgeSigma = 7;               // 1..64: colour difference (8-bit RGB levels) the cut follows
	int cutMaxBandPixels = 2500000;     // 0..8294400: a larger band is smoothed instead (a safety valve above a 1080p frame)
	int cutLevels = 1;                  // 0..4: the cut solved coarse to fine over 2x2 blocks at 640 wide, + log2(width / 640) rounded (algo/coarse_to_fine_cut.hpp)
	int cutMargin = 0;                  // 0..8: coarse cells around a coarse edge cut again at the finer level
	int edgeUnmixing = 100;             // 0..195075: least |F - B|^2 to unmix edge pixels (algo/boundary_unmixing.hpp); 0 = off
	bool operator==(const DecisionSettings &) const = default;
};

struct CompositeSettings {
	double opacity = 0.5;               // 0..1, lecturer over board
	bool operator==(const CompositeSettings &) const = default;
};

// The board's own picture behind the lecturer (paper Figure 1) and the
// geometry it is composited in (hal/board/, algo/board_compositor.hpp).
struct BoardSettings {
	std::string backend = "sim";        // colour | image | v4l2 | sim
	uint32_t colour = 0x1e3c28;         // 0xRRGGBB: "colour", and until a picture arrives
	std::string image = "";             // PNG/JPEG for "image", absolute
	// v4l2: the capture stick; width/height are also the picture size of
	// "colour" and the width of "sim" (whose height follows the display)
	std::string device = "/dev/video2";
	int width = 1920;                   // 16..3840
	int height = 1080;                  // 16..2160
	int fps = 10;                       // 1..60, v4l2 and sim
	std::string pixelFormat = "auto";   // auto | yuyv | nv12 | mjpeg
	int timeoutMs = 2000;               // no frame this long: capture lost
	int outputWidth = 0;                // composite size in board geometry; 0 = the picture's
	int outputHeight = 0;
	std::string homographyFile = "";    // H colour px -> board px (depthkey-calibrate --board); "" = camera geometry
	bool operator==(const BoardSettings &) const = default;
};

struct OutputSettings {
	std::string compositeName = "/depthkey.composite";
	std::string lecturerName = "/depthkey.lecturer";
	std::string boardLecturerName = "/depthkey.lecturer.board"; // the layer in board geometry
	int slots = 2;                      // 2..8 ring slots per stream
	std::string group = "";             // group owning the objects (mode 0660); "" = own group
	// The virtual webcam: the composite as YUYV to this v4l2loopback node
	// (hal/v4l2/v4l2_output.hpp); "" = off. Not part of the shared memory:
	// see sameSharedMemory().
	std::string v4l2Device = "";
	bool operator==(const OutputSettings &) const = default;
};

// Whether two [output]s describe the same shared-memory streams (a change of
// v4l2Device alone must not re-create them under their readers).
inline bool sameSharedMemory(const OutputSettings &a, const OutputSettings &b)
{
	OutputSettings x = a;
	x.v4l2Device = b.v4l2Device;
	return x == b;
}

// The live preview page (hal/preview/preview_server.hpp).
struct PreviewSettings {
	std::string listen = "127.0.0.1:8080"; // IP:PORT; "" = off; beyond loopback needs passwordFile
	std::string passwordFile = "";      // "USER:CRYPT-HASH" lines, mode 0600; required off loopback
	int maxClients = 10;                // 1..32 concurrent streams (the page opens 5)
	int jpegQuality = 80;               // 10..100
	bool operator==(const PreviewSettings &) const = default;
};

struct LedSettings {
	std::string backend = "none";       // none | gpiod
	std::string chip = "gpiochip0";     // name, /dev path, label or number
	bool activeLow = false;
	// Line offsets on the chip, -1 = not wired.
	int powerLine = 0;
	int depthLine = 1;
	int colourLine = 2;
	int calibrationLine = 3;
	int readerLine = 4;
	int errorLine = 5;
	int boardLine = 6;
	bool operator==(const LedSettings &) const = default;
};

// The simulated lecture scene and camera pair (backend "sim", depthkey-eval
// --sim). Every artefact has its own switch so a test can isolate it.
struct SimSettings {
	uint64_t seed = 1;                  // same seed, same frames
	// Scene
	int boardDistanceMm = 2000;         // 1500..2500, board plane from the colour camera
	double walkSpeedMps = 1.0;          // 0.1..3, lecturer's walking speed
	bool table = true;                  // a table (with a monitor) at lecturer depth
	bool boardChanges = true;           // strokes written and erased, slide changes
	bool lightingChange = true;         // slow variation of the room light
	double lightingAmplitude = 0.15;    // 0..0.5, relative brightness swing
	double lightingPeriodS = 23.0;      // 1..600
	// Colour camera
	double colourNoise = 3.0;           // 0..30, sensor noise sigma in 8-bit levels; 0 = off
	double colourJitterMs = 2.0;        // 0..20, frame time jitter (uniform +-)
	// Both lenses
	bool distortion = true;             // radial distortion of both lenses; false = pinholes
	int baselineMm = 60;                // 0..200, ToF optical centre beside the colour camera's
	// ToF camera
	bool depthNoise = true;             // sigma = L/sqrt(8) * sqrt(I) / (2A)
	double tofAmplitude = 6000;         // 500..30000, amplitude of the board at the centre
	double tofCornerAmplitude = 0.045;  // 0.01..1, amplitude at the corner relative to centre
	double tofAmbient = 3000;           // 0..30000, background light in the intensity image
	int haloWidthPx = 4;                // 0..20, scatter halo around the lecturer; 0 = off
	double haloStrength = 0.5;          // 0..1, share of scattered light at the silhouette
	int saturationMm = 750;             // 0..2000, nearer saturates (no depth); 0 = off
	bool motionBlur = true;             // depth of moving parts mixes over the exposure
	double tofExposureMs = 30.0;        // 1..100, integration time
	double depthLatencyMs = 40.0;       // 0..300, capture before the depth timestamp
	double depthJitterMs = 5.0;         // 0..50, depth frame time jitter (uniform +-)
	bool operator==(const SimSettings &) const = default;
};

// The "replay" backend: a recorded sequence folder played back.
struct ReplaySettings {
	std::string path = "";              // absolute folder; required by a "replay" backend
	bool realtime = true;               // false: as fast as the daemon takes frames
	bool loop = true;                   // start again at the end
	bool operator==(const ReplaySettings &) const = default;
};

struct Settings {
	DaemonSettings daemon;
	ColourCameraSettings colour;
	DepthCameraSettings depth;
	PairingSettings pairing;
	SegmentationSettings segmentation;
	MappingSettings mapping;
	LearningSettings learning;
	SioxSettings siox;
	DecisionSettings decision;
	CompositeSettings composite;
	BoardSettings board;
	OutputSettings output;
	PreviewSettings preview;
	LedSettings leds;
	SimSettings sim;
	ReplaySettings replay;
	bool operator==(const Settings &) const = default;
};

} // namespace depthkey
