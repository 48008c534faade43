#include "nearshore/osg/sea_node.hpp"

#include <osg/Drawable>
#include <osg/GLExtensions>
#include <osg/Geometry>
#include <osg/Material>
#include <osg/Notify>
#include <osg/RenderInfo>
#include <osg/TriangleIndexFunctor>
#include <osg/Viewport>

#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "gl_state_guard.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/ocean/whitecap_coverage.hpp"
#include "nearshore/playback/gl_loader.hpp"

namespace nearshore::scenegraph {

namespace {

playback::Matrix4 to_matrix4(const ::osg::Matrixd& m) {
  // osg::Matrixd's memory order is OpenGL's column-major order for column vectors (glLoadMatrixd).
  playback::Matrix4 out;
  for (int k = 0; k < 16; ++k) out[std::size_t(k)] = m.ptr()[k];
  return out;
}

// An OSG colour (display-referred, as modellers pick it) as the linear albedo playback lights.
Rgb linear_albedo(const ::osg::Vec4& colour) {
  auto linear = [](float c) { return float(std::pow(std::clamp(double(c), 0.0, 1.0), 2.2)); };
  return {linear(colour.r()), linear(colour.g()), linear(colour.b())};
}

struct TriangleIndices {
  std::vector<std::uint32_t>* out = nullptr;
  void operator()(unsigned a, unsigned b, unsigned c) const { out->insert(out->end(), {a, b, c}); }
};

// One osg::Geometry's triangles in its own frame, scaled by the scale its matrix had when read.
struct CachedMesh {
  std::vector<float> vertices_m;
  std::vector<std::uint32_t> triangles;
  unsigned modified_count = 0;
  std::array<double, 3> scale{};
  std::uint64_t id = 0;
};

}  // namespace

// What the update side publishes (under `mutex`) and the draw side reads. The engine, sampler
// and mesh cache belong to the update thread; the renderer to the draw thread.
struct SeaNode::Shared {
  std::mutex mutex;
  std::unique_ptr<runtime::StreamingEngine> engine;
  SeaNodeSettings settings;
  playback::Lighting lighting;
  ocean::WhitecapFoamOnset whitecaps;
  std::optional<double> fixed_time_s;
  double advanced_time_s = std::numeric_limits<double>::quiet_NaN();
  // Published by advance_to, read by the draw.
  runtime::SurfaceSnapshot snapshot;
  std::vector<std::shared_ptr<const runtime::HarbourKeyframe>> upcoming_harbour;
  std::vector<std::shared_ptr<const runtime::DeepWaterKeyframe>> upcoming_deep;
  std::shared_ptr<const runtime::SurfaceSampler> sampler;
  // The reflected subgraph: its meshes (kept alive by `reflected_meshes` while a draw uses them).
  ::osg::ref_ptr<::osg::Node> reflected;
  std::map<const ::osg::Geometry*, std::shared_ptr<CachedMesh>> mesh_cache;
  std::uint64_t next_mesh_id = 1;
  std::shared_ptr<const std::vector<std::shared_ptr<CachedMesh>>> reflected_meshes;
  std::shared_ptr<const playback::SurfaceLayers> layers;
  // The draw side.
  std::unique_ptr<playback::WaterRenderer> renderer;
  unsigned context_id = 0;
  bool other_context_warned = false;
  playback::FrameStatistics statistics;
  ::osg::observer_ptr<SeaNode> node;

  void update_reflection(const SeaNode& sea);
  // The sampler of the last advance; throws when there was none.
  std::shared_ptr<const runtime::SurfaceSampler> current_sampler();
};

namespace {

// Collects the reflected subgraph's geometries with their matrices relative to the sea node.
class ReflectedGeometryVisitor : public ::osg::NodeVisitor {
 public:
  struct Found {
    const ::osg::Geometry* geometry;
    ::osg::Matrixd to_site;
    ::osg::Vec4 colour;
  };
  ReflectedGeometryVisitor(const ::osg::Matrixd& above_root, const ::osg::Matrixd& world_to_site)
      : ::osg::NodeVisitor(TRAVERSE_ACTIVE_CHILDREN), above_root_(above_root), world_to_site_(world_to_site) {}

