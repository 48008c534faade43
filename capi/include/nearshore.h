/* nearshore.h: the plain C API of the nearshore runtime (libnearshore.so).
 *
 * A host engine (a ship-handling simulator, a game) opens a baked harbour sequence, advances it
 * once per displayed frame, asks the CPU for the water surface under its ships, and either lets
 * nearshore draw into the host's OpenGL context or takes the current textures and draws them
 * itself. docs/runtime.md and docs/c-api.md explain the model; samples/ has one program per use.
 *
 * Conventions
 *  - Handles are opaque. Every call returns a nearshore_status; NEARSHORE_OK is 0. On failure the
 *    message (which file, which value, and the fix) is kept per thread: nearshore_last_error().
 *    No C++ exception ever crosses this API.
 *  - Positions are in the SITE frame: metres east (x) and north (y) of the harbour grid's south-west
 *    corner, z up from the still-water level. nearshore_site_info_get() gives the corner's projected
 *    coordinates and latitude/longitude; nearshore_site_from_lat_lon() converts.
 *  - Times are display seconds of the sea's own timeline: time 0 is the first step of its plan.
 *    Any clock the host uses: faster or slower than real time, paused, stepped, or going back (an
 *    instructor's rewind); nearshore_sea_options.time_mode says what a sea does when its
 *    background decoder is not where the clock is.
 *  - Thread safety is stated per call: "render thread" calls must come from one thread at a time
 *    (the one that advances and draws); "any thread" calls may run concurrently with everything,
 *    including nearshore_sea_advance, because queries read an immutable snapshot.
 *  - Structs with a `struct_size` first member are versioned: set it to sizeof(the struct) (the
 *    *_init functions do), so a newer library can read an older host's struct.
 */
#ifndef NEARSHORE_H
#define NEARSHORE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define NEARSHORE_API __attribute__((visibility("default")))
#else
#define NEARSHORE_API
#endif

/* 2: ships (nearshore_fleet_*). 3: the renderer draws a fleet (nearshore_renderer_set_fleet).
 * 4: a ship's dispersive wake (nearshore_ship_options.dispersive_wake, nearshore_fleet_dispersive_wake).
 * 5: host-driven time: nearshore_sea_options.time_mode and ready_timeout_s, nearshore_sea_wait_until_ready,
 *    NEARSHORE_TIMEOUT, NEARSHORE_UNDERRUN, the underrun counters of nearshore_stats; time may go back.
 *    Hulls stop at structures and land (nearshore_fleet_next_contact); every ship option range-checked.
 * 6: harbour heights joined in time by a cubic Hermite of the bake's own d eta / dt:
 *    nearshore_sea_query_vertical_velocity, the rate textures of nearshore_gl_textures.
 * 7: weather: nearshore_lighting.cloud_cover, visibility_m, fog_top_m (a version 6 struct is
 *    still taken, with clear air).
 * 8: every wave layer of a ship listed (nearshore_fleet_wave_layer_count, nearshore_fleet_wave_layer:
 *    each field with its kind and shown weight).
 * 9: the dispersive wake on by default (nearshore_ship_options_init sets dispersive_wake = 1; it is
 *    forced by the hull's thin-ship sources and breaks at Michell's steepness); its breaking crests'
 *    foam follows the stern wake's decals in nearshore_fleet_wake_decals. A host that draws only
 *    nearshore_fleet_bow_wave should draw every layer (nearshore_fleet_wave_layer) or set
 *    dispersive_wake = 0.
 * A host built against version N runs on a library of version >= N. */
#define NEARSHORE_API_VERSION 9

typedef enum nearshore_status {
  NEARSHORE_OK = 0,
  NEARSHORE_INVALID_ARGUMENT = 1, /* a null handle or pointer, a value out of range */
  NEARSHORE_IO_ERROR = 2,         /* a file is missing, unreadable, truncated or corrupt */
  NEARSHORE_FORMAT_ERROR = 3,     /* a manifest or loops.json of another version or another bake */
  NEARSHORE_GL_ERROR = 4,         /* no current OpenGL 3.3 core context, a shader that fails */
  NEARSHORE_INTERNAL_ERROR = 5,   /* a bug: the message says where; please report it */
  NEARSHORE_TIMEOUT = 6,          /* a wait ran out before the sea was ready (version 5) */
  NEARSHORE_UNDERRUN = 7          /* not a failure: nearshore_sea_advance moved the sea, but the background
                                     decoder had not made the planned keyframes of that time, so older
                                     ones are shown (free-running mode; version 5). nearshore_stats counts
                                     them; NEARSHORE_TIME_LOCKSTEP never underruns. */
} nearshore_status;

/* The message of the last failed call on this thread ("" if none). Valid until the next failing
 * call on this thread. Any thread. */
NEARSHORE_API const char* nearshore_last_error(void);
/* "NEARSHORE_OK", ... Any thread. */
NEARSHORE_API const char* nearshore_status_name(nearshore_status status);
/* NEARSHORE_API_VERSION of the library actually loaded. Any thread. */
NEARSHORE_API int nearshore_api_version(void);

