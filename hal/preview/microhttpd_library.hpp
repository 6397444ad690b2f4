// libmicrohttpd, loaded with dlopen() when the preview's first client
// connects, not when depthkeyd starts (issue 15).
//
// Why: Debian's libmicrohttpd12 links GnuTLS, and its constructor
// initialises it, so merely linking the library costs every depthkeyd about
// 2.5 MB of resident memory (libgnutls, p11-kit, nettle, hogweed, gmp,
// libunistring, libtasn1 and libmicrohttpd itself) for a page a technician
// opens while installing the box and rarely after. The preview's listening
// socket is ours (hal/preview/preview_server.cpp), so the box can listen
// without the library and load it when somebody knocks.
//
// Only the functions the preview calls are looked up, each typed by the
// header's own declaration (decltype), so a signature the header changes
// fails to compile rather than to run. Once loaded the library stays loaded
// for the life of the process (a reload of [preview] reuses it).
#pragma once

#include <microhttpd.h>
#include <string>

namespace depthkey {

struct MicroHttpd {
	decltype(&::MHD_start_daemon) startDaemon;
	decltype(&::MHD_stop_daemon) stopDaemon;
	decltype(&::MHD_create_response_from_buffer) createResponseFromBuffer;
	decltype(&::MHD_create_response_from_callback) createResponseFromCallback;
	decltype(&::MHD_add_response_header) addResponseHeader;
	decltype(&::MHD_queue_response) queueResponse;
	decltype(&::MHD_destroy_response) destroyResponse;
	decltype(&::MHD_basic_auth_get_username_password) basicAuthGetUsernamePassword;
	decltype(&::MHD_queue_basic_auth_fail_response) queueBasicAuthFailResponse;
	decltype(&::MHD_free) free;
	decltype(&::MHD_get_connection_info) getConnectionInfo;
	decltype(&::MHD_lookup_connection_value) lookupConnectionValue;
};

// The library's soname, as Debian's libmicrohttpd12 installs it.
inline constexpr const char *kMicroHttpdSoname = "libmicrohttpd.so.12";

// Loads the library (the first call; later calls return the same table)
// and returns its functions, or null with error naming the library and
// what failed. Thread-safe. A failed load is tried again on the next call.
const MicroHttpd *loadMicroHttpd(std::string &error);

} // namespace depthkey
