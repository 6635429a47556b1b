#include "compiler/import/mesh_reader.hpp"

#include <assimp/DefaultIOSystem.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <map>
#include <numbers>
#include <optional>

#include "compiler/import/texture_image.hpp"
#include "compiler/import/uv_fit.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

using model::Vec3;

// Emissive faces of one mesh whose normals agree within this cosine and whose planes are within
// kSamePlaneDistance (metres) form one luminaire: the two triangles of a quad lamp are one lamp.
constexpr double kSameNormalCosine = 0.999;
constexpr double kSamePlaneDistance = 1e-3;

struct Lamp {
  Vec3 normal{0.0};
  double offset = 0.0;
  std::vector<Vec3> points;
  double area = 0.0;
  model::Rgb emission{0.0};
  std::uint32_t circuit = 0;
  std::string name;
};

model::Luminaire lamp_luminaire(const Lamp& lamp, double emission_scale) {
  model::Luminaire l;
  l.name = lamp.name;
  l.normal = lamp.normal;
  // The rectangle: the points' extent along the first edge's direction and across it, in the lamp's plane.
  Vec3 u = lamp.points[1] - lamp.points[0];
  u = glm::normalize(u - l.normal * glm::dot(u, l.normal));
  const Vec3 v = glm::cross(l.normal, u);
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  for (const Vec3& p : lamp.points) {
    u0 = std::min(u0, glm::dot(p, u));
    u1 = std::max(u1, glm::dot(p, u));
    v0 = std::min(v0, glm::dot(p, v));
    v1 = std::max(v1, glm::dot(p, v));
  }
  l.u_axis = u;
  l.width = u1 - u0;
  l.height = v1 - v0;
  l.position = u * (0.5 * (u0 + u1)) + v * (0.5 * (v0 + v1)) + l.normal * lamp.offset;
  l.power = lamp.emission * (std::numbers::pi * lamp.area * emission_scale);
  l.circuit = lamp.circuit;
  return l;
}

// Every file assimp opens besides the model, and those it could not: an OBJ's `mtllib` that is not beside it
// makes assimp go on with a default material and say nothing a user sees. Watching assimp's own opens finds
// them without reading the model a second time.
class OpenRecorder final : public Assimp::DefaultIOSystem {
 public:
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    Assimp::IOStream* stream = Assimp::DefaultIOSystem::Open(file, mode);
    (stream ? opened : missing).emplace_back(file);
    return stream;
  }
  std::vector<std::string> opened, missing;
};

// Warns about each material library the model names that assimp could not open. When the named one is
// missing, assimp tries <model>.mtl beside the model; that guess is reported as where the materials came
// from, or left out when it is missing too (the model never named it).
void warn_missing_material_libraries(const std::string& path, const OpenRecorder& io, MeshStats& stats) {
  const std::string guess = std::filesystem::path(path).replace_extension(".mtl").filename().string();
  auto is_guess = [&](const std::string& f) { return std::filesystem::path(f).filename().string() == guess; };
  const bool guess_opened = std::any_of(io.opened.begin(), io.opened.end(), is_guess);
  const bool named_elsewhere =
      std::any_of(io.missing.begin(), io.missing.end(), [&](const std::string& f) { return !is_guess(f); });
  std::vector<std::string> reported;
  for (const auto& file : io.missing) {
    if ((is_guess(file) && named_elsewhere) ||
        std::find(reported.begin(), reported.end(), file) != reported.end())
      continue;
    reported.push_back(file);
    ++stats.material_libraries_missing;
    spdlog::warn("{}: the file '{}' it names cannot be opened; {} (put it beside the model)", path, file,
                 guess_opened ? "its materials come from " + guess + " instead"
                              : std::string("its materials get the default grey"));
  }
}

// Where a texture named `name` is: beside the model (as named, then by its file name alone, since models
// often carry the author's absolute or Windows paths), then in each configured folder the same two ways.
std::optional<std::filesystem::path> find_texture(const std::string& name, const std::string& model_path,
                                                  const std::vector<std::string>& folders) {
  std::string slashed = name;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  const std::filesystem::path named(slashed);
  std::vector<std::filesystem::path> places{std::filesystem::path(model_path).parent_path()};
  for (const auto& f : folders) places.emplace_back(f);
  std::error_code ec;
  for (const auto& place : places)
    for (const auto& candidate : {place / named, place / named.filename()})
      if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
  return std::nullopt;
}