/* ---- a sea: one baked harbour sequence, streamed, inside an endless deep-water field ---------- */
typedef struct nearshore_sea nearshore_sea;

typedef enum nearshore_plan {
  NEARSHORE_PLAN_AUTO = 0,         /* the exact period of a periodic bake, else the planned loop,
                                      else a random walk, else frame order */
  NEARSHORE_PLAN_EXACT_PERIOD = 1,
  NEARSHORE_PLAN_OPTIMAL_LOOP = 2,
  NEARSHORE_PLAN_RANDOM_WALK = 3,
  NEARSHORE_PLAN_FRAME_ORDER = 4
} nearshore_plan;

/* What a sea does when the host's clock is somewhere its background decoder has not reached
 * (version 5). */
typedef enum nearshore_time_mode {
  /* The default. nearshore_sea_advance never waits: a missing keyframe is an underrun, the
   * nearest older ones are shown and the call returns NEARSHORE_UNDERRUN. For a visual channel
   * that must never stall. The first advance after opening is the exception: it makes what it
   * lacks, so a sea never starts flat. */
  NEARSHORE_TIME_FREE_RUNNING = 0,
  /* The host's clock drives everything: nearshore_sea_advance shows exactly the keyframes of the
   * requested time, decoding and synthesising on the calling thread what the background has not
   * made yet (the call then takes milliseconds to tens of milliseconds). Any time rate, pausing,
   * stepping and rewinding give the same fields, bit for bit, as real time at the same display
   * times. For ship physics, faster-than-real-time runs, several stations that must agree, and
   * recordings. */
  NEARSHORE_TIME_LOCKSTEP = 1
} nearshore_time_mode;

/* Every number has a range, and a value outside it is refused with NEARSHORE_INVALID_ARGUMENT and
 * a message naming the field, its range and why (docs/c-api.md "Sea options"). */
typedef struct nearshore_sea_options {
  uint32_t struct_size;
  nearshore_plan plan;
  uint64_t seed;                      /* random walk seed; 0: the one loops.json records */
  int ring_keyframes;                 /* harbour keyframes decoded ahead: 0 (the default, about 1 s of
                                         play within 512 MiB) or 2-1024 */
  double deep_water_interval_s;       /* deep-water keyframe spacing: 0 (the default, 1/30 s) or
                                         1/240 - 1 s */
  int beaufort_force;                 /* deep water when the bake has none: 0-12; -1: the default */
  double wind_direction_deg;          /* compass direction the wind blows FROM: -360 - 720 degrees */
  int verify_checksums;               /* 1: check each frame's XXH64 before use */
  /* Since version 5 (a host's older, shorter struct gets FREE_RUNNING, 10 s and OK on underruns). */
  nearshore_time_mode time_mode;      /* NEARSHORE_TIME_FREE_RUNNING (default) or NEARSHORE_TIME_LOCKSTEP */
  double ready_timeout_s;             /* the open waits until the first frame (display time 0) is decoded,
                                         at most this long (0-600 s; 0: no wait; default 10 s);
                                         NEARSHORE_TIMEOUT if it is not */
} nearshore_sea_options;

/* Fills the defaults. Any thread. */
NEARSHORE_API void nearshore_sea_options_init(nearshore_sea_options* options);

/* Opens `sequence_folder` (a `nearshore bake` output) and starts its background decoder.
 * options may be NULL (defaults). Any thread; the sea is then used as stated per call. */
NEARSHORE_API nearshore_status nearshore_sea_open(const char* sequence_folder, const nearshore_sea_options* options,
                                                  nearshore_sea** sea);
/* Opens a sea-state library (a `nearshore library` output folder, with library.json) and streams
 * its baked state nearest `conditions`: "KEY=VALUE,..." with the quantities the library sweeps,
 * e.g. "wind_direction_deg=30,tide_m=1.5" ("" or NULL: the first state). Any thread. */
NEARSHORE_API nearshore_status nearshore_sea_open_library(const char* library_folder, const char* conditions,
                                                          const nearshore_sea_options* options, nearshore_sea** sea);
/* A sea opened from a library: crossfades to the baked state nearest `conditions` over
 * `crossfade_s` seconds of display time from the next advance (0: a cut), e.g. the tide rising or
 * the wind veering during an exercise. `state_id` (may be NULL) receives the chosen state's id.
 * Render thread. */
NEARSHORE_API nearshore_status nearshore_sea_request_conditions(nearshore_sea* sea, const char* conditions,
                                                                double crossfade_s, char state_id[64]);

/* Stops the decoder and frees everything. NULL is allowed. Render thread, after the last call on
 * any thread has returned. */
NEARSHORE_API void nearshore_sea_close(nearshore_sea* sea);

