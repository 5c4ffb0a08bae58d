#include "pathspace/ray_benchmark.h"

#include <atomic>
#include <vector>

#include "core/frame.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/stopwatch.h"

namespace dualight {

RayCastStats cast_random_rays(const Scene& scene, const PinholeCamera& camera, uint64_t n_rays, uint64_t seed,
                              int threads) {
  // Generate the rays first so only traversal is timed.
  struct Origin {
    Vec3 p, n;
  };
  std::vector<Ray> rays;
  rays.reserve(n_rays);
  Pcg32 rng(seed, 0x5eed);
  std::vector<Origin> origins;
  for (int attempt = 0; origins.size() < 4096 && attempt < 100000; ++attempt) {
    const Ray r = camera.generate_ray(rng.next_float() * camera.width(), rng.next_float() * camera.height());
    SurfaceHit hit;
    if (scene.intersect(r, hit)) origins.push_back({hit.p, dot(hit.n, r.d) < 0.f ? hit.n : -hit.n});
  }
  RayCastStats stats;
  if (origins.empty()) return stats;
  for (uint64_t i = 0; i < n_rays; ++i) {
    const Origin& o = origins[rng.next_uint() % origins.size()];
    const Vec3 d = Frame::from_normal(o.n).to_world(square_to_cosine_hemisphere({rng.next_float(), rng.next_float()}));
    rays.push_back({scene.spawn_origin(o.p, o.n), d});
  }
  constexpr size_t kChunk = 4096;
  const size_t n_chunks = (rays.size() + kChunk - 1) / kChunk;
  std::atomic<uint64_t> hits{0};
  const Stopwatch start;
  parallel_for_each_index(threads, n_chunks, [&](size_t c) {
    uint64_t local = 0;
    for (size_t i = c * kChunk; i < std::min(rays.size(), (c + 1) * kChunk); ++i) {
      SurfaceHit hit;
      local += scene.intersect(rays[i], hit) ? 1 : 0;
    }
    hits.fetch_add(local, std::memory_order_relaxed);
  });
  stats.seconds = start();
  stats.rays = rays.size();
  stats.hits = hits.load();
  return stats;
}

}  // namespace dualight
