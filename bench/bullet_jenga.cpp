// The Jenga pull of docs/benchmarks.md ("3-D: Jenga tower") in Bullet: the
// comparison a user would otherwise make, simulating the tower until it
// settles and judging by how far the other blocks moved.
//
//   bullet_jenga [SCENE] [PLAN] [--dt=S] [--iterations=N] [--threshold=M]
//                [--settle_max=S] [--margin=M] [--guided] [--quiet]
//
// SCENE and PLAN default to examples/jenga.json and
// examples/plans/jenga_pull_l9.plan.json. The scene is read with Cairn's own
// reader, so Bullet gets the same boxes, masses and friction:
//
//  - every part is an axis-aligned box (btBoxShape, its vertices' bounding
//    box), restitution 0, friction √μ on every body (Bullet multiplies the two
//    bodies' coefficients: the pair gets μ), no rolling friction; the collision
//    margin is 0.1 mm (Bullet's default 4 cm is larger than a block's half
//    thickness, 7.5 mm); fixed parts are static; no body ever sleeps
//    (Bullet's sleeping thresholds are sized for metre-sized bodies and would
//    freeze the tower mid-pull);
//  - the pulled part (the plan's one step, one gripped part) is kinematic:
//    its pose is set each step along the plan's path at the plan's speed. A
//    kinematic body carries its own weight and cannot tip (Cairn's support
//    "none" lets it do both), and it cannot give way under a load either, so
//    it takes more of the tower's weight than a dynamic block would. With
//    --guided it is instead a dynamic body whose velocity along the path
//    (a straight path along x, y or z) is set to the plan's speed before
//    every step and which Bullet's impulses cannot change in that direction
//    (its linear factor is 0 there): Cairn's support "none";
//  - phases: the tower first settles from its built pose (until every body is
//    slower than 1 mm/s and 0.01 rad/s for 0.1 s, at most --settle_max s),
//    then the part is pulled along the path, then the tower settles again;
//  - the verdict: unstable when a block other than the pulled one ends more
//    than --threshold (default 1 mm, 1/15 of a block's thickness) from where
//    it was when the pull began, or turned by more than 1°; else stable.
//
// Printed: the settings, each phase's steps and wall time, the largest
// displacement (and which block), the verdict, the first step at which some
// block had moved beyond the threshold (the earliest an "unstable" verdict
// could be called), and the total wall time. Bullet is the Debian package
// (single precision, pkg-config "bullet").

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

btVector3 Bt(const cairn::Vector3& v) {
  return {btScalar(v.x()), btScalar(v.y()), btScalar(v.z())};
}

struct Options {
  std::string scene = std::string(CAIRN_SOURCE_DIR) + "/examples/jenga.json";
  std::string plan = std::string(CAIRN_SOURCE_DIR) + "/examples/plans/jenga_pull_l9.plan.json";
  double dt = 1.0 / 240;
  int iterations = 10;      // Bullet's default solver iterations
  double threshold = 1e-3;  // length (m): what counts as "moved"
  double angle_threshold = M_PI / 180;
  double settle_max = 5.0;  // s
  double margin = 1e-4;     // collision margin (m)
  bool quiet = false;
  bool guided = false;
};

// One Bullet world holding the scene.
struct World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btBoxShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;  // by part index

  ~World() {
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
};

