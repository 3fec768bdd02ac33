#pragma once
// The checks' command-line options, "--name=value": a value that is not wholly an integer, or
// is below its least, is an error naming the option (std::stoi alone would take "8x" as 8 and
// say only "stoi" for "x").
#include <stdexcept>
#include <string>

namespace gpucheck {

// True (and out set) where arg is "--name=<integer>"; false where arg is another option.
inline bool intOption(const std::string& arg, const char* name, int least, int& out) {
  const std::string prefix = std::string(name) + "=";
  if (arg.rfind(prefix, 0) != 0) return false;
  const std::string v = arg.substr(prefix.size());
  std::size_t used = 0;
  int x = 0;
  try {
    x = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v.size())
    throw std::invalid_argument(std::string(name) + " = \"" + v + "\" is not an integer");
  if (x < least)
    throw std::invalid_argument(std::string(name) + " = " + v + " is below " +
                                std::to_string(least));
  out = x;
  return true;
}

}  // namespace gpucheck
