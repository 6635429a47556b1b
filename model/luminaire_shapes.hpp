#pragma once
// Luminaire shapes and measured distributions in and out of a bundle (LMSH, DIST, DSTV), so that tools
// reading a compiled bundle (`walk probe`) see each luminaire as the light stage did.
#include <vector>

#include "model/bundle.hpp"
#include "model/model.hpp"

namespace walk::model {

// Fills out.luminaire_shapes (one per luminaire, in order) and the distributions they use, each table once.
void store_luminaire_shapes(const std::vector<Luminaire>& luminaires, BundleContents& out);

// The bundle's luminaires in local coordinates with kind, cone, exponent and distribution; names from the
// string table. A bundle without LMSH gives area panels, as it was written before shapes were stored.
[[nodiscard]] std::vector<Luminaire> load_luminaires(const Bundle& bundle);

}  // namespace walk::model
