// A small declarative binder from a TOML document to plain structs.
//
// A schema is a function that, section by section, binds each key to a field
// with its type and allowed values, one call per key:
//
//	root.table("segmentation", [&](TomlSection &sec) {
//		sec.integer("near_mm", s.nearMm, 300, 7500);
//	});
//
// The binder never throws and never stops at the first problem: every
// wrong type, out-of-range or not-allowed value becomes a ConfigError with the
// file, line, column and dotted key, and a field keeps its default unless its
// value was valid. Once a section's schema has run, every key in it that no
// call asked for is reported as unknown, so a typo can never fall back to a
// default silently.
#pragma once

#include <concepts>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "config/config_error.hpp"

namespace depthkey {

class TomlSection;

using TomlSchema = std::function<void(TomlSection &root)>;

// Returns "" when a string is acceptable, else why not ("must start with '/'").
using StringCheck = std::function<std::string(std::string_view value)>;

struct TomlBindResult {
	// In file order, at most kMaxReportedErrors of them plus a closing
	// "and N more errors" entry (config_error.hpp).
	std::vector<ConfigError> errors;
	std::vector<std::string> absent;        // dotted keys bound but not in the file (defaults apply)
};

// Parses text (a syntax error is reported with its position, and nothing is
// bound) then runs schema on the root table.
TomlBindResult bindToml(std::string_view text, const std::string &file,
			const TomlSchema &schema);

class TomlSection
{
public:
	// Each binder returns false when the key is present but its value is
	// rejected, true when it was absent (field untouched) or stored.
	bool boolean(std::string_view key, bool &out);

	// Any integer field type; limits are clamped to what TOML can hold (int64).
	template<std::integral T>
		requires(!std::same_as<T, bool>)
	bool integer(std::string_view key, T &out,
		     std::type_identity_t<T> min, std::type_identity_t<T> max);

	// A float; an integer is accepted too ("opacity = 1").
	bool number(std::string_view key, double &out, double min, double max);
	// An array of numbers, each in [min, max] (so NaN and infinities are
	// refused), with minCount..maxCount elements. out is replaced only when
	// every element is valid.
	bool numbers(std::string_view key, std::vector<double> &out,
		     size_t minCount, size_t maxCount, double min, double max);

	bool string(std::string_view key, std::string &out);
	// An enumeration: the value must be one of allowed.
	bool string(std::string_view key, std::string &out,
		    std::span<const std::string_view> allowed);
	bool string(std::string_view key, std::string &out,
		    std::initializer_list<std::string_view> allowed);
	bool string(std::string_view key, std::string &out, const StringCheck &check);

	// An integer in [min, max], or the string `word` (isWord is set then):
	// a setting with an automatic choice, e.g. offset_ms = "auto".
	bool integerOrWord(std::string_view key, int &out, int min, int max, std::string_view word, bool &isWord);

	// 0xRRGGBB as an integer, or "#rrggbb" as a string.
	bool colour(std::string_view key, uint32_t &out);

	// A sub-table ([this.key]). schema runs even when the table is absent, so
	// that its keys are listed as absent; its unknown keys are reported after.
	bool table(std::string_view key, const TomlSchema &schema);
	// An array of tables ([[this.key]]): schema runs once per element, whose
	// keys are reported as "this.key[index].name".
	bool tables(std::string_view key,
		    const std::function<void(TomlSection &element, size_t index)> &schema);

	// A rule across fields. When !ok, reports message against key: at its
	// value when the file has it, else at this section's header.
	void require(bool ok, std::string_view key, std::string_view message);

	bool has(std::string_view key) const { return table_.contains(key); }
	const std::string &path() const { return path_; }

private:
	friend TomlBindResult bindToml(std::string_view, const std::string &,
				       const TomlSchema &);

	TomlSection(const toml::table &table, std::string path,
		    const std::string &file, TomlBindResult &result, size_t &omitted)
		: table_(table), path_(std::move(path)), file_(file), result_(result),
		  omitted_(omitted)
	{
	}

	const toml::node *find(std::string_view key);
	bool integerValue(std::string_view key, int64_t min, int64_t max,
			  std::optional<int64_t> &value);
	std::optional<double> numberValue(std::string_view key, const toml::node &node,
					  double min, double max);
	bool wrongType(std::string_view key, const toml::node &node,
		       std::string_view expected);
	void error(const toml::source_region &where, std::string_view key,
		   std::string message);
	std::string dotted(std::string_view key) const;
	void reportUnknown();
	size_t errorCount() const { return result_.errors.size() + omitted_; }

	const toml::table &table_;
	std::string path_;
	const std::string &file_;
	TomlBindResult &result_;
	size_t &omitted_;       // errors dropped while binding (bounded memory)
	std::vector<std::string> known_;
};

template<std::integral T>
	requires(!std::same_as<T, bool>)
bool TomlSection::integer(std::string_view key, T &out,
			  std::type_identity_t<T> min, std::type_identity_t<T> max)
{
	constexpr int64_t kLowest = std::numeric_limits<int64_t>::min();
	constexpr int64_t kHighest = std::numeric_limits<int64_t>::max();
	int64_t lo = std::cmp_less(min, kLowest) ? kLowest : static_cast<int64_t>(min);
	int64_t hi = std::cmp_greater(max, kHighest) ? kHighest : static_cast<int64_t>(max);

	std::optional<int64_t> value;
	bool ok = integerValue(key, lo, hi, value);
	if (value)
		out = static_cast<T>(*value);
	return ok;
}

} // namespace depthkey
