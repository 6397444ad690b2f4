// Comparing secrets (password hashes, remembered passwords) without telling
// the client, by how long it took, how much of its guess was right.
#pragma once

#include <string>

namespace depthkey {

// Every byte is compared whatever differs; only the lengths are compared
// first (a length is no secret worth guessing at).
inline bool equalConstantTime(const std::string &a, const std::string &b)
{
	if (a.size() != b.size())
		return false;
	unsigned char diff = 0;
	for (size_t i = 0; i < a.size(); i++)
		diff |= static_cast<unsigned char>(a[i] ^ b[i]);
	return diff == 0;
}

} // namespace depthkey
