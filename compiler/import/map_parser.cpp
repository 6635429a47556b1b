#include "compiler/import/map_parser.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

#include "model/error.hpp"

namespace walk::compiler {
namespace {

class Lexer {
 public:
  Lexer(const std::string& text, const std::string& file) : s_(text), file_(file) {}

  // Next token: a single brace/paren/bracket, a quoted string (without quotes, `quoted` set) or a word.
  bool next(std::string& out, bool& quoted) {
    skip();
    if (i_ >= s_.size()) return false;
    token_line_ = line_;
    quoted = false;
    const char c = s_[i_];
    if (c == '{' || c == '}' || c == '(' || c == ')' || c == '[' || c == ']') {
      out.assign(1, c);
      ++i_;
      return true;
    }
    if (c == '"') {
      const std::size_t start = ++i_;
      while (i_ < s_.size() && s_[i_] != '"') {
        if (s_[i_] == '\n') fail("a quoted string runs past the end of its line", "close the string with \"");
        ++i_;
      }
      if (i_ >= s_.size()) fail("the file ends inside a quoted string", "close the string with \"");
      out = s_.substr(start, i_ - start);
      ++i_;
      quoted = true;
      return true;
    }
    const std::size_t start = i_;
    while (i_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[i_])) && s_[i_] != '"' &&
           !(s_[i_] == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '/'))
      ++i_;
    out = s_.substr(start, i_ - start);
    return true;
  }

  std::string expect_any(const char* what) {
    std::string t;
    bool quoted = false;
    if (!next(t, quoted))
      fail(std::string("the file ends where ") + what + " was expected", "the file is truncated");
    return t;
  }

  void expect(const char* token) {
    const std::string t = expect_any(token);
    if (t != token)
      fail("expected \"" + std::string(token) + "\", found \"" + t + "\"", "fix the brush syntax");
  }

  double number() {
    const std::string t = expect_any("a number");
    double v = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
      fail("expected a finite number, found \"" + t + "\"", "fix the plane or texture values");
    return v;
  }

  [[noreturn]] void fail(const std::string& what, const std::string& hint) const {
    throw Error(located(file_, token_line_, what, hint));
  }
  [[nodiscard]] std::size_t line() const { return token_line_; }

 private:
  void skip() {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\n') {
        ++line_;
        ++i_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++i_;
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '/') {
        while (i_ < s_.size() && s_[i_] != '\n') ++i_;
      } else {
        break;
      }
    }
  }

  const std::string& s_;
  const std::string& file_;
  std::size_t i_ = 0;
  std::size_t line_ = 1;
  std::size_t token_line_ = 1;
};

model::Vec3 point(Lexer& lex) {
  lex.expect("(");
  model::Vec3 p;
  p.x = lex.number();
  p.y = lex.number();
  p.z = lex.number();
  lex.expect(")");
  return p;
}

MapBrush brush(Lexer& lex, bool& valve220) {
  MapBrush b;
  b.line = lex.line();
  for (;;) {
    std::string t;
    bool quoted = false;
    if (!lex.next(t, quoted))
      lex.fail("the file ends inside a brush", "the file is truncated: close the brush with }");
    if (t == "}") break;
    if (t != "(")
      lex.fail("expected \"(\" starting a brush plane or \"}\", found \"" + t + "\"", "fix the brush syntax");
    MapPlane plane;
    plane.line = lex.line();
    // The first "(" is consumed: read the rest of the first point by hand.
    plane.points[0] = {lex.number(), lex.number(), lex.number()};
    lex.expect(")");
    plane.points[1] = point(lex);
    plane.points[2] = point(lex);
    plane.texture = lex.expect_any("a texture name");
    if (plane.texture == "(" || plane.texture == "}" || plane.texture == "{")
      lex.fail("expected a texture name, found \"" + plane.texture + "\"", "fix the brush plane");
    // Texture alignment: "xoff yoff rot xscale yscale" or Valve 220 "[ u off ] [ v off ] rot xs ys". Some
    // writers add three more numbers (Quake 2/3 flags); all of them are skipped up to the next plane.
    std::string peek = lex.expect_any("texture alignment");
    if (peek == "[") {
      valve220 = true;
      for (int axis = 0; axis < 2; ++axis) {
        if (axis == 1) lex.expect("[");
        for (int k = 0; k < 4; ++k) (void)lex.number();
        lex.expect("]");
      }
      for (int k = 0; k < 3; ++k) (void)lex.number();
    } else {
      for (int k = 0; k < 4; ++k) (void)lex.number();
    }
    if (b.planes.size() >= kMaxBrushPlanes)
      lex.fail("a brush with more than " + std::to_string(kMaxBrushPlanes) + " planes", "split the brush");
    b.planes.push_back(std::move(plane));
  }
  return b;
}

}  // namespace

MapFile parse_map(const std::string& text, const std::string& file) {
  Lexer lex(text, file);
  MapFile map;
  std::string t;
  bool quoted = false;
  while (lex.next(t, quoted)) {
    if (t != "{" || quoted)
      lex.fail("expected \"{\" starting an entity, found \"" + t + "\"", "is this a Quake .map file?");
    MapEntity entity;
    entity.line = lex.line();
    for (;;) {
      if (!lex.next(t, quoted))
        lex.fail("the file ends inside an entity", "the file is truncated: close it with }");
      if (t == "}" && !quoted) break;
      if (t == "{" && !quoted) {
        entity.brushes.push_back(brush(lex, map.valve220));
        continue;
      }
      if (!quoted) lex.fail("expected a \"key\", a brush or \"}\", found \"" + t + "\"", "fix the entity");
      std::string value;
      bool value_quoted = false;
      if (!lex.next(value, value_quoted) || !value_quoted)
        lex.fail("key \"" + t + "\" has no quoted value", "write entity fields as \"key\" \"value\"");
      entity.keys[t] = value;
    }
    map.entities.push_back(std::move(entity));
  }
  if (map.entities.empty())
    throw Error(located(file, 0, "the .map file has no entities", "is this a Quake .map file?"));
  return map;
}

}  // namespace walk::compiler
