#pragma once
// Nodes with as much memory as a test wants: tfeti_NodeMemory.hpp reads the meminfo file that
// TFETI_MEMINFO names instead of /proc/meminfo.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace tfeti_test {

// A meminfo file of this process with the given lines, removed again at the end.
class MeminfoFile {
 public:
  explicit MeminfoFile(const std::string& text)
      : path_(
            (std::filesystem::temp_directory_path() / ("tfeti_meminfo_" + std::to_string(getpid())))
                .string()) {
    std::ofstream(path_) << text;
  }
  ~MeminfoFile() { std::remove(path_.c_str()); }
  MeminfoFile(const MeminfoFile&) = delete;
  MeminfoFile& operator=(const MeminfoFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// TFETI_MEMINFO names a meminfo file with the given MemAvailable while this lives.
class FakeNodeMemory {
 public:
  explicit FakeNodeMemory(long long availableKib)
      : file_("MemTotal:       24000000 kB\nMemAvailable:   " + std::to_string(availableKib) +
              " kB\n") {
    setenv("TFETI_MEMINFO", file_.path().c_str(), 1);
  }
  ~FakeNodeMemory() { unsetenv("TFETI_MEMINFO"); }
  FakeNodeMemory(const FakeNodeMemory&) = delete;
  FakeNodeMemory& operator=(const FakeNodeMemory&) = delete;

 private:
  MeminfoFile file_;
};

// The whole KiB at or above the given bytes: a node that has just that.
inline long long kibAtLeast(double bytes) {
  return static_cast<long long>((bytes + 1023.0) / 1024.0);
}

}  // namespace tfeti_test
