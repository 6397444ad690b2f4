// Reading a whole text file with the errno that says why it failed.
#pragma once

#include <string>

namespace depthkey {

// Returns 0, or a negative errno (ENOENT, EACCES, EISDIR...), which is what a
// technician needs to fix it, with step set to "open" or "read".
int readTextFile(const std::string &path, std::string &text, const char *&step);

} // namespace depthkey
