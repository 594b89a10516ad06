// The scene: everything a run needs, as read from a TOML scene file.
// Dimension-agnostic: vectors are stored with 3 components; in 2D the third
// is unused (and must be absent from the file). See docs/scenes.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sablier {

using Vec3d = std::array<double, 3>;
using Vec3i = std::array<int, 3>;

// An invalid scene: the message names the file, the key and what is allowed.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class BoundaryType { Stick, Slip, Free };

// Faces in the order xmin, xmax, ymin, ymax, zmin, zmax (index 2*axis + side).
enum Face { XMin = 0, XMax, YMin, YMax, ZMin, ZMax };

// A stretch of a face that behaves as `free` (an orifice): the face's points
// whose tangential coordinates lie in [min, max] (normal coordinate ignored).
struct Opening {
  int face = YMin;
  Vec3d min{0, 0, 0};
  Vec3d max{0, 0, 0};
};

struct BoundaryConfig {
  std::array<BoundaryType, 6> faces{BoundaryType::Slip, BoundaryType::Slip, BoundaryType::Slip,
                                    BoundaryType::Slip, BoundaryType::Slip, BoundaryType::Slip};
  std::vector<Opening> openings;
};

// mu(I) rheology (METHOD.md section 1): mu = mu_s + delta_mu / (1 + I0 / I).
struct MuIConfig {
  double delta_mu = 0.26;        // dimensionless
  double I0 = 0.279;             // dimensionless
  double grain_diameter = 1e-3;  // m
};

struct MaterialConfig {
  double density = 2500.0;      // kg/m^3 of grains
  double mu = 0.5;              // simple-shear friction coefficient (METHOD.md section 4)
  double phi_max = 0.6;         // maximum volume fraction, (0, 1]
  double viscosity = 0.0;       // Pa s
  double cohesion = 0.0;        // Pa
  double cohesion_decay = 0.0;  // per unit shear strain; 0 = cohesion never decays
  std::optional<MuIConfig> mu_i;
};

enum class Decompaction { Move, Push, Clamp, Project };

struct SolverConfig {
  double tolerance = 1e-5;  // relative velocity change of the last sweep (docs/method.md)
  int max_iterations = 2000;
  int anderson = 5;  // Anderson acceleration depth; 0 = plain Gauss-Seidel
  // The fraction of its local change a row that cycles between stick and
  // slide takes (solver/relaxation.hpp); 1 = none.
  double relaxation = 0.5;
  // The sand's stress rows are swept in zones of about this many rows, one
  // thread per zone (solver/zones.hpp); 0 = one zone. It sets the order of
  // the Gauss-Seidel updates, so results depend on it, not on the threads.
  int zone_rows = 500;
  // How grains crowded beyond phi_max by transfer errors are spread out
  // again (docs/method.md, "What the decompaction costs"). Project (the
  // default since 0.3.0): the cone problem only clamps (METHOD.md step 5)
  // and after advection the grains are moved apart as under Move, then by
  // a projection (node potentials whose gradient takes every node back to
  // phi_max, decompaction_moves rounds at most); it holds phi_max, and
  // solids driven into the sand need it. Move (the default of 0.2.0): the
  // grains are moved apart decompaction_moves times per step after
  // advection, velocities untouched; draining bins compact beyond phi_max.
  // Push: the cone problem pushes them apart, 10% of the excess per step
  // (the default before 0.2.0; it does not converge under refinement).
  // Clamp: METHOD.md's pure clamp and nothing else (over-compacts).
  Decompaction decompaction = Decompaction::Project;
  int decompaction_moves = 4;
  // Node-to-node stabilisation (solver/cell_rows.hpp): linear viscous rows
  // on the sand's interior cells that resist motions alternating from node
  // to node, eta = stabilization rho phi_max h^2 / dt; 0 = none (METHOD.md's
  // discretisation alone).
  double stabilization = 0.0;
};

struct TimeConfig {
  double fps = 30.0;
  int frames = 30;
  int substeps = 0;  // 0 = adaptive (CFL on advection)
  double cfl = 1.0;  // adaptive: at most this many cells of travel per step
};

// A [[sand]] block's own material: each key set overrides [material], each
// absent one inherits it. phi_max and viscosity have no per-block value: the
// phi_max bound is a constraint on a node's total grain volume, whatever the
// grains, and the viscosity a grid operator (docs/scenes.md).
struct SandMaterial {
  std::optional<double> density;         // kg/m^3
  std::optional<double> mu;              // simple-shear friction coefficient
  std::optional<double> cohesion;        // Pa
  std::optional<double> cohesion_decay;  // per unit shear strain
  std::optional<MuIConfig> mu_i;         // all three keys, when given
};

// "disk" in 2D is a Cylinder; Sphere is 3D only, Polygon 2D only, Mesh 3D only.
enum class SandShape { Box, Cylinder, Sphere, Polygon, Mesh };

class SolidMesh;  // core/mesh.hpp

