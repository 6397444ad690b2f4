// The FunctionFS descriptor and string blobs of the emulated SR-2: one vendor
// interface with bulk IN 0x88 (frames) and bulk OUT 0x02 (register writes),
// written to ep0 before the gadget is bound.
#pragma once

#include <cstdint>
#include <vector>

namespace depthkey {

// The UDC assigns the endpoint numbers: the first bulk IN endpoint of the
// HIL VM's dummy_hcd is number 8 (tests/hil/kmod), the first bulk OUT one 2,
// so the host sees 0x88 and 0x02 as on the camera. (FUNCTIONFS_VIRTUAL_ADDR
// would rename them, but then FunctionFS fails to enable them on 6.1.)
// The endpoint files are ep1 (frames) and ep2 (registers).
// FUNCTIONFS_ALL_CTRL_RECIP hands the device-recipient vendor request 0xB0
// to ep0, which FunctionFS otherwise answers itself.
std::vector<uint8_t> sr2FunctionFsDescriptors(uint8_t endpointIn, uint8_t endpointOut);
std::vector<uint8_t> sr2FunctionFsStrings();

} // namespace depthkey
