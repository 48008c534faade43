// The netcdf export: one CF-1.8 NetCDF-4 file (CF conventions 1.8, sections 4 (coordinates), 5.6
// (grid mappings, auxiliary lat/lon) and 2.5.1 (_FillValue)). The only file that includes netcdf.h.
#include <netcdf.h>
#include <sys/statvfs.h>

#include <cerrno>

#include <array>
#include <vector>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/map_projection.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::exports {
namespace {

// WGS 84, the datum of every projection nearshore writes (core/map_projection.hpp).
constexpr double kWgs84SemiMajorAxis_m = 6378137.0;
constexpr double kWgs84InverseFlattening = 298.257223563;

class NetcdfFile {
 public:
  NetcdfFile(const std::filesystem::path& temporary, const std::filesystem::path& final_path) : path_(final_path) {
    check(nc_create(temporary.c_str(), NC_NETCDF4 | NC_CLOBBER, &id_), "creating the file");
  }
  // A file not closed cleanly (a write failed, e.g. on a full disk) is aborted, not closed: nc_close
  // would flush again into the full disk, and a failed nc_close leaves the file open in netCDF's and
  // HDF5's lists, which HDF5 then flushed once more at exit and segfaulted (issue 44). nc_abort
  // releases it without writing and always drops netCDF's handle.
  ~NetcdfFile() {
    if (id_ >= 0) nc_abort(id_);
  }
  NetcdfFile(const NetcdfFile&) = delete;
  NetcdfFile& operator=(const NetcdfFile&) = delete;

  int id() const { return id_; }
  void check(int status, const std::string& what) const {
    if (status == NC_NOERR) return;
    // netCDF says only "HDF error" when HDF5's write failed; the errno of that write, or the free
    // space left, says whether the disk is full.
    const int error_number = errno;
    std::string reason = nc_strerror(status);
    struct statvfs disk {};
    if (error_number == ENOSPC || error_number == EDQUOT)
      reason += ": " + write_failure_reason(error_number);
    else if (::statvfs(path_.parent_path().c_str(), &disk) == 0 &&
             static_cast<double>(disk.f_bavail) * static_cast<double>(disk.f_frsize) < 65536.0)
      reason += ": " + write_failure_reason(ENOSPC);
    throw Error(path_.string(), fmt::format("{} failed: {}", what, reason),
                "check that the output folder is writable and has space; nothing was replaced");
  }
  int dimension(const char* name, std::size_t length) {
    int dimension_id = -1;
    check(nc_def_dim(id_, name, length, &dimension_id), std::string("defining dimension ") + name);
    return dimension_id;
  }
  int variable(const char* name, nc_type type, std::initializer_list<int> dimensions) {
    int variable_id = -1;
    const std::vector<int> ids(dimensions);
    check(nc_def_var(id_, name, type, static_cast<int>(ids.size()), ids.data(), &variable_id),
          std::string("defining variable ") + name);
    return variable_id;
  }
  void text(int variable, const char* name, const std::string& value) {
    check(nc_put_att_text(id_, variable, name, value.size(), value.c_str()), std::string("writing attribute ") + name);
  }
  void number(int variable, const char* name, double value) {
    check(nc_put_att_double(id_, variable, name, NC_DOUBLE, 1, &value), std::string("writing attribute ") + name);
  }
  void close() {
    const int status = nc_close(id_);
    if (status == NC_NOERR) id_ = -1;  // else the destructor aborts it
    check(status, "closing the file");
  }

