// A small command-line parser shared by the subcommands: positionals, flags (--name), options
// with a value (--name VALUE or --name=VALUE, repeatable ones collected in order), the short
// forms of the common ones (-s VALUE or -s=VALUE), and `--`, after which every argument is
// positional.
#pragma once
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "host/io/suggest.h"

namespace lpir {

// The short forms, for every command that has the long one: -s --sensor, -o --out, -b --backend,
// -f --format, -t --topic, -p --protocol, -r --recursive, -q --quiet, -v --verbose, -h --help.
inline const std::map<char, std::string>& ShortOptions() {
  static const std::map<char, std::string> table = {
      {'s', "--sensor"},  {'o', "--out"},      {'b', "--backend"},   {'f', "--format"},
      {'t', "--topic"},   {'p', "--protocol"}, {'r', "--recursive"}, {'q', "--quiet"},
      {'v', "--verbose"}, {'h', "--help"}};
  return table;
}

// True for an argument that is an option, not a value or a file: "-" and a letter, or "--" and
// more ("-3.5" and "-" are values).
inline bool IsOptionArgument(const std::string& a) {
  if (a.size() < 2 || a[0] != '-') return false;
  return a[1] == '-' ? a.size() > 2 : (a[1] >= 'a' && a[1] <= 'z') || (a[1] >= 'A' && a[1] <= 'Z');
}

class Args {
 public:
  // `flags` take no value; `options` take one; `repeatable` options may be given several times
  // (GetAll). Anything else that IsOptionArgument is std::invalid_argument, with the nearest
  // known option when one is near ("unknown option --sensr (did you mean --sensor?)").
  Args(int argc, char** argv, const std::set<std::string>& flags,
       const std::set<std::string>& options, const std::set<std::string>& repeatable = {}) {
    bool options_end = false;
    for (int i = 0; i < argc; ++i) {
      const std::string a = argv[i];
      if (!options_end && a == "--") {
        options_end = true;
        continue;
      }
      if (options_end || !IsOptionArgument(a)) {
        positional_.push_back(a);
        continue;
      }
      // "--name=VALUE", "-s=VALUE"
      const size_t eq = a.rfind("--", 0) == 0 ? a.find('=') : a[2] == '=' ? 2 : std::string::npos;
      const std::string key =
          Long(eq == std::string::npos ? a : a.substr(0, eq), flags, options, repeatable);
      if (flags.count(key)) {
        if (eq != std::string::npos) throw std::invalid_argument(key + " takes no value");
        values_[key] = {"1"};
        continue;
      }
      std::string value;
      if (eq != std::string::npos) {
        value = a.substr(eq + 1);
      } else {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        value = argv[++i];
      }
      if (repeatable.count(key))
        values_[key].push_back(value);
      else
        values_[key] = {value};
    }
  }
  const std::vector<std::string>& positional() const { return positional_; }
  bool Has(const std::string& key) const { return values_.count(key) != 0; }
  std::string Get(const std::string& key, const std::string& fallback = "") const {
    auto it = values_.find(key);
    return it == values_.end() ? fallback : it->second.back();
  }
  // Every value of a repeatable option, in the order given.
  std::vector<std::string> GetAll(const std::string& key) const {
    auto it = values_.find(key);
    return it == values_.end() ? std::vector<std::string>{} : it->second;
  }
  // The value of a required option, or std::invalid_argument naming it.
  std::string Require(const std::string& key) const {
    if (!Has(key)) throw std::invalid_argument(key + " is required");
    return Get(key);
  }
  double GetNumber(const std::string& key, double fallback) const {
    if (!Has(key)) return fallback;
    try {
      size_t used = 0;
      double v = std::stod(Get(key), &used);
      if (used != Get(key).size()) throw std::invalid_argument("");
      return v;
    } catch (const std::exception&) {
      throw std::invalid_argument(key + " expects a number, got '" + Get(key) + "'");
    }
  }

 private:
  // The long name of option `name` ("-s" -> "--sensor"), or std::invalid_argument naming it and
  // the nearest known option.
  static std::string Long(const std::string& name, const std::set<std::string>& flags,
                          const std::set<std::string>& options,
                          const std::set<std::string>& repeatable) {
    auto known = [&](const std::string& k) {
      return flags.count(k) || options.count(k) || repeatable.count(k);
    };
    if (name.size() == 2 && name[0] == '-') {
      auto it = ShortOptions().find(name[1]);
      if (it != ShortOptions().end() && known(it->second)) return it->second;
    } else if (known(name)) {
      return name;
    }
    std::vector<std::string> names;
    for (const auto* set : {&flags, &options, &repeatable})
      names.insert(names.end(), set->begin(), set->end());
    // "-sensor" is compared as "--sensor"; a short form as itself
    const std::string typed = name.rfind("--", 0) == 0 || name.size() == 2 ? name : "-" + name;
    throw std::invalid_argument("unknown option " + name + DidYouMean(typed, names));
  }

  std::vector<std::string> positional_;
  std::map<std::string, std::vector<std::string>> values_;
};

}  // namespace lpir