  void apply(::osg::Node& node) override {
    push(node.getStateSet());
    traverse(node);
    pop(node.getStateSet());
  }
  void apply(::osg::Geometry& geometry) override {
    push(geometry.getStateSet());
    ::osg::Vec4 colour = colours_.empty() ? ::osg::Vec4(0.6f, 0.6f, 0.6f, 1.f) : colours_.back();
    if (!geometry.getStateSet() || !geometry.getStateSet()->getAttribute(::osg::StateAttribute::MATERIAL))
      if (const auto* array = dynamic_cast<const ::osg::Vec4Array*>(geometry.getColorArray());
          array && !array->empty() && geometry.getColorArray()->getBinding() == ::osg::Array::BIND_OVERALL)
        colour = array->front();
    // The path from the subgraph's root down, times what lies above the root, into the site frame.
    found.push_back({&geometry, ::osg::computeLocalToWorld(getNodePath()) * above_root_ * world_to_site_, colour});
    pop(geometry.getStateSet());
  }
  std::vector<Found> found;

 private:
  void push(const ::osg::StateSet* set) {
    const auto* material =
        set ? dynamic_cast<const ::osg::Material*>(set->getAttribute(::osg::StateAttribute::MATERIAL)) : nullptr;
    if (material) colours_.push_back(material->getDiffuse(::osg::Material::FRONT));
    pushed_.push_back(material != nullptr);
  }
  void pop(const ::osg::StateSet*) {
    if (pushed_.back()) colours_.pop_back();
    pushed_.pop_back();
  }
  ::osg::Matrixd above_root_, world_to_site_;
  std::vector<::osg::Vec4> colours_;
  std::vector<bool> pushed_;
};

}  // namespace

void SeaNode::Shared::update_reflection(const SeaNode& sea) {
  if (!reflected) {
    std::lock_guard lock(mutex);
    layers.reset();
    reflected_meshes.reset();
    return;
  }
  // Where the subgraph's root and the sea node stand in the world (their first parental paths).
  ::osg::Matrixd above_root, sea_to_world;
  if (const ::osg::NodePathList paths = reflected->getParentalNodePaths(); !paths.empty()) {
    ::osg::NodePath path = paths.front();
    path.pop_back();  // the root's own transform is applied by the visitor
    above_root = ::osg::computeLocalToWorld(path);
  }
  if (const ::osg::NodePathList paths = sea.getParentalNodePaths(); !paths.empty())
    sea_to_world = ::osg::computeLocalToWorld(paths.front());
  ReflectedGeometryVisitor visitor(above_root, ::osg::Matrixd::inverse(sea_to_world));
  reflected->accept(visitor);

  auto next_layers = std::make_shared<playback::SurfaceLayers>();
  auto next_meshes = std::make_shared<std::vector<std::shared_ptr<CachedMesh>>>();
  for (const auto& item : visitor.found) {
    const auto* vertices = dynamic_cast<const ::osg::Vec3Array*>(item.geometry->getVertexArray());
    if (!vertices || vertices->empty()) continue;  // only float vertices are mirrored (what OSG's loaders give)
    // OSG's matrices act on row vectors: site = v M. Rows 0-2 of M's upper 3 x 3 are the images of
    // the body axes; their lengths are the scale, baked into the cached vertices.
    const ::osg::Matrixd& m = item.to_site;
    std::array<double, 3> scale{};
    for (int r = 0; r < 3; ++r) scale[std::size_t(r)] = std::hypot(m(r, 0), m(r, 1), m(r, 2));
    if (scale[0] <= 0 || scale[1] <= 0 || scale[2] <= 0) continue;
    std::shared_ptr<CachedMesh>& cached = mesh_cache[item.geometry];
    const bool stale = !cached || cached->modified_count != vertices->getModifiedCount() ||
                       std::abs(cached->scale[0] - scale[0]) > 1e-9 * scale[0] ||
                       std::abs(cached->scale[1] - scale[1]) > 1e-9 * scale[1] ||
                       std::abs(cached->scale[2] - scale[2]) > 1e-9 * scale[2];
    if (stale) {
      auto mesh = std::make_shared<CachedMesh>();
      mesh->modified_count = vertices->getModifiedCount();
      mesh->scale = scale;
      mesh->id = (std::uint64_t(0x05C) << 48) + next_mesh_id++;  // a new id: the renderer uploads it anew
      mesh->vertices_m.reserve(vertices->size() * 3);
      for (const ::osg::Vec3& v : *vertices)
        mesh->vertices_m.insert(mesh->vertices_m.end(),
                                {float(v.x() * scale[0]), float(v.y() * scale[1]), float(v.z() * scale[2])});
      ::osg::TriangleIndexFunctor<TriangleIndices> triangles;
      triangles.out = &mesh->triangles;
      const_cast<::osg::Geometry*>(item.geometry)->accept(triangles);
      cached = mesh;
    }
    if (cached->triangles.empty()) continue;
    playback::SolidMesh solid;
    solid.id = cached->id;
    solid.vertices_m = cached->vertices_m.data();
    solid.vertex_count = cached->vertices_m.size() / 3;
    solid.triangles = cached->triangles.data();
    solid.triangle_count = cached->triangles.size() / 3;
    solid.position_m = {m(3, 0), m(3, 1), m(3, 2)};
    // Row-major body -> site rotation: column c of R is row c of M without its scale.
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) solid.rotation[std::size_t(r * 3 + c)] = m(c, r) / scale[std::size_t(c)];
    solid.albedo_above = solid.albedo_below = linear_albedo(item.colour);
    solid.boot_top_z_m = -std::numeric_limits<double>::max();  // the model's own paint, no boot top
    next_layers->meshes.push_back(solid);
    next_meshes->push_back(cached);
  }
  std::lock_guard lock(mutex);
  reflected_meshes = next_meshes;
  layers = next_layers;
}

