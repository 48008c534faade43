// A program that links the runtime and nothing else: the ldd test reads its shared libraries to
// prove the runtime brings none of the bake side's (GDAL, OpenVDB, CGAL, libpng, FreeType).
#include <cstdio>

#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"

int main(int argc, char** argv) {
  if (argc > 1) {
    // Reached only when asked, so the linker keeps the runtime's code in the probe.
    nearshore::runtime::StreamingEngine engine(argv[1]);
    engine.advance_to(0.0);
    const nearshore::runtime::SurfaceSampler sampler(engine.snapshot());
    std::printf("%.3f m at the origin\n", sampler.elevation_m(0.0, 0.0));
    nearshore::playback::WaterRenderer renderer;
  }
  return 0;
}
