#include "nearshore/core/image.hpp"

#include <algorithm>
#include <cstddef>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore {

Image::Image(int width, int height, Rgb background)
    : width_(width), height_(height), pixels_(static_cast<std::size_t>(std::max(width, 0)) * std::max(height, 0) * 3) {
  if (width <= 0 || height <= 0) throw Error("image", fmt::format("invalid size {} x {} px", width, height));
  for (std::size_t i = 0; i < pixels_.size(); i += 3)
    std::copy(background.begin(), background.end(), &pixels_[i]);
}

void Image::set(int x, int y, Rgb colour) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  std::copy(colour.begin(), colour.end(), &pixels_[(static_cast<std::size_t>(y) * width_ + x) * 3]);
}

Rgb Image::get(int x, int y) const {
  const float* p = &pixels_[(static_cast<std::size_t>(y) * width_ + x) * 3];
  return {p[0], p[1], p[2]};
}

void Image::fill_rectangle(int x0, int y0, int x1, int y1, Rgb colour) {
  for (int y = std::max(0, std::min(y0, y1)); y <= std::min(height_ - 1, std::max(y0, y1)); ++y)
    for (int x = std::max(0, std::min(x0, x1)); x <= std::min(width_ - 1, std::max(x0, x1)); ++x)
      set(x, y, colour);
}

}  // namespace nearshore
