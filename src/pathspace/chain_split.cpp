#include "pathspace/chain_split.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace dualight {

ChainStartUp ChainStartUp::for_chains(uint64_t first, uint64_t count) const {
  ChainStartUp copy = *this;
  for (ChainPopulation& p : copy.populations) {
    const bool overlaps = p.first_chain < first + count && first < p.first_chain + p.chains;
    if (!overlaps) {
      p.weights.clear();
      p.weights.shrink_to_fit();
    }
  }
  return copy;
}

void ChainPart::merge(const ChainPart& next) {
  // Gaps are allowed: an interrupted split render merges the parts that finished.
  if (chains > 0 && next.first_chain < first_chain + chains) {
    throw std::invalid_argument("chain parts must be merged in chain order");
  }
  if (chains == 0) first_chain = next.first_chain;
  chains = next.first_chain + next.chains - first_chain;
  if (populations.size() < next.populations.size()) populations.resize(next.populations.size());
  for (size_t p = 0; p < next.populations.size(); ++p) {
    PopulationPart& into = populations[p];
    const PopulationPart& from = next.populations[p];
    into.metropolis.add(from.metropolis);
    into.large.add(from.large);
    into.large_f.insert(into.large_f.end(), from.large_f.begin(), from.large_f.end());
    into.mutations += from.mutations;
    into.accepted += from.accepted;
    into.large_steps += from.large_steps;
    into.large_steps_accepted += from.large_steps_accepted;
    into.zero_proposals += from.zero_proposals;
  }
  if (mutations.empty()) {
    mutations = next.mutations;
  } else if (mutations.size() == next.mutations.size()) {
    for (size_t i = 0; i < mutations.size(); ++i) {
      mutations[i].proposed += next.mutations[i].proposed;
      mutations[i].accepted += next.mutations[i].accepted;
      mutations[i].failed += next.mutations[i].failed;
    }
  } else if (!next.mutations.empty()) {
    throw std::invalid_argument("chain parts with different mutation sets cannot be merged");
  }
  stats.samples += next.stats.samples;
  stats.rays += next.stats.rays;
  stats.skipped_connections += next.stats.skipped_connections;
  stats.skipped_shadow_rays += next.stats.skipped_shadow_rays;
  stats.unoccluded = next.stats.unoccluded;
  stats.invalid_samples += next.stats.invalid_samples;
  stats.seconds += next.stats.seconds;
  stats.interrupted = stats.interrupted || next.stats.interrupted;
  stats.time_limited = stats.time_limited || next.stats.time_limited;
}

ChainPart empty_part(const ChainStartUp& start, uint64_t first, uint64_t count) {
  ChainPart part;
  part.first_chain = std::min(first, start.chains());
  part.chains = std::min(count, start.chains() - part.first_chain);
  part.populations.resize(start.populations.size());
  return part;
}

namespace {

bool all_finite_non_negative(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x) && x >= 0.0; });
}

void check_population(const ChainPopulation& p, const ChainStartUpShape& shape) {
  if (p.depth < shape.first_depth || p.depth > shape.last_depth) {
    throw std::invalid_argument("malformed chain start-up: a population of path length " + std::to_string(p.depth) +
                                " where " + std::to_string(shape.first_depth) + " to " +
                                std::to_string(shape.last_depth) + " are possible");
  }
  if (!all_finite_non_negative(p.weights) || !std::isfinite(p.b_splat) || p.b_splat < 0.0) {
    throw std::invalid_argument("malformed chain start-up: bootstrap weights or b not finite and non-negative");
  }
  const bool has_weight = std::any_of(p.weights.begin(), p.weights.end(), [](double w) { return w > 0.0; });
  if (p.chains > 0 && (!(p.b_splat > 0.0) || (!p.weights.empty() && !has_weight))) {
    throw std::invalid_argument("malformed chain start-up: chains in a population without light");
  }
  if (p.chains > 0 && (shape.mutations == 0) != (p.target == 0)) {
    throw std::invalid_argument("malformed chain start-up: a mutation target where the render has none, or none "
                                "where it has one");
  }
}

}  // namespace

