# Debian packages of nearshore, made by CPack's DEB generator from the install rules (docs/packages.md):
#
#   component  package            what it holds
#   runtime    libnearshore0      libnearshore.so.0 (the runtime a host links: capi/)
#   dev        libnearshore-dev   the libnearshore.so link, nearshore.h and the C++ headers, the CMake
#                                 package and nearshore.pc, the C API reference
#   tools      nearshore-tools    the `nearshore` command line (bake side included) and its pages
#   python     python3-nearshore  the Python module `nearshore` (built where pybind11 is found)
#   osg        libnearshore-osg0  libnearshore_osg.so.0, the OpenSceneGraph node kit (osg/, docs/osg.md;
#                                 built where OpenSceneGraph is found)
#   osg_dev    libnearshore-osg-dev  its link, header nearshore/osg/sea_node.hpp and CMake package
#                                 (find_package(nearshore_osg): nearshore::osg)
#
# Every installed file belongs to exactly one component (tests/packaging checks it against a plain
# `cmake --install`). Depends are what dpkg-shlibdeps finds in each package's ELF files (the Debian
# package of every shared library they load) plus what no ELF file shows: libnearshore-dev needs the
# library of its own version; python3-nearshore the interpreter its extension was built for and
# NumPy. A C host needs neither Eigen nor nlohmann_json (nearshore::c and nearshore.pc name neither),
# so libnearshore-dev only recommends them, for the C++ API of nearshore::nearshore.
#
#   scripts/build-debs.sh  -> build/release/debs/*.deb (builds only what the packages hold, then cpack;
#                             the `package` target builds everything first, tests included)
include(GNUInstallDirs)

set(NEARSHORE_PACKAGE_MAINTAINER "nearshore developers <dev@nearshore.invalid>" CACHE STRING
  "The Maintainer field of the Debian packages")
set(NEARSHORE_PACKAGE_RELEASE 1 CACHE STRING "The Debian revision of the packages (the N of 0.1.0-N)")
set(nearshore_deb_version "${PROJECT_VERSION}-${NEARSHORE_PACKAGE_RELEASE}")

# The packages' documentation: /usr/share/doc/<package>/ with the copyright file and the
# changelog.Debian.gz Debian asks of each; the changelog has one entry for this build, pointing at
# the project's CHANGELOG.md (dated by SOURCE_DATE_EPOCH where set, else the configure time).
set(nearshore_package_names runtime libnearshore0 dev libnearshore-dev tools nearshore-tools python python3-nearshore
  osg libnearshore-osg0 osg_dev libnearshore-osg-dev)
set(nearshore_package_components runtime dev tools)
if(TARGET nearshore_python)
  list(APPEND nearshore_package_components python)
endif()
if(TARGET nearshore_osg)
  list(APPEND nearshore_package_components osg osg_dev)