/* Moves the sea to display time `time_s` (any finite time >= 0; going back is a seek like going
 * far ahead: the decoder restarts there). NEARSHORE_TIME_FREE_RUNNING: never waits on disk; if the
 * decoder is behind, the nearest older keyframes are shown, the underrun is counted and the call
 * returns NEARSHORE_UNDERRUN (the sea did move; keep calling). NEARSHORE_TIME_LOCKSTEP: always the
 * planned keyframes of `time_s`, made on this thread when the decoder has not got there.
 * Render thread. */
NEARSHORE_API nearshore_status nearshore_sea_advance(nearshore_sea* sea, double time_s);

/* Waits until the keyframes of display time `time_s` are decoded (at most `timeout_s`, 0-600 s):
 * NEARSHORE_OK when they are, NEARSHORE_TIMEOUT when not. For a host's start-up (before it starts
 * its clock), after a seek, or before a frame that must be exact; never for the render loop.
 * Render thread. Since version 5. */
NEARSHORE_API nearshore_status nearshore_sea_wait_until_ready(nearshore_sea* sea, double time_s, double timeout_s);

/* Changes the deep water's wind when the bake has no deep-water section (the field is rebuilt in
 * the background and swapped in). Render thread. */
NEARSHORE_API nearshore_status nearshore_sea_set_wind(nearshore_sea* sea, int beaufort_force, double wind_direction_deg);

typedef struct nearshore_site_info {
  uint32_t struct_size;
  int columns, rows;               /* harbour grid cells */
  double cell_size_x_m, cell_size_y_m;  /* dx (east) and dy (north); equal for square cells */
  double width_m, height_m;        /* the harbour rectangle in the site frame: [0, width] x [0, height] */
  double origin_x_m, origin_y_m;   /* the site origin in the grid's projected CRS */
  double origin_latitude_deg, origin_longitude_deg; /* the site origin (NaN if the grid has no CRS) */
  double frame_interval_s;         /* of the baked frames */
  int frame_count;
} nearshore_site_info;
/* Any thread. */
NEARSHORE_API nearshore_status nearshore_site_info_get(const nearshore_sea* sea, nearshore_site_info* info);
/* Latitude/longitude (WGS 84, degrees) to the site frame. Any thread. */
NEARSHORE_API nearshore_status nearshore_site_from_lat_lon(const nearshore_sea* sea, double latitude_deg,
                                                           double longitude_deg, double* x_m, double* y_m);

typedef struct nearshore_stats {
  uint32_t struct_size;
  double display_time_s;
  int ring_filled, ring_capacity;     /* harbour keyframes decoded ahead / room for */
  uint64_t underruns;                 /* display frames that found their keyframe not ready */
  uint64_t keyframes_decoded;
  double decode_frames_per_s;         /* background decode throughput */
  double decode_real_time_multiple;   /* throughput x frame interval: > 1 keeps up */
  uint64_t bad_frames_held;           /* missing/corrupt frames replaced by the previous one */
  uint64_t transitions_taken;         /* jumps of the plan played so far */
  long long plan_step;                /* the step on display */
  int crossfading;                    /* 1 while a planned crossfade is on display */
  char plan_name[32];                 /* the plan's kind: "exact period", "optimal loop", "random walk" or
                                         "frame order" (after a fallback; message says why) */
  char message[512];                  /* the last warning (a held frame, no loops.json...), or "" */
  /* Since version 5 (a host's older, shorter struct is filled up to message). */
  uint64_t harbour_underruns;         /* advances that lacked a harbour keyframe */
  uint64_t deep_underruns;            /* advances that lacked a deep-water keyframe */
  uint64_t synchronous_keyframes;     /* keyframes made on the calling thread (lockstep, the first
                                         advance, nearshore_sea_query_at) */
  int last_advance_planned;           /* 1: the last advance showed the planned keyframes */
  nearshore_time_mode time_mode;
} nearshore_stats;
/* Any thread (a consistent copy). struct_size: sizeof(nearshore_stats), or an older version's. */
NEARSHORE_API nearshore_status nearshore_sea_stats(const nearshore_sea* sea, nearshore_stats* stats);

/* ---- CPU surface queries: the water the GPU draws, without a read-back ------------------------ */
typedef struct nearshore_surface_sample {
  float elevation_m;                  /* of the surface above still water */
  float velocity_x_m_s, velocity_y_m_s; /* depth-averaged current (flux / total depth); 0 where dry */
  float normal[3];                    /* unit, z up */
  int dry;                            /* 1 on land or where the water has run off. There velocity is 0
                                         and elevation_m is what the baked frames hold at that point
                                         (blended with the open sea by the harbour weight): on the
                                         cells a bake marks as land, the frames' value there, which a
                                         host must not read as water; buoyancy code should skip dry
                                         points */
} nearshore_surface_sample;

/* Samples the surface at `count` site points (xy_m: x0, y0, x1, y1, ...) as displayed after the
 * last nearshore_sea_advance. Any thread. */
NEARSHORE_API nearshore_status nearshore_sea_query(const nearshore_sea* sea, const double* xy_m, size_t count,
                                                   nearshore_surface_sample* samples);
