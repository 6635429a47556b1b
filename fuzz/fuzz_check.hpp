#pragma once
// What every fuzz target checks besides "no crash, no hang" (which libFuzzer and the sanitizers see): a
// rejected input fails with walk::Error whose message starts with the file name and a line number
// ("input.dxf:12: ..."), or the file name alone for whole-file problems ("input.dxf:0: ..." is not used).
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "model/error.hpp"

namespace walk::fuzz {

inline void check_located(const walk::Error& e, const std::string& file) {
  const std::string m = e.what();
  bool ok = m.rfind(file + ":", 0) == 0;
  if (ok) {
    std::size_t i = file.size() + 1;
    // Either "file:LINE: what" or "file: what".
    if (i < m.size() && std::isdigit(static_cast<unsigned char>(m[i]))) {
      while (i < m.size() && std::isdigit(static_cast<unsigned char>(m[i]))) ++i;
      ok = i < m.size() && m[i] == ':';
    } else {
      ok = i < m.size() && m[i] == ' ';
    }
  }
  if (!ok) {
    std::fprintf(stderr, "rejection without file and line: %s\n", m.c_str());
    std::abort();
  }
}

}  // namespace walk::fuzz
