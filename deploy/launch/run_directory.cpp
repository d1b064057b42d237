#include "run_directory.h"

#include <fstream>
#include <stdexcept>
#include <string>

namespace swa::launch {
namespace fs = std::filesystem;

namespace {

bool earlierRun(const fs::path& out) {
  std::error_code ec;
  if (fs::exists(out / kRunMarker, ec)) return true;
  return fs::is_directory(out / "logs", ec) &&
         (fs::exists(out / "scenario.yaml", ec) || fs::exists(out / "report.html", ec));
}

}  // namespace

void claimRunDirectory(const fs::path& out) {
  std::error_code ec;
  if (!fs::exists(out, ec)) return;
  if (!fs::is_directory(out, ec)) throw std::runtime_error("--out " + out.string() + " is a file, not a directory");
  if (fs::is_empty(out, ec)) return;
  if (!earlierRun(out)) {
    throw std::runtime_error("--out " + out.string() +
                             " is not empty and holds no earlier swa_launch run; give a new or empty directory "
                             "(a launch replaces only a directory it wrote)");
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(out, ec)) {
    fs::remove_all(entry.path(), ec);
    if (ec) throw std::runtime_error("cannot remove " + entry.path().string() + " of the earlier run: " + ec.message());
  }
}

void markRunDirectory(const fs::path& out) {
  std::ofstream marker(out / kRunMarker);
  marker << "A directory of swa_launch: the next swa_launch --out here replaces everything in it.\n";
  if (!marker) throw std::runtime_error("cannot write " + (out / kRunMarker).string());
}

}  // namespace swa::launch
