// Replacing a file so that a reader never sees half of it.
#pragma once

#include <string>
#include <string_view>

namespace depthkey {

// Replaces path with text: writes a temporary file in the same directory,
// fsyncs it, renames it over path and fsyncs the directory, so that after a
// crash or power cut path holds either the old content or the new, whole.
// Returns 0, or a negative errno with error saying which step failed on
// which file; the temporary is removed on failure and path is untouched.
int writeFileAtomically(const std::string &path, std::string_view text, std::string &error);

} // namespace depthkey
