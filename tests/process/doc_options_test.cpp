// Docs that stay true (issue 30): every `--option` that docs/, README.md and
// the man pages give a depthkey program is one its --help accepts, and every
// option a program's --help lists is in its man page.
//
// Which program an option belongs to is read as a person reads it: the
// program last named before it in the same paragraph, list item, table row
// or code line (or the section whose heading names one, or the man page's
// own program); another command named in between (make, ffmpeg, curl, an
// environment variable...) ends that, and its options are not checked.
// gcc 12 warns inside <regex>'s std::function under -fsanitize (a false
// -Wmaybe-uninitialized in libstdc++'s own code, which -Werror makes an
// error in `make SAN=1`); this test only reads docs, and only here.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "tests/process/shell_command.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace depthkey;

namespace {

const std::vector<std::string> kPrograms = { "depthkeyd", "depthkey-calibrate", "depthkey-eval", "depthkey-shmcat",
					     "depthkey-siox" };

std::string manPage(const std::string &program)
{
	return test::sourceDir() + "/man/" + program + (program == "depthkeyd" ? ".8" : ".1");
}

std::string readFile(const std::string &path)
{
	std::ifstream in(path);
	std::stringstream text;
	text << in.rdbuf();
	return text.str();
}

// A program's --help, as the options it names.
std::set<std::string> optionsIn(const std::string &text)
{
	std::set<std::string> options;
	static const std::regex option(R"((^|[^A-Za-z0-9_-])(--[a-z][a-z0-9-]*)(?![A-Za-z0-9_]))");
	for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it)
		options.insert((*it)[2]);
	return options;
}

std::set<std::string> helpOptions(const std::string &program)
{
	int status = 0;
	std::string out = test::run(test::binDir() + "/" + program + " --help", status);
	EXPECT_EQ(status, 0) << program << " --help: " << out;
	std::set<std::string> options = optionsIn(out);
	options.insert("--help");
	return options;
}

// Roff as text: \- is -, font escapes go.
std::string roffText(std::string text)
{
	text = std::regex_replace(text, std::regex(R"(\\-)"), "-");
	text = std::regex_replace(text, std::regex(R"(\\f[BIRP])"), "");
	return text;
}

struct Use {
	std::string program, option, where;
};

bool isProgram(const std::string &word)
{
	for (const std::string &p : kPrograms)
		if (word == p)
			return true;
	return false;
}

// The options in one block of text attributed to programs. A word that
// begins a command (the first of a code line or code span, or one after |,
// &&, ;, $( ) names the program that follows; a program's name anywhere
// does too.
void scanBlock(const std::string &block, const std::string &initial, const std::string &where, std::vector<Use> &uses)
{
	std::string current = initial;
	bool commandStart = true, inSpan = false, spanStart = false;
	size_t i = 0;
	while (i < block.size()) {
		char c = block[i];
		if (c == '`')
			spanStart = inSpan = !inSpan;
		if (c == '`' || c == '|' || c == ';' || c == '\n' || c == '(' || (c == '&' && i + 1 < block.size() && block[i + 1] == '&')) {
			commandStart = true;
			i++;
			continue;
		}
		if (std::isspace(static_cast<unsigned char>(c)) || c == '$' || c == '&' || c == '"' || c == '\'') {
			i++;
			continue;
		}
		size_t end = i;
		while (end < block.size() && !std::isspace(static_cast<unsigned char>(block[end])) &&
		       std::string("`|;()\"',").find(block[end]) == std::string::npos)
			end++;
		if (end == i) { // a ")" or "," on its own
			i++;
			continue;
		}
		std::string word = block.substr(i, end - i);
		std::string base = word.substr(word.rfind('/') == std::string::npos ? 0 : word.rfind('/') + 1);
		while (!base.empty() && (base.back() == '.' || base.back() == ':' || base.back() == '\'' || base.back() == ')'))
			base.pop_back();
		// A code span that begins with an option (`--csv` writes...) is
		// the section's program speaking, whatever the prose named before.
		if (spanStart && word.rfind("--", 0) == 0)
			current = initial;
		spanStart = false;
		std::smatch m;
		if (word.rfind("--", 0) == 0 && std::regex_match(word, m, std::regex(R"((--[a-z][a-z0-9-]*)([=.,:;)\]]*.*)?)")) &&
		    (m[2].str().empty() || !std::isalnum(static_cast<unsigned char>(m[2].str()[0])))) {
			if (!current.empty())
				uses.push_back({ current, m[1], where });
		} else if (isProgram(base)) {
			current = base;
		} else if (word.find('=') != std::string::npos && word[0] != '-') {
			current.clear(); // VAR=value: make's or the environment's
		} else if (commandStart && !word.empty() && word[0] != '-' && std::isalpha(static_cast<unsigned char>(word[0])) &&
			   word != "sudo" && word != "exec" && word != "timeout") {
			current.clear(); // another command
		}
		commandStart = false;
		i = end;
	}
}

