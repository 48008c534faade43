/* samples/ship_track.c: a ship on the sea, through the C API only. It opens a baked harbour, puts
 * a harbour tug in it under a speed order heading for the shore, and prints every second where
 * the ship is, how it lies and what the water under its bow does (the sea plus every ship's bow
 * wave), and the fleet's events (grounding) on stderr. It also shows that a ship placed on land
 * is refused with a message naming it, while everything else goes on.
 *
 *   ship_track SEQUENCE_FOLDER [SECONDS] [X_M Y_M HEADING_DEG]
 *
 * Prints CSV: time_s,x_m,y_m,heading_deg,roll_deg,pitch_deg,speed_m_s,aground,bow_elevation_m,wake_decals
 * Built by CI as C11 with a C compiler against the installed package (docs/c-api.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <nearshore.h>

static int fail(const char* what) {
  fprintf(stderr, "ship_track: %s failed: %s\n", what, nearshore_last_error());
  return 1;
}

static void print_events(nearshore_fleet* fleet) {
  char text[512];
  int has_event = 1;
  while (nearshore_fleet_next_event(fleet, text, sizeof text, &has_event) == NEARSHORE_OK && has_event)
    fprintf(stderr, "ship_track: %s\n", text);
}

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: ship_track SEQUENCE_FOLDER [SECONDS] [X_M Y_M HEADING_DEG]\n");
    return 2;
  }
  const double duration_s = argc > 2 ? atof(argv[2]) : 60.0;

  /* Ship physics steps as fast as the CPU allows (faster than real time): lockstep, so every
   * advance shows the planned sea of its time, made on this thread when the decoder is behind. */
  nearshore_sea_options sea_options;
  nearshore_sea_options_init(&sea_options);
  sea_options.time_mode = NEARSHORE_TIME_LOCKSTEP;
  nearshore_sea* sea = NULL;
  if (nearshore_sea_open(argv[1], &sea_options, &sea) != NEARSHORE_OK) return fail("nearshore_sea_open");
  nearshore_site_info site;
  site.struct_size = sizeof site;
  nearshore_fleet* fleet = NULL;
  if (nearshore_site_info_get(sea, &site) != NEARSHORE_OK || nearshore_fleet_create(sea, &fleet) != NEARSHORE_OK) {
    nearshore_sea_close(sea);
    return fail("opening the fleet");
  }

  /* A ship on land is refused by name; the fleet carries on without it. */
  nearshore_ship_options options;
  nearshore_ship_options_init(&options);
  options.name = "Ashore";
  options.x_m = site.width_m - 1.0;
  options.y_m = 0.5 * site.height_m;
  if (nearshore_fleet_add_ship(fleet, &options, NULL) != NEARSHORE_OK)
    fprintf(stderr, "ship_track: refused as it should be: %s\n", nearshore_last_error());

  /* The tug (24 m, draft 3 m) at 4 m/s, by default from the west quarter towards the east. */
  options.name = "Tug 1";
  options.x_m = argc > 5 ? atof(argv[3]) : 0.25 * site.width_m;
  options.y_m = argc > 5 ? atof(argv[4]) : 0.5 * site.height_m;
  options.heading_deg = argc > 5 ? atof(argv[5]) : 90.0;
  options.order = NEARSHORE_ORDER_SPEED;
  options.speed_m_s = 4.0;
  options.initial_speed_m_s = 4.0;
  int tug = -1;
  if (nearshore_fleet_add_ship(fleet, &options, &tug) != NEARSHORE_OK) {
    nearshore_fleet_destroy(fleet);
    nearshore_sea_close(sea);
    return fail("nearshore_fleet_add_ship");
  }

  printf("time_s,x_m,y_m,heading_deg,roll_deg,pitch_deg,speed_m_s,aground,bow_elevation_m,wake_decals\n");
  const double frame_s = 1.0 / 30.0;
  int status = 0;
  for (int frame = 1; frame <= (int)(duration_s / frame_s + 0.5); ++frame) {
    const double t = frame * frame_s;
    /* Once per displayed frame: the sea, then the ships on it. */
    if (nearshore_sea_advance(sea, t) != NEARSHORE_OK) { status = fail("nearshore_sea_advance"); break; }
    if (nearshore_fleet_step(fleet, frame_s) != NEARSHORE_OK) { status = fail("nearshore_fleet_step"); break; }
    print_events(fleet);
    if (frame % 30 != 0) continue;
    nearshore_ship_pose pose;
    pose.struct_size = sizeof pose;
    if (nearshore_fleet_ship_pose(fleet, tug, &pose) != NEARSHORE_OK) { status = fail("nearshore_fleet_ship_pose"); break; }
    /* The water 14 m ahead of the centre of gravity (just ahead of the bow), bow waves included. */
    const double heading_rad = pose.heading_deg * acos(-1.0) / 180.0;
    const double bow[2] = {pose.x_m + 14.0 * sin(heading_rad), pose.y_m + 14.0 * cos(heading_rad)};
    nearshore_surface_sample water;
    if (nearshore_fleet_query(fleet, bow, 1, &water) != NEARSHORE_OK) { status = fail("nearshore_fleet_query"); break; }
    size_t decals = 0;
    if (nearshore_fleet_wake_decals(fleet, tug, NULL, 0, &decals) != NEARSHORE_OK) { status = fail("nearshore_fleet_wake_decals"); break; }
    printf("%.0f,%.2f,%.2f,%.2f,%.3f,%.3f,%.3f,%d,%.4f,%zu\n", t, pose.x_m, pose.y_m, pose.heading_deg, pose.roll_deg,
           pose.pitch_deg, pose.speed_m_s, pose.aground, water.elevation_m, decals);
  }
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
  return status;
}