namespace {

// The drawable OSG draws: the renderer's frame into OSG's framebuffer, between a GL-state guard.
class SeaDrawable : public ::osg::Drawable {
 public:
  explicit SeaDrawable(std::shared_ptr<SeaNode::Shared> shared) : shared_(std::move(shared)) {
    setSupportsDisplayList(false);
    setUseDisplayList(false);
    setUseVertexBufferObjects(false);
    setCullingActive(false);  // the sky and the sea fill every view
    setDataVariance(DYNAMIC);
  }
  SeaDrawable(const SeaDrawable& other, const ::osg::CopyOp& op) : ::osg::Drawable(other, op), shared_(other.shared_) {}
  META_Object(nearshore_osg, SeaDrawable)
  SeaDrawable() = default;

  // The site and the grid's reach around it: what OSG's near/far computation sees of the sea.
  ::osg::BoundingBox computeBoundingBox() const override {
    ::osg::BoundingBox box;
    if (!shared_) return box;
    const auto site = shared_->engine->site();
    const double reach = shared_->settings.renderer.quadtree.reach_m;
    const double width = site ? site->width_m : 0.0, height = site ? site->height_m : 0.0;
    box.expandBy(::osg::Vec3(float(-reach), float(-reach), -50.f));
    box.expandBy(::osg::Vec3(float(width + reach), float(height + reach), 50.f));
    return box;
  }

