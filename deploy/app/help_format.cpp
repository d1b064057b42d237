#include "help_format.h"

#include <sstream>
#include <utility>
#include <vector>

namespace swa::app {
namespace {

// The help texts were written for terminals of about this width.
constexpr std::size_t kLineWidth = 116;
constexpr std::size_t kColumn = 30;  // CLI11's default: where the meanings start

// The words of one line; a range such as "[0.001, 3600]" stays one word.
std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  std::string word;
  while (in >> word) {
    const bool inside_range = !out.empty() && out.back().find('[') != std::string::npos &&
                              out.back().find(']', out.back().rfind('[')) == std::string::npos;
    if (inside_range) {
      out.back() += ' ' + word;
    } else {
      out.push_back(word);
    }
  }
  return out;
}

// Greedy word wrap, keeping the text's own line breaks (CLI11 indents every line after a '\n').
std::string wrap(const std::string& text, std::size_t width) {
  std::string out;
  std::istringstream lines(text);
  std::string line;
  for (bool first = true; std::getline(lines, line); first = false) {
    if (!first) out += '\n';
    std::size_t used = 0;
    for (const std::string& word : words(line)) {
      if (used > 0 && used + 1 + word.size() > width) {
        out += '\n';
        used = 0;
      } else if (used > 0) {
        out += ' ';
        ++used;
      }
      out += word;
      used += word.size();
    }
  }
  return out;
}

// A flag with a default value ("--record{all}", Cli::flagChoice) and the text of its values.
bool isFlagChoice(const CLI::Option* option) {
  return option->get_name(false, true).find('{') != std::string::npos && !option->get_option_text().empty();
}

}  // namespace

HelpFormat::HelpFormat(std::string usage, std::string details) : usage_(std::move(usage)), details_(std::move(details)) {
  column_width(kColumn);
}

std::string HelpFormat::make_usage(const CLI::App* /*app*/, std::string /*name*/) const {
  return "\nUsage: " + usage_ + "\n" + (details_.empty() ? "" : "\n" + details_ + "\n");
}

std::string HelpFormat::make_option_desc(const CLI::Option* option) const {
  return wrap(option->get_description(), kLineWidth - kColumn);
}

std::string HelpFormat::make_option_name(const CLI::Option* option, bool positional) const {
  if (!positional && isFlagChoice(option)) return option->get_name() + option->get_option_text();
  return CLI::Formatter::make_option_name(option, positional);
}

std::string HelpFormat::make_option_opts(const CLI::Option* option) const {
  return isFlagChoice(option) ? std::string() : CLI::Formatter::make_option_opts(option);
}

}  // namespace swa::app
