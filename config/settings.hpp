// Everything the config file can set, with the defaults that apply when a key
// is absent. The loader (config_loader.hpp) fills this from TOML and refuses
// anything it does not know; config/depthkey.toml documents each key.
#pragma once

#include <cstdint>
#include <string>

namespace depthkey {

struct DaemonSettings {
	std::string logLevel = "info";      // error | warning | info | debug
	std::string snapshotDir = "";       // where SIGUSR1 stage snapshots go; "" = off
	bool operator==(const DaemonSettings &) const = default;
};

struct ColourCameraSettings {
	std::string backend = "sim";        // sim
	std::string device = "/dev/video0";
	int width = 640;                    // 16..1920
	int height = 480;                   // 16..1080
	int fps = 25;                       // 1..60
	bool operator==(const ColourCameraSettings &) const = default;
};

struct DepthCameraSettings {
	std::string backend = "sim";        // sim
	int fps = 10;                       // 1..60
	bool operator==(const DepthCameraSettings &) const = default;
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
	std::string backend = "none";       // none
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
	SegmentationSettings segmentation;
	CompositeSettings composite;
	OutputSettings output;
	LedSettings leds;
	SimSettings sim;
	bool operator==(const Settings &) const = default;
};

} // namespace depthkey