/* The same at display time `time_s` (not necessarily the displayed one): from the frames already
 * decoded when the time is within the ring, else decoded on the calling thread (slow). Any thread. */
NEARSHORE_API nearshore_status nearshore_sea_query_at(const nearshore_sea* sea, double time_s, const double* xy_m,
                                                      size_t count, nearshore_surface_sample* samples);

/* d eta / dt (m/s) of the displayed surface at `count` site points, one float each: the time
 * derivative of the cubic Hermite the harbour's keyframes are joined by (heights are smooth in
 * time: the rates come from the bake's mass equation), blended with the open sea's. For heave
 * damping and relative motion. Any thread. (API version 6.) */
NEARSHORE_API nearshore_status nearshore_sea_query_vertical_velocity(const nearshore_sea* sea, const double* xy_m,
                                                                     size_t count, float* vertical_velocity_m_s);

/* ---- drawing in the host's OpenGL context -------------------------------------------------- */
typedef struct nearshore_renderer nearshore_renderer;

typedef enum nearshore_grid {
  NEARSHORE_GRID_RADIAL = 0,     /* rings around the camera (seed 003) */
  NEARSHORE_GRID_QUADTREE = 1,   /* CDLOD quadtree, crack-free */
  NEARSHORE_GRID_PROJECTED = 2   /* screen-space grid on the Earth's sphere, for high views */
} nearshore_grid;

typedef struct nearshore_camera {
  uint32_t struct_size;
  double eye_m[3];                 /* site frame */
  double target_m[3];
  double vertical_fov_deg;
  double near_m, far_m;
  double sun_azimuth_deg, sun_elevation_deg;
} nearshore_camera;
/* Fills a camera looking north from 100 m up, 45 degree field of view, sun at 200/35 degrees.
 * Any thread. */
NEARSHORE_API void nearshore_camera_init(nearshore_camera* camera);

/* Returns the address of an OpenGL function by name (glfwGetProcAddress, SDL_GL_GetProcAddress,
 * eglGetProcAddress, ...). */
typedef void* (*nearshore_gl_proc_address)(const char* name);

/* Loads OpenGL through `get_proc_address` and creates the GL objects in the host's CURRENT OpenGL
 * 3.3+ core context (the host made it current on this thread). Render thread, with that context
 * current. */
NEARSHORE_API nearshore_status nearshore_renderer_create(nearshore_sea* sea, nearshore_grid grid,
                                                         nearshore_gl_proc_address get_proc_address,
                                                         nearshore_renderer** renderer);
/* Frees the GL objects; the same context must be current. NULL is allowed. Render thread. */
NEARSHORE_API void nearshore_renderer_destroy(nearshore_renderer* renderer);
/* Draws the sea as of the last advance into the framebuffer bound by the host, viewport
 * width x height pixels. Render thread, context current. */
NEARSHORE_API nearshore_status nearshore_renderer_draw(nearshore_renderer* renderer, const nearshore_camera* camera,
                                                       int width_px, int height_px);
/* Reads back the last nearshore_renderer_draw as RGBA8, row 0 at the top (screenshots). Render
 * thread, context current. */
NEARSHORE_API nearshore_status nearshore_renderer_read_pixels(nearshore_renderer* renderer, int width_px,
                                                              int height_px, uint8_t* rgba);

/* ---- lighting (docs/lighting.md) -------------------------------------------------------------
 * What a renderer draws the sea under: the sun (from a place and a UTC time, or the camera's
 * sun_azimuth_deg / sun_elevation_deg), the clear sky of that sun (Preetham), what is in the air
 * and in the water, the wind's sub-grid roughness. Set once or per frame; kept until changed. */
typedef struct nearshore_lighting {
  uint32_t struct_size;
  /* When not empty, the sun stands where it does at this UTC instant ("2026-06-21T11:00:00Z"),
   * seen from latitude_deg / longitude_deg (WGS 84), or from the site's centre when either is
   * NaN; when empty (the default), the camera's sun_azimuth_deg / sun_elevation_deg hold. */
  char utc_iso8601[40];
  double latitude_deg, longitude_deg;  /* NaN: the site's centre */
  double atmospheric_turbidity;        /* Preetham T: 2 very clear, 3 clear, 6 hazy, 10 thin fog (1.7-10) */
  double chlorophyll_mg_m3;            /* phytoplankton (0-100): greener water */
  double cdom_absorption_440_per_m;    /* dissolved organic matter at 440 nm (browner); < 0: from the chlorophyll */
  double water_turbidity_ntu;          /* suspended sediment (0-1000 NTU): milkier, the seabed hides sooner */
  double wind_speed_m_s;               /* at 10 m: the roughness the grid cannot show, shoreline waves */
  double wind_direction_deg;           /* compass direction the wind blows FROM, degrees */
  double exposure_compensation;        /* 1: automatic exposure; 2: one stop brighter */
  int local_reflections;               /* 1: land and structures mirrored in the water; 0: sky only */
  /* API version 7: the weather (docs/lighting.md step 13). A struct of version 6 (struct_size up
   * to local_reflections, padded) is taken with clear air. */
  double cloud_cover;                  /* 0..1: the share of the CIE overcast sky; the sun's beam dims by 1 - c */
  double visibility_m;                 /* meteorological optical range (5 % contrast), m; 0: no fog or haze */
  double fog_top_m;                    /* top of the fog or haze layer above the sea, m */
} nearshore_lighting;
/* Fills the defaults (struct_size, no UTC time, T 2.5, chlorophyll 0.3, sediment 0.5 NTU, wind
 * 5 m/s from the north, exposure 1, local reflections on, clear sky: no cloud, no fog, a fog top
 * of 150 m). Any thread. */
