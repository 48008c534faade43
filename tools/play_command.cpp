#include "command_support.hpp"

namespace nearshore::tools {

void add_play_command(CLI::App& app) {
  add_unbuilt_command(app, "play", "Play a baked sequence back with the OpenGL runtime (window or screenshot)", "nearshore play out/bake --screenshot shot.png", "the playback issue, not filed yet");
}

}  // namespace nearshore::tools
