// nearshore::scenegraph::SeaNode in an OpenSceneGraph viewer on Mesa llvmpipe (Xvfb), on the real demo
// bake (the ctest fixture demo_harbour_bake, or NEARSHORE_DEMO_BAKE): the picture OSG makes with
// the node equals the picture playback's own renderer makes of the same snapshot from the same
// camera (the path behind `nearshore play`), within a stated tolerance; a box that stands through
// the water surface shows above it and is hidden below it (the sea depth-tested against OSG's
// depth buffer), is drawn by OSG's fixed-function state after the sea (the GL-state contract), and
// shows in the sea's local reflection; the node's height queries are the runtime sampler's.
#include <gtest/gtest.h>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Material>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>
#include <osgViewer/Viewer>

#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <string>
#include <memory>
#include <stdexcept>

#include "nearshore/osg/sea_node.hpp"
#include "nearshore/playback/camera.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/runtime/surface_sampler.hpp"

namespace nearshore {
namespace {
namespace fs = std::filesystem;

fs::path demo_bake() {
  if (const char* folder = std::getenv("NEARSHORE_DEMO_BAKE")) return folder;
  return NEARSHORE_DEMO_BAKE_DIR;  // tests/CMakeLists.txt: the fixture demo_harbour_bake's output
}

constexpr int kWidth = 320, kHeight = 180;
constexpr double kTime_s = 120.0, kNear_m = 0.5, kFar_m = 4000.0;

// Reads the framebuffer after OSG's draw (row 0 at the bottom, RGB bytes).
struct ReadBack : ::osg::Camera::DrawCallback {
  mutable std::vector<unsigned char> rgb;
  void operator()(::osg::RenderInfo&) const override {
    rgb.assign(std::size_t(kWidth) * kHeight * 3, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  }
};

// An offscreen OSG viewer (pbuffer) whose camera has exactly playback's matrices for `camera`.
struct OsgScene {
  osgViewer::Viewer viewer;
  ::osg::ref_ptr<::osg::Group> root = new ::osg::Group;
  ::osg::ref_ptr<ReadBack> read_back = new ReadBack;
  ::osg::ref_ptr<::osg::GraphicsContext> context;