NEARSHORE_API void nearshore_lighting_init(nearshore_lighting* lighting);
/* Render thread. A bad value (a UTC string that does not parse, a place with no map projection,
 * a number out of its range) is refused, naming the field, and the previous lighting is kept. */
NEARSHORE_API nearshore_status nearshore_renderer_set_lighting(nearshore_renderer* renderer,
                                                               const nearshore_lighting* lighting);
/* Where the sun stands (compass azimuth, apparent elevation in degrees) seen from a place at a UTC
 * instant (NOAA/Meeus). Needs no sea and no OpenGL. Any thread. */
NEARSHORE_API nearshore_status nearshore_sun_position(double latitude_deg, double longitude_deg,
                                                      const char* utc_iso8601, double* azimuth_deg,
                                                      double* elevation_deg);

/* ---- the host draws itself: the current fields as GL textures or CPU arrays -------------------- */
typedef struct nearshore_gl_textures {
  uint32_t struct_size;
  /* Harbour: R32F GL_TEXTURE_2D, columns x rows texels, texel (i, j) at the centre of cell (i, j)
   * ((i + 0.5) cell_size_x_m, (j + 0.5) cell_size_y_m), row 0 south. [0] from, [1] to. */
  unsigned int harbour_elevation[2], harbour_breaking[2];
  float harbour_fraction;               /* f; without rates (below) shown = (1 - f) from + f to */
  /* Deep water: R32F GL_TEXTURE_2D_ARRAY, N x N texels, one layer per cascade; texel (i, j) of
   * layer c at (i L_c / N, j L_c / N) of the site frame, repeating with period L_c. */
  unsigned int deep_elevation[2], deep_displacement_x[2], deep_displacement_y[2];
  unsigned int deep_slope_x[2], deep_slope_y[2];
  int cascade_count;                    /* 0: no deep water */
  int deep_grid_size;                   /* N */
  float cascade_tile_m[8];              /* L_c */
  float deep_water_fraction;
  /* API version 6: the harbour's d eta / dt (R32F, m/s) at each keyframe. With harbour_has_rates,
   * shown = h00 E0 + h10 T R0 + h01 E1 + h11 T R1 (cubic Hermite in f: h00 = 2f^3 - 3f^2 + 1,
   * h10 = f^3 - 2f^2 + f, h01 = -2f^3 + 3f^2, h11 = f^3 - f^2; T = frame_interval_s). A struct of
   * version 5 (struct_size up to deep_water_fraction) is filled without these. */
  unsigned int harbour_elevation_rate[2];
  int harbour_has_rates;
  float frame_interval_s;
} nearshore_gl_textures;
/* Makes the fields of the last nearshore_sea_advance resident on the GPU without drawing (for a
 * host that draws them itself) and returns their texture names (owned by nearshore, valid until
 * the next upload or draw). Render thread, context current. */
NEARSHORE_API nearshore_status nearshore_renderer_upload(nearshore_renderer* renderer, nearshore_gl_textures* textures);

/* Copies the displayed harbour surface elevation (m), joined in time as drawn (the Hermite above), into `elevation_m`
 * (columns x rows floats, row 0 south; `capacity` floats available). Any thread. */
NEARSHORE_API nearshore_status nearshore_sea_copy_harbour_elevation(const nearshore_sea* sea, float* elevation_m,
                                                                    size_t capacity);

/* ---- ships: buoyant hulls on the sea, bow waves, stern wakes (docs/ships.md) ------------------
 * A fleet is bound to a sea: each nearshore_fleet_step moves every ship by the forces of the water
 * the renderer draws (the sea after the last nearshore_sea_advance, plus the other ships' bow
 * waves), runs each ship's bow-wave grid and stern wake, pushes ships apart and grounds them on the
 * harbour's depth. Ships are numbered 0, 1, ... in the order they were added. Positions are site
 * metres; the body frame is x forward, y port, z up. Every fleet call is render thread: not
 * concurrent with nearshore_fleet_step. The sea must outlive its fleets. */
typedef struct nearshore_fleet nearshore_fleet;

