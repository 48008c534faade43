#include "viewer_panel.hpp"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::viewer {

ViewerPanel::ViewerPanel(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the user's files
  ImGui::StyleColorsDark();
  // install_callbacks = true chains GLFW's input callbacks to any the viewer set before.
  if (!ImGui_ImplGlfw_InitForOpenGL(window, true) || !ImGui_ImplOpenGL3_Init("#version 330 core")) {
    ImGui::DestroyContext();
    throw Error("the viewer's panel", "Dear ImGui could not start on this OpenGL context",
                "run with an OpenGL 3.3 core context (under Xvfb: xvfb-run -a)");
  }
}

ViewerPanel::~ViewerPanel() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

bool ViewerPanel::wants_input() const {
  const ImGuiIO& io = ImGui::GetIO();
  return io.WantCaptureMouse || io.WantCaptureKeyboard;
}

bool ViewerPanel::draw(ViewerPanelModel& m) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  bool changed = false;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.75f);
  ImGui::SetNextWindowSize(ImVec2(420, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("nearshore");
  ImGui::Text("%.1f fps   frame %.2f ms   main thread %.2f ms", m.frames_per_s, m.frame_time_ms, m.main_thread_ms);
  ImGui::Text("t = %.2f s   step %lld%s", m.display_time_s, m.plan_step, m.crossfading ? "  (crossfade)" : "");
  ImGui::TextWrapped("plan: %s", m.plan_name.c_str());
  const float fill = m.ring_capacity > 0 ? float(m.ring_filled) / float(m.ring_capacity) : 0.f;
  ImGui::ProgressBar(fill, ImVec2(220, 0), fmt::format("ring {}/{}", m.ring_filled, m.ring_capacity).c_str());
  ImGui::Text("underruns %llu   held frames %llu   transitions %llu", m.underruns, m.bad_frames_held,
              m.transitions_taken);
  ImGui::Text("decode %.1fx real time", m.decode_real_time_multiple);
  if (!m.message.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.75f, 0.3f, 1.f));
    ImGui::TextWrapped("%s", m.message.c_str());
    ImGui::PopStyleColor();
  }
  if (!m.ships.empty()) {
    ImGui::Separator();
    ImGui::Text("ships: %.2f ms a frame   ship 0: arrows throttle and helm, Enter midships", m.ships_ms);
    if (ImGui::BeginTable("ships", 5, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit)) {
      for (const char* heading : {"ship", "speed kn", "heading", "engine / rudder", "state"}) ImGui::TableSetupColumn(heading);
      ImGui::TableHeadersRow();
      for (const ShipReadout& ship : m.ships) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::Text("%s%s", ship.name.c_str(), ship.manual ? " (keys)" : "");
        ImGui::TableNextColumn();
        ImGui::Text("%.1f", ship.speed_kn);
        ImGui::TableNextColumn();
        ImGui::Text("%03.0f deg", ship.heading_deg);
        ImGui::TableNextColumn();
        ImGui::Text("%+.2f / %+.0f deg", ship.engine_order, ship.rudder_deg);
        ImGui::TableNextColumn();
        if (ship.aground) {
          ImGui::TextColored(ImVec4(1.f, 0.4f, 0.3f, 1.f), "AGROUND, heel %.1f deg", ship.heel_deg);
        } else {
          ImGui::Text("afloat");
        }
      }
      ImGui::EndTable();
    }
  }
  ImGui::Separator();
  ImGui::Text("camera %.5f, %.5f  height %.0f m", m.camera_latitude_deg, m.camera_longitude_deg, m.camera_height_m);
  const char* grids[] = {"radial", "quadtree", "projected"};
  changed |= ImGui::Combo("grid", &m.grid, grids, 3);
  const char* plans[] = {"auto", "exact period", "optimal loop", "random walk", "frame order"};
  changed |= ImGui::Combo("plan", &m.plan, plans, 5);
  float scale = float(m.time_scale);
  if (ImGui::SliderFloat("time scale", &scale, 0.f, 4.f, "%.2fx")) m.time_scale = scale, changed = true;
  changed |= ImGui::Checkbox("paused", &m.paused);
  if (m.deep_water_from_bake) {
    ImGui::TextDisabled("deep water: the bake's own cascades");
  } else {
    changed |= ImGui::SliderInt("Beaufort", &m.beaufort_force, 0, 12);
    float wind = float(m.wind_from_deg);
    if (ImGui::SliderFloat("wind from", &wind, 0.f, 360.f, "%.0f deg")) m.wind_from_deg = wind, changed = true;
  }
  ImGui::InputDouble("latitude", &m.jump_lat_lon_deg[0], 0.0, 0.0, "%.6f");
  ImGui::InputDouble("longitude", &m.jump_lat_lon_deg[1], 0.0, 0.0, "%.6f");
  if (ImGui::Button("jump there")) m.jump_requested = true, changed = true;
  // Lighting (docs/lighting.md): the sun, the air, what is in the water.
  const auto slider = [&changed](const char* label, double& value, float low, float high, const char* format) {
    float v = float(value);
    if (ImGui::SliderFloat(label, &v, low, high, format)) value = v, changed = true;
  };
  slider("sun azimuth", m.sun_azimuth_deg, 0.f, 360.f, "%.0f deg");
  slider("sun elevation", m.sun_elevation_deg, -20.f, 90.f, "%.1f deg");
  slider("haze (T)", m.haze, 1.7f, 10.f, "%.1f");
  slider("turbidity", m.turbidity_ntu, 0.f, 30.f, "%.1f NTU");
  slider("chlorophyll", m.chlorophyll_mg_m3, 0.f, 20.f, "%.2f mg/m3");
  slider("exposure", m.exposure, 0.1f, 10.f, "%.2fx");
  ImGui::TextDisabled("%s", m.gl_description.c_str());
  ImGui::End();
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  return changed;
}

}  // namespace nearshore::viewer
