// samples/osg/nearshore_osgviewer.cpp: an osgviewer-style host of nearshore's OpenSceneGraph node
// (docs/osg.md). It loads a baked sequence and a ship model (.osgt, .obj, ... through osgDB's
// plugins), floats the ship on the sea through the node's height queries (heave, pitch and roll
// from the surface under it, every frame), mirrors it in the sea, and either opens a window with
// OSG's trackball or writes one headless screenshot.
//
//   nearshore_osgviewer SEQUENCE_FOLDER MODEL [--at X,Y] [--heading DEG] [--time S]
//                       [--eye X,Y,Z --target X,Y] [--screenshot OUT.png] [--size W,H]
//
// The ship stands at site metres (X, Y) (default: the middle of the harbour), bow towards
// HEADING degrees counter-clockwise from east; the camera looks at it from the starboard quarter,
// or from --eye at --target (site metres, z up; `nearshore play`'s flags of the same names, its
// 45-degree field of view and sun: the same picture). MODEL `none` draws the sea alone.
#include <osg/LightModel>
#include <osg/MatrixTransform>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>
#include <osgGA/TrackballManipulator>
#include <osgUtil/SmoothingVisitor>
#include <osgViewer/Viewer>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "nearshore/osg/sea_node.hpp"

namespace {

// Floats the ship: the surface's elevation at its position, and its slope as pitch and roll.
class FloatOnSea : public osg::NodeCallback {
 public:
  FloatOnSea(nearshore::scenegraph::SeaNode* sea, double x, double y, double heading_rad)
      : sea_(sea), x_(x), y_(y), heading_(heading_rad) {}
  void operator()(osg::Node* node, osg::NodeVisitor* visitor) override {
    const nearshore::runtime::SurfaceState s = sea_->surface_at(x_, y_);
    const osg::Vec3d up(s.normal_x, s.normal_y, s.normal_z);
    static_cast<osg::MatrixTransform*>(node)->setMatrix(osg::Matrixd::rotate(heading_, osg::Vec3d(0, 0, 1)) *
                                                        osg::Matrixd::rotate(osg::Vec3d(0, 0, 1), up) *
                                                        osg::Matrixd::translate(x_, y_, s.surface_elevation_m));
    traverse(node, visitor);
  }

