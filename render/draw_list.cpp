#include "render/draw_list.hpp"

#include "model/model.hpp"

namespace walk::render {

bool is_drawn(std::uint32_t role) {
  return role != std::uint32_t(model::Role::Opening) && role != std::uint32_t(model::Role::Ignored);
}

}  // namespace walk::render
