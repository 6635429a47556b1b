#pragma once
// Typed access to TOML values that names the file, line and dotted key in every error, so a user can go
// straight to the mistake. Shared by the scene config and (later) other TOML readers of the compiler.
#include <toml++/toml.h>

#include <optional>
#include <string>
#include <vector>

namespace walk::compiler {

class TomlTable {
 public:
  TomlTable(const toml::table& table, std::string file, std::string prefix)
      : table_(table), file_(std::move(file)), prefix_(std::move(prefix)) {}

  [[nodiscard]] bool has(const std::string& key) const { return table_.contains(key); }
  [[nodiscard]] std::string key_path(const std::string& key) const {
    return prefix_.empty() ? key : prefix_ + "." + key;
  }
  [[nodiscard]] std::string where(const std::string& key) const;  // "file:line" of the key, or of the table
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  [[nodiscard]] std::optional<std::string> string(const std::string& key) const;
  [[nodiscard]] std::optional<double> number(const std::string& key) const;  // integer or float
  [[nodiscard]] std::optional<long long> integer(const std::string& key) const;
  [[nodiscard]] std::optional<bool> boolean(const std::string& key) const;
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

}  // namespace walk::compiler
