// A rough per-pixel estimate of an image from an earlier, noisier render of it: its luminance,
// box-blurred. Used where only the image's scale per pixel matters (MLT's target function,
// mlt_importance.h; a guided light tracer's pixel weights; adjoint-driven Russian roulette).
#pragma once
#include <vector>

#include "film/film.h"

namespace dualight {

// Each pixel's mean luminance, row-major.
std::vector<double> film_luminance(const Film& film);

// The mean of each pixel's (2 radius + 1)^2 box (clipped at the borders); negative values count as 0.
std::vector<double> box_blurred(const std::vector<double>& image, int width, int height, int radius);

}  // namespace dualight