  explicit OsgScene(const playback::CameraView& view) {
    ::osg::ref_ptr<::osg::GraphicsContext::Traits> traits = new ::osg::GraphicsContext::Traits;
    traits->width = kWidth;
    traits->height = kHeight;
    traits->pbuffer = true;
    traits->doubleBuffer = false;
    traits->depth = 24;
    traits->readDISPLAY();  // $DISPLAY (xvfb-run's), not :0
    traits->setUndefinedScreenDetailsToDefaultScreen();
    context = ::osg::GraphicsContext::createGraphicsContext(traits.get());
    if (!context) {  // no pbuffer visual: a window (Xvfb shows it to no one)
      traits->pbuffer = false;
      traits->windowDecoration = false;
      context = ::osg::GraphicsContext::createGraphicsContext(traits.get());
    }
    ::osg::Camera* camera = viewer.getCamera();
    camera->setGraphicsContext(context.get());
    camera->setViewport(0, 0, kWidth, kHeight);
    camera->setClearColor({0.f, 0.f, 0.f, 1.f});
    camera->setComputeNearFarMode(::osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    camera->setProjectionMatrix(::osg::Matrixd(view.projection.data()));
    camera->setViewMatrix(::osg::Matrixd(view.view.data()));
    camera->setFinalDrawCallback(read_back.get());
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);
    viewer.setSceneData(root.get());
    viewer.setCameraManipulator(nullptr);
    viewer.realize();
    if (!context || !context->valid()) throw std::runtime_error("no OpenGL context for the OSG viewer (run under xvfb-run)");
  }
  // One frame; the picture as RGB bytes, row 0 at the top.
  std::vector<unsigned char> frame() {
    viewer.frame(kTime_s);
    if (read_back->rgb.size() != std::size_t(kWidth) * kHeight * 3) throw std::runtime_error("OSG drew no frame");
    std::vector<unsigned char> top_down(read_back->rgb.size());
    for (int y = 0; y < kHeight; ++y)
      std::copy_n(&read_back->rgb[std::size_t(kHeight - 1 - y) * kWidth * 3], kWidth * 3, &top_down[std::size_t(y) * kWidth * 3]);
    return top_down;
  }
};

// The pictures for a reader (docs/osg.md): binary PPM files in test-output/osg/.
void write_ppm(const std::vector<unsigned char>& rgb, const std::string& name) {
  const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "test-output" / "osg";
  fs::create_directories(folder);
  std::FILE* file = std::fopen((folder / name).c_str(), "wb");
  if (!file) return;
  std::fprintf(file, "P6\n%d %d\n255\n", kWidth, kHeight);
  std::fwrite(rgb.data(), 1, rgb.size(), file);
  std::fclose(file);
}

std::vector<unsigned char> bytes_of(const Image& image) {
  std::vector<unsigned char> out(std::size_t(image.width()) * image.height() * 3);
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = static_cast<unsigned char>(std::clamp(image.pixels()[k], 0.f, 1.f) * 255.f + 0.5f);
  return out;
}

// Where a site point lands on screen (pixel column, row from the top).
std::array<int, 2> pixel_of(const playback::CameraView& view, double x, double y, double z) {
  const auto clip = playback::transform(view.view_projection, {x, y, z, 1.0});
  return {int((clip[0] / clip[3] * 0.5 + 0.5) * kWidth), int((0.5 - clip[1] / clip[3] * 0.5) * kHeight)};
}

std::array<int, 3> pixel(const std::vector<unsigned char>& rgb, std::array<int, 2> at) {
  const std::size_t k = (std::size_t(at[1]) * kWidth + at[0]) * 3;
  return {rgb[k], rgb[k + 1], rgb[k + 2]};
}

class SeaNodeInOsg : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(demo_bake() / "manifest.json"))
        << demo_bake() << " holds no bake: ctest runs DemoHarbourLoops.PeriodicBakeRepeatsWithSeamRatioBelowATenth first "
        << "(fixture demo_harbour_bake), or set NEARSHORE_DEMO_BAKE to a demo bake";
  }
};