// The largest linear and angular speed of the dynamic bodies.
std::pair<double, double> MaxSpeed(const World& w) {
  double v = 0, omega = 0;
  for (const auto& b : w.bodies) {
    if (b->isStaticOrKinematicObject()) continue;
    v = std::max(v, double(b->getLinearVelocity().length()));
    omega = std::max(omega, double(b->getAngularVelocity().length()));
  }
  return {v, omega};
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  int positional = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&](const char* key) -> const char* {
      const std::string k = std::string(key) + "=";
      return a.rfind(k, 0) == 0 ? argv[i] + k.size() : nullptr;
    };
    if (const char* v = value("--dt"))
      o.dt = std::stod(v);
    else if (const char* v2 = value("--iterations"))
      o.iterations = std::stoi(v2);
    else if (const char* v3 = value("--threshold"))
      o.threshold = std::stod(v3);
    else if (const char* v4 = value("--settle_max"))
      o.settle_max = std::stod(v4);
    else if (const char* v5 = value("--margin"))
      o.margin = std::stod(v5);
    else if (a == "--quiet")
      o.quiet = true;
    else if (a == "--guided")
      o.guided = true;
    else if (a.rfind("--", 0) == 0) {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    } else if (positional++ == 0)
      o.scene = a;
    else
      o.plan = a;
  }

  const auto t_total = Clock::now();
  const cairn::Assembly assembly = cairn::ReadScene(o.scene);
  const cairn::Plan plan = cairn::ReadPlan(o.plan, assembly);
  if (plan.steps.size() != 1 || plan.steps[0].grip.size() != 1) {
    std::fprintf(stderr, "bullet_jenga: the plan must have one step gripping one part\n");
    return 2;
  }
  const cairn::PlanStep& step = plan.steps[0];
  const int pulled = step.grip[0];
  const int n = assembly.num_parts();

  World w;
  w.world.setGravity(Bt(assembly.gravity()));
  w.world.getSolverInfo().m_numIterations = o.iterations;
  std::vector<btVector3> start(n);
  for (int i = 0; i < n; ++i) {
    const cairn::Part& part = assembly.part(i);
    cairn::Vector3 lo = part.vertices[0], hi = lo;
    for (const auto& v : part.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    auto shape = std::make_unique<btBoxShape>(Bt(0.5 * (hi - lo)));
    shape->setMargin(btScalar(o.margin));
    const bool kinematic = i == pulled && !o.guided;
    const btScalar mass = part.fixed || kinematic ? 0 : btScalar(part.mass);
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btTransform pose;
    pose.setIdentity();
    pose.setOrigin(Bt(0.5 * (lo + hi)));
    start[i] = pose.getOrigin();
    auto state = std::make_unique<btDefaultMotionState>(pose);
    btRigidBody::btRigidBodyConstructionInfo info(mass, state.get(), shape.get(), inertia);
    info.m_friction = btScalar(std::sqrt(assembly.Friction(i, i == 0 ? 1 : 0)));
    info.m_restitution = 0;
    auto body = std::make_unique<btRigidBody>(info);
    if (kinematic)
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    if (i == pulled && o.guided) {
      // Impulses move it in every direction but the path's.
      const cairn::Vector3 d = step.At(step.Length()).normalized();
      body->setLinearFactor(btVector3(1, 1, 1) - Bt(d.cwiseAbs()));
    }
    body->setActivationState(DISABLE_DEACTIVATION);
    w.world.addRigidBody(body.get());
    w.shapes.push_back(std::move(shape));
    w.states.push_back(std::move(state));
    w.bodies.push_back(std::move(body));
  }
  std::printf(
      "Bullet %d (%s precision): %d bodies, dt %g s, %d solver iterations, margin %g, μ %g, "
      "threshold %g (and 1°), pulled part %s\n",
      btGetVersion(), sizeof(btScalar) == 8 ? "double" : "single", n, o.dt, o.iterations, o.margin,
      assembly.Friction(1, 2), o.threshold, o.guided ? "guided (dynamic)" : "kinematic");

  int steps = 0;
  // Steps until every dynamic body is slower than 1 mm/s and 0.01 rad/s for
  // 0.1 s (or `max_time`); returns the phase's steps.
  const auto settle = [&](double max_time) {
    int quiet_steps = 0, k = 0;
    const int need = static_cast<int>(std::ceil(0.1 / o.dt));
    for (; k * o.dt < max_time && quiet_steps < need; ++k) {
      w.world.stepSimulation(btScalar(o.dt), 0);
      const auto [v, omega] = MaxSpeed(w);
      quiet_steps = (v < 1e-3 && omega < 1e-2) ? quiet_steps + 1 : 0;
    }
    steps += k;
    return k;
  };
  // How far each non-pulled movable block is from `ref`; the worst one.
  std::vector<btVector3> ref(n);
  std::vector<btQuaternion> ref_q(n);
  const auto snapshot = [&] {
    for (int i = 0; i < n; ++i) {
      ref[i] = w.bodies[i]->getWorldTransform().getOrigin();
      ref_q[i] = w.bodies[i]->getWorldTransform().getRotation();
    }
  };
  struct Worst {
    double distance = 0, angle = 0;
    int part = -1;
  };
  const auto worst = [&] {
    Worst out;
    for (int i = 0; i < n; ++i) {
      if (i == pulled || assembly.part(i).fixed) continue;
      const btTransform& X = w.bodies[i]->getWorldTransform();
      const double d = (X.getOrigin() - ref[i]).length();
      const double angle = std::abs(double(X.getRotation().angleShortestPath(ref_q[i])));
      if (d > out.distance) out.distance = d, out.part = i;
      out.angle = std::max(out.angle, angle);
    }
    return out;
  };

  // 1. Settle the tower as built.
  auto t0 = Clock::now();
  snapshot();
  const int settle1 = settle(o.settle_max);
  const double t_settle1 = Since(t0);
  const Worst drift = worst();
  if (!o.quiet)
    std::printf(
        "settle: %d steps (%.3f s simulated), %.3f s wall; blocks moved up to %.3g m (%s)\n",
        settle1, settle1 * o.dt, t_settle1, drift.distance,
        drift.part >= 0 ? assembly.part(drift.part).name.c_str() : "-");

  // 2. Pull along the path at the plan's speed.
  snapshot();
  t0 = Clock::now();
  const double L = step.Length();
  const int pull_steps = static_cast<int>(std::ceil(L / (plan.speed * o.dt) - 1e-9));
  int first_over = -1;
  for (int k = 1; k <= pull_steps; ++k) {
    const double s = std::min(L, k * plan.speed * o.dt);
    btTransform X;
    X.setIdentity();
    X.setOrigin(start[pulled] + Bt(step.At(s)));
    if (o.guided) {
      // Its velocity along the path is the gripper's; the rest is its own.
      const cairn::Vector3 d = step.At(L).normalized();
      btRigidBody& b = *w.bodies[pulled];
      const btVector3 v = b.getLinearVelocity();
      b.setLinearVelocity(v - Bt(d) * v.dot(Bt(d)) + Bt(d) * btScalar(plan.speed));
    } else {
      w.bodies[pulled]->getMotionState()->setWorldTransform(X);
    }
    w.world.stepSimulation(btScalar(o.dt), 0);
    if (first_over < 0) {
      const Worst now = worst();
      if (now.distance > o.threshold || now.angle > o.angle_threshold) first_over = steps + k;
    }
  }
  steps += pull_steps;
  const double t_pull = Since(t0);
  if (o.guided) w.bodies[pulled]->setLinearFactor(btVector3(1, 1, 1));  // let go
  if (!o.quiet) {
    // Where the blocks are at the end of the pull: the largest displacement
    // of each layer (parts named "Lkk_i"; others each on their own).
    std::vector<std::pair<std::string, double>> groups;
    for (int i = 0; i < n; ++i) {
      if (i == pulled || assembly.part(i).fixed) continue;
      const std::string& name = assembly.part(i).name;
      const std::string group = name.size() == 5 && name[0] == 'L' ? name.substr(0, 3) : name;
      const double d = (w.bodies[i]->getWorldTransform().getOrigin() - ref[i]).length();
      if (groups.empty() || groups.back().first != group) groups.emplace_back(group, 0.0);
      groups.back().second = std::max(groups.back().second, d);
    }
    std::printf("end of the pull, largest displacement per layer (mm):");
    for (const auto& [g, d] : groups) std::printf(" %s %.2f", g.c_str(), 1e3 * d);
    std::printf("\n");
  }

  // 3. Settle again.
  t0 = Clock::now();
  const int settle2 = settle(o.settle_max);
  const double t_settle2 = Since(t0);
  const Worst end = worst();
  const bool unstable = end.distance > o.threshold || end.angle > o.angle_threshold;
  const double total = Since(t_total);
  std::string moved;
  int n_moved = 0;
  for (int i = 0; i < n; ++i) {
    if (i == pulled || assembly.part(i).fixed) continue;
    const btTransform& X = w.bodies[i]->getWorldTransform();
    if ((X.getOrigin() - ref[i]).length() > o.threshold ||
        std::abs(double(X.getRotation().angleShortestPath(ref_q[i]))) > o.angle_threshold) {
      ++n_moved;
      if (n_moved <= 30) moved += (moved.empty() ? "" : " ") + assembly.part(i).name;
    }
  }
  if (!o.quiet) {
    std::printf("pull: %d steps (%.3f s simulated), %.3f s wall\n", pull_steps, pull_steps * o.dt,
                t_pull);
    std::printf("settle: %d steps (%.3f s simulated), %.3f s wall\n", settle2, settle2 * o.dt,
                t_settle2);
  }
  std::printf(
      "verdict: %s; largest displacement since the pull began %.3g m (%s), largest rotation "
      "%.3g°; first over the threshold at step %d (%.3f s after the start of the pull)\n",
      unstable ? "UNSTABLE" : "stable", end.distance,
      end.part >= 0 ? assembly.part(end.part).name.c_str() : "-", end.angle * 180 / M_PI,
      first_over, first_over < 0 ? -1.0 : (first_over - settle1) * o.dt);
  std::printf("blocks beyond the threshold: %d%s%s\n", n_moved, n_moved ? ": " : "", moved.c_str());
  std::printf(
      "total: %d steps, %.3f s wall (settle %.3f, pull %.3f, settle %.3f; the rest is reading)\n",
      steps, total, t_settle1, t_pull, t_settle2);
  return 0;
}
