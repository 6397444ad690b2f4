// preview.password_file: crypt(3) hashes checked with libxcrypt, the file's
// mode and owner enforced, bad lines named by file and line.
#include "hal/preview/password_file.hpp"

#include <gtest/gtest.h>

#include <crypt.h>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

using namespace depthkey;

namespace {

std::string hashOf(const char *password, const char *prefix)
{
	char salt[CRYPT_GENSALT_OUTPUT_SIZE];
	if (!crypt_gensalt_rn(prefix, 0, nullptr, 0, salt, sizeof(salt)))
		return {};
	crypt_data data{};
	const char *hash = crypt_r(password, salt, &data);
	return hash && hash[0] != '*' ? hash : std::string();
}

class PasswordFileTest : public ::testing::Test
{
protected:
	std::string write(const std::string &text, mode_t mode)
	{
		std::ofstream(path_) << text;
		chmod(path_.c_str(), mode);
		return path_;
	}
	void TearDown() override { unlink(path_.c_str()); }
	std::string path_ = "/tmp/depthkey-passwd-test-" + std::to_string(getpid());
};

} // namespace

TEST_F(PasswordFileTest, VerifiesYescryptAndSha512Hashes)
{
	const std::string yes = hashOf("chalk dust", "$y$"), sha = hashOf("s3cret", "$6$");
	ASSERT_FALSE(yes.empty());
	ASSERT_FALSE(sha.empty());
	PasswordFile file;
	std::string error;
	ASSERT_EQ(file.load(write("# technicians\n\ntech:" + yes + "\nlead:" + sha + "\n", 0600), error), 0) << error;
	EXPECT_EQ(file.size(), 2u);
	EXPECT_TRUE(file.verify("tech", "chalk dust"));
	EXPECT_TRUE(file.verify("lead", "s3cret"));
	EXPECT_FALSE(file.verify("tech", "chalk dust "));
	EXPECT_FALSE(file.verify("tech", "s3cret")) << "another user's password";
	EXPECT_FALSE(file.verify("nobody", "chalk dust"));
	EXPECT_FALSE(file.verify("tech", ""));
}

TEST_F(PasswordFileTest, RefusesAFileOthersCanRead)
{
	PasswordFile file;
	std::string error;
	EXPECT_EQ(file.load(write("tech:" + hashOf("x", "$y$") + "\n", 0644), error), -EPERM);
	EXPECT_EQ(error, path_ + ": mode 0644 lets other users read or change the password hashes; chmod 600 it");
	EXPECT_EQ(file.load(write("tech:" + hashOf("x", "$y$") + "\n", 0640), error), -EPERM);
	EXPECT_EQ(file.load(write("tech:" + hashOf("x", "$y$") + "\n", 0400), error), 0) << error;
}

TEST_F(PasswordFileTest, NamesTheBadLine)
{
	PasswordFile file;
	std::string error;
	EXPECT_EQ(file.load(write("tech:" + hashOf("x", "$y$") + "\ntech2:plaintext\n", 0600), error), -EINVAL);
	EXPECT_EQ(error.rfind(path_ + ":2: 'tech2': not a crypt(3) hash", 0), 0u) << error;
	EXPECT_EQ(file.load(write("no colon here\n", 0600), error), -EINVAL);
	EXPECT_EQ(error, path_ + ":1: expected USER:HASH");
	EXPECT_EQ(file.load(write("# nothing\n", 0600), error), -EINVAL);
	EXPECT_EQ(error, path_ + ": no USER:HASH line");
	EXPECT_EQ(file.load("/nonexistent/passwd", error), -ENOENT);
	EXPECT_NE(error.find("/nonexistent/passwd: cannot open"), std::string::npos);
}
