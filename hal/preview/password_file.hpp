// preview.password_file: the accounts allowed on the preview page when it
// listens beyond loopback. One "USER:HASH" per line (blank lines and # comments
// allowed), HASH a crypt(3) hash that libxcrypt checks (yescrypt from
// `mkpasswd -m yescrypt`, bcrypt from `htpasswd -nB`, sha512crypt, ...).
// The file must be a regular file of our user (or root) that nobody else may
// read or write (mode 0600 or 0400): the hashes are worth guessing at.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace depthkey {

class PasswordFile
{
public:
	// Returns 0, or a negative errno with error naming the file (and line).
	int load(const std::string &path, std::string &error);
	// Hashes the password with the user's salt and compares in constant
	// time. Costs what the hash costs (yescrypt: some ms): callers cache.
	bool verify(const std::string &user, const std::string &password) const;
	size_t size() const { return accounts_.size(); }

private:
	std::vector<std::pair<std::string, std::string>> accounts_; // user, hash
};

} // namespace depthkey
