// The rule for a shared-memory object name the daemon can create, shared by
// the config check (--check-config, a reload) and ShmRingWriter::open(), so
// that a name the check passes is one the writer can create.
//
// "/name": a leading '/', then only letters, digits, '.', '_' and '-' (no
// '/', no control or non-ASCII characters: they cannot be typed reliably
// into a viewer's settings, and a newline would break the journal line that
// names the object), not "/." or "/.." (directories), at most
// kMaxShmNameLength characters including the slash.
//
// The limit: the object is the file /dev/shm/<name after the slash>, and
// glibc before 2.34 refuses a name whose length after the slash plus its NUL
// reaches NAME_MAX (255), i.e. longer than 253; newer glibc takes 255. We take
// the older bound, 254 with the slash, so a config is portable across the
// boxes' C libraries (header-only: the config fuzzer links config/ alone).
// The stream's presence object (hal/depthkey_shm.h) adds ".readers" to the
// name, so a stream name may have 246 characters.
#pragma once

#include "hal/depthkey_shm.h"

#include <climits>
#include <string>
#include <string_view>

namespace depthkey {

constexpr size_t kMaxShmNameLength = DK_SHM_NAME_MAX; // 246, the leading '/' included
static_assert(DK_SHM_NAME_MAX + sizeof(DK_SHM_PRESENCE_SUFFIX) - 1 == NAME_MAX - 1);

// The stream's presence object (readers' heartbeats), for a valid name.
inline std::string shmPresenceName(std::string_view name)
{
	return std::string(name) + DK_SHM_PRESENCE_SUFFIX;
}

// "" when the daemon can create an object of this name, else why not.
inline const char *shmNameProblem(std::string_view name)
{
	if (name.size() < 2 || name[0] != '/')
		return "must be \"/name\": a leading '/', then letters, digits, '.', '_' or '-'";
	if (name.size() > kMaxShmNameLength)
		return "is longer than 246 characters (the leading '/' included; \".readers\" is added for the readers' object)";
	if (name == "/." || name == "/..")
		return "must not be \"/.\" or \"/..\"";
	for (char c : name.substr(1)) {
		bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
			  c == '_' || c == '-';
		if (!ok)
			return "may hold only letters, digits, '.', '_' and '-' after its leading '/'";
	}
	return "";
}

} // namespace depthkey
