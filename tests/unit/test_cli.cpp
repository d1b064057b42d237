// The command-line conventions every SWA program shares (swa/app/cli.h): both spellings, values that look like
// options, every problem reported together, -h/--help winning, required options, lists, choices, and the --help
// text CLI11 generates.

#include <algorithm>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "swa/app/cli.h"

namespace swa::app {

// An enum named by toString, as agent::Mode is: Cli::choice finds it by argument-dependent lookup.
namespace fixture {
enum class Colour { kRed, kGreen };
std::string toString(Colour c) { return c == Colour::kRed ? "red" : "green"; }
}  // namespace fixture

namespace {

struct Options {
  bool help = false;
  bool verbose = false;
  bool list_keys = false;
  std::string out = "out/x";
  std::string name;
  double rate = 2.5;
  int count = 3;
  std::vector<std::string> sets;
  std::vector<std::string> pairs;
  std::optional<fixture::Colour> colour;
  std::string scenario;
  std::optional<std::string> domain;
};

Cli makeCli(Options& o) {
  Cli cli("tool", "a program under test.");
  cli.usage("tool --scenario FILE [options]");
  cli.details("Details after the options.");
  cli.scenario(o.scenario, "scenario YAML");
  cli.required("--scenario");
  cli.path("--out", "DIR", o.out, "output directory");
  cli.text("--name", "NAME", o.name, "a label", "a name");
  cli.real("--rate", "R", o.rate, 0.5, 10.0, "a rate in hertz", "how often");
  cli.integer("--count", "N", o.count, 1, 100, "a count", "how many");
  cli.overrides(o.sets, "override a key");
  cli.list("--pair", "A=B", o.pairs, "pairs", true);
  cli.choice("--colour", "C", {fixture::Colour::kRed, fixture::Colour::kGreen}, o.colour, "the colour");
  cli.domain(o.domain, 232);
  cli.flag("--verbose", o.verbose, "say more");
  cli.answer("--keys", o.list_keys, "list the keys and exit");
  cli.footer("Exit status: 0 done.\n");
  return cli;
}

// The problems of one command line ("" when there are none) and the options read.
std::string problemsOf(const std::vector<std::string>& args, Options* read = nullptr) {
  Options o;
  Cli cli = makeCli(o);
  const Problems problems = cli.parse(args);
  if (read != nullptr) *read = o;
  std::string all;
  for (const std::string& p : problems) all += p + "\n";
  return all;
}

bool mentions(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

TEST(Cli, ReadsBothSpellingsAndLeavesDefaultsAlone) {
  // GIVEN every kind of option, some as "--opt value", some as "--opt=value"
  Options o;
  const std::string problems =
      problemsOf({"--scenario", "s.yaml", "--out=d", "--rate", "0.5", "--count=100", "--set", "a=1", "--set=b=2",
                  "--colour", "green", "--domain=7", "--verbose", "--name", "n"},
                 &o);
  // THEN no problem, and each value where it belongs; `--set=b=2` splits at the first '=' only
  EXPECT_EQ(problems, "");
  EXPECT_EQ(o.scenario, "s.yaml");
  EXPECT_EQ(o.out, "d");
  EXPECT_DOUBLE_EQ(o.rate, 0.5);
  EXPECT_EQ(o.count, 100);
  EXPECT_EQ(o.sets, (std::vector<std::string>{"a=1", "b=2"}));
  ASSERT_TRUE(o.colour.has_value());
  EXPECT_TRUE(*o.colour == fixture::Colour::kGreen);
  ASSERT_TRUE(o.domain.has_value());
  EXPECT_EQ(*o.domain, "7");
  EXPECT_TRUE(o.verbose);
  EXPECT_EQ(o.name, "n");

  // GIVEN only the required option
  Options d;
  EXPECT_EQ(problemsOf({"--scenario", "s"}, &d), "");
  // THEN everything else keeps its default
  EXPECT_EQ(d.out, "out/x");
  EXPECT_DOUBLE_EQ(d.rate, 2.5);
  EXPECT_EQ(d.count, 3);
  EXPECT_FALSE(d.colour.has_value());
  EXPECT_FALSE(d.domain.has_value());
  EXPECT_FALSE(d.verbose);
}

TEST(Cli, TheArgumentAfterAnOptionIsItsValueWhateverItLooksLike) {
  // GIVEN values starting with '-'
  Options o;
  const std::string problems = problemsOf({"--scenario", "s", "--rate", "-1", "--name", "--verbose"}, &o);
  // THEN they are values (a bad number, a name), not options
  EXPECT_TRUE(mentions(problems, "--rate '-1' is not a rate in hertz in [0.5, 10]")) << problems;
  EXPECT_EQ(o.name, "--verbose");
  EXPECT_FALSE(o.verbose);
}

TEST(Cli, EveryProblemOfOneLineIsReportedOnePerLine) {
  // GIVEN a bad real, a bad integer, an empty path, an empty name, a bad choice, an unknown option, a stray word,
  // no --scenario and an option without its value at the end
  const std::string p = problemsOf({"stray", "--rate", "nan", "--count", "3x", "--out=", "--name", "", "--colour",
                                    "blue", "--frobnicate", "--count"});
  // THEN each is named, in a line of its own
  for (const char* line :
       {"--rate 'nan' is not a rate in hertz in [0.5, 10]\n", "--count '3x' is not a count in [1, 100]\n",
        "--out needs a file name\n", "--name needs a name\n", "--colour must be red or green, got 'blue'\n",
        "unknown option '--frobnicate' (see --help)\n", "unknown argument 'stray' (see --help)\n",
        "--count needs a value\n", "--scenario FILE is required\n"}) {
    EXPECT_TRUE(mentions(p, line)) << line << " missing from:\n" << p;
  }
  EXPECT_EQ(std::count(p.begin(), p.end(), '\n'), 9) << p;
}

TEST(Cli, AMistypedOptionIsAnsweredWithTheNearestOneAndKeepsItsValue) {
  // GIVEN an option one or two letters off a known one, with its value as the next word or after '='
  // THEN the problem names the option it was probably meant to be, in one line with the value it was given
  EXPECT_TRUE(mentions(problemsOf({"--scenario", "s", "--rat", "2"}),
                       "unknown option '--rat' (given '2'): did you mean --rate? (see --help)\n"));
  EXPECT_TRUE(mentions(problemsOf({"--scenario", "s", "--colur=red"}),
                       "unknown option '--colur=red': did you mean --colour? (see --help)\n"));
  // AND an option far from every known one gets no guess, a word after it is still taken as its value, and an
  // option after it is not
  const std::string far = problemsOf({"--scenario", "s", "--frobnicate", "x", "--verbose"});
  EXPECT_EQ(far, "unknown option '--frobnicate' (given 'x') (see --help)\n");
}

TEST(Cli, AnEmptyInlineValueIsAValueAndTakesNothingAfterIt) {
  // GIVEN "--out=" followed by another option
  Options o;
  const std::string p = problemsOf({"--scenario", "s", "--out=", "--verbose"}, &o);
  // THEN --out got the empty value (and says so) and --verbose stays an option
  EXPECT_EQ(p, "--out needs a file name\n");
  EXPECT_TRUE(o.verbose);
}

TEST(Cli, NumbersMustBeWholeAndInRange) {
  for (const char* bad : {"", " 3", "3 ", "0x10", "1e2", "101", "0", "-5"}) {
    EXPECT_TRUE(mentions(problemsOf({"--scenario", "s", "--count", bad}), "--count '")) << "'" << bad << "'";
  }
  for (const char* bad : {"inf", "nan", "10.5", "0.4", "1,5", "5s"}) {
    EXPECT_TRUE(mentions(problemsOf({"--scenario", "s", "--rate", bad}), "--rate '")) << bad;
  }
  Options o;
  EXPECT_EQ(problemsOf({"--scenario", "s", "--rate", "1e1", "--count", "007"}, &o), "");
  EXPECT_DOUBLE_EQ(o.rate, 10.0);
  EXPECT_EQ(o.count, 7);  // decimal, not octal
}

TEST(Cli, TheLastValueOfARepeatedOptionWinsAndEachIsChecked) {
  Options o;
  const std::string p = problemsOf({"--scenario", "s", "--count", "x", "--count", "4", "--out", "a", "--out", "b"}, &o);
  EXPECT_EQ(p, "--count 'x' is not a count in [1, 100]\n");
  EXPECT_EQ(o.count, 4);
  EXPECT_EQ(o.out, "b");
}

TEST(Cli, ListsKeepOrderAndSeveralValuesRunToTheNextOption) {
  // GIVEN one --pair with two values, a repeated --pair, and a word after another option
  Options o;
  const std::string p =
      problemsOf({"--pair", "a=1", "b=2", "--scenario", "s", "--pair=c=3", "d=4", "--out", "o", "e=5"}, &o);
  // THEN the pairs in order, and the word after --out's value is no pair
  EXPECT_EQ(o.pairs, (std::vector<std::string>{"a=1", "b=2", "c=3", "d=4"}));
  EXPECT_EQ(p, "unknown argument 'e=5' (see --help)\n");
  // AND --set takes one value per flag
  EXPECT_EQ(problemsOf({"--scenario", "s", "--set", "a=1", "b=2"}), "unknown argument 'b=2' (see --help)\n");
}

TEST(Cli, HelpWinsAndAnswerFlagsNeedNoRequiredOption) {
  // GIVEN --help among problems
  Options o;
  Cli cli = makeCli(o);
  const Problems problems = cli.parse({"--bogus", "-h", "--count", "x"});
  // THEN the problems are found but not reported, and no required option is asked for
  EXPECT_TRUE(cli.given("--help"));
  EXPECT_EQ(problems.size(), 2u);
  EXPECT_NO_THROW(cli.report(problems));

  // GIVEN an answer flag alone
  Options a;
  // THEN --scenario is not required
  EXPECT_EQ(problemsOf({"--keys"}, &a), "");
  EXPECT_TRUE(a.list_keys);
}

TEST(Cli, ReportThrowsEveryProblemOnePerLine) {
  Options o;
  Cli cli = makeCli(o);
  const Problems problems = cli.parse({"--bogus", "--count", "x"});
  try {
    cli.report(problems);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "--count 'x' is not a count in [1, 100]\nunknown option '--bogus' (see --help)\n"
              "--scenario FILE is required");
  }
  EXPECT_NO_THROW(cli.report({}));
}

TEST(Cli, AnOptionLackingItsValueCountsAsGiven) {
  // GIVEN the required option last, without its value
  Options o;
  Cli cli = makeCli(o);
  const Problems problems = cli.parse({"--verbose", "--scenario"});
  // THEN only the missing value is reported, and the option before it is read
  EXPECT_EQ(problems, (Problems{"--scenario needs a value"}));
  EXPECT_TRUE(cli.given("--scenario"));
  EXPECT_TRUE(o.verbose);
  EXPECT_FALSE(cli.given("--out"));
}

TEST(Cli, ParseOptionsRunsTheProgramsCrossChecksAndSetsHelp) {
  // GIVEN a cross-check that --verbose and --keys do not go together
  const auto finish = [](Options& o, const Cli& cli, Problems& p) {
    if (o.verbose && cli.given("--keys")) p.push_back("--verbose and --keys do not go together");
  };
  // THEN it is reported with the other problems
  try {
    parseOptions<Options>({"--verbose", "--keys", "--count", "0"}, makeCli, finish);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "--count '0' is not a count in [1, 100]\n--verbose and --keys do not go together");
  }
  // AND --help is in the options, winning over the problems
  EXPECT_TRUE(parseOptions<Options>({"--help", "--verbose", "--keys"}, makeCli, finish).help);
}

TEST(Cli, HelpListsEveryOptionWithValueNameDefaultRangeAndMeaning) {
  const std::string h = helpText(makeCli);
  // THEN the parts come in order: summary, usage, options, details, footer
  const std::size_t summary = h.find("tool: a program under test.");
  const std::size_t usage = h.find("Usage: tool --scenario FILE [options]");
  const std::size_t options = h.find("Options:");
  const std::size_t details = h.find("Details after the options.");
  const std::size_t footer = h.find("Exit status: 0 done.");
  EXPECT_EQ(summary, 0u);
  EXPECT_LT(summary, usage);
  EXPECT_LT(usage, options);
  EXPECT_LT(options, details);
  EXPECT_LT(details, footer);
  EXPECT_NE(footer, std::string::npos);
  // AND each option with its value name, default, range or choices
  for (const char* must :
       {"-h,--help", "--scenario FILE REQUIRED", "--out DIR=out/x", "--rate R=2.5", "how often; in [0.5, 10]",
        "--count N=3", "how many; in [1, 100]", "--set key=value", "repeatable, applied in order", "--pair A=B ...",
        "one of red or green", "--domain D", "0..232 (default: $SWA_DOMAIN, else 0)", "--verbose", "--keys"}) {
    EXPECT_TRUE(mentions(h, must)) << must << " missing from:\n" << h;
  }
  // AND an empty text shows no default
  EXPECT_FALSE(mentions(h, "--name NAME=")) << h;
}

TEST(Cli, HelpWrapsLongMeaningsWithoutSplittingARange) {
  // GIVEN a meaning far longer than a line, and one whose range would straddle the end of the first line
  bool flag = false;
  double x = 1;
  Cli cli("tool", "wraps.");
  cli.usage("tool");
  std::string meaning;
  for (int k = 0; k < 40; ++k) meaning += "word" + std::to_string(k) + " ";
  cli.flag("--long", flag, meaning);
  cli.real("--x", "X", x, 0.001, 3600.0, "a time", std::string(37, 'm'));  // "[0.001," fits, "3600]" does not
  const std::string h = cli.help();
  // THEN no line is longer than an 80-column terminal, every word is there, and the range stays on one line
  std::istringstream lines(h);
  std::string line;
  while (std::getline(lines, line)) EXPECT_LE(line.size(), 80u) << line;
  EXPECT_TRUE(mentions(h, "word39")) << h;
  EXPECT_TRUE(mentions(h, "[0.001, 3600]")) << h;
}

// The lines of a help text after the line holding `start`, up to the next empty line.
std::vector<std::string> linesAfter(const std::string& text, const std::string& start) {
  std::istringstream in(text.substr(text.find(start)));
  std::vector<std::string> out;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line) && !line.empty()) out.push_back(line);
  return out;
}

