// The exr-displacement export: per frame an RGBA float OpenEXR of the surface's displacement from
// still water, what Blender's Vector Displacement node, Houdini's and Nuke's displacement read:
//   R = x (east), G = y (north), B = z (up) displacement, metres, Z up; A = 1 water, 0 land.
// z is eta; x and y are the depth-averaged excursion of horizontal_excursion.hpp (zero, and said
// so, when fewer than two frames are exported: there is no motion to integrate). The only file of
// the export that includes OpenEXR.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <exception>
#include <vector>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/export/horizontal_excursion.hpp"

namespace nearshore::exports {
namespace {

constexpr const char* kExcursionMeaning =
    "depth-averaged horizontal excursion: the time integral of (P, Q) / (depth + eta) about the mean current over the "
    "exported frames (horizontal_excursion.hpp)";

void write_displacement_exr(const ExportInput& input, int index, double time_s, const std::string& horizontal,
                            const Raster<float>& eta, const Raster<float>* excursion_x, const Raster<float>* excursion_y) {
  const GridGeometry& g = input.harbour.geometry;
  const std::filesystem::path path = input.frame_file("displacement", index, "exr");
  std::vector<float> pixels(g.cell_count() * 4);
  for (int row = 0; row < g.rows; ++row)
    for (int column = 0; column < g.columns; ++column) {
      const std::size_t cell = static_cast<std::size_t>(row) * g.columns + column;
      float* rgba = &pixels[(static_cast<std::size_t>(g.rows - 1 - row) * g.columns + column) * 4];  // line 0 north
      if (input.is_land(cell)) {
        rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.0f;
        continue;
      }
      rgba[0] = excursion_x ? excursion_x->values()[cell] : 0.0f;
      rgba[1] = excursion_y ? excursion_y->values()[cell] : 0.0f;
      rgba[2] = eta.values()[cell];
      rgba[3] = 1.0f;
    }
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    try {
      Imf::Header header(g.columns, g.rows);
      header.compression() = Imf::ZIP_COMPRESSION;
      for (const char* channel : {"R", "G", "B", "A"}) header.channels().insert(channel, Imf::Channel(Imf::FLOAT));
      header.insert("nearshore_frame_index", Imf::IntAttribute(index));
      header.insert("nearshore_time_s", Imf::DoubleAttribute(time_s));
      header.insert("nearshore_displacement",
                    Imf::StringAttribute("R = x (east), G = y (north), B = z (up), metres; A = 1 water, 0 land"));
      header.insert("nearshore_horizontal_displacement", Imf::StringAttribute(horizontal));
      header.insert("nearshore_origin_x_m", Imf::DoubleAttribute(g.origin_x_m));
      header.insert("nearshore_origin_y_m", Imf::DoubleAttribute(g.origin_y_m));
      header.insert("nearshore_spacing_x_m", Imf::DoubleAttribute(g.spacing_x_m()));
      header.insert("nearshore_spacing_y_m", Imf::DoubleAttribute(g.spacing_y_m()));
      header.insert("nearshore_crs_wkt", Imf::StringAttribute(g.crs_wkt));
      Imf::FrameBuffer buffer;
      const std::size_t pixel_stride = 4 * sizeof(float), line_stride = pixel_stride * g.columns;
      const char* names[4] = {"R", "G", "B", "A"};
      for (int c = 0; c < 4; ++c)
        buffer.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data() + c), pixel_stride, line_stride));
      Imf::OutputFile file(temporary.c_str(), header);
      file.setFrameBuffer(buffer);
      file.writePixels(g.rows);
    } catch (const std::exception& e) {
      throw Error(path.string(), std::string("writing the EXR failed: ") + e.what(),
                  "check that the output folder is writable and has space");
    }
  });
}

}  // namespace

void write_exr_displacement(const ExportInput& input, ExportSummary& summary) {
  const int frames = input.frame_count();
  const bool horizontal = frames >= 2;
  summary.horizontal_displacement =
      horizontal ? kExcursionMeaning : "zero: one frame has no motion to integrate; export two frames or more";
  HorizontalExcursion excursion(input.harbour, input.reader.frame_interval_s());
  ProgressBar progress("EXR displacement export", horizontal ? 2.0 * frames : frames, "frames");
  sequence::Frame frame;
  if (horizontal) {
    // Pass 1: the mean current and the mean of the running integral.
    for (int index = input.first_frame; index < input.end_frame; ++index) {
      input.reader.read_frame_into(index, frame, sequence::ChannelSelection::dynamics());
      excursion.accumulate(frame.surface_elevation_m, frame.flux_x_m2_s, frame.flux_y_m2_s);
      progress.update(index - input.first_frame + 1.0, "pass 1: mean current");
    }
    excursion.finish_accumulation();
  }
  Raster<float> excursion_x, excursion_y;
  long long folded_cell_frames = 0;
  int worst_folded_cells = 0, worst_frame = -1;
  for (int index = input.first_frame; index < input.end_frame; ++index) {
    input.reader.read_frame_into(index, frame, sequence::ChannelSelection::dynamics());
    if (horizontal) {
      excursion.excursion(frame.surface_elevation_m, frame.flux_x_m2_s, frame.flux_y_m2_s, excursion_x, excursion_y);
      const int folded = folded_cell_count(input.harbour, excursion_x, excursion_y);
      folded_cell_frames += folded;
      if (folded > worst_folded_cells) worst_folded_cells = folded, worst_frame = index;
    }
    write_displacement_exr(input, index, input.reader.manifest().frame_time_s(index), summary.horizontal_displacement,
                           frame.surface_elevation_m, horizontal ? &excursion_x : nullptr,
                           horizontal ? &excursion_y : nullptr);
    record_file(summary, input.frame_file("displacement", index, "exr"));
    progress.update((horizontal ? frames : 0) + index - input.first_frame + 1.0, horizontal ? "pass 2: write" : "");
  }
  progress.finish();
  if (folded_cell_frames > 0) {
    std::size_t water_cells = 0;
    for (std::size_t cell = 0; cell < input.harbour.geometry.cell_count(); ++cell) water_cells += !input.is_land(cell);
    summary.notes.push_back(fmt::format(
        "the horizontal shift folds the displaced surface over itself in {:.3f} % of the water cells over the "
        "frames (at most {} cells, in frame {}): where the run-up is longer than a cell (swash); scale R and G "
        "down there if a displaced mesh must not overlap",
        100.0 * static_cast<double>(folded_cell_frames) / (static_cast<double>(water_cells) * frames),
        worst_folded_cells, worst_frame));
  }
}

}  // namespace nearshore::exports
