#include "validation_plots.hpp"

#include <algorithm>

namespace nearshore::validation {

Image tile_plots(const std::vector<LinePlot>& plots, int columns) {
  std::vector<Image> images;
  int cell_width = 0, cell_height = 0;
  for (const LinePlot& plot : plots) {
    images.push_back(render_line_plot(plot));
    cell_width = std::max(cell_width, images.back().width());
    cell_height = std::max(cell_height, images.back().height());
  }
  const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
  Image out(cell_width * std::min<int>(columns, static_cast<int>(images.size())), cell_height * rows);
  for (std::size_t k = 0; k < images.size(); ++k) {
    const int x0 = static_cast<int>(k % columns) * cell_width, y0 = static_cast<int>(k / columns) * cell_height;
    for (int y = 0; y < images[k].height(); ++y)
      for (int x = 0; x < images[k].width(); ++x) out.set(x0 + x, y0 + y, images[k].get(x, y));
  }
  return out;
}

}  // namespace nearshore::validation
