#include "bipednav/sim/sdf_world.hpp"

#include <algorithm>
#include <exception>
#include <new>
#include <sdf/sdf.hh>
#include <string>
#include <system_error>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/mesh_loader.hpp"

namespace bipednav::sim {
namespace fs = std::filesystem;
namespace {

SE3 to_se3(const ignition::math::Pose3d& p) {
  SE3 T = SE3::Identity();
  T.linear() = Eigen::Quaterniond(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z()).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.Pos().X(), p.Pos().Y(), p.Pos().Z());
  return T;
}

// Pose of an SDF element in its default parent frame (honours `relative_to` through sdformat's
// pose graph; falls back to the raw pose when the graph cannot resolve it).
template <typename T>
SE3 pose_in_parent(const T& elem) {
  if (elem.PoseRelativeTo().empty()) return to_se3(elem.RawPose());  // the common case, and fast
  ignition::math::Pose3d p;
  if (!elem.SemanticPose().Resolve(p).empty()) p = elem.RawPose();
  return to_se3(p);
}

struct Context {
  fs::path file;
  std::vector<fs::path> model_paths;
};

Shape convert_shape(const sdf::Geometry& g, const Context& ctx, const std::string& name) {
  switch (g.Type()) {
    case sdf::GeometryType::BOX: {
      const auto s = g.BoxShape()->Size();
      return Box{Eigen::Vector3d(s.X(), s.Y(), s.Z())};
    }
    case sdf::GeometryType::CYLINDER:
      return Cylinder{g.CylinderShape()->Radius(), g.CylinderShape()->Length()};
    case sdf::GeometryType::SPHERE:
      return Sphere{g.SphereShape()->Radius()};
    case sdf::GeometryType::CAPSULE:
      return Cylinder{g.CapsuleShape()->Radius(), g.CapsuleShape()->Length() + 2 * g.CapsuleShape()->Radius()};
    case sdf::GeometryType::ELLIPSOID: {
      const auto r = g.EllipsoidShape()->Radii();
      return Box{Eigen::Vector3d(2 * r.X(), 2 * r.Y(), 2 * r.Z())};
    }
    case sdf::GeometryType::PLANE: {
      const auto n = g.PlaneShape()->Normal();
      const auto s = g.PlaneShape()->Size();
      return Plane{Eigen::Vector3d(n.X(), n.Y(), n.Z()).normalized(), Eigen::Vector2d(s.X(), s.Y())};
    }
    case sdf::GeometryType::MESH: {
      const sdf::Mesh& m = *g.MeshShape();
      const fs::path base = m.FilePath().empty() ? ctx.file.parent_path() : fs::path(m.FilePath()).parent_path();
      const fs::path mesh_file = resolve_model_uri(m.Uri(), base, ctx.model_paths);
      if (mesh_file.empty())
        throw FileError(ctx.file.string(), name, "cannot resolve mesh uri '" + m.Uri() + "' through the model paths");
      const auto s = m.Scale();
      return load_mesh(mesh_file, Eigen::Vector3d(s.X(), s.Y(), s.Z()));
    }
    default:
      throw FileError(ctx.file.string(), name, "unsupported geometry (heightmap or empty)");
  }
}

// Appends the geometry of one link: collisions, or visuals when it has no collision.
void append_link(const sdf::Link& link, const SE3& T_parent_link, const std::string& prefix, const Context& ctx,
                 std::vector<Geometry>& out) {
  const bool use_collisions = link.CollisionCount() > 0;
  const uint64_t n = use_collisions ? link.CollisionCount() : link.VisualCount();
  for (uint64_t i = 0; i < n; ++i) {
    const sdf::Geometry* g = nullptr;
    std::string name;
    SE3 T_link_geom;
    if (use_collisions) {
      const sdf::Collision& c = *link.CollisionByIndex(i);
      g = c.Geom(), name = c.Name(), T_link_geom = pose_in_parent(c);
    } else {
      const sdf::Visual& v = *link.VisualByIndex(i);
      g = v.Geom(), name = v.Name(), T_link_geom = pose_in_parent(v);
    }
    if (g == nullptr || g->Type() == sdf::GeometryType::EMPTY) continue;
    const std::string full = prefix + link.Name() + "::" + name;
    out.push_back(Geometry{full, T_parent_link * T_link_geom, convert_shape(*g, ctx, full)});
  }
}

void append_model(const sdf::Model& model, const SE3& T_world_parent, const std::string& prefix, const Context& ctx,
                  std::vector<Geometry>& out) {
  const SE3 T_world_model = T_world_parent * pose_in_parent(model);
  const std::string name = prefix + model.Name() + "::";
  for (uint64_t i = 0; i < model.LinkCount(); ++i) {
    const sdf::Link& link = *model.LinkByIndex(i);
    append_link(link, T_world_model * pose_in_parent(link), name, ctx, out);
  }
  for (uint64_t i = 0; i < model.ModelCount(); ++i) append_model(*model.ModelByIndex(i), T_world_model, name, ctx, out);
}

Actor convert_actor(const sdf::Actor& a, const Context& ctx) {
  Actor actor;
  actor.name = a.Name();
  actor.loop = a.ScriptLoop();
  actor.delay_s = a.ScriptDelayStart();
  double t_offset = 0.0;  // trajectories play one after another
  for (uint64_t t = 0; t < a.TrajectoryCount(); ++t) {
    const sdf::Trajectory& traj = *a.TrajectoryByIndex(t);
    double t_end = t_offset;
    for (uint64_t w = 0; w < traj.WaypointCount(); ++w) {
      const sdf::Waypoint& wp = *traj.WaypointByIndex(w);
      actor.trajectory.push_back(Waypoint{t_offset + wp.Time(), to_se3(wp.Pose())});
      t_end = std::max(t_end, t_offset + wp.Time());
    }
    t_offset = t_end;
  }
  std::stable_sort(actor.trajectory.begin(), actor.trajectory.end(),
                   [](const Waypoint& x, const Waypoint& y) { return x.time_s < y.time_s; });
  if (actor.trajectory.empty()) actor.trajectory.push_back(Waypoint{0.0, to_se3(a.RawPose())});
  for (uint64_t i = 0; i < a.LinkCount(); ++i) {
    const sdf::Link& link = *a.LinkByIndex(i);
    append_link(link, to_se3(link.RawPose()), "", ctx, actor.parts);
  }
  if (actor.parts.empty()) {
    // Skin-only actor (an animated mesh): a person-sized cylinder standing on the ground.
    const double z0 = actor.trajectory.front().pose.translation().z();
    SE3 T = SE3::Identity();
    T.translation().z() = 0.5 * kActorStandInHeight_m - z0;
    actor.parts.push_back(Geometry{"stand_in", T, Cylinder{kActorStandInRadius_m, kActorStandInHeight_m}});
  }
  return actor;
}

bool is_remote(const std::string& uri) { return uri.rfind("http://", 0) == 0 || uri.rfind("https://", 0) == 0; }

// Handles sdformat's errors: unreachable Fuel includes are tolerated (see the header), anything
// else is fatal. Returns true when a Fuel ground plane was requested.
bool check_errors(const sdf::Errors& errors, const fs::path& file) {
  bool ground = false;
  for (const sdf::Error& e : errors) {
    const std::string& msg = e.Message();
    const bool fuel = msg.find("http://") != std::string::npos || msg.find("https://") != std::string::npos;
    if (fuel && (e.Code() == sdf::ErrorCode::URI_LOOKUP || e.Code() == sdf::ErrorCode::FILE_READ)) {
      std::string lower = msg;
      std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
      ground =
          ground || lower.find("ground plane") != std::string::npos || lower.find("ground_plane") != std::string::npos;
      continue;
    }
    throw FileError(file.string(), e.LineNumber() ? "line " + std::to_string(*e.LineNumber()) : "", "sdformat: " + msg);
  }
  return ground;
}

}  // namespace

