// What the chains of path-space MLT aim at. Veach's target f* is a path's image luminance: the
// chains then put mutations where the image is bright, and a pixel's variance grows with its
// brightness, so dark pixels end with large relative errors. Dividing f* by a smoothed estimate
// of the pixel's brightness (an importance function in the sense of Hoberock and Hart 2010)
// spreads the mutations over the film instead. For relMSE, sum over pixels of Var_p / T_p^2,
// the best divisor is the pixel's total value T_p (direct light included; by Cauchy-Schwarz on
// Var_p ~ I_p w_p * sum_q I_q / w_q). That holds for an exact T_p; ours comes from a noisy pilot
// and the chains mix worse on a flatter f*, so the divisor is sqrt(T_p), which measured best
// (door, equal mutations, relMSE: luminance 1.33e-2; T^0.35 9.3e-3, T^0.5 8.4e-3, T^0.75
// 8.8e-3, T 1.01e-2; on the caustic box the full T let chains stick: relMSE x10). Any positive
// divisor fixed before the bootstrap keeps the estimate unbiased: b, the start paths and the
// splats (f / f*) all use the same f*.
#pragma once
#include <cstdint>
#include <vector>

namespace dualight {

enum class MltImportance { Luminance, Flattened };

class PixelImportance {
 public:
  PixelImportance() = default;  // f* = luminance
  // From a per-pixel luminance estimate T of the whole image: box-blurred over (2 radius + 1)^2
  // pixels, plus `floor_fraction` of its mean so that pixels the estimate missed stay finite;
  // the factor is sqrt(mean / T).
  PixelImportance(const std::vector<double>& luminance, int width, int height, int radius, double floor_fraction);

  // The factor f* / luminance of paths through `pixel`.
  float operator()(uint32_t pixel) const { return factor_.empty() ? 1.f : factor_[pixel]; }
  bool uniform() const { return factor_.empty(); }

 private:
  std::vector<float> factor_;
};

}  // namespace dualight
