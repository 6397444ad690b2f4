// Who may see the preview (hal/preview/preview_auth.hpp, issue 31): a
// reload re-reads the password file, so changed and removed passwords stop
// working at once; a refused file closes the page; wrong passwords back off
// per client address and all hashing has a budget, both without hashing.
// Times are given, so nothing here sleeps.
#include "hal/preview/failure_limiter.hpp"
#include "hal/preview/preview_auth.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <crypt.h>
#include <cstdio>
#include <netinet/in.h>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

using namespace depthkey;

namespace {

constexpr uint64_t kSecond = 1000000000ull;

class PreviewAuthTest : public ::testing::Test
{
protected:
	void SetUp() override
	{
		char dir[] = "/tmp/depthkey-preview-auth-test-XXXXXX";
		ASSERT_NE(mkdtemp(dir), nullptr);
		dir_ = dir;
		path_ = dir_ + "/passwords";
	}
	void TearDown() override
	{
		unlink(path_.c_str());
		rmdir(dir_.c_str());
	}

	// "USER:HASH" lines from "user:password" pairs (the fewest rounds
	// crypt allows: the tests hash often); raw lines are written as given.
	void write(const std::vector<std::pair<std::string, std::string>> &accounts, const std::string &raw = "")
	{
		FILE *f = std::fopen(path_.c_str(), "w");
		ASSERT_NE(f, nullptr);
		for (const auto &[user, password] : accounts) {
			crypt_data data{};
			std::fprintf(f, "%s:%s\n", user.c_str(), crypt_r(password.c_str(), "$6$rounds=1000$dktest$", &data));
		}
		std::fputs(raw.c_str(), f);
		std::fclose(f);
		chmod(path_.c_str(), 0600);
	}

	std::string dir_, path_;
};

} // namespace

TEST_F(PreviewAuthTest, AReloadRevokesChangedAndRemovedPasswordsAtOnce)
{
	PreviewAuth auth;
	std::string error;
	write({ { "alice", "old" }, { "bob", "bob1" } });
	ASSERT_EQ(auth.load(path_, error), 0) << error;
	// Both verified, so both in the cache: the reload must empty it.
	EXPECT_EQ(auth.check("10.0.0.1", "alice", "old", 0), AuthVerdict::Allowed);
	EXPECT_EQ(auth.check("10.0.0.1", "bob", "bob1", 0), AuthVerdict::Allowed);
	EXPECT_EQ(auth.check("10.0.0.1", "alice", "old", 0), AuthVerdict::Allowed);

	write({ { "alice", "new" }, { "carol", "carol1" } });
	ASSERT_EQ(auth.load(path_, error), 0) << error;
	EXPECT_EQ(auth.check("10.0.0.2", "alice", "old", kSecond), AuthVerdict::Refused);
	EXPECT_EQ(auth.check("10.0.0.2", "bob", "bob1", kSecond), AuthVerdict::Refused);
	EXPECT_EQ(auth.check("10.0.0.2", "alice", "new", kSecond), AuthVerdict::Allowed);
	EXPECT_EQ(auth.check("10.0.0.2", "carol", "carol1", kSecond), AuthVerdict::Allowed);
}

TEST_F(PreviewAuthTest, ARefusedFileClosesThePageUntilAGoodOneIsRead)
{
	PreviewAuth auth;
	std::string error;
	write({ { "alice", "a1" } });
	ASSERT_EQ(auth.load(path_, error), 0) << error;
	EXPECT_EQ(auth.check("10.0.0.1", "alice", "a1", 0), AuthVerdict::Allowed);

	write({ { "alice", "a2" } }, "bob:not-a-hash\n");
	EXPECT_LT(auth.load(path_, error), 0);
	EXPECT_NE(error.find(path_ + ":2: 'bob': not a crypt(3) hash"), std::string::npos) << error;
	// Neither the old password (cached) nor the new one: the page is shut.
	EXPECT_EQ(auth.check("10.0.0.1", "alice", "a1", 0), AuthVerdict::Closed);
	EXPECT_EQ(auth.check("10.0.0.1", "alice", "a2", 0), AuthVerdict::Closed);
	EXPECT_EQ(auth.stats().failures, 0u) << "nothing was hashed";

	write({ { "alice", "a2" } });
	ASSERT_EQ(auth.load(path_, error), 0) << error;
	EXPECT_EQ(auth.check("10.0.0.1", "alice", "a2", 0), AuthVerdict::Allowed);
	EXPECT_EQ(auth.check("10.0.0.1", "alice", "a1", 0), AuthVerdict::Refused);
}