TEST(Cli, HelpReflowsDetailsWrittenForWiderTerminalsKeepingTheirStructure) {
  // GIVEN details written for a 116-column terminal: a paragraph broken where that terminal ended, a numbered item
  // with its continuation under its text, a table of terms with aligned meanings, and short lines meant as they are
  const std::string wide(" and more words to fill a line that an eighty-column terminal would wrap again");
  Cli cli("tool", "reflows.");
  cli.usage("tool");
  cli.details("Paragraph:\nThe first line of a paragraph" + wide + " itself,\ngoes on here.\n" +
              "  1. a numbered item" + wide + " at the\n     end of its line.\n" + "  TERM     the meaning of a term" +
              wide + ", so\n           it goes on under the meaning.\n" + "  OTHER    short.\n" +
              "Example:\n  tool --a\n  tool --b    # aligned on purpose");
  const std::string h = cli.help();
  // THEN every line fits 80 columns
  std::istringstream all(h);
  std::string line;
  while (std::getline(all, line)) EXPECT_LE(line.size(), 80u) << line;
  // AND the paragraph is one flowing text again, the item's lines stay under its text, the term's under its meaning
  const std::vector<std::string> body = linesAfter(h, "Paragraph:");
  ASSERT_GE(body.size(), 9u) << h;
  std::string flowing;
  for (std::size_t k = 0; k < 3; ++k) flowing += (k ? " " : "") + body[k];
  EXPECT_EQ(flowing.rfind("The first line", 0), 0u) << h;
  EXPECT_TRUE(mentions(flowing, "would wrap again itself, goes on here.")) << h;
  bool item_end = false;
  bool term_end = false;
  for (const std::string& l : body) {
    if (mentions(l, "its line.")) item_end = l.rfind("     ", 0) == 0 && l[5] != ' ';
    if (mentions(l, "meaning.")) term_end = l.rfind("           ", 0) == 0 && l[11] != ' ';
  }
  EXPECT_TRUE(item_end) << h;
  EXPECT_TRUE(term_end) << h;
  EXPECT_TRUE(mentions(h, "\n  TERM     the meaning of a term")) << h;
  // AND lines that fit stay exactly as written, alignment included
  EXPECT_TRUE(mentions(h, "\n  OTHER    short.\n")) << h;
  EXPECT_TRUE(mentions(h, "\n  tool --a\n  tool --b    # aligned on purpose")) << h;
}