// Particles per cell and axis when a [[sand]] or [[spout]] block does not
// say: 5 in 2D (25 per cell), 3 in 3D (27). Fewer grains per cell let the
// sand over-compact, the more so on finer grids: the 2D collapse with 2 per
// axis rests at median phi 0.65 at 1 cm cells and 0.89 at 5 mm, against
// 0.62 with 3 at 5 mm; the 3D collapse with 2 at 0.613 (12.5 mm cells) and
// 0.624 (8.3 mm), with 3 at 0.603 and 0.606 (docs/method.md). In 2D, 3 per
// axis still let flows drift: a mu(I) layer ran up to 15% fast against the
// infinite layer of its rheology (1.6% with 5), a heap's slump and a
// collapse's run-out drifted as the cell shrank, and a plough's blade felt
// 186 N/m against Rankine's 221 (220 with 5) (docs/scenes.md, "How many
// particles per cell"). 3D flows would want 4, at 2.4 times the grains.
constexpr int kDefaultParticlesPerCell = 3;  // the structs' until the dimension is read
constexpr int default_particles_per_cell(int dimension) {
  return dimension == 2 ? 5 : kDefaultParticlesPerCell;
}

struct SandConfig {
  SandShape shape = SandShape::Box;
  Vec3d min{0, 0, 0};  // box
  Vec3d max{0, 0, 0};  // box
  // cylinder / disk: centre of the base (3D, axis along z) or of the disk (2D)
  Vec3d center{0, 0, 0};
  double radius = 0.0;                                // cylinder / disk
  double height = 0.0;                                // cylinder (3D only)
  int particles_per_cell = kDefaultParticlesPerCell;  // per axis
  double jitter = 0.0;                                // in [0, 1]: fraction of the particle spacing
  Vec3d velocity{0, 0, 0};                            // initial velocity, m/s
  SandMaterial material{};  // overrides of [material] for this block's grains
  // Polygon (2D): the corners in order, either orientation; z unused.
  std::vector<Vec3d> vertices{};
  // Mesh (3D): the file as given, its absolute path (relative paths are
  // relative to the scene file's folder), the transform applied to its
  // vertices (x -> scale x + translate), and the closed mesh, transformed.
  std::string file{};
  std::string file_path{};
  double scale = 1.0;
  Vec3d translate{0, 0, 0};
  std::shared_ptr<const SolidMesh> mesh{};
};

// A [[spout]] block: grains pouring in through a cross-section (a segment
// in 2D, a disk in 3D, centred on `center` and perpendicular to `velocity`)
// at the spout's velocity, with volume fraction phi_max
// (physics/emission.cpp).
struct SpoutConfig {
  Vec3d center{0, 0, 0};    // m
  double radius = 0.0;      // m: half-width (2D) or radius (3D) of the cross-section
  Vec3d velocity{0, 0, 0};  // m/s, nonzero
  double start = 0.0;       // s
  double stop = std::numeric_limits<double>::infinity();  // s; infinity = never
  int particles_per_cell = kDefaultParticlesPerCell;      // per axis
  double jitter = 0.0;  // in [0, 1]: fraction of the particle spacing
};

// An [[obstacle]] block: a solid that sand cannot enter and slides on with
// Coulomb friction `mu` (METHOD.md section 3; physics/obstacle.hpp): fixed,
// a plane moving along itself, or, with a density, a rigid disk or sphere
// that the sand pushes.
// "disk" (2D) and "sphere" (3D) are both Ball; Cylinder is 3D only (axis
// along z, `center` the centre of its base). A plane's solid side is the one
// its normal points away from. Polygon is 2D only, Mesh 3D only.
enum class ObstacleShape { Plane, Box, Ball, Cylinder, Polygon, Mesh };

class SolidPolygon;   // core/polygon.hpp
class DistanceGrid;   // core/distance_grid.hpp
struct TriangleMesh;  // core/mesh.hpp
struct FeatureEdge;   // core/mesh.hpp