TEST_F(PreviewAuthTest, WrongPasswordsBackOffPerAddressWithoutHashing)
{
	PreviewAuthLimits limits;
	limits.perAddress.maxFailures = 5;
	limits.perAddress.windowNs = 60 * kSecond;
	limits.perAddress.backOffNs = 30 * kSecond;
	limits.hashesPerSecond = 1000;
	PreviewAuth auth(limits);
	std::string error;
	write({ { "alice", "right" } });
	ASSERT_EQ(auth.load(path_, error), 0) << error;

	for (int i = 0; i < 5; i++)
		EXPECT_EQ(auth.check("10.0.0.9", "alice", "guess", i * kSecond), AuthVerdict::Refused) << i;
	EXPECT_EQ(auth.stats().failures, 5u);
	EXPECT_EQ(auth.stats().blocks, 1u);
	// Backing off: turned away unhashed, the right password too (it is not
	// known yet: knowing it would need the hash the back-off saves).
	EXPECT_EQ(auth.check("10.0.0.9", "alice", "guess", 5 * kSecond), AuthVerdict::Limited);
	EXPECT_EQ(auth.check("10.0.0.9", "alice", "right", 6 * kSecond), AuthVerdict::Limited);
	EXPECT_EQ(auth.stats().failures, 5u) << "no hash while backing off";
	EXPECT_EQ(auth.stats().limited, 2u);
	// Another address is not held back by this one.
	EXPECT_EQ(auth.check("10.0.0.10", "alice", "right", 6 * kSecond), AuthVerdict::Allowed);
	// After the back-off the address is checked again.
	EXPECT_EQ(auth.check("10.0.0.9", "alice", "right", 35 * kSecond), AuthVerdict::Allowed);
}

TEST_F(PreviewAuthTest, AKnownPasswordGetsInWhileItsAddressBacksOff)
{
	PreviewAuth auth;
	std::string error;
	write({ { "alice", "right" } });
	ASSERT_EQ(auth.load(path_, error), 0) << error;
	// Through ssh -L every client is 127.0.0.1: a guesser there must not
	// lock out the technician whose password was verified already.
	EXPECT_EQ(auth.check("127.0.0.1", "alice", "right", 0), AuthVerdict::Allowed);
	for (int i = 0; i < 20; i++)
		auth.check("127.0.0.1", "alice", "guess", kSecond);
	EXPECT_GT(auth.stats().limited, 0u);
	EXPECT_EQ(auth.check("127.0.0.1", "alice", "right", kSecond), AuthVerdict::Allowed);
	EXPECT_EQ(auth.check("127.0.0.1", "alice", "righ", kSecond), AuthVerdict::Limited);
	EXPECT_EQ(auth.check("127.0.0.1", "alice", "right!", kSecond), AuthVerdict::Limited);
}

