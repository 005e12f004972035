#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "bipednav/common/se3.hpp"
#include "bipednav/sim/shape_tessellation.hpp"

namespace bipednav::sim {

// Triangles for rasterisation, unindexed (9 floats per triangle), in chunks of neighbouring
// triangles with their bounds so that a camera skips whole chunks outside its frustum.
// Triangles of a closed convex solid (box, cylinder, sphere) are wound outwards: from outside
// the solid's bounds its back faces are hidden behind its front faces and are skipped.
struct RasterMesh {
  static constexpr std::uint32_t kChunkTriangles = 32;
  struct Chunk {
    Eigen::Vector3f center, half_extent;  // axis-aligned bounds in the mesh frame
    std::uint32_t first = 0, count = 0;   // triangles [first, first + count)
    std::int32_t solid = -1;              // index into solids, -1: not part of a convex solid
  };
  std::vector<float> xyz;  // triangle i: vertices xyz[9 i .. 9 i + 8]
  std::vector<Chunk> chunks;
  std::vector<Eigen::AlignedBox3f> solids;  // bounds of each convex solid, mesh frame

  // Appends the soup's triangles as chunks of consecutive triangles (one shape's triangles
  // are close together, so a chunk never spans two calls). `convex_solid`: the soup is the
  // closed surface of a convex body (its triangles are then re-wound outwards).
  void add(const TriangleSoup& soup, bool convex_solid = false);
  std::size_t size() const { return xyz.size() / 9; }
};

// Everything a depth image can show: what RayCaster casts against, in the same triangles.
struct RasterScene {
  RasterMesh statics;              // world frame
  std::vector<RasterMesh> actors;  // each in its actor's frame
  std::vector<SE3> T_world_actor;  // the actors' poses now
  std::vector<float> plane_z;      // unbounded horizontal planes (intersected analytically)
};

// Z-buffer rasteriser of a pinhole depth image. Pixel (u, v) samples the ray
// (1, slope_u[u], slope_v[v]) of the camera frame (x forward); render() writes its depth
// (distance along x to the first surface, both faces of every triangle count) or +inf.
// Coverage uses homogeneous edge functions (Olano & Greer 1997): no clipping, triangles
// behind or across the camera plane are exact, and edges shared by two triangles of a mesh
// leave no holes (their edge functions are exact negatives). Depth is 1 / (plane's inverse
// depth), affine in the slopes, so it matches a ray cast up to float rounding.
class DepthRasterizer {
 public:
  DepthRasterizer() = default;
  DepthRasterizer(std::vector<float> slope_u, std::vector<float> slope_v, float max_depth_m);

  // Draws the scene into the z-buffer; depth_row() then reads it out row by row.
  void render(const RasterScene& scene, const SE3& T_world_camera);
  // Depth of row v (width floats; +inf where nothing was drawn).
  void depth_row(int v, float* out) const;
  // render() and every row into depth (width * height floats, row-major).
  void render(const RasterScene& scene, const SE3& T_world_camera, float* depth);

 private:
  struct Frustum;
  void clear(const RasterScene& scene, const Eigen::Matrix3f& R_world_camera, float camera_z);
  void draw(const RasterMesh& mesh, const SE3& T_camera_mesh);
  // cull_back: skip the triangle if the camera is behind it (outward winding).
  void draw_triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c, bool cull_back);

  int width_ = 0, height_ = 0, stride_ = 0;  // stride_: width rounded up to 4 lanes
  std::vector<float> su_, sv_;               // su_ padded to stride_
  float max_depth_m_ = 0.0f;
  std::vector<float> inv_depth_;  // z-buffer of 1 / depth (0: nothing), stride_ per row
  std::vector<char> cull_back_;   // scratch: per solid of the mesh being drawn
};

}  // namespace bipednav::sim
