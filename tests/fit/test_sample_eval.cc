// The metric pass's predictions (ModelOps::eval_samples, fit/sample_geometry.h): every catalog
// model over a range of samples equals its per-sample evaluator at SampleGeometry, bit for bit,
// for sets with on-demand and stored geometry, paired or not, in or out of cell order.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "fit/model_ops.h"
#include "fit/samples.h"
#include "fit_test_util.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SynthModel;

TEST(SampleEval, RangeEqualsPerSampleEvaluation) {
  const std::vector<internal::ModelOps> ops = testing::AllModelOps();
  ASSERT_GT(ops.size(), 10u);
  const Grid g{16, 16, 33, ThetaHMapping::kSqrt};  // odd phi_d: a unit of one cell per row
  const Table t = SynthModel("lambert", Params("lambert", {}), g, 0.0, 0.3, 5);
  std::vector<Samples> sets;
  for (const bool pair : {true, false}) {
    SampleOptions o;
    o.pair_mirrors = pair;
    sets.push_back(PrepareSamples(t, o, GeometryStorage::kOnDemand));
    sets.push_back(PrepareSamples(t, o));  // stored geometry
    Samples sub = Subsample(sets.front(), 200, 3);
    sub.geometry = {};  // a selection's order, geometry on demand
    sets.push_back(std::move(sub));
  }
  for (const internal::ModelOps& m : ops) {
    std::vector<double> p;
    for (const ParamSpec& spec : m.layout.specs) p.push_back(spec.init);
    for (const Samples& s : sets) {
      const std::size_t begin = s.NumSamples() / 5, end = s.NumSamples() - 3;
      std::vector<double> range(3 * (end - begin));
      m.eval_samples(p.data(), s, begin, end, range.data());
      for (std::size_t k = begin; k < end; ++k) {
        double one[3];
        m.eval(p.data(), SampleGeometry(s, k), one);
        ASSERT_EQ(std::memcmp(one, &range[3 * (k - begin)], sizeof one), 0) << m.name << " " << k;
      }
    }
  }
}

}  // namespace
}  // namespace brdfit