struct ObstacleConfig {
  ObstacleShape shape = ObstacleShape::Plane;
  Vec3d point{0, 0, 0};   // plane: a point on it, m
  Vec3d normal{0, 1, 0};  // plane: unit normal pointing into the sand (normalised by the parser)
  Vec3d min{0, 0, 0};     // box, m
  Vec3d max{0, 0, 0};     // box, m
  Vec3d center{0, 0, 0};  // ball: centre; cylinder: centre of the base, m
  double radius = 0.0;    // ball / cylinder, m
  double height = 0.0;    // cylinder, m
  // Polygon (2D): the corners in order, either orientation (z unused), and
  // the solid they bound.
  std::vector<Vec3d> vertices{};
  std::shared_ptr<const SolidPolygon> polygon{};
  // Mesh (3D): as for [[sand]] meshes (the file as given, its absolute path,
  // x -> scale x + translate), and its signed distance sampled at half the
  // cell size over the box (read by the parser, which knows the grid).
  std::string file{};
  std::string file_path{};
  double scale = 1.0;
  Vec3d translate{0, 0, 0};
  std::shared_ptr<const SolidMesh> solid{};        // the closed mesh, transformed (exact queries)
  std::shared_ptr<const DistanceGrid> distance{};  // sampled once every obstacle is read
  std::shared_ptr<const TriangleMesh> surface{};   // the triangles, transformed (for outputs)
  // The mesh's convex edges (core/mesh.hpp), for rigid bodies' edge contacts.
  std::shared_ptr<const std::vector<FeatureEdge>> edges{};
  // Its vertices' outward normals (core/mesh.hpp, vertex_normals), for the
  // rows of its corners at other solids' edges (physics/corners.hpp).
  std::shared_ptr<const std::vector<std::array<double, 3>>> vertex_normals{};
  Vec3d extent_min{0, 0, 0}, extent_max{0, 0, 0};  // polygon, mesh: bounding box, m
  // Its thinnest part when thinner than kThinSolidCells cells, measured
  // once the scene is read (scene_obstacles.hpp, thinnest_part), and where;
  // 0 when none is (and for rigid bodies, which are not measured).
  double thin = 0.0;
  Vec3d thin_at{0, 0, 0};
  double mu = 0.5;  // Coulomb friction of sand on the obstacle, [0, kMaxObstacleMu]
  // m/s: a fixed obstacle translates rigidly, x(t) = x(0) + velocity t (a
  // plane along itself: a conveyor belt); a rigid body's initial velocity.
  Vec3d velocity{0, 0, 0};
  // s: a fixed obstacle is taken away for the steps that start at or after
  // this time (a gate lifted, a shutter opened); infinity = never.
  double until = std::numeric_limits<double>::infinity();
  // kg/m^3: 0 for a fixed (or kinematic) obstacle; > 0 makes a disk,
  // sphere or box a rigid body that the sand pushes (two-way coupling,
  // METHOD.md section 3), starting at `velocity` and falling under gravity.
  double density = 0.0;
  // The initial orientation of a rigid body, or of a fixed box, polygon or
  // mesh: turned by angle_degrees about its centre, counter-clockwise about
  // `axis` (3D, a unit vector; z in 2D).
  double angle_degrees = 0.0;
  Vec3d axis{0, 0, 1};
  // A rigid body's initial angular velocity, or a fixed solid's constant
  // one (it turns about its centre at that rate), rad/s about world axes
  // (2D: spin[2], counter-clockwise, about z).
  Vec3d spin{0, 0, 0};
  // A rigid polygon or mesh: the centroid of its solid as given (the
  // parser's; its `center` starts there), m.
  Vec3d centroid{0, 0, 0};
  bool dynamic() const { return density > 0.0; }
  // A fixed box, polygon or mesh that is turned or turns: laid out as a
  // body is (physics/obstacle.hpp), its centre `center` (a polygon's or
  // mesh's: its centroid).
  bool posed() const {
    const bool turning = spin[0] != 0.0 || spin[1] != 0.0 || spin[2] != 0.0;
    return !dynamic() && (turning || angle_degrees != 0.0) &&
           (shape == ObstacleShape::Box || shape == ObstacleShape::Polygon ||
            shape == ObstacleShape::Mesh);
  }
};

// The same bound as material.mu. The paper's form (the full tensor in
// DP(mu_RB)) gives the Signorini condition only below about 0.7 (METHOD.md
// section 3); ours, a Coulomb cone on the traction (docs/method.md,
// "Frictional obstacles"), gives it for any mu >= 0.
constexpr double kMaxObstacleMu = 5.0;

struct SceneConfig {
  std::string source;  // file name, for messages
  int dimension = 2;
  Vec3d size{1, 1, 1};        // m, box from the origin
  Vec3i resolution{1, 1, 1};  // cells per axis
  TimeConfig time;
  Vec3d gravity{0, -9.81, 0};
  MaterialConfig material;
  SolverConfig solver;
  BoundaryConfig boundary;
  std::vector<SandConfig> sand;
  std::vector<SpoutConfig> spouts;
  std::vector<ObstacleConfig> obstacles;
  std::uint64_t seed = 0;

  double cell_size() const { return size[0] / resolution[0]; }
};

// Reads and validates a scene file. `overrides` are "dotted.key=value" strings
// (from --set), applied to the TOML document before validation and checked as
// strictly as the file. Throws SceneError.
SceneConfig load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// Same, from TOML text (`source` names it in messages).
SceneConfig parse_scene(const std::string& toml_text, const std::string& source,
                        const std::vector<std::string>& overrides = {});

// The resolved scene (every key, defaults filled in) as TOML text; parsing it
// back gives the same SceneConfig.
std::string scene_to_toml(const SceneConfig& scene);

// The material of [[sand]] block `block`: [material] with the block's
// overrides applied (phi_max and viscosity are always [material]'s).
MaterialConfig sand_material(const SceneConfig& scene, std::size_t block);

// Every dotted key the parser accepts, as docs/scenes.md names them:
// "material.mu", "material.mu_i.I0", "sand[].shape", "boundary.opening[].face".
std::vector<std::string> known_scene_keys();

}  // namespace sablier
