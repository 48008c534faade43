#pragma once
// Pictures of model against data for docs/validation.md: several core line plots tiled into one PNG.
#include <filesystem>
#include <vector>

#include "nearshore/plot/plot.hpp"

namespace nearshore::validation {

/// The plots laid out `columns` per row (each at its own size, cells as large as the largest), on white.
Image tile_plots(const std::vector<LinePlot>& plots, int columns);

/// The data's colour (markers) and the model's (line), the same in every figure.
inline constexpr Rgb kDataColour = {0.85f, 0.33f, 0.10f};
inline constexpr Rgb kModelColour = {0.00f, 0.45f, 0.74f};
inline constexpr Rgb kReferenceColour = {0.40f, 0.40f, 0.40f};

}  // namespace nearshore::validation
