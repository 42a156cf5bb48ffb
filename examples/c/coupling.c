/* A tiny CFD–DEM coupling loop through Clump's C API (docs/c_api.md).
 *
 * The "fluid solver" here is one line: an upward flow whose interstitial
 * velocity is U / eps in each horizontal layer of cells, with eps the
 * layer's void fraction, which this program reads from Clump's
 * void-fraction grid. Every coupling interval it reads the bodies, hands
 * Clump its fields on grids (the void fraction per cell, the velocity at
 * nodes on the layers' centres, which Clump interpolates at each body),
 * sets a persistent external force per body, steps Clump, and reads back
 * the fluid forces.
 *
 * Build: cc coupling.c -I crates/clump-capi/include -L target/ci -lclump_capi
 * Run:   ./a.out examples/c/settling.toml
 * It prints one line per interval and "done" at the end; the exit status
 * is 0 on success, 1 on an error (printed with Clump's message). */
#include "clump.h"

#include <stdio.h>
#include <stdlib.h>

#define CHECK(call)                                                        \
  do {                                                                     \
    int32_t s_ = (call);                                                   \
    if (s_ != CLUMP_OK) {                                                  \
      fprintf(stderr, "%s failed: %s: %s\n", #call, clump_status_name(s_), \
              clump_sim_error_message(sim));                               \
      clump_sim_free(sim);                                                 \
      return 1;                                                            \
    }                                                                      \
  } while (0)

int main(int argc, char **argv) {
  const char *scenario = argc > 1 ? argv[1] : "examples/c/settling.toml";
  const double superficial = 0.002; /* m/s, upward */
  const size_t nz = 8;              /* cell layers over the domain height */
  const double lo[3] = {-0.01, -0.01, 0.0}, cell[3] = {0.02, 0.02, 0.005};
  const size_t n[3] = {1, 1, nz};
  /* the velocity nodes sit on the cells' centres */
  const double node_origin[3] = {0.0, 0.0, lo[2] + 0.5 * cell[2]};
  double eps_grid[8], eps_field[8];

  ClumpSim *sim = clump_sim_new();
  printf("clump %s\n", clump_version());
  CHECK(clump_sim_load(sim, scenario));

  /* a bad call fails with a code and a message, and the handle stays usable */
  int32_t s = clump_sim_set_uniform_fluid_velocity(sim, NULL);
  printf("NULL velocity: %s (%s)\n", clump_status_name(s), clump_sim_error_message(sim));

  for (int interval = 0; interval < 5; ++interval) {
    size_t nb = 0, ns = 0;
    CHECK(clump_sim_counts(sim, &nb, &ns));
    double *x = malloc(3 * nb * sizeof(double));
    double *f = calloc(3 * nb, sizeof(double));
    double *r = malloc(ns * sizeof(double));
    size_t *owner = malloc(ns * sizeof(size_t));
    CHECK(clump_sim_body_field(sim, CLUMP_BODY_POSITION, x, 3 * nb));
    CHECK(clump_sim_sphere_field(sim, CLUMP_SPHERE_RADIUS, r, ns));
    CHECK(clump_sim_sphere_body(sim, owner, ns));
    CHECK(clump_sim_void_fraction_grid(sim, lo, cell, n, NULL, eps_grid, nz));
    /* the fluid's fields: eps per layer (at least 0.4), u_z = U / eps at
       the node on each layer's centre */
    double node_u[3 * 8];
    for (size_t k = 0; k < nz; ++k) {
      double e = eps_grid[k] < 0.4 ? 0.4 : eps_grid[k];
      eps_field[k] = e;
      node_u[3 * k] = 0.0;
      node_u[3 * k + 1] = 0.0;
      node_u[3 * k + 2] = superficial / e;
    }
    CHECK(clump_sim_set_void_fraction_field(sim, lo, cell, n, eps_field, nz));
    CHECK(clump_sim_set_fluid_velocity_grid(sim, node_origin, cell, n, node_u, 3 * nz));
    for (size_t b = 0; b < nb; ++b) f[3 * b] = 1e-7; /* a small persistent push along x, N */
    CHECK(clump_sim_set_external_loads(sim, f, NULL, 3 * nb, CLUMP_LOAD_PERSISTENT));
    uint64_t taken = 0;
    CHECK(clump_sim_step(sim, 50, &taken));
    CHECK(clump_sim_body_field(sim, CLUMP_BODY_FLUID_FORCE, f, 3 * nb));
    double fz = 0.0;
    for (size_t b = 0; b < nb; ++b) fz += f[3 * b + 2];
    double t = 0.0;
    CHECK(clump_sim_clock(sim, &t, NULL, NULL));
    printf("t = %.6e s  bodies %zu  spheres %zu  steps %llu  sum fluid Fz = %.6e N  eps(layer 0) = %.4f\n",
           t, nb, ns, (unsigned long long)taken, fz, eps_grid[0]);
    free(x);
    free(f);
    free(r);
    free(owner);
  }
  clump_sim_free(sim);
  printf("done\n");
  return 0;
}
