#include "swa/app/cli.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <CLI/CLI.hpp>

#include "help_format.h"
#include "swa/app/number.h"
#include "swa/params/text.h"

namespace swa::app {
namespace {

std::string withoutTrailingNewlines(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

std::string range(double min, double max) { return "[" + formatNumber(min) + ", " + formatNumber(max) + "]"; }

std::string oneOf(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    out += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  }
  return out;
}

}  // namespace

struct Cli::Impl {
  struct Entry {
    CLI::Option* option;
    Read read;  // empty for flags
    bool is_path;
  };

  CLI::App app;
  std::string usage;
  std::string details;
  std::string footer;
  std::vector<Entry> entries;  // declaration order
  std::vector<std::string> answers;
  std::vector<std::string> required;
  // Named last on the command line without the value they need (entries are all declared before parse()).
  std::vector<const Entry*> lacking;

  Impl(const std::string& program, const std::string& summary) : app(program + ": " + summary, program) {
    // Unknown arguments are collected, not thrown (every problem is reported at once), and -h/--help is an ordinary
    // flag, so that it wins over the problems instead of cutting the parse short.
    app.allow_extras();
    app.set_help_flag();
    entries.push_back({app.add_flag("-h,--help", "this text"), {}, false});
  }

  const Entry* find(const std::string& name) const {
    for (const Entry& e : entries) {
      if (e.option->check_name(name)) return &e;
    }
    return nullptr;
  }

  bool given(const std::string& name) const {
    const Entry* e = find(name);
    return e != nullptr && (e->option->count() > 0 || std::find(lacking.begin(), lacking.end(), e) != lacking.end());
  }

  CLI::Option* value(const std::string& name, const std::string& value_name, const std::string& meaning,
                     const std::string& default_text, Read read) {
    CLI::Option* o = app.add_option(name, CLI::callback_t{}, meaning);
    // Values stay text for `read`; TakeAll: every occurrence reaches it, and for a single value the last one wins.
    o->type_name(value_name)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    if (!default_text.empty()) o->default_str(default_text);
    entries.push_back({o, std::move(read), false});
    return o;
  }

  void flag(const std::string& name, bool& out, const std::string& meaning) {
    entries.push_back({app.add_flag(name, meaning), [&out](const std::string&, Problems&) { out = true; }, false});
  }

  // CLI11 reads "--opt=" as "--opt" and takes the next argument as its value; here it is an empty value, which the
  // option's own check then judges.
  std::vector<std::string> emptyValuesSpelledOut(const std::vector<std::string>& args) const {
    std::vector<std::string> out;
    for (const std::string& a : args) {
      const bool empty_value = a.size() > 3 && a.rfind("--", 0) == 0 && a.back() == '=';
      const Entry* e = empty_value ? find(a.substr(0, a.size() - 1)) : nullptr;
      if (e != nullptr && e->option->get_type_size() > 0) {
        out.push_back(a.substr(0, a.size() - 1));
        out.emplace_back();
      } else {
        out.push_back(a);
      }
    }
    return out;
  }

  // CLI11 stops with ArgumentMismatch when an option lacks its value. Every option takes the argument after it,
  // whatever it is, so only the last argument can lack one: it is reported, and the others are read again.
  Problems parseAll(std::vector<std::string> args) {
    Problems problems;
    lacking.clear();
    for (;;) {
      try {
        app.clear();
        app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 takes them from the back
        return problems;
      } catch (const CLI::ArgumentMismatch&) {
        if (args.empty() || find(args.back()) == nullptr) throw;
        problems.push_back(args.back() + " needs a value");
        lacking.push_back(find(args.back()));
        args.pop_back();
      }
    }
  }

