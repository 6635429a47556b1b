#include "model/luminaire_shapes.hpp"

#include <map>

namespace walk::model {

void store_luminaire_shapes(const std::vector<Luminaire>& luminaires, BundleContents& out) {
  std::map<const IntensityDistribution*, std::uint32_t> stored;
  out.luminaire_shapes.clear();
  for (const auto& l : luminaires) {
    LuminaireShapeRecord r{static_cast<std::uint32_t>(l.kind), static_cast<float>(l.cone),
                           static_cast<float>(l.exponent), kNoDistribution};
    if (l.kind == LuminaireKind::Photometric && l.distribution) {
      const auto [it, added] =
          stored.emplace(l.distribution.get(), static_cast<std::uint32_t>(out.distributions.size()));
      if (added) {
        const auto& d = *l.distribution;
        out.distributions.push_back({static_cast<std::uint32_t>(out.distribution_values.size()),
                                     static_cast<std::uint32_t>(d.gamma_deg.size()),
                                     static_cast<std::uint32_t>(d.c_deg.size()),
                                     static_cast<float>(d.lumens)});
        for (const auto* v : {&d.gamma_deg, &d.c_deg, &d.candela})
          for (double x : *v) out.distribution_values.push_back(static_cast<float>(x));
      }
      r.distribution = it->second;
    }
    out.luminaire_shapes.push_back(r);
  }
}

std::vector<Luminaire> load_luminaires(const Bundle& bundle) {
  std::vector<std::shared_ptr<const IntensityDistribution>> tables;
  const auto values = bundle.distribution_values();
  for (const auto& r : bundle.distributions()) {
    auto d = std::make_shared<IntensityDistribution>();
    d->source = bundle.path();
    const float* v = values.data() + r.first;
    d->gamma_deg.assign(v, v + r.gamma_count);
    d->c_deg.assign(v + r.gamma_count, v + r.gamma_count + r.c_count);
    v += r.gamma_count + r.c_count;
    d->candela.assign(v, v + std::size_t(r.gamma_count) * r.c_count);
    d->lumens = r.lumens;
    tables.push_back(std::move(d));
  }
  std::vector<Luminaire> out;
  const auto shapes = bundle.luminaire_shapes();
  for (std::size_t i = 0; i < bundle.luminaires().size(); ++i) {
    const auto& r = bundle.luminaires()[i];
    Luminaire l;
    l.name = std::string(bundle.string(r.name));
    l.position = {r.position[0], r.position[1], r.position[2]};
    l.normal = {r.normal[0], r.normal[1], r.normal[2]};
    l.u_axis = {r.u_axis[0], r.u_axis[1], r.u_axis[2]};
    l.width = r.width;
    l.height = r.height;
    l.power = {r.power[0], r.power[1], r.power[2]};
    l.circuit = r.circuit;
    if (!shapes.empty()) {
      l.kind = static_cast<LuminaireKind>(shapes[i].kind);
      l.cone = shapes[i].cone;
      l.exponent = shapes[i].exponent;
      if (shapes[i].distribution != kNoDistribution) l.distribution = tables[shapes[i].distribution];
    }
    out.push_back(std::move(l));
  }
  return out;
}

}  // namespace walk::model
