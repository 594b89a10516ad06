// Particle to grid (METHOD.md section 2, steps 1 and 2): sorting by cell,
// P2G with APIC and the coupling vectors g_ji of the forms. The way back,
// G2P and advection, is grid_to_particles.cpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/corners.hpp"
#include "physics/edges.hpp"
#include "physics/shape.hpp"
#include "physics/simulation.hpp"
#include "solver/zones.hpp"

namespace sablier {

template <int D>
void Simulation<D>::sort_particles() {
  const std::size_t n = particles_.size();
  const auto& cells = grid_.cells();
  const double h = grid_.h();
  std::vector<std::int64_t> cell(n);
  std::vector<std::int64_t> count(grid_.cell_count() + 1, 0);
  for (std::size_t p = 0; p < n; ++p) {
    const Vec<D>& x = particles_.position[p];
    bool outside = false;  // left through a free face or an opening
    for (int a = 0; a < D; ++a) outside |= !(x[a] >= 0.0 && x[a] <= cells[a] * h);
    cell[p] = outside ? -1 : grid_.cell_index(grid_.cell_of(x));
    if (!outside) ++count[cell[p] + 1];
  }
  for (std::int64_t c = 0; c < grid_.cell_count(); ++c) count[c + 1] += count[c];
  cell_start_ = count;
  std::vector<std::int64_t> order(cell_start_.back());
  for (std::size_t p = 0; p < n; ++p)  // stable counting sort
    if (cell[p] >= 0) order[count[cell[p]]++] = static_cast<std::int64_t>(p);
  particles_.permute(order);
  clearance_.resize(n, 0.0);  // each grain's goes with it (transfer_to_particles keeps it)
  sorted_clearance_.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted_clearance_[k] = clearance_[order[k]];
  clearance_.swap(sorted_clearance_);

  active_cells_.clear();
  for (auto& list : cells_by_parity_) list.clear();
  for (std::int64_t c = 0; c < grid_.cell_count(); ++c) {
    if (cell_start_[c + 1] == cell_start_[c]) continue;
    active_cells_.push_back(c);
    const auto cc = grid_.cell_coords(c);
    int parity = 0;
    for (int a = 0; a < D; ++a) parity |= (cc[a] & 1) << a;
    cells_by_parity_[parity].push_back(c);
  }
}

template <int D>
void Simulation<D>::transfer_to_grid(double dt) {
  constexpr int NC = ipow(2, D);
  std::fill(node_grain_volume_.begin(), node_grain_volume_.end(), 0.0);
  std::fill(node_mass_.begin(), node_mass_.end(), 0.0);
  std::fill(node_momentum_.begin(), node_momentum_.end(), Vec<D>::Zero());

  // Stress rows: the nodes of cells holding particles, laid out in zones and
  // colours (solver/zones.hpp): rows of one run have disjoint stencils.
  const auto corner = grid_.corner_offsets();
  place_thin_solids(time_);  // where the step finds them
  find_own_sides();          // next to thin solids: for P2G here and G2P after the solve
  std::fill(row_of_node_.begin(), row_of_node_.end(), -1);
  std::vector<std::int64_t> nodes;
  std::vector<std::array<int, D>> coords;
  for (std::int64_t c : active_cells_) {
    const std::int64_t base = grid_.cell_base_node(grid_.cell_coords(c));
    for (int k = 0; k < NC; ++k) {
      const std::int64_t node = base + corner[k];
      if (row_of_node_[node] != -1) continue;
      row_of_node_[node] = -2;
      nodes.push_back(node);
      coords.push_back(grid_.node_coords(node));
    }
  }
  // The zones balance the rows' costs in a sweep (kZoneCost), told by their
  // warm starts and by the case each node's row ended the last solve in.
  std::vector<int> cost(nodes.size());
  for (std::size_t r = 0; r < nodes.size(); ++r) {
    const std::int64_t i = nodes[r];
    cost[r] =
        zone_row_cost<D>(warm_lambda_[i].squaredNorm() > 0.0, static_cast<DPCase>(warm_case_[i]));
  }
  const ZoneLayout layout = zone_layout<D>(coords, nodes, scene_.solver.zone_rows, cost);
  constexpr int kColours = ipow(3, D);
  const int sand_runs = static_cast<int>(layout.run_start.size()) - 1;
  std::vector<std::int64_t> sand_node(layout.order.size());  // the rows' nodes, in row order
  for (std::size_t i = 0; i < sand_node.size(); ++i) sand_node[i] = nodes[layout.order[i]];
  ConeProblem<D>& P = problem_;
  P.zones = layout.zones;
  P.colour_start = layout.run_start;
  int rows = layout.run_start.back();
  // Obstacle rows (METHOD.md section 3): every sand node within one cell of
  // an obstacle gets a second row pairing the obstacle's contact stress with
  // gamma_RB = sym(u n^T) / h. Such a row touches only its own node (the
  // solver writes only that node); they take the same 3^d colours, after
  // the sand's, which fixes where their updates fall among the sand rows'.
  const double h = grid_.h();
  const int sand_rows = rows;
  // Where the obstacles are at the start of the step: a moving plane only
  // slides along itself (its solid stays put, docs/scenes.md) and a rigid
  // body is where the last step left it.
  const std::vector<Obstacle<D>> obstacles = obstacles_at(time_);
  struct Contact {
    std::int64_t node;
    Vec<D> normal;
    int which;
    double gap = -1.0;                         // a body against a solid: the gap (m); else -1
    double mu = 0.0;                           // and the friction there
    int other = -1;                            // the solid, when it is another body
    Vec<D> surface_velocity = Vec<D>::Zero();  // the solid's, when it is a moving obstacle
    Vec<D> arm = Vec<D>::Zero();               // a body against a solid: its point from its centre
    Vec<D> other_arm = Vec<D>::Zero();         // and the other body's, from that one's centre
  };
  std::vector<std::vector<Contact>> obstacle_by_colour;
  // Rigid bodies' rows come last, in one group that the solver updates in
  // order on one thread (they share their body's velocity; cone_problem.hpp).
  std::vector<Contact> body_contacts;
  std::vector<double> solid(sand_rows, 0.0);
  std::vector<char> in_solid(sand_rows, 0);
  if (!obstacles.empty()) {
    obstacle_by_colour.resize(kColours);
    for (int run = 0; run < sand_runs; ++run)
      for (int row = layout.run_start[run]; row < layout.run_start[run + 1]; ++row) {
        const std::int64_t node = sand_node[row];
        const auto nc = grid_.node_coords(node);
        Vec<D> x, n;
        for (int a = 0; a < D; ++a) x[a] = nc[a] * h;
        int which = 0;
        const double dist = obstacle_distance(obstacles, x, &n, &which);
        solid[row] = solid_fraction(dist, h);
        in_solid[row] = dist <= -0.5 * h;
        if (dist >= h) continue;
        (obstacles[which].dynamic ? body_contacts : obstacle_by_colour[run % kColours])
            .push_back({node, n, which});
      }
    // A rigid body meets walls and other solids by points: a ball by its
    // centre, reaching its radius further, a box or polygon by its corners,
    // a mesh by its vertices, and in 3D other solids by its edges too
    // (docs/scenes.md, "Rigid boxes, polygons and meshes"). Such a point
    // within a cell of one of the box's walls gets a row against it: on the
    // ghost node just outside the wall nearest the point, whose velocity and
    // inverse mass are zero, so that the row sees the body alone. Its normal
    // points from the body to the wall; the row lets the body close the gap
    // within the step (contact_velocity, below), and stick walls get the
    // body's friction, slip walls none. Free faces and openings hold nothing
    // back.
    const auto& cells = grid_.cells();
    const std::int64_t count = static_cast<std::int64_t>(obstacles.size());
    constexpr int NC = ipow(2, D);
    struct Touch {
      Vec<D> at;
      double reach;
    };
    std::vector<Vec<D>> corners;
    const auto touch_points = [&corners](const Obstacle<D>& o, std::vector<Touch>& out) {
      out.clear();
      if (o.shape == ObstacleShape::Ball) {
        out.push_back({o.a, o.radius});
        return static_cast<int>(out.size());
      }
      body_points(o, corners);
      for (const Vec<D>& c : corners) out.push_back({c, 0.0});
      return static_cast<int>(out.size());
    };
    std::vector<Touch> points;
    // The ghost node of a row's key (one per pair of solids and point).
    const auto ghost_node = [&](std::int64_t key) {
      std::array<int, D> ghost{};
      ghost[0] = -1;
      ghost[1] = static_cast<int>(key % (cells[1] + 1));
      if constexpr (D == 3) ghost[2] = static_cast<int>((key / (cells[1] + 1)) % (cells[2] + 1));
      return grid_.node_index(ghost);
    };
    // Slots of the rows' keys: a body's points (t), a fixed solid's corners
    // or vertices (NC + t), edge crossings (edge_slot + their pair), and
    // the rows of faces at concave folds (edge_slot + 2 kFolds t + ...; their
    // warm starts may share a ghost node with an edge crossing's, as rows
    // past a face's node count do).
    std::int64_t edge_slot = 2 * NC;
    for (const Obstacle<D>& o : obstacles) {
      if (o.points)
        edge_slot = std::max(edge_slot, NC + static_cast<std::int64_t>(o.points->size()));
      if (o.shape == ObstacleShape::Cylinder)
        edge_slot = std::max(edge_slot, NC + std::int64_t(2 * kRimPoints + 2));
    }
    constexpr int kFolds = 4;
    Vec<D> fold_normal[kFolds];
    double fold_distance[kFolds];
    // Whether face f of those a point lies over is one its distance was
    // measured to (the same plane distance, to a part in 1e9 of a cell):
    // that face's row is the point's own, whose normal, the direction from
    // the nearest point, is round-off for a point on the face, so that
    // comparing normals would not tell.
    const auto measured = [&](int f, double distance) {
      return std::abs(fold_distance[f] - distance) <= 1e-9 * h;
    };
    // Rows of body b's points against solid s (the smaller friction of the
    // two, and the solid's motion: a moving plane drags the body along, as
    // it does the sand), on ghost nodes beyond the xmin face (zero velocity
    // and inverse mass, like the walls'), one per pair and point so that
    // each keeps its own warm start (past the face's node count they share
    // one; only their warm starts mix).
    const auto against_solid = [&](std::size_t b, std::size_t s) {
      const Obstacle<D>& o = obstacles[b];
      const Obstacle<D>& q = obstacles[s];
      const int n_points = touch_points(o, points);
      for (int t = 0; t < n_points; ++t) {
        Vec<D> out;  // from the solid towards the point
        // A box's, polygon's or mesh's corner: the normal of a box, polygon
        // or mesh it meets chosen by its own direction where it sits at that
        // solid's edge, and a mesh's exact distance (corner_distance).
        Vec<D> inward = Vec<D>::Zero();
        const double distance = corner_inward(o, t, &inward)
                                    ? corner_distance(q, points[t].at, inward, h, &out)
                                    : signed_distance(q, points[t].at, &out);
        const double gap = distance - points[t].reach;
        if (gap >= h) continue;
        const Vec<D> n = -out;
        const std::int64_t key =
            static_cast<std::int64_t>(b) * count + static_cast<std::int64_t>(s) + count * count * t;
        Contact c{ghost_node(key),
                  n,
                  static_cast<int>(b),
                  std::max(gap, 0.0),
                  std::min(o.mu, q.mu),
                  q.dynamic ? static_cast<int>(s) : -1,
                  q.dynamic ? Vec<D>::Zero()
                            : surface_velocity(q, Vec<D>(points[t].at - distance * out))};
        c.arm = (points[t].at - o.a) + points[t].reach * n;
        if (q.dynamic)  // the solid's point nearest ours, from its centre
          c.other_arm = q.shape != ObstacleShape::Ball ? Vec<D>(points[t].at - distance * out - q.a)
                                                       : Vec<D>(-q.radius * n);
        body_contacts.push_back(c);
        // At a concave fold of a polygon or mesh, a row for each other face
        // the point lies over (corners.hpp, faces_over).
        const int over = faces_over(q, points[t].at, inward, h + points[t].reach, h, fold_normal,
                                    fold_distance, kFolds);
        for (int f = 0; f < over; ++f) {
          if (measured(f, distance)) continue;
          const Vec<D> on = points[t].at - fold_distance[f] * fold_normal[f];
          Contact e = c;
          e.node = ghost_node(static_cast<std::int64_t>(s) * count + static_cast<std::int64_t>(b) +
                              count * count * (edge_slot + 2 * kFolds * t + f));
          e.normal = -fold_normal[f];
          e.gap = std::max(fold_distance[f] - points[t].reach, 0.0);
          e.surface_velocity = q.dynamic ? Vec<D>::Zero() : surface_velocity(q, on);
          e.arm = (points[t].at - o.a) - points[t].reach * fold_normal[f];
          if (q.dynamic) e.other_arm = on - q.a;
          body_contacts.push_back(e);
        }
      }
    };
    // How much further than point t of solid q its row reaches: a ball's
    // radius, a cylinder's axis balls' (edges.hpp, cylinder_points).
    const auto point_reach = [](const Obstacle<D>& q, std::size_t t) {
      if (q.shape == ObstacleShape::Ball) return q.radius;
      if (q.shape == ObstacleShape::Cylinder && t >= 2 * kRimPoints)
        return std::min(q.radius, 0.5 * q.height);
      return 0.0;
    };
    // Rows of a fixed solid's corners (a box's, a polygon's, a mesh's vertices) against body b
    // (a box, polygon or mesh), where a corner pokes at the body's face (a
    // box landing on a ledge's edge), and of a fixed disk's or sphere's
    // centre, reaching its radius further (a box set on a drum): the normal,
    // the body's outward one there, points from the body to the corner, and
    // the row's point on the body is the corner's nearest on its surface.
    const auto corners_against_body = [&](std::size_t b, std::size_t s) {
      const Obstacle<D>& o = obstacles[b];
      const Obstacle<D>& q = obstacles[s];
      if (q.gone) return;
      corners.clear();
      if (q.posed || q.shape == ObstacleShape::Mesh) {
        body_points(q, corners);  // a turned box's or polygon's corners, a mesh's vertices
      } else if (q.shape == ObstacleShape::Box) {
        for (int c = 0; c < NC; ++c) {
          Vec<D> x;
          for (int a = 0; a < D; ++a) x[a] = (c >> a & 1) ? q.b[a] : q.a[a];
          corners.push_back(x);
        }
      } else if (q.shape == ObstacleShape::Polygon) {
        for (const auto& p : q.polygon->corners()) {
          Vec<D> x = Vec<D>::Zero();
          for (int a = 0; a < 2; ++a) x[a] = p[a] + q.a[a];
          corners.push_back(x);
        }
      } else if (q.shape == ObstacleShape::Ball) {
        corners.push_back(q.a);  // a fixed disk or sphere: its centre, a radius further
      } else if (q.shape == ObstacleShape::Cylinder) {
        if constexpr (D == 3) cylinder_points(q, o, h, corners);  // edges.hpp
      }
      for (std::size_t t = 0; t < corners.size(); ++t) {
        const Vec<D>& x = corners[t];
        const double further = point_reach(q, t);
        const double reach = bounding_radius(o) + h + further;
        if ((x - o.a).squaredNorm() >= reach * reach) continue;
        Vec<D> n;  // the body's outward normal
        Vec<D> inward = Vec<D>::Zero();
        const double from_point = corner_inward(q, static_cast<int>(t), &inward)
                                      ? corner_distance(o, x, inward, h, &n)
                                      : signed_distance(o, x, &n);
        const double distance = from_point - further;
        if (distance >= h) continue;
        const std::int64_t key = static_cast<std::int64_t>(s) * count +
                                 static_cast<std::int64_t>(b) +
                                 count * count * (NC + static_cast<std::int64_t>(t));
        Contact c{ghost_node(key),
                  n,
                  static_cast<int>(b),
                  std::max(distance, 0.0),
                  std::min(o.mu, q.mu),
                  -1,
                  surface_velocity(q, Vec<D>(x - further * n))};
        c.arm = x - from_point * n - o.a;
        body_contacts.push_back(c);
        // A concave fold of the body: a row for each other face the corner
        // lies over.
        const int over =
            faces_over(o, x, inward, h + further, h, fold_normal, fold_distance, kFolds);
        for (int f = 0; f < over; ++f) {
          if (measured(f, from_point)) continue;
          Contact e = c;
          e.node = ghost_node(static_cast<std::int64_t>(s) * count + static_cast<std::int64_t>(b) +
                              count * count * (edge_slot + 2 * kFolds * t + kFolds + f));
          e.normal = fold_normal[f];
          e.gap = std::max(fold_distance[f] - further, 0.0);
          e.surface_velocity = surface_velocity(q, Vec<D>(x - further * fold_normal[f]));
          e.arm = x - fold_distance[f] * fold_normal[f] - o.a;
          body_contacts.push_back(e);
        }
      }
    };
    // Rows where an edge of body b crosses an edge of solid s, a fixed box
    // or mesh or another body (3D, edges.hpp): the normal from the body to
    // the solid across both edges, the arms to the edges' closest points.
    // Their keys' slots start at edge_slot (above).
    EdgeScratch edge_scratch;
    std::vector<EdgeContact> crossings;
    const auto edges_against = [&](std::size_t b, std::size_t s) {
      if constexpr (D == 3) {
        const Obstacle<D>& o = obstacles[b];
        const Obstacle<D>& q = obstacles[s];
        if (q.shape == ObstacleShape::Cylinder) {
          edges_against_cylinder(o, q, h, edge_scratch, crossings);
        } else {
          edge_contacts(o, q, h, edge_scratch, crossings);
        }
        for (const EdgeContact& e : crossings) {
          const std::int64_t key = static_cast<std::int64_t>(b) * count +
                                   static_cast<std::int64_t>(s) +
                                   count * count * (edge_slot + e.pair);
          Contact c{ghost_node(key),
                    e.normal,
                    static_cast<int>(b),
                    std::max(e.separation, 0.0),
                    std::min(o.mu, q.mu),
                    q.dynamic ? static_cast<int>(s) : -1,
                    q.dynamic ? Vec<D>::Zero() : surface_velocity(q, e.on_solid)};
          c.arm = e.on_body - o.a;
          if (q.dynamic) c.other_arm = e.on_solid - q.a;
          body_contacts.push_back(c);
        }
      }
    };
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      const Obstacle<D>& o = obstacles[k];
      if (!o.dynamic) continue;
      const int n_points = touch_points(o, points);
      for (int t = 0; t < n_points; ++t)
        for (int a = 0; a < D; ++a)
          for (int side = 0; side < 2; ++side) {
            const Vec<D>& x = points[t].at;
            const double reach = points[t].reach;
            const double gap = side == 0 ? x[a] - reach : cells[a] * h - x[a] - reach;
            if (gap >= h) continue;
            Vec<D> n = Vec<D>::Zero();
            n[a] = side == 0 ? -1.0 : 1.0;
            const Vec<D> touch = x + reach * n;
            if (leaves_through_free_face(a, side, touch)) continue;
            std::array<int, D> ghost;
            for (int b = 0; b < D; ++b)
              ghost[b] = std::clamp(static_cast<int>(std::lround(x[b] / h)), 0, cells[b]);
            ghost[a] = side == 0 ? -1 : cells[a] + 1;
            const bool stick = scene_.boundary.faces[2 * a + side] == BoundaryType::Stick;
            Contact c{grid_.node_index(ghost), n, static_cast<int>(k), std::max(gap, 0.0),
                      stick ? o.mu : 0.0};
            c.arm = (x - o.a) + reach * n;
            body_contacts.push_back(c);
          }
      // Against the other obstacles and bodies, each pair of bodies once: a
      // ball's centre against the other's distance, a box's, polygon's or
      // mesh's points against a fixed solid's distance (and the solid's
      // corners against the body's), two such bodies each one's points
      // against the other's distance, and in 3D edges crossing edges.
      for (std::size_t m = 0; m < obstacles.size(); ++m) {
        const Obstacle<D>& q = obstacles[m];
        if (m == k || (q.dynamic && m < k)) continue;
        const bool pointed = o.shape != ObstacleShape::Ball;  // meets by its corners
        if (pointed && q.dynamic && q.shape == ObstacleShape::Ball) {
          against_solid(m, k);  // the ball against this body
          continue;
        }
        against_solid(k, m);
        if (pointed && q.dynamic) against_solid(m, k);
        if (pointed && !q.dynamic) corners_against_body(k, m);
        edges_against(k, m);
      }
    }
    for (const auto& list : obstacle_by_colour) {
      rows += static_cast<int>(list.size());
      P.colour_start.push_back(rows);
    }
  }
  P.first_body_row = std::numeric_limits<int>::max();
  if (!body_contacts.empty()) {
    P.first_body_row = rows;
    rows += static_cast<int>(body_contacts.size());
    P.colour_start.push_back(rows);
    obstacle_by_colour.push_back(std::move(body_contacts));
  }
  P.resize_rows(rows);
  int r = 0;
  for (std::int64_t node : sand_node) {
    P.node[r] = node;
    row_of_node_[node] = r;
    P.coupling[r].setZero();
    ++r;
  }
  obstacle_row_start_ = sand_rows;
  P.first_contact = sand_rows;
  P.contact_frame.clear();
  P.contact_velocity.clear();
  obstacle_index_.clear();
  wall_gap_.clear();
  wall_mu_.clear();
  contact_other_.clear();
  contact_arm_.clear();
  contact_other_arm_.clear();
  const auto node_position = [&](std::int64_t node) {
    const auto nc = grid_.node_coords(node);
    Vec<D> x;
    for (int a = 0; a < D; ++a) x[a] = nc[a] * h;
    return x;
  };
  for (const auto& list : obstacle_by_colour)
    for (const Contact& c : list) {
      contact_arm_.push_back(c.arm);
      contact_other_arm_.push_back(c.other_arm);
      P.node[r] = c.node;
      P.coupling[r].setZero();
      obstacle_index_.push_back(c.which);
      wall_gap_.push_back(c.gap);
      wall_mu_.push_back(c.mu);
      contact_other_.push_back(c.other);
      P.contact_frame.push_back(contact_frame<D>(c.normal));
      // A body's own motion enters through its velocity unknowns instead.
      // Against a solid the roles swap: the row's node stands for the solid
      // and the body for the obstacle, so the node's side moves at
      // -contact_velocity. The solid is given its surface velocity plus
      // gap / dt along n, away from the ball: the ball may close the gap
      // within the step, not pass it.
      P.contact_velocity.push_back(
          c.gap >= 0.0 ? Vec<D>(-c.surface_velocity - (c.gap / dt) * c.normal)
          : obstacles[c.which].dynamic
              ? Vec<D>::Zero()
              : surface_velocity(obstacles[c.which], node_position(c.node)));
      ++r;
    }
  row_solid_ = std::move(solid);
  row_in_solid_ = std::move(in_solid);
  row_mu_sum_.assign(rows, 0.0);
  row_cohesion_sum_.assign(rows, 0.0);