typedef enum nearshore_ship_order {
  NEARSHORE_ORDER_MANUAL = 0,  /* the host's telegraph and helm: nearshore_fleet_set_controls */
  NEARSHORE_ORDER_ENGINE = 1,  /* a fixed engine order, `engine_order` */
  NEARSHORE_ORDER_SPEED = 2    /* the engine holds `speed_m_s` ahead */
} nearshore_ship_order;

typedef struct nearshore_ship_options {
  uint32_t struct_size;
  const char* name;              /* in messages and events; NULL: "ship N" */
  const char* hull;              /* "box_barge", "wigley", "tug", or a mesh file (OBJ, PLY, glTF, STL:
                                    closed, normals out, metres, x forward, z up) */
  double length_m, beam_m, depth_m; /* a generic hull's main dimensions; 0: the hull's default */
  double draft_m;                /* the loading: the draft (m), or ... */
  double mass_kg;                /* ... the displacement (kg) when > 0 (then draft_m is ignored) */
  double x_m, y_m;               /* start position of the hull's centre, site frame, or ... */
  int use_lat_lon;               /* ... 1: at latitude_deg, longitude_deg (WGS 84; the grid needs a CRS) */
  double latitude_deg, longitude_deg;
  double heading_deg;            /* compass, clockwise from north */
  double initial_speed_m_s;      /* along the heading */
  nearshore_ship_order order;
  double engine_order;           /* NEARSHORE_ORDER_ENGINE: -1 full astern .. 1 full ahead */
  double speed_m_s;              /* NEARSHORE_ORDER_SPEED */
  const double* route_xy_m;      /* optional waypoints x0, y0, x1, y1, ... (site m), followed by an
                                    autopilot (copied by add_ship); NULL: none */
  size_t route_count;
  int hull_points;               /* pressure points sampled on the hull; 0: 2000 */
  int bow_wave;                  /* 1 (default): a bow-wave grid; 0: none */
  int bow_wave_cells;            /* N of its N x N grid; 0: 128 */
  int dispersive_wake;           /* 1 (default since version 9): also a dispersive linear wave layer
                                    (Kelvin's wake; docs/ships.md), shown instead of the bow-wave grid
                                    below depth Froude number 0.7 where its window resolves the ship's
                                    waves; 0: the bow-wave grid alone (the default before version 9).
                                    Both layers: nearshore_fleet_wave_layer (version 8) */
} nearshore_ship_options;

/* Fills the defaults: a tug at draft 3 m, manual orders, bow wave and dispersive wake on. Any thread. */
NEARSHORE_API void nearshore_ship_options_init(nearshore_ship_options* options);

/* A fleet on `sea` (grounding and bow-wave bottoms from its harbour depth). Render thread. */
NEARSHORE_API nearshore_status nearshore_fleet_create(const nearshore_sea* sea, nearshore_fleet** fleet);
/* Frees the fleet. NULL is allowed. */
NEARSHORE_API void nearshore_fleet_destroy(nearshore_fleet* fleet);

/* Adds a ship upright at its draft; `ship` (may be NULL) receives its number. Refused with a message
 * naming the ship or the file: an unreadable, open or inverted mesh (NEARSHORE_IO_ERROR /
 * NEARSHORE_FORMAT_ERROR), a mass the hull cannot float, a position on land, on a structure or in
 * water shallower than the draft (NEARSHORE_INVALID_ARGUMENT). A refused ship changes nothing.
 * Since version 5 every field has a range, and a value outside it (NaN and infinities included) is
 * NEARSHORE_INVALID_ARGUMENT naming the field, the range and its reason (docs/ships.md "Ranges"):
 * length_m 2-500, beam_m 0.5-80, depth_m 0.5-50, draft_m 0.05-35 (0: not given), mass_kg 1-1e9 and
 * floating the hull at a draft of at least 5 % of its depth, x_m / y_m and waypoints within 1e6 m,
 * heading_deg finite, |initial_speed_m_s| and speed_m_s up to 30 m/s and length Froude number 1
 * (sqrt(9.81 L)), hull_points 100-20000 (0: 2000), bow_wave_cells 16-512 (0: 128). */
NEARSHORE_API nearshore_status nearshore_fleet_add_ship(nearshore_fleet* fleet, const nearshore_ship_options* options,
                                                        int* ship);
NEARSHORE_API nearshore_status nearshore_fleet_ship_count(const nearshore_fleet* fleet, int* count);

/* The host's telegraph and helm: engine order in [-1, 1], rudder order in degrees (> 0 turns to
 * port; clamped to the rudder's limit). Drops the ship's orders (its engine order, speed or route). */
NEARSHORE_API nearshore_status nearshore_fleet_set_controls(nearshore_fleet* fleet, int ship, double engine_order,
                                                            double rudder_deg);
/* Orders: hold `speed_m_s` ahead with the engine, and follow `route_xy_m` (route_count waypoints;
 * NULL / 0: keep the heading under manual rudder). */
NEARSHORE_API nearshore_status nearshore_fleet_set_speed(nearshore_fleet* fleet, int ship, double speed_m_s,
                                                         const double* route_xy_m, size_t route_count);

