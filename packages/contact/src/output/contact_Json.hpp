#pragma once
// A small JSON document builder for summary.json: objects keep insertion order so the file
// reads in the order the run produced it. Numbers read back as the same double (the fewest
// digits from 15 that do); non-finite numbers are written as null (JSON has no NaN), so a
// failed run still produces a parsable file.
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace contact {

class Json {
 public:
  enum class Kind { Null, Bool, Number, Integer, String, Array, Object };

  Json() = default;
  Json(bool b) : kind_(Kind::Bool), bool_(b) {}
  Json(double d) : kind_(Kind::Number), number_(d) {}
  Json(int i) : kind_(Kind::Integer), integer_(i) {}
  Json(long i) : kind_(Kind::Integer), integer_(i) {}
  Json(long long i) : kind_(Kind::Integer), integer_(i) {}
  Json(unsigned long i) : kind_(Kind::Integer), integer_(static_cast<long long>(i)) {}
  Json(unsigned long long i) : kind_(Kind::Integer), integer_(static_cast<long long>(i)) {}
  Json(const char* s) : kind_(Kind::String), string_(s) {}
  Json(std::string s) : kind_(Kind::String), string_(std::move(s)) {}

  static Json object() {
    Json j;
    j.kind_ = Kind::Object;
    return j;
  }
  static Json array() {
    Json j;
    j.kind_ = Kind::Array;
    return j;
  }

  // Object member (created on first use, insertion order kept).
  Json& operator[](const std::string& key);
  // Array append.
  void push(Json value);

  std::string dump(int indent = 2) const;

 private:
  void write(std::string& out, int indent, int depth) const;
  Kind kind_ = Kind::Null;
  bool bool_ = false;
  double number_ = 0.0;
  long long integer_ = 0;
  std::string string_;
  std::vector<Json> items_;
  std::vector<std::string> keys_;
};

}  // namespace contact
