#include "json_reader.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <tuple>

#include "erkn/error.hpp"

namespace erkn::detail {
namespace {

class Parser {
 public:
  Parser(const std::string& text, const std::string& source) : s_(text), source_(source) {}

  JsonValue document() {
    JsonValue v = value();
    skip();
    if (i_ != s_.size()) fail("text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    const auto line = 1 + std::count(s_.begin(), s_.begin() + long(std::min(i_, s_.size())), '\n');
    throw Error(source_ + ":" + std::to_string(line) + ": malformed JSON: " + what);
  }
  void skip() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool take(char ch) {
    skip();
    if (i_ < s_.size() && s_[i_] == ch) return ++i_, true;
    return false;
  }
  void expect(char ch) {
    if (!take(ch)) fail(std::string("expected '") + ch + "'");
  }

  JsonValue value() {
    skip();
    if (i_ >= s_.size()) fail("unexpected end");
    const char ch = s_[i_];
    if (ch == '{') return object();
    if (ch == '[') return array();
    if (ch == '"') return JsonValue{JsonValue::Type::string, false, string(), {}, {}};
    for (const auto& [word, type, b] : {std::tuple{"true", JsonValue::Type::boolean, true},
                                        std::tuple{"false", JsonValue::Type::boolean, false},
                                        std::tuple{"null", JsonValue::Type::null, false}})
      if (s_.compare(i_, std::char_traits<char>::length(word), word) == 0) {
        i_ += std::char_traits<char>::length(word);
        return JsonValue{type, b, {}, {}, {}};
      }
    return number();
  }

  JsonValue number() {
    const size_t start = i_;
    while (i_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[i_])) ||
                              std::string_view("+-.eE").find(s_[i_]) != std::string_view::npos))
      ++i_;
    if (i_ == start) fail(std::string("unexpected '") + s_[i_] + "'");
    return JsonValue{JsonValue::Type::number, false, s_.substr(start, i_ - start), {}, {}};
  }

  std::string string() {
    expect('"');
    std::string out;
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\' && ++i_ < s_.size()) {
        const char e = s_[i_];
        out += e == 'n' ? '\n' : e == 't' ? '\t' : e;  // \" \\ \/ and the two used here
      } else {
        out += s_[i_];
      }
      ++i_;
    }
    if (i_ >= s_.size()) fail("unterminated string");
    ++i_;
    return out;
  }

  JsonValue array() {
    expect('[');
    JsonValue v{JsonValue::Type::array, false, {}, {}, {}};
    if (take(']')) return v;
    do v.items.push_back(value());
    while (take(','));
    expect(']');
    return v;
  }

  JsonValue object() {
    expect('{');
    JsonValue v{JsonValue::Type::object, false, {}, {}, {}};
    if (take('}')) return v;
    do {
      skip();
      std::string key = string();
      expect(':');
      if (!v.members.emplace(key, value()).second) fail("duplicate key '" + key + "'");
    } while (take(','));
    expect('}');
    return v;
  }

  const std::string& s_;
  const std::string& source_;
  size_t i_ = 0;
};

}  // namespace

const JsonValue& JsonValue::at(const std::string& key, const std::string& where) const {
  auto it = members.find(key);
  if (type != Type::object || it == members.end()) throw Error(where + ": no '" + key + "'");
  return it->second;
}

JsonValue parse_json(const std::string& text, const std::string& source) {
  return Parser(text, source).document();
}

}  // namespace erkn::detail
