// Lanes of float and int32 (GCC's vector extensions), as many as one register holds (16 with
// AVX-512, 8 with AVX2, 4 with SSE2), for code that runs one sample per lane
// (pathspace/path_lanes_kernel.h). Deliberately without include guard or includes: only
// the per-ISA translation units include it, after their `#pragma GCC target` and with
// DUALIGHT_LANES_NS naming their namespace and DUALIGHT_LANES_BITS their vector width, so
// each gets its own copy compiled for its instruction set (the headers it needs are included
// before the pragma, at the baseline, by pathspace/path_tracer_lanes.h).
//
// Every operation is the IEEE operation the scalar code performs on each value (those units
// build with -ffp-contract=off: no fused multiply-add), so a lane computes the scalar code's
// bits; the scalar code's std::max(a, b) is (a < b ? b : a), and so on.

namespace dualight::DUALIGHT_LANES_NS {

constexpr int kLanes = DUALIGHT_LANES_BITS / 32;
using vf = float __attribute__((vector_size(4 * kLanes)));
using vi = int32_t __attribute__((vector_size(4 * kLanes)));  // masks: -1 true, 0 false

inline vf splat(float x) { return vf{} + x; }
inline vi splat_i(int32_t x) { return vi{} + x; }
inline vf load(const float* p) {
  vf v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline vi load(const int32_t* p) {
  vi v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store(float* p, vf v) { std::memcpy(p, &v, sizeof v); }
inline void store(int32_t* p, vi v) { std::memcpy(p, &v, sizeof v); }

inline vf select(vi m, vf a, vf b) { return m ? a : b; }
inline vi select(vi m, vi a, vi b) { return m ? a : b; }
// Bit i: lane i of mask m is true.
inline uint32_t lane_bits(vi m) {
#if DUALIGHT_LANES_BITS == 512
  return _mm512_test_epi32_mask((__m512i)m, (__m512i)m);
#elif DUALIGHT_LANES_BITS == 256
  return static_cast<uint32_t>(_mm256_movemask_ps((__m256)m));
#else
  return static_cast<uint32_t>(_mm_movemask_ps((__m128)m));
#endif
}
inline bool any(vi m) { return lane_bits(m) != 0; }
inline uint64_t count(vi m) { return static_cast<uint64_t>(__builtin_popcount(lane_bits(m))); }

inline vf bits_to_float(vi x) { return (vf)x; }  // a vector cast keeps the bits
inline vi float_to_bits(vf x) { return (vi)x; }
inline vf abs(vf x) { return bits_to_float(float_to_bits(x) & 0x7fffffff); }
// std::copysign(1.f, x)
inline vf copysign_one(vf x) { return bits_to_float((float_to_bits(x) & int32_t(0x80000000u)) | 0x3f800000); }
inline vf max(vf a, vf b) { return select(a < b, b, a); }  // std::max
inline vf min(vf a, vf b) { return select(b < a, b, a); }  // std::min

inline vf sqrt(vf x) {
#if DUALIGHT_LANES_BITS == 512
  return (vf)_mm512_sqrt_ps((__m512)x);
#elif DUALIGHT_LANES_BITS == 256
  return (vf)_mm256_sqrt_ps((__m256)x);
#else
  return (vf)_mm_sqrt_ps((__m128)x);
#endif
}

// base[index[i]] for each lane (index 0 where a lane has nothing to read: the tables are not empty).
inline vf gather(const float* base, vi index) {
#if DUALIGHT_LANES_BITS == 512
  return (vf)_mm512_i32gather_ps((__m512i)index, base, 4);
#elif DUALIGHT_LANES_BITS == 256
  return (vf)_mm256_i32gather_ps(base, (__m256i)index, 4);
#else
  vf r;
  for (int k = 0; k < kLanes; ++k) r[k] = base[index[k]];
  return r;
#endif
}

using vu = uint32_t __attribute__((vector_size(4 * kLanes)));
using vu64 = uint64_t __attribute__((vector_size(8 * kLanes)));
using vi64 = int64_t __attribute__((vector_size(8 * kLanes)));

// mix64 and hash_combine (core/rng.h), lane-wide.
inline vu64 mix64(vu64 z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
inline vu64 hash_combine(vu64 a, vu64 b) { return mix64(a ^ mix64(b)); }

// PCG32 generators (core/rng.h), one per lane, stepped together: lane i yields what its own
// Pcg32 would, where `active` (the others do not advance).
struct LanePcg32 {
  vu64 state, inc;
  vf next_float(vi active) {
    const vu64 old = state;
    // old * multiplier + inc where active, as old + (old * (multiplier - 1) + inc) masked: the same
    // sum modulo 2^64, without a 64-bit select (which GCC 12 takes apart lane by lane).
    const auto step = (vu64)__builtin_convertvector(active, vi64);
    state = old + ((old * (6364136223846793005ull - 1u) + inc) & step);
    const vu xorshifted = __builtin_convertvector(((old >> 18u) ^ old) >> 27u, vu);
    const vu rot = __builtin_convertvector(old >> 59u, vu);
    const vu bits = (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
    return select(active, __builtin_convertvector((vi)(bits >> 8u), vf) * 0x1p-24f, vf{});
  }
};

// SobolSampler (core/sampler.h), one per lane, stepped together: lane i yields what its own
// sampler would, where `active` (the others keep their dimension). The integer steps of the
// scalar sampler, lane-wide: mix64 (core/rng.h), reverse_bits, laine_karras_permutation and
// sobol_dimension1 (its byte tables gathered).
struct LaneSobol {
  vu64 pixel_seed{};
  vu reversed_index{}, dimension{};

  static vu reverse_bits(vu x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
  }
  static vu laine_karras_permutation(vu x, vu seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
  }
  // The byte table's entries, gathered as floats and taken back as bits (as the kernel's gather_int).
  static vu table(int byte, vu index) {
    const auto* entries = reinterpret_cast<const float*>(sobol_detail::kDimension1.by_byte[byte]);
    return (vu)float_to_bits(gather(entries, (vi)index));
  }
  static vu sobol_dimension1(vu index) {
    return table(0, index & 0xffu) ^ table(1, (index >> 8) & 0xffu) ^ table(2, (index >> 16) & 0xffu) ^
           table(3, index >> 24);
  }
  static vf to_unit_float(vu x) { return __builtin_convertvector((vi)(x >> 8), vf) * 0x1p-24f; }

  // The next dimension's seeds where active: shuffle, x and (second) the mix for y.
  void next_seeds(vi active, vu& shuffle, vu& x, vu64& a) {
    dimension -= (vu)active;  // + 1 where active (-1)
    a = mix64(pixel_seed + 0x9e3779b97f4a7c15ull * __builtin_convertvector(dimension, vu64));
    shuffle = __builtin_convertvector(a, vu);
    x = __builtin_convertvector(a >> 32, vu);
  }
  vu shuffled_index(vu seed) const { return reverse_bits(laine_karras_permutation(reversed_index, seed)); }
  vf next_1d(vi active) {
    vu shuffle, x;
    vu64 a;
    next_seeds(active, shuffle, x, a);
    return select(active, to_unit_float(reverse_bits(laine_karras_permutation(shuffled_index(shuffle), x))), vf{});
  }
  void next_2d(vi active, vf& u, vf& v) {
    vu shuffle, x;
    vu64 a;
    next_seeds(active, shuffle, x, a);
    const vu y = __builtin_convertvector(mix64(a), vu);
    const vu index = shuffled_index(shuffle);
    u = select(active, to_unit_float(reverse_bits(laine_karras_permutation(index, x))), vf{});
    const vu dim1 = reverse_bits(sobol_dimension1(index));
    v = select(active, to_unit_float(reverse_bits(laine_karras_permutation(dim1, y))), vf{});
  }
};

// A Vec3 (or Color) per lane; operations in Vec3's order.
struct V3 {
  vf x, y, z;
};
inline V3 splat(const Vec3& v) { return {splat(v.x), splat(v.y), splat(v.z)}; }
inline V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator-(const V3& a) { return {-a.x, -a.y, -a.z}; }
inline V3 operator*(const V3& a, const V3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline V3 operator*(const V3& a, vf s) { return {a.x * s, a.y * s, a.z * s}; }
inline V3 operator*(const V3& a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline V3 operator/(const V3& a, vf s) { return {a.x / s, a.y / s, a.z / s}; }
inline vf dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 select(vi m, const V3& a, const V3& b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}
inline vi is_black(const V3& v) { return (v.x == 0.f) & (v.y == 0.f) & (v.z == 0.f); }
inline vf max_component(const V3& v) { return max(v.x, max(v.y, v.z)); }

}  // namespace dualight::DUALIGHT_LANES_NS