/* Advances every ship by dt_s (> 0, at most 1 s) on the sea as displayed after the last
 * nearshore_sea_advance: call once per displayed frame, after advancing the sea. */
NEARSHORE_API nearshore_status nearshore_fleet_step(nearshore_fleet* fleet, double dt_s);

typedef struct nearshore_ship_pose {
  uint32_t struct_size;
  double x_m, y_m, z_m;              /* the centre of gravity, site frame (z up from still water) */
  double orientation[4];             /* body -> site rotation as a unit quaternion (w, x, y, z) */
  double heading_deg;                /* compass, [0, 360) */
  double roll_deg;                   /* starboard down > 0 */
  double pitch_deg;                  /* bow down > 0 */
  double velocity_m_s[3];            /* of the centre of gravity, site frame */
  double angular_velocity_rad_s[3];  /* site frame */
  double speed_m_s;                  /* over ground along the body's x axis */
  double engine_order, rudder_deg;   /* the controls applied in the last step */
  int aground;                       /* 1 while hull points are below the seabed */
} nearshore_ship_pose;
NEARSHORE_API nearshore_status nearshore_fleet_ship_pose(const nearshore_fleet* fleet, int ship,
                                                         nearshore_ship_pose* pose);

/* The oldest message since the last call ("ship 'Tug 1' ran aground at (812.4, 1033.0) m ..."),
 * copied into text (capacity chars, cut to fit, NUL-terminated); *has_event = 0 when none is left. */
NEARSHORE_API nearshore_status nearshore_fleet_next_event(nearshore_fleet* fleet, char* text, size_t capacity,
                                                          int* has_event);

/* Since version 5. A ship touching, or coming clear of, a structure of the harbour grid (a
 * breakwater, quay or pier: its cells of porosity < 1, standing 2.5 m above still water) or the land.
 * Hulls do not pass through them: a hull point inside one is pushed out along the face's normal,
 * with friction; the ship keeps its orders (a tug may push on a quay). Structures are numbered 1, 2,
 * ... as connected groups of structure cells, row by row from the south-west; 0 is the land. */
typedef struct nearshore_ship_contact {
  uint32_t struct_size;
  int ship;                  /* the ship's number when it happened */
  int began;                 /* 1: it struck; 0: it is clear again */
  int structure;             /* 0: the land; k >= 1: structure k */
  int wall;                  /* 1: a quay wall or caisson (porosity < 0.05); 0: a porous breakwater or land */
  double porosity;           /* the structure's lowest porosity (1 for land) */
  double x_m, y_m, z_m;      /* began: the deepest contact point; ended: the ship's centre of gravity */
  double normal[2];          /* began: the face's normal there (site frame, out of the structure) */
  double closing_speed_m_s;  /* began: how fast the hull met the face */
  double time_s;             /* the fleet's time (the sum of its steps) */
  char description[128];     /* "structure 2 (a quay wall, porosity 0.00, 40 cells about (512.0, 880.0) m)" */
} nearshore_ship_contact;
/* The oldest contact since the last call into `contact` (its struct_size set); *has_contact = 0
 * when none is left. Each contact is also a text event (nearshore_fleet_next_event). */
NEARSHORE_API nearshore_status nearshore_fleet_next_contact(nearshore_fleet* fleet, nearshore_ship_contact* contact,
                                                            int* has_contact);

/* One stern-wake foam decal: a quad of width_m (across the track) x length_m (along it), centred
 * at (x_m, y_m), rotated yaw_rad counter-clockwise from east, drawn with foam texture `variant`
 * (0-3) at `opacity` (0-1). */
typedef struct nearshore_wake_decal {
  float x_m, y_m, yaw_rad, width_m, length_m, opacity;
  int variant;
} nearshore_wake_decal;
/* Copies up to `capacity` of ship `ship`'s decals: its stern wake's, oldest first, then (since
 * version 9) the foam of its breaking wave crests, oldest first; *count receives how many it has
 * (call with capacity 0 to size the array). */
NEARSHORE_API nearshore_status nearshore_fleet_wake_decals(const nearshore_fleet* fleet, int ship,
                                                           nearshore_wake_decal* decals, size_t capacity,
                                                           size_t* count);

/* A ship's bow-wave height field, for hosts that draw it themselves: columns x rows floats (m above
 * still water, added to the sea's surface), row 0 south, texel (i, j) at the site point
 * (origin_x_m + (i + 0.5) spacing_m, origin_y_m + (j + 0.5) spacing_m); 0 outside. `serial`
 * changes with every step (upload once per serial). columns = 0 when the ship has no bow wave. */