// The material's albedo map (a diffuse or glTF base colour texture) as an index into model.textures, loaded
// once per file; kNoTexture when it names none, or a missing or unreadable one (warned about by name: the
// material's colour is used then).
std::uint32_t albedo_map(const aiScene& scene, const aiMaterial& material, const std::string& path,
                         const std::vector<std::string>& folders, model::Model& model, MeshStats& stats,
                         std::map<std::string, std::uint32_t>& loaded) {
  aiString name;
  if (material.GetTexture(aiTextureType_DIFFUSE, 0, &name) != AI_SUCCESS &&
      material.GetTexture(aiTextureType_BASE_COLOR, 0, &name) != AI_SUCCESS)
    return model::kNoTexture;
  if (name.length == 0) return model::kNoTexture;
  ++stats.textures_named;
  const model::Material& m = model.materials.back();
  const std::string named = name.C_Str();
  const aiTexture* embedded = scene.GetEmbeddedTexture(name.C_Str());
  std::string key;
  std::optional<std::filesystem::path> file;
  if (embedded) {
    key = "embedded " + named;
  } else {
    file = find_texture(named, path, folders);
    if (!file) {
      ++stats.textures_missing;
      spdlog::warn(
          "{}: material '{}' names the texture '{}', found neither beside the model nor in the scene's "
          "texture folders ([model] textures); its colour ({:.3f} {:.3f} {:.3f}) is used",
          path, m.name, named, m.reflectance.r, m.reflectance.g, m.reflectance.b);
      return model::kNoTexture;
    }
    key = file->string();
  }
  if (const auto it = loaded.find(key); it != loaded.end()) return it->second;
  model::Texture texture;
  try {
    if (!embedded) {
      texture = load_texture(file->string());
    } else if (embedded->mHeight == 0) {  // a whole compressed file (PNG, JPEG) of mWidth bytes
      texture = decode_texture({reinterpret_cast<const std::uint8_t*>(embedded->pcData), embedded->mWidth},
                               path + ": embedded texture " + named);
    } else {  // raw BGRA texels
      std::vector<std::uint8_t> rgba;
      rgba.reserve(std::size_t(embedded->mWidth) * embedded->mHeight * 4);
      for (std::size_t i = 0; i < std::size_t(embedded->mWidth) * embedded->mHeight; ++i) {
        const aiTexel& t = embedded->pcData[i];
        rgba.insert(rgba.end(), {t.r, t.g, t.b, t.a});
      }
      texture = texture_from_rgba(std::move(rgba), embedded->mWidth, embedded->mHeight);
    }
  } catch (const Error& e) {
    ++stats.textures_missing;
    spdlog::warn("{}: material '{}': {}; its colour is used", path, m.name, e.what());
    loaded[key] = model::kNoTexture;
    return model::kNoTexture;
  }
  texture.name = named;
  ++stats.textures_loaded;
  const auto index = static_cast<std::uint32_t>(model.textures.size());
  model.textures.push_back(std::move(texture));
  loaded[key] = index;
  return index;
}

}  // namespace

