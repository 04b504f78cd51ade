// A small JSON reader for method files (Method::load): objects, arrays, strings, numbers, true,
// false, null. Numbers keep their text, so a coefficient can be read both as a double and in
// long double for validation.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace erkn::detail {

struct JsonValue {
  enum class Type { null, boolean, number, string, array, object };
  Type type = Type::null;
  bool boolean = false;
  std::string text;  ///< a string's contents, or a number as written
  std::vector<JsonValue> items;
  std::map<std::string, JsonValue> members;

  /// The member `key` of an object; throws erkn::Error naming `where` and the key if absent.
  const JsonValue& at(const std::string& key, const std::string& where) const;
  bool has(const std::string& key) const { return members.count(key) != 0; }
};

/// Parses `text`; throws erkn::Error naming `source` and the line of the first malformed token.
JsonValue parse_json(const std::string& text, const std::string& source);

}  // namespace erkn::detail