  Problems missing() const {
    Problems problems;
    const bool answered =
        std::any_of(answers.begin(), answers.end(), [this](const std::string& n) { return given(n); });
    if (given("--help") || answered) return problems;
    for (const std::string& name : required) {
      if (given(name)) continue;
      const Entry* e = find(name);
      problems.push_back(name + (e->is_path ? " " + e->option->get_type_name() : "") + " is required");
    }
    return problems;
  }
};

Cli::Cli(const std::string& program, const std::string& summary) : impl_(std::make_unique<Impl>(program, summary)) {}
Cli::~Cli() = default;
Cli::Cli(Cli&&) noexcept = default;
Cli& Cli::operator=(Cli&&) noexcept = default;

void Cli::usage(const std::string& lines) { impl_->usage = withoutTrailingNewlines(lines); }
void Cli::details(const std::string& text) { impl_->details = withoutTrailingNewlines(text); }
void Cli::footer(const std::string& text) { impl_->footer = withoutTrailingNewlines(text); }

void Cli::flag(const std::string& name, bool& out, const std::string& meaning) { impl_->flag(name, out, meaning); }

void Cli::answer(const std::string& name, bool& out, const std::string& meaning) {
  impl_->flag(name, out, meaning);
  impl_->answers.push_back(name);
}

void Cli::text(const std::string& name, const std::string& value_name, std::string& out, const std::string& meaning,
               const std::string& needs) {
  impl_->value(name, value_name, meaning, out, [&out, name, needs](const std::string& v, Problems& p) {
    if (v.empty() && !needs.empty()) p.push_back(name + " needs " + needs);
    out = v;
  });
}

void Cli::path(const std::string& name, const std::string& value_name, std::string& out, const std::string& meaning) {
  text(name, value_name, out, meaning, "a file name");
  impl_->entries.back().is_path = true;
}

void Cli::real(const std::string& name, const std::string& value_name, double& out, double min, double max,
               const std::string& what, const std::string& meaning) {
  const std::string problem = "' is not " + what + " in " + range(min, max);
  impl_->value(name, value_name, meaning + "; in " + range(min, max), formatNumber(out),
               [&out, name, min, max, problem](const std::string& v, Problems& p) {
                 if (const auto x = parseReal(v, min, max)) {
                   out = *x;
                 } else {
                   p.push_back(name + " '" + v + problem);
                 }
               });
}

void Cli::integer(const std::string& name, const std::string& value_name, int& out, int min, int max,
                  const std::string& what, const std::string& meaning) {
  const std::string problem = "' is not " + what + " in " + range(min, max);
  impl_->value(name, value_name, meaning + "; in " + range(min, max), std::to_string(out),
               [&out, name, min, max, problem](const std::string& v, Problems& p) {
                 if (const auto n = parseInteger(v, min, max)) {
                   out = static_cast<int>(*n);
                 } else {
                   p.push_back(name + " '" + v + problem);
                 }
               });
}

void Cli::list(const std::string& name, const std::string& value_name, std::vector<std::string>& out,
               const std::string& meaning, bool several) {
  value(
      name, value_name, [&out](const std::string& v, Problems&) { out.push_back(v); }, meaning, several);
}

void Cli::value(const std::string& name, const std::string& value_name, Read read, const std::string& meaning,
                bool several) {
  CLI::Option* o = impl_->value(name, value_name, meaning, "", std::move(read));
  if (several) o->expected(1, CLI::detail::expected_max_vector_size)->allow_extra_args();
}

void Cli::choice(const std::string& name, const std::string& value_name, const std::vector<std::string>& names,
                 std::function<void(std::size_t)> take, const std::string& meaning) {
  const std::string problem = name + " must be " + oneOf(names) + ", got '";
  impl_->value(name, value_name, meaning + "; one of " + oneOf(names), "",
               [names, take = std::move(take), problem](const std::string& v, Problems& p) {
                 const auto it = std::find(names.begin(), names.end(), v);
                 if (it == names.end()) {
                   p.push_back(problem + v + "'");
                 } else {
                   take(static_cast<std::size_t>(it - names.begin()));
                 }
               });
}

void Cli::flagChoice(const std::string& name, const std::vector<std::string>& names,
                     std::function<void(std::size_t)> take, const std::string& meaning) {
  // CLI11's flag default "{value}": a bare flag reads as names[0], "--name=x" as x; any other value reaches the check.
  CLI::Option* o = impl_->app.add_flag(name + "{" + names.front() + "}");
  o->description(meaning + "; one of " + oneOf(names));
  o->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  std::string shown = "[=";
  for (std::size_t k = 0; k < names.size(); ++k) shown += (k ? "|" : "") + names[k];
  o->option_text(shown + "]");
  const std::string problem = name + " must be " + oneOf(names) + ", got '";
  impl_->entries.push_back({o,
                            [names, take = std::move(take), problem](const std::string& v, Problems& p) {
                              const auto it = std::find(names.begin(), names.end(), v);
                              if (it == names.end()) {
                                p.push_back(problem + v + "'");
                              } else {
                                take(static_cast<std::size_t>(it - names.begin()));
                              }
                            },
                            false});
}

void Cli::scenario(std::string& out, const std::string& meaning) { path("--scenario", "FILE", out, meaning); }

void Cli::overrides(std::vector<std::string>& out, const std::string& example) {
  list("--set", "key=value", out, example + "; repeatable, applied in order");
}

void Cli::domain(std::optional<std::string>& out, int max_domain, const std::string& note) {
  impl_->value("--domain", "D",
               "DDS domain 0.." + std::to_string(max_domain) + " (default: $SWA_DOMAIN, else 0)" +
                   (note.empty() ? "" : "; " + note),
               "", [&out](const std::string& v, Problems&) { out = v; });
}

void Cli::required(const std::string& name) {
  const Impl::Entry* e = impl_->find(name);
  if (e == nullptr) throw std::logic_error("Cli::required: no option " + name);
  e->option->default_str("");  // what the program holds before is no default: it must be given
  impl_->required.push_back(name);
}

Problems Cli::parse(const std::vector<std::string>& args) {
  const Problems lacking = impl_->parseAll(impl_->emptyValuesSpelledOut(args));
  Problems problems;
  for (const Impl::Entry& e : impl_->entries) {
    if (!e.read) continue;
    for (const std::string& v : e.option->results()) e.read(v, problems);
  }
  // An unknown option gets the nearest known one as a hint, and the word after it, which it would have taken as its
  // value, is reported with it rather than as a second unknown argument.
  std::vector<std::string> names{"--help"};
  for (const Impl::Entry& e : impl_->entries) {
    for (const std::string& n : e.option->get_lnames()) names.push_back("--" + n);
  }
  const std::vector<std::string> extras = impl_->app.remaining();
  for (std::size_t k = 0; k < extras.size(); ++k) {
    const std::string& arg = extras[k];
    if (arg.size() < 2 || arg[0] != '-') {
      problems.push_back("unknown argument '" + arg + "' (see --help)");
      continue;
    }
    std::string text = "unknown option '" + arg + "'";
    const std::size_t equals = arg.find('=');
    if (equals == std::string::npos && k + 1 < extras.size() && extras[k + 1].rfind('-', 0) != 0) {
      text += " (given '" + extras[++k] + "')";
    }
    const std::string hint = params::closestMatch(arg.substr(0, equals), names);
    if (!hint.empty()) text += ": did you mean " + hint + "?";
    problems.push_back(text + " (see --help)");
  }
  problems.insert(problems.end(), lacking.begin(), lacking.end());
  const Problems missing = impl_->missing();
  problems.insert(problems.end(), missing.begin(), missing.end());
  return problems;
}

bool Cli::given(const std::string& name) const { return impl_->given(name); }

void Cli::report(const Problems& problems) const {
  if (problems.empty() || given("--help")) return;
  std::ostringstream msg;
  for (std::size_t k = 0; k < problems.size(); ++k) msg << (k ? "\n" : "") << problems[k];
  throw std::invalid_argument(msg.str());
}

std::string Cli::help() const {
  CLI::App& app = impl_->app;
  // REQUIRED only in the text: as a CLI11 requirement it would stop parse() at the first missing option.
  for (const std::string& name : impl_->required) app.get_option(name)->required(true);
  app.formatter(std::make_shared<HelpFormat>(impl_->usage, impl_->details));
  app.footer(impl_->footer);
  std::string text = app.help();
  for (const std::string& name : impl_->required) app.get_option(name)->required(false);
  return text;
}

}  // namespace swa::app