  void drawImplementation(::osg::RenderInfo& render_info) const override {
    if (!shared_) return;  // a clone made by cloneType(): no sea
    ::osg::State& state = *render_info.getState();
    SeaNode::Shared& s = *shared_;
    runtime::SurfaceSnapshot snapshot;
    std::vector<std::shared_ptr<const runtime::HarbourKeyframe>> harbour;
    std::vector<std::shared_ptr<const runtime::DeepWaterKeyframe>> deep;
    std::shared_ptr<const playback::SurfaceLayers> layers;
    std::shared_ptr<const std::vector<std::shared_ptr<CachedMesh>>> keep_meshes;
    playback::Lighting lighting;
    playback::DrawOptions options;
    {
      std::lock_guard lock(s.mutex);
      snapshot = s.snapshot;
      harbour = s.upcoming_harbour;
      deep = s.upcoming_deep;
      layers = s.layers;
      keep_meshes = s.reflected_meshes;
      lighting = s.lighting;
      options = s.settings.draw;
    }
    if (!snapshot.site && !snapshot.deep_from) return;  // nothing advanced yet
    if (s.renderer && state.getContextID() != s.context_id) {
      if (!s.other_context_warned)
        OSG_WARN << "nearshore::scenegraph::SeaNode: drawn in OpenGL context " << state.getContextID()
                 << " but its renderer lives in context " << s.context_id << "; drawn there only" << std::endl;
      s.other_context_warned = true;
      return;
    }
    const ::osg::Viewport* viewport = state.getCurrentViewport();
    if (!viewport || viewport->width() < 1 || viewport->height() < 1) return;
    GlStateGuard guard(state);
    if (guard.pending_error() != GL_NO_ERROR)
      OSG_NOTICE << "nearshore::scenegraph::SeaNode: OpenGL error 0x" << std::hex << guard.pending_error() << std::dec
                 << " was pending before the sea's draw (not the sea's)" << std::endl;
    try {
      if (!s.renderer) {
        playback::load_opengl(&::osg::getGLExtensionFuncPtr);
        s.renderer = std::make_unique<playback::WaterRenderer>(s.settings.renderer);
        s.context_id = state.getContextID();
      }
      for (auto& keyframe : harbour) s.renderer->stage(std::move(keyframe));
      for (auto& keyframe : deep) s.renderer->stage(std::move(keyframe));
      // The drawable's model-view is the camera's view times the transforms above the sea node:
      // the site frame is the node's local frame.
      const playback::CameraView view =
          playback::camera_view_from_matrices(to_matrix4(state.getModelViewMatrix()),
                                              to_matrix4(state.getProjectionMatrix()), int(viewport->width()),
                                              int(viewport->height()));
      options.draw_meshes = false;  // OSG draws the reflected objects itself
      s.renderer->render_into_bound_framebuffer(snapshot, view, lighting, options, layers.get());
      std::lock_guard lock(s.mutex);
      s.statistics = s.renderer->last_frame();
    } catch (const std::exception& error) {
      OSG_WARN << "nearshore::scenegraph::SeaNode: " << error.what() << std::endl;
    }
  }

  void releaseGLObjects(::osg::State* state) const override {
    ::osg::Drawable::releaseGLObjects(state);
    // Called by OSG with the context current while it closes it: the renderer's GL objects go with it.
    if (shared_ && state && shared_->renderer && state->getContextID() == shared_->context_id)
      shared_->renderer.reset();
  }

 private:
  std::shared_ptr<SeaNode::Shared> shared_;
};

// Advances the sea in the update traversal: to the frame stamp's simulation time, or the fixed one.
class FrameClock : public ::osg::NodeCallback {
 public:
  void operator()(::osg::Node* node, ::osg::NodeVisitor* visitor) override {
    auto* sea = static_cast<SeaNode*>(node);
    const double frame_time = visitor->getFrameStamp() ? visitor->getFrameStamp()->getSimulationTime() : 0.0;
    sea->advance_to(sea->display_time_s_for_frame(frame_time));
    traverse(node, visitor);
  }
};

}  // namespace

SeaNode::SeaNode(const std::filesystem::path& sequence_folder, SeaNodeSettings settings)
    : shared_(std::make_shared<Shared>()) {
  Shared& s = *shared_;
  s.settings = std::move(settings);
  s.engine = std::make_unique<runtime::StreamingEngine>(sequence_folder, s.settings.streaming);
  if (s.settings.lighting) {
    s.lighting = *s.settings.lighting;
  } else {
    // As `nearshore play` lights a sea by default (viewer/src/viewer.cpp): Beaufort 3's wind, and
    // the bake's unresolved slope variance when the deep water is the bake's.
    s.lighting.wind_speed_m_s = ocean::beaufort_preset(3).wind_speed_10_m_s;
    const auto& deep = s.engine->manifest().deep_water;
    if (s.engine->deep_water_is_bakes() && deep && deep->unresolved_slope_variance > 0.0)
      s.lighting.sub_grid_slope_variance = deep->unresolved_slope_variance;
  }
  s.node = this;
  addDrawable(new SeaDrawable(shared_));
  setUpdateCallback(new FrameClock);
}

