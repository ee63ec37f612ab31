// blocking_report.h: the NDBG as JSON and text say what ComputeNdbg found,
// cell for cell, with the parts by name.
#include "cairn/report/blocking_report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "example_scene.h"

namespace cairn {
namespace {

TEST(NdbgToJson, OneCellPerCellWithItsRemovablePartsByName) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Assembly& a = fig1.assembly;
  const Ndbg ndbg = ComputeNdbg(a, Configuration::Assembled(a));
  ASSERT_FALSE(ndbg.cells.empty());
  const nlohmann::json doc = NdbgToJson(a, ndbg, {});
  EXPECT_EQ(doc["dimension"], 2);
  ASSERT_EQ(doc["cells"].size(), ndbg.cells.size());
  EXPECT_EQ(doc["normals"].size(), ndbg.normals.size());
  for (size_t i = 0; i < ndbg.cells.size(); ++i) {
    const NdbgCell& c = ndbg.cells[i];
    const nlohmann::json& j = doc["cells"][i];
    EXPECT_EQ(j["dimension"], c.cell_dimension);
    ASSERT_EQ(j["removable"].size(), c.removable.size());
    for (size_t k = 0; k < c.removable.size(); ++k)
      EXPECT_EQ(j["removable"][k], a.part(c.removable[k]).name);
    size_t arcs = 0;
    for (const std::vector<int>& b : c.infinity.blockers) arcs += b.size();
    EXPECT_EQ(j["infinity"].size(), arcs);
  }
  // Paper Fig. 1: straight up, C and D (resting on B, nothing above them) can leave.
  const auto up = std::find_if(ndbg.cells.begin(), ndbg.cells.end(), [](const NdbgCell& c) {
    return c.direction.isApprox(Vector3(0, 1, 0));
  });
  ASSERT_NE(up, ndbg.cells.end());
  EXPECT_EQ(up->removable, (std::vector<int>{a.FindPart("C"), a.FindPart("D")}));
}

TEST(NdbgToText, AThreeLineHeadlineThenOneLinePerCell) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Ndbg ndbg = ComputeNdbg(fig1.assembly, Configuration::Assembled(fig1.assembly));
  std::istringstream text(NdbgToText(fig1.assembly, ndbg, {}));
  std::string line;
  size_t lines = 0;
  while (std::getline(text, line)) ++lines;
  EXPECT_EQ(lines, ndbg.cells.size() + 3);
}

}  // namespace
}  // namespace cairn