typedef struct nearshore_bow_wave_field {
  uint32_t struct_size;
  int columns, rows;
  double origin_x_m, origin_y_m, spacing_m;
  uint64_t serial;
} nearshore_bow_wave_field;
/* Fills `field` with the ship's shallow-water bow-wave grid (wave layer 0, below); copies the heights
 * into `heights_m` when it is not NULL (`capacity` floats, at least columns x rows). The heights carry
 * the grid's shown weight: 1 for a ship without a dispersive wake; for a ship with one, 0 where that
 * layer is shown (depth Froude number below 0.7), so a host that draws the fields itself draws every
 * layer of nearshore_fleet_wave_layer. */
NEARSHORE_API nearshore_status nearshore_fleet_bow_wave(const nearshore_fleet* fleet, int ship,
                                                        nearshore_bow_wave_field* field, float* heights_m,
                                                        size_t capacity);

/* The same for a ship's dispersive wake layer (columns = 0 when the ship has none). Each layer's
 * heights carry the weight the fleet shows it with (the two weights sum to 1 and fade over 2 s when
 * the depth Froude number crosses 0.7 / 0.8, or the ship's transverse wave 2 pi U^2 / g crosses 8 / 6
 * of the layer's nodes), so a host that draws both fields added to the sea draws what the fleet
 * queries below return. */
NEARSHORE_API nearshore_status nearshore_fleet_dispersive_wake(const nearshore_fleet* fleet, int ship,
                                                               nearshore_bow_wave_field* field, float* heights_m,
                                                               size_t capacity);

/* Since version 8. A ship's wave layers, for hosts that draw them themselves: layer 0 is the
 * shallow-water bow-wave grid, layer 1 (a ship with dispersive_wake) the dispersive layer; a ship
 * without a bow wave has none. The list is fixed when the ship is added; which layer is shown changes
 * with the ship's depth Froude number (docs/ships.md "Which layer a ship shows"), and the shown weights
 * of a ship's layers sum to 1. Drawing every layer's field added to the sea draws what the fleet
 * queries below and nearshore's renderer show. */
typedef enum nearshore_wave_layer_kind {
  NEARSHORE_WAVE_LAYER_SHALLOW_WATER = 0, /* the nonlinear shallow-water grid (nearshore_fleet_bow_wave):
                                             shown near and above depth Froude number 0.8 */
  NEARSHORE_WAVE_LAYER_DISPERSIVE = 1     /* the linear layer with exact dispersion (Kelvin's pattern;
                                             nearshore_fleet_dispersive_wake): shown below 0.7 */
} nearshore_wave_layer_kind;
typedef struct nearshore_wave_layer {
  uint32_t struct_size;
  nearshore_wave_layer_kind kind;
  double shown_weight;  /* 0-1, already in the layer's heights; a layer at 0 has zero heights and is
                           not stepped (it restarts from rest when chosen again) */
} nearshore_wave_layer;
/* How many wave layers ship `ship` has (0, 1 or 2) into *count. */
NEARSHORE_API nearshore_status nearshore_fleet_wave_layer_count(const nearshore_fleet* fleet, int ship, int* count);
/* Layer `layer` (0 .. count - 1) of ship `ship`: its kind and shown weight into `info` and its height
 * field into `field` (as nearshore_fleet_bow_wave); the heights into `heights_m` when it is not NULL
 * (`capacity` floats, at least columns x rows). A layer outside the list is NEARSHORE_INVALID_ARGUMENT
 * naming `layer` and the ship's count. */
NEARSHORE_API nearshore_status nearshore_fleet_wave_layer(const nearshore_fleet* fleet, int ship, int layer,
                                                          nearshore_wave_layer* info, nearshore_bow_wave_field* field,
                                                          float* heights_m, size_t capacity);

/* nearshore_sea_query / nearshore_sea_query_at with the fleet's bow waves added: elevation and
 * normal include every ship's bow wave as of its last step (the velocity is the sea's). For buoys,
 * other vessels and cameras that must ride the same surface the ships make. */
NEARSHORE_API nearshore_status nearshore_fleet_query(const nearshore_fleet* fleet, const double* xy_m, size_t count,
                                                     nearshore_surface_sample* samples);
NEARSHORE_API nearshore_status nearshore_fleet_query_at(const nearshore_fleet* fleet, double time_s,
                                                        const double* xy_m, size_t count,
                                                        nearshore_surface_sample* samples);

/* Since version 3. The renderer draws `fleet` with its sea from the next nearshore_renderer_draw
 * on: every ship's bow wave added to the drawn surface and its normal (the first 16 ships'; the
 * same sum nearshore_fleet_query makes on the CPU), the stern-wake decals as foam, each hull at
 * its pose (lit, its bottom paint below the design waterline, hidden by the water below it), as
 * they stand after the last nearshore_fleet_step. The fleet must be bound to the renderer's sea;
 * NULL unbinds. The fleet must outlive the binding (unbind before nearshore_fleet_destroy). Render
 * thread, with the renderer's context current. */
NEARSHORE_API nearshore_status nearshore_renderer_set_fleet(nearshore_renderer* renderer, nearshore_fleet* fleet);

#ifdef __cplusplus
}
#endif

#endif /* NEARSHORE_H */
