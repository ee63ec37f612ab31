#include "planning/task_codec.h"

namespace cairn::planning_codec {

// Every field, in declaration order, both ways.

void Writer::Put(const Contact& c) {
  Put(c.part_a), Put(c.part_b), Put(c.p_WC), Put(c.n_W), Put(c.gap), Put(c.mu);
  Put(c.feature), Put(c.index_a), Put(c.index_b), Put(c.patch);
}
void Reader::Get(Contact& c) {
  Get(c.part_a), Get(c.part_b), Get(c.p_WC), Get(c.n_W), Get(c.gap), Get(c.mu);
  Get(c.feature), Get(c.index_a), Get(c.index_b), Get(c.patch);
}

void Writer::Put(const PartMotion& m) {
  Put(m.part), Put(m.role), Put(m.component), Put(m.moving), Put(m.kind);
  Put(m.linear), Put(m.angular), Put(m.pivot), Put(m.point_motion);
}
void Reader::Get(PartMotion& m) {
  Get(m.part), Get(m.role), Get(m.component), Get(m.moving), Get(m.kind);
  Get(m.linear), Get(m.angular), Get(m.pivot), Get(m.point_motion);
}

void Writer::Put(const ContactReport& r) {
  Put(r.contact), Put(r.component), Put(r.normal_force), Put(r.friction_force);
  Put(r.normal_motion), Put(r.tangent_motion), Put(r.breaking), Put(r.sliding);
}
void Reader::Get(ContactReport& r) {
  Get(r.contact), Get(r.component), Get(r.normal_force), Get(r.friction_force);
  Get(r.normal_motion), Get(r.tangent_motion), Get(r.breaking), Get(r.sliding);
}

void Writer::Put(const MotionFailure& f) {
  Put(f.verdict), Put(f.step), Put(f.tick), Put(f.time), Put(f.parts), Put(f.pushed);
  Put(f.pushers), Put(f.motions), Put(f.contacts), Put(f.solver_note);
}
void Reader::Get(MotionFailure& f) {
  Get(f.verdict), Get(f.step), Get(f.tick), Get(f.time), Get(f.parts), Get(f.pushed);
  Get(f.pushers), Get(f.motions), Get(f.contacts), Get(f.solver_note);
}

void Writer::Put(const PathTrial& t) {
  Put(t.disassembly), Put(t.assembly), Put(t.decided_by), Put(t.failure), Put(t.failure_mode);
  Put(static_cast<uint64_t>(t.fixels.size()));
  for (const FixtureDef& x : t.fixels) Put(x.part), Put(x.point), Put(x.normal);
}
void Reader::Get(PathTrial& t) {
  Get(t.disassembly), Get(t.assembly), Get(t.decided_by), Get(t.failure), Get(t.failure_mode);
  uint64_t n = 0;
  Get(n);
  Need(n);
  t.fixels.resize(n);
  for (FixtureDef& x : t.fixels) Get(x.part), Get(x.point), Get(x.normal);
}

}  // namespace cairn::planning_codec