fs::path resolve_model_uri(const std::string& uri, const fs::path& base_dir, const std::vector<fs::path>& model_paths) {
  const std::string model_prefix = "model://", file_prefix = "file://";
  if (uri.rfind(model_prefix, 0) == 0) {
    const std::string rel = uri.substr(model_prefix.size());
    for (const fs::path& dir : model_paths)
      if (fs::exists(dir / rel)) return dir / rel;
    return {};
  }
  fs::path p = uri.rfind(file_prefix, 0) == 0 ? fs::path(uri.substr(file_prefix.size())) : fs::path(uri);
  if (p.is_relative()) p = base_dir / p;
  return fs::exists(p) ? p : fs::path();
}

World load_sdf_world(const fs::path& file, const std::vector<fs::path>& model_paths) {
  if (std::error_code ec; !fs::is_regular_file(file, ec)) throw FileError(file.string(), "", "SDF file not found");
  Context ctx{file, model_paths};
  for (const fs::path& extra : {file.parent_path() / "models", file.parent_path().parent_path() / "models"})
    if (fs::is_directory(extra)) ctx.model_paths.push_back(extra);

  sdf::ParserConfig config;
  for (const fs::path& dir : ctx.model_paths) config.AddURIPath("model://", fs::absolute(dir).string());
  config.SetFindCallback([](const std::string& uri) { return is_remote(uri) ? std::string() : uri; });
  sdf::Root root;
  sdf::Errors errors;
  try {
    errors = root.Load(file.string(), config);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    // libsdformat lets some parse failures escape as standard exceptions (e.g. std::stoi on a
    // malformed version or number): report them as a load error of this file.
    throw FileError(file.string(), "", std::string("libsdformat could not parse the file: ") + e.what());
  }
  const bool fuel_ground = check_errors(errors, file);

  World world;
  world.name = file.stem().string();
  if (root.WorldCount() > 0) {
    const sdf::World& w = *root.WorldByIndex(0);
    world.name = w.Name();
    for (uint64_t i = 0; i < w.ModelCount(); ++i)
      append_model(*w.ModelByIndex(i), SE3::Identity(), "", ctx, world.statics);
    for (uint64_t i = 0; i < w.ActorCount(); ++i) world.actors.push_back(convert_actor(*w.ActorByIndex(i), ctx));
  } else if (root.Model() != nullptr) {
    append_model(*root.Model(), SE3::Identity(), "", ctx, world.statics);
  } else if (root.Actor() != nullptr) {
    world.actors.push_back(convert_actor(*root.Actor(), ctx));
  } else {
    throw FileError(file.string(), "", "no <world>, <model> or <actor> in the file");
  }
  if (fuel_ground) world.statics.push_back(Geometry{"ground_plane", SE3::Identity(), Plane{}});
  return world;
}

}  // namespace bipednav::sim
