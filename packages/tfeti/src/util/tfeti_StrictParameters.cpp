#include "tfeti_StrictParameters.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_FileInputSource.hpp>
#include <Teuchos_StrUtils.hpp>
#include <Teuchos_XMLObject.hpp>

#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tfeti {
namespace strict {

namespace {

using Kind = NumberValidator::Kind;

// The shortest decimal text that reads back as v ("-0.1", not "-0.10000000000000001").
std::string number(double v) {
  std::string text;
  for (int digits = 6; digits <= 17; ++digits) {
    std::ostringstream s;
    s.precision(digits);
    s << v;
    text = s.str();
    if (std::strtod(text.c_str(), nullptr) == v) break;
  }
  return text;
}

std::string listed(const std::vector<double>& values) {
  std::string text = "{";
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + number(values[i]);
  return text + "}";
}

bool isArray(Kind k) {
  return k == Kind::DoubleArray || k == Kind::IntArray;
}
bool isInt(Kind k) {
  return k == Kind::Int || k == Kind::IntArray;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

// The values of an entry of kind k as doubles; false when its type is not k's.
bool valuesOf(const Teuchos::ParameterEntry& e, Kind k, std::vector<double>& out) {
  const auto& any = e.getAny(false);
  switch (k) {
    case Kind::Double:
      if (any.type() != typeid(double)) return false;
      out = {Teuchos::any_cast<double>(any)};
      return true;
    case Kind::Int:
      if (any.type() != typeid(int)) return false;
      out = {static_cast<double>(Teuchos::any_cast<int>(any))};
      return true;
    case Kind::DoubleArray:
      if (any.type() != typeid(Teuchos::Array<double>)) return false;
      for (double v : Teuchos::any_cast<Teuchos::Array<double>>(any)) out.push_back(v);
      return true;
    case Kind::IntArray:
      if (any.type() != typeid(Teuchos::Array<int>)) return false;
      for (int v : Teuchos::any_cast<Teuchos::Array<int>>(any)) out.push_back(v);
      return true;
  }
  return false;
}

const char* typeName(Kind k) {
  switch (k) {
    case Kind::Double:
      return "double";
    case Kind::Int:
      return "int";
    case Kind::DoubleArray:
      return "Array(double)";
    case Kind::IntArray:
      return "Array(int)";
  }
  return "";
}

// Parses `text` as one number of the XML type `type` (int, double, ...): the whole text must
// be the number. Returns an empty string or what is wrong.
std::string parseNumber(const std::string& raw, bool integer, bool nonFiniteAllowed) {
  const std::string text = trim(raw);
  if (text.empty()) return "an empty value";
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  if (integer) {
    const long v = std::strtol(begin, &end, 10);
    if (end != begin + text.size()) return "not an integer";
    if (errno == ERANGE || v < INT_MIN || v > INT_MAX) return "an integer out of range";
    return "";
  }
  const double v = std::strtod(begin, &end);
  if (end != begin + text.size()) return "not a number";
  if (!nonFiniteAllowed && !std::isfinite(v))
    return std::isnan(v) ? "not a finite number" : "not a finite number (overflow)";
  return "";
}

const Teuchos::ParameterList* subOf(const Teuchos::ParameterList* valid, const std::string& name) {
  if (valid == nullptr || !valid->isSublist(name)) return nullptr;
  return &valid->sublist(name);
}

bool nonFiniteAllowedFor(const Teuchos::ParameterList* valid, const std::string& name) {
  if (valid == nullptr || !valid->isParameter(name) || valid->isSublist(name)) return false;
  const auto v =
      Teuchos::rcp_dynamic_cast<const NumberValidator>(valid->getEntryPtr(name)->validator());
  return !v.is_null() && v->nonFiniteAllowed();
}

void checkParameterNode(const std::string& file, const Teuchos::XMLObject& node,
                        const std::string& path, const Teuchos::ParameterList* valid) {
  if (!node.hasAttribute("name") || !node.hasAttribute("type") || !node.hasAttribute("value"))
    return;  // Teuchos reports malformed entries itself
  const std::string name = node.getAttribute("name"), type = node.getAttribute("type");
  const std::string& value = node.getAttribute("value");
  const std::string where0 = file + ": " + (path.empty() ? "" : path + "/") + name + ": ";
  if (type == "bool") {  // Teuchos's own message names neither the parameter nor the file
    std::string upper;
    for (char c : trim(value)) upper += static_cast<char>(std::toupper(c));
    if (upper != "TRUE" && upper != "FALSE" && upper != "YES" && upper != "NO" && upper != "1" &&
        upper != "0")
      throw std::invalid_argument(where0 + "\"" + value +
                                  "\" is not a bool; expected true or false");
    return;
  }
  const bool array = type.rfind("Array(", 0) == 0;
  const std::string scalar = array ? type.substr(6, type.size() - 7) : type;
  const bool integer = scalar == "int" || scalar == "short" || scalar == "long long";
  const std::string braces = trim(value);
  if (array && (braces.size() < 2 || braces.front() != '{' || braces.back() != '}'))
    throw std::invalid_argument(where0 + "\"" + value +
                                "\" is not an array; expected {item, ...} (type " + type + ")");
  if (!integer && scalar != "double" && scalar != "float") return;
  const bool nonFinite = nonFiniteAllowedFor(valid, name);
  const std::string where = file + ": " + (path.empty() ? "" : path + "/") + name + ": ";
  const std::string expected = std::string(integer     ? "an integer"
                                           : nonFinite ? "a number"
                                                       : "a finite number");
  if (!array) {
    const std::string why = parseNumber(value, integer, nonFinite);
    if (!why.empty())
      throw std::invalid_argument(where + "\"" + value + "\" is " + why + "; expected " + expected +
                                  " (type " + type + ")");
    return;
  }
  const std::string text = trim(value);
  if (text.size() < 2 || text.front() != '{' || text.back() != '}')
    throw std::invalid_argument(where + "\"" + value + "\" is not an array; expected {" + expected +
                                ", ...} (type " + type + ")");
  const std::string inner = trim(text.substr(1, text.size() - 2));
  if (inner.empty()) return;
  std::istringstream items(inner);
  std::string item;
  int index = 0;
  while (std::getline(items, item, ',')) {
    const std::string why = parseNumber(item, integer, nonFinite);
    if (!why.empty())
      throw std::invalid_argument(where + "item " + std::to_string(index) + " \"" + trim(item) +
                                  "\" of \"" + value + "\" is " + why + "; expected " + expected +
                                  " per item, items separated by commas (type " + type + ")");
    ++index;
  }
  if (inner.back() == ',')
    throw std::invalid_argument(where + "\"" + value + "\" ends with a comma; expected {" +
                                expected + ", ...} (type " + type + ")");
}

void checkListNode(const std::string& file, const Teuchos::XMLObject& list, const std::string& path,
                   const Teuchos::ParameterList* valid) {
  for (int i = 0; i < list.numChildren(); ++i) {
    const auto& child = list.getChild(i);
    if (child.getTag() == "Parameter") {
      checkParameterNode(file, child, path, valid);
    } else if (child.getTag() == "ParameterList" && child.hasAttribute("name")) {
      const std::string name = child.getAttribute("name");
      checkListNode(file, child, path.empty() ? name : path + "/" + name, subOf(valid, name));
    }
  }
}

}  // namespace

NumberValidator& NumberValidator::lengthBetween(int lo, int hi) {
  minLength_ = lo, maxLength_ = hi;
  return *this;
}

std::string NumberValidator::describe() const {
  std::ostringstream s;
  const bool integer = isInt(kind_);
  if (isArray(kind_)) {
    s << "array of ";
    if (minLength_ == maxLength_)
      s << minLength_ << " ";
    else if (maxLength_ == std::numeric_limits<int>::max() && minLength_ > 0)
      s << minLength_ << " or more ";
    else if (maxLength_ != std::numeric_limits<int>::max())
      s << minLength_ << " to " << maxLength_ << " ";
    s << (integer ? "ints" : "doubles") << ", each ";
  } else {
    s << (integer ? "int" : "double") << " ";
  }
  const bool hasLo = std::isfinite(lo_), hasHi = std::isfinite(hi_);
  if (hasLo && hasHi)
    s << "in " << (loOpen_ ? "(" : "[") << number(lo_) << ", " << number(hi_)
      << (hiOpen_ ? ")" : "]");
  else if (hasLo)
    s << (loOpen_ ? "> " : ">= ") << number(lo_);
  else if (hasHi)
    s << (hiOpen_ ? "< " : "<= ") << number(hi_);
  else
    s << "any value";
  if (!integer) s << (nonFinite_ ? ", nan and inf allowed" : ", finite");
  return s.str();
}

std::string NumberValidator::checkValue(double v) const {
  if (!std::isfinite(v)) return nonFinite_ ? "" : "not finite";
  if (v < lo_ || (loOpen_ && v == lo_) || v > hi_ || (hiOpen_ && v == hi_)) return "out of range";
  return "";
}

void NumberValidator::printDoc(const std::string& docString, std::ostream& out) const {
  Teuchos::StrUtils::printLines(out, "# ", docString);
  out << "#   (" << describe() << ")\n";
}

void NumberValidator::validate(const Teuchos::ParameterEntry& entry, const std::string& paramName,
                               const std::string& sublistName) const {
  const std::string where = parameterPath(sublistName, paramName);
  std::vector<double> values;
  if (!valuesOf(entry, kind_, values))
    throw std::invalid_argument(where + ": has type " + entry.getAny(false).typeName() +
                                "; expected " + typeName(kind_) + " (" + describe() + ")");
  const int n = static_cast<int>(values.size());
  if (isArray(kind_) && (n < minLength_ || n > maxLength_))
    throw std::invalid_argument(where + ": " + listed(values) + " has " + std::to_string(n) +
                                " items; expected an " + describe());
  for (int i = 0; i < n; ++i) {
    const std::string why = checkValue(values[i]);
    if (why.empty()) continue;
    const std::string item = isArray(kind_) ? " item " + std::to_string(i) : std::string();
    throw std::invalid_argument(where + ":" + item + " " + number(values[i]) + " is " + why +
                                "; expected " + describe());
  }
}

Validator finite() {
  return Teuchos::rcp(new NumberValidator(Kind::Double));
}
Validator positive() {
  auto v = finite();
  v->greaterThan(0.0);
  return v;
}
Validator nonNegative() {
  auto v = finite();
  v->atLeast(0.0);
  return v;
}
Validator between(double lo, double hi, bool loOpen, bool hiOpen) {
  auto v = finite();
  if (loOpen)
    v->greaterThan(lo);
  else
    v->atLeast(lo);
  if (hiOpen)
    v->lessThan(hi);
  else
    v->atMost(hi);
  return v;
}
Validator count(int min) {
  auto v = Teuchos::rcp(new NumberValidator(Kind::Int));
  v->atLeast(min);
  return v;
}
Validator intBetween(int lo, int hi) {
  auto v = count(lo);
  v->atMost(hi);
  return v;
}
Teuchos::RCP<Teuchos::StringToIntegralParameterEntryValidator<int>> choice(
    const std::vector<std::string>& names) {
  return Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<int>(
      Teuchos::Array<std::string>(names.begin(), names.end()), names.front()));
}
Validator doubles(int length) {
  auto v = Teuchos::rcp(new NumberValidator(Kind::DoubleArray));
  if (length > 0) v->length(length);
  return v;
}
Validator positiveInts(int length) {
  auto v = Teuchos::rcp(new NumberValidator(Kind::IntArray));
  v->atLeast(1);
  if (length > 0) v->length(length);
  return v;
}

std::string parameterPath(const std::string& sublistName, const std::string& paramName) {
  const auto arrow = sublistName.find("->");
  if (arrow == std::string::npos) return paramName;
  std::string path = sublistName.substr(arrow + 2);
  for (std::size_t p; (p = path.find("->")) != std::string::npos;) path.replace(p, 2, "/");
  return path + "/" + paramName;
}

void requireNumbers(Teuchos::ParameterList& valid) {
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& name = valid.name(it);
    if (valid.isSublist(name)) {
      requireNumbers(valid.sublist(name));
      continue;
    }
    auto* entry = valid.getEntryPtr(name);
    if (!entry->validator().is_null()) continue;
    const auto& type = entry->getAny(false).type();
    Kind kind;
    if (type == typeid(double))
      kind = Kind::Double;
    else if (type == typeid(int))
      kind = Kind::Int;
    else if (type == typeid(Teuchos::Array<double>))
      kind = Kind::DoubleArray;
    else if (type == typeid(Teuchos::Array<int>))
      kind = Kind::IntArray;
    else
      continue;
    entry->setValidator(Teuchos::rcp(new NumberValidator(kind)));
  }
}

void checkXmlNumbers(const std::string& file, const Teuchos::ParameterList& valid) {
  Teuchos::XMLObject root;
  try {
    root = Teuchos::FileInputSource(file).getObject();
  } catch (const std::exception& e) {
    throw std::invalid_argument(file + ": not a valid XML file: " + e.what());
  }
  if (root.getTag() != "ParameterList")
    throw std::invalid_argument(file + ": the root element is <" + root.getTag() +
                                ">; expected <ParameterList>");
  checkListNode(file, root, "", &valid);
}

}  // namespace strict
}  // namespace tfeti
