#pragma once
// A DXF file read into its parts: header variables the importer uses, the layer table, block definitions and
// the ENTITIES section, each entity kept as its raw (group code, value) pairs with line numbers. POLYLINE and
// INSERT entities own the VERTEX/ATTRIB entities that follow them up to SEQEND. Knows nothing of geometry.
#include <cstddef>
#include <istream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "compiler/import/dxf_tokenizer.hpp"

namespace walk::compiler {

struct DxfEntity {
  std::string type;
  std::size_t line = 0;  // line of its `0` group code
  std::string comment;   // the last 999 comment before it (EnergyPlus surface names)
  std::vector<DxfPair> pairs;
  std::vector<DxfEntity> children;  // VERTEX of a POLYLINE, ATTRIB of an INSERT

  [[nodiscard]] const DxfPair* find(int code) const;
  [[nodiscard]] std::string text(int code, const std::string& fallback) const;
};

struct DxfLayer {
  int color = 7;                  // ACI; negative in the file means "off" (we keep the absolute value)
  std::optional<int> true_color;  // 0xRRGGBB (group code 420)
  bool frozen = false;
};

struct DxfBlock {
  std::string name;
  std::size_t line = 0;
  std::vector<DxfPair> header;  // the BLOCK entity's own pairs (base point 10/20/30)
  std::vector<DxfEntity> entities;
};

struct DxfDocument {
  std::optional<int> insunits;  // $INSUNITS, when the HEADER has it
  std::size_t insunits_line = 0;
  std::map<std::string, DxfLayer> layers;
  std::map<std::string, DxfBlock> blocks;
  std::vector<DxfEntity> entities;
  std::size_t lines = 0;
};

// Throws walk::Error naming `file` and the line for a malformed, truncated or empty file.
[[nodiscard]] DxfDocument read_dxf_document(std::istream& in, const std::string& file);

}  // namespace walk::compiler
