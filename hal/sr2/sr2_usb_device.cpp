#include "hal/sr2/sr2_usb_device.hpp"

#include "hal/sr2/sr2_protocol.hpp"
#include "hal/usb/usb_event_bridge.hpp"

#include <cerrno>
#include <cstdio>
#include <libusb.h>

namespace depthkey {

std::string usbPortPath(libusb_device *device)
{
	uint8_t ports[8];
	int n = libusb_get_port_numbers(device, ports, sizeof(ports));
	std::string path = std::to_string(libusb_get_bus_number(device));
	for (int i = 0; i < n; i++)
		path += (i == 0 ? "-" : ".") + std::to_string(ports[i]);
	return path;
}

namespace {

bool isSr2(libusb_device *device)
{
	libusb_device_descriptor desc;
	return libusb_get_device_descriptor(device, &desc) == 0 &&
	       desc.idVendor == sr2::kVendorId && desc.idProduct == sr2::kProductId;
}

std::string idText()
{
	char text[16];
	std::snprintf(text, sizeof(text), "%04x:%04x", sr2::kVendorId, sr2::kProductId);
	return text;
}

} // namespace

int openSr2(libusb_context *context, const std::string &usbPath,
	    libusb_device_handle *&handle, std::string &detail)
{
	handle = nullptr;
	libusb_device **list = nullptr;
	ssize_t count = libusb_get_device_list(context, &list);
	if (count < 0) {
		detail = "cannot list USB devices";
		return usbErrno(static_cast<int>(count));
	}
	libusb_device *found = nullptr;
	for (ssize_t i = 0; i < count && !found; i++)
		if (isSr2(list[i]) && (usbPath.empty() || usbPortPath(list[i]) == usbPath))
			found = list[i];
	int ret = found ? libusb_open(found, &handle) : LIBUSB_ERROR_NO_DEVICE;
	std::string where = found ? " at " + usbPortPath(found) : "";
	libusb_free_device_list(list, 1);
	if (!found) {
		detail = "no SR-2 (" + idText() + ")" + (usbPath.empty() ? "" : " at " + usbPath);
		return -ENODEV;
	}
	if (ret < 0) {
		handle = nullptr;
		detail = "cannot open SR-2" + where + ": " + libusb_error_name(ret);
		return usbErrno(ret);
	}
	libusb_set_auto_detach_kernel_driver(handle, 1);
	ret = libusb_claim_interface(handle, sr2::kInterface);
	if (ret < 0) {
		detail = "cannot claim interface 0 of SR-2" + where + ": " + libusb_error_name(ret);
		libusb_close(handle);
		handle = nullptr;
		return usbErrno(ret);
	}
	detail = "SR-2" + where;
	return 0;
}

void closeSr2(libusb_device_handle *handle)
{
	if (!handle)
		return;
	libusb_release_interface(handle, sr2::kInterface);
	libusb_close(handle);
}

} // namespace depthkey
