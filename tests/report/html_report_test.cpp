// html_report.h: the page data says what the result says (the scene's
// shapes, each tick's poses and forces), and no text of the scene can break
// out of the page's <script> elements. The pages in a real browser:
// tests/web (web/test/page_test.mjs).
#include "cairn/report/html_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cairn/io/plan_reader.h"
#include "cairn/report/check_report.h"
#include "cairn/report/plan_report.h"
#include "cairn/report/simulation_report.h"
#include "cairn/report/words.h"
#include "example_scene.h"
#include "test_paths.h"

namespace cairn {
namespace {

using nlohmann::json;

// The page data: the text of <script id="cairn-data">, parsed.
json PageData(const std::string& page) {
  const std::string open = "<script id=\"cairn-data\" type=\"application/json\">";
  const size_t from = page.find(open);
  EXPECT_NE(from, std::string::npos);
  const size_t begin = from + open.size();
  const size_t end = page.find("</script>", begin);
  EXPECT_NE(end, std::string::npos);
  return json::parse(page.substr(begin, end - begin));
}

TEST(HtmlPage, NoTextOfTheDataCanEndItsScriptElement) {
  const std::string evil = "</script><script>alert(1)</script><!-- \"'&</SCRIPT >";
  const json data = {{"kind", "check"}, {"title", evil}, {"result", {{"name", evil}}}};
  const std::string page = HtmlPage(data);
  // The data element ends at the first "</script": it must hold all of it.
  EXPECT_EQ(PageData(page), data);
  const size_t body = page.find("<script id=\"cairn-data\"");
  const size_t data_end = page.find("</script>", body);
  EXPECT_EQ(page.substr(body, data_end - body).find('<', 1), std::string::npos)
      << "every '<' of the data is escaped";
  // The title is text.
  EXPECT_NE(page.find("<title>&lt;/script&gt;&lt;script&gt;alert(1)&lt;/script&gt;&lt;!-- "
                      "&quot;'&amp;&lt;/SCRIPT &gt; — cairn check</title>"),
            std::string::npos);
  // Exactly two script elements, neither loading anything.
  size_t scripts = 0;
  for (size_t at = page.find("<script"); at != std::string::npos; at = page.find("<script", at + 1))
    ++scripts;
  EXPECT_EQ(scripts, 2u);
  EXPECT_EQ(page.find(" src="), std::string::npos);
  EXPECT_EQ(page.find(" href="), std::string::npos);
}

TEST(HtmlPage, TheViewerIsEmbeddedWhole) {
  const std::string page = HtmlPage({{"kind", "check"}});
  // The bundle's first and last lines (web/build.mjs writes the banner).
  EXPECT_NE(page.find("/* Cairn viewer; three.js"), std::string::npos);
  EXPECT_NE(page.find("dataset.cairnReady"), std::string::npos)
      << "the viewer sets <body data-cairn-ready>";
  EXPECT_GT(page.size(), 100000u);
}

// 2-D: the outline is the part's polygon, its centroid the part's.
TEST(CheckPage, CarriesTheShapesAndTheCheckDocumentUnchanged) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Assembly& a = fig1.assembly;
  Configuration config = Configuration::Assembled(a);
  config.present[a.FindPart("C")] = false;
  ReportOptions options;
  options.without = {a.FindPart("C")};
  const StabilityResult r = AnalyzeConfiguration(a, config, {});
  const json doc = StabilityToJson(a, config, r, options);
  const json data = PageData(CheckPage(a, doc, CheckStory(a, r), options));
  EXPECT_EQ(data["kind"], "check");
  EXPECT_EQ(data["result"], doc);
  // The story: the parts that move, in the text summary's words.
  EXPECT_EQ(data["story"],
            json::array({"B tips about (1, 1.25) clockwise, because no equilibrium exists",
                         "D tips about (1, 2.5) clockwise, because no equilibrium exists"}));
  const json& parts = data["scene"]["parts"];
  ASSERT_EQ(parts.size(), static_cast<size_t>(a.num_parts()));
  for (int i = 0; i < a.num_parts(); ++i) {
    const Part& p = a.part(i);
    EXPECT_EQ(parts[i]["name"], p.name);
    EXPECT_EQ(parts[i]["fixed"], p.fixed);
    ASSERT_EQ(parts[i]["outline"].size(), p.polygon.size());
    // The shoelace area of the outline is the part's area.
    double area2 = 0;
    const json& o = parts[i]["outline"];
    for (size_t k = 0; k < o.size(); ++k) {
      const json& u = o[k];
      const json& v = o[(k + 1) % o.size()];
      area2 += u[0].get<double>() * v[1].get<double>() - v[0].get<double>() * u[1].get<double>();
    }
    EXPECT_NEAR(std::abs(area2) / 2, p.area, 1e-6 * p.area) << p.name;
  }
}

// 3-D: the triangles cover the surface: the divergence theorem over them
// gives the part's volume.
TEST(CheckPage, TheTrianglesOfA3dPartEncloseItsVolume) {
  const testing::ExampleScene jenga("jenga.json");
  const Assembly& a = jenga.assembly;
  const Configuration config = Configuration::Assembled(a);
  const StabilityResult r = AnalyzeConfiguration(a, config, {});
  const json data = PageData(CheckPage(a, StabilityToJson(a, config, r, {}), {}, {}));
  for (int i = 0; i < a.num_parts(); i += 7) {
    const json& p = data["scene"]["parts"][i];
    const std::vector<double> v = p["vertices"].get<std::vector<double>>();
    const std::vector<int> t = p["triangles"].get<std::vector<int>>();
    ASSERT_EQ(t.size() % 3, 0u);
    double volume6 = 0;  // Σ a · (b × c) over outward triangles = 6 V
    for (size_t k = 0; k < t.size(); k += 3) {
      const Vector3 A(v[3 * t[k]], v[3 * t[k] + 1], v[3 * t[k] + 2]);
      const Vector3 B(v[3 * t[k + 1]], v[3 * t[k + 1] + 1], v[3 * t[k + 1] + 2]);
      const Vector3 C(v[3 * t[k + 2]], v[3 * t[k + 2] + 1], v[3 * t[k + 2] + 2]);
      volume6 += A.dot(B.cross(C));
    }
    EXPECT_NEAR(volume6 / 6, a.part(i).area, 1e-5 * a.part(i).area) << a.part(i).name;
    // A box: 12 edges drawn, each once.
    EXPECT_EQ(p["edges"].size(), 24u) << a.part(i).name;
  }
}

// Every analysed tick is a frame; the gripped part's pose is the path's
// displacement at the frame's time, and the frame's forces are the
// timeline's.
TEST(SimulationPage, OneFramePerTickWithThePosesAndForcesOfThatTick) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Assembly& a = fig1.assembly;
  const Plan plan = ReadPlan(testing::ExamplePath("plans/paper_fig1_dcba.plan.json"), a);
  SimulationOptions options;
  options.record_timeline = true;
  std::vector<SimulationFrame> frames;
  options.on_analysis = [&](const AnalysisInputs& in) {
    if (in.judged)
      frames.push_back({in.step, in.tick, in.time, in.config->present, in.config->poses, {}});
  };
  const SimulationResult result = SimulatePlan(a, plan, options);
  ASSERT_TRUE(result.stable());
  const json doc = SimulationToJson(a, plan, result, {});
  const json data = PageData(SimulationPage(a, result, frames, doc, "", {}));
  const json& pf = data["frames"];
  ASSERT_EQ(pf.size(), frames.size());
  int ticks = 0;
  for (const MotionStepReport& s : result.steps) ticks += s.ticks;
  EXPECT_EQ(pf.size(), static_cast<size_t>(ticks));
  for (size_t k = 0; k < pf.size(); ++k) {
    const PlanStep& step = plan.steps[pf[k]["step"].get<int>()];
    const double t0 = result.steps[pf[k]["step"].get<int>()].start_time;
    const Vector3 want = step.At(plan.speed * (pf[k]["time"].get<double>() - t0));
    // The gripped part: moved by the path (or, at s = 0, not listed).
    const int gripped = step.grip[0];
    Vector3 got = Vector3::Zero();
    for (const json& pose : pf[k]["poses"])
      if (pose[0] == gripped)
        got = Vector3(pose[1].get<double>(), pose[2].get<double>(), pose[3].get<double>());
    EXPECT_LT((got - want).norm(), 1e-6) << "frame " << k;
    // The forces of the tick: the timeline's, in the same order.
    double page_sum = 0, timeline_sum = 0;
    for (const json& c : pf[k]["contacts"]) page_sum += c["normal_force"].get<double>();
    for (const TimelineRow& row : result.timeline)
      if (row.step == pf[k]["step"] && row.tick == pf[k]["tick"])
        timeline_sum += row.contact.normal_force;
    EXPECT_NEAR(page_sum, timeline_sum, 1e-6 * (1 + timeline_sum)) << "frame " << k;
  }
}

