# The conical island basin of Briggs et al. (1995) as an ESRI ASCII grid of still-water depths
# (m, positive down; land above still water negative): data/cases/conical_island.toml's frame,
# 32 m along the waves (the laboratory's x + 5 m) by 27.6 m, 0.32 m of water, a 1:4 cone of base
# radius 3.6 m centred at (17.96, 13.80) whose flat top stands 0.305 m above still water
# (data/validation/briggs_1995/README.md). Usage: awk -f conical_island_grid.awk -v cell=0.05
BEGIN {
  if (cell <= 0) cell = 0.05
  columns = int(32.0 / cell + 0.5); rows = int(27.6 / cell + 0.5)
  printf "ncols %d\nnrows %d\nxllcorner 0\nyllcorner 0\ncellsize %g\nNODATA_value -9999\n", columns, rows, cell
  for (row = rows - 1; row >= 0; row--) {  # the northern row first
    line = ""
    for (column = 0; column < columns; column++) {
      x = (column + 0.5) * cell; y = (row + 0.5) * cell
      r = sqrt((x - 17.96) ^ 2 + (y - 13.80) ^ 2)
      depth = r > 3.6 ? 0.32 : 0.32 - 0.25 * (3.6 - r)
      if (depth < 0.32 - 0.625) depth = 0.32 - 0.625
      line = line sprintf(column ? " %.5f" : "%.5f", depth)
    }
    print line
  }
}
