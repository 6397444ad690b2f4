// Finding and claiming an SR-2 on the USB bus: by vendor/product id, or at a
// fixed port path when two cameras are plugged in.
#pragma once

#include <string>

struct libusb_context;
struct libusb_device;
struct libusb_device_handle;

namespace depthkey {

// "BUS-PORT[.PORT...]" as sysfs names it, e.g. "1-2.3".
std::string usbPortPath(libusb_device *device);

// Opens the first SR-2 (or the one at usbPath), detaches a kernel driver and
// claims interface 0. Returns a negative errno and says why in detail.
int openSr2(libusb_context *context, const std::string &usbPath,
	    libusb_device_handle *&handle, std::string &detail);

void closeSr2(libusb_device_handle *handle);

} // namespace depthkey