// The page counts a plan's steps from 1 everywhere: the viewer writes
// "Step k + 1" for the step of index k (steps[].index) and "step k + 1"
// beside the time of a frame (frames[].step), and the failure's words, shown
// as they are, say the same number (paper Fig. 1 with B first fails in the
// first step, index 0).
TEST(SimulationPage, TheFailuresWordsCountStepsFromOneAsTheViewerDoes) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Assembly& a = fig1.assembly;
  const Plan plan = ReadPlan(testing::ExamplePath("plans/paper_fig1_b_first.plan.json"), a);
  std::vector<SimulationFrame> frames;
  SimulationOptions options;
  options.on_analysis = [&](const AnalysisInputs& in) {
    if (in.judged)
      frames.push_back({in.step, in.tick, in.time, in.config->present, in.config->poses, {}});
  };
  const SimulationResult result = SimulatePlan(a, plan, options);
  ASSERT_TRUE(result.failure);
  const json doc = SimulationToJson(a, plan, result, {});
  const json data = PageData(SimulationPage(a, result, frames, doc, "", {}));
  const json& failure = data["result"]["failure"];
  ASSERT_EQ(failure["step"], 0);  // an index, as steps[].index and frames[].step
  EXPECT_EQ(data["result"]["steps"][0]["index"], 0);
  EXPECT_EQ(data["frames"][0]["step"], 0);
  EXPECT_EQ(failure["description"].get<std::string>().rfind("t = 0 s (step 1, tick 0): ", 0), 0u)
      << failure["description"];
  EXPECT_NE(SimulationToText(a, plan, result, {}).find("\n  step 1 (B, support "),
            std::string::npos);
}