void check_chain_start_up(const ChainStartUp& start, size_t pixels, const ChainStartUpShape& shape) {
  if (start.image.size() != 3 * pixels || !all_finite_non_negative(start.image)) {
    throw std::invalid_argument("malformed chain start-up: its direct-light image is not " + std::to_string(pixels) +
                                " finite pixels");
  }
  if (!(start.pilot_luminance.empty() || start.pilot_luminance.size() == pixels) ||
      !all_finite_non_negative(start.pilot_luminance)) {
    throw std::invalid_argument("malformed chain start-up: its pilot image is not " + std::to_string(pixels) +
                                " finite pixels");
  }
  if (start.populations.size() > shape.populations) {
    throw std::invalid_argument("malformed chain start-up: more populations than path lengths");
  }
  std::vector<int> seen;
  uint64_t chains = 0, mutations = 0;
  for (const ChainPopulation& p : start.populations) {
    check_population(p, shape);
    if (std::find(seen.begin(), seen.end(), p.depth) != seen.end()) {
      throw std::invalid_argument("malformed chain start-up: two populations of one path length");
    }
    seen.push_back(p.depth);
    chains += p.chains;  // each at most 2^32 (start_up_from_bytes), so no wrap-around
    mutations += std::min<uint64_t>(p.target, uint64_t{1} << 62);
  }
  // Apportioned with at least one chain and mutation per population.
  const uint64_t extra = start.populations.size();
  if (chains > std::max(shape.chains, extra) || mutations > std::max(shape.mutations, extra)) {
    throw std::invalid_argument("malformed chain start-up: more chains or mutations than the render asks for");
  }
  const MltStats& m = start.mlt;
  if (!std::isfinite(m.b) || !std::isfinite(m.b_ci95) || !std::isfinite(m.b_splatted)) {
    throw std::invalid_argument("malformed chain start-up: b is not finite");
  }
}

void check_chain_part(const ChainStartUp& start, const ChainPart& part, size_t values) {
  if (part.populations.size() > start.populations.size() || part.first_chain > start.chains() ||
      part.chains > start.chains() - part.first_chain) {
    throw std::invalid_argument("the chain part does not belong to this start-up (more chains or populations)");
  }
  for (size_t i = 0; i < part.populations.size(); ++i) {
    const PopulationPart& p = part.populations[i];
    for (const ExactSums* sums : {&p.metropolis, &p.large}) {
      if (!sums->empty() && sums->size() != values) {
        throw std::invalid_argument("the chain part's image has another size than the start-up's");
      }
    }
    if (!p.metropolis.non_negative() || !p.large.non_negative()) {
      throw std::invalid_argument("the chain part's image holds negative sums");
    }
    if (p.mutations > 0 && p.metropolis.empty()) {
      throw std::invalid_argument("the chain part counts mutations but holds no image for them");
    }
    if (p.large_f.size() > start.populations[i].chains) {
      throw std::invalid_argument("the chain part has more chains than its population");
    }
    const bool finite = std::all_of(p.large_f.begin(), p.large_f.end(), [](const MeanEstimate& e) {
      return std::isfinite(e.sum) && std::isfinite(e.sum_sq) && e.sum >= 0.0 && e.sum_sq >= 0.0;
    });
    if (!finite || p.accepted > p.mutations || p.large_steps_accepted > p.large_steps) {
      throw std::invalid_argument("the chain part's estimates are not finite or its counts do not add up");
    }
  }
}

std::vector<float> chain_image(const std::vector<double>& image) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (!std::all_of(image.begin(), image.end(), [](double x) { return x >= 0.0 && x <= kMax; })) {
    throw std::invalid_argument("the chain parts' sums give an image beyond float32's range");
  }
  return {image.begin(), image.end()};
}

