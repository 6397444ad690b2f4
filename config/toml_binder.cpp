// The TOML binder: type and range checks, error positions, unknown keys.
#include "config/toml_binder.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>

namespace depthkey {

namespace {

std::string_view typeName(toml::node_type type)
{
	switch (type) {
	case toml::node_type::table:
		return "a table";
	case toml::node_type::array:
		return "an array";
	case toml::node_type::string:
		return "a string";
	case toml::node_type::integer:
		return "an integer";
	case toml::node_type::floating_point:
		return "a floating-point number";
	case toml::node_type::boolean:
		return "a boolean";
	case toml::node_type::date:
	case toml::node_type::time:
	case toml::node_type::date_time:
		return "a date/time";
	default:
		return "nothing";
	}
}

std::string formatNumber(double value)
{
	char buf[32];
	std::snprintf(buf, sizeof(buf), "%g", value);
	return buf;
}

std::string quote(std::string_view s)
{
	return '"' + std::string(s) + '"';
}

// Levenshtein distance, to suggest the key a typo was meant to be, or
// `bound` once it is clear the distance is at least that: only near names
// are suggested, and a file of long or many unknown keys (up to the 1 MB
// cap) must not cost seconds of full distances at a reload (issue 14).
size_t editDistance(std::string_view a, std::string_view b, size_t bound)
{
	// The distance is at least the difference in length.
	if ((a.size() > b.size() ? a.size() - b.size() : b.size() - a.size()) >= bound)
		return bound;
	std::vector<size_t> row(b.size() + 1);
	for (size_t j = 0; j <= b.size(); j++)
		row[j] = j;
	for (size_t i = 1; i <= a.size(); i++) {
		size_t diagonal = row[0];
		row[0] = i;
		size_t least = row[0];
		for (size_t j = 1; j <= b.size(); j++) {
			size_t above = row[j];
			row[j] = std::min({ row[j] + 1, row[j - 1] + 1,
					    diagonal + (a[i - 1] == b[j - 1] ? 0 : 1) });
			diagonal = above;
			least = std::min(least, row[j]);
		}
		// A row's least never shrinks in the rows below it.
		if (least >= bound)
			return bound;
	}
	return std::min(row[b.size()], bound);
}

bool isHex(char c)
{
	return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

} // namespace

TomlBindResult bindToml(std::string_view text, const std::string &file,
			const TomlSchema &schema)
{
	TomlBindResult result;
	toml::table root;

	// Debian's shared libtomlplusplus is built with exceptions only (there is
	// no toml::noex::parse to link against), so the parse error is caught
	// here and goes no further.
	try {
		root = toml::parse(text, std::string_view(file));
	} catch (const toml::parse_error &e) {
		result.errors.push_back({ file, static_cast<int>(e.source().begin.line),
					  static_cast<int>(e.source().begin.column), "",
					  std::string(e.description()) });
		return result;
	}

	size_t omitted = 0;
	TomlSection section(root, "", file, result, omitted);
	schema(section);
	section.reportUnknown();

	// Tables iterate in key order; a technician reads the file top down.
	capErrors(result.errors, omitted, file);
	return result;
}

const toml::node *TomlSection::find(std::string_view key)
{
	known_.emplace_back(key);
	return table_.get(key);
}

bool TomlSection::wrongType(std::string_view key, const toml::node &node,
			    std::string_view expected)
{
	error(node.source(), key, "expected " + std::string(expected) + ", got " +
				  std::string(typeName(node.type())));
	return false;
}

void TomlSection::error(const toml::source_region &where, std::string_view key,
			std::string message)
{
	result_.errors.push_back({ file_, static_cast<int>(where.begin.line),
				   static_cast<int>(where.begin.column), dotted(key),
				   std::move(message) });
	// Keep memory bounded however many errors the file has: now and then
	// only the earliest are kept (capErrors() sorts them into file order).
	constexpr size_t kTrimAt = 16 * kMaxReportedErrors;
	if (result_.errors.size() >= kTrimAt) {
		size_t before = result_.errors.size();
		capErrors(result_.errors, 0, file_);
		if (!result_.errors.empty() && result_.errors.back().omitted)
			result_.errors.pop_back();
		omitted_ += before - result_.errors.size();
	}
}

std::string TomlSection::dotted(std::string_view key) const
{
	return path_.empty() ? std::string(key) : path_ + '.' + std::string(key);
}

bool TomlSection::boolean(std::string_view key, bool &out)
{
	const toml::node *node = find(key);
	if (!node) {
		result_.absent.push_back(dotted(key));
		return true;
	}
	const auto *value = node->as_boolean();
	if (!value)
		return wrongType(key, *node, "a boolean (true or false)");
	out = value->get();
	return true;
}

bool TomlSection::integerValue(std::string_view key, int64_t min, int64_t max,
			       std::optional<int64_t> &out)
{
	const toml::node *node = find(key);
	if (!node) {
		result_.absent.push_back(dotted(key));
		return true;
	}
	const auto *value = node->as_integer();
	if (!value)
		return wrongType(key, *node, "an integer");

	int64_t v = value->get();
	if (v < min || v > max) {
		std::string range = max == std::numeric_limits<int64_t>::max()
					    ? "must be at least " + std::to_string(min)
					    : std::to_string(min) + ".." + std::to_string(max);
		error(node->source(), key, std::to_string(v) + " is out of range: " + range);
		return false;
	}
	out = v;
	return true;
}

std::optional<double> TomlSection::numberValue(std::string_view key, const toml::node &node,
					      double min, double max)
{
	std::optional<double> value;
	if (const auto *f = node.as_floating_point())
		value = f->get();
	else if (const auto *i = node.as_integer())
		value = static_cast<double>(i->get());
	if (!value) {
		wrongType(key, node, "a number");
		return std::nullopt;
	}

	// Written as a negation so that NaN is rejected too.
	if (!(*value >= min && *value <= max)) {
		error(node.source(), key, formatNumber(*value) + " is out of range: " +
					  formatNumber(min) + ".." + formatNumber(max));
		return std::nullopt;
	}
	return value;
}

bool TomlSection::number(std::string_view key, double &out, double min, double max)
{
	const toml::node *node = find(key);
	if (!node) {
		result_.absent.push_back(dotted(key));
		return true;
	}
	std::optional<double> value = numberValue(key, *node, min, max);
	if (value)
		out = *value;
	return value.has_value();
}

bool TomlSection::numbers(std::string_view key, std::vector<double> &out,
			  size_t minCount, size_t maxCount, double min, double max)
{
	const toml::node *node = find(key);
	if (!node) {
		result_.absent.push_back(dotted(key));
		return true;
	}
	const toml::array *array = node->as_array();
	if (!array)
		return wrongType(key, *node, "an array of numbers");
	if (array->size() < minCount || array->size() > maxCount) {
		std::string expected = minCount == maxCount
					       ? std::to_string(minCount)
					       : std::to_string(minCount) + ".." + std::to_string(maxCount);
		error(node->source(), key, "has " + std::to_string(array->size()) +
					   " numbers, expected " + expected);
		return false;
	}

	// Every bad element is reported, each at its own position.
	std::vector<double> values;
	for (size_t i = 0; i < array->size(); i++) {
		std::string name = std::string(key) + '[' + std::to_string(i) + ']';
		if (std::optional<double> value = numberValue(name, *array->get(i), min, max))
			values.push_back(*value);
	}
	if (values.size() != array->size())
		return false;
	out = std::move(values);
	return true;
}

bool TomlSection::string(std::string_view key, std::string &out)
{
	return string(key, out, StringCheck());
}

bool TomlSection::string(std::string_view key, std::string &out,
			 std::initializer_list<std::string_view> allowed)
{
	return string(key, out, std::span(allowed.begin(), allowed.size()));
}

bool TomlSection::string(std::string_view key, std::string &out,
			 std::span<const std::string_view> allowed)
{
	return string(key, out, [allowed](std::string_view value) {
		if (std::find(allowed.begin(), allowed.end(), value) != allowed.end())
			return std::string();
		std::string message = "is not one of";
		for (std::string_view a : allowed)
			message += ' ' + quote(a);
		return message;
	});
}

bool TomlSection::string(std::string_view key, std::string &out, const StringCheck &check)
{
	const toml::node *node = find(key);
	if (!node) {
		result_.absent.push_back(dotted(key));
		return true;
	}
	const auto *value = node->as_string();
	if (!value)
		return wrongType(key, *node, "a string");

	if (check) {
		std::string why = check(value->get());
		if (!why.empty()) {
			error(node->source(), key, quote(value->get()) + ' ' + why);
			return false;
		}
	}
	out = value->get();
	return true;
}

bool TomlSection::integerOrWord(std::string_view key, int &out, int min, int max, std::string_view word,
				bool &isWord)
{
	const toml::node *node = find(key);
	if (node && node->is_string()) {
		const std::string &s = node->as_string()->get();
		if (s != word) {
			error(node->source(), key, quote(s) + " is not allowed: expected an integer or " + quote(word));
			return false;
		}
		isWord = true;
		return true;
	}
	if (node && !node->is_integer())
		return wrongType(key, *node, "an integer or " + quote(word));
	bool ok = integer(key, out, min, max);
	if (ok && node)
		isWord = false;
	return ok;
}

bool TomlSection::colour(std::string_view key, uint32_t &out)
{
	const toml::node *node = find(key);
	if (!node) {
		result_.absent.push_back(dotted(key));
		return true;
	}
	if (const auto *value = node->as_integer()) {
		int64_t v = value->get();
		if (v < 0 || v > 0xffffff) {
			error(node->source(), key, std::to_string(v) +
						   " is not a colour: expected 0x000000..0xffffff");
			return false;
		}
		out = static_cast<uint32_t>(v);
		return true;
	}
	if (const auto *value = node->as_string()) {
		const std::string &s = value->get();
		if (s.size() != 7 || s[0] != '#' || !std::all_of(s.begin() + 1, s.end(), isHex)) {
			error(node->source(), key, quote(s) + " is not a colour: expected \"#rrggbb\"");
			return false;
		}
		out = static_cast<uint32_t>(std::stoul(s.substr(1), nullptr, 16));
		return true;
	}
	return wrongType(key, *node, "a colour (0xRRGGBB or \"#rrggbb\")");
}

bool TomlSection::table(std::string_view key, const TomlSchema &schema)
{
	// An absent section binds against an empty table, which leaves every
	// field at its default and lists each key as absent.
	static const toml::table empty;

	const toml::node *node = find(key);
	const toml::table *table = node ? node->as_table() : &empty;
	if (!table)
		return wrongType(key, *node, "a table ([" + dotted(key) + "])");

	size_t before = errorCount();
	TomlSection section(*table, dotted(key), file_, result_, omitted_);
	schema(section);
	section.reportUnknown();
	return errorCount() == before;
}

bool TomlSection::tables(std::string_view key,
			 const std::function<void(TomlSection &, size_t)> &schema)
{
	const toml::node *node = find(key);
	if (!node)
		return true;
	const toml::array *array = node->as_array();
	if (!array)
		return wrongType(key, *node, "an array of tables ([[" + dotted(key) + "]])");

	size_t before = errorCount();
	for (size_t i = 0; i < array->size(); i++) {
		const toml::node &element = *array->get(i);
		std::string name = std::string(key) + '[' + std::to_string(i) + ']';
		const toml::table *table = element.as_table();
		if (!table) {
			wrongType(name, element, "a table");
			continue;
		}
		TomlSection section(*table, dotted(name), file_, result_, omitted_);
		schema(section, i);
		section.reportUnknown();
	}
	return errorCount() == before;
}

void TomlSection::require(bool ok, std::string_view key, std::string_view message)
{
	if (ok)
		return;
	const toml::node *node = table_.get(key);
	error(node ? node->source() : table_.source(), key, std::string(message));
}

void TomlSection::reportUnknown()
{
	for (auto &&[key, node] : table_) {
		std::string_view name = key.str();
		if (std::find(known_.begin(), known_.end(), name) != known_.end())
			continue;

		bool isSection = node.is_table() || node.is_array_of_tables();
		std::string message = isSection ? "unknown section" : "unknown key";

		// Suggest the nearest known name, as long as it is a plausible typo.
		const std::string *best = nullptr;
		size_t bestDistance = 3;
		for (const std::string &candidate : known_) {
			size_t d = editDistance(name, candidate, bestDistance);
			if (d < bestDistance) {
				best = &candidate;
				bestDistance = d;
			}
		}
		if (best)
			message += " (did you mean " + quote(*best) + "?)";

		error(key.source(), name, message);
	}
}

} // namespace depthkey
