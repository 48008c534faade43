#pragma once
// An RGB picture in memory: what a renderer reads back and what a plot draws into. Pixels only;
// drawing lines and text and writing PNG files belong to the plot library (nearshore/plot/plot.hpp),
// so the runtime, which reads pictures back, does not link libpng or FreeType.
#include <array>
#include <vector>

namespace nearshore {

using Rgb = std::array<float, 3>;  ///< linear 0..1 red, green, blue

/// An RGB picture, row 0 at the TOP (as images are viewed).
class Image {
 public:
  Image(int width, int height, Rgb background = {1.f, 1.f, 1.f});
  int width() const { return width_; }
  int height() const { return height_; }
  /// Pixels outside the picture are ignored.
  void set(int x, int y, Rgb colour);
  Rgb get(int x, int y) const;
  void fill_rectangle(int x0, int y0, int x1, int y1, Rgb colour);
  const std::vector<float>& pixels() const { return pixels_; }

 private:
  int width_, height_;
  std::vector<float> pixels_;  // width * height * 3
};

}  // namespace nearshore
