// A program that links the runtime and nothing else: the ldd test reads its shared libraries to
// prove the runtime brings none of the bake side's (GDAL, OpenVDB, CGAL, libpng, FreeType).
#include <cstdio>

#include "nearshore/playback/sequence_player.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

int main(int argc, char** argv) {
  if (argc > 1) {
    // Reached only when asked, so the linker keeps the runtime's code in the probe.
    const nearshore::sequence::SequenceReader reader(argv[1]);
    nearshore::playback::SequencePlayer player(reader);
    player.advance_to(0.0);
    std::printf("%zu frames in the order\n", player.frame_order().size());
  }
  return 0;
}
