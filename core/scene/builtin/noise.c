/* Random numbers and noise for the procedural scenes: a private splitmix64 generator and
 * integer-lattice value noise, no global state. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_internal.h"
#include "../scene_internal.h"

uint64_t
bs_mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

uint64_t
bs_rng_next(bs_rng *r)
{
    return bs_mix64(r->state += 0x9E3779B97F4A7C15ull);
}

/* Uniform in [lo, hi). */
double
bs_rng_range(bs_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * (double)(bs_rng_next(r) >> 11) * 0x1.0p-53;
}

static double
lattice(int64_t ix, int64_t iz, uint64_t seed)
{
    uint64_t h = bs_mix64(seed ^ bs_mix64((uint64_t)ix * 0x9E3779B97F4A7C15ull ^ (uint64_t)iz));
    return (double)(h >> 11) * 0x1.0p-53;
}

static double
quintic(double t)
{
    return t * t * t * (t * (t * 6 - 15) + 10);
}

/* Value noise in [0, 1): smooth interpolation of random values on the integer lattice. */
double
bs_value_noise(double x, double z, uint64_t seed)
{
    double fx = floor(x), fz = floor(z);
    int64_t ix = (int64_t)fx, iz = (int64_t)fz;
    double u = quintic(x - fx), v = quintic(z - fz);
    double a = lattice(ix, iz, seed), b = lattice(ix + 1, iz, seed);
    double c = lattice(ix, iz + 1, seed), d = lattice(ix + 1, iz + 1, seed);
    return (a + (b - a) * u) + ((c + (d - c) * u) - (a + (b - a) * u)) * v;
}

/* Fractal Brownian motion: 5 octaves, each half the amplitude and twice the frequency;
 * the result is centred on 0 and lies in about [-1, 1]. */
double
bs_fbm(double x, double z, uint64_t seed)
{
    double sum = 0, amp = 1, norm = 0;
    for (int o = 0; o < 5; o++) {
        sum += amp * (2 * bs_value_noise(x, z, seed + (uint64_t)o * 7919) - 1);
        norm += amp;
        amp *= 0.5;
        x = x * 2.03 + 17.1;
        z = z * 2.03 - 5.3;
    }
    return sum / norm;
}
