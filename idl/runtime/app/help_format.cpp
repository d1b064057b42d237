#include "help_format.h"

#include <cctype>
#include <sstream>
#include <utility>
#include <vector>

namespace swa::app {
namespace {

// An 80-column terminal shows every line of a help text without wrapping it again.
constexpr std::size_t kLineWidth = 80;
// The texts were first written for terminals this wide: a source line longer than kLineWidth and at most this long
// was broken by its author where such a terminal ended.
constexpr std::size_t kOldLineWidth = 116;
constexpr std::size_t kColumn = 30;  // CLI11's default: where the meanings start

// A unit that stays on the line of its number ("8 s", "5 %").
bool isUnit(const std::string& word) {
  for (const char* unit : {"s", "s,", "s;", "s)", "ms", "m", "m,", "m)", "%", "%,", "%)", "Hz", "MB", "kB"}) {
    if (word == unit) return true;
  }
  return false;
}

// The words of one line; a range such as "[0.001, 3600]" stays one word, and so does a number with its unit.
std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  std::string word;
  while (in >> word) {
    const bool inside_range = !out.empty() && out.back().find('[') != std::string::npos &&
                              out.back().find(']', out.back().rfind('[')) == std::string::npos;
    const bool unit = !out.empty() && isUnit(word) && std::isdigit(static_cast<unsigned char>(out.back().back())) != 0;
    if (inside_range || unit) {
      out.back() += ' ' + word;
    } else {
      out.push_back(word);
    }
  }
  return out;
}

// A word too long for any line (a list such as "a=1,b=2,c=3") is broken after its commas.
std::vector<std::string> piecesOf(const std::vector<std::string>& all, std::size_t room) {
  std::vector<std::string> out;
  for (const std::string& word : all) {
    if (word.size() <= room) {
      out.push_back(word);
      continue;
    }
    std::size_t start = 0;
    while (start < word.size()) {
      std::size_t end = word.size();
      if (end - start > room) {
        const std::size_t comma = word.rfind(',', start + room - 1);
        if (comma != std::string::npos && comma >= start) end = comma + 1;
      }
      out.push_back(word.substr(start, end - start));
      start = end;
    }
  }
  return out;
}

// Greedy word wrap of one paragraph: the first line starts `first` spaces in, the others `hang` spaces in.
std::string fill(const std::string& text, std::size_t first, std::size_t hang, std::size_t width) {
  std::string out(first, ' ');
  std::size_t used = first;
  bool line_empty = true;
  for (const std::string& word : piecesOf(words(text), width - hang)) {
    if (!line_empty && used + 1 + word.size() > width) {
      out += '\n' + std::string(hang, ' ');
      used = hang;
      line_empty = true;
    } else if (!line_empty) {
      out += ' ';
      ++used;
    }
    out += word;
    used += word.size();
    line_empty = false;
  }
  return out;
}

// Greedy word wrap keeping the text's own line breaks (CLI11 indents every line after a '\n').
std::string wrap(const std::string& text, std::size_t width) {
  std::string out;
  std::istringstream lines(text);
  std::string line;
  for (bool first = true; std::getline(lines, line); first = false) {
    out += (first ? "" : "\n") + fill(line, 0, 0, width);
  }
  return out;
}

// The length of a list marker ("- ", "* ", "12. ", "3) ") at `at`, 0 for none.
std::size_t markerLength(const std::string& line, std::size_t at) {
  if (line.compare(at, 2, "- ") == 0 || line.compare(at, 2, "* ") == 0) return 2;
  std::size_t end = at;
  while (end < line.size() && std::isdigit(static_cast<unsigned char>(line[end])) != 0) ++end;
  if (end == at || end + 1 >= line.size()) return 0;
  const bool numbered = (line[end] == '.' || line[end] == ')') && line[end + 1] == ' ';
  return numbered ? end + 2 - at : 0;
}

// Where the meaning of a definition line ("  SWA_DOMAIN   DDS domain id ...") starts: after the first gap of two
// or more spaces near the start of the line; 0 when the line is not one.
std::size_t definitionColumn(const std::string& line, std::size_t indent) {
  constexpr std::size_t kTermMax = 40;
  const std::size_t gap = line.find("  ", indent);
  if (gap == std::string::npos || gap > kTermMax) return 0;
  const std::size_t meaning = line.find_first_not_of(' ', gap);
  return meaning == std::string::npos ? 0 : meaning;
}

// One paragraph of a text written for wider terminals: its first line's start kept as written (indent, list
// marker or defined term), where its other lines start, and its words.
struct Paragraph {
  std::string lead;
  std::size_t indent = 0;
  std::size_t hang = 0;
  std::string text;
  std::size_t lines = 0;
  std::size_t last_line = 0;  // length of the paragraph's last source line
  std::string source;         // the first source line, kept as written when it is the whole paragraph and fits
};

// Re-wraps a text to `width` columns. A source line longer than `width` (but not than kOldLineWidth) was broken by
// its author only because a wider terminal ended there, so the next line continues it if it is neither blank nor a
// new list item, nor a term being defined, nor a new sentence after a full stop or colon, and is indented like the
// paragraph's other lines (or, as its second line, further in than the first: a hanging indent). Every other line
// break is the author's and stays; a line that fits stays as written.
std::string reflow(const std::string& text, std::size_t width) {
  std::vector<Paragraph> paragraphs;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t indent = line.find_first_not_of(' ');
    if (indent == std::string::npos) {
      paragraphs.push_back(Paragraph{});
      continue;
    }
    const std::size_t marker = markerLength(line, indent);
    const std::size_t column = marker == 0 ? definitionColumn(line, indent) : 0;
    Paragraph* open = paragraphs.empty() ? nullptr : &paragraphs.back();
    const bool capital = std::isupper(static_cast<unsigned char>(line[indent])) != 0;
    const bool new_sentence =
        open != nullptr && open->lines > 0 && capital && (open->text.back() == '.' || open->text.back() == ':');
    const bool wrapped = open != nullptr && open->lines > 0 && open->last_line > width &&
                         open->last_line <= kOldLineWidth && marker == 0 && column == 0 && !new_sentence;
    const bool hanging = wrapped && open->lines == 1 && indent > open->indent;
    if (wrapped && (indent == open->hang || hanging)) {
      if (hanging) open->hang = indent;
      open->text += ' ' + line.substr(indent);
      open->last_line = line.size();
      ++open->lines;
      continue;
    }
    const std::size_t start = column != 0 ? column : indent + marker;
    paragraphs.push_back(Paragraph{line.substr(0, start), indent, start, line.substr(start), 1, line.size(), line});
  }
  std::string out;
  for (std::size_t k = 0; k < paragraphs.size(); ++k) {
    const Paragraph& p = paragraphs[k];
    if (k > 0) out += '\n';
    if (p.lines == 1 && p.source.size() <= width) {
      out += p.source;  // its own spacing (an aligned column) stays
    } else if (p.lines > 0) {
      out += p.lead + fill(p.text, p.lead.size(), p.hang, width).substr(p.lead.size());
    }
  }
  return out;
}

