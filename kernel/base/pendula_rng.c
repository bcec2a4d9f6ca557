/* A counter-based generator of standard normal numbers for the Langevin
 * integrator (kernel/integrators/pendula_langevin.f90).
 *
 * The uniform number with index j of a stream with key k is SplitMix64's
 * output mix(k + (j + 1) * gamma) (Steele, Lea and Flood, "Fast splittable
 * pseudorandom number generators", OOPSLA 2014; the finaliser of Stafford's
 * variant 13): a pure function of (k, j), so a path's noise never depends on
 * which thread draws it, on chunks or on what ran before.  The normal number
 * with index j is Box-Muller's cosine branch on the uniform pair (2j, 2j+1):
 * again a function of (k, j) alone.  Unsigned 64-bit arithmetic wraps modulo
 * 2^64 by the C standard (Fortran's signed integers may not), hence C.
 */
#include <math.h>
#include <stdint.h>

static const uint64_t gamma64 = 0x9e3779b97f4a7c15ULL;

static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* The key of stream `index` of a run seeded with `seed`. */
uint64_t pendula_rng_key(uint64_t seed, uint64_t index)
{
    return mix64(mix64(seed + gamma64) + (index + 1) * gamma64);
}

/* z[i] = the normal number of index first + i of stream key, i = 0 .. n - 1. */
void pendula_rng_normals(uint64_t key, uint64_t first, int32_t n, double *z)
{
    const double two_pi = 6.283185307179586476925286766559;
    for (int32_t i = 0; i < n; i++) {
        uint64_t j = 2 * (first + (uint64_t)i);
        /* 53 random bits, offset by half a unit: u in (0, 1), never 0 */
        double u1 = ((double)(mix64(key + (j + 1) * gamma64) >> 11) + 0.5) * 0x1.0p-53;
        double u2 = ((double)(mix64(key + (j + 2) * gamma64) >> 11) + 0.5) * 0x1.0p-53;
        z[i] = sqrt(-2.0 * log(u1)) * cos(two_pi * u2);
    }
}
