#include "swa/monitor/output_dir.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace swa::monitor {

void prepareOutputDir(const std::string& dir, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create " + what + " " + dir + ": " + ec.message());
  const fs::path probe = fs::path(dir) / ".swa_write_test";
  std::ofstream(probe) << "";
  const bool ok = fs::exists(probe, ec);
  fs::remove(probe, ec);
  if (!ok) throw std::runtime_error("cannot write into " + what + " " + dir);
}

}  // namespace swa::monitor