  // Scatter, one cell parity at a time: cells of equal parity share no node,
  // so the sums are race-free and their order is fixed (bit-reproducible).
  // Each particle brings its own material (material.hpp): its density to the
  // mass and momentum, its friction to the row's phi-weighted mean; the
  // grain volume Phi_i and the coupling vectors g_ji take V_p alone.
  const Material* mats = materials_.data();
  for (const auto& cells : cells_by_parity_) {
    const std::int64_t ncells = static_cast<std::int64_t>(cells.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t ci = 0; ci < ncells; ++ci) {
      const std::int64_t c = cells[ci];
      const auto cc = grid_.cell_coords(c);
      const std::int64_t base = grid_.cell_base_node(cc);
      Vec<D> origin;
      for (int a = 0; a < D; ++a) origin[a] = cc[a] * h;
      for (std::int64_t p = cell_start_[c]; p < cell_start_[c + 1]; ++p) {
        const Vec<D>& x = particles_.position[p];
        const Vec<D> local = (x - origin) / h;
        Q1Stencil<D> s = q1_stencil<D>(local, h);
        if (!thin_solids_.empty()) keep_corners<D>(across_[p], s);
        const Material& mp = mats[particles_.material[p]];
        const double vp = particles_.volume[p];
        const double mass_p = mp.mass_ratio * vp;  // rho_p V_p / rho_0
        const double mu_p = mp.friction(particles_.inertial[p]);
        for (int a = 0; a < NC; ++a) {
          const std::int64_t node = base + corner[a];
          const double m = vp * s.w[a];
          const double mass = mass_p * s.w[a];
          Vec<D> offset;  // x_i - x_p
          for (int ax = 0; ax < D; ++ax) offset[ax] = (((a >> ax) & 1) - local[ax]) * h;
          node_grain_volume_[node] += m;
          node_mass_[node] += mass;
          node_momentum_[node] += mass * (particles_.velocity[p] + particles_.affine[p] * offset);
          const int row = row_of_node_[node];
          auto& g = P.coupling[row];
          for (int b = 0; b < NC; ++b) g.col(corner_pair_slot<D>(a, b)) += m * s.grad[b];
          row_mu_sum_[row] += m * mu_p;
          row_cohesion_sum_[row] += m * particles_.cohesion[p];
        }
      }
    }
  }
}

#define SABLIER_INSTANTIATE(D)                   \
  template void Simulation<D>::sort_particles(); \
  template void Simulation<D>::transfer_to_grid(double);
SABLIER_INSTANTIATE(2)
SABLIER_INSTANTIATE(3)
#undef SABLIER_INSTANTIATE

}  // namespace sablier
