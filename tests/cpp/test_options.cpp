// The options structs' validate(): what no single field's range says (a budget, a bounded depth
// where one is needed, ordered pairs of bounds) throws std::invalid_argument, so the C++ API
// checks what the Python bindings check; their defaults pass.
#include <stdexcept>

#include "check.h"
#include "pathspace/bdpt.h"
#include "pathspace/mlt.h"
#include "pathspace/path_tracer.h"
#include "pathspace/pssmlt.h"
#include "radiosity/form_factors.h"

using namespace dualight;

namespace {

template <class Options>
bool valid(const Options& o) {
  try {
    o.validate();
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

}  // namespace

TEST_CASE("options_defaults_are_valid") {
  CHECK(valid(PathTracerOptions{}));
  CHECK(valid(BdptOptions{}));
  CHECK(valid(PssmltOptions{}));
  CHECK(valid(MltOptions{}));
  CHECK(valid(FormFactorOptions{}));
}

TEST_CASE("options_reject_what_relates_their_fields") {
  PathTracerOptions no_budget;
  no_budget.spp = 0;
  CHECK(!valid(no_budget));
  no_budget.time_limit = 1.0;  // a time limit is a budget too
  CHECK(valid(no_budget));

  BdptOptions strategies;
  strategies.strategy_images = true;  // unbounded depth: no finite set of strategies
  CHECK(!valid(strategies));
  strategies.max_depth = 3;
  CHECK(valid(strategies));

  PssmltOptions multiplexed;
  multiplexed.multiplexed = true;
  CHECK(!valid(multiplexed));
  multiplexed.max_depth = 4;
  CHECK(valid(multiplexed));

  MltOptions mlt;
  mlt.angle_max = mlt.angle_min;
  CHECK(!valid(mlt));
  mlt = MltOptions{};
  mlt.lens_radius_max = mlt.lens_radius_min;
  CHECK(!valid(mlt));
  mlt.lens_radius_max = 0.f;  // 0: a tenth of the film's width
  CHECK(valid(mlt));

  FormFactorOptions quadrature;
  quadrature.quadrature = 5;
  CHECK(!valid(quadrature));
}