 private:
  std::filesystem::path path_;
  int id_ = -1;
};

// The CF grid mapping (appendix F, transverse_mercator) of the projections nearshore writes.
void write_grid_mapping(NetcdfFile& file, int crs, const GridGeometry& geometry) {
  const nlohmann::json& projection = geometry.projection;
  const std::string kind = projection.value("kind", std::string{});
  file.text(crs, "grid_mapping_name", "transverse_mercator");
  if (kind == "utm") {
    const int zone = projection.value("zone", 0);
    const bool north = projection.value("north", true);
    file.number(crs, "longitude_of_central_meridian", -183.0 + 6.0 * zone);
    file.number(crs, "latitude_of_projection_origin", 0.0);
    file.number(crs, "scale_factor_at_central_meridian", 0.9996);
    file.number(crs, "false_easting", 500000.0);
    file.number(crs, "false_northing", north ? 0.0 : 10000000.0);
  } else {
    file.number(crs, "longitude_of_central_meridian", projection.value("central_meridian_deg", 0.0));
    file.number(crs, "latitude_of_projection_origin", projection.value("origin_latitude_deg", 0.0));
    file.number(crs, "scale_factor_at_central_meridian", projection.value("scale_factor", 1.0));
    file.number(crs, "false_easting", projection.value("false_easting_m", 0.0));
    file.number(crs, "false_northing", projection.value("false_northing_m", 0.0));
  }
  file.text(crs, "reference_ellipsoid_name", "WGS 84");
  file.number(crs, "semi_major_axis", kWgs84SemiMajorAxis_m);
  file.number(crs, "inverse_flattening", kWgs84InverseFlattening);
  file.text(crs, "long_name", MapProjection::from_json(projection, "grid geometry").describe());
}

struct FieldVariable {
  const char* name;
  const char* standard_name;  // empty: CF has none for this quantity, long_name says what it is
  const char* long_name;
  const char* units;
  Raster<float> sequence::Frame::* field;
};

// P and Q have no CF standard name (depth-integrated volume flux per unit width); long_name and
// units say what they are, and the depth-averaged velocity is (P, Q) / (depth + eta).
constexpr std::array<FieldVariable, 4> kFields = {{
    {"surface_elevation", "sea_surface_height_above_mean_sea_level",
     "surface elevation eta above the still water level of the bake", "m", &sequence::Frame::surface_elevation_m},
    {"flux_x", "", "depth-integrated volume flux P along x (east) per unit width", "m2 s-1",
     &sequence::Frame::flux_x_m2_s},
    {"flux_y", "", "depth-integrated volume flux Q along y (north) per unit width", "m2 s-1",
     &sequence::Frame::flux_y_m2_s},
    {"breaking", "", "wave breaking indicator, 0 none .. 1 fully breaking", "1", &sequence::Frame::breaking},
}};

}  // namespace

