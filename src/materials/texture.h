// Textures: spatially varying BSDF parameters looked up at a surface point's (u, v), with the
// semantics of Mitsuba 3's `bitmap` and `checkerboard` plugins, so its scene files map one to
// one. A closed set held in a std::variant, evaluated by free functions (texture.cpp).
//
// bitmap: linear texels (8-bit images are sRGB-decoded when loaded, unless `raw`), row 0 at
// v = 0 and column 0 at u = 0; texel (i, j) covers [j, j + 1) / width x [i, i + 1) / height.
// Bilinear filtering interpolates between texel centres; `nearest` takes the texel under uv.
// Indices outside the image wrap (repeat), reflect (mirror) or clamp. checkerboard: colour0
// where the fractional parts of u and v are both below or both above 1/2, else colour1. Both
// first map (u, v) through the affine `to_uv`.
#pragma once
#include <cstdint>
#include <memory>
#include <variant>
#include <vector>

#include "core/sampling.h"
#include "core/vec3.h"

namespace dualight {

// (u, v) -> (m[0] u + m[1] v + m[2], m[3] u + m[4] v + m[5]).
struct UvTransform {
  float m[6] = {1.f, 0.f, 0.f, 0.f, 1.f, 0.f};
  Point2 operator()(Point2 p) const { return {m[0] * p.u + m[1] * p.v + m[2], m[3] * p.u + m[4] * p.v + m[5]}; }
};

enum class WrapMode : uint8_t { Repeat, Mirror, Clamp };
enum class TextureFilter : uint8_t { Bilinear, Nearest };

// Linear texel values, row-major, `channels` (1 or 3) per texel.
struct Texels {
  int width = 0, height = 0, channels = 3;
  std::vector<float> values;
};

struct BitmapTexture {
  std::shared_ptr<const Texels> texels;  // shared by every copy of the material
  WrapMode wrap = WrapMode::Repeat;
  TextureFilter filter = TextureFilter::Bilinear;
  UvTransform to_uv;
};

struct CheckerboardTexture {
  Color color0{0.4f}, color1{0.2f};
  UvTransform to_uv;
};

using Texture = std::variant<BitmapTexture, CheckerboardTexture>;

// The texture's RGB at uv (a one-channel bitmap gives grey).
Color eval_rgb(const Texture& t, Point2 uv);
// The texture as one number at uv, as Mitsuba 3's eval_1 gives it (roughness): a one-channel
// bitmap's value, the luminance of an RGB one; a checkerboard's colours (the mean of their
// channels) swapped against eval_rgb (colour1 where eval_rgb gives colour0), as Mitsuba 3.9
// does.
float eval_scalar(const Texture& t, Point2 uv);
// The mean over the unit square of uv (before to_uv for the checkerboard, as Mitsuba: the mean
// of its two colours; a bitmap's mean texel).
Color mean_rgb(const Texture& t);
// The mean of eval_rgb over the triangle of surface coordinates (a, b, c): the midpoint rule on
// its split into n x n similar triangles, n from the triangle's size in texels (or checkerboard
// squares), about four points per texel along each side, 2 <= n <= 64.
Color mean_rgb_over_triangle(const Texture& t, Point2 a, Point2 b, Point2 c);

}  // namespace dualight
