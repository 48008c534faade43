// samples/embed_window.cpp: a host with its own GLFW window, in which nearshore draws the sea
// (C++ API). The host owns the window, the context and the clock; nearshore streams the baked
// harbour, synthesises the deep water around it and draws both, with a tug under way (its hull,
// bow wave and wake: ships::ShipFleet drawn through ships::FleetLayers; from C the same is
// nearshore_renderer_set_fleet).
//
//   embed_window SEQUENCE_FOLDER [FRAMES [OUT.ppm]]
//
// With FRAMES it draws that many frames at a fixed 30 fps clock and exits (CI runs it under
// xvfb-run), writing the last one to OUT.ppm if given; without, it runs until the window closes.
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "nearshore/core/error.hpp"
#include "nearshore/playback/gl_loader.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/ships/fleet_layers.hpp"
#include "nearshore/ships/generic_hulls.hpp"

namespace {

void write_ppm(const nearshore::Image& image, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << image.width() << " " << image.height() << "\n255\n";
  for (float value : image.pixels()) {
    const float clamped = value < 0.f ? 0.f : (value > 1.f ? 1.f : value);
    out.put(static_cast<char>(static_cast<unsigned char>(clamped * 255.f + 0.5f)));
  }
}

int run(int argc, char** argv) {
  const int frame_limit = argc > 2 ? std::atoi(argv[2]) : 0;  // 0: until the window closes
  const int width = 960, height = 540;
  if (!glfwInit()) throw nearshore::Error("GLFW", "cannot start (no display?)", "run under xvfb-run -a");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, frame_limit > 0 ? GLFW_FALSE : GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(width, height, "host window: nearshore draws", nullptr, nullptr);
  if (!window) throw nearshore::Error("GLFW", "no OpenGL 3.3 core window", "run under xvfb-run -a");
  glfwMakeContextCurrent(window);

  {  // nearshore's GL objects live inside this scope, while the context is alive
    // 1. nearshore loads OpenGL from the host's context, then opens the sea.
    nearshore::playback::load_opengl(reinterpret_cast<nearshore::playback::GlProcAddressFunction>(glfwGetProcAddress));
    nearshore::runtime::StreamingEngine sea(argv[1]);
    nearshore::playback::WaterRenderer renderer;  // quadtree grid, default settings
    const auto site = sea.site();
    const nearshore::playback::Camera camera = nearshore::playback::Camera::overlooking_site(site->width_m, site->height_m);
    const nearshore::playback::Lighting lighting;
    sea.wait_until_ready(0.0, std::chrono::seconds(10));  // start-up only; the loop never waits

    // 2. A tug at 3 m/s heading east from a quarter of the way across; a place it cannot float
    //    (land, too shallow) is refused by name and the sea plays on without it.
    nearshore::ships::ShipFleet fleet;
    nearshore::ships::FleetLayers fleet_layers;
    fleet.set_site(site);
    nearshore::ships::ShipDefinition tug;
    tug.name = "Tug";
    tug.hull = nearshore::ships::harbour_tug();
    tug.loading.draft_m = 3.0;
    tug.x_m = 0.25 * site->width_m, tug.y_m = 0.5 * site->height_m;
    tug.heading_deg = 90.0;
    tug.initial_speed_m_s = 3.0;
    tug.orders.speed_m_s = 3.0;
    try {
      const std::size_t index = fleet.add_ship(tug);
      fleet_layers.set_hull(index, tug.hull, fleet.ship(index).body().particulars());
    } catch (const nearshore::Error& refused) {
      std::fprintf(stderr, "embed_window: no tug: %s\n", refused.what());
    }

    // 3. Per frame: advance the sea on the host's clock, step the ships on it, draw, present.
    double previous_s = 0.0;
    for (int frame = 0; !glfwWindowShouldClose(window) && (frame_limit == 0 || frame < frame_limit); ++frame) {
      const double time_s = frame_limit > 0 ? frame / 30.0 : glfwGetTime();
      const double dt_s = frame_limit > 0 || frame == 0 ? 1.0 / 30.0 : time_s - previous_s;
      previous_s = time_s;
      sea.advance_to(time_s);
      if (dt_s > 0) fleet.step(sea.snapshot(), dt_s);
      renderer.stage_upcoming(sea);  // the next keyframes go up within the upload budget
      int fb_width = 0, fb_height = 0;
      glfwGetFramebufferSize(window, &fb_width, &fb_height);
      renderer.render(sea.snapshot(), camera, lighting, fb_width, fb_height, {}, &fleet_layers.update(fleet));
      renderer.blit_to_window(fb_width, fb_height);
      glfwSwapBuffers(window);
      glfwPollEvents();
    }
    const nearshore::runtime::StreamingStats stats = sea.stats();
    std::printf("embed_window: %s, step %lld, %lld underruns, %.0f bytes uploaded in the last frame\n",
                stats.plan.c_str(), stats.plan_step, stats.underruns, double(renderer.last_frame().upload_bytes));
    if (argc > 3) write_ppm(renderer.read_pixels(), argv[3]);
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: embed_window SEQUENCE_FOLDER [FRAMES [OUT.ppm]]\n");
    return 2;
  }
  try {
    return run(argc, argv);
  } catch (const std::exception& error) {  // nearshore::Error names the file and the fix
    std::fprintf(stderr, "embed_window: %s\n", error.what());
    return 1;
  }
}