RenderStats chain_render_stats(const ChainStartUp& start, const ChainPart& part, uint64_t mutations,
                               size_t pixels) {
  RenderStats stats = part.stats;
  stats.rays += start.stats.rays;
  stats.skipped_connections += start.stats.skipped_connections;
  stats.skipped_shadow_rays += start.stats.skipped_shadow_rays;
  stats.unoccluded = start.stats.unoccluded;
  stats.invalid_samples += start.stats.invalid_samples;
  stats.samples = mutations;
  stats.spp = static_cast<uint32_t>(mutations / pixels);
  stats.interrupted = stats.interrupted || start.cancelled;
  return stats;
}

namespace {

// Little-endian bytes of plain values and vectors of them; the machines of one cluster share a
// byte order, and a tag and version guard against other input.
constexpr uint32_t kStartUpTag = 0x444c5355, kPartTag = 0x444c4350, kVersion = 1;

class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&v);
    bytes_.append(p, sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(v.size());
    if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put(const std::string& s) {
    put<uint64_t>(s.size());
    bytes_.append(s);
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<T> get_vector() {
    const uint64_t n = get<uint64_t>();
    if (n > (bytes_.size() - at_) / sizeof(T)) fail();
    std::vector<T> v(n);
    if (n > 0) std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));  // data() may be null when empty
    at_ += n * sizeof(T);
    return v;
  }
  std::string get_string() {
    const uint64_t n = get<uint64_t>();
    need(n);
    std::string s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  void expect(uint32_t tag) {
    if (bytes_.size() < 8 || get<uint32_t>() != tag || get<uint32_t>() != kVersion) {
      throw std::invalid_argument("not a dualight chain start-up or chain part of this version");
    }
  }
  void finish() const {
    if (at_ != bytes_.size()) fail();
  }

 private:
  void need(uint64_t n) const {
    if (n > bytes_.size() - at_) fail();
  }
  [[noreturn]] static void fail() { throw std::invalid_argument("truncated or malformed chain data"); }
  const std::string& bytes_;
  size_t at_ = 0;
};

void put(ByteWriter& w, const RenderStats& s) {
  w.put(s.samples);
  w.put(s.rays);
  w.put(s.skipped_connections);
  w.put(s.skipped_shadow_rays);
  w.put(s.unoccluded);
  w.put(s.invalid_samples);
  w.put(s.spp);
  w.put(s.seconds);
  w.put(s.interrupted);
  w.put(s.time_limited);
}

RenderStats get_stats(ByteReader& r) {
  RenderStats s;
  s.samples = r.get<uint64_t>();
  s.rays = r.get<uint64_t>();
  s.skipped_connections = r.get<uint64_t>();
  s.skipped_shadow_rays = r.get<uint64_t>();
  s.unoccluded = r.get<uint8_t>() != 0;
  s.invalid_samples = r.get<uint64_t>();
  s.spp = r.get<uint32_t>();
  s.seconds = r.get<double>();
  s.interrupted = r.get<uint8_t>() != 0;
  s.time_limited = r.get<uint8_t>() != 0;
  return s;
}

void put(ByteWriter& w, const ExactSums& s) {
  w.put(s.exponent());
  w.put(s.words());
}

ExactSums get_sums(ByteReader& r) {
  const int exponent = r.get<int>();
  return ExactSums(r.get_vector<uint64_t>(), exponent);
}

}  // namespace

std::string to_bytes(const ChainStartUp& start) {
  ByteWriter w;
  w.put(kStartUpTag);
  w.put(kVersion);
  w.put(start.image);
  put(w, start.direct);
  put(w, start.stats);
  const MltStats& m = start.mlt;
  w.put(m.b);
  w.put(m.b_ci95);
  w.put(m.b_splatted);
  w.put(m.independent_samples);
  w.put(m.pilot_samples);
  w.put<uint64_t>(start.populations.size());
  for (const ChainPopulation& p : start.populations) {
    w.put(p.depth);
    w.put(p.weights);
    w.put(p.b_splat);
    w.put(p.first_chain);
    w.put(p.chains);
    w.put(p.target);
    w.put(p.chain_ids);
  }
  w.put(start.pilot_luminance);
  w.put(start.cancelled);
  return w.take();
}