TEST_F(PreviewAuthTest, AllHashingTogetherHasABudgetPerSecond)
{
	PreviewAuthLimits limits;
	limits.hashesPerSecond = 3;
	PreviewAuth auth(limits);
	std::string error;
	write({ { "alice", "right" } });
	ASSERT_EQ(auth.load(path_, error), 0) << error;
	// Ten addresses, one guess each, in the same instant: 3 are hashed.
	int refused = 0, limited = 0;
	for (int i = 0; i < 10; i++) {
		const AuthVerdict v = auth.check("10.1.0." + std::to_string(i), "alice", "guess", 10 * kSecond);
		refused += v == AuthVerdict::Refused;
		limited += v == AuthVerdict::Limited;
	}
	EXPECT_EQ(refused, 3);
	EXPECT_EQ(limited, 7);
	EXPECT_EQ(auth.check("10.2.0.1", "alice", "right", 10 * kSecond), AuthVerdict::Limited);
	// A second later the budget is back.
	EXPECT_EQ(auth.check("10.2.0.1", "alice", "right", 11 * kSecond), AuthVerdict::Allowed);
}

TEST_F(PreviewAuthTest, MissingCredentialsCostNothingAndCountNothing)
{
	PreviewAuth auth;
	std::string error;
	write({ { "alice", "right" } });
	ASSERT_EQ(auth.load(path_, error), 0) << error;
	for (int i = 0; i < 50; i++)
		EXPECT_EQ(auth.check("10.0.0.1", nullptr, nullptr, 0), AuthVerdict::Refused);
	EXPECT_EQ(auth.stats().failures, 0u);
	EXPECT_EQ(auth.stats().limited, 0u);
	EXPECT_EQ(auth.check("10.0.0.1", "alice", "right", 0), AuthVerdict::Allowed);
}

TEST(FailureLimiter, RemembersABoundedNumberOfAddresses)
{
	FailureLimits limits;
	limits.maxFailures = 2;
	limits.maxAddresses = 3;
	FailureLimiter limiter(limits);
	for (int i = 0; i < 10; i++)
		limiter.failed("10.0.0." + std::to_string(i), uint64_t(i));
	EXPECT_LE(limiter.addresses(), 3u);
	// The newest are kept: 10.0.0.9 backs off at its second failure.
	EXPECT_TRUE(limiter.failed("10.0.0.9", 20));
	EXPECT_TRUE(limiter.blocked("10.0.0.9", 21));
	limiter.succeeded("10.0.0.9");
	EXPECT_FALSE(limiter.blocked("10.0.0.9", 22));
}

TEST(FailureLimiter, FailuresOutsideTheWindowAreForgotten)
{
	FailureLimits limits;
	limits.maxFailures = 3;
	limits.windowNs = 10 * kSecond;
	FailureLimiter limiter(limits);
	EXPECT_FALSE(limiter.failed("a", 0));
	EXPECT_FALSE(limiter.failed("a", kSecond));
	EXPECT_FALSE(limiter.failed("a", 11 * kSecond)); // a new window: 1
	EXPECT_FALSE(limiter.failed("a", 12 * kSecond));
	EXPECT_TRUE(limiter.failed("a", 13 * kSecond));
	EXPECT_TRUE(limiter.blocked("a", 14 * kSecond));
}

TEST(ClientAddressKey, IPv4WholeAndIPv6ByItsSlash64)
{
	sockaddr_in v4{};
	v4.sin_family = AF_INET;
	inet_pton(AF_INET, "192.168.10.7", &v4.sin_addr);
	v4.sin_port = htons(40000);
	EXPECT_EQ(clientAddressKey(reinterpret_cast<sockaddr *>(&v4)), "192.168.10.7");
	sockaddr_in6 a{}, b{};
	a.sin6_family = b.sin6_family = AF_INET6;
	inet_pton(AF_INET6, "2001:db8:1:2::1", &a.sin6_addr);
	inet_pton(AF_INET6, "2001:db8:1:2:ffff::99", &b.sin6_addr);
	EXPECT_EQ(clientAddressKey(reinterpret_cast<sockaddr *>(&a)), "2001:db8:1:2::/64");
	EXPECT_EQ(clientAddressKey(reinterpret_cast<sockaddr *>(&a)), clientAddressKey(reinterpret_cast<sockaddr *>(&b)));
	EXPECT_EQ(clientAddressKey(nullptr), "");
}
