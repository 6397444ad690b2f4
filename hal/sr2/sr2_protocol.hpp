// Everything known about the SwissRanger SR-2 on the wire, in one table:
// ids, endpoints, requests, register addresses, image layout and scales.
// Sources: /work/shared/reference/sr2-usb-protocol.md (CSEM's Linux driver,
// RobWork's wrapper). What is not public (the other registers, the exact
// distance scale) is marked as assumed; a technician with the vendor's
// register list adds writes through [[depth.sr2_register]] in the config.
#pragma once

#include <cstddef>
#include <cstdint>

namespace depthkey::sr2 {

constexpr uint16_t kVendorId = 0x0852;          // CSEM
constexpr uint16_t kProductId = 0x0071;         // Swiss Ranger 2
constexpr int kInterface = 0;

// Frame request: vendor control transfer, host to device, no data stage.
constexpr uint8_t kRequestTypeVendorOut = 0x40;
constexpr uint8_t kRequestFrame = 0xB0;

constexpr uint8_t kEndpointFramesIn = 0x88;     // bulk IN: the images
constexpr uint8_t kEndpointRegistersOut = 0x02; // bulk OUT: [address, value]
constexpr size_t kBulkChunk = 512;              // reads are rounded up to this

constexpr unsigned kTransferTimeoutMs = 1000;   // what the vendor driver uses

// Registers (one byte each).
struct Register {
	uint8_t address;
	const char *name;
};
constexpr Register kRegOutputMode = { 0x02, "output mode" };
constexpr Register kRegIntegrationTime = { 0x09, "integration time" };
// Output mode 0xC0: distance, intensity and amplitude images, in that order.
constexpr uint8_t kOutputDistanceIntensityAmplitude = 0xC0;

// Image layout: three consecutive little-endian u16 images of 160x124.
constexpr int kWidth = 160;
constexpr int kHeight = 124;
constexpr size_t kPixels = static_cast<size_t>(kWidth) * kHeight;
constexpr size_t kImageBytes = kPixels * 2;
constexpr int kImages = 3;
constexpr int kDistanceImage = 0, kIntensityImage = 1, kAmplitudeImage = 2;
constexpr size_t kFrameBytes = kImageBytes * kImages;                            // 119040
constexpr size_t kReadBytes = (kFrameBytes + kBulkChunk - 1) / kBulkChunk * kBulkChunk; // 119296

// Distance scale (assumed, not public): the 16-bit raw distance spans the
// 7.5 m non-ambiguity range of 20 MHz modulation, so mm = raw * 7500 / 65536.
constexpr uint32_t kRangeMm = 7500;
constexpr int kDistanceShift = 16;

// Frame validation: the camera has no checksum, so a frame is refused when
// its words cannot be a real scene. A saturated word (0xFFFF) in the distance
// image is an ADC overflow or filler; a real scene has a few (specular
// highlights), more than this share means the transfer is garbage.
constexpr size_t kMaxSaturatedPixels = kPixels / 4;
// Sensor noise makes a real distance image never perfectly flat: a constant
// image (all zeros, a repeated word) is a stuck sensor or a filler transfer.

// Auto integration time: nudge register 0x09 by (target - mean) / 1000 per
// frame, the gain used with this camera.
constexpr int kAutoIntegrationGainDivisor = 1000;

} // namespace depthkey::sr2
