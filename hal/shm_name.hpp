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
#pragma once

#include <climits>
#include <string_view>

namespace depthkey {

constexpr size_t kMaxShmNameLength = NAME_MAX - 1; // 254, the leading '/' included

// "" when the daemon can create an object of this name, else why not.
inline const char *shmNameProblem(std::string_view name)
{
	if (name.size() < 2 || name[0] != '/')
		return "must be \"/name\": a leading '/', then letters, digits, '.', '_' or '-'";
	if (name.size() > kMaxShmNameLength)
		return "is longer than 254 characters (the leading '/' included)";
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