 private:
  nearshore::scenegraph::SeaNode* sea_;
  double x_, y_, heading_;
};

bool pair_of(const char* text, double& a, double& b) { return std::sscanf(text, "%lf,%lf", &a, &b) == 2; }
bool triple_of(const char* text, double& a, double& b, double& c) {
  return std::sscanf(text, "%lf,%lf,%lf", &a, &b, &c) == 3;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: %s SEQUENCE_FOLDER MODEL|none [--at X,Y] [--heading DEG] [--time S] [--eye X,Y,Z --target X,Y]"
                 " [--screenshot OUT.png] [--size W,H]\n",
                 argv[0]);
    return 2;
  }
  double x = -1, y = -1, heading_deg = 60, time_s = -1, width = 960, height = 540;
  std::string screenshot;
  bool own_camera = false, has_target = false;
  osg::Vec3d eye_m, target_m;
  for (int k = 3; k + 1 < argc; k += 2) {
    const std::string flag = argv[k];
    if (flag == "--at" && pair_of(argv[k + 1], x, y)) continue;
    if (flag == "--eye" && triple_of(argv[k + 1], eye_m.x(), eye_m.y(), eye_m.z())) {
      own_camera = true;
      continue;
    }
    if (flag == "--target" && pair_of(argv[k + 1], target_m.x(), target_m.y())) {
      has_target = true;
      continue;
    }
    if (flag == "--heading") { heading_deg = std::atof(argv[k + 1]); continue; }
    if (flag == "--time") { time_s = std::atof(argv[k + 1]); continue; }
    if (flag == "--screenshot") { screenshot = argv[k + 1]; continue; }
    if (flag == "--size" && pair_of(argv[k + 1], width, height)) continue;
    std::fprintf(stderr, "nearshore_osgviewer: unknown option %s %s\n", argv[k], argv[k + 1]);
    return 2;
  }
  if (own_camera != has_target) {
    std::fprintf(stderr, "nearshore_osgviewer: give --eye and --target together\n");
    return 2;
  }
  const bool with_model = std::string(argv[2]) != "none";
  try {
    nearshore::scenegraph::SeaNodeSettings settings;
    settings.streaming.lockstep = !screenshot.empty();  // a screenshot shows exactly its time
    osg::ref_ptr<nearshore::scenegraph::SeaNode> sea = new nearshore::scenegraph::SeaNode(argv[1], settings);
    const auto site = sea->site();
    if (x < 0) x = 0.5 * site->width_m, y = 0.5 * site->height_m;
    if (time_s >= 0) sea->set_display_time_s(time_s);
    sea->advance_to(time_s >= 0 ? time_s : 0.0);  // heights for the first frame's placement

    osg::ref_ptr<osg::Node> model =
        with_model ? osgDB::readRefNodeFile(argv[2]) : osg::ref_ptr<osg::Node>(new osg::Group);
    if (!model) {
      std::fprintf(stderr, "nearshore_osgviewer: cannot read the model %s (is there an osgDB plugin for it?)\n", argv[2]);
      return 1;
    }
    // Normals where the file has none (OBJ without vn lines): from the faces' winding, smoothed.
    osgUtil::SmoothingVisitor smoothing;
    smoothing.setCreaseAngle(osg::DegreesToRadians(40.0));
    model->accept(smoothing);
    model->getOrCreateStateSet()->setAttributeAndModes(new osg::LightModel);  // both sides lit
    static_cast<osg::LightModel*>(model->getStateSet()->getAttribute(osg::StateAttribute::LIGHTMODEL))->setTwoSided(true);
    const double heading = heading_deg * M_PI / 180.0;
    osg::ref_ptr<osg::MatrixTransform> ship = new osg::MatrixTransform;
    ship->addChild(model.get());
    ship->setUpdateCallback(new FloatOnSea(sea.get(), x, y, heading));
    if (with_model) sea->set_reflected(ship.get());

    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(sea.get());
    if (with_model) root->addChild(ship.get());
    osgViewer::Viewer viewer;
    viewer.setSceneData(root.get());
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);
    const double r = std::max(model->getBound().radius(), 5.0f);
    // From the starboard quarter: 130 degrees clockwise from the bow, three radii off, one up.
    const double look_from = heading - 130.0 * M_PI / 180.0;
    const osg::Vec3d target = own_camera ? target_m : osg::Vec3d(x, y, 0.0);
    const osg::Vec3d eye =
        own_camera ? eye_m : target + osg::Vec3d(std::cos(look_from) * 3 * r, std::sin(look_from) * 3 * r, 0.8 * r);
    if (screenshot.empty()) {
      viewer.setUpViewInWindow(50, 50, int(width), int(height));
      auto* manipulator = new osgGA::TrackballManipulator;
      manipulator->setHomePosition(eye, target, osg::Vec3d(0, 0, 1));
      viewer.setCameraManipulator(manipulator);
      return viewer.run();
    }
    // Headless: one pbuffer frame, read back and written by osgDB's image plugins.
    osg::ref_ptr<osg::GraphicsContext::Traits> traits = new osg::GraphicsContext::Traits;
    traits->readDISPLAY();
    traits->setUndefinedScreenDetailsToDefaultScreen();
    traits->width = int(width), traits->height = int(height);
    traits->pbuffer = true;
    traits->doubleBuffer = false;
    osg::ref_ptr<osg::GraphicsContext> context = osg::GraphicsContext::createGraphicsContext(traits.get());
    if (!context) {
      std::fprintf(stderr, "nearshore_osgviewer: no OpenGL pbuffer (no display? run under xvfb-run -a)\n");
      return 1;
    }
    osg::Camera* camera = viewer.getCamera();
    camera->setGraphicsContext(context.get());
    camera->setViewport(0, 0, int(width), int(height));
    camera->setProjectionMatrixAsPerspective(45.0, width / height, 0.5, 20000.0);
    camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    camera->setViewMatrixAsLookAt(eye, target, osg::Vec3d(0, 0, 1));
    osg::ref_ptr<osg::Image> image = new osg::Image;
    struct ReadBack : osg::Camera::DrawCallback {
      osg::Image* image;
      int w, h;
      void operator()(osg::RenderInfo&) const override { image->readPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE); }
    };
    osg::ref_ptr<ReadBack> read_back = new ReadBack;
    read_back->image = image.get(), read_back->w = int(width), read_back->h = int(height);
    camera->setFinalDrawCallback(read_back.get());
    viewer.realize();
    viewer.frame(time_s >= 0 ? time_s : 0.0);
    if (!osgDB::writeImageFile(*image, screenshot)) {
      std::fprintf(stderr, "nearshore_osgviewer: cannot write %s\n", screenshot.c_str());
      return 1;
    }
    std::printf("nearshore_osgviewer: %s (%dx%d), ship at (%.0f, %.0f) m floating at %.2f m, %d reflected meshes\n",
                screenshot.c_str(), int(width), int(height), x, y, sea->elevation_m(x, y), sea->reflected_mesh_count());
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "nearshore_osgviewer: %s\n", error.what());
    return 1;
  }
}
