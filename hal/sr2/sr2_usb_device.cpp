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

// The wanted endpoint if interface 0 has it, else its first bulk endpoint
// of the same direction; 0 if there is none.
uint8_t findBulkEndpoint(const libusb_interface_descriptor &alt, uint8_t wanted)
{
	uint8_t fallback = 0;
	for (int i = 0; i < alt.bNumEndpoints; i++) {
		const libusb_endpoint_descriptor &ep = alt.endpoint[i];
		bool bulk = (ep.bmAttributes & LIBUSB_TRANSFER_TYPE_MASK) == LIBUSB_TRANSFER_TYPE_BULK;
		bool sameDirection = (ep.bEndpointAddress & LIBUSB_ENDPOINT_IN) ==
				     (wanted & LIBUSB_ENDPOINT_IN);
		if (ep.bEndpointAddress == wanted && bulk)
			return wanted;
		if (bulk && sameDirection && !fallback)
			fallback = ep.bEndpointAddress;
	}
	return fallback;
}

int findEndpoints(libusb_device *device, Sr2Endpoints &endpoints)
{
	libusb_config_descriptor *config = nullptr;
	int ret = libusb_get_active_config_descriptor(device, &config);
	if (ret < 0)
		return usbErrno(ret);
	endpoints = {};
	if (config->bNumInterfaces > sr2::kInterface &&
	    config->interface[sr2::kInterface].num_altsetting > 0) {
		const libusb_interface_descriptor &alt = config->interface[sr2::kInterface].altsetting[0];
		endpoints.framesIn = findBulkEndpoint(alt, sr2::kEndpointFramesIn);
		endpoints.registersOut = findBulkEndpoint(alt, sr2::kEndpointRegistersOut);
	}
	libusb_free_config_descriptor(config);
	return endpoints.framesIn && endpoints.registersOut ? 0 : -ENODEV;
}

} // namespace

int openSr2(libusb_context *context, const std::string &usbPath,
	    libusb_device_handle *&handle, Sr2Endpoints &endpoints, std::string &detail)
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
	ret = findEndpoints(libusb_get_device(handle), endpoints);
	if (ret < 0) {
		detail = "SR-2" + where + " has no bulk IN and OUT endpoints on interface 0";
		libusb_close(handle);
		handle = nullptr;
		return ret;
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

std::string findSr2(const std::string &usbPath)
{
	// A context of its own: enumerating needs no open device, and the
	// daemon's context belongs to its event loop's thread.
	libusb_context *context = nullptr;
	if (libusb_init(&context) < 0)
		return "";
	libusb_device **list = nullptr;
	ssize_t count = libusb_get_device_list(context, &list);
	std::string port;
	for (ssize_t i = 0; i < count && port.empty(); i++)
		if (isSr2(list[i]) && (usbPath.empty() || usbPortPath(list[i]) == usbPath))
			port = usbPortPath(list[i]);
	if (count >= 0)
		libusb_free_device_list(list, 1);
	libusb_exit(context);
	return port;
}

void closeSr2(libusb_device_handle *handle)
{
	if (!handle)
		return;
	libusb_release_interface(handle, sr2::kInterface);
	libusb_close(handle);
}

} // namespace depthkey
