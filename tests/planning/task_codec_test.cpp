// planning/task_codec.h: a planner task's result travels between processes
// bit for bit (doubles as their bits: −0, subnormals, NaN's payload), and
// bytes cut short or corrupt are refused, never read past their end.
#include "planning/task_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace cairn::planning_codec {
namespace {

// The bits of a double, so that NaN and −0 compare exactly.
uint64_t Bits(double x) {
  uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

void ExpectSameBits(const Vector3& a, const Vector3& b) {
  for (int k = 0; k < 3; ++k) EXPECT_EQ(Bits(a[k]), Bits(b[k])) << k;
}

// A failure with every field set, and doubles no decimal form round-trips
// by accident.
MotionFailure AwkwardFailure() {
  Contact c;
  c.part_a = 3;
  c.part_b = kWorld;
  c.p_WC = {1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min()};
  c.n_W = {0.6, 0.8, 0.0};
  c.gap = -1e-300;
  c.mu = 0.1 + 0.2;
  c.feature = ContactFeature::kFaceFace;
  c.index_a = 7, c.index_b = 11, c.patch = 2;
  ContactReport r;
  r.contact = c;
  r.component = 1;
  r.normal_force = std::nextafter(1.0, 2.0);
  r.friction_force = {std::numeric_limits<double>::quiet_NaN(), 1e308, -1e-308};
  r.normal_motion = -std::numeric_limits<double>::infinity();
  r.tangent_motion = {0.1, 0.2, 0.3};
  r.breaking = true;
  PartMotion m;
  m.part = 3;
  m.role = PartRole::kCarried;
  m.component = 1;
  m.moving = true;
  m.kind = MotionKind::kTips;
  m.linear = {1e-17, 2, 3};
  m.angular = {0, 0, M_PI};
  m.pivot = Vector3(0.5, 0.25, -0.125);
  m.point_motion = std::sqrt(2.0);
  MotionFailure f;
  f.verdict = MotionVerdict::kUnsupported;
  f.step = 4, f.tick = 17, f.time = 0.7;
  f.parts = {3, 5};
  f.pushed = {5};
  f.pushers = {3};
  f.motions = {m, PartMotion{}};
  f.contacts = {r};
  f.solver_note = "a note with \0 a zero byte";
  f.solver_note.push_back('\0');
  return f;
}

TEST(TaskCodec, APathTrialRoundTripsBitForBit) {
  PathTrial t;
  t.disassembly = MotionVerdict::kUnstable;
  t.assembly = MotionVerdict::kInfeasible;
  t.decided_by = "simulation";
  t.failure = AwkwardFailure();
  t.failure_mode = PlanMode::kAssemble;
  t.fixels = {{"A", {0.1, 0.2, 0.3}, {0, -1, 0}}, {"B b", {-0.0, 1e-300, 5}, {1, 0, 0}}};
  Writer w;
  w.Put(t);
  const std::string bytes = w.Take();
  Reader r(bytes);
  PathTrial back;
  r.Get(back);
  EXPECT_TRUE(r.done());
  EXPECT_EQ(back.disassembly, t.disassembly);
  EXPECT_EQ(back.assembly, t.assembly);
  EXPECT_EQ(back.decided_by, t.decided_by);
  EXPECT_EQ(back.failure_mode, t.failure_mode);
  ASSERT_EQ(back.fixels.size(), 2u);
  EXPECT_EQ(back.fixels[1].part, "B b");
  ExpectSameBits(back.fixels[1].point, t.fixels[1].point);
  ASSERT_TRUE(back.failure);
  const MotionFailure& f = *back.failure;
  const MotionFailure& g = *t.failure;
  EXPECT_EQ(f.verdict, g.verdict);
  EXPECT_EQ(f.step, g.step);
  EXPECT_EQ(f.tick, g.tick);
  EXPECT_EQ(Bits(f.time), Bits(g.time));
  EXPECT_EQ(f.parts, g.parts);
  EXPECT_EQ(f.pushed, g.pushed);
  EXPECT_EQ(f.pushers, g.pushers);
  EXPECT_EQ(f.solver_note, g.solver_note);
  ASSERT_EQ(f.motions.size(), 2u);
  EXPECT_EQ(f.motions[0].kind, MotionKind::kTips);
  EXPECT_EQ(f.motions[0].role, PartRole::kCarried);
  ASSERT_TRUE(f.motions[0].pivot);
  ExpectSameBits(*f.motions[0].pivot, *g.motions[0].pivot);
  EXPECT_FALSE(f.motions[1].pivot);
  ASSERT_EQ(f.contacts.size(), 1u);
  const ContactReport& c = f.contacts[0];
  EXPECT_EQ(c.contact.feature, ContactFeature::kFaceFace);
  EXPECT_EQ(c.contact.part_b, kWorld);
  EXPECT_EQ(c.contact.patch, 2);
  ExpectSameBits(c.contact.p_WC, g.contacts[0].contact.p_WC);
  EXPECT_EQ(Bits(c.contact.gap), Bits(g.contacts[0].contact.gap));
  EXPECT_EQ(Bits(c.contact.mu), Bits(g.contacts[0].contact.mu));
  EXPECT_EQ(Bits(c.normal_force), Bits(g.contacts[0].normal_force));
  ExpectSameBits(c.friction_force, g.contacts[0].friction_force);  // NaN included
  EXPECT_EQ(Bits(c.normal_motion), Bits(g.contacts[0].normal_motion));
  EXPECT_TRUE(c.breaking);
  EXPECT_FALSE(c.sliding);
  // Encoding again gives the same bytes: the encoding is a function.
  Writer again;
  again.Put(back);
  EXPECT_EQ(again.Take(), bytes);
}

// Every prefix of a result is refused with the codec's message; a count
// corrupted to 2⁶³ is refused before anything is allocated for it.
TEST(TaskCodec, TruncatedOrCorruptBytesAreRefused) {
  PathTrial t;
  t.decided_by = "nodes";
  t.failure = AwkwardFailure();
  Writer w;
  w.Put(t);
  const std::string bytes = w.Take();
  for (size_t n = 0; n < bytes.size(); ++n) {
    const std::string cut = bytes.substr(0, n);
    Reader r(cut);
    PathTrial back;
    EXPECT_THROW(r.Get(back), std::invalid_argument) << "prefix of " << n << " bytes";
  }
  std::string corrupt = bytes;
  const uint64_t huge = uint64_t{1} << 63;
  // The first field after the two verdicts is decided_by's length.
  std::memcpy(&corrupt[2 * sizeof(MotionVerdict)], &huge, sizeof huge);
  Reader r(corrupt);
  PathTrial back;
  EXPECT_THROW(r.Get(back), std::invalid_argument);
}

}  // namespace
}  // namespace cairn::planning_codec
