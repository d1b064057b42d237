#include "swa/app/run_directory.h"

#include <fstream>
#include <stdexcept>

namespace swa::app {
namespace fs = std::filesystem;

namespace {
constexpr const char* kMarkerHeader =
    "# What an SWA run wrote here; the next run with --out here removes these entries (and nothing else).";
}  // namespace

void claimRunDirectory(const fs::path& out) {
  std::error_code ec;
  if (!fs::exists(out, ec)) return;
  if (!fs::is_directory(out, ec)) throw std::runtime_error("--out " + out.string() + " is a file, not a directory");
  std::ifstream marker(out / kRunMarker);
  if (!marker) return;
  std::string name;
  while (std::getline(marker, name)) {
    // Only plain names of entries directly in `out`: a marker edited to name a path elsewhere removes nothing.
    if (name.empty() || name[0] == '#' || name == "." || name == ".." || name.find('/') != std::string::npos) continue;
    fs::remove_all(out / name, ec);
    if (ec) throw std::runtime_error("cannot remove " + (out / name).string() + " of the earlier run: " + ec.message());
  }
  marker.close();
  fs::remove(out / kRunMarker, ec);
}

std::set<std::string> entriesOf(const fs::path& out) {
  std::set<std::string> names;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(out, ec)) names.insert(e.path().filename().string());
  return names;
}

void markRunDirectory(const fs::path& out, const std::set<std::string>& before) {
  std::ofstream marker(out / kRunMarker);
  marker << kMarkerHeader << "\n";
  for (const std::string& name : entriesOf(out)) {
    if (before.count(name) == 0 && name != kRunMarker) marker << name << "\n";
  }
  if (!marker) throw std::runtime_error("cannot write " + (out / kRunMarker).string());
}

}  // namespace swa::app
