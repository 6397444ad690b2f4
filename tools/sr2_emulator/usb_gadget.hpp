// A USB gadget made through configfs with one FunctionFS function: the kernel
// side of an emulated USB device whose endpoints a userspace program serves.
// Bound to a UDC (dummy_udc.0 in the test VM) it appears on the host side as
// a real device, enumerated by usbcore and reachable through usbfs/libusb.
// Unbinding and binding the UDC is an unplug and a replug.
#pragma once

#include <cstdint>
#include <string>

namespace depthkey {

struct UsbGadgetIdentity {
	uint16_t vendorId = 0;
	uint16_t productId = 0;
	std::string manufacturer;
	std::string product;
	std::string serial;
};

class UsbGadget
{
public:
	UsbGadget(std::string name, std::string udc) : name_(std::move(name)), udc_(std::move(udc)) {}
	~UsbGadget() { close(); }
	UsbGadget(const UsbGadget &) = delete;
	UsbGadget &operator=(const UsbGadget &) = delete;

	// Creates the gadget in configfs and mounts its FunctionFS. The caller
	// then writes the descriptors to functionFsDir()/ep0 before bind().
	int open(const UsbGadgetIdentity &identity);
	const std::string &functionFsDir() const { return ffsDir_; }

	int bind();   // plug in: the host enumerates the device
	int unbind(); // unplug
	bool bound() const { return bound_; }

	// Unbinds, unmounts and removes what open() created. Idempotent.
	void close();

private:
	std::string name_;
	std::string udc_;
	std::string gadgetDir_;
	std::string ffsDir_;
	bool mounted_ = false;
	bool bound_ = false;
};

} // namespace depthkey
