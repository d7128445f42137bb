// A command line read through a table of options: the rules lineraster-sim and lineraster-asset
// share, in one place.
//   - Every argument is an option of the table, spelled exactly ("--name", no "--name=value", no
//     grouped short options); a flag stands alone, a value option takes the next argument.
//   - A value never starts with "--": "--obj --out x.png" is a missing value, not a file "--out".
//   - Options are applied in the order given (a later --material replaces an earlier --diffuse);
//     the first problem ends the parse with a one-line message, and nothing else is applied.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace lr::host {

// What an option's handler is given: the option as spelled and its value ("" for a flag).
struct OptionArg {
  std::string_view name, value;

  // "NAME: bad value 'VALUE'", then " (HINT)" when a hint is given.
  std::string bad(std::string_view hint = {}) const {
    std::string s = std::string(name) + ": bad value '" + std::string(value) + "'";
    if (!hint.empty()) s += " (" + std::string(hint) + ")";
    return s;
  }
};

// kStop: a flag after which nothing more is read (--help: what follows is not checked).
enum class OptionKind : uint8_t { kFlag, kValue, kStop };

// A handler's verdict: empty when the option was applied, else the whole one-line message.
using OptionError = std::string;

// One row of a program's table. `missing` replaces "NAME: missing value" when not empty.
template <class Options>
struct OptionRow {
  std::string_view name;
  OptionKind kind;
  OptionError (*apply)(Options&, const OptionArg&);
  std::string_view missing = {};
};

// Applies argv[1..argc) to `out` through `table`. False with a one-line message (without the
// program's name) at the first unknown option, missing value or rejected value; an unknown
// option's message ends in `unknown_hint`.
template <class Options>
bool parse_options(std::span<const OptionRow<Options>> table, int argc, const char* const* argv,
                   std::string_view unknown_hint, Options& out, std::string& error) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view name = argv[i];
    const OptionRow<Options>* row = nullptr;
    for (const OptionRow<Options>& r : table)
      if (r.name == name) row = &r;
    if (row == nullptr) {
      error = "unknown option '" + std::string(name) + "' " + std::string(unknown_hint);
      return false;
    }
    OptionArg arg{name, {}};
    if (row->kind == OptionKind::kValue) {
      if (i + 1 >= argc || std::string_view(argv[i + 1]).starts_with("--")) {
        error = row->missing.empty() ? std::string(name) + ": missing value"
                                     : std::string(row->missing);
        return false;
      }
      arg.value = argv[++i];
    }
    error = row->apply(out, arg);
    if (!error.empty()) return false;
    if (row->kind == OptionKind::kStop) return true;
  }
  return true;
}

}  // namespace lr::host