TEST_F(SeaNodeInOsg, DrawsWhatPlaybackDrawsDepthSortsABoxAndReflectsIt) {
  // The demo harbour's approach from a ship's bridge (tests/playback/demo_render_test.cpp's view).
  playback::Camera camera;
  camera.eye_m = {1100.0, 540.0, 25.0};
  camera.target_m = {720.0, 860.0, 0.0};
  camera.near_m = kNear_m;
  camera.far_m = kFar_m;
  const playback::CameraView view = playback::camera_view(camera, kWidth, kHeight, kNear_m, kFar_m);

  scenegraph::SeaNodeSettings settings;
  settings.streaming.lockstep = true;
  settings.renderer.msaa_samples = 1;
  // A host's framebuffer is drawn without the screen-space refraction (water_renderer.cpp 2d,
  // docs/osg.md "Limits"): the reference is drawn without it too.
  settings.renderer.refraction = false;
  ::osg::ref_ptr<scenegraph::SeaNode> sea = new scenegraph::SeaNode(demo_bake(), settings);
  sea->set_display_time_s(kTime_s);
  OsgScene scene(view);
  scene.root->addChild(sea.get());
  const std::vector<unsigned char> osg_sea = scene.frame();
  ASSERT_GT(sea->last_frame().triangles_drawn, 0) << "the node drew no sea";
  EXPECT_NEAR(sea->last_frame().near_m, kNear_m, 1e-6 * kNear_m);  // OSG's projection, read back
  EXPECT_NEAR(sea->last_frame().far_m, kFar_m, 1e-6 * kFar_m);

  // playback's renderer (what `nearshore play` draws with) in a context of its own: the same
  // snapshot, camera and lighting.
  std::vector<unsigned char> reference;
  {
    ::osg::ref_ptr<::osg::GraphicsContext::Traits> traits =
        new ::osg::GraphicsContext::Traits(*scene.context->getTraits());
    ::osg::ref_ptr<::osg::GraphicsContext> own = ::osg::GraphicsContext::createGraphicsContext(traits.get());
    ASSERT_TRUE(own && own->realize() && own->makeCurrent());
    {
      playback::WaterRenderer renderer(settings.renderer);
      renderer.render(sea->engine().snapshot(), camera, sea->lighting(), kWidth, kHeight);
      reference = bytes_of(renderer.read_pixels());
    }
    own->releaseContext();
    own->close(false);
  }

  // The whole picture (sky, land, sea): mean absolute difference per channel and the share of
  // pixels differing by more than 8 of 255 in a channel. Both paths run the same shaders with the
  // same matrices; what may differ is the depth buffer (OSG's window: 24-bit fixed point;
  // playback's target: 32-bit float), which decides the waterline where the sea meets land and
  // structures at grazing angles: a few pixels along those lines.
  double sum = 0;
  int differing = 0;
  for (std::size_t p = 0; p < reference.size(); p += 3) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(int(osg_sea[p + std::size_t(c)]) - int(reference[p + std::size_t(c)]));
      sum += d;
      worst = std::max(worst, d);
    }
    differing += worst > 8;
  }
  const double mean_abs = sum / double(reference.size());
  const double share = differing / double(kWidth * kHeight);
  RecordProperty("mean_abs_difference", std::to_string(mean_abs));
  RecordProperty("share_differing_over_8", std::to_string(share));
  std::printf("OSG node vs playback renderer: mean |difference| %.3f of 255, %.3f %% of pixels off by more than 8\n",
              mean_abs, 100.0 * share);
  EXPECT_LT(mean_abs, 0.5);
  EXPECT_LT(share, 0.005);

  // A red box (OSG's fixed-function state, GL_LIGHTING off: flat red, 255 0 0, exactly as OSG draws
  // it without the sea; drawn lit (25 0 0 on its sides) if the sea's draw left OSG's record of the
  // modes wrong, as State::dirtyAllModes after the restore did) 12 x 12 m standing from -6 m to +6 m, 100 m ahead on the
  // approach, drawn AFTER the sea (render bin): its top half shows, its bottom half is behind the
  // water surface and hidden; it is red only if the sea's draw left OSG's state as OSG recorded it.
  const double bx = 1100.0 + (720.0 - 1100.0) * 0.2, by = 540.0 + (860.0 - 540.0) * 0.2;
  const double eta = sea->elevation_m(bx, by);
  EXPECT_DOUBLE_EQ(eta, runtime::SurfaceSampler(sea->engine().snapshot()).elevation_m(bx, by));
  ::osg::ref_ptr<::osg::Geode> box = new ::osg::Geode;
  ::osg::ref_ptr<::osg::ShapeDrawable> shape = new ::osg::ShapeDrawable(new ::osg::Box({}, 12.f));
  shape->setColor({1.f, 0.f, 0.f, 1.f});
  box->addDrawable(shape.get());
  box->getOrCreateStateSet()->setMode(GL_LIGHTING, ::osg::StateAttribute::OFF | ::osg::StateAttribute::PROTECTED);
  ::osg::ref_ptr<::osg::MatrixTransform> placed = new ::osg::MatrixTransform(::osg::Matrixd::translate(bx, by, 0.0));
  placed->addChild(box.get());
  sea->getOrCreateStateSet()->setRenderBinDetails(-1, "RenderBin");  // the sea first
  scene.root->addChild(placed.get());
  const std::vector<unsigned char> with_box = scene.frame();
  write_ppm(osg_sea, "osg_sea.ppm");
  write_ppm(reference, "playback_sea.ppm");
  write_ppm(with_box, "osg_sea_with_box.ppm");
  // Points on the box's face towards the camera (the face normal closest to the view).
  const double to_eye_x = 1100.0 - bx, to_eye_y = 540.0 - by;
  const double face_x = bx + (std::abs(to_eye_x) > std::abs(to_eye_y) ? std::copysign(6.0, to_eye_x) : 0.0);
  const double face_y = by + (std::abs(to_eye_x) > std::abs(to_eye_y) ? 0.0 : std::copysign(6.0, to_eye_y));
  int above_red = 0, below_red = 0, above_n = 0, below_n = 0;
  for (double along = -4.0; along <= 4.0; along += 1.0) {
    const double px = face_x + (std::abs(to_eye_x) > std::abs(to_eye_y) ? 0.0 : along);
    const double py = face_y + (std::abs(to_eye_x) > std::abs(to_eye_y) ? along : 0.0);
    for (double z : {eta + 2.0, eta + 3.5, eta + 5.0}) {
      const auto c = pixel(with_box, pixel_of(view, px, py, z));
      above_red += c[0] > 200 && c[1] < 40 && c[2] < 40;
      ++above_n;
    }
    for (double z : {eta - 2.0, eta - 3.5, eta - 5.0}) {
      const auto c = pixel(with_box, pixel_of(view, px, py, z));
      below_red += c[0] > 10 && c[0] > 3 * (c[1] + c[2]);  // any trace of the box: water is green-blue
      ++below_n;
    }
  }
  std::printf("box through the surface: %d of %d points above the water red, %d of %d below\n", above_red, above_n,
              below_red, below_n);
  EXPECT_EQ(above_red, above_n) << "the box's part above the water must show, flat red as OSG draws it (unlit)";
  EXPECT_EQ(below_red, 0) << "the box's part below the water must be hidden by the sea";

  // The box in the sea's local reflection: the water just in front of it (on screen below its
  // waterline) turns redder when the box is given to the node as its reflected subgraph.
  sea->set_reflected(placed.get());
  EXPECT_EQ(sea->reflected_mesh_count(), 1);
  const std::vector<unsigned char> reflected = scene.frame();
  write_ppm(reflected, "osg_sea_with_box_reflected.ppm");
  const auto waterline = pixel_of(view, face_x, face_y, eta);
  const auto box_left = pixel_of(view, face_x - 4.0, face_y - 4.0, eta), box_right = pixel_of(view, face_x + 4.0, face_y + 4.0, eta);
  double red_gain = 0;
  int n = 0;
  for (int y = waterline[1] + 2; y < std::min(waterline[1] + 8, kHeight); ++y)
    for (int x = std::min(box_left[0], box_right[0]) + 1; x < std::max(box_left[0], box_right[0]); ++x) {
      const std::size_t k = (std::size_t(y) * kWidth + x) * 3;
      red_gain += (int(reflected[k]) - int(reflected[k + 2])) - (int(with_box[k]) - int(with_box[k + 2]));
      ++n;
    }
  ASSERT_GT(n, 0);
  std::printf("reflection: the water below the box's waterline is %.1f of 255 redder (red - blue) with the box reflected\n",
              red_gain / n);
  EXPECT_GT(red_gain / n, 5.0) << "the box must show in the sea's reflection";

  // The same box lit by OSG's headlight (fixed-function lighting): its face above the water has the
  // colour it has when OSG draws it without the sea. Re-applying OSG's attributes after the sea
  // (State::dirtyAllAttributes) re-issued the headlight's position under the box's model-view and
  // lit it from above instead.
  box->getOrCreateStateSet()->removeMode(GL_LIGHTING);
  const std::vector<unsigned char> lit_with_sea = scene.frame();
  scene.root->removeChild(sea.get());
  const std::vector<unsigned char> lit_alone = scene.frame();
  const auto face = pixel_of(view, face_x, face_y, eta + 3.0);
  const auto with_sea = pixel(lit_with_sea, face), alone = pixel(lit_alone, face);
  std::printf("lit box face: %d %d %d after the sea, %d %d %d without it\n", with_sea[0], with_sea[1], with_sea[2],
              alone[0], alone[1], alone[2]);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(with_sea[std::size_t(c)], alone[std::size_t(c)], 2) << "channel " << c;
}

}  // namespace
}  // namespace nearshore