// A flag that may carry a value (swa_launch --record[=all|monitor]): what each spelling reads as.
struct FlagChoiceRead {
  std::optional<std::size_t> value;  // index into {"all", "monitor"}; nullopt: the flag was not taken
  std::string problems;
  std::string help;
};

FlagChoiceRead readFlagChoice(const std::vector<std::string>& args) {
  FlagChoiceRead r;
  bool verbose = false;
  Cli cli("tool", "a program under test.");
  cli.flagChoice(
      "--record", {"all", "monitor"}, [&r](std::size_t k) { r.value = k; }, "record the run");
  cli.flag("--verbose", verbose, "say more");
  for (const std::string& p : cli.parse(args)) r.problems += p + "\n";
  r.help = cli.help();
  return r;
}

TEST(Cli, AFlagChoiceIsItsFirstNameBareAndTakesAValueOnlyAfterAnEqualsSign) {
  // WHEN the flag is given bare, before another option THEN it reads as the first name and takes nothing after it
  FlagChoiceRead bare = readFlagChoice({"--record", "--verbose"});
  EXPECT_EQ(bare.problems, "");
  EXPECT_EQ(bare.value, std::optional<std::size_t>(0));
  // WHEN given "=monitor" or "=all" THEN that name
  EXPECT_EQ(readFlagChoice({"--record=monitor"}).value, std::optional<std::size_t>(1));
  EXPECT_EQ(readFlagChoice({"--record=all"}).value, std::optional<std::size_t>(0));
  // WHEN absent THEN nothing is taken
  EXPECT_FALSE(readFlagChoice({"--verbose"}).value.has_value());
  // WHEN the value is unknown (also "true", which a plain CLI11 flag would accept) THEN the problem lists the names
  EXPECT_EQ(readFlagChoice({"--record=sensors"}).problems, "--record must be all or monitor, got 'sensors'\n");
  EXPECT_EQ(readFlagChoice({"--record=true"}).problems, "--record must be all or monitor, got 'true'\n");
  // WHEN the value is a separate argument THEN it is not the flag's: an unknown argument, the flag bare
  const FlagChoiceRead separate = readFlagChoice({"--record", "monitor"});
  EXPECT_EQ(separate.problems, "unknown argument 'monitor' (see --help)\n");
  // AND --help shows the values next to the name and lists them in the meaning
  EXPECT_TRUE(mentions(bare.help, "--record[=all|monitor]")) << bare.help;
  EXPECT_TRUE(mentions(bare.help, "record the run; one of all or monitor")) << bare.help;
  EXPECT_FALSE(mentions(bare.help, "{all}")) << bare.help;
}

}  // namespace
}  // namespace swa::app
