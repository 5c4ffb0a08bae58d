// The one place that knows OpenImageIO: reads and writes EXR, HDR, PNG and whatever else OIIO
// supports, with string metadata. Pixels are row-major, interleaved channels, row 0 at the top.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace dualight {

using ImageMetadata = std::map<std::string, std::string>;

struct LoadedImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // float values as OIIO converts them (8-bit formats map to [0, 1])
  ImageMetadata metadata;
  bool low_dynamic_range = false;  // stored as 8/16-bit integers (PNG, JPEG, ...)
};

// Writes float pixels. 8/16-bit formats are written from `pixels` as they are (already tone
// mapped to [0, 1] by the caller); float formats keep full precision (EXR as 32-bit float).
void write_image(const std::string& path, int width, int height, int channels, const float* pixels,
                 const ImageMetadata& metadata);
// Largest image read_image accepts, in values (width x height x channels): 1 GiB of float32, an
// 8k x 8k RGBA image. Larger, empty or volume (depth > 1) images raise std::invalid_argument
// before any allocation.
inline constexpr uint64_t kMaxImageValues = uint64_t{1} << 28;
// Reads subimage 0 as float pixels; std::invalid_argument if the file cannot be read.
LoadedImage read_image(const std::string& path);

}  // namespace dualight
