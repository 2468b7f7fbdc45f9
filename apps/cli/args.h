// A small command-line parser shared by the subcommands: positionals, --flag, --key value.
#pragma once
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace lpir {

class Args {
 public:
  // `flags` take no value; `options` take one. Anything else starting with "--" is an error.
  Args(int argc, char** argv, const std::set<std::string>& flags,
       const std::set<std::string>& options) {
    for (int i = 0; i < argc; ++i) {
      std::string a = argv[i];
      if (a.rfind("--", 0) != 0) {
        positional_.push_back(a);
      } else if (flags.count(a)) {
        values_[a] = "1";
      } else if (options.count(a)) {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        values_[a] = argv[++i];
      } else {
        throw std::invalid_argument("unknown option " + a);
      }
    }
  }
  const std::vector<std::string>& positional() const { return positional_; }
  bool Has(const std::string& key) const { return values_.count(key) != 0; }
  std::string Get(const std::string& key, const std::string& fallback = "") const {
    auto it = values_.find(key);
    return it == values_.end() ? fallback : it->second;
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
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
};

}  // namespace lpir
