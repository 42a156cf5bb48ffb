/* A tiny CFD–DEM coupling loop through Clump's C API (docs/c_api.md).
 *
 * The "fluid solver" here is one line: an upward flow whose interstitial
 * velocity is U / eps, with eps the void fraction of the horizontal layer
 * of cells that holds each body, which this program reads from Clump's
 * void-fraction grid. Every coupling interval it reads the bodies, sets
 * the fluid velocity and void fraction at each body and a persistent
 * external force, steps Clump, and reads back the fluid forces.
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
  double eps_grid[8];

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
    double *u = malloc(3 * nb * sizeof(double));
    double *eps = malloc(nb * sizeof(double));
    double *f = calloc(3 * nb, sizeof(double));
    double *r = malloc(ns * sizeof(double));
    size_t *owner = malloc(ns * sizeof(size_t));
    CHECK(clump_sim_body_field(sim, CLUMP_BODY_POSITION, x, 3 * nb));
    CHECK(clump_sim_sphere_field(sim, CLUMP_SPHERE_RADIUS, r, ns));
    CHECK(clump_sim_sphere_body(sim, owner, ns));
    CHECK(clump_sim_void_fraction_grid(sim, lo, cell, n, NULL, eps_grid, nz));
    for (size_t b = 0; b < nb; ++b) {
      long k = (long)((x[3 * b + 2] - lo[2]) / cell[2]);
      double e = (k >= 0 && k < (long)nz) ? eps_grid[k] : 1.0;
      if (e < 0.4) e = 0.4;
      eps[b] = e;
      u[3 * b] = 0.0;
      u[3 * b + 1] = 0.0;
      u[3 * b + 2] = superficial / e;
      f[3 * b] = 1e-7; /* a small persistent push along x, N */
    }
    CHECK(clump_sim_set_fluid_velocities(sim, u, 3 * nb));
    CHECK(clump_sim_set_void_fractions(sim, eps, nb));
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
    free(u);
    free(eps);
    free(f);
    free(r);
    free(owner);
  }
  clump_sim_free(sim);
  printf("done\n");
  return 0;
}
