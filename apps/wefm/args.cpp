#include "args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace wefm_cli {

namespace {

const OptionSpec* find_long(const std::vector<OptionSpec>& specs, const std::string& name) {
  for (const auto& s : specs)
    if (s.name == name) return &s;
  return nullptr;
}

const OptionSpec* find_short(const std::vector<OptionSpec>& specs, char c) {
  for (const auto& s : specs)
    if (s.short_name == c) return &s;
  return nullptr;
}

bool store(const OptionSpec& spec, const std::string& value, ParsedArgs& out, std::string& error) {
  auto& slot = out.values[spec.name];
  if (!slot.empty() && !spec.repeatable) {
    error = "option --" + spec.name + " given more than once";
    return false;
  }
  slot.push_back(value);
  return true;
}

}  // namespace

bool parse_args(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs, ParsedArgs& out,
                std::string& error) {
  // Scan for help first: a user asking for help should get it even if the rest of the line is wrong.
  for (const auto& a : args) {
    if (a == "--") break;
    if (a == "--help" || a == "-h") {
      out.help = true;
      return true;
    }
  }
  bool options_done = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (options_done || a.size() < 2 || a[0] != '-' || a == "-") {
      out.positionals.push_back(a);
      continue;
    }
    if (a == "--") {
      options_done = true;
      continue;
    }
    const OptionSpec* spec = nullptr;
    std::string value;
    bool has_inline_value = false;
    if (a[1] == '-') {
      std::string name = a.substr(2);
      const size_t eq = name.find('=');
      if (eq != std::string::npos) {
        value = name.substr(eq + 1);
        name.resize(eq);
        has_inline_value = true;
      }
      spec = find_long(specs, name);
      if (!spec) {
        error = "unknown option --" + name;
        return false;
      }
    } else {
      // A negative number is never an option: every numeric option takes its value separately.
      spec = find_short(specs, a[1]);
      if (!spec) {
        error = "unknown option " + a;
        return false;
      }
      if (a.size() > 2) {
        value = a.substr(2);
        has_inline_value = true;
      }
    }
    if (spec->value_name.empty()) {
      if (has_inline_value) {
        error = "option --" + spec->name + " takes no value";
        return false;
      }
      if (!store(*spec, std::string(), out, error)) return false;
      continue;
    }
    if (!has_inline_value) {
      if (i + 1 >= args.size()) {
        error = "option --" + spec->name + " needs a value (" + spec->value_name + ")";
        return false;
      }
      value = args[++i];
    }
    if (!store(*spec, value, out, error)) return false;
  }
  return true;
}

std::string format_options(const std::vector<OptionSpec>& specs) {
  std::string text;
  for (const auto& s : specs) {
    std::string left = "  ";
    left += s.short_name ? std::string("-") + s.short_name + ", " : std::string("    ");
    left += "--" + s.name;
    if (!s.value_name.empty()) left += " " + s.value_name;
    if (left.size() < 35) left.append(36 - left.size(), ' ');
    else left += "\n" + std::string(36, ' ');
    text += left + s.help;
    if (!s.default_text.empty()) text += " [default: " + s.default_text + "]";
    if (s.repeatable) text += " (repeatable)";
    text += "\n";
  }
  return text;
}

bool parse_double(const std::string& text, double& out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(v)) return false;
  out = v;
  return true;
}

bool parse_int(const std::string& text, long long& out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size()) return false;
  out = v;
  return true;
}

}  // namespace wefm_cli
