#include "tools/sr2_emulator/ffs_descriptors.hpp"

#include <cstring>
#include <endian.h>
#include <linux/usb/ch9.h>
#include <linux/usb/functionfs.h>

namespace depthkey {

namespace {

struct [[gnu::packed]] InterfaceDescriptors {
	usb_interface_descriptor interface;
	usb_endpoint_descriptor_no_audio in;
	usb_endpoint_descriptor_no_audio out;
};

struct [[gnu::packed]] DescriptorBlob {
	usb_functionfs_descs_head_v2 header;
	uint32_t fullSpeedCount;
	uint32_t highSpeedCount;
	InterfaceDescriptors fullSpeed;
	InterfaceDescriptors highSpeed;
};

InterfaceDescriptors interfaceDescriptors(uint8_t endpointIn, uint8_t endpointOut, uint16_t maxPacket)
{
	InterfaceDescriptors d{};
	d.interface.bLength = sizeof(d.interface);
	d.interface.bDescriptorType = USB_DT_INTERFACE;
	d.interface.bNumEndpoints = 2;
	d.interface.bInterfaceClass = USB_CLASS_VENDOR_SPEC;
	d.interface.iInterface = 1;
	for (auto *ep : { &d.in, &d.out }) {
		ep->bLength = sizeof(*ep);
		ep->bDescriptorType = USB_DT_ENDPOINT;
		ep->bmAttributes = USB_ENDPOINT_XFER_BULK;
		ep->wMaxPacketSize = htole16(maxPacket);
	}
	d.in.bEndpointAddress = endpointIn;
	d.out.bEndpointAddress = endpointOut;
	return d;
}

template<typename T>
std::vector<uint8_t> bytesOf(const T &value)
{
	std::vector<uint8_t> bytes(sizeof(value));
	std::memcpy(bytes.data(), &value, sizeof(value));
	return bytes;
}

} // namespace

std::vector<uint8_t> sr2FunctionFsDescriptors(uint8_t endpointIn, uint8_t endpointOut)
{
	DescriptorBlob blob{};
	blob.header.magic = htole32(FUNCTIONFS_DESCRIPTORS_MAGIC_V2);
	blob.header.length = htole32(sizeof(blob));
	blob.header.flags = htole32(FUNCTIONFS_HAS_FS_DESC | FUNCTIONFS_HAS_HS_DESC |
				    FUNCTIONFS_ALL_CTRL_RECIP);
	blob.fullSpeedCount = htole32(3);
	blob.highSpeedCount = htole32(3);
	blob.fullSpeed = interfaceDescriptors(endpointIn, endpointOut, 64);
	blob.highSpeed = interfaceDescriptors(endpointIn, endpointOut, 512);
	return bytesOf(blob);
}

std::vector<uint8_t> sr2FunctionFsStrings()
{
	static constexpr char kInterfaceName[] = "Swiss Ranger 2 (emulated)";
	struct [[gnu::packed]] {
		usb_functionfs_strings_head header;
		uint16_t language;
		char name[sizeof(kInterfaceName)];
	} blob{};
	blob.header.magic = htole32(FUNCTIONFS_STRINGS_MAGIC);
	blob.header.length = htole32(sizeof(blob));
	blob.header.str_count = htole32(1);
	blob.header.lang_count = htole32(1);
	blob.language = htole16(0x0409);
	std::memcpy(blob.name, kInterfaceName, sizeof(kInterfaceName));
	return bytesOf(blob);
}

} // namespace depthkey