// Markdown: paragraphs, list items, table rows, fenced code lines.
void scanMarkdown(const std::string &path, std::vector<Use> &uses)
{
	std::istringstream in(readFile(path));
	std::string line, block, section;
	int lineNo = 0, blockLine = 0;
	bool fenced = false;
	auto flush = [&] {
		if (!block.empty())
			scanBlock(block, section, path + ":" + std::to_string(blockLine), uses);
		block.clear();
	};
	while (std::getline(in, line)) {
		lineNo++;
		if (line.rfind("```", 0) == 0) {
			flush();
			fenced = !fenced;
			continue;
		}
		bool starts = fenced || line.empty() || line[0] == '#' || line[0] == '|' || line.rfind("- ", 0) == 0 ||
			      std::regex_search(line, std::regex(R"(^\d+\. )"));
		if (starts)
			flush();
		if (!fenced && !line.empty() && line[0] == '#') {
			section.clear();
			for (const std::string &p : kPrograms)
				if (std::regex_search(line, std::regex("(^|[^a-z-])" + p + "($|[^a-z-])")))
					section = p;
			continue;
		}
		if (block.empty())
			blockLine = lineNo;
		block += line + "\n";
	}
	flush();
}

// A man page: each paragraph macro starts a block; the page's program is
// every block's first.
void scanManPage(const std::string &path, const std::string &program, std::vector<Use> &uses)
{
	std::istringstream in(roffText(readFile(path)));
	std::string line, block;
	int lineNo = 0, blockLine = 0;
	auto flush = [&] {
		if (!block.empty())
			scanBlock(block, program, path + ":" + std::to_string(blockLine), uses);
		block.clear();
	};
	while (std::getline(in, line)) {
		lineNo++;
		if (std::regex_search(line, std::regex(R"(^\.(PP|TP|SH|SS|EX|EE|IP|br))")))
			flush();
		if (block.empty())
			blockLine = lineNo;
		// Macro names are not words of the text.
		block += std::regex_replace(line, std::regex(R"(^\.[A-Z]+ ?)"), "") + " ";
	}
	flush();
}

} // namespace

TEST(DocOptions, EveryOptionTheDocsGiveAProgramIsInItsHelp)
{
	std::map<std::string, std::set<std::string>> help;
	for (const std::string &p : kPrograms)
		help[p] = helpOptions(p);

	std::vector<Use> uses;
	for (const auto &entry : std::filesystem::directory_iterator(test::sourceDir() + "/docs"))
		if (entry.path().extension() == ".md")
			scanMarkdown(entry.path().string(), uses);
	scanMarkdown(test::sourceDir() + "/README.md", uses);
	for (const std::string &p : kPrograms)
		scanManPage(manPage(p), p, uses);

	ASSERT_GT(uses.size(), 100u); // the scan found the docs' options at all
	for (const Use &u : uses)
		EXPECT_TRUE(help[u.program].count(u.option))
			<< u.where << ": " << u.program << " " << u.option << " is not in " << u.program << " --help";
}

TEST(DocOptions, EveryOptionOfAProgramIsInItsManPage)
{
	for (const std::string &p : kPrograms) {
		std::set<std::string> man = optionsIn(roffText(readFile(manPage(p))));
		for (const std::string &option : helpOptions(p))
			EXPECT_TRUE(man.count(option)) << manPage(p) << " does not mention " << p << " " << option;
	}
}
