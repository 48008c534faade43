# The rooms and their allowed arrows (docs/architecture.md): every library may link only the
# libraries listed for it, all of them further down the data flow. Checked at configure time from
# the targets' own link lists, so a new arrow fails the build before anyone compiles it.
#   ocean, sequence, plot, core_vdb and core_geotiff (the one road to an OpenVDB file, to a GeoTIFF)
#   -> core; boussinesq -> ocean; bathymetry, export and sequence_vdb -> core_vdb; bathymetry, bake
#   and export -> core_geotiff; bathymetry -> core, plot;
#   bake -> bathymetry (a case file's grid in local metres), boussinesq, ocean, ocean_netcdf (wave
#   models' NetCDF spectra: libnetcdf stays off the runtime side), sequence;
#   loops -> sequence, ocean, plot; playback -> sequence, ocean;
#   tools -> all. Never: playback to bathymetry, bake, boussinesq, loops or plot; no library to tools.
#   runtime -> sequence, ocean (GL-free: streaming, deep water, CPU queries); playback -> runtime.
#   ships -> runtime, ocean (CPU only: hulls, rigid bodies, bow-wave grids on the runtime's queries);
#   ships_mesh (hull files, assimp) -> ships; ships_scenario (TOML) -> ships, ships_mesh;
#   ships_layers (a fleet as the renderer's SurfaceLayers) -> ships, playback.
#   viewer (the application behind `nearshore play`: window, panel, ships on the shown sea) ->
#   playback, runtime, ships, ships_scenario, ships_layers and what they stand on; never the bake
#   side (bathymetry, bake, boussinesq, loops, plot, library, export): positions through core.
#   export (sequence -> NetCDF, GeoTIFF, EXR, VDB files) -> sequence, plot (the GeoTIFF's Hs map).
#   library (the sea-state library) -> bake, loops, sequence, export (berth agitation for the
#   operability of a library), plot (its bar chart); library_mpi -> library (built only
#   where MPI is found: a rule whose library name ends in "?" applies when that target exists).
#   shared (libnearshore.so, the C API: capi/) -> the runtime side only: runtime, playback, ships,
#   ships_mesh, ships_layers and what they stand on; never the bake side (bathymetry, boussinesq,
#   bake, loops, library, export).
#   bench_runtime (bench/runtime: the runtime side's benchmarks, play and ships) -> playback, runtime,
#   ships and what they stand on; never the bake side. bench (bench/: the bake side's benchmarks,
#   bake, bathy, deepwater, loops, library) -> bake, bathymetry, loops, sequence, ocean, core: like
#   tools/, the top of the graph; no library links either (the runtime rules above list neither).
#   python (the module `_nearshore`, python/; built where pybind11 is found) -> runtime, sequence,
#   core and, being a tool like the CLI and never linked by a host, bathymetry, bake, loops, library
#   and export (`nearshore.bathy`, `.bake`, `.loops`, `.library`, `.export`). No runtime library links it.
#   osg (libnearshore_osg.so, the OpenSceneGraph node kit, osg/; built where OpenSceneGraph is found)
#   -> shared through nearshore_cxx (libnearshore.so with its C++ headers: runtime, playback,
#   sequence, ocean, core in one copy per process); never the bake side, nor viewer or tools.
set(NEARSHORE_ALLOWED_ARROWS
  "nearshore_core:"
  "nearshore_core_vdb:nearshore_core"
  "nearshore_core_geotiff:nearshore_core"
  "nearshore_plot:nearshore_core"
  "nearshore_ocean:nearshore_core"
  "nearshore_ocean_netcdf:nearshore_ocean,nearshore_core"
  "nearshore_sequence:nearshore_core"
  "nearshore_boussinesq:nearshore_ocean,nearshore_core"
  "nearshore_bathymetry:nearshore_plot,nearshore_core_vdb,nearshore_core_geotiff,nearshore_core"
  "nearshore_bake:nearshore_core_geotiff,nearshore_bathymetry,nearshore_boussinesq,nearshore_ocean_netcdf,nearshore_ocean,nearshore_sequence,nearshore_core"
  "nearshore_loops:nearshore_sequence,nearshore_ocean,nearshore_plot,nearshore_core"
  "nearshore_sequence_vdb:nearshore_sequence,nearshore_core_vdb,nearshore_core"
  "nearshore_runtime:nearshore_sequence,nearshore_ocean,nearshore_core"
  "nearshore_ships:nearshore_runtime,nearshore_ocean,nearshore_core"
  "nearshore_ships_mesh:nearshore_ships,nearshore_core"
  "nearshore_ships_scenario:nearshore_ships,nearshore_ships_mesh,nearshore_core"
  "nearshore_ships_layers:nearshore_ships,nearshore_playback,nearshore_core"
  "nearshore_playback:nearshore_runtime,nearshore_sequence,nearshore_ocean,nearshore_core,nearshore_glad"
  "nearshore_viewer:nearshore_playback,nearshore_runtime,nearshore_ships,nearshore_ships_scenario,nearshore_ships_layers,nearshore_sequence,nearshore_ocean,nearshore_core"
  "nearshore_library:nearshore_bake,nearshore_loops,nearshore_export,nearshore_plot,nearshore_sequence,nearshore_core"
  "nearshore_library_mpi?:nearshore_library,nearshore_core"
  "nearshore_export:nearshore_sequence,nearshore_plot,nearshore_core_vdb,nearshore_core_geotiff,nearshore_core"
  "nearshore_bench_runtime:nearshore_playback,nearshore_runtime,nearshore_ships,nearshore_sequence,nearshore_ocean,nearshore_core"
  "nearshore_bench:nearshore_bake,nearshore_bathymetry,nearshore_loops,nearshore_sequence,nearshore_ocean,nearshore_core"
  "nearshore_python?:nearshore_runtime,nearshore_bake,nearshore_bathymetry,nearshore_loops,nearshore_library,nearshore_export,nearshore_sequence,nearshore_core"
  "nearshore_osg?:nearshore_cxx,nearshore_shared"
  "nearshore_shared:nearshore_runtime,nearshore_playback,nearshore_ships,nearshore_ships_mesh,nearshore_ships_layers,nearshore_sequence,nearshore_ocean,nearshore_core,nearshore_glad")

function(nearshore_check_architecture)
  foreach(rule IN LISTS NEARSHORE_ALLOWED_ARROWS)
    string(REPLACE ":" ";" parts "${rule}")
    list(GET parts 0 library)
    if(library MATCHES "\\?$")
      string(REGEX REPLACE "\\?$" "" library "${library}")
      if(NOT TARGET ${library})
        continue()
      endif()
    endif()
    list(LENGTH parts part_count)
    set(allowed "")
    if(part_count GREATER 1)
      list(GET parts 1 allowed_text)
      string(REPLACE "," ";" allowed "${allowed_text}")
    endif()
    if(NOT TARGET ${library})
      message(FATAL_ERROR "architecture: ${library} is in NEARSHORE_ALLOWED_ARROWS but no such library exists")
    endif()
    get_target_property(links ${library} LINK_LIBRARIES)
    if(NOT links)
      set(links "")
    endif()
    foreach(link IN LISTS links)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" link "${link}")
      if(link MATCHES "^nearshore" AND NOT link IN_LIST allowed)
        message(FATAL_ERROR "architecture: ${library} links ${link}, which docs/architecture.md does not allow "
                            "(allowed: ${allowed}). Move the code to the room that owns it, or change the "
                            "architecture on purpose (docs/architecture.md and cmake/NearshoreArchitecture.cmake).")
      endif()
    endforeach()
  endforeach()
endfunction()