// A flag with a default value ("--record{all}", Cli::flagChoice) and the text of its values.
bool isFlagChoice(const CLI::Option* option) {
  return option->get_name(false, true).find('{') != std::string::npos && !option->get_option_text().empty();
}

}  // namespace

HelpFormat::HelpFormat(std::string usage, std::string details)
    : usage_(std::move(usage)), details_(std::move(details)) {
  column_width(kColumn);
}

// What a reader looks for first comes first: how to call the program, then its options; the longer explanation
// and the exit status follow them.
std::string HelpFormat::make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const {
  if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
  std::string out = make_description(app);
  out += make_usage(app, std::move(name));
  out += make_positionals(app);
  out += make_groups(app, mode);
  if (!details_.empty()) out += '\n' + reflow(details_, kLineWidth) + '\n';
  const std::string footer = app->get_footer();
  if (!footer.empty()) out += '\n' + reflow(footer, kLineWidth) + '\n';
  return out;
}

std::string HelpFormat::make_description(const CLI::App* app) const {
  const std::string description = app->get_description();
  return description.empty() ? std::string() : reflow(description, kLineWidth) + '\n';
}

// Each of the program's usage forms starts a line under the first; a form too long for one goes on further in. A
// source line that starts with an option ("[--out DIR]", "--out DIR") continues the form above it.
std::string HelpFormat::make_usage(const CLI::App* /*app*/, std::string /*name*/) const {
  constexpr std::size_t kForm = 7;  // under the first form, after "Usage: "
  std::vector<std::string> forms;
  std::istringstream lines(usage_);
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t start = line.find_first_not_of(' ');
    if (start == std::string::npos) continue;
    const bool continues = !forms.empty() && (line[start] == '[' || line[start] == '-');
    if (continues) {
      forms.back() += ' ' + line.substr(start);
    } else {
      forms.push_back(line.substr(start));
    }
  }
  std::string out = "\nUsage: ";
  for (std::size_t k = 0; k < forms.size(); ++k) {
    if (k > 0) out += '\n' + std::string(kForm, ' ');
    out += fill(forms[k], 0, kForm + 2, kLineWidth - kForm);
  }
  return out + "\n";
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