endif()
string(TIMESTAMP nearshore_package_date "%a, %d %b %Y %H:%M:%S +0000" UTC)
foreach(component IN LISTS nearshore_package_components)
  list(FIND nearshore_package_names ${component} index)
  math(EXPR index "${index} + 1")
  list(GET nearshore_package_names ${index} package)
  set(folder "${CMAKE_BINARY_DIR}/packaging/${package}")
  file(MAKE_DIRECTORY "${folder}")
  file(WRITE "${folder}/changelog.Debian" "nearshore (${nearshore_deb_version}) unstable; urgency=medium\n\n"
    "  * Built by CPack from the nearshore source tree.\n"
    "    What changed upstream: the repository's CHANGELOG.md.\n\n"
    " -- ${NEARSHORE_PACKAGE_MAINTAINER}  ${nearshore_package_date}\n")
  execute_process(COMMAND gzip -9nf "${folder}/changelog.Debian" RESULT_VARIABLE gzip_status)
  if(NOT gzip_status EQUAL 0)
    message(FATAL_ERROR "packaging: gzip of ${folder}/changelog.Debian failed (${gzip_status})")
  endif()
  install(FILES "${CMAKE_SOURCE_DIR}/cmake/packaging/copyright" "${folder}/changelog.Debian.gz"
    DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/doc/${package}" COMPONENT ${component})
endforeach()
install(FILES "${CMAKE_SOURCE_DIR}/docs/c-api.md" "${CMAKE_SOURCE_DIR}/docs/c-api-reference.md"
  "${CMAKE_SOURCE_DIR}/docs/packages.md"
  DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/doc/libnearshore-dev" COMPONENT dev)
file(GLOB nearshore_command_pages "${CMAKE_SOURCE_DIR}/docs/commands/*.md")
install(FILES ${nearshore_command_pages} DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/doc/nearshore-tools" COMPONENT tools)
if(TARGET nearshore_python)
  install(FILES "${CMAKE_SOURCE_DIR}/docs/python.md"
    DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/doc/python3-nearshore" COMPONENT python)
  install(FILES "${CMAKE_SOURCE_DIR}/python/examples/gauges_hs.py" "${CMAKE_SOURCE_DIR}/python/examples/bay_gauges.toml"
    DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/doc/python3-nearshore/examples" COMPONENT python)
endif()
# What the packages are made from: `cmake --build build/release --target nearshore_packaged_targets`
# builds them alone (scripts/build-debs.sh), not the tests.
add_custom_target(nearshore_packaged_targets)
add_dependencies(nearshore_packaged_targets nearshore_shared nearshore)
if(TARGET nearshore_python)
  add_dependencies(nearshore_packaged_targets nearshore_python)
endif()
if(TARGET nearshore_osg)
  add_dependencies(nearshore_packaged_targets nearshore_osg)
  install(FILES "${CMAKE_SOURCE_DIR}/docs/osg.md" "${CMAKE_SOURCE_DIR}/samples/osg/nearshore_osgviewer.cpp"
    "${CMAKE_SOURCE_DIR}/data/ships/models/coaster.obj" "${CMAKE_SOURCE_DIR}/data/ships/models/coaster.mtl"
    DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/doc/libnearshore-osg-dev" COMPONENT osg_dev)
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME nearshore)
set(CPACK_PACKAGE_VENDOR "nearshore")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_CONTACT "${NEARSHORE_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_COMPONENTS_ALL ${nearshore_package_components})
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_RELEASE "${NEARSHORE_PACKAGE_RELEASE}")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${NEARSHORE_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# gzip: the packages test builds them in every CI run; xz takes several times longer for 10 % less.
set(CPACK_DEBIAN_COMPRESSION_TYPE gzip)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# Stripped ELF files, as Debian ships them; what was stripped (the symbol tables that name frames in
# a backtrace; a Release build has no -g) goes into <package>-dbgsym_*.ddeb beside each package.
set(CPACK_DEBIAN_DEBUGINFO_PACKAGE ON)

set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME libnearshore0)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION libs)
# A shlibs file (so a package built against libnearshore.so.0 depends on libnearshore0 >= the version
# it was built with) and the ldconfig trigger.
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)   # libnearshore0 and libnearshore-osg0 have versioned libraries
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS_POLICY ">=")
# Debian's way to refresh the loader's cache is the ldconfig trigger (CPack also writes a postinst
# and postrm that call ldconfig: twice is harmless).
file(WRITE "${CMAKE_BINARY_DIR}/packaging/libnearshore0/triggers" "activate-noawait ldconfig\n")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_CONTROL_EXTRA "${CMAKE_BINARY_DIR}/packaging/libnearshore0/triggers")
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION "nearshore runtime: baked harbour waves streamed inside an endless FFT sea
libnearshore.so.0, what a simulator, image generator or game links to play
baked harbour sequences forever by their loop plans inside a deep-water FFT
sea: streaming, CPU surface queries, OpenGL 3.3 drawing with lighting, ships
on the sea. C API nearshore.h and a C++ API; the headers are in
libnearshore-dev.")

