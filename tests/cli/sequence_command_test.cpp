// `cairn sequence` end to end: build orders with the fewest holds
// (planning/sequence.h, docs/sequence.md).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "cli/cli_run.h"
#include "test_paths.h"

namespace cairn {
namespace {

using json = nlohmann::json;
using testing::ExamplePath;
using testing::SharedDir;

json Sequence(const std::string& args, int expected_exit = 0) {
  const CliRun r = Cairn("sequence " + args + " --json");
  EXPECT_EQ(r.exit_code, expected_exit) << r.err;
  return r.exit_code == 0 || r.exit_code == 1 ? json::parse(r.out) : json();
}

// A semicircular arch of n voussoirs (inner radius 1, outer 1.15: thicker
// than the least thickness of a semicircular arch, 0.107 R) on two fixed
// springers, μ 0.6; each voussoir a quadrilateral between its radial joints.
json Arch(int n) {
  const double ri = 1, ro = 1.15;
  json parts = json::array();
  parts.push_back({{"name", "left springer"},
                   {"fixed", true},
                   {"box", {{"min", {-ro - 0.5, -1}}, {"max", {-ri, 0}}}}});
  parts.push_back({{"name", "right springer"},
                   {"fixed", true},
                   {"box", {{"min", {ri, -1}}, {"max", {ro + 0.5, 0}}}}});
  for (int k = 0; k < n; ++k) {
    const double t0 = std::numbers::pi * (1 - double(k) / n);
    const double t1 = std::numbers::pi * (1 - double(k + 1) / n);
    // Counter-clockwise: inner t0, inner t1, outer t1, outer t0 (t0 > t1).
    const json polygon = {{ri * std::cos(t0), ri * std::sin(t0)},
                          {ro * std::cos(t0), ro * std::sin(t0)},
                          {ro * std::cos(t1), ro * std::sin(t1)},
                          {ri * std::cos(t1), ri * std::sin(t1)}};
    parts.push_back({{"name", "v" + std::to_string(k + 1)}, {"polygon", polygon}});
  }
  return {
      {"cairn", 1}, {"name", "arch of " + std::to_string(n)}, {"friction", 0.6}, {"parts", parts}};
}

std::string ArchFile(int n, bool reversed = false) {
  json doc = Arch(n);
  if (reversed) {
    json parts = json::array();
    for (auto it = doc["parts"].rbegin(); it != doc["parts"].rend(); ++it) parts.push_back(*it);
    doc["parts"] = parts;
  }
  return TempFile("arch" + std::to_string(n) + (reversed ? "_reversed" : "") + ".json", doc.dump());
}

// Every state of the order checked again by `cairn check` (a fresh analysis,
// no cache, no warm start): the scene with the parts not yet placed left out
// the held ones fixed and the props as fixels.
void EveryStateStands(const json& scene, const json& sequence) {
  std::set<std::string> placed, held;
  for (const json& step : sequence["steps"]) {
    placed.insert(step["place"].get<std::string>());
    held.clear();
    json state = scene;
    state["fixtures"] = json::array();
    for (const json& t : step["temporary_in_place"]) {
      if (t["kind"] == "hold")
        held.insert(t["part"].get<std::string>());
      else
        state["fixtures"].push_back(
            {{"part", t["part"]}, {"point", t["point"]}, {"normal", t["normal"]}});
    }
    json parts = json::array();
    for (json p : scene["parts"]) {
      const std::string name = p["name"];
      if (p.value("fixed", false) || placed.count(name)) {
        if (held.count(name)) p["fixed"] = true;
        parts.push_back(p);
      }
    }
    state["parts"] = parts;
    const std::string file = TempFile("state.json", state.dump());
    const CliRun r = Cairn("check " + file);
    EXPECT_EQ(r.exit_code, 0) << "after placing " << step["place"] << ": " << r.out;
  }
}

// A prism of `section` ((y, z) points counter-clockwise seen from +x) from
// x0 to x1 along its channel, the channel turned by theta about z.
json Prism(const std::string& name, const std::vector<std::pair<double, double>>& section,
           double x0, double x1, double theta, bool fixed) {
  const double c = std::cos(theta), s = std::sin(theta);
  json vertices = json::array(), faces = json::array();
  const int n = static_cast<int>(section.size());
  for (const double x : {x0, x1})
    for (const auto& [y, z] : section) vertices.push_back({c * x - s * y, s * x + c * y, z});
  json cap0 = json::array(), cap1 = json::array();
  for (int i = n - 1; i >= 0; --i) cap0.push_back(i);
  for (int i = 0; i < n; ++i) cap1.push_back(n + i);
  faces.push_back(cap0);
  faces.push_back(cap1);
  for (int i = 0; i < n; ++i) faces.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
  json part = {{"name", name}, {"polyhedron", {{"vertices", vertices}, {"faces", faces}}}};
  if (fixed) part["fixed"] = true;
  return part;
}

// An interlocking puzzle of 24 parts: 12 dovetail channels in a fixed base,
// at 15 + 30 k degrees (none along an axis), each with an inner and an outer
// slider. A slider is wider at the bottom than between its rails' overhangs
// and rests against the end stop at the hub: its only free direction is
// straight out along its channel; the outer slider blocks the inner one.
constexpr int kChannels = 12;
double ChannelAngle(int k) { return (15.0 + 30.0 * k) * std::numbers::pi / 180; }

std::string Puzzle() {
  const std::vector<std::pair<double, double>>
      slider = {{-0.5, 0}, {0.5, 0}, {0.3, 0.4}, {-0.3, 0.4}},
      left = {{-0.9, 0}, {-0.5, 0}, {-0.3, 0.4}, {-0.9, 0.4}},
      right = {{0.5, 0}, {0.9, 0}, {0.9, 0.4}, {0.3, 0.4}},
      stop = {{-0.9, 0}, {0.9, 0}, {0.9, 0.4}, {-0.9, 0.4}};
  json parts = json::array();
  parts.push_back({{"name", "ground"},
                   {"fixed", true},
                   {"box", {{"min", {-10, -10, -1}}, {"max", {10, 10, 0}}}}});
  for (int k = 0; k < kChannels; ++k) {
    const double th = ChannelAngle(k);
    const std::string K = std::to_string(k);
    parts.push_back(Prism("rail" + K + "L", left, 5, 7, th, true));
    parts.push_back(Prism("rail" + K + "R", right, 5, 7, th, true));
    parts.push_back(Prism("stop" + K, stop, 4.7, 5, th, true));
    parts.push_back(Prism("in" + K, slider, 5, 6, th, false));
    parts.push_back(Prism("out" + K, slider, 6, 7, th, false));
  }
  const json scene = {{"cairn", 1},
                      {"name", "radial dovetail puzzle"},
                      {"friction", 0.3},
                      {"gravity", {0, 0, -9.81}},
                      {"parts", parts}};
  return TempFile("puzzle.json", scene.dump());
}

// From above or along the axes nothing can go in; along the NDBG's cells
// every slider comes in along its own channel, the inner one before the
// outer one, with no support. Each arrival is checked again by `cairn
// blocking` at that direction with the parts not yet placed taken away: the
// part can leave along its reverse (the NDBG computed afresh for the state).
TEST(Sequence, InterlockingPuzzleArrivesAlongTheNdbgsCells) {
  const std::string puzzle = Puzzle();
  for (const char* directions : {"up", "axes"}) {
    const json s = Sequence(puzzle + " --directions " + directions, 1);
    EXPECT_EQ(s["complete"], false) << directions;
    EXPECT_EQ(s["order"].size(), 0u) << directions;
  }
  const json s = Sequence(puzzle + " --directions ndbg");
  ASSERT_EQ(s["complete"], true);
  ASSERT_EQ(s["order"].size(), 2u * kChannels);
  EXPECT_EQ(s["temporary"]["max_in_place"], 0);
  EXPECT_EQ(s["temporary"]["optimal"], true);
  std::set<std::string> unplaced;
  for (const json& p : s["order"]) unplaced.insert(p.get<std::string>());
  for (const json& step : s["steps"]) {
    const std::string part = step["place"];
    unplaced.erase(part);
    const int k = std::stoi(part.substr(part[0] == 'i' ? 2 : 3));
    if (part[0] == 'o') {
      EXPECT_FALSE(unplaced.count("in" + std::to_string(k))) << part;  // the inner one first
    }
    // Inward along its channel.
    const std::vector<double> d = step["direction"];
    EXPECT_NEAR(d[0], -std::cos(ChannelAngle(k)), 1e-9) << part;
    EXPECT_NEAR(d[1], -std::sin(ChannelAngle(k)), 1e-9) << part;
    EXPECT_NEAR(d[2], 0, 1e-9) << part;
    std::string without;
    for (const std::string& u : unplaced) without += (without.empty() ? "" : ",") + u;
    char away[96];
    std::snprintf(away, sizeof away, "%.17g,%.17g,%.17g", -d[0], -d[1], -d[2]);
    const CliRun b = Cairn("blocking " + puzzle + " --direction " + away + " --json" +
                           (without.empty() ? "" : " --without " + without));
    ASSERT_EQ(b.exit_code, 0) << b.err;
    const json removable = json::parse(b.out)["cells"][0]["removable"];
    EXPECT_NE(std::find(removable.begin(), removable.end(), part), removable.end())
        << part << " cannot leave along " << away;
  }
}

// Every state of the order checked again by `cairn check` on the model as
// read (`model_args`): the parts not yet placed taken away (--without), the
// held ones fixed (--fixed). A fresh analysis: no cache, no warm start.
void EveryStateStandsByCheck(const std::string& model_args, const json& sequence) {
  std::set<std::string> unplaced;
  for (const json& p : sequence["order"]) unplaced.insert(p.get<std::string>());
  for (const json& step : sequence["steps"]) {
    unplaced.erase(step["place"].get<std::string>());
    std::string without, held;
    for (const std::string& p : unplaced) without += (without.empty() ? "" : ",") + p;
    for (const json& t : step["temporary_in_place"])
      held += (held.empty() ? "" : ",") + t["part"].get<std::string>();
    const CliRun r =
        Cairn("check " + model_args + (without.empty() ? "" : " --without " + without) +
              (held.empty() ? "" : " --fixed " + held));
    EXPECT_EQ(r.exit_code, 0) << "after placing " << step["place"] << ": " << r.out << r.err;
  }
}

// `--emit-plans`: the order written as an assembly plan, which `cairn
// simulate` runs stable on the same model (its holds and props in place as
// the plan says); with every support taken out of the plan, the simulation
// fails where the order needed one (`needs_supports`), and a plan with no
// supports says nothing.
void EmittedPlanSimulates(const std::string& model_args, const std::string& options,
                          bool needs_supports) {
  static int run = 0;
  const std::string dir = TempDir("emitted_plans_" + std::to_string(run++));
  std::filesystem::remove_all(dir);
  const CliRun seq = Cairn("sequence " + model_args + " " + options + " --emit-plans " + dir);
  ASSERT_EQ(seq.exit_code, 0) << seq.err;
  const std::string plan = dir + "/sequence.assemble.plan.json";
  const CliRun sim = Cairn("simulate " + model_args + " " + plan + " --json");
  EXPECT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  json doc = json::parse(Slurp(plan));
  EXPECT_EQ(doc["mode"], "assemble");
  bool any = false;
  for (json& step : doc["steps"])
    for (const char* key : {"hold", "hold_at_rest", "props", "props_at_rest"}) {
      any = any || !step.value(key, json::array()).empty();
      step[key] = json::array();
    }
  EXPECT_EQ(any, needs_supports);
  if (!needs_supports) return;
  const std::string bare = TempFile("plan_without_supports.json", doc.dump());
  const CliRun fails = Cairn("simulate " + model_args + " " + bare + " --json");
  EXPECT_EQ(fails.exit_code, 1) << fails.out << fails.err;
}

// The 3-voussoir arch: no voussoir stands alone on a springer (each leans
// inward past its joint's inner edge), so every order needs a hold from its
// first step: the lower bound 1. Arriving from above only, the keystone v2
// must come last (it locks v1 and v3 in: their joints with it face up), so
// both halves stand held: 2 at once, and trying every order of the three
// (the exhaustive bound) proves no order from above does with fewer. With
// the axes, v3 can come in
// sideways after v2: v1 held, v2 held and v1 released (v1 between its
// springer and v2 stands), v3 from the side closes the arch: 1, optimal.
TEST(Sequence, ArchOfThreeVoussoirsNeedsOneHoldAndTheBoundProvesIt) {
  const std::string file = ArchFile(3);
  const json up = Sequence(file);
  EXPECT_EQ(up["complete"], true);
  EXPECT_EQ(up["temporary"]["max_in_place"], 2);
  EXPECT_EQ(up["temporary"]["lower_bound"], 2);
  EXPECT_EQ(up["temporary"]["optimal"], true);
  EXPECT_NE(up["temporary"]["lower_bound_reason"].get<std::string>().find("every order"),
            std::string::npos);
  EXPECT_EQ(up["order"].back(), "v2");

  const json axes = Sequence(file + " --directions axes");
  EXPECT_EQ(axes["complete"], true);
  EXPECT_EQ(axes["temporary"]["max_in_place"], 1);
  EXPECT_EQ(axes["temporary"]["lower_bound"], 1);
  EXPECT_EQ(axes["temporary"]["optimal"], true);
  EXPECT_EQ(axes["order"], json({"v1", "v2", "v3"}));
  EXPECT_EQ(axes["steps"][2]["direction"], json({-1.0, 0.0}));
  EveryStateStands(Arch(3), axes);
  // What the hold carries balances the held part: at step 1, v1's weight
  // and the springer's push (the springer is fixed, so not counted): its
  // weight alone, upward.
  const json& hold = axes["steps"][0]["temporary_in_place"][0];
  EXPECT_EQ(hold["part"], "v1");
  EXPECT_GT(hold["force"][1].get<double>(), 0);

  EmittedPlanSimulates(file, "--directions axes", true);
  EmittedPlanSimulates(file, "", true);

  // No support allowed: no order, and no plan of part of one.
  const std::string dir = TempDir("no_plan");
  std::filesystem::remove_all(dir);
  const json none = Sequence(file + " --directions axes --max-temporary 0 --emit-plans " + dir, 1);
  EXPECT_EQ(none["complete"], false);
  EXPECT_NE(none["message"].get<std::string>().find("at most 0"), std::string::npos);
  EXPECT_NE(none["message"].get<std::string>().find("no plan written"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir + "/sequence.assemble.plan.json"));
}

// Props (`--temporary prop`), the centering of the 3-voussoir arch derived by
// hand. v1 (between 180° and 120°, radii 1 and 1.15) rests on the left
// springer's top across x ∈ [−1.15, −1]; its centroid, at radius
// r̄ = (2/3)(1.15³ − 1)/(1.15² − 1) · sin(π/6)/(π/6) on the 150° ray, lies at
// x_c = r̄ cos 150° = −0.890, inward of the joint's inner edge (−1, 0): alone
// it tips inward about that edge. About it the springer's pushes (at the
// edge, or at −1.15 turning the same way) and friction (along the joint) can
// only add to the weight's clockwise moment W (x_c + 1); a prop pushing
// along n at p must undo it: P (p − e) × n ≥ W (x_c + 1), P ≥ P_min. So
// each side voussoir needs a prop of its own, the keystone (locking both
// from above) comes last, and two props are in place at once: the bound (a
// hold does what any props on its part can, and two holds are the fewest:
// ArchOfThree...) proves it. Every prop sits on its voussoir's intrados,
// pushes outward along the intrados' normal and carries at least P_min.
TEST(Sequence, ArchOfThreeVoussoirsNeedsTwoPropsAsDerivedByHand) {
  const std::string file = ArchFile(3);
  const json s = Sequence(file + " --temporary prop");
  EXPECT_EQ(s["complete"], true);
  EXPECT_EQ(s["order"], json({"v1", "v3", "v2"}));
  EXPECT_EQ(s["temporary"]["kinds"], json({"prop"}));
  EXPECT_EQ(s["temporary"]["max_in_place"], 2);
  EXPECT_EQ(s["temporary"]["lower_bound"], 2);
  EXPECT_EQ(s["temporary"]["optimal"], true);
  const double pi = std::numbers::pi, ri = 1, ro = 1.15, g = 9.81;
  const double weight = g * (pi / 3) / 2 * (ro * ro - ri * ri);  // density 1
  const double rbar = 2.0 / 3 * (ro * ro * ro - 1) / (ro * ro - 1) * std::sin(pi / 6) / (pi / 6);
  const double lever = rbar * std::cos(5 * pi / 6) + 1;  // x_c − (−1): 0.1095
  ASSERT_GT(lever, 0) << "v1 leans inward of its joint";
  std::set<std::string> propped;
  for (const json& step : s["steps"])
    for (const json& t : step["temporary_in_place"]) {
      const std::string part = t["part"];
      SCOPED_TRACE(part + " after placing " + step["place"].get<std::string>());
      propped.insert(part);
      EXPECT_EQ(t["kind"], "prop");
      // Mirrored for v3 (x → −x).
      const double side = part == "v1" ? 1 : -1;
      const double px = side * t["point"][0].get<double>(), py = t["point"][1];
      const double nx = side * t["normal"][0].get<double>(), ny = t["normal"][1];
      // On v1's intrados, the chord from (−1, 0) to (−0.5, 0.866), pushing
      // along its normal away from the arch's centre.
      EXPECT_NEAR((px + 1) * std::sin(pi / 3) - py * 0.5, 0, 1e-9);
      EXPECT_NEAR(nx, -std::cos(pi / 6), 1e-9);
      EXPECT_NEAR(ny, std::sin(pi / 6), 1e-9);
      const double arm = (px + 1) * ny - py * nx;  // (p − e) × n
      ASSERT_GT(arm, 0) << "the prop turns v1 back";
      const double fx = side * t["force"][0].get<double>(), fy = t["force"][1];
      const double force = std::hypot(fx, fy);
      EXPECT_NEAR(fx * ny - fy * nx, 0, 1e-9 * (1 + force)) << "a prop pushes along its normal";
      EXPECT_GE(force, weight * lever / arm * (1 - 1e-9));
    }
  EXPECT_EQ(propped, (std::set<std::string>{"v1", "v3"}));
  // v1 on its own: falls without its prop, stands with it (cairn check of
  // the scene with the prop as a fixel).
  json alone = Arch(3);
  alone["parts"].erase(4);  // v3
  alone["parts"].erase(3);  // v2
  const json& prop = s["steps"][0]["added"][0];
  EXPECT_EQ(Cairn("check " + TempFile("v1_alone.json", alone.dump())).exit_code, 1);
  alone["fixtures"] = {{{"part", "v1"}, {"point", prop["point"]}, {"normal", prop["normal"]}}};
  EXPECT_EQ(Cairn("check " + TempFile("v1_propped.json", alone.dump())).exit_code, 0);
  EmittedPlanSimulates(file, "--temporary prop", true);
}

// Both kinds: never more supports at once than holds alone; the search
// weighs a hold that carries a growing cantilever against props that each
// carry one part (a prop under the last voussoir of a half arch does not
// keep the ones before it up).
TEST(Sequence, HoldsAndPropsTogetherNeedNoMoreThanHolds) {
  for (const std::string& file : {ArchFile(3), ArchFile(7)})
    for (const std::string directions : {"up", "axes"}) {
      SCOPED_TRACE(file + " " + directions);
      const json hold = Sequence(file + " --directions " + directions);
      const json both = Sequence(file + " --directions " + directions + " --temporary both");
      EXPECT_EQ(both["temporary"]["kinds"], json({"hold", "prop"}));
      EXPECT_LE(both["temporary"]["max_in_place"], hold["temporary"]["max_in_place"]);
      EXPECT_EQ(both["temporary"]["optimal"], true);
      EveryStateStands(Arch(file.find("arch7") != std::string::npos ? 7 : 3), both);
    }
}

// Seven voussoirs: v1 and v7 stand alone on their springers, but no arch
// missing one voussoir stands, so the state before the last needs a hold
// (the bound 1); one hold moved up voussoir by voussoir reaches it.
TEST(Sequence, ArchOfSevenVoussoirsNeedsOneHold) {
  const json axes = Sequence(ArchFile(7) + " --directions axes");
  EXPECT_EQ(axes["complete"], true);
  EXPECT_EQ(axes["temporary"]["max_in_place"], 1);
  EXPECT_EQ(axes["temporary"]["lower_bound"], 1);
  EXPECT_EQ(axes["temporary"]["optimal"], true);
  EveryStateStands(Arch(7), axes);
  // From above only, the keystone goes last: each half stands held, 2 at
  // once, and every order of the 7 tried (the exhaustive bound) proves it.
  const json up = Sequence(ArchFile(7));
  EXPECT_EQ(up["complete"], true);
  EXPECT_EQ(up["temporary"]["max_in_place"], 2);
  EXPECT_EQ(up["temporary"]["lower_bound"], 2);
  EXPECT_EQ(up["temporary"]["optimal"], true);
  EXPECT_EQ(up["order"].back(), "v4");
  EveryStateStands(Arch(7), up);
}

// A stack of boxes and the wall of examples/: no support, optimal.
TEST(Sequence, StackAndWallNeedNoSupport) {
  for (const std::string name : {"stack3.json", "wall.json", "pyramid10.json"}) {
    SCOPED_TRACE(name);
    const json s = Sequence(ExamplePath(name) + " --beam 1");
    EXPECT_EQ(s["complete"], true);
    EXPECT_EQ(s["temporary"]["max_in_place"], 0);
    EXPECT_EQ(s["temporary"]["optimal"], true);
    for (const json& step : s["steps"]) {
      EXPECT_EQ(step["verdict"], "stands");
      EXPECT_TRUE(step["temporary_in_place"].empty());
    }
    if (name != "wall.json") EmittedPlanSimulates(ExamplePath(name), "--beam 1", false);
  }
}

// The same document for 1 and 2 threads (with both kinds of support the
// searches with holds alone and with both run side by side; with one, the
// order's states are confirmed on both threads) and every core (but the
// seconds).
TEST(Sequence, DeterministicWhateverTheThreads) {
  const auto doc = [](const std::string& args) {
    json d = Sequence(args);
    d["stats"].erase("seconds");
    return d;
  };
  for (const std::string& model :
       {ArchFile(7) + " --directions axes", ArchFile(3), ExamplePath("paper_fig17.json")}) {
    SCOPED_TRACE(model);
    const json one = doc(model + " --temporary both --threads 1");
    EXPECT_EQ(one, doc(model + " --temporary both --threads 2"));
    EXPECT_EQ(one, doc(model + " --temporary both"));
    EXPECT_EQ(one["temporary"]["kinds"], json({"hold", "prop"}));
  }
  for (const std::string& model :
       {ArchFile(7) + " --directions axes", ExamplePath("pyramid14.json")}) {
    SCOPED_TRACE(model);
    EXPECT_EQ(doc(model + " --threads 1"), doc(model + " --threads 2"));
  }
}

// The same document for the parts given in another order, and run after run
// (but the seconds).
TEST(Sequence, DeterministicWhateverThePartsOrder) {
  json a = Sequence(ArchFile(7) + " --directions axes");
  json b = Sequence(ArchFile(7, true) + " --directions axes");
  json c = Sequence(ArchFile(7) + " --directions axes");
  for (json* d : {&a, &b, &c}) {
    (*d)["stats"].erase("seconds");
    d->erase("scene_file");
  }
  EXPECT_EQ(a, c);
  EXPECT_EQ(a["order"], b["order"]);
  EXPECT_EQ(a["steps"], b["steps"]);
  EXPECT_EQ(a["temporary"], b["temporary"]);
  // Props too: the same points, whatever the order of the parts.
  const json p = Sequence(ArchFile(7) + " --temporary prop");
  const json q = Sequence(ArchFile(7, true) + " --temporary prop");
  EXPECT_EQ(p["order"], q["order"]);
  EXPECT_EQ(p["steps"], q["steps"]);
}

TEST(Sequence, BadInputExitsTwo) {
  const std::string file = ArchFile(3);
  for (const std::string& bad :
       std::vector<std::string>{"--temporary crane", "--direction 0,0", "--direction 1,0,1",
                                "--max-temporary -1", "--beam 0", "--directions sideways",
                                "--threads -1", "--html /", "--emit-plans " + file}) {
    const CliRun r = Cairn("sequence " + file + " " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_FALSE(r.err.empty()) << bad;
  }
}

// An assembly that does not stand has no build order: the message names
// what moves, and says when nothing is fixed; no bound is claimed.
TEST(Sequence, AnAssemblyThatFallsHasNoOrderAndSaysWhy) {
  const json tips = Sequence(ExamplePath("overhang_tips.json"), 1);
  EXPECT_EQ(tips["complete"], false);
  EXPECT_NE(
      tips["message"].get<std::string>().find("the assembly itself does not stand (block moves)"),
      std::string::npos)
      << tips["message"];
  EXPECT_EQ(tips["message"].get<std::string>().find("nothing is fixed"), std::string::npos);
  EXPECT_EQ(tips["temporary"]["lower_bound_reason"],
            "no order exists: the assembly itself does not stand");
  json loose = Arch(3);
  for (json& p : loose["parts"]) p["fixed"] = false;
  const json none = Sequence(TempFile("nothing_fixed.json", loose.dump()), 1);
  EXPECT_NE(none["message"].get<std::string>().find("nothing is fixed"), std::string::npos)
      << none["message"];
}

// Anytime: at --time-limit the best order so far, its states checked, with
// its bound, --json included (a millisecond ends the search before its first
// placement: the assembled wall's own check takes longer).
TEST(Sequence, TimeLimitGivesTheBestOrderSoFar) {
  const json s = Sequence(ExamplePath("wall.json") + " --time-limit 0.001", 1);
  EXPECT_EQ(s["complete"], false);
  EXPECT_EQ(s["stopped"], true);
  EXPECT_NE(s["message"].get<std::string>().find("time limit"), std::string::npos);
  EXPECT_LT(s["order"].size(), 105u);
  for (const json& step : s["steps"]) EXPECT_EQ(step["verdict"], "stands");
  EXPECT_TRUE(s["temporary"].contains("lower_bound"));
}

// `cairn sequence` on the cross vault sent SIGINT as `signal` says (a shell
// line around "CAIRN", which becomes the command): it ends with the best
// order so far, printed whole (the equilibrium rule: the confirmation of the
// order's states is the LP's, seconds rather than minutes under the
// sanitizers).
void InterruptedRunPrintsTheBestOrder(const std::string& signal) {
  const std::string cairn = testing::CliPath() + " sequence " + SharedDir() +
                            "/datasets/compas_assembly/crossvault_assembly.json --format compas "
                            "--friction 0.84 --rule equilibrium --json";
  std::string line = signal;
  line.replace(line.find("CAIRN"), 5, cairn);
  const CliRun r = testing::RunCommand(line);
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const json s = json::parse(r.out);
  EXPECT_EQ(s["stopped"], true);
  EXPECT_EQ(s["complete"], false);
  EXPECT_NE(s["message"].get<std::string>().find("stopped"), std::string::npos);
}

TEST(Sequence, InterruptGivesTheBestOrderSoFar) {
  if (SharedDir().empty()) GTEST_SKIP() << "../shared (the COMPAS datasets) is absent";
  InterruptedRunPrintsTheBestOrder("timeout --preserve-status -s INT 6 CAIRN");
}

// Two SIGINTs a moment apart (what `timeout -s INT` sends: to the process,
// then to its group) are one request: the document, not a killed process.
TEST(Sequence, TwoInterruptsAMomentApartAreOneRequest) {
  if (SharedDir().empty()) GTEST_SKIP() << "../shared (the COMPAS datasets) is absent";
  InterruptedRunPrintsTheBestOrder(
      "sh -c 'CAIRN & p=$!; sleep 5; kill -INT $p; kill -INT $p; wait $p'");
}

// The 30-block arch of compas_assembly: one hold at once, proved optimal by
// the bound, every state checked again.
TEST(Sequence, CompasArchNeedsOneHold) {
  if (SharedDir().empty()) GTEST_SKIP() << "../shared (the COMPAS datasets) is absent";
  const std::string model =
      SharedDir() + "/datasets/compas_assembly/arch_assembly.json --format compas --friction 0.84";
  const json s = Sequence(model + " --directions axes --beam 1");
  EXPECT_EQ(s["complete"], true);
  EXPECT_EQ(s["order"].size(), 28u);
  EXPECT_EQ(s["temporary"]["lower_bound"], 1);
  EXPECT_EQ(s["temporary"]["max_in_place"], 1);
  EXPECT_EQ(s["temporary"]["optimal"], true);
  for (const json& step : s["steps"]) EXPECT_EQ(step["verdict"], "stands");
  EveryStateStandsByCheck(model, s);
  EmittedPlanSimulates(model, "--directions axes --beam 1", true);
}

// The COMPAS wall (stretcher bond on the ground): no support at all, and
// every state checked again.
TEST(Sequence, CompasWallNeedsNoSupport) {
  if (SharedDir().empty()) GTEST_SKIP() << "../shared (the COMPAS datasets) is absent";
  const std::string model =
      SharedDir() + "/datasets/compas_assembly/wall_assembly.json --format compas --friction 0.84";
  const json s = Sequence(model);
  EXPECT_EQ(s["complete"], true);
  EXPECT_EQ(s["temporary"]["max_in_place"], 0);
  EXPECT_EQ(s["temporary"]["optimal"], true);
  EveryStateStandsByCheck(model, s);
  EmittedPlanSimulates(model, "", false);
}

}  // namespace
}  // namespace cairn
