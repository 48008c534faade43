#pragma once
// Pictures of a flat-coloured sea (magenta on black, no sky), and where the water lies in them: for
// the grids' and the horizon's render tests.
#include <cstddef>
#include <vector>

#include "nearshore/core/image.hpp"
#include "nearshore/playback/water_renderer.hpp"

namespace nearshore::test {

// Flat magenta sea on black, no sky: every pixel is plainly water or not.
inline playback::DrawOptions flat_options() {
  playback::DrawOptions options;
  options.colouring = playback::SurfaceColouring::flat;
  options.flat_colour = {1.f, 0.f, 1.f};
  options.sky = false;
  options.background = {0.f, 0.f, 0.f};
  return options;
}
inline bool is_water(const Rgb& p) { return p[0] > 0.5f && p[1] < 0.5f && p[2] > 0.5f; }

// The first water row (from the top) of each column, -1 where the column has none.
inline std::vector<int> first_water_rows(const Image& image) {
  std::vector<int> rows(std::size_t(image.width()), -1);
  for (int x = 0; x < image.width(); ++x)
    for (int y = 0; y < image.height(); ++y)
      if (is_water(image.get(x, y))) {
        rows[std::size_t(x)] = y;
        break;
      }
  return rows;
}

}  // namespace nearshore::test