model::Model read_mesh(const std::string& path, const MeshOptions& options, MeshStats* stats_out) {
  if (!(options.unit_scale > 0.0) || !std::isfinite(options.unit_scale))
    throw Error(located(path, 0, "unit scale is not a positive number", "set `units` or `scale` in [model]"));
  Assimp::Importer importer;
  auto* io = new OpenRecorder;  // the importer owns it (SetIOHandler takes ownership)
  importer.SetIOHandler(io);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure);
  if (!scene || !scene->mRootNode)
    throw Error(located(path, 0, std::string("assimp cannot read the file: ") + importer.GetErrorString(),
                        "check the format and that the file is complete (OBJ also needs its .mtl)"));
  MeshStats stats;
  warn_missing_material_libraries(path, *io, stats);
  model::Model model;
  model.materials.push_back({"default", {0.5, 0.5, 0.5}});
  std::vector<std::uint32_t> material_index(scene->mNumMaterials, 0);
  std::vector<model::Rgb> emission(scene->mNumMaterials, model::Rgb(0.0));
  std::map<std::string, std::uint32_t> textures;  // file (or embedded name) -> model.textures index
  for (unsigned i = 0; i < scene->mNumMaterials; ++i) {
    const aiMaterial* m = scene->mMaterials[i];
    aiString name;
    m->Get(AI_MATKEY_NAME, name);
    aiColor3D kd(0.5f, 0.5f, 0.5f), ke(0.f, 0.f, 0.f);
    m->Get(AI_MATKEY_COLOR_DIFFUSE, kd);
    m->Get(AI_MATKEY_COLOR_EMISSIVE, ke);
    const model::Rgb rho(std::clamp<double>(kd.r, 0.0, 1.0), std::clamp<double>(kd.g, 0.0, 1.0),
                         std::clamp<double>(kd.b, 0.0, 1.0));
    material_index[i] = static_cast<std::uint32_t>(model.materials.size());
    model.materials.push_back({name.length ? name.C_Str() : "material" + std::to_string(i), rho});
    emission[i] = {std::max(0.f, ke.r), std::max(0.f, ke.g), std::max(0.f, ke.b)};
    ++stats.materials;
    const std::uint32_t texture = albedo_map(*scene, *m, path, options.texture_dirs, model, stats, textures);
    if (texture != model::kNoTexture) {
      model.materials.back().texture = texture;
      // Rounded to float like every colour assimp reads: a material given the map's mean as its colour
      // solves to exactly the same light.
      model.materials.back().reflectance = glm::dvec3(glm::vec3(rho * model.textures[texture].mean));
    }
  }
  // Meshes are placed by walking the node tree (assimp's PreTransformVertices would do it, but it joins
  // every mesh of one material into one and so loses the groups, which name the rooms).
  struct Placement {
    const aiNode* node;
    aiMatrix4x4 transform;
  };
  std::vector<Placement> placements;
  std::vector<Placement> stack{{scene->mRootNode, scene->mRootNode->mTransformation}};
  while (!stack.empty()) {
    const Placement at = stack.back();
    stack.pop_back();
    placements.push_back(at);
    for (unsigned c = at.node->mNumChildren; c-- > 0;)  // reversed: the file's order comes off the stack
      stack.push_back({at.node->mChildren[c], at.transform * at.node->mChildren[c]->mTransformation});
  }
  std::map<unsigned, std::uint32_t> circuits;  // emissive material -> circuit
  std::vector<Lamp> lamps;
  for (const Placement& at : placements)
    for (unsigned nm = 0; nm < at.node->mNumMeshes; ++nm) {
      const unsigned mi = at.node->mMeshes[nm];
      const aiMesh* mesh = scene->mMeshes[mi];
      const aiMatrix4x4& m = at.transform;
      const bool mirrored = m.Determinant() < 0;  // a mirroring transform turns the faces inside out
      const auto convert = [&](const aiVector3D& local) {
        const aiVector3D a = m * local;
        const Vec3 p(a.x, a.y, a.z);
        return (options.y_up ? Vec3(p.x, -p.z, p.y) : p) * options.unit_scale;
      };
      ++stats.meshes;
      stats.vertices += mesh->mNumVertices;
      // The group: the node (an OBJ object or group, a glTF node) that holds the mesh; the mesh's own name
      // where the node has none (assimp names OBJ meshes after their material when one group has several).
      std::string group = at.node != scene->mRootNode && at.node->mName.length ? at.node->mName.C_Str() : "";
      if (group.empty()) group = mesh->mName.length ? mesh->mName.C_Str() : "mesh" + std::to_string(mi);
      const std::uint32_t g = model.group_index(group);
      const unsigned mat = mesh->mMaterialIndex;
      const bool emissive =
          mat < emission.size() && std::max({emission[mat].r, emission[mat].g, emission[mat].b}) > 0;
      const std::size_t first_lamp = lamps.size();
      for (unsigned fi = 0; fi < mesh->mNumFaces; ++fi) {
        const aiFace& f = mesh->mFaces[fi];
        if (f.mNumIndices < 3) {
          ++stats.skipped_primitives;
          continue;
        }
        model::Polygon p;
        for (unsigned k = 0; k < f.mNumIndices; ++k)
          p.vertices.push_back(convert(mesh->mVertices[f.mIndices[k]]));
        p.group = g;
        p.material = mat < material_index.size() ? material_index[mat] : 0;
        if (model.materials[p.material].texture != model::kNoTexture && mesh->HasTextureCoords(0)) {
          std::vector<glm::dvec2> uvs;
          for (unsigned k = 0; k < f.mNumIndices; ++k) {
            const aiVector3D& t = mesh->mTextureCoords[0][f.mIndices[k]];
            uvs.emplace_back(t.x, t.y);
          }
          p.texture_map = fit_texture_map(p.vertices, uvs);
          stats.faces_textured += p.texture_map ? 1 : 0;
        }
        if (mirrored) std::reverse(p.vertices.begin(), p.vertices.end());
        p.name = model.materials[p.material].name;
        p.source_line = fi + 1;  // face number within its mesh: assimp keeps no line numbers
        if (emissive) {
          p.role = model::Role::Luminaire;
          ++stats.emissive_faces;
          const Vec3 n2 = model::area_vector(p.vertices);
          const double twice = glm::length(n2);
          if (twice > 0.0) {
            const Vec3 n = n2 / twice;
            const double offset = glm::dot(n, p.vertices[0]);
            Lamp* lamp = nullptr;
            for (std::size_t k = first_lamp; k < lamps.size(); ++k)
              if (glm::dot(lamps[k].normal, n) > kSameNormalCosine &&
                  std::abs(lamps[k].offset - offset) < kSamePlaneDistance)
                lamp = &lamps[k];
            if (!lamp) {
              auto [it, added] = circuits.emplace(mat, static_cast<std::uint32_t>(model.circuits.size()));
              if (added) model.circuits.push_back({"emissive " + model.materials[p.material].name, 1.0});
              lamps.push_back(
                  {n,
                   offset,
                   {},
                   0.0,
                   emission[mat],
                   it->second,
                   group + "/" + model.materials[p.material].name + "#" + std::to_string(lamps.size())});
              lamp = &lamps.back();
            }
            lamp->points.insert(lamp->points.end(), p.vertices.begin(), p.vertices.end());
            lamp->area += 0.5 * twice;
          }
        }
        if (p.vertices.size() == 3) ++stats.triangles;
        model.polygons.push_back(std::move(p));
        ++stats.faces;
      }
    }
  for (const Lamp& lamp : lamps) model.luminaires.push_back(lamp_luminaire(lamp, options.emission_scale));
  stats.luminaires = lamps.size();
  if (model.polygons.empty())
    throw Error(
        located(path, 0, "the file has no faces (only points or lines)", "export surfaces, not curves"));
  if (stats_out) *stats_out = stats;
  return model;
}

}  // namespace walk::compiler
