// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::common::Image's pixel formats and their names
// (gazebo/common/Image.hh): the enum PixelFormat, PixelFormatNames and ConvertPixelFormat, as Gazebo 11's. Images
// themselves (loading, saving, pixels) are not offered: constructing one does not build.
#pragma once

#include <string>

namespace gazebo {
namespace common {

// The names of Image::PixelFormat, in its order.
static std::string PixelFormatNames[] = {
    "UNKNOWN_PIXEL_FORMAT", "L_INT8",      "L_INT16",     "RGB_INT8",    "RGBA_INT8",   "BGRA_INT8",
    "RGB_INT16",            "RGB_INT32",   "BGR_INT8",    "BGR_INT16",   "BGR_INT32",   "R_FLOAT16",
    "RGB_FLOAT16",          "R_FLOAT32",   "RGB_FLOAT32", "BAYER_RGGB8", "BAYER_BGGR8", "BAYER_GBRG8",
    "BAYER_GRBG8"};

class Image {
 public:
  enum PixelFormat {
    UNKNOWN_PIXEL_FORMAT = 0,
    L_INT8,
    L_INT16,
    RGB_INT8,
    RGBA_INT8,
    BGRA_INT8,
    RGB_INT16,
    RGB_INT32,
    BGR_INT8,
    BGR_INT16,
    BGR_INT32,
    R_FLOAT16,
    RGB_FLOAT16,
    R_FLOAT32,
    RGB_FLOAT32,
    BAYER_RGGB8,
    BAYER_BGGR8,
    BAYER_GBRG8,
    BAYER_GRBG8,
    PIXEL_FORMAT_COUNT
  };
  // A format's name (PixelFormatNames) or an older one: "L8", "L16", "L_UINT16", "R8G8B8", "R16G16B16",
  // "RGB_UINT16", "FLOAT32", "FLOAT16"; anything else UNKNOWN_PIXEL_FORMAT.
  static PixelFormat ConvertPixelFormat(const std::string& _format);
  // car: images are not offered
  Image() = delete;
};

}  // namespace common
}  // namespace gazebo
