#include "compiler/textures/polygon_textures.hpp"

#include <algorithm>

namespace walk::compiler {
namespace {

// The texture a polygon shows: its material's, when it also has coordinates to show it with.
std::uint32_t texture_of(const model::Model& model, const model::Polygon& p) {
  if (!p.texture_map || p.material >= model.materials.size()) return model::kNoTexture;
  const std::uint32_t t = model.materials[p.material].texture;
  return t < model.textures.size() ? t : model::kNoTexture;
}

}  // namespace

void add_polygon_textures(const model::Model& model, std::span<const model::Polygon* const> polygons,
                          model::BundleContents& out) {
  if (std::none_of(polygons.begin(), polygons.end(),
                   [&](const model::Polygon* p) { return texture_of(model, *p) != model::kNoTexture; }))
    return;
  std::vector<std::uint32_t> slot(model.textures.size(), model::kNoTextureRecord);
  out.polygon_textures.reserve(polygons.size());
  for (const model::Polygon* p : polygons) {
    model::PolygonTextureRecord rec{};
    rec.texture = model::kNoTextureRecord;
    const std::uint32_t t = texture_of(model, *p);
    if (t != model::kNoTexture) {
      if (slot[t] == model::kNoTextureRecord) {
        const model::Texture& texture = model.textures[t];
        slot[t] = static_cast<std::uint32_t>(out.textures.size());
        model::TextureRecord tr{};
        tr.width = texture.width;
        tr.height = texture.height;
        tr.first_byte = out.texels.size();
        for (int c = 0; c < 3; ++c) tr.mean[c] = static_cast<float>(std::clamp(texture.mean[c], 1e-4, 1.0));
        tr.name = out.add_string(texture.name);
        out.textures.push_back(tr);
        out.texels.insert(out.texels.end(), texture.rgba.begin(), texture.rgba.end());
      }
      rec.texture = slot[t];
      const model::TextureMap& m = *p->texture_map;
      for (int a = 0; a < 3; ++a) {
        rec.u[a] = static_cast<float>(m.u_gradient[a]);
        rec.v[a] = static_cast<float>(m.v_gradient[a]);
      }
      rec.u[3] = static_cast<float>(m.u_offset);
      rec.v[3] = static_cast<float>(m.v_offset);
    }
    out.polygon_textures.push_back(rec);
  }
}

}  // namespace walk::compiler