ChainStartUp start_up_from_bytes(const std::string& bytes) {
  ByteReader r(bytes);
  r.expect(kStartUpTag);
  ChainStartUp start;
  start.image = r.get_vector<double>();
  start.direct = get_stats(r);
  start.stats = get_stats(r);
  MltStats& m = start.mlt;
  m.b = r.get<double>();
  m.b_ci95 = r.get<double>();
  m.b_splatted = r.get<double>();
  m.independent_samples = r.get<uint64_t>();
  m.pilot_samples = r.get<uint64_t>();
  const auto n = r.get<uint64_t>();
  uint64_t next_chain = 0;
  for (uint64_t i = 0; i < n; ++i) {
    ChainPopulation p;
    p.depth = r.get<int>();
    p.weights = r.get_vector<double>();
    p.b_splat = r.get<double>();
    p.first_chain = r.get<uint64_t>();
    p.chains = r.get<uint64_t>();
    p.target = r.get<uint64_t>();
    p.chain_ids = r.get_vector<uint32_t>();
    const bool ids_fit = p.chain_ids.empty() || p.chain_ids.size() == p.chains;
    if (p.first_chain != next_chain || p.chains > (1ull << 32) || !ids_fit) {
      throw std::invalid_argument("malformed chain start-up: populations out of order");
    }
    next_chain += p.chains;
    start.populations.push_back(std::move(p));
  }
  start.pilot_luminance = r.get_vector<double>();
  start.cancelled = r.get<uint8_t>() != 0;
  r.finish();
  return start;
}

std::string to_bytes(const ChainPart& part) {
  ByteWriter w;
  w.put(kPartTag);
  w.put(kVersion);
  w.put(part.first_chain);
  w.put(part.chains);
  w.put<uint64_t>(part.populations.size());
  for (const PopulationPart& p : part.populations) {
    put(w, p.metropolis);
    put(w, p.large);
    w.put(p.large_f);
    w.put(p.mutations);
    w.put(p.accepted);
    w.put(p.large_steps);
    w.put(p.large_steps_accepted);
    w.put(p.zero_proposals);
  }
  w.put<uint64_t>(part.mutations.size());
  for (const MutationStats& m : part.mutations) {
    w.put(m.name);
    w.put(m.proposed);
    w.put(m.accepted);
    w.put(m.failed);
  }
  put(w, part.stats);
  return w.take();
}

ChainPart part_from_bytes(const std::string& bytes) {
  ByteReader r(bytes);
  r.expect(kPartTag);
  ChainPart part;
  part.first_chain = r.get<uint64_t>();
  part.chains = r.get<uint64_t>();
  // Counts bounded by the bytes left (a population part takes at least 72, a mutation's 32), so
  // that a malformed count fails as truncated instead of allocating without bound.
  const auto n = r.get<uint64_t>();
  if (n > bytes.size() / 72) throw std::invalid_argument("truncated or malformed chain data");
  part.populations.resize(n);
  for (PopulationPart& p : part.populations) {
    p.metropolis = get_sums(r);
    p.large = get_sums(r);
    p.large_f = r.get_vector<MeanEstimate>();
    p.mutations = r.get<uint64_t>();
    p.accepted = r.get<uint64_t>();
    p.large_steps = r.get<uint64_t>();
    p.large_steps_accepted = r.get<uint64_t>();
    p.zero_proposals = r.get<uint64_t>();
  }
  const auto m = r.get<uint64_t>();
  if (m > bytes.size() / 32) throw std::invalid_argument("truncated or malformed chain data");
  for (uint64_t i = 0; i < m; ++i) {
    MutationStats s;
    s.name = r.get_string();
    s.proposed = r.get<uint64_t>();
    s.accepted = r.get<uint64_t>();
    s.failed = r.get<uint64_t>();
    part.mutations.push_back(std::move(s));
  }
  part.stats = get_stats(r);
  r.finish();
  return part;
}

}  // namespace dualight
