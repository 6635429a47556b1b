#pragma once
// Typed access to TOML values that names the file, line and dotted key in every error, so a user can go
// straight to the mistake. The one accessor of every TOML reader: the scene config (compiler) and the
// kiosk config (walkd).
#include <toml++/toml.h>

#include <optional>
#include <string>
#include <vector>

namespace walk {

class TomlTable {
 public:
  TomlTable(const toml::table& table, std::string file, std::string prefix)
      : table_(table), file_(std::move(file)), prefix_(std::move(prefix)) {}

  [[nodiscard]] bool has(const std::string& key) const { return table_.contains(key); }
  [[nodiscard]] std::string key_path(const std::string& key) const {
    return prefix_.empty() ? key : key.empty() ? prefix_ : prefix_ + "." + key;
  }
  [[nodiscard]] std::string where(const std::string& key) const;  // "file:line" of the key, or of the table
  // Throws walk::Error "file:line: key 'a.b': what" at the key's line (key "": the table's own line).
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  [[nodiscard]] std::optional<std::string> string(const std::string& key) const;
  [[nodiscard]] std::optional<double> number(const std::string& key) const;  // integer or float
  [[nodiscard]] std::optional<long long> integer(const std::string& key) const;
  [[nodiscard]] std::optional<bool> boolean(const std::string& key) const;
  // With a fallback for a missing key, and a range (inclusive) that a given value must lie in.
  [[nodiscard]] double number(const std::string& key, double fallback, double lo, double hi) const;
  [[nodiscard]] int integer(const std::string& key, int fallback, int lo, int hi) const;
  [[nodiscard]] bool boolean(const std::string& key, bool fallback) const;
  // An array of exactly `count` numbers (count 0: any length).
  [[nodiscard]] std::optional<std::vector<double>> numbers(const std::string& key, std::size_t count) const;
  [[nodiscard]] std::optional<std::vector<std::string>> strings(const std::string& key) const;
  [[nodiscard]] std::optional<TomlTable> table(const std::string& key) const;
  [[nodiscard]] std::vector<TomlTable> array_of_tables(const std::string& key) const;
  // Fails on any key not in `known`: a misspelt key must not be silently ignored.
  void only(std::initializer_list<const char*> known) const;

  [[nodiscard]] const toml::table& raw() const { return table_; }
  [[nodiscard]] const std::string& file() const { return file_; }

 private:
  const toml::node* node(const std::string& key) const { return table_.get(key); }
  const toml::table& table_;
  std::string file_;
  std::string prefix_;
};

// Parses a TOML file; a syntax error becomes walk::Error "file:line: ...".
[[nodiscard]] toml::table parse_toml_file(const std::string& path, std::string* text = nullptr);

}  // namespace walk
