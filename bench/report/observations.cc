#include "bench/report/observations.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "bench/report/markdown_format.h"
#include "bench/report/summaries.h"

namespace pd_bench {

void WriteObservations(const BenchRun& run, std::ostream& md) {
  md << "## Observations (generated from this run's data)\n\n";
  int lines = 0;
  for (const PairResult& p : run.pairs)
    for (const ScenarioResult& s : p.scenarios) {
      const std::string where = p.pair.name + " / " + ScenarioName(s.scenario);
      std::vector<int> invalid, ref_collide, big_err;
      std::map<std::string, int> inits;
      const CaseRecord* slowest = nullptr;
      const CaseRecord* worst = nullptr;
      double worst_err = 0.0;
      for (const CaseRecord& r : s.cases) {
        if (!r.c.colliding) continue;
        ++inits[r.pd.initializer];
        if (!(r.pd.valid && r.pd.verified_free)) invalid.push_back(r.c.index);
        if (r.has_ref && !r.ref.pd_answer_free) ref_collide.push_back(r.c.index);
        if (!slowest || r.pd.time_us > slowest->pd.time_us) slowest = &r;
        if (r.has_ref) {
          const double e = RelativeError(r.pd.depth, r.ref.depth);
          if (std::fabs(e) > 0.10) big_err.push_back(r.c.index);
          if (std::fabs(e) > std::fabs(worst_err)) worst_err = e, worst = &r;
        }
      }
      auto list = [](const std::vector<int>& v) {
        std::ostringstream o;
        for (size_t i = 0; i < std::min<size_t>(v.size(), 8); ++i) o << (i ? ", " : "") << v[i];
        if (v.size() > 8) o << ", ...";
        return o.str();
      };
      const ScenarioSummary m = Summarize(s);
      if (!invalid.empty())
        md << "- " << where << ": " << invalid.size() << " of " << m.n
           << " answers invalid (result.valid false or pd::InCollision at the answer); case "
           << list(invalid) << ".\n", ++lines;
      if (!ref_collide.empty())
        md << "- " << where << ": pd::ReferenceInCollision finds the translated probe still "
              "colliding in " << ref_collide.size() << " of " << m.n_ref << " reference cases ("
           << list(ref_collide) << ").\n", ++lines;
      if (!big_err.empty())
        md << "- " << where << ": " << big_err.size() << " of " << m.n_ref
           << " reference cases with |error| > 10% (" << list(big_err) << "); worst case "
           << worst->c.index << ": PolyDepth " << F(worst->pd.depth * 1000, 3) << " mm vs reference "
           << F(worst->ref.depth * 1000, 3) << " mm (" << Pct(worst_err, 1) << ", initializer "
           << worst->pd.initializer << ").\n", ++lines;
      if (m.n_pocket > 0)
        md << "- " << where << ": " << m.n_pocket << " of " << m.n
           << " answers sit in a thin free pocket (free, but colliding again "
           << F(100 * kPocketProbe, 1) << "% further along the same direction).\n", ++lines;
      if (m.n_ref_not_free > 0)
        md << "- " << where << ": " << m.n_ref_not_free << " of " << m.n_ref
           << " reference answers are not collision-free by pd::InCollision (the reference "
              "or the collision test is wrong there).\n", ++lines;
      if (m.n_below_ref > 0)
        md << "- " << where << ": PolyDepth found a shallower escape than the reference in "
           << m.n_below_ref << " of " << m.n_ref << " reference cases.\n", ++lines;
      if (slowest && m.n >= 5 && slowest->pd.time_us > 10 * m.time_us.median)
        md << "- " << where << ": slowest query " << F(slowest->pd.time_us / 1000, 2)
           << " ms (case " << slowest->c.index << ", " << slowest->pd.iterations
           << " iterations, initializer " << slowest->pd.initializer << "), "
           << F(slowest->pd.time_us / m.time_us.median, 0) << "x the median.\n", ++lines;
      std::ostringstream mix;
      for (const auto& [name, count] : inits) mix << (mix.tellp() ? ", " : "") << name << " " << count;
      md << "- " << where << ": winning initializers: " << mix.str() << ".\n", ++lines;
      if (m.fcl_mesh.n_no_collision > 0)
        md << "- " << where << ": FCL mesh-mesh contacts found no collision in "
           << m.fcl_mesh.n_no_collision << " of " << m.fcl_mesh.n
           << " colliding cases (containment without surface crossing, which it does not "
              "detect).\n", ++lines;
    }
  if (lines == 0) md << "- Nothing unusual.\n";
  md << "\n";
}


}  // namespace pd_bench
