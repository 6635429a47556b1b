#pragma once
// The light a bundle stores on its drawn surfaces, read anywhere on them: found by a ray against its own
// triangles (so a point need not know which triangle of this bundle's dicing holds it) and interpolated from
// the triangle's corners as the display does. Shared by `walk probe` and `walk bench lighting`.
#include <memory>
#include <vector>

#include "compiler/lighting/drawn_triangles.hpp"
#include "compiler/raycast/triangle_bvh.hpp"
#include "model/bundle.hpp"

namespace walk::compiler {

class StoredLight {
 public:
  explicit StoredLight(const model::Bundle& bundle);  // the bundle must outlive this
  [[nodiscard]] const TriangleBvh& bvh() const { return *bvh_; }

  // Light per circuit and channel ([circuit][channel], W/m2) where the ray from `origin` along `dir` first
  // meets a surface's front; false for a miss or a back face (`back`: the inside of a wall).
  bool along_ray(const model::Vec3& origin, const model::Vec3& dir, std::vector<double>& out, bool& back,
                 double* distance = nullptr) const;

  // Every circuit at full at a point on a surface (local metres) facing `normal`: read by a ray from just
  // in front of it; black where no front face is found there.
  [[nodiscard]] model::Rgb on_surface(const model::Vec3& position, const model::Vec3& normal) const;

 private:
  const model::Bundle& bundle_;
  std::vector<TriangleCorners> corners_;  // per BVH triangle id
  std::unique_ptr<TriangleBvh> bvh_;
};

}  // namespace walk::compiler
