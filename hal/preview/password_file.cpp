#include "hal/preview/password_file.hpp"

#include "hal/preview/constant_time.hpp"
#include "hal/unique_fd.hpp"

#include <cerrno>
#include <crypt.h>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace depthkey {

namespace {

std::string modeText(mode_t mode)
{
	char text[8];
	std::snprintf(text, sizeof(text), "%04o", static_cast<unsigned>(mode & 07777));
	return text;
}

} // namespace

int PasswordFile::load(const std::string &path, std::string &error)
{
	accounts_.clear();
	UniqueFd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW));
	if (!fd.isValid()) {
		int ret = -errno;
		error = path + ": cannot open: " + std::strerror(errno);
		return ret;
	}
	struct stat st{};
	if (fstat(fd.get(), &st) < 0 || !S_ISREG(st.st_mode)) {
		error = path + ": not a regular file";
		return -EINVAL;
	}
	if (st.st_mode & 077) {
		error = path + ": mode " + modeText(st.st_mode) +
			" lets other users read or change the password hashes; chmod 600 it";
		return -EPERM;
	}
	if (st.st_uid != geteuid() && st.st_uid != 0) {
		error = path + ": owned by uid " + std::to_string(st.st_uid) + ", not by this user (" +
			std::to_string(geteuid()) + ") or root";
		return -EPERM;
	}
	std::string text;
	char buffer[4096];
	ssize_t n;
	while ((n = ::read(fd.get(), buffer, sizeof(buffer))) > 0 && text.size() < (1u << 20))
		text.append(buffer, static_cast<size_t>(n));
	fd.reset();

	std::istringstream lines(text);
	std::string line;
	for (int number = 1; std::getline(lines, line); number++) {
		if (!line.empty() && line.back() == '\r')
			line.pop_back();
		if (line.empty() || line[0] == '#')
			continue;
		const std::string at = path + ":" + std::to_string(number) + ": ";
		size_t colon = line.find(':');
		if (colon == 0 || colon == std::string::npos) {
			error = at + "expected USER:HASH";
			return -EINVAL;
		}
		std::string hash = line.substr(colon + 1);
		if (crypt_checksalt(hash.c_str()) != CRYPT_SALT_OK || hash.size() < 13) {
			error = at + "'" + line.substr(0, colon) +
				"': not a crypt(3) hash this system checks (make one with mkpasswd -m yescrypt)";
			return -EINVAL;
		}
		accounts_.emplace_back(line.substr(0, colon), hash);
	}
	if (accounts_.empty()) {
		error = path + ": no USER:HASH line";
		return -EINVAL;
	}
	return 0;
}

bool PasswordFile::verify(const std::string &user, const std::string &password) const
{
	for (const auto &[name, hash] : accounts_) {
		if (name != user)
			continue;
		auto data = std::make_unique<crypt_data>(); // 32 KiB: not on a thread's stack
		const char *result = crypt_r(password.c_str(), hash.c_str(), data.get());
		// crypt_r fails with a string starting '*', never equal to a hash.
		return result && equalConstantTime(result, hash);
	}
	return false;
}

} // namespace depthkey
