#include "compiler/import/dxf_document.hpp"

#include <cstdlib>

#include "model/error.hpp"

namespace walk::compiler {
namespace {

// Entities that belong to the entity before them rather than standing alone.
bool is_child(const std::string& type) {
  return type == "VERTEX" || type == "ATTRIB" || type == "SEQEND";
}

bool owns_children(const std::string& type) {
  return type == "POLYLINE" || type == "INSERT";
}

}  // namespace

const DxfPair* DxfEntity::find(int code) const {
  for (const auto& p : pairs)
    if (p.code == code) return &p;
  return nullptr;
}

std::string DxfEntity::text(int code, const std::string& fallback) const {
  const DxfPair* p = find(code);
  return p ? p->value : fallback;
}

DxfDocument read_dxf_document(std::istream& in, const std::string& file) {
  DxfTokenizer tokens(in, file);
  DxfDocument doc;
  std::string section;
  bool expect_section_name = false;
  bool saw_eof = false;
  std::string comment;
  std::string header_variable;
  // Where the entity being read goes: the list it was appended to and whether it accepts children.
  std::vector<DxfEntity>* list = nullptr;
  DxfEntity* current = nullptr;
  DxfBlock* block = nullptr;
  bool in_block_header = false;
  std::size_t last_entity_line = 0;
  std::string last_entity_type;

  DxfPair pair;
  while (tokens.next(pair)) {
    if (pair.code == 999) {
      comment = pair.value;
      continue;
    }
    if (pair.code == 0) {
      last_entity_line = pair.code_line;
      last_entity_type = pair.value;
      in_block_header = false;
      if (pair.value == "EOF") {
        saw_eof = true;
        break;
      }
      if (pair.value == "SECTION") {
        expect_section_name = true;
        current = nullptr;
        continue;
      }
      if (pair.value == "ENDSEC") {
        section.clear();
        current = nullptr;
        block = nullptr;
        continue;
      }
      if (section == "BLOCKS") {
        if (pair.value == "BLOCK") {
          block = nullptr;
          in_block_header = true;
          DxfBlock b;
          b.line = pair.code_line;
          // The name comes with code 2 below; park it under a placeholder until then.
          doc.blocks["\x01pending"] = std::move(b);
          block = &doc.blocks["\x01pending"];
          current = nullptr;
          continue;
        }
        if (pair.value == "ENDBLK") {
          block = nullptr;
          current = nullptr;
          continue;
        }
        list = block ? &block->entities : nullptr;
      } else if (section == "ENTITIES" || section.empty()) {
        // Entities outside any section are accepted: hand-made files often have only ENTITIES content.
        list = &doc.entities;
      } else if (section == "TABLES") {
        current = nullptr;
        if (pair.value == "LAYER") {
          doc.entities.emplace_back();  // parsed below into a temporary, then moved into the layer table
          doc.entities.back().type = "\x01LAYER";
          doc.entities.back().line = pair.code_line;
          current = &doc.entities.back();
        }
        continue;
      } else {
        current = nullptr;
        continue;
      }
      if (!list) {
        current = nullptr;
        continue;
      }
      if (is_child(pair.value) && !list->empty() && owns_children(list->back().type) && current != nullptr) {
        DxfEntity& owner = list->back();
        if (pair.value == "SEQEND") {
          current = nullptr;
          continue;
        }
        owner.children.push_back({pair.value, pair.code_line, comment, {}, {}});
        current = &owner.children.back();
        continue;
      }
      list->push_back({pair.value, pair.code_line, comment, {}, {}});
      current = &list->back();
      continue;
    }
    if (expect_section_name) {
      if (pair.code == 2) section = pair.value;
      expect_section_name = false;
      continue;
    }
    if (section == "HEADER") {
      if (pair.code == 9) {
        header_variable = pair.value;
      } else if (header_variable == "$INSUNITS" && pair.code == 70) {
        doc.insunits = tokens.integer(pair);
        doc.insunits_line = pair.value_line;
      }
      continue;
    }
    if (in_block_header && block) {
      if (pair.code == 2) {
        DxfBlock b = std::move(*block);
        doc.blocks.erase("\x01pending");
        b.name = pair.value;
        auto [it, inserted] = doc.blocks.insert_or_assign(pair.value, std::move(b));
        block = &it->second;
      } else {
        block->header.push_back(pair);
      }
      continue;
    }
    if (current) current->pairs.push_back(pair);
  }
  doc.blocks.erase("\x01pending");
  doc.lines = tokens.lines_read();
  if (doc.lines == 0) throw Error(located(file, 0, "the DXF file is empty", "copy or export the file again"));
  if (!saw_eof) {
    const std::string inside =
        last_entity_type.empty()
            ? std::string()
            : " inside the " + last_entity_type + " entity at line " + std::to_string(last_entity_line);
    throw Error(located(file, doc.lines,
                        "the DXF file ends without its \"0 EOF\" marker" + inside + ": it is truncated",
                        "copy or export the file again"));
  }
  // Move layer table entries out of the entity list.
  std::vector<DxfEntity> kept;
  kept.reserve(doc.entities.size());
  for (auto& e : doc.entities) {
    if (e.type != "\x01LAYER") {
      kept.push_back(std::move(e));
      continue;
    }
    DxfLayer layer;
    for (const auto& p : e.pairs) {
      if (p.code == 62) layer.color = std::abs(tokens.integer(p));
      if (p.code == 420) layer.true_color = tokens.integer(p) & 0xffffff;
      if (p.code == 70) layer.frozen = (tokens.integer(p) & 1) != 0;
    }
    doc.layers[e.text(2, "0")] = layer;
  }
  doc.entities = std::move(kept);
  return doc;
}

}  // namespace walk::compiler
