#include "bipednav/sim/mesh_loader.hpp"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <system_error>

#include "bipednav/common/error.hpp"

namespace bipednav::sim {
namespace {

// Appends the triangles of `node` and its children, with the accumulated node transform.
void append_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& T_parent, const Eigen::Vector3d& scale,
                 Mesh& out) {
  const aiMatrix4x4 T = T_parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = T * mesh.mVertices[v];
      out.vertices.emplace_back(static_cast<float>(p.x * scale.x()), static_cast<float>(p.y * scale.y()),
                                static_cast<float>(p.z * scale.z()));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left over after triangulation
      out.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                                 base + static_cast<int>(face.mIndices[2]));
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) append_node(scene, *node.mChildren[c], T, scale, out);
}

}  // namespace

Mesh load_mesh(const std::filesystem::path& file, const Eigen::Vector3d& scale) {
  if (std::error_code ec; !std::filesystem::is_regular_file(file, ec))
    throw FileError(file.string(), "", "mesh file not found");
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene =
      importer.ReadFile(file.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr)
    throw FileError(file.string(), "", std::string("cannot read mesh: ") + importer.GetErrorString());
  Mesh out;
  append_node(*scene, *scene->mRootNode, aiMatrix4x4(), scale, out);
  if (out.triangles.empty()) throw FileError(file.string(), "", "mesh has no triangles");
  return out;
}

}  // namespace bipednav::sim