void write_netcdf(const ExportInput& input, ExportSummary& summary) {
  const GridGeometry& g = input.harbour.geometry;
  const sequence::SequenceManifest& manifest = input.reader.manifest();
  const std::filesystem::path path = input.output_folder / "sequence.nc";
  const bool georeferenced = !g.projection.is_null() && g.projection.is_object() && g.projection.contains("kind");
  if (!georeferenced)
    summary.notes.push_back("the grid has no map projection (a laboratory frame): x and y are metres from its "
                            "south-west corner, and the file has no lat/lon and no grid mapping");
  const std::size_t cells = g.cell_count();
  const float fill = kNoDataValue;

  // The disk it needs, before anything is written: HDF5 does not recover from a write that meets a
  // full disk (the failed close leaves its file open, and HDF5's clean-up at exit then segfaulted,
  // issue 44). Upper bound: the fields uncompressed (4 of float32 per cell and frame), the
  // coordinates and depth, and 1 MiB of HDF5 metadata; deflate makes the file smaller.
  {
    const double field_bytes = 4.0 * 4.0 * static_cast<double>(cells) * input.frame_count();
    const double needed_bytes = field_bytes + (georeferenced ? 20.0 : 4.0) * static_cast<double>(cells) + (1 << 20);
    struct statvfs disk {};
    if (::statvfs(input.output_folder.c_str(), &disk) == 0) {
      const double free_bytes = static_cast<double>(disk.f_bavail) * static_cast<double>(disk.f_frsize);
      if (free_bytes < needed_bytes)
        throw Error(path.string(),
                    fmt::format("needs up to {:.1f} MB of disk ({} frames of {} cells, uncompressed) but {:.1f} MB are free in "
                                "{}: HDF5 cannot recover from a write that meets a full disk, so the export does not start",
                                needed_bytes / 1e6, input.frame_count(), cells, free_bytes / 1e6, input.output_folder.string()),
                    "free disk space, choose another output folder, or export fewer frames (ExportRequest::frames)");
    }
  }
  ProgressBar progress("NetCDF export", input.frame_count(), "frames");
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    NetcdfFile file(temporary, path);
    const int time_dimension = file.dimension("time", static_cast<std::size_t>(input.frame_count()));
    const int y_dimension = file.dimension("y", static_cast<std::size_t>(g.rows));
    const int x_dimension = file.dimension("x", static_cast<std::size_t>(g.columns));

    file.text(NC_GLOBAL, "Conventions", "CF-1.8");
    file.text(NC_GLOBAL, "title", "nearshore baked sequence " + input.reader.folder().filename().string());
    file.text(NC_GLOBAL, "source",
              "enhanced Boussinesq bake (Li, Jin, Ren & Hua 2010; Madsen & Sorensen 1992), nearshore sequence format 1");
    file.text(NC_GLOBAL, "history", "nearshore export of " + input.reader.folder().string());
    file.text(NC_GLOBAL, "comment",
              "Land cells of the harbour grid are _FillValue in every field; the frames' still water level is taken "
              "as mean sea level.");
    file.number(NC_GLOBAL, "nearshore_first_frame", input.first_frame);
    file.number(NC_GLOBAL, "nearshore_frame_interval_s", manifest.frame_interval_s);
    file.number(NC_GLOBAL, "nearshore_loop_period_s", manifest.loop_period_s);

    // Coordinates: time, then the projected x/y of the cell centres (CF 4.4, 5.6).
    const int time = file.variable("time", NC_DOUBLE, {time_dimension});
    file.text(time, "standard_name", "time");
    file.text(time, "long_name", "simulated time after the bake's spin-up");
    // CF 4.4 asks for a reference time; a bake has none, so the epoch stands in for its start.
    file.text(time, "units", "seconds since 1970-01-01 00:00:00");
    file.text(time, "calendar", "standard");
    file.text(time, "axis", "T");
    file.text(time, "comment", "a bake has no calendar date: the reference time stands for the bake's start");
    const int x = file.variable("x", NC_DOUBLE, {x_dimension});
    const int y = file.variable("y", NC_DOUBLE, {y_dimension});
    for (const auto& [variable, axis, direction] :
         {std::tuple{x, "X", "x"}, std::tuple{y, "Y", "y"}}) {
      if (georeferenced) {
        file.text(variable, "standard_name", std::string("projection_") + direction + "_coordinate");
        file.text(variable, "long_name", std::string(direction) + " coordinate of projection (cell centres)");
      } else {
        file.text(variable, "long_name",
                  std::string(direction) + " of the cell centres from the grid's south-west corner");
      }
      file.text(variable, "units", "m");
      file.text(variable, "axis", axis);
    }
    int crs = -1, latitude = -1, longitude = -1;
    if (georeferenced || !g.crs_wkt.empty()) {
      crs = file.variable("crs", NC_INT, {});
      if (georeferenced) write_grid_mapping(file, crs, g);
      if (!g.crs_wkt.empty()) {
        file.text(crs, "crs_wkt", g.crs_wkt);
        file.text(crs, "spatial_ref", g.crs_wkt);  // where GDAL looks first
      }
    }
    if (georeferenced) {
      latitude = file.variable("lat", NC_DOUBLE, {y_dimension, x_dimension});
      file.text(latitude, "standard_name", "latitude");
      file.text(latitude, "long_name", "latitude of the cell centre (WGS 84)");
      file.text(latitude, "units", "degrees_north");
      longitude = file.variable("lon", NC_DOUBLE, {y_dimension, x_dimension});
      file.text(longitude, "standard_name", "longitude");
      file.text(longitude, "long_name", "longitude of the cell centre (WGS 84)");
      file.text(longitude, "units", "degrees_east");
    }
    auto describe_field = [&](int variable, const char* standard_name, const char* long_name, const char* units) {
      if (standard_name[0] != '\0') file.text(variable, "standard_name", standard_name);
      file.text(variable, "long_name", long_name);
      file.text(variable, "units", units);
      file.check(nc_def_var_fill(file.id(), variable, NC_FILL, &fill), "setting _FillValue");
      if (georeferenced) file.text(variable, "coordinates", "lat lon");
      if (crs >= 0) file.text(variable, "grid_mapping", "crs");
    };
    const int depth = file.variable("depth", NC_FLOAT, {y_dimension, x_dimension});
    describe_field(depth, "sea_floor_depth_below_sea_level", "still-water depth d of the harbour grid", "m");
    file.text(depth, "positive", "down");
    std::array<int, kFields.size()> field_ids{};
    const std::size_t chunk[3] = {1, static_cast<std::size_t>(g.rows), static_cast<std::size_t>(g.columns)};
    for (std::size_t f = 0; f < kFields.size(); ++f) {
      field_ids[f] = file.variable(kFields[f].name, NC_FLOAT, {time_dimension, y_dimension, x_dimension});
      describe_field(field_ids[f], kFields[f].standard_name, kFields[f].long_name, kFields[f].units);
      // One chunk per frame (a reader of one time step touches one chunk); deflate level 1 with
      // the byte shuffle: the frames' half-precision values leave the low mantissa bytes zero.
      file.check(nc_def_var_chunking(file.id(), field_ids[f], NC_CHUNKED, chunk), "setting chunks");
      file.check(nc_def_var_deflate(file.id(), field_ids[f], 1, 1, 1), "setting compression");
    }
    file.check(nc_enddef(file.id()), "ending the definitions");

    // 2. Coordinate values: time of each exported frame, cell centres, lat/lon through the grid's
    //    projection (GeographicLib), the still-water depth with land filled.
    std::vector<double> times;
    for (int index = input.first_frame; index < input.end_frame; ++index) times.push_back(manifest.frame_time_s(index));
    file.check(nc_put_var_double(file.id(), time, times.data()), "writing time");
    std::vector<double> xs(static_cast<std::size_t>(g.columns)), ys(static_cast<std::size_t>(g.rows));
    for (int column = 0; column < g.columns; ++column) xs[static_cast<std::size_t>(column)] = g.cell_centre_x_m(column);
    for (int row = 0; row < g.rows; ++row) ys[static_cast<std::size_t>(row)] = g.cell_centre_y_m(row);
    file.check(nc_put_var_double(file.id(), x, xs.data()), "writing x");
    file.check(nc_put_var_double(file.id(), y, ys.data()), "writing y");
    if (georeferenced) {
      const MapProjection projection = MapProjection::from_json(g.projection, input.reader.folder().string());
      std::vector<double> latitudes(cells), longitudes(cells);
      for (int row = 0; row < g.rows; ++row)
        for (int column = 0; column < g.columns; ++column) {
          const LonLat place = projection.reverse({g.cell_centre_x_m(column), g.cell_centre_y_m(row)});
          const std::size_t cell = static_cast<std::size_t>(row) * g.columns + column;
          latitudes[cell] = place.latitude_deg;
          longitudes[cell] = place.longitude_deg;
        }
      file.check(nc_put_var_double(file.id(), latitude, latitudes.data()), "writing lat");
      file.check(nc_put_var_double(file.id(), longitude, longitudes.data()), "writing lon");
    }
    std::vector<float> values(cells);
    for (std::size_t cell = 0; cell < cells; ++cell)
      values[cell] = input.is_land(cell) ? fill : input.harbour.still_water_depth_m.values()[cell];
    file.check(nc_put_var_float(file.id(), depth, values.data()), "writing depth");

    // 3. The frames, one time step of every field at a time (netCDF rows run south to north like
    //    the Raster rows, so no flip), land filled: the frames hold the terrain height there.
    sequence::Frame frame;
    for (int index = input.first_frame; index < input.end_frame; ++index) {
      input.reader.read_frame_into(index, frame);
      const std::size_t start[3] = {static_cast<std::size_t>(index - input.first_frame), 0, 0};
      for (std::size_t f = 0; f < kFields.size(); ++f) {
        const std::vector<float>& source = (frame.*kFields[f].field).values();
        for (std::size_t cell = 0; cell < cells; ++cell) values[cell] = input.is_land(cell) ? fill : source[cell];
        file.check(nc_put_vara_float(file.id(), field_ids[f], start, chunk, values.data()),
                   fmt::format("writing {} of frame {}", kFields[f].name, index));
      }
      progress.update(index - input.first_frame + 1.0);
    }
    file.close();
  });
  progress.finish();
  record_file(summary, path);
}

}  // namespace nearshore::exports
