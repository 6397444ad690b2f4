#include "hal/preview/microhttpd_library.hpp"

#include <dlfcn.h>
#include <mutex>

namespace depthkey {

namespace {

std::mutex loadMutex;
MicroHttpd table;
bool loaded = false;

template<typename Function>
bool lookUp(void *handle, const char *name, Function &out, std::string &error)
{
	dlerror();
	out = reinterpret_cast<Function>(dlsym(handle, name));
	if (out)
		return true;
	const char *why = dlerror();
	error = std::string("cannot load ") + kMicroHttpdSoname + ": no " + name + (why ? std::string(": ") + why : "");
	return false;
}

} // namespace

const MicroHttpd *loadMicroHttpd(std::string &error)
{
	std::lock_guard lock(loadMutex);
	if (loaded)
		return &table;
	void *handle = dlopen(kMicroHttpdSoname, RTLD_NOW | RTLD_LOCAL);
	if (!handle) {
		const char *why = dlerror();
		error = std::string("cannot load ") + kMicroHttpdSoname + ": " + (why ? why : "dlopen failed") +
			" (package libmicrohttpd12)";
		return nullptr;
	}
	MicroHttpd t{};
	const bool ok = lookUp(handle, "MHD_start_daemon", t.startDaemon, error) &&
			lookUp(handle, "MHD_stop_daemon", t.stopDaemon, error) &&
			lookUp(handle, "MHD_create_response_from_buffer", t.createResponseFromBuffer, error) &&
			lookUp(handle, "MHD_create_response_from_callback", t.createResponseFromCallback, error) &&
			lookUp(handle, "MHD_add_response_header", t.addResponseHeader, error) &&
			lookUp(handle, "MHD_queue_response", t.queueResponse, error) &&
			lookUp(handle, "MHD_destroy_response", t.destroyResponse, error) &&
			lookUp(handle, "MHD_basic_auth_get_username_password", t.basicAuthGetUsernamePassword, error) &&
			lookUp(handle, "MHD_queue_basic_auth_fail_response", t.queueBasicAuthFailResponse, error) &&
			lookUp(handle, "MHD_free", t.free, error) &&
			lookUp(handle, "MHD_get_connection_info", t.getConnectionInfo, error) &&
			lookUp(handle, "MHD_lookup_connection_value", t.lookupConnectionValue, error);
	if (!ok) {
		dlclose(handle);
		return nullptr;
	}
	table = t;
	loaded = true; // the handle is never closed: its functions stay in use
	return &table;
}

} // namespace depthkey
