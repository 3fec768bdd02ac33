#include "contact_Json.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace contact {

Json& Json::operator[](const std::string& key) {
  if (kind_ == Kind::Null) kind_ = Kind::Object;
  if (kind_ != Kind::Object) throw std::logic_error("json: member access on a non-object");
  for (std::size_t i = 0; i < keys_.size(); ++i)
    if (keys_[i] == key) return items_[i];
  keys_.push_back(key);
  items_.emplace_back();
  return items_.back();
}

void Json::push(Json value) {
  if (kind_ == Kind::Null) kind_ = Kind::Array;
  if (kind_ != Kind::Array) throw std::logic_error("json: push on a non-array");
  items_.push_back(std::move(value));
}

namespace {
void writeString(std::string& out, const std::string& s) {
  out += '"';
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}
}  // namespace

void Json::write(std::string& out, int indent, int depth) const {
  const std::string pad(static_cast<std::size_t>(indent) * (depth + 1), ' ');
  const std::string padEnd(static_cast<std::size_t>(indent) * depth, ' ');
  const char* nl = indent > 0 ? "\n" : "";
  switch (kind_) {
    case Kind::Null:
      out += "null";
      break;
    case Kind::Bool:
      out += bool_ ? "true" : "false";
      break;
    case Kind::Integer:
      out += std::to_string(integer_);
      break;
    case Kind::Number: {
      if (!std::isfinite(number_)) {
        out += "null";
        break;
      }
      // The fewest digits (from 15) that read back as the same double: 0.3 stays 0.3, and a
      // computed figure keeps every digit a comparison between runs (1e-10 and below) needs.
      char buf[32];
      for (int digits = 15; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, number_);
        if (std::strtod(buf, nullptr) == number_) break;
      }
      out += buf;
      break;
    }
    case Kind::String:
      writeString(out, string_);
      break;
    case Kind::Array:
    case Kind::Object: {
      const bool obj = kind_ == Kind::Object;
      out += obj ? '{' : '[';
      if (items_.empty()) {
        out += obj ? '}' : ']';
        break;
      }
      out += nl;
      for (std::size_t i = 0; i < items_.size(); ++i) {
        out += pad;
        if (obj) {
          writeString(out, keys_[i]);
          out += indent > 0 ? ": " : ":";
        }
        items_[i].write(out, indent, depth + 1);
        if (i + 1 < items_.size()) out += ',';
        out += nl;
      }
      out += padEnd;
      out += obj ? '}' : ']';
      break;
    }
  }
}

std::string Json::dump(int indent) const {
  std::string out;
  write(out, indent, 0);
  out += '\n';
  return out;
}

}  // namespace contact