SeaNode::~SeaNode() {
  // Without a current context the renderer's GL objects cannot be deleted here; OSG's
  // releaseGLObjects (when the context closes) has normally done it. Otherwise they are left to
  // the context's own destruction rather than calling OpenGL with no context current.
  if (shared_ && shared_->renderer) static_cast<void>(shared_->renderer.release());
}

void SeaNode::set_display_time_s(double display_time_s) {
  if (!runtime::is_display_time(display_time_s))
    throw Error("SeaNode", "display time " + std::to_string(display_time_s) + " s",
                "give a finite time from 0 to 1e9 s");
  shared_->fixed_time_s = display_time_s;
}

void SeaNode::follow_frame_clock() { shared_->fixed_time_s.reset(); }

double SeaNode::display_time_s_for_frame(double frame_time_s) const {
  return shared_->fixed_time_s ? *shared_->fixed_time_s : std::max(frame_time_s, 0.0);
}

void SeaNode::advance_to(double display_time_s) {
  Shared& s = *shared_;
  if (display_time_s == s.advanced_time_s && s.reflected == nullptr) return;
  if (display_time_s != s.advanced_time_s) {
    s.engine->advance_to(display_time_s);
    runtime::SurfaceSnapshot snapshot = s.engine->snapshot();
    // The foam onset of the deep water on screen, as the viewer and the C API measure it.
    std::optional<double> onset;
    if (snapshot.deep_from)
      if (const auto measured = s.whitecaps.update(snapshot.deep_from->cascades,
                                                   snapshot.site ? snapshot.site->choppiness : 1.0,
                                                   s.lighting.wind_speed_m_s))
        onset = measured->jacobian_foam_onset;
    auto sampler = std::make_shared<const runtime::SurfaceSampler>(snapshot);
    auto harbour = s.engine->upcoming_harbour_keyframes(2);
    auto deep = s.engine->upcoming_deep_keyframes(1);
    std::lock_guard lock(s.mutex);
    s.snapshot = std::move(snapshot);
    s.sampler = std::move(sampler);
    s.upcoming_harbour = std::move(harbour);
    s.upcoming_deep = std::move(deep);
    if (onset) s.lighting.jacobian_foam_onset = *onset;
    s.advanced_time_s = display_time_s;
  }
  // The reflected objects move every frame (a ship on the waves), the sea's time or not.
  s.update_reflection(*this);
}

double SeaNode::display_time_s() const { return shared_->advanced_time_s; }

std::shared_ptr<const runtime::SurfaceSampler> SeaNode::Shared::current_sampler() {
  std::lock_guard lock(mutex);
  if (!sampler)
    throw Error("SeaNode", "has not advanced yet: no surface to query",
                "call advance_to (or let one update traversal run) before querying heights");
  return sampler;
}

runtime::SurfaceState SeaNode::surface_at(double x_m, double y_m) const {
  return shared_->current_sampler()->state(x_m, y_m);
}

double SeaNode::elevation_m(double x_m, double y_m) const {
  return shared_->current_sampler()->elevation_m(x_m, y_m);
}

std::shared_ptr<const runtime::HarbourSite> SeaNode::site() const { return shared_->engine->site(); }

void SeaNode::set_reflected(::osg::Node* subgraph) {
  shared_->reflected = subgraph;
  shared_->mesh_cache.clear();
  shared_->update_reflection(*this);
}

playback::Lighting SeaNode::lighting() const {
  std::lock_guard lock(shared_->mutex);
  return shared_->lighting;
}

void SeaNode::set_lighting(const playback::Lighting& lighting) {
  std::lock_guard lock(shared_->mutex);
  shared_->lighting = lighting;
}

playback::FrameStatistics SeaNode::last_frame() const {
  std::lock_guard lock(shared_->mutex);
  return shared_->statistics;
}

int SeaNode::reflected_mesh_count() const {
  std::lock_guard lock(shared_->mutex);
  return shared_->layers ? int(shared_->layers->meshes.size()) : 0;
}

runtime::StreamingEngine& SeaNode::engine() { return *shared_->engine; }

}  // namespace nearshore::scenegraph