// The rest state of every node of the listed sequences: the forces at each
// node balance the weights of its parts (frictionless Fig. 1: the vertical
// normal forces on the fixed table E carry every present block).
TEST(PlanPage, EveryNodeOfTheListedSequencesCarriesItsWeight) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Assembly& a = fig1.assembly;
  PlannerOptions options;
  options.threads = 1;
  const PlannerResult r = PlanDisassembly(fig1.def, a, options);
  ASSERT_FALSE(r.sequences.empty());
  const json data = PageData(PlanPage(a, r, PlannerToJson(a, r, "fig1"), {}));
  EXPECT_EQ(data["plan"]["sequences_shown"], r.sequences.size());
  ASSERT_FALSE(data["plan"]["nodes"].empty());
  for (const auto& [key, c] : data["plan"]["nodes"].items()) {
    double weight = 0;
    for (size_t at = 0; at <= key.size();) {
      const size_t comma = std::min(key.find(',', at), key.size());
      const int i = std::stoi(key.substr(at, comma - at));
      if (!a.part(i).fixed) weight += a.part(i).mass * a.gravity().norm();
      at = comma + 1;
    }
    double on_table = 0;  // the table's push on the blocks (b = E) and theirs on it (a = E)
    for (const json& k : c) {
      const double up = k["normal"][1].get<double>() * k["normal_force"].get<double>();
      if (k["parts"][1] == "E") on_table += up;
      if (k["parts"][0] == "E") on_table -= up;
    }
    EXPECT_NEAR(on_table, weight, 1e-6 * weight) << "node " << key;
  }
}

}  // namespace
}  // namespace cairn
