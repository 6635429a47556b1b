#pragma once
// A TOML table plus its dotted path, so every config error says "file:line: devices.treadmill.port: ...".
#include <toml++/toml.h>

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "model/error.hpp"

namespace walk::kiosk {

// A table plus its dotted path, so every error can say "file:line: display.width: ...".
class Section {
 public:
  Section(const toml::table& table, const std::string& file, std::string prefix)
      : table_(table), file_(file), prefix_(std::move(prefix)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const toml::node* n = key.empty() ? nullptr : table_.get(key);
    const auto line = n ? n->source().begin.line : table_.source().begin.line;
    throw Error(located(file_, line, (key.empty() ? prefix_ : path(key)) + ": " + what));
  }
  [[nodiscard]] std::string path(const std::string& key) const {
    return prefix_.empty() ? key : prefix_ + "." + key;
  }

  void only(std::initializer_list<const char*> known) const {
    for (const auto& [k, v] : table_) {
      bool ok = false;
      for (const char* name : known) ok = ok || k.str() == name;
      if (!ok) fail(std::string(k.str()), "unknown key");
    }
  }
  std::optional<double> number(const std::string& key) const {
    const toml::node* n = table_.get(key);
    if (!n) return std::nullopt;
    if (auto v = n->value<double>(); v && (n->is_floating_point() || n->is_integer())) return *v;
    fail(key, "expected a number");
  }
  double number(const std::string& key, double fallback, double lo, double hi) const {
    const double v = number(key).value_or(fallback);
    if (!(v >= lo && v <= hi)) fail(key, "must be between " + fmt(lo) + " and " + fmt(hi));
    return v;
  }
  int integer(const std::string& key, int fallback, int lo, int hi) const {
    const toml::node* n = table_.get(key);
    if (!n) return fallback;
    if (!n->is_integer()) fail(key, "expected an integer");
    const auto v = *n->value<long long>();
    if (v < lo || v > hi) fail(key, "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    return static_cast<int>(v);
  }
  bool boolean(const std::string& key, bool fallback) const {
    const toml::node* n = table_.get(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(key, "expected true or false");
    return *n->value<bool>();
  }
  std::optional<std::string> string(const std::string& key) const {
    const toml::node* n = table_.get(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(key, "expected a string");
    return *n->value<std::string>();
  }
  std::vector<std::string> strings(const std::string& key) const {
    const toml::node* n = table_.get(key);
    if (!n) return {};
    const auto* arr = n->as_array();
    if (!arr) fail(key, "expected an array of strings");
    std::vector<std::string> out;
    for (const auto& item : *arr) {
      if (!item.is_string()) fail(key, "expected an array of strings");
      out.push_back(*item.value<std::string>());
    }
    return out;
  }
  [[nodiscard]] const toml::table& raw() const { return table_; }
  [[nodiscard]] const std::string& file() const { return file_; }
  std::optional<Section> table(const std::string& key) const {
    const toml::node* n = table_.get(key);
    if (!n) return std::nullopt;
    if (!n->is_table()) fail(key, "expected a table");
    return Section(*n->as_table(), file_, path(key));
  }

 private:
  static std::string fmt(double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  }
  const toml::table& table_;
  const std::string& file_;
  std::string prefix_;
};

}  // namespace walk::kiosk
