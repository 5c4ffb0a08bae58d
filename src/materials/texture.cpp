// Texture lookups with Mitsuba 3's semantics (bitmap with Dr.Jit's texture filtering and
// wrapping, checkerboard); see texture.h.
#include "materials/texture.h"

#include <algorithm>
#include <cmath>

#include "core/triangle_grid.h"

namespace dualight {

namespace {

// A texel index wrapped into [0, n).
int wrap_index(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::Clamp:
      return i < 0 ? 0 : (i >= n ? n - 1 : i);
    case WrapMode::Mirror: {
      const int period = 2 * n;
      int k = i % period;
      if (k < 0) k += period;
      return k < n ? k : period - 1 - k;
    }
    case WrapMode::Repeat:
      break;
  }
  const int k = i % n;
  return k < 0 ? k + n : k;
}

// floor(x) as an int, saturated: uv far outside the image must still give a valid index.
int floor_index(float x) {
  const float f = std::floor(x);
  return f < -1e9f ? -1000000000 : (f > 1e9f ? 1000000000 : static_cast<int>(f));
}

Color texel(const Texels& t, int row, int col) {
  const float* p = &t.values[(static_cast<size_t>(row) * t.width + col) * t.channels];
  return t.channels == 1 ? Color(p[0]) : Color(p[0], p[1], p[2]);
}

Color eval_bitmap(const BitmapTexture& b, Point2 uv_in) {
  const Texels& t = *b.texels;
  const Point2 uv = b.to_uv(uv_in);
  if (!std::isfinite(uv.u) || !std::isfinite(uv.v)) return Color(0.f);
  const float x = uv.u * t.width, y = uv.v * t.height;
  if (b.filter == TextureFilter::Nearest) {
    return texel(t, wrap_index(floor_index(y), t.height, b.wrap), wrap_index(floor_index(x), t.width, b.wrap));
  }
  // Between the four texel centres around (x, y) [Dr.Jit's linear texture filter].
  const float xc = x - 0.5f, yc = y - 0.5f;
  const int i0 = floor_index(yc), j0 = floor_index(xc);
  const float fy = yc - std::floor(yc), fx = xc - std::floor(xc);
  const int r0 = wrap_index(i0, t.height, b.wrap), r1 = wrap_index(i0 + 1, t.height, b.wrap);
  const int c0 = wrap_index(j0, t.width, b.wrap), c1 = wrap_index(j0 + 1, t.width, b.wrap);
  const Color top = texel(t, r0, c0) * (1.f - fx) + texel(t, r0, c1) * fx;
  const Color bottom = texel(t, r1, c0) * (1.f - fx) + texel(t, r1, c1) * fx;
  return top * (1.f - fy) + bottom * fy;
}

// Whether the checkerboard shows colour0 at uv (eval_rgb's sense).
bool checker_first(const CheckerboardTexture& c, Point2 uv_in) {
  const Point2 uv = c.to_uv(uv_in);
  const bool mu = uv.u - std::floor(uv.u) > 0.5f, mv = uv.v - std::floor(uv.v) > 0.5f;
  return mu == mv;
}

// The texture's features per unit of its own (u, v): texels, or a checkerboard's two squares.
float features_per_unit(const Texture& t) {
  if (const auto* b = std::get_if<BitmapTexture>(&t)) return static_cast<float>(std::max(b->texels->width, b->texels->height));
  return 2.f;
}

float uv_span(const UvTransform& m, Point2 a, Point2 b) {
  const Point2 p = m(a), q = m(b);
  return std::hypot(p.u - q.u, p.v - q.v);
}

const UvTransform& to_uv_of(const Texture& t) {
  return std::visit([](const auto& x) -> const UvTransform& { return x.to_uv; }, t);
}

}  // namespace

Color eval_rgb(const Texture& t, Point2 uv) {
  if (const auto* b = std::get_if<BitmapTexture>(&t)) return eval_bitmap(*b, uv);
  const auto& c = std::get<CheckerboardTexture>(t);
  return checker_first(c, uv) ? c.color0 : c.color1;
}

float eval_scalar(const Texture& t, Point2 uv) {
  if (const auto* b = std::get_if<BitmapTexture>(&t)) {
    const Color c = eval_bitmap(*b, uv);
    // Mitsuba's luminance: the Y row of its sRGB-to-XYZ matrix (a little off Rec. 709's rounding).
    return b->texels->channels == 1 ? c.x : 0.212671f * c.x + 0.715160f * c.y + 0.072169f * c.z;
  }
  // Mitsuba's `rgb` texture gives the mean of its channels as one number.
  const auto& c = std::get<CheckerboardTexture>(t);
  return average(checker_first(c, uv) ? c.color1 : c.color0);
}

Color mean_rgb(const Texture& t) {
  if (const auto* c = std::get_if<CheckerboardTexture>(&t)) return (c->color0 + c->color1) * 0.5f;
  const Texels& x = *std::get<BitmapTexture>(t).texels;
  double sum[3] = {0.0, 0.0, 0.0};
  const size_t n = static_cast<size_t>(x.width) * x.height;
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) sum[k] += x.values[i * x.channels + (x.channels == 1 ? 0 : k)];
  }
  return Color(static_cast<float>(sum[0] / n), static_cast<float>(sum[1] / n), static_cast<float>(sum[2] / n));
}

Color mean_rgb_over_triangle(const Texture& t, Point2 a, Point2 b, Point2 c) {
  const UvTransform& m = to_uv_of(t);
  const float span = std::max({uv_span(m, a, b), uv_span(m, b, c), uv_span(m, c, a)});
  const float wanted = 4.f * span * features_per_unit(t);
  const int n = std::isfinite(wanted) ? std::clamp(static_cast<int>(std::ceil(wanted)), 2, 64) : 64;
  double sum[3] = {0.0, 0.0, 0.0};
  for (const Point2 w : centroid_grid(n)) {
    const Point2 uv{a.u + w.u * (b.u - a.u) + w.v * (c.u - a.u), a.v + w.u * (b.v - a.v) + w.v * (c.v - a.v)};
    const Color x = eval_rgb(t, uv);
    for (int k = 0; k < 3; ++k) sum[k] += x[k];
  }
  const double count = static_cast<double>(n) * n;
  return Color(static_cast<float>(sum[0] / count), static_cast<float>(sum[1] / count), static_cast<float>(sum[2] / count));
}

}  // namespace dualight
