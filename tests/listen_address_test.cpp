// preview.listen: IP literals only, loopback told apart, and the config
// refuses an address off loopback without a password file.
#include "config/config_loader.hpp"
#include "config/listen_address.hpp"

#include <gtest/gtest.h>

using namespace depthkey;

TEST(ListenAddress, ParsesIpv4AndIpv6Literals)
{
	ListenAddress a;
	ASSERT_EQ(parseListenAddress("127.0.0.1:8080", a), "");
	EXPECT_EQ(a.ip, "127.0.0.1");
	EXPECT_EQ(a.port, 8080);
	EXPECT_FALSE(a.ipv6);
	EXPECT_TRUE(a.loopback);
	ASSERT_EQ(parseListenAddress("[::1]:0", a), "");
	EXPECT_EQ(a.ip, "::1");
	EXPECT_EQ(a.port, 0);
	EXPECT_TRUE(a.ipv6);
	EXPECT_TRUE(a.loopback);
	ASSERT_EQ(parseListenAddress("192.168.1.20:80", a), "");
	EXPECT_FALSE(a.loopback);
	ASSERT_EQ(parseListenAddress("127.1.2.3:1", a), "");
	EXPECT_TRUE(a.loopback) << "all of 127/8 is loopback";
	ASSERT_EQ(parseListenAddress("[fe80::1]:8080", a), "");
	EXPECT_FALSE(a.loopback);
}

TEST(ListenAddress, RefusesWhatIsNotIpPort)
{
	ListenAddress a;
	EXPECT_NE(parseListenAddress("localhost:8080", a).find("host names are not accepted"), std::string::npos);
	EXPECT_EQ(parseListenAddress("127.0.0.1:65536", a), "port must be 0..65535");
	EXPECT_EQ(parseListenAddress("127.0.0.1:80x", a), "port must be 0..65535");
	EXPECT_NE(parseListenAddress("127.0.0.1", a), "");
	EXPECT_NE(parseListenAddress(":8080", a), "");
	EXPECT_NE(parseListenAddress("::1:8080", a), "") << "IPv6 needs brackets";
	EXPECT_NE(parseListenAddress("[::1:8080", a), "");
	EXPECT_NE(parseListenAddress("[zz::1]:8080", a).find("not an IPv6 address"), std::string::npos);
}

TEST(ListenAddress, ConfigRefusesTheNetworkWithoutAPassword)
{
	ConfigResult r = parseConfig("[preview]\nlisten = \"0.0.0.0:8080\"\n", "t.toml");
	ASSERT_EQ(r.errors.size(), 1u);
	EXPECT_EQ(r.errors[0].toString().rfind("t.toml:2:", 0), 0u) << r.errors[0].toString();
	EXPECT_NE(r.errors[0].toString().find("preview.listen"), std::string::npos) << r.errors[0].toString();
	EXPECT_NE(r.errors[0].toString().find("set preview.password_file"), std::string::npos);

	EXPECT_TRUE(parseConfig("[preview]\nlisten = \"0.0.0.0:8080\"\npassword_file = \"/etc/depthkey/preview.passwd\"\n",
				"t.toml")
			    .ok());
	EXPECT_TRUE(parseConfig("[preview]\nlisten = \"\"\n", "t.toml").ok()) << "off";
	ConfigResult bad = parseConfig("[preview]\nlisten = \"box:80\"\npassword_file = \"rel/path\"\n", "t.toml");
	EXPECT_EQ(bad.errors.size(), 2u);
	Settings defaults;
	EXPECT_EQ(defaults.preview.listen, "127.0.0.1:8080");
	EXPECT_EQ(parseConfig("", "t.toml").settings.preview.listen, "127.0.0.1:8080");
}
