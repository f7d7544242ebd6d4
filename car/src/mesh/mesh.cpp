// Mesh files through assimp, and the resolution of every mesh URI of a model or world.
#include "car_sim/mesh.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstdlib>
#include <map>
#include <mutex>
#include <sstream>

namespace car_sim {

namespace {

std::mutex cache_mutex;
std::map<std::string, std::shared_ptr<const TriMesh>>& cache() {
  static std::map<std::string, std::shared_ptr<const TriMesh>> c;
  return c;
}

// Appends a node's meshes (and its children's) with the node transforms applied, in the file's root frame.
void collect(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, TriMesh* out) {
  const aiMatrix4x4 T = parent * node->mTransformation;
  for (unsigned m = 0; m < node->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
    const uint32_t base = static_cast<uint32_t>(out->vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = T * mesh->mVertices[v];
      out->vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines (triangulated input has only triangles)
      for (int k = 0; k < 3; ++k) out->indices.push_back(base + face.mIndices[k]);
    }
    if (!out->colour && mesh->mMaterialIndex < scene->mNumMaterials) {
      aiColor4D c;
      if (scene->mMaterials[mesh->mMaterialIndex]->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
        out->colour = Eigen::Vector4d(c.r, c.g, c.b, c.a);
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) collect(scene, node->mChildren[c], T, out);
}

// Loads one shape's mesh; the error names the element, the URI and where it looked.
void load_shape(Shape* s, const std::string& source, const std::string& element, const std::string& base_dir) {
  if (s->type != ShapeType::Mesh || s->mesh) return;
  if (s->mesh_uri.empty()) throw LoadError(source, 0, element, "<mesh> has no file name");
  const std::string path = resolve_uri(s->mesh_uri, base_dir);
  if (path.empty())
    throw LoadError(source, 0, element,
                    "mesh '" + s->mesh_uri + "' not found (looked in " + mesh_search_description(s->mesh_uri, base_dir) + ")");
  try {
    s->mesh = load_mesh(path);
  } catch (const LoadError& e) {
    throw LoadError(source, 0, element, "mesh '" + s->mesh_uri + "' (" + path + "): " + e.reason());
  }
  s->mesh_path = path;
}

}  // namespace

std::shared_ptr<const TriMesh> load_mesh(const std::string& path) {
  {
    std::lock_guard<std::mutex> lock(cache_mutex);
    const auto it = cache().find(path);
    if (it != cache().end()) return it->second;
  }
  Assimp::Importer importer;
  // COLLADA: keep the file's own axes (Gazebo does not turn Z-up files to Y-up as assimp would by default); its
  // <unit meter> scale is applied. Triangles only, identical vertices merged.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                     aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) {
    const std::string why = importer.GetErrorString();
    throw LoadError(path, 0, "", why.empty() ? "assimp cannot read this file" : "assimp: " + why);
  }
  auto mesh = std::make_shared<TriMesh>();
  collect(scene, scene->mRootNode, aiMatrix4x4(), mesh.get());
  if (mesh->indices.empty()) throw LoadError(path, 0, "", "the file holds no triangles");
  for (const auto& v : mesh->vertices)
    if (!v.allFinite()) throw LoadError(path, 0, "", "a vertex is not finite");
  std::lock_guard<std::mutex> lock(cache_mutex);
  cache()[path] = mesh;
  return mesh;
}

std::string mesh_search_description(const std::string& uri, const std::string& base_dir) {
  auto list = [](const std::vector<std::string>& v) {
    std::string out;
    for (const auto& s : v) out += (out.empty() ? "" : ":") + s;
    return out;
  };
  if (uri.rfind("model://", 0) == 0) return "the model path " + list(model_path());
  if (uri.rfind("package://", 0) == 0) {
    const char* rpp = std::getenv("ROS_PACKAGE_PATH");
    return std::string("ROS_PACKAGE_PATH ") + (rpp && *rpp ? rpp : "(not set)") + " and car's own folder";
  }
  std::string path = uri.rfind("file://", 0) == 0 ? uri.substr(7) : uri;
  if (!path.empty() && path[0] != '/') path = (base_dir.empty() ? std::string(".") : base_dir) + "/" + path;
  return path;
}

namespace {

// A visual's mesh that cannot be found or read: Gazebo's server logs it and simulates the model (physics and
// sensors use collisions), so it is a warning and the visual keeps no triangles (docs/COMPAT-spawn.md).
void load_visual(Shape* s, const std::string& source, const std::string& element, const std::string& base_dir,
                 std::vector<Diagnostic>* out) {
  try {
    load_shape(s, source, element, base_dir);
  } catch (const LoadError& e) {
    out->push_back({Severity::Warning, "visual-mesh-missing", element,
                    e.reason() + "; the visual is not drawn (the model is simulated: physics and sensors use "
                                 "its collisions)",
                    0});
  }
}

}  // namespace

void load_meshes(RobotModel* model, const std::string& base_dir) {
  for (auto& l : model->links) {
    for (size_t i = 0; i < l.collisions.size(); ++i)
      load_shape(&l.collisions[i], model->source, "link[" + l.name + "]/collision[" + std::to_string(i) + "]/mesh",
                 base_dir);
    for (auto& v : l.visuals)
      if (v.shape.type == ShapeType::Mesh && !v.shape.mesh)
        load_visual(&v.shape, model->source, "link[" + l.name + "]/visual[" + v.name + "]/mesh", base_dir,
                    &model->diagnostics);
  }
}

void load_meshes(WorldDescription* world, const std::string& base_dir) {
  for (auto& m : world->models)
    for (auto& l : m.links) {
      const std::string where = "model[" + m.name + "]/link[" + l.name + "]";
      for (auto& c : l.collisions) load_shape(&c.shape, world->source, where + "/collision[" + c.name + "]/mesh", base_dir);
      for (auto& v : l.visuals)
        if (v.shape.type == ShapeType::Mesh && !v.shape.mesh)
          load_visual(&v.shape, world->source, where + "/visual[" + v.name + "]/mesh", base_dir, &world->diagnostics);
    }
}

}  // namespace car_sim
