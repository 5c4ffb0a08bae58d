#include "film/image_io.h"

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

namespace dualight {

namespace {

// File formats that can hold float samples; everything else gets 8 bits per channel.
bool holds_float(const std::string& format) {
  return format == "openexr" || format == "hdr" || format == "tiff" || format == "fits" || format == "pfm";
}

}  // namespace

void write_image(const std::string& path, int width, int height, int channels, const float* pixels,
                 const ImageMetadata& metadata) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::invalid_argument("cannot write '" + path + "': " + OIIO::geterror());
  const std::string format = out->format_name();
  const OIIO::TypeDesc storage = holds_float(format) ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(width, height, channels, storage);
  if (format == "openexr") spec.attribute("compression", "zip");
  for (const auto& [key, value] : metadata) spec.attribute(key, value);
  if (!out->open(path, spec)) throw std::runtime_error("cannot open '" + path + "': " + out->geterror());
  if (!out->write_image(OIIO::TypeDesc::FLOAT, pixels)) {
    throw std::runtime_error("cannot write '" + path + "': " + out->geterror());
  }
  if (!out->close()) throw std::runtime_error("cannot close '" + path + "': " + out->geterror());
}

namespace {

LoadedImage read_image_unchecked(const std::string& path);

}  // namespace

LoadedImage read_image(const std::string& path) {
  // A damaged header can also make the decoder itself ask for more memory than there is (found by
  // fuzzing: an EXR whose chunk table was out of all proportion): that is a bad file, not a crash.
  try {
    return read_image_unchecked(path);
  } catch (const std::bad_alloc&) {
    throw std::invalid_argument("cannot read image '" + path +
                                "': decoding it asks for more memory than is available (a damaged header?)");
  }
}

namespace {

LoadedImage read_image_unchecked(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::invalid_argument("cannot read image '" + path + "': " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  // The header is checked before anything is allocated: a damaged or hostile header can claim a
  // huge data window (found by fuzzing: an EXR whose dataWindow asked for terabytes), and a
  // volume image (depth > 1, as TIFF allows) would hold depth times the pixels read below.
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw std::invalid_argument("cannot read image '" + path + "': it has no pixels (" +
                                std::to_string(spec.width) + " x " + std::to_string(spec.height) + " x " +
                                std::to_string(spec.nchannels) + " channels)");
  }
  if (spec.depth != 1) {
    throw std::invalid_argument("cannot read image '" + path + "': volume images (depth " +
                                std::to_string(spec.depth) + ") are not supported");
  }
  const uint64_t values = static_cast<uint64_t>(spec.width) * static_cast<uint64_t>(spec.height) *
                          static_cast<uint64_t>(spec.nchannels);
  if (values > kMaxImageValues) {
    throw std::invalid_argument("cannot read image '" + path + "': " + std::to_string(spec.width) + " x " +
                                std::to_string(spec.height) + " x " + std::to_string(spec.nchannels) +
                                " channels is more than " + std::to_string(kMaxImageValues) +
                                " values (1 GiB of float32)");
  }
  LoadedImage img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.nchannels;
  img.low_dynamic_range = !(spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                            spec.format.basetype == OIIO::TypeDesc::HALF ||
                            spec.format.basetype == OIIO::TypeDesc::DOUBLE);
  img.pixels.resize(static_cast<size_t>(img.width) * img.height * img.channels);
  if (!in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::FLOAT, img.pixels.data())) {
    throw std::invalid_argument("cannot decode image '" + path + "': " + in->geterror());
  }
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    if (p.type() == OIIO::TypeDesc::STRING) img.metadata[p.name().string()] = p.get_string();
  }
  in->close();
  return img;
}

}  // namespace

}  // namespace dualight
