// Everything the config file can set, with the defaults that apply when a key
// is absent. The loader (config_loader.hpp) fills this from TOML and refuses
// anything it does not know; config/depthkey.toml documents each key.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace depthkey {

struct DaemonSettings {
	std::string logLevel = "info";      // error | warning | info | debug
	std::string snapshotDir = "";       // where SIGUSR1 stage snapshots go; "" = off
	bool operator==(const DaemonSettings &) const = default;
};

struct ColourCameraSettings {
	std::string backend = "sim";        // sim | v4l2
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
	std::string backend = "sim";        // sim | sr2 | v4l2
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
	int maxSkewMs = 150;                // farther apart: colour goes out unkeyed
	bool operator==(const PairingSettings &) const = default;
};

struct SegmentationSettings {
	int nearMm = 500;                   // lecturer depth interval [near, far]
	int farMm = 1600;
	bool operator==(const SegmentationSettings &) const = default;
};

struct CompositeSettings {
	double opacity = 0.5;               // 0..1, lecturer over board
	uint32_t boardColour = 0x1e3c28;    // 0xRRGGBB board source (solid colour)
	bool operator==(const CompositeSettings &) const = default;
};

struct OutputSettings {
	std::string compositeName = "/depthkey.composite";
	std::string lecturerName = "/depthkey.lecturer";
	int slots = 3;                      // 2..8 ring slots per stream
	std::string group = "";             // group owning the objects (mode 0640); "" = own group
	bool operator==(const OutputSettings &) const = default;
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
	bool operator==(const LedSettings &) const = default;
};

struct SimSettings {
	uint64_t seed = 1;
	bool operator==(const SimSettings &) const = default;
};

struct Settings {
	DaemonSettings daemon;
	ColourCameraSettings colour;
	DepthCameraSettings depth;
	PairingSettings pairing;
	SegmentationSettings segmentation;
	CompositeSettings composite;
	OutputSettings output;
	LedSettings leds;
	SimSettings sim;
	bool operator==(const Settings &) const = default;
};

} // namespace depthkey
