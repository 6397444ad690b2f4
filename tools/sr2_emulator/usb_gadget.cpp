#include "tools/sr2_emulator/usb_gadget.hpp"

#include "hal/unique_fd.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

namespace depthkey {

namespace {

constexpr const char *kConfigfsGadgets = "/sys/kernel/config/usb_gadget";

int writeFile(const std::string &path, const std::string &value)
{
	UniqueFd fd(::open(path.c_str(), O_WRONLY | O_CLOEXEC));
	if (!fd.isValid())
		return -errno;
	if (::write(fd.get(), value.data(), value.size()) < 0)
		return -errno;
	return 0;
}

int makeDir(const std::string &path)
{
	if (::mkdir(path.c_str(), 0755) < 0 && errno != EEXIST)
		return -errno;
	return 0;
}

std::string hex4(uint16_t value)
{
	char text[8];
	std::snprintf(text, sizeof(text), "0x%04x", value);
	return text;
}

} // namespace

int UsbGadget::open(const UsbGadgetIdentity &identity)
{
	if (::access(kConfigfsGadgets, F_OK) < 0) {
		std::fprintf(stderr, "sr2-emulator: %s missing: load libcomposite and mount configfs\n",
			     kConfigfsGadgets);
		return -ENOENT;
	}
	gadgetDir_ = std::string(kConfigfsGadgets) + "/" + name_;
	ffsDir_ = "/run/" + name_ + "-ffs";
	const std::string strings = gadgetDir_ + "/strings/0x409";
	const std::string config = gadgetDir_ + "/configs/c.1";
	const std::string function = gadgetDir_ + "/functions/ffs." + name_;
	int err = 0;
	// Each step stops at the first failure; close() removes what exists.
	for (const std::string &dir : { gadgetDir_, strings, config, config + "/strings/0x409", function })
		if (!err)
			err = makeDir(dir);
	const std::pair<std::string, std::string> attributes[] = {
		{ gadgetDir_ + "/idVendor", hex4(identity.vendorId) },
		{ gadgetDir_ + "/idProduct", hex4(identity.productId) },
		{ gadgetDir_ + "/bcdUSB", "0x0200" },
		{ strings + "/manufacturer", identity.manufacturer },
		{ strings + "/product", identity.product },
		{ strings + "/serialnumber", identity.serial },
		{ config + "/strings/0x409/configuration", "SR-2" },
		// The root hub of dummy_hcd budgets little power: more and usbcore
		// leaves the device unconfigured.
		{ config + "/MaxPower", "100" },
	};
	for (const auto &[path, value] : attributes)
		if (!err)
			err = writeFile(path, value);
	const std::string link = config + "/ffs." + name_;
	if (!err && ::symlink(function.c_str(), link.c_str()) < 0 && errno != EEXIST)
		err = -errno;
	if (!err)
		err = makeDir(ffsDir_);
	if (!err && ::mount(name_.c_str(), ffsDir_.c_str(), "functionfs", 0, nullptr) < 0)
		err = -errno;
	if (err) {
		std::fprintf(stderr, "sr2-emulator: cannot create gadget %s: %s\n", gadgetDir_.c_str(),
			     strerror(-err));
		close();
		return err;
	}
	mounted_ = true;
	return 0;
}

int UsbGadget::bind()
{
	int err = writeFile(gadgetDir_ + "/UDC", udc_);
	if (err)
		return err;
	bound_ = true;
	return 0;
}

int UsbGadget::unbind()
{
	int err = writeFile(gadgetDir_ + "/UDC", "\n");
	if (err)
		return err;
	bound_ = false;
	return 0;
}

void UsbGadget::close()
{
	if (gadgetDir_.empty())
		return;
	if (bound_)
		unbind();
	if (mounted_)
		::umount(ffsDir_.c_str());
	mounted_ = false;
	::rmdir(ffsDir_.c_str());
	const std::string config = gadgetDir_ + "/configs/c.1";
	::unlink((config + "/ffs." + name_).c_str());
	for (const std::string &dir : { config + "/strings/0x409", config, gadgetDir_ + "/functions/ffs." + name_,
					gadgetDir_ + "/strings/0x409", gadgetDir_ })
		::rmdir(dir.c_str());
	gadgetDir_.clear();
}

} // namespace depthkey
