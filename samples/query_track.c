/* samples/query_track.c: the smallest host. It opens a baked harbour, sails a ship across it on a
 * straight track at 5 m/s, and prints the water under the ship every second, as a ship-motion
 * model would ask for it: no window, no OpenGL, only the C API (nearshore.h).
 *
 *   query_track SEQUENCE_FOLDER [SECONDS]
 *
 * Prints CSV: time_s,x_m,y_m,elevation_m,velocity_x_m_s,velocity_y_m_s,dry
 * Built by CI as C11 with a C compiler against the installed package (docs/c-api.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <nearshore.h>

static int fail(const char* what) {
  fprintf(stderr, "query_track: %s failed: %s\n", what, nearshore_last_error());
  return 1;
}

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: query_track SEQUENCE_FOLDER [SECONDS]\n");
    return 2;
  }
  const double duration_s = argc > 2 ? atof(argv[2]) : 60.0;

  nearshore_sea_options options;
  nearshore_sea_options_init(&options);
  options.plan = NEARSHORE_PLAN_AUTO; /* the bake's seamless loop when it has one */
  nearshore_sea* sea = NULL;
  if (nearshore_sea_open(argv[1], &options, &sea) != NEARSHORE_OK) return fail("nearshore_sea_open");

  nearshore_site_info site;
  site.struct_size = sizeof site;
  if (nearshore_site_info_get(sea, &site) != NEARSHORE_OK) {
    nearshore_sea_close(sea);
    return fail("nearshore_site_info_get");
  }
  /* A track from the south-west quarter to the north-east quarter of the harbour rectangle. */
  const double start[2] = {0.25 * site.width_m, 0.25 * site.height_m};
  const double end[2] = {0.75 * site.width_m, 0.75 * site.height_m};
  const double speed_m_s = 5.0;
  const double dx = end[0] - start[0], dy = end[1] - start[1];
  const double length_m = fmax(sqrt(dx * dx + dy * dy), 1.0);

  printf("time_s,x_m,y_m,elevation_m,velocity_x_m_s,velocity_y_m_s,dry\n");
  int status = 0;
  for (double t = 0.0; t <= duration_s; t += 1.0) {
    double along = speed_m_s * t;
    if (along > length_m) along = length_m;
    const double position[2] = {start[0] + dx * along / length_m, start[1] + dy * along / length_m};
    nearshore_surface_sample sample;
    /* The water at time t, whether or not a renderer has displayed it (decoded here if needed). */
    if (nearshore_sea_query_at(sea, t, position, 1, &sample) != NEARSHORE_OK) {
      status = fail("nearshore_sea_query_at");
      break;
    }
    printf("%.1f,%.2f,%.2f,%.4f,%.4f,%.4f,%d\n", t, position[0], position[1], sample.elevation_m,
           sample.velocity_x_m_s, sample.velocity_y_m_s, sample.dry);
  }
  nearshore_sea_close(sea);
  return status;
}