set(CPACK_DEBIAN_DEV_PACKAGE_NAME libnearshore-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "libnearshore0 (= ${nearshore_deb_version})")
set(CPACK_DEBIAN_DEV_PACKAGE_RECOMMENDS "libeigen3-dev (>= 3.4), nlohmann-json3-dev (>= 3.10), pkg-config")
set(CPACK_DEBIAN_DEV_DESCRIPTION "nearshore runtime: development files (C API, C++ API)
The libnearshore.so link, the C header nearshore.h, the C++ headers of the
runtime, a CMake package (find_package(nearshore): nearshore::c,
nearshore::nearshore) and a pkg-config file (nearshore.pc), with the C API
reference. A C host needs nothing else; the C++ headers use Eigen 3.4 and
nlohmann_json 3.10 (recommended).")

set(CPACK_DEBIAN_TOOLS_PACKAGE_NAME nearshore-tools)
set(CPACK_DEBIAN_TOOLS_PACKAGE_SECTION science)
# Plot text is drawn in DejaVu Sans, and skipped without it; `nearshore library` runs on several
# ranks under mpirun.
set(CPACK_DEBIAN_TOOLS_PACKAGE_RECOMMENDS "fonts-dejavu-core")
set(CPACK_DEBIAN_TOOLS_PACKAGE_SUGGESTS "openmpi-bin")
set(CPACK_DEBIAN_TOOLS_DESCRIPTION "nearshore command line: bake harbour waves, loop, play and export them
The nearshore command: chart data to a harbour grid (bathy), the enhanced
Boussinesq bake (bake), loop-transition tables (loops), sea-state libraries
(library), the viewer (play), exports to NetCDF, GeoTIFF, EXR and VDB
(export), benchmarks (bench) and the demo harbour (demo).")

if(TARGET nearshore_python)
  # The extension is built for one interpreter (its file name says cpython-3XY): the package says which.
  find_package(Python3 COMPONENTS Interpreter QUIET)
  math(EXPR nearshore_python_next_minor "${Python3_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-nearshore)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS
    "python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}), python3 (<< ${Python3_VERSION_MAJOR}.${nearshore_python_next_minor}), python3-numpy")
  set(CPACK_DEBIAN_PYTHON_PACKAGE_RECOMMENDS "fonts-dejavu-core")
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SUGGESTS "python3-matplotlib, python3-xarray")
  set(CPACK_DEBIAN_PYTHON_DESCRIPTION "nearshore for Python: sequences as NumPy arrays, surface queries, bake
The Python module nearshore: a baked sequence's frames, harbour grid, gauges
and loop plans as NumPy arrays sharing the library's memory, the runtime's
surface queries at arrays of points and times (equal to the C API's), gauge
statistics, and bake and loops as functions with the command line's options.")
endif()

if(TARGET nearshore_osg)
  # libnearshore_osg.so.0 links libnearshore.so.0 and OSG's libraries: shlibdeps finds libnearshore0
  # (from the shlibs file of the same build) and libopenscenegraph161; the exact version of
  # libnearshore0 is stated, since the node kit uses its C++ API (no stable ABI across versions).
  # dpkg-shlibdeps looks for libnearshore.so.0 among the installed system's libraries; during the
  # build it is in libnearshore0's package, not installed: it is found in the build tree instead
  # (-l), and the dependency on it is the one stated below.
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS "${CMAKE_BINARY_DIR}/capi")
  set(CPACK_DEBIAN_OSG_PACKAGE_NAME libnearshore-osg0)
  set(CPACK_DEBIAN_OSG_PACKAGE_SECTION libs)
  set(CPACK_DEBIAN_OSG_PACKAGE_DEPENDS "libnearshore0 (= ${nearshore_deb_version})")
  file(WRITE "${CMAKE_BINARY_DIR}/packaging/libnearshore-osg0/triggers" "activate-noawait ldconfig\n")
  set(CPACK_DEBIAN_OSG_PACKAGE_CONTROL_EXTRA "${CMAKE_BINARY_DIR}/packaging/libnearshore-osg0/triggers")
  set(CPACK_DEBIAN_OSG_DESCRIPTION "nearshore for OpenSceneGraph: the streamed harbour sea as a scene-graph node
libnearshore_osg.so.0: a node that draws nearshore's streamed sea (the
renderer of libnearshore0) inside any OpenSceneGraph scene and camera,
depth-sorted against the scene's objects and reflecting them, with height
queries to float a host's objects. Headers in libnearshore-osg-dev.")
  set(CPACK_DEBIAN_OSG_DEV_PACKAGE_NAME libnearshore-osg-dev)
  set(CPACK_DEBIAN_OSG_DEV_PACKAGE_SECTION libdevel)
  set(CPACK_DEBIAN_OSG_DEV_PACKAGE_DEPENDS
    "libnearshore-osg0 (= ${nearshore_deb_version}), libnearshore-dev (= ${nearshore_deb_version}), libopenscenegraph-dev (>= 3.6), libeigen3-dev (>= 3.4), nlohmann-json3-dev (>= 3.10)")
  set(CPACK_DEBIAN_OSG_DEV_DESCRIPTION "nearshore for OpenSceneGraph: development files
The libnearshore_osg.so link, nearshore/osg/sea_node.hpp, the CMake package
nearshore_osg (target nearshore::osg) and the sample nearshore_osgviewer with
a ship model. The node's header uses the C++ API of libnearshore-dev (Eigen,
nlohmann_json) and OpenSceneGraph's headers.")
endif()

include(CPack)
