// A minimal libusb client of the SR-2 protocol for the HIL suite: checks the
// emulated camera on its own, before the daemon's backend talks to it.
//   depthkey-hil-sr2-probe FRAMES   opens 0852:0071, writes the output mode
//   register, requests and reads FRAMES frames, prints each length; exits 0
//   when every frame had exactly the three images' bytes.
#include "hal/sr2/sr2_protocol.hpp"

#include <cstdio>
#include <cstdlib>
#include <libusb.h>
#include <vector>

using namespace depthkey;

int main(int argc, char **argv)
{
	int frames = argc > 1 ? std::atoi(argv[1]) : 1;
	libusb_context *context = nullptr;
	if (libusb_init(&context) != 0)
		return 2;
	libusb_device_handle *handle = libusb_open_device_with_vid_pid(context, sr2::kVendorId, sr2::kProductId);
	if (!handle) {
		std::fprintf(stderr, "sr2-probe: no device %04x:%04x\n", sr2::kVendorId, sr2::kProductId);
		return 1;
	}
	int err = libusb_claim_interface(handle, sr2::kInterface);
	uint8_t reg[2] = { sr2::kRegOutputMode.address, sr2::kOutputDistanceIntensityAmplitude };
	int moved = 0;
	if (!err)
		err = libusb_bulk_transfer(handle, sr2::kEndpointRegistersOut, reg, sizeof(reg), &moved,
					   sr2::kTransferTimeoutMs);
	std::vector<uint8_t> frame(sr2::kReadBytes);
	int good = 0;
	for (int i = 0; !err && i < frames; i++) {
		err = libusb_control_transfer(handle, sr2::kRequestTypeVendorOut, sr2::kRequestFrame, 0, 0,
					      nullptr, 0, sr2::kTransferTimeoutMs);
		if (err < 0)
			break;
		err = libusb_bulk_transfer(handle, sr2::kEndpointFramesIn, frame.data(), static_cast<int>(frame.size()),
					   &moved, sr2::kTransferTimeoutMs);
		std::printf("sr2-probe: frame %d: %d bytes%s\n", i, moved, err ? libusb_error_name(err) : "");
		good += !err && moved == static_cast<int>(sr2::kFrameBytes);
	}
	if (err < 0)
		std::fprintf(stderr, "sr2-probe: %s\n", libusb_error_name(err));
	libusb_close(handle);
	libusb_exit(context);
	return good == frames ? 0 : 1;
}
