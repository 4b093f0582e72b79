#pragma once
// Hand-written command-line parser: GNU-style long options (--name value, --name=value), a few
// single-letter aliases (-o value, -j4), flags, repeatable options and positionals. Kept free of any
// dependency so the tool builds wherever the library builds.
#include <map>
#include <string>
#include <vector>

namespace wefm_cli {

struct OptionSpec {
  std::string name;          // long name without the dashes
  char short_name = 0;       // 0 = none
  std::string value_name;    // empty = a flag that takes no value
  std::string help;
  std::string default_text;  // shown in --help; empty = no default shown
  bool repeatable = false;
};

struct ParsedArgs {
  std::map<std::string, std::vector<std::string>> values;  // flags get one empty string per occurrence
  std::vector<std::string> positionals;
  bool help = false;

  bool has(const std::string& name) const { return values.count(name) != 0; }
  // Last value given (options that are not repeatable keep only one anyway).
  const std::string& value(const std::string& name) const { return values.at(name).back(); }
};

// Returns false and sets `error` on an unknown option, a missing value, or a repeated option that is
// not repeatable. "--help"/"-h" anywhere set `help` instead of failing, so "wefm flatten --bad --help"
// still shows the help.
bool parse_args(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs, ParsedArgs& out,
                std::string& error);

// Formats the option table for --help: every option, its value, its default.
std::string format_options(const std::vector<OptionSpec>& specs);

// Strict numeric conversions: the whole string must be consumed (so "--s 1x" is a usage error, not 1).
bool parse_double(const std::string& text, double& out);
bool parse_int(const std::string& text, long long& out);

}  // namespace wefm_cli
