#include "compiler/partition/visibility_config.hpp"

namespace walk::compiler {

const char* pvs_method_name(PvsMethod m) {
  switch (m) {
    case PvsMethod::Sampled:
      return "sampled";
    case PvsMethod::Conservative:
      return "conservative";
    case PvsMethod::Combined:
      return "combined";
  }
  return "?";
}

bool parse_pvs_method(const std::string& text, PvsMethod& out) {
  for (PvsMethod m : {PvsMethod::Sampled, PvsMethod::Conservative, PvsMethod::Combined})
    if (text == pvs_method_name(m)) {
      out = m;
      return true;
    }
  return false;
}

}  // namespace walk::compiler
