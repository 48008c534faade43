#include "nearshore/bake/deep_water_record.hpp"

namespace nearshore::bake {

sequence::DeepWaterSection describe_deep_water_field(const ocean::DeepWaterField& field) {
  const ocean::DeepWaterSpecification& spec = field.specification();
  sequence::DeepWaterSection section;
  section.spectrum = spec.spectrum->to_json();
  section.mean_direction_rad = spec.spectrum->mean_direction_rad();
  section.still_water_depth_m = spec.still_water_depth_m;
  section.loop_period_s = spec.loop_period_s;
  section.choppiness = spec.choppiness;
  section.seed = spec.seed;
  section.significant_wave_height_m = field.significant_wave_height_m();
  section.spectrum_significant_wave_height_m = spec.spectrum->significant_wave_height_m();
  section.unresolved_slope_variance = field.unresolved_slope_variance();
  section.foam_breaking_jacobian = ocean::kStokesBreakingJacobian;
  for (int i = 0; i < field.cascade_count(); ++i) {
    const ocean::CascadeBand band = field.band(i);
    sequence::DeepWaterCascadeRecord cascade;
    cascade.tile_length_m = band.tile_length_m;
    cascade.grid_size = field.lattice(i).grid_size;
    cascade.min_wavenumber_rad_m = band.min_wavenumber_rad_m;
    cascade.max_wavenumber_rad_m = band.max_wavenumber_rad_m;
    cascade.variance_m2 = field.cascade_variance_m2(i);
    cascade.slope_variance = field.cascade_slope_variance(i);
    section.cascades.push_back(cascade);
  }
  return section;
}

void write_deep_water_coefficient_files(const ocean::DeepWaterField& field, const std::filesystem::path& folder,
                                        sequence::DeepWaterSection& section) {
  for (int i = 0; i < field.cascade_count(); ++i) {
    const ocean::CascadeLattice lattice = field.lattice(i);
    sequence::DeepWaterCoefficients coefficients;
    coefficients.grid_size = lattice.grid_size;
    coefficients.tile_length_m = lattice.tile_length_m;
    coefficients.loop_period_s = field.specification().loop_period_s;
    coefficients.amplitude_m.assign(lattice.amplitude_m.begin(), lattice.amplitude_m.end());
    // The file stores phases and frequencies as float32 and harmonics as int32 (docs/deep-water.md).
    coefficients.phase_rad.assign(lattice.phase_rad.begin(), lattice.phase_rad.end());
    coefficients.angular_frequency_rad_s.assign(lattice.angular_frequency_rad_s.begin(),
                                                lattice.angular_frequency_rad_s.end());
    coefficients.harmonic.reserve(lattice.harmonic.size());
    for (const long long harmonic : lattice.harmonic) coefficients.harmonic.push_back(static_cast<std::int32_t>(harmonic));
    section.cascades.at(static_cast<std::size_t>(i)).coefficients =
        sequence::write_deep_water_coefficients(folder, i, coefficients);
  }
}

}  // namespace nearshore::bake
