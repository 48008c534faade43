#pragma once
// nearshore::scenegraph::SeaNode (namespace not nearshore::osg: OSG's macros write osg:: unqualified
// and would find it): the streamed sea inside an OpenSceneGraph scene graph (docs/osg.md).
//
// One node holds a runtime::StreamingEngine over a baked sequence folder and draws its
// SurfaceSnapshot with playback::WaterRenderer (the shaders and the snapshot contract of
// `nearshore play`) in OSG's draw traversal, with the OSG camera's own view and projection, into
// the framebuffer OSG is drawing (its window or a render-to-texture camera's target), depth-tested
// against and writing OSG's depth buffer: a ship model in the same scene is sorted against the
// water per pixel (its underwater part hidden). The node's local frame is the SITE frame of
// runtime/surface_snapshot.hpp (metres east, north of the harbour grid's south-west corner, z up
// from still water), so a host places its objects in site metres (or puts the node under a
// transform).
//
// Around its draw it saves the OpenGL state it changes and puts it back, then tells osg::State
// which of its records it can no longer trust (docs/osg.md "The GL-state contract").
//
// Threads: advance_to, set_display_time_s, set_reflected and the height queries belong to the
// thread that runs the update traversal (the host's main loop); the draw runs on OSG's draw
// thread and only reads what the last update published (under a lock). One OpenGL context: the
// renderer's GL objects live in the first context that draws the node (the loader nearshore uses
// is process-wide); another context drawing it is refused with an osg::notify warning.
#include <osg/Geode>
#include <osg/NodeVisitor>

#include <filesystem>
#include <memory>
#include <optional>

#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"

namespace nearshore::scenegraph {

struct SeaNodeSettings {
  playback::RendererSettings renderer;  ///< the grid, its parameters, local reflections, upload budget
  /// The sky, sun, weather and water optics. Its wind and sub-grid slope variance are set as
  /// `nearshore play` sets them (Beaufort 3's wind; the bake's unresolved slope variance) unless
  /// the host changes them; the foam onset is measured per deep keyframe as the viewer does.
  std::optional<playback::Lighting> lighting;
  playback::DrawOptions draw;           ///< sky on or off, colouring; draw_meshes is always false here
  runtime::StreamingOptions streaming;  ///< lockstep = true for pictures that depend on the time only
};

/// Elevation and more at a point of the sea the node shows, for a host floating its objects.
struct SeaPoint {
  double x_m = 0.0, y_m = 0.0;  ///< site frame
  runtime::SurfaceState state;
};

class SeaNode : public ::osg::Geode {
 public:
  /// Opens `sequence_folder` (a bake; throws nearshore::Error naming it when it cannot).
  explicit SeaNode(const std::filesystem::path& sequence_folder, SeaNodeSettings settings = {});

  const char* className() const override { return "SeaNode"; }
  const char* libraryName() const override { return "nearshore_osg"; }

  /// The display time is the frame stamp's simulation time (osgViewer's clock) unless fixed here:
  /// then every frame shows `display_time_s` (screenshots, tests, a host's own clock).
  void set_display_time_s(double display_time_s);
  void follow_frame_clock();
  /// The display time a frame whose frame stamp says `frame_time_s` shows (the fixed one, if set).
  double display_time_s_for_frame(double frame_time_s) const;
  /// Advances the sea to `display_time_s` now (what the update traversal does each frame), so a
  /// host can query the heights of the frame it is about to draw before its own update.
  void advance_to(double display_time_s);
  double display_time_s() const;

  /// The surface over site point (x_m, y_m) at the display time of the last advance, through the
  /// runtime's SurfaceSampler (the CPU twin of the drawn surface: docs/runtime.md).
  double elevation_m(double x_m, double y_m) const;
  runtime::SurfaceState surface_at(double x_m, double y_m) const;
  /// The site (size, grid, georeference of the harbour): where the sea is.
  std::shared_ptr<const runtime::HarbourSite> site() const;

  /// A subgraph whose objects are mirrored in the sea's local reflection (null: none). Its
  /// triangles are read once per osg::Geometry (again when its vertex array changes) and drawn
  /// by the renderer's hull path (playback::SolidMesh, mirrored only: OSG draws the objects
  /// themselves), placed each update by the subgraph's matrices relative to this node, coloured by
  /// the first osg::Material diffuse (or colour array) on the way down. The subgraph is usually
  /// also a child of the scene (the ship OSG draws).
  void set_reflected(::osg::Node* subgraph);

  /// The lighting drawn with (the foam onset changes as the deep water does).
  playback::Lighting lighting() const;
  void set_lighting(const playback::Lighting& lighting);
  /// What the last draw did (uploads, clip distances, grid) and how many objects it reflected.
  playback::FrameStatistics last_frame() const;
  int reflected_mesh_count() const;

  runtime::StreamingEngine& engine();

  struct Shared;  ///< what the update side publishes and the draw side reads (sea_node.cpp)

 protected:
  ~SeaNode() override;

 private:
  std::shared_ptr<Shared> shared_;
};

}  // namespace nearshore::scenegraph
