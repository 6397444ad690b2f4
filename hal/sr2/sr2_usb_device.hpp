// Finding and claiming an SR-2 on the USB bus: by vendor/product id, or at a
// fixed port path when two cameras are plugged in.
#pragma once

#include <cstdint>
#include <string>

struct libusb_context;
struct libusb_device;
struct libusb_device_handle;

namespace depthkey {

// "BUS-PORT[.PORT...]" as sysfs names it, e.g. "1-2.3".
std::string usbPortPath(libusb_device *device);

struct Sr2Endpoints {
	uint8_t framesIn = 0;
	uint8_t registersOut = 0;
};

// Opens the first SR-2 (or the one at usbPath), detaches a kernel driver and
// claims interface 0. Returns a negative errno and says why in detail.
// The endpoints are the SR-2's (0x88, 0x02) when interface 0 has them, else
// its first bulk IN and OUT: a USB device controller may number endpoints
// its own way (an emulated SR-2 on dummy_hcd gets bulk IN 0x81).
int openSr2(libusb_context *context, const std::string &usbPath,
	    libusb_device_handle *&handle, Sr2Endpoints &endpoints, std::string &detail);

void closeSr2(libusb_device_handle *handle);

// Whether an SR-2 (the first, or the one at usbPath) is on the bus, without
// opening it (it may be the daemon's, claimed): its port path, or "" when
// there is none (depthkeyd --check-config and the setup report, issue 30).
std::string findSr2(const std::string &usbPath);

} // namespace depthkey
