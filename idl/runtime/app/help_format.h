#pragma once
// How every SWA program's --help looks: the summary, the program's own usage lines instead of CLI11's one-line
// usage, CLI11's options (one column, "=default", REQUIRED), then the details and the exit status; everything
// wrapped to 80 columns.

#include <string>

#include <CLI/CLI.hpp>

namespace swa::app {

class HelpFormat : public CLI::Formatter {
 public:
  HelpFormat(std::string usage, std::string details);

  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override;
  std::string make_description(const CLI::App* app) const override;
  std::string make_usage(const CLI::App* app, std::string name) const override;
  std::string make_option_desc(const CLI::Option* option) const override;
  // A flag that may carry a value (Cli::flagChoice) shows as "--record[=all|monitor]", not CLI11's
  // "--record{all} [=all|monitor]": its value is attached, never a separate argument.
  std::string make_option_name(const CLI::Option* option, bool positional) const override;
  std::string make_option_opts(const CLI::Option* option) const override;

 private:
  std::string usage_;
  std::string details_;
};

}  // namespace swa::app
