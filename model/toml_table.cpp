#include "model/toml_table.hpp"

#include <fstream>
#include <sstream>

#include "model/error.hpp"

namespace walk {

std::string TomlTable::where(const std::string& key) const {
  const toml::node* n = node(key);
  const auto line = n ? n->source().begin.line : table_.source().begin.line;
  return file_ + ":" + std::to_string(line);
}

void TomlTable::fail(const std::string& key, const std::string& what) const {
  const toml::node* n = node(key);
  const auto line = n ? n->source().begin.line : table_.source().begin.line;
  const std::string path = key_path(key);
  throw Error(located(file_, line, path.empty() ? what : "key '" + path + "': " + what));
}

std::optional<std::string> TomlTable::string(const std::string& key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_string()) fail(key, "expected a string");
  return n->value<std::string>();
}

std::optional<double> TomlTable::number(const std::string& key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_number()) fail(key, "expected a number");
  return n->value<double>();
}

std::optional<long long> TomlTable::integer(const std::string& key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_integer()) fail(key, "expected an integer");
  return n->value<long long>();
}

std::optional<bool> TomlTable::boolean(const std::string& key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_boolean()) fail(key, "expected true or false");
  return n->value<bool>();
}

namespace {
// 0.25, 1e6, 480: the shortest form that reads back as the same number.
std::string short_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}
}  // namespace

double TomlTable::number(const std::string& key, double fallback, double lo, double hi) const {
  const double v = number(key).value_or(fallback);
  if (!(v >= lo && v <= hi)) fail(key, "must be between " + short_number(lo) + " and " + short_number(hi));
  return v;
}

int TomlTable::integer(const std::string& key, int fallback, int lo, int hi) const {
  const long long v = integer(key).value_or(fallback);
  if (v < lo || v > hi) fail(key, "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
  return static_cast<int>(v);
}

bool TomlTable::boolean(const std::string& key, bool fallback) const {
  return boolean(key).value_or(fallback);
}

std::optional<std::vector<double>> TomlTable::numbers(const std::string& key, std::size_t count) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  const toml::array* a = n->as_array();
  if (!a || (count > 0 && a->size() != count))
    fail(key, count > 0 ? "expected an array of " + std::to_string(count) + " numbers" : "expected an array");
  std::vector<double> out;
  for (const auto& e : *a) {
    if (!e.is_number()) fail(key, "expected only numbers in the array");
    out.push_back(*e.value<double>());
  }
  return out;
}

std::optional<std::vector<std::string>> TomlTable::strings(const std::string& key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (n->is_string()) return std::vector<std::string>{*n->value<std::string>()};
  const toml::array* a = n->as_array();
  if (!a) fail(key, "expected a string or an array of strings");
  std::vector<std::string> out;
  for (const auto& e : *a) {
    if (!e.is_string()) fail(key, "expected only strings in the array");
    out.push_back(*e.value<std::string>());
  }
  return out;
}

std::optional<TomlTable> TomlTable::table(const std::string& key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_table()) fail(key, "expected a table");
  return TomlTable(*n->as_table(), file_, key_path(key));
}

std::vector<TomlTable> TomlTable::array_of_tables(const std::string& key) const {
  std::vector<TomlTable> out;
  const toml::node* n = node(key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a) fail(key, "expected an array of tables ([[" + key_path(key) + "]])");
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table* t = (*a)[i].as_table();
    if (!t) fail(key, "expected an array of tables ([[" + key_path(key) + "]])");
    out.emplace_back(*t, file_, key_path(key) + "[" + std::to_string(i) + "]");
  }
  return out;
}

void TomlTable::only(std::initializer_list<const char*> known) const {
  for (const auto& [k, v] : table_) {
    bool ok = false;
    for (const char* name : known) ok = ok || k.str() == name;
    if (!ok) {
      std::string list;
      for (const char* name : known) list += (list.empty() ? "" : ", ") + std::string(name);
      throw Error(located(file_, v.source().begin.line,
                          "unknown key '" + key_path(std::string(k.str())) + "'",
                          "known keys here: " + list));
    }
  }
}

toml::table parse_toml_file(const std::string& path, std::string* text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(located(path, 0, "cannot open config file", "check the path"));
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string content = buffer.str();
  if (text) *text = content;
  try {
    return toml::parse(content, path);
  } catch (const toml::parse_error& e) {
    throw Error(located(path, e.source().begin.line,
                        std::string("TOML syntax error: ") + std::string(e.description())));
  }
}

}  // namespace walk
