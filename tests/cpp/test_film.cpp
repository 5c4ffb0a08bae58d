// The film's sample blocks: a film merged from per-block films (Film::add_accumulators, as
// render(executor=...) merges its tasks) equals the film that summed every block itself, bit for
// bit, with values chosen so that any other order of additions would round differently.
#include <vector>

#include "check.h"
#include "film/film.h"

using namespace dualight;

namespace {

// Sample s of the one pixel: large and small magnitudes mixed, so the order of sums matters.
Color value(uint32_t s) {
  const float big = (s % 3 == 0) ? 3.0e7f : 1.0f;
  return Color(big + 0.1f * static_cast<float>(s), 0.7f / static_cast<float>(s + 1), 1.0f);
}

void add_block(Film& film, uint32_t first, uint32_t count) {
  for (uint32_t s = first; s < first + count; ++s) {
    film.add_sample(0, value(s));
    SplatList splats;
    splats.begin_path();
    splats.add(1, value(s + 7));
    splats.end_path();
    film.add_splats(splats, 1);
    if ((s + 1) % kBlockSpp == 0) {
      film.end_block(0);
      film.end_splat_block();
    }
  }
  film.end_blocks();
}

}  // namespace

TEST_CASE("film_merged_from_blocks_equals_one_film") {
  const uint32_t spp = 3 * kBlockSpp + 5;  // a short last block too
  Film whole(2, 1);
  add_block(whole, 0, spp);
  Film merged(2, 1);
  for (uint32_t first = 0; first < spp; first += kBlockSpp) {
    Film task(2, 1);
    add_block(task, first, std::min(kBlockSpp, spp - first));
    merged.add_accumulators(task.accumulators());
  }
  CHECK(whole.mean() == merged.mean());
  CHECK(whole.variance_of_mean() == merged.variance_of_mean());
  CHECK(whole.sample_counts() == merged.sample_counts());
  CHECK((whole.light_paths() == merged.light_paths() && whole.light_paths() == spp));
  // Negative control: one block of all samples sums in another order and rounds differently.
  Film unblocked(2, 1);
  for (uint32_t s = 0; s < spp; ++s) unblocked.add_sample(0, value(s));
  unblocked.end_blocks();
  const FilmAccumulators a = unblocked.accumulators(), b = whole.accumulators();
  CHECK((a.sum != b.sum || a.sum_sq != b.sum_sq));
}
